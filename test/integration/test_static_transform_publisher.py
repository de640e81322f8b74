# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``static_transform_publisher`` over real DDS: the transform on ``/tf_static``, upstream's errors.

A late subscriber (transient local) receives the one message; the node has upstream's random
name; Ctrl-C exits 0. A refused command line is upstream's error line, the usage and exit
code 1; a frame equal to its child is refused at start-up.
"""

import math

import pytest
from test_robot_state_publisher import Peer  # noqa: I100 - helpers next to this file
from test_robot_state_publisher import transforms

pytest.importorskip('rclpy')


def test_publishes_the_transform_to_late_subscribers(procs, exe, ros_env):
    proc = procs.start([exe('static_transform_publisher'), '--x', '2', '--y', '-1',
                        '--yaw', str(math.pi / 2), '--frame-id', 'world',
                        '--child-frame-id', 'r1/odom'], ros_env)
    assert proc.wait_for_output("from 'world' to 'r1/odom'", 60.0), proc.output
    assert "translation: ('2.000000', '-1.000000', '0.000000')" in proc.output
    assert "rotation: ('0.000000', '0.000000', '0.707107', '0.707107')" in proc.output
    assert '[static_transform_publisher_' in proc.output  # upstream's random node name
    peer = Peer(int(ros_env['ROS_DOMAIN_ID']))  # joins after the message was sent
    try:
        assert peer.spin_until(lambda: ('world', 'r1/odom') in transforms(peer.static), 60.0)
        t = transforms(peer.static)[('world', 'r1/odom')].transform
        assert (t.translation.x, t.translation.y, t.translation.z) == (2.0, -1.0, 0.0)
        half = math.sqrt(0.5)
        assert (t.rotation.z, t.rotation.w) == pytest.approx((half, half))
    finally:
        peer.close()
    assert proc.interrupt(timeout=30.0) == 0, proc.output
    assert 'Traceback' not in proc.output


@pytest.mark.parametrize('args,line', [
    (['--x', 'one', '--frame-id', 'a', '--child-frame-id', 'b'],
     'error parsing command line arguments: Failed to parse --x argument as float'),
    (['--x', '1'], 'error parsing command line arguments: Frame id must not be empty'),
    (['--frame-id', 'a', '--child-frame-id', 'a'],
     "cannot publish static transform from 'a' to 'a', exiting"),
])
def test_refused_command_lines(procs, exe, ros_env, args, line):
    proc = procs.start([exe('static_transform_publisher')] + args, ros_env)
    assert proc.wait(60.0) == 1, proc.output
    assert line in proc.output and 'Traceback' not in proc.output, proc.output
    if 'parsing' in line:
        assert 'usage: static_transform_publisher [--x X]' in proc.output
