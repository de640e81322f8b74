# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
slam_toolbox's synchronous mapper over real DDS, as a user runs ``online_sync_launch.py``.

The ``sim`` stack in arena.sdf and ``ros2 launch amr_description online_sync_launch.py``
(``sync_slam_toolbox_node``, configured and activated by the launch file): the robot drives a
circle; every ``/pose`` (one per scan the processing thread gave the mapper, in stamp order)
is within 10 cm and 3 deg of the ground truth; ``/map`` holds the arena's walls and pillars;
``slam_toolbox/clear_queue`` answers ``status=True`` with upstream's line;
``deserialize_map`` with ``LOCALIZE_AT_POSE`` is refused with upstream's line; the
loop-closure assistant's services answer with upstream's lines (``toggle_interactive_mode``
sets ``paused_processing``); Ctrl-C stops
the node and its processing thread with exit code 0 and no traceback.
"""

import math
import subprocess

import numpy as np
import pytest
from test_slam import _call  # noqa: I100 - the SLAM test's peer and helpers
from test_slam import _errors
from test_slam import _occupied_near_walls
from test_slam import SlamPeer

pytest.importorskip('slam_toolbox.srv')


def test_sync_mapper_maps_the_arena(procs, exe, ros_env):
    sim = procs.start([exe('ros2'), 'launch', 'amr_description', 'sim.launch.py',
                       'world:=arena', 'viewer:=false'], ros_env)
    slam = procs.start([exe('ros2'), 'launch', 'amr_description', 'online_sync_launch.py'],
                       ros_env)
    peer = SlamPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert slam.wait_for_output('process has finished cleanly', 120.0), slam.output
        assert peer.spin_until(lambda: peer.odom and peer.map_tf, 180.0), slam.output[-3000:]
        start = peer.now
        assert peer.spin_until(lambda: (peer.drive(0.14, 0.4) or peer.now - start > 20.0
                                        and len(peer.poses) >= 8), 240.0), slam.output[-3000:]
        peer.drive(0.0, 0.0)

        stamps = [m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in peer.poses]
        assert all(b > a for a, b in zip(stamps, stamps[1:])), stamps
        errors = _errors(peer, peer.poses)
        worst = np.max(errors, axis=0)
        print(f'/pose vs ground truth over {len(errors)} poses: worst {100 * worst[0]:.1f} cm, '
              f'{math.degrees(worst[1]):.2f} deg')
        assert worst[0] < 0.1 and worst[1] < math.radians(3.0), errors

        assert peer.spin_until(lambda: len(peer.maps) >= 1, 60.0)
        count, near = _occupied_near_walls(peer.maps[-1])
        print(f'/map: {count} occupied cells, {100 * near:.1f} % within 1.5 cells of a surface')
        assert count > 200 and near >= 0.95

        cleared = _call(exe, ros_env, '/slam_toolbox/clear_queue', 'slam_toolbox/srv/ClearQueue',
                        '{}')
        assert 'status=True' in cleared.stdout, cleared.stdout + cleared.stderr
        assert 'SynchronousSlamToolbox: Clearing all queued scans to add to map.' in slam.output
        refused = _call(exe, ros_env, '/slam_toolbox/deserialize_map',
                        'slam_toolbox/srv/DeserializePoseGraph',
                        "{filename: '/nonexistent/graph', match_type: 3}")
        assert refused.returncode == 0, refused.stdout + refused.stderr
        assert 'Requested a localization deserialization in non-localization mode.' \
            in slam.output

        # the loop-closure assistant (enable_interactive_mode: true in the config)
        for service, kind, line in (
                ('toggle_interactive_mode', 'ToggleInteractive',
                 'SlamToolbox: Toggling on interactive mode.'),
                ('manual_loop_closure', 'LoopClosure',
                 'No moved nodes to attempt manual loop closure.'),
                ('clear_changes', 'Clear',
                 'LoopClosureAssistant: Clearing manual loop closure nodes.')):
            done = _call(exe, ros_env, f'/slam_toolbox/{service}', f'slam_toolbox/srv/{kind}',
                         '{}')
            assert done.returncode == 0 and line in slam.output, done.stdout + done.stderr
        paused = subprocess.run([exe('ros2'), 'param', 'get', '/slam_toolbox',
                                 'paused_processing'], env=ros_env, capture_output=True,
                                text=True, timeout=180)
        assert 'Boolean value is: True' in paused.stdout, paused.stdout + paused.stderr
        unused = [line for line in slam.output.splitlines() if 'not used by this' in line]
        assert len(unused) == 1 and 'interactive_mode' not in unused[0], unused
    finally:
        peer.close()
        code = slam.interrupt(60)
        assert sim.interrupt(60) is not None
    assert code == 0, slam.output[-3000:]
    assert 'Traceback' not in slam.output, slam.output[-3000:]
