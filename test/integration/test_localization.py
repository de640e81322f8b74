# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Localization over real DDS as a Nav2 user runs it: ``localization_launch.py`` beside the sim.

The ``sim`` stack in arena.sdf and ``localization_launch.py map:=arena.yaml`` (a Nav2 map of
the arena's walls and pillars, written with map_io); amcl waits for a pose, saying so; an
``/initialpose`` 0.5 m and 20 deg off (issue 30's target) with RViz's covariance is refined
while the robot drives 2.8 m, until ``/amcl_pose`` is within 12 cm and 5 deg of the ground
truth (the skid-steer odometry slips in the turn; the distance driven before the pose stays
within the target's 5 cm and 3 deg is printed for docs/navigation.md);
``/particle_cloud`` (best effort) holds Nav2's particle count; poses in the wrong frame or
with NaN are refused with one line and the node stays active;
``reinitialize_global_localization`` spreads the particles over the map (and the distance
driven before the poses after it settle within 5 cm and 3 deg is printed).
"""

import math

from amr_description.nav import map_io
import numpy as np
import pytest
from test_slam import SlamPeer  # noqa: I100 - the SLAM test's DDS peer

pytest.importorskip('nav2_msgs.msg')

RVIZ_COVARIANCE = (0.25, 0.25, 0.06853891945200942)


class LocalizationPeer(SlamPeer):
    """SlamPeer plus /initialpose, /amcl_pose and /particle_cloud."""

    def __init__(self, domain_id):
        from geometry_msgs.msg import PoseWithCovarianceStamped
        from nav2_msgs.msg import ParticleCloud
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import qos_profile_sensor_data
        from rclpy.qos import QoSProfile
        from std_srvs.srv import Empty
        super().__init__(domain_id)
        self.Pose = PoseWithCovarianceStamped
        self.initial = self.node.create_publisher(PoseWithCovarianceStamped, '/initialpose', 10)
        self.amcl_poses, self.clouds = [], []
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.node.create_subscription(PoseWithCovarianceStamped, '/amcl_pose',
                                      self.amcl_poses.append, latched)
        self.node.create_subscription(ParticleCloud, '/particle_cloud', self.clouds.append,
                                      qos_profile_sensor_data)
        self.clients['global'] = self.node.create_client(
            Empty, '/reinitialize_global_localization')
        self.Empty = Empty

    def set_pose(self, x, y, yaw, frame='map'):
        msg = self.Pose()
        msg.header.frame_id = frame
        msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = \
            math.sin(yaw / 2), math.cos(yaw / 2)
        cov = [0.0] * 36
        cov[0], cov[7], cov[35] = RVIZ_COVARIANCE
        msg.pose.covariance = cov
        self.initial.publish(msg)


def _arena_map(folder):
    from amr_description.tools.benchmark.amcl_accuracy import arena_map
    path = str(folder / 'arena')
    map_io.save_map(path, arena_map())
    return path + '.yaml'


def _converged(poses, odom):
    """Say after how much driving every later ``/amcl_pose`` was within 5 cm and 3 deg."""
    from amr_description.ros.transforms import stamp_seconds
    from amr_description.ros.transforms import yaw_of
    truth = np.array([(m.pose.pose.position.x, m.pose.pose.position.y,
                       yaw_of(m.pose.pose.orientation)) for m in odom])
    driven = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(truth[:, :2], axis=0).T))])
    stamps = np.array([stamp_seconds(m.header.stamp) for m in odom])
    since = None
    for msg in poses:
        nearest = int(np.argmin(abs(stamps - stamp_seconds(msg.header.stamp))))
        x, y, yaw = truth[nearest]
        p = msg.pose.pose
        inside = (math.hypot(p.position.x - x, p.position.y - y) <= 0.05 and
                  abs(math.remainder(yaw_of(p.orientation) - yaw, math.tau)) <= math.radians(3))
        if not inside:
            since = None
        elif since is None:
            since = float(driven[nearest])
    if since is None:
        return 'not within 5 cm and 3 deg at the end'
    return f'within 5 cm and 3 deg from {since:.2f} m of driving on (of {driven[-1]:.2f} m)'


def test_amcl_localizes_the_driving_robot(procs, exe, ros_env, tmp_path):
    from amr_description.ros.transforms import stamp_seconds
    from test_slam import _truth_at
    from test_slam import _yaw
    map_yaml = _arena_map(tmp_path)
    sim = procs.start([exe('ros2'), 'launch', 'amr_description', 'sim.launch.py',
                       'world:=arena', 'viewer:=false'], ros_env)
    loc = procs.start([exe('ros2'), 'launch', 'amr_description', 'localization_launch.py',
                       f'map:={map_yaml}', 'use_sim_time:=true'], ros_env)
    peer = LocalizationPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert loc.wait_for_output('Managed nodes are active', 180.0), loc.output[-3000:]
        assert loc.wait_for_output('Please set the initial pose', 60.0), loc.output[-2000:]
        assert peer.spin_until(lambda: len(peer.odom) > 0, 120.0), sim.output[-2000:]
        assert not peer.amcl_poses  # nothing before a pose is known

        # refused: another frame, NaN; the node stays active
        assert peer.spin_until(lambda: peer.set_pose(0.0, 0.0, 0.0, frame='odom') or
                               'Ignoring initial pose in frame "odom"' in loc.output, 60.0)
        assert peer.spin_until(lambda: peer.set_pose(float('nan'), 0.0, 0.0) or
                               'initialpose: NaN or infinite value' in loc.output, 60.0)

        # 0.5 m and 20 deg off (the robot stands at the origin facing +x), then drive a
        # 0.35 m circle between the pillars
        assert peer.spin_until(lambda: peer.set_pose(0.4, -0.3, math.radians(20.0))
                               or peer.amcl_poses, 60.0), loc.output[-2000:]
        start = peer.now
        assert peer.spin_until(lambda: peer.drive(0.14, 0.4) or peer.now - start > 20.0,
                               240.0)
        peer.drive(0.0, 0.0)
        last = peer.amcl_poses[-1]
        stamp = last.header.stamp.sec + last.header.stamp.nanosec * 1e-9
        x, y, yaw = _truth_at(peer.odom, stamp)
        p = last.pose.pose
        error = math.hypot(p.position.x - x, p.position.y - y)
        turn = abs(math.remainder(_yaw(p.orientation) - yaw, math.tau))
        print(f'amcl_pose after {len(peer.amcl_poses)} updates: {100 * error:.1f} cm, '
              f'{math.degrees(turn):.2f} deg from the ground truth; '
              + _converged(peer.amcl_poses, peer.odom))
        assert last.header.frame_id == 'map'
        # the engine benchmark (exact odometry) reaches 2 cm; here the skid-steer odometry
        # slips in the turn: 2.2-4.9 cm in seven runs with the omni motion model, 5-10 cm
        # before it (docs/navigation.md), hence the margin
        assert error < 0.12 and turn < math.radians(5.0)
        assert peer.map_tf and peer.clouds
        assert 500 <= len(peer.clouds[-1].particles) <= 2000
        assert sum(q.weight for q in peer.clouds[-1].particles) == pytest.approx(1.0)

        # global localization: particles over the whole free space
        peer.call('global', peer.Empty.Request())
        assert loc.wait_for_output('Initializing with uniform distribution', 60.0)
        since = peer.now  # a cloud of an update before the request may still be on its way

        def spread():
            return [c for c in peer.clouds
                    if stamp_seconds(c.header.stamp) > since]
        assert peer.spin_until(lambda: peer.drive(0.14, 0.4) or spread(), 60.0)
        xs = [q.pose.position.x for q in spread()[0].particles]
        assert np.std(xs) > 0.8, np.std(xs)
        # measured, not asserted (a symmetric arena may keep a wrong mode): 5.6 m more of the
        # circle, and where the poses after the request settled within 5 cm and 3 deg
        begin = peer.now
        assert peer.spin_until(lambda: peer.drive(0.14, 0.4) or peer.now - begin > 40.0,
                               400.0)
        peer.drive(0.0, 0.0)

        def after(messages):
            return [m for m in messages if stamp_seconds(m.header.stamp) > since]
        print('after global localization: ' + _converged(after(peer.amcl_poses),
                                                         after(peer.odom)))
    finally:
        peer.drive(0.0, 0.0)
        peer.close()
        assert loc.interrupt(60) is not None
        assert sim.interrupt(60) is not None
