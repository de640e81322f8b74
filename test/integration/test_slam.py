# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
SLAM over real DDS as a slam_toolbox user runs it: the ``slam`` stack in arena.sdf, driven.

One stack (simulator, controllers, ``async_slam_toolbox_node`` configured and activated as
``online_async_launch.py`` does): the robot drives a circle; ``/pose`` follows the ground
truth, ``/map`` (transient local) holds the arena's walls and pillars where they are, TF has
``map -> odom``; ``slam_toolbox/save_map`` writes Nav2's map files (through ``ros2 run
nav2_map_server map_saver_cli``), ``serialize_map`` the pose graph; a scan whose ranges do not
match its angles is dropped with one line and the node stays active;
``slam_toolbox/graph_visualization`` draws the pose graph. A params file with a
wrong type fails configure with one line naming the parameter.
"""

import math
import os
import subprocess

import numpy as np
import pytest
from test_sim import Peer  # noqa: I100 - the simulator tests' DDS peer

pytest.importorskip('slam_toolbox.srv')


class SlamPeer(Peer):
    """Peer plus cmd_vel, /pose, /map and /tf."""

    def __init__(self, domain_id):
        from geometry_msgs.msg import PoseWithCovarianceStamped
        from geometry_msgs.msg import TwistStamped
        from nav_msgs.msg import OccupancyGrid
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        from sensor_msgs.msg import LaserScan
        from tf2_msgs.msg import TFMessage
        from visualization_msgs.msg import MarkerArray
        super().__init__(domain_id)
        self.TwistStamped, self.LaserScan = TwistStamped, LaserScan
        self.cmd = self.node.create_publisher(TwistStamped, '/diff_drive_controller/cmd_vel',
                                              10)
        self.bad_scan = self.node.create_publisher(LaserScan, '/scan', 10)
        self.poses, self.maps, self.map_tf = [], [], []
        self.node.create_subscription(PoseWithCovarianceStamped, '/pose', self.poses.append, 10)
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.node.create_subscription(OccupancyGrid, '/map', self.maps.append, latched)
        self.node.create_subscription(TFMessage, '/tf', self._on_tf, 100)
        self.graphs = []
        self.node.create_subscription(MarkerArray, '/slam_toolbox/graph_visualization',
                                      self.graphs.append, 1)

    def _on_tf(self, msg):
        self.map_tf += [t for t in msg.transforms
                        if t.header.frame_id == 'map' and t.child_frame_id == 'odom']

    def drive(self, linear, angular):
        msg = self.TwistStamped()
        msg.twist.linear.x, msg.twist.angular.z = float(linear), float(angular)
        self.cmd.publish(msg)


def _yaw(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def _truth_at(odom, stamp):
    """Return the ground-truth (x, y, yaw) nearest in time to ``stamp`` (s)."""
    best = min(odom, key=lambda m: abs(m.header.stamp.sec + m.header.stamp.nanosec * 1e-9
                                       - stamp))
    p = best.pose.pose
    return p.position.x, p.position.y, _yaw(p.orientation)


def _errors(peer, poses):
    """Return each pose's distance (m) and turn (rad) from the ground truth at its stamp."""
    out = []
    for msg in poses:
        x, y, yaw = _truth_at(peer.odom, msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9)
        p = msg.pose.pose
        out.append((math.hypot(p.position.x - x, p.position.y - y),
                    abs(math.remainder(_yaw(p.orientation) - yaw, math.tau))))
    return np.array(out)


def _occupied_near_walls(grid_msg):
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.core.scan_map import surface_distance
    from amr_description.core.scan_map import world_sections
    from amr_description.nav.grid_message import grid_from_message
    grid = grid_from_message(grid_msg)
    rows, cols = np.nonzero(grid.data == 100)
    centres = np.stack([grid.origin[0] + (cols + 0.5) * grid.resolution,
                        grid.origin[1] + (rows + 0.5) * grid.resolution], axis=1)
    d = surface_distance(centres, world_sections(load_world('arena'), 0.25))
    return len(centres), float(np.mean(d <= 1.5 * grid.resolution))


def _call(exe, env, service, srv_type, values):
    return subprocess.run([exe('ros2'), 'service', 'call', service, srv_type, values], env=env,
                          capture_output=True, text=True, timeout=180)


def test_slam_stack_maps_the_arena(procs, exe, ros_env, tmp_path):
    from amr_description.nav import map_io
    stack = procs.start([exe('ros2'), 'launch', 'amr_description', 'slam.launch.py',
                         'world:=arena', 'viewer:=false'], ros_env)
    peer = SlamPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert stack.wait_for_output('process has finished cleanly', 120.0), stack.output
        assert peer.spin_until(lambda: peer.odom and peer.maps, 120.0), stack.output[-3000:]
        # a circle of radius 0.35 m between the pillars: 0.14 m/s, 0.4 rad/s
        start = peer.now
        assert peer.spin_until(lambda: (peer.drive(0.14, 0.4) or peer.now - start > 25.0
                                        and len(peer.poses) >= 8), 240.0), stack.output[-3000:]
        peer.drive(0.0, 0.0)
        assert 'Parameters not used by this implementation: ' in stack.output
        assert 'Creating bond' not in stack.output  # no lifecycle manager: no bond

        # /pose (map frame; map == world here, the robot started at the origin) vs truth
        assert all(msg.header.frame_id == 'map' for msg in peer.poses)
        errors = _errors(peer, peer.poses[2:])
        worst = np.max(errors, axis=0)
        print(f'/pose vs ground truth over {len(errors)} poses: worst {100 * worst[0]:.1f} cm, '
              f'{math.degrees(worst[1]):.2f} deg')
        assert worst[0] < 0.1 and worst[1] < math.radians(3.0), errors

        # map -> odom on TF, stamped after the scans; /map holds the arena where it is
        assert peer.spin_until(lambda: len(peer.map_tf) > 5, 30.0)
        assert peer.spin_until(lambda: len(peer.maps) >= 2, 60.0)
        count, near = _occupied_near_walls(peer.maps[-1])
        print(f'/map: {count} occupied cells, {100 * near:.1f} % within 1.5 cells of a surface')
        assert count > 200 and near >= 0.95

        # the pose graph's markers, drawn after the last /pose (the robot stands): a sphere per
        # node, the last at the last /pose, the edges
        def _s(stamp):
            return stamp.sec + stamp.nanosec * 1e-9
        assert peer.spin_until(lambda: peer.graphs and _s(peer.graphs[-1].markers[0].header.stamp)
                               > _s(peer.poses[-1].header.stamp), 60.0)
        markers = peer.graphs[-1].markers
        spheres = [m for m in markers if m.ns == 'slam_toolbox']
        edges = [m for m in markers if m.ns == 'slam_toolbox_edges']
        assert markers[0].action == 3 and len(spheres) >= len(peer.poses) - 1, markers
        assert len(edges) == 2 and len(edges[0].points) >= 2 * (len(spheres) - 1)
        last, pose = spheres[-1].pose.position, peer.poses[-1].pose.pose.position
        assert math.hypot(last.x - pose.x, last.y - pose.y) < 0.05, (last, pose)

        # save_map: Nav2's map files through map_saver_cli; serialize_map: the pose graph
        stem = os.path.join(str(tmp_path), 'arena')
        saved = _call(exe, ros_env, '/slam_toolbox/save_map', 'slam_toolbox/srv/SaveMap',
                      f"{{name: {{data: '{stem}'}}}}")
        assert 'result=0' in saved.stdout, saved.stdout + saved.stderr + stack.output[-2000:]
        grid, metadata = map_io.load_map(stem + '.yaml')
        assert metadata.resolution == pytest.approx(0.05)
        assert np.count_nonzero(grid.data == 100) > 200
        graph = _call(exe, ros_env, '/slam_toolbox/serialize_map',
                      'slam_toolbox/srv/SerializePoseGraph', f"{{filename: '{stem}'}}")
        assert 'result=0' in graph.stdout, graph.stdout + graph.stderr
        assert os.path.getsize(stem + '.posegraph') > 0 and os.path.getsize(stem + '.data') > 0

        # a scan whose ranges do not match its angles: one line, the node stays active
        bad = peer.LaserScan()
        bad.header.frame_id = 'lidar_link'
        bad.header.stamp = peer.poses[-1].header.stamp
        bad.angle_min, bad.angle_max, bad.angle_increment = -1.0, 1.0, 0.1
        bad.range_min, bad.range_max = 0.1, 10.0
        bad.ranges = [1.0] * 5
        assert peer.spin_until(lambda: peer.bad_scan.publish(bad) or
                               'ranges has 5 readings' in stack.output, 60.0), stack.output[-2000:]
        state = _call(exe, ros_env, '/slam_toolbox/get_state', 'lifecycle_msgs/srv/GetState',
                      '{}')
        assert "label='active'" in state.stdout, state.stdout
    finally:
        peer.close()
        assert stack.interrupt(60) is not None


def test_wrong_parameter_type_fails_configure(procs, exe, ros_env, tmp_path):
    params = tmp_path / 'bad.yaml'
    params.write_text('slam_toolbox:\n  ros__parameters:\n    resolution: fine\n')
    node = procs.start([exe('async_slam_toolbox_node'), '--ros-args', '--params-file',
                        str(params)], ros_env)
    from conftest import run_until
    result = run_until([exe('ros2'), 'lifecycle', 'set', '/slam_toolbox', 'configure'], ros_env,
                       lambda r: 'Transitioning' in r.stdout + r.stderr)
    assert 'Transitioning failed' in result.stdout + result.stderr, result
    assert node.wait_for_output("parameter 'resolution': expected a double, got str 'fine'",
                                30.0), node.output
    lines = [ln for ln in node.output.splitlines() if 'resolution' in ln]
    assert len(lines) == 1 and 'Traceback' not in node.output
    assert node.popen.poll() is None  # still running
