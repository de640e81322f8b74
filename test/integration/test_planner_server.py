# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
planner_server and its global costmap over real DDS, as nav2_bringup starts them.

One stack (map_server with arena.sdf's map, planner_server with config/nav2_params.yaml, a
static ``map -> base_footprint``, lifecycle_manager with bonds): ``/global_costmap/costmap``
(transient local) holds the arena's walls as 100 with Nav2's inflation around them, in
``map``; ``compute_path_to_pose`` plans from the robot's TF pose around the pillars, every
pose on a cell below the inscribed cost, the last with the goal's orientation, and ``/plan``
carries the same path; an unknown planner id, a goal outside the map, a NaN goal and a goal
in a wall with tolerance 0 fail with ComputePathToPose's codes, and the server keeps planning.
``ros2 param set`` then reaches the planner (a tolerance of 0.5 m: the goal in the pillar is
planned to) and its costmap (inflated cells within the new inflation radius, not the old).
"""

import math

import numpy as np
import pytest
from test_controller_server import ros2_param  # noqa: I100 - the servers' ros2 param
from test_sim import Peer  # the simulator tests' DDS peer

pytest.importorskip('nav2_msgs.action')

ACTIVE = 'Managed nodes are active'


class PlannerPeer(Peer):
    """Peer plus the costmap topics, /plan and the compute_path_to_pose action."""

    def __init__(self, domain_id):
        from nav2_msgs.action import ComputePathToPose
        from nav2_msgs.msg import Costmap
        from nav_msgs.msg import OccupancyGrid
        from nav_msgs.msg import Path
        from rclpy.action import ActionClient
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        from rclpy.qos import ReliabilityPolicy
        super().__init__(domain_id)
        latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.grids, self.raws, self.plans = [], [], []
        self.node.create_subscription(OccupancyGrid, '/global_costmap/costmap',
                                      self.grids.append, latched)
        self.node.create_subscription(Costmap, '/global_costmap/costmap_raw', self.raws.append,
                                      latched)
        self.node.create_subscription(Path, '/plan', self.plans.append, 10)
        from nav2_msgs.srv import GetCost
        from nav2_msgs.srv import IsPathValid
        self.Action = ComputePathToPose
        self.action = ActionClient(self.node, ComputePathToPose, '/compute_path_to_pose')
        self.clients['is_path_valid'] = self.node.create_client(IsPathValid, '/is_path_valid')
        self.clients['get_cost'] = self.node.create_client(
            GetCost, '/global_costmap/get_cost_global_costmap')

    def plan(self, x, y, yaw=0.0, planner_id='', frame='map'):
        """Send a goal; return ``(status, result)``."""
        goal = self.Action.Goal()
        goal.goal.header.frame_id = frame
        goal.goal.pose.position.x, goal.goal.pose.position.y = x, y
        goal.goal.pose.orientation.z = math.sin(yaw / 2) if math.isfinite(yaw) else yaw
        goal.goal.pose.orientation.w = math.cos(yaw / 2) if math.isfinite(yaw) else 1.0
        goal.planner_id = planner_id
        assert self.action.wait_for_server(timeout_sec=60.0)
        sent = self.action.send_goal_async(goal)
        assert self.spin_until(sent.done, 60.0)
        result = sent.result().get_result_async()
        assert self.spin_until(result.done, 60.0)
        return result.result().status, result.result().result


def _cells(raw, x, y):
    m = raw.metadata
    mx = int(math.floor((x - m.origin.position.x) / m.resolution))
    my = int(math.floor((y - m.origin.position.y) / m.resolution))
    return np.asarray(raw.data, np.uint8).reshape(m.size_y, m.size_x)[my, mx]


def _inflation_reach(raw):
    """Return the farthest an inflated cell (cost 1..252) lies from a lethal one, m."""
    from scipy import ndimage
    m = raw.metadata
    costs = np.asarray(raw.data, np.uint8).reshape(m.size_y, m.size_x)
    distance = ndimage.distance_transform_edt(costs != 254) * m.resolution
    return float(distance[(costs >= 1) & (costs <= 252)].max())


def test_global_costmap_and_compute_path_to_pose(procs, exe, ros_env, tmp_path):
    from action_msgs.msg import GoalStatus
    from amr_description.launch.nav_stacks import share_file
    from amr_description.nav import map_io
    from amr_description.tools.benchmark.amcl_accuracy import arena_map
    map_io.save_map(str(tmp_path / 'arena'), arena_map())
    params = share_file('config', 'nav2_params.yaml')
    server = procs.start([exe('map_server'), '--ros-args', '--params-file', params, '-p',
                          f'yaml_filename:={tmp_path}/arena.yaml'], ros_env)
    planner = procs.start([exe('planner_server'), '--ros-args', '--params-file', params],
                          ros_env)
    procs.start([exe('static_transform_publisher'), '--frame-id', 'map', '--child-frame-id',
                 'base_footprint'], ros_env)
    manager = procs.start([exe('lifecycle_manager'), '--ros-args', '-p',
                           'node_names:=[map_server, planner_server]', '-p', 'autostart:=true'],
                          ros_env)
    peer = PlannerPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert manager.wait_for_output(ACTIVE, 180.0), manager.output + planner.output
        assert 'Created global planner plugin GridBased of type ' \
            'nav2_navfn_planner::NavfnPlanner' in planner.output

        # the costmap: the map's size, walls 100, inflated cells between, unknown -1 outside
        # (before the map arrives it has the params' 5 m x 5 m, as upstream's: wait for the
        # map's 100 x 110 cells)
        assert peer.spin_until(lambda: peer.grids and peer.raws and
                               (peer.grids[-1].info.width, peer.grids[-1].info.height) ==
                               (100, 110) and peer.raws[-1].metadata.size_y == 110,
                               120.0), planner.output
        grid, raw = peer.grids[-1], peer.raws[-1]
        assert grid.header.frame_id == 'map' and (grid.info.width, grid.info.height) == (100, 110)
        assert grid.info.origin.position.x == pytest.approx(-1.5)
        assert raw.metadata.layer == 'master'
        values = np.asarray(grid.data, np.int16)
        assert set(np.unique(values)) <= set(range(-1, 101))
        assert _cells(raw, 3.28, 0.0) == 254  # the arena's east wall
        assert 1 <= np.asarray(raw.data)[np.asarray(raw.data) < 253].max() <= 252  # inflation

        # a plan around the pillars, from the robot's TF pose, on free cells
        status, result = peer.plan(2.6, 2.2, yaw=1.0)
        assert status == GoalStatus.STATUS_SUCCEEDED and result.error_code == 0, result.error_msg
        poses = [(p.pose.position.x, p.pose.position.y) for p in result.path.poses]
        assert result.path.header.frame_id == 'map'
        assert math.hypot(*poses[0]) < 0.05 and math.hypot(poses[-1][0] - 2.6,
                                                           poses[-1][1] - 2.2) < 0.05
        assert all(_cells(raw, x, y) < 253 for x, y in poses)
        length = sum(math.dist(a, b) for a, b in zip(poses, poses[1:]))
        assert math.hypot(2.6, 2.2) <= length < 1.5 * math.hypot(2.6, 2.2)
        q = result.path.poses[-1].pose.orientation
        assert 2 * math.atan2(q.z, q.w) == pytest.approx(1.0, abs=1e-6)
        assert peer.spin_until(lambda: peer.plans and len(peer.plans[-1].poses) == len(poses))

        # is_path_valid: the plan is; a straight line through the centre pillar is not, at the
        # poses within it (cost 253 or 254 in the costmap), all after the robot's nearest
        from nav2_msgs.srv import GetCost
        from nav2_msgs.srv import IsPathValid
        answer = peer.call('is_path_valid', IsPathValid.Request(path=result.path))
        assert answer.is_valid and list(answer.invalid_pose_indices) == []
        line = IsPathValid.Request()
        line.path.header.frame_id = 'map'
        for i in range(41):
            pose = type(result.path.poses[0])()
            pose.header.frame_id = 'map'
            pose.pose.position.x, pose.pose.orientation.w = 0.05 * i, 1.0
            line.path.poses.append(pose)
        answer = peer.call('is_path_valid', line)
        blocked = [i for i in range(41) if _cells(raw, 0.05 * i, 0.0) >= 253]
        assert blocked and not answer.is_valid, blocked
        assert list(answer.invalid_pose_indices) == blocked
        assert not peer.call('is_path_valid', IsPathValid.Request()).is_valid  # empty path
        # get_cost_global_costmap: the east wall's cell, a free cell, and -1 off the map
        for (x, y), cost in [((3.28, 0.0), 254.0), ((0.0, 0.0), float(_cells(raw, 0.0, 0.0))),
                             ((50.0, 0.0), -1.0)]:
            assert peer.call('get_cost', GetCost.Request(x=x, y=y)).cost == cost, (x, y)

        # bad goals: one line each, the codes of ComputePathToPose, the server keeps going
        codes = peer.Action.Result
        for args, kwargs, code in [((2.0, 1.0), {'planner_id': 'Nope'}, codes.INVALID_PLANNER),
                                   ((50.0, 0.0), {}, codes.GOAL_OUTSIDE_MAP),
                                   ((float('nan'), 0.0), {}, codes.GOAL_OUTSIDE_MAP),
                                   ((1.0, 1.0), {'frame': 'nowhere'}, codes.TF_ERROR),
                                   # on the centre pillar's surface, tolerance 0 in the params
                                   ((1.12, 0.0), {}, codes.GOAL_OCCUPIED)]:
            status, result = peer.plan(*args, **kwargs)
            assert status == GoalStatus.STATUS_ABORTED and result.error_code == code, \
                (args, kwargs, result.error_code, result.error_msg)
            assert result.error_msg
        status, result = peer.plan(1.0, -0.5)
        assert status == GoalStatus.STATUS_SUCCEEDED, planner.output[-2000:]

        # ros2 param set, as upstream's dynamic parameters: the planner's next plan ...
        out = ros2_param(exe, ros_env, 'set', '/planner_server', 'GridBased.tolerance', '0.5')
        assert out.stdout.strip() == 'Set parameter successful', out
        status, result = peer.plan(1.12, 0.0)
        assert status == GoalStatus.STATUS_SUCCEEDED, (result.error_code, result.error_msg)
        end = result.path.poses[-1].pose.position
        assert math.hypot(end.x - 1.12, end.y) <= 0.55, (end.x, end.y)
        # ... and the costmap's next update: inflated cells (1..252) reach 0.45 m from the
        # nearest lethal cell, not 0.7 m (config/nav2_params.yaml's inflation_radius)
        assert _inflation_reach(raw) == pytest.approx(0.70, abs=0.026)
        out = ros2_param(exe, ros_env, 'set', '/global_costmap/global_costmap',
                         'inflation_layer.inflation_radius', '0.45')
        assert out.stdout.strip() == 'Set parameter successful', out
        assert peer.spin_until(lambda: _inflation_reach(peer.raws[-1]) <= 0.45 + 1e-6, 60.0), \
            (_inflation_reach(peer.raws[-1]), planner.output[-2000:])
        out = ros2_param(exe, ros_env, 'set', '/global_costmap/global_costmap', 'width', '0')
        assert 'Setting parameter failed' in out.stderr, out
        assert planner.wait_for_output('You try to set width of map to be negative or zero', 30)
        assert server.popen.poll() is None and planner.popen.poll() is None
    finally:
        peer.close()
