# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
slam_toolbox's localization mode over real DDS, as a user runs it on a saved pose graph.

A pose graph of one lap of arena.sdf is built in this process (the lidar cast by MuJoCo along
the lap, exact odometry, :class:`~amr_description.nav.slam.Mapper`) and serialized; the ``sim``
stack in the arena and ``slam_toolbox_localization_launch.py`` (slam_toolbox's
``localization_launch.py``) with ``map_file_name`` and a ``map_start_pose`` 0.25 m and 6 deg
off localize the robot: ``map -> odom`` within 5 cm and 3 deg of the truth after the first
scan, every ``/pose`` within 5 cm and 3 deg of the ground truth while it drives a circle,
again after an ``/initialpose`` 0.3 m off; ``/map`` is the graph's;
``serialize_map`` is refused with upstream's line.
"""

import math
import subprocess

import numpy as np
import pytest
from test_slam import _errors  # noqa: I100 - the SLAM test's peer and helpers
from test_slam import _yaw
from test_slam import SlamPeer

pytest.importorskip('slam_toolbox.srv')

LAP = [(-0.65, -0.55), (2.65, -0.55), (2.65, 0.55), (-0.65, 0.55), (-0.65, -0.55)]
"""One lap between the arena's pillars and its walls (m, world frame)."""


def _saved_graph(folder):
    """Map one lap with exact odometry (map frame = world) and serialize it; return the stem."""
    from amr_description.nav import slam
    from amr_description.tools.benchmark.slam_accuracy import scans
    from amr_description.tools.benchmark.slam_accuracy import trajectory
    truth, _ = trajectory(LAP)
    ranges, msg, sensor = scans('arena', truth)
    mapper = slam.Mapper()
    for k, pose in enumerate(truth):
        mapper.process(pose, slam.Scan(np.asarray(ranges[k]), msg.angle_min, msg.angle_increment,
                                       msg.range_min, msg.range_max, sensor), k * 0.1)
    stem = str(folder / 'arena')
    slam.save_graph(mapper, stem)
    return stem


def test_localization_on_a_saved_graph(procs, exe, ros_env, tmp_path):
    import yaml
    from amr_description.launch.nav_stacks import share_file
    stem = _saved_graph(tmp_path)
    with open(share_file('config', 'mapper_params_localization.yaml')) as f:
        params = yaml.safe_load(f)
    node = params['slam_toolbox']['ros__parameters']
    node['map_file_name'] = stem
    node['map_start_pose'] = [0.2, -0.15, math.radians(6.0)]  # the robot is at the origin
    params_file = tmp_path / 'localization.yaml'
    params_file.write_text(yaml.safe_dump(params))
    sim = procs.start([exe('ros2'), 'launch', 'amr_description', 'sim.launch.py',
                       'world:=arena', 'viewer:=false'], ros_env)
    loc = procs.start([exe('ros2'), 'launch', 'amr_description',
                       'slam_toolbox_localization_launch.py',
                       f'slam_params_file:={params_file}'], ros_env)
    peer = SlamPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert loc.wait_for_output('Loaded pose graph', 120.0), loc.output[-3000:]
        # the first scan's /pose may come before this peer hears the node (a standing robot
        # sends no other), so the start is checked on map -> odom, sent every 20 ms once a
        # scan is localized: the robot was spawned at the world's origin, where odom starts
        assert peer.spin_until(lambda: peer.odom and peer.map_tf, 180.0), loc.output[-3000:]
        t = peer.map_tf[-1].transform
        first = (math.hypot(t.translation.x, t.translation.y), abs(_yaw(t.rotation)))
        print(f'map -> odom after the first scan: {100 * first[0]:.1f} cm, '
              f'{math.degrees(first[1]):.2f} deg')
        assert first[0] < 0.05 and first[1] < math.radians(3.0), first
        # a circle of radius 0.35 m (0.14 m/s, 0.4 rad/s): a scan localized every 0.5 rad
        seen = len(peer.poses)
        assert peer.spin_until(lambda: peer.drive(0.14, 0.4) or len(peer.poses) >= seen + 4,
                               120.0), loc.output[-2000:]
        peer.drive(0.0, 0.0)
        worst = _errors(peer, peer.poses).max(axis=0)
        print(f'{len(peer.poses)} poses driving: worst {100 * worst[0]:.1f} cm, '
              f'{math.degrees(worst[1]):.2f} deg')
        assert worst[0] < 0.05 and worst[1] < math.radians(3.0), worst
        assert peer.spin_until(lambda: peer.maps and len(peer.map_tf) > 5, 60.0)
        assert peer.maps[-1].info.resolution == pytest.approx(0.05)

        # "2D Pose Estimate" 0.3 m off: the next scan is localized near it, then put right
        from geometry_msgs.msg import PoseWithCovarianceStamped
        pub = peer.node.create_publisher(PoseWithCovarianceStamped, '/initialpose', 1)
        truth = peer.odom[-1].pose.pose
        estimate = PoseWithCovarianceStamped()
        estimate.header.frame_id = 'map'
        estimate.pose.pose.position.x = truth.position.x + 0.3
        estimate.pose.pose.position.y = truth.position.y
        estimate.pose.pose.orientation = truth.orientation
        seen = len(peer.poses)
        assert peer.spin_until(lambda: pub.publish(estimate) or
                               'LocalizePoseCallback: Localizing to' in loc.output, 60.0)
        assert peer.spin_until(lambda: len(peer.poses) > seen, 60.0), loc.output[-2000:]
        after = _errors(peer, peer.poses[seen:])[-1]
        print(f'after /initialpose: {100 * after[0]:.1f} cm, {math.degrees(after[1]):.2f} deg')
        assert after[0] < 0.05 and after[1] < math.radians(3.0), after

        refused = subprocess.run(
            [exe('ros2'), 'service', 'call', '/slam_toolbox/serialize_map',
             'slam_toolbox/srv/SerializePoseGraph', f"{{filename: '{tmp_path}/again'}}"],
            env=ros_env, capture_output=True, text=True, timeout=180)
        assert 'result=255' in refused.stdout, refused.stdout + refused.stderr
        assert 'Cannot call serialize map in localization mode!' in loc.output
    finally:
        peer.close()
        assert loc.interrupt(60) is not None
        assert sim.interrupt(60) is not None
