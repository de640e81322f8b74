# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Two terminals, as in the tutorial: ``bringup sim`` and the keyboard teleop drive the robot.

The sim stack runs in real time; the teleop runs on a pseudo-terminal with
``stamped:=true``, ``use_sim_time:=true`` and the cmd_vel remap. Held ``i`` drives the robot
forward, and ``/odom`` follows the ground truth; after the keys stop, ``cmd_vel_timeout``
stops it; held ``j`` turns it counter-clockwise.
"""

import math
import os
import subprocess
import time

from test_drive import DrivePeer  # noqa: I100 - the drive tests' DDS peer
from test_teleop import _start_teleop


def _hold(peer, master, key, seconds, period=0.1, until=None):
    """
    Type ``key`` every ``period`` s (a held key auto-repeats).

    :returns: True once ``until()`` holds (then stops typing), or after ``seconds``.
    """
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        os.write(master, key)
        if until is not None and peer.spin_until(until, period):
            return True
        peer.spin_until(lambda: False, period)
    return until is None


def test_teleop_drives_simulated_robot(ros_env, procs, exe):
    stack = procs.start([exe('bringup'), 'sim', 'viewer:=false'], ros_env)
    assert stack.wait_for_output('Configured and activated diff_drive_controller', 60.0), \
        stack.output[-3000:]
    peer = DrivePeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert peer.spin_until(lambda: peer.odom and peer.ctrl_odom, 15.0), stack.output[-2000:]
        # each node its own parameters: the simulator's (passed to its process as a '/**'
        # file, as launch_ros writes a dict) are not the controller's, which runs there too
        listed = subprocess.run([exe('ros2'), 'param', 'list', '/diff_drive_controller'],
                                env=ros_env, capture_output=True, text=True, timeout=60).stdout
        names = listed.split()
        assert 'wheel_separation' in names and 'use_sim_time' in names, listed
        assert 'headless' not in names and 'real_time_factor' not in names, listed
        teleop, master = _start_teleop(procs, exe, ros_env, extra=('-p', 'use_sim_time:=true'))
        assert teleop.wait_for_output('currently:', 15.0), teleop.output
        # hold 'i' until the robot moves (the controller has discovered the teleop), then 2 s
        assert _hold(peer, master, b'i', 10.0,
                     until=lambda: peer.ctrl_odom[-1].twist.twist.linear.x > 0.2), \
            teleop.output[-1000:]
        gx0, gy0, gyaw0, ox0, oy0, oyaw0 = peer.pose()
        _hold(peer, master, b'i', 2.0)
        peer.spin_until(lambda: False, 1.5)  # keys released: cmd_vel_timeout brakes
        gx, gy, gyaw, ox, oy, oyaw = peer.pose()
        odom_distance = math.hypot(ox - ox0, oy - oy0)
        true_distance = math.hypot(gx - gx0, gy - gy0)
        assert ox - ox0 > 0.8, (odom_distance, teleop.output[-1000:])
        assert abs(odom_distance - true_distance) < 0.03 * true_distance + 0.01
        assert abs(peer.ctrl_odom[-1].twist.twist.linear.x) < 0.02  # stopped

        _hold(peer, master, b'j', 1.5)
        peer.spin_until(lambda: False, 1.5)
        _, _, gyaw2, _, _, oyaw2 = peer.pose()
        odom_turn = math.atan2(math.sin(oyaw2 - oyaw), math.cos(oyaw2 - oyaw))
        true_turn = math.atan2(math.sin(gyaw2 - gyaw), math.cos(gyaw2 - gyaw))
        assert odom_turn > 0.3 and true_turn > 0.2, (odom_turn, true_turn)

        assert teleop.interrupt(timeout=30.0) == 0, teleop.output[-1000:]
        os.close(master)
    finally:
        peer.close()
    assert stack.interrupt(timeout=60.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]
