# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Fleets: two namespaced robots in one simulator, driven independently over DDS.

``create -robot_namespace rI`` gives each robot its controller manager
``/rI/controller_manager``, cmd_vel ``/rI/diff_drive_controller/cmd_vel``, odometry
``/rI/odom`` (remapped as the fleet stack does), ground truth ``/rI/ground_truth/odom`` and TF
frames ``rI/...`` (diff_drive_controller's ``tf_frame_prefix_enable``, robot_state_publisher's
``frame_prefix``). The simulator is paused and stepped so sim-time durations are exact; each
chunk is preceded by fresh commands (zero stamp: stamped on receipt by the controller).
"""

import math
import os
import re
import sys

import pytest
from test_sim import Peer  # noqa: I100 - the simulator tests' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')
CHUNK_STEPS = 250  # 0.25 s of 1 ms physics steps
ROBOTS = {'r1': (0.0, 0.0), 'r2': (2.0, 0.0)}
STACK_ROBOTS = {'r1': (0.0, 0.0), 'r2': (2.0, 0.0), 'r3': (0.0, 2.0), 'r4': (2.0, 2.0)}


def _pose(msg):
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    return p.x, p.y, math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class FleetPeer(Peer):
    """Peer with per-robot cmd_vel publishers, odometry, ground truth and a /tf listener."""

    def __init__(self, domain_id, robots=ROBOTS):
        from geometry_msgs.msg import TwistStamped
        from nav_msgs.msg import Odometry
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        from tf2_msgs.msg import TFMessage
        super().__init__(domain_id)
        self.TwistStamped = TwistStamped
        self.cmd, self.odom_of, self.truth_of = {}, {}, {}
        for ns in robots:
            self.cmd[ns] = self.node.create_publisher(
                TwistStamped, f'/{ns}/diff_drive_controller/cmd_vel', 10)
            self.odom_of[ns], self.truth_of[ns] = [], []
            self.node.create_subscription(Odometry, f'/{ns}/odom', self.odom_of[ns].append, 100)
            self.node.create_subscription(Odometry, f'/{ns}/ground_truth/odom',
                                          self.truth_of[ns].append, 100)
        self.edges = set()  # (parent, child) frame pairs seen on /tf and /tf_static
        self.node.create_subscription(TFMessage, '/tf', self._on_tf, 100)
        latched = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.node.create_subscription(TFMessage, '/tf_static', self._on_tf, latched)

    def _on_tf(self, msg):
        for t in msg.transforms:
            self.edges.add((t.header.frame_id, t.child_frame_id))

    def command(self, twists):
        for ns, (linear, angular) in twists.items():
            msg = self.TwistStamped()
            msg.twist.linear.x = float(linear)
            msg.twist.angular.z = float(angular)
            self.cmd[ns].publish(msg)
        self.spin_for(0.15)  # delivery over DDS while the simulation is paused

    def step(self, steps):
        start = self.now
        request = self.srv.StepSimulation.Request()
        request.steps = steps
        assert self.call('step', request).result.result == self.msg.Result.RESULT_OK
        assert self.spin_until(lambda: self.now >= start + steps * 1e-3 - 1e-9, 10)
        self.spin_for(0.2)  # the last odometry and ground truth messages

    def poses(self, ns):
        return _pose(self.truth_of[ns][-1]), _pose(self.odom_of[ns][-1])


@pytest.fixture
def fleet_peer(ros_env):
    pytest.importorskip('controller_manager_msgs.srv')
    p = FleetPeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def test_two_namespaced_robots_drive_independently(procs, exe, ros_env, fleet_peer):
    peer = fleet_peer
    remaps = []
    for ns in ROBOTS:
        remaps += ['-r', f'/{ns}/diff_drive_controller/odom:=/{ns}/odom']
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0.0'] +
                      remaps, ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 20), sim.output
    with open(URDF_PATH) as f:
        urdf = f.read()
    for ns, (x, y) in ROBOTS.items():
        procs.start([exe('robot_state_publisher'), '--ros-args', '-r', f'__ns:=/{ns}',
                     '-p', 'use_sim_time:=true', '-p', f'frame_prefix:={ns}/',
                     '-p', f'robot_description:={urdf}'], ros_env)
        create = procs.start([exe('create'), '-topic', f'/{ns}/robot_description', '-name', ns,
                              '-robot_namespace', ns, '-x', str(x), '-y', str(y), '-z', '0.2'],
                             ros_env)
        assert create.wait(60) == 0, create.output + sim.output
    for ns in ROBOTS:
        spawner = procs.start([exe('spawner'), '-c', f'/{ns}/controller_manager',
                               'joint_state_broadcaster', 'diff_drive_controller',
                               '--controller-manager-timeout', '30'], ros_env)
        assert spawner.wait(90) == 0, spawner.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    peer.step(500)
    assert all(peer.odom_of[ns] and peer.truth_of[ns] for ns in ROBOTS), sim.output[-3000:]
    start = {ns: peer.poses(ns) for ns in ROBOTS}
    for ns, (x, y) in ROBOTS.items():  # each ground truth is its own robot's
        assert start[ns][0][:2] == pytest.approx((x, y), abs=0.05)

    # r1 forward, r2 turning in place, at the same time
    for _ in range(8):
        peer.command({'r1': (0.5, 0.0), 'r2': (0.0, 0.8)})
        peer.step(CHUNK_STEPS)
    peer.command({'r1': (0.0, 0.0), 'r2': (0.0, 0.0)})
    peer.step(500)
    end = {ns: peer.poses(ns) for ns in ROBOTS}

    (t0, o0), (t1, o1) = start['r1'], end['r1']
    forward = math.hypot(t1[0] - t0[0], t1[1] - t0[1])
    assert forward == pytest.approx(1.0, rel=0.1) and t1[0] - t0[0] > 0.9
    assert abs(t1[2] - t0[2]) < 0.05
    assert math.hypot(o1[0] - o0[0], o1[1] - o0[1]) == pytest.approx(forward, rel=0.03)

    (t0, o0), (t1, o1) = start['r2'], end['r2']
    turn = t1[2] - t0[2]
    assert turn > 0.8  # about 1.6 rad commanded
    assert math.hypot(t1[0] - t0[0], t1[1] - t0[1]) < 0.1
    assert o1[2] - o0[2] == pytest.approx(turn, rel=0.1)

    # TF: two separate trees, every frame prefixed with its robot's namespace
    assert peer.spin_until(lambda: all((f'{ns}/base_footprint', f'{ns}/base_link') in peer.edges
                                       for ns in ROBOTS), 60), peer.edges
    edges = set(peer.edges)
    for ns in ROBOTS:
        # REP 105: odometry to the URDF root; base_link has one parent
        assert (f'{ns}/odom', f'{ns}/base_footprint') in edges, edges
        assert (f'{ns}/odom', f'{ns}/base_link') not in edges, edges
        assert (f'{ns}/base_link', f'{ns}/wheel_front_left') in edges, edges
    for parent, child in edges:
        assert re.match(r'r[12]/', child) and child[:3] == parent[:3], (parent, child)
    # the controller's odometry frames too
    assert peer.odom_of['r2'][-1].header.frame_id == 'r2/odom'
    assert peer.odom_of['r2'][-1].child_frame_id == 'r2/base_footprint'


def test_fleet_stack_comes_up_in_the_arena(procs, exe, ros_env, tmp_path):
    # four robots (all 10 processes started at once, as a launch file does: the robot state
    # publishers composed in one container) in real time, in the shipped arena world (its
    # pillars and walls keep clear of the fleet grid: no robot overlaps a model);
    # every robot's two controllers active (both spawners' log lines), each robot's
    # odometry and ground truth heard at its grid position; deadlines generous for a
    # loaded machine (the fleet benchmark measures the start-up time)
    pytest.importorskip('controller_manager_msgs.srv')
    peer = FleetPeer(int(ros_env['ROS_DOMAIN_ID']), STACK_ROBOTS)
    try:
        proc = procs.start([exe('bringup'), 'fleet', f'robots:={len(STACK_ROBOTS)}',
                            'world:=arena', 'viewer:=false'], ros_env)

        def activated():
            return proc.output.count('Configured and activated') == 2 * len(STACK_ROBOTS)
        assert peer.spin_until(activated, 240), proc.output[-4000:]
        assert peer.spin_until(lambda: all(peer.odom_of[ns] and peer.truth_of[ns]
                                           for ns in STACK_ROBOTS), 60), proc.output[-4000:]
        for ns, (x, y) in STACK_ROBOTS.items():
            assert _pose(peer.truth_of[ns][-1])[:2] == pytest.approx((x, y), abs=0.05)
        assert peer.spin_until(lambda: ('r4/base_footprint', 'r4/base_link') in peer.edges,
                               30), peer.edges
        assert "world 'arena'" in proc.output, proc.output[-3000:]
        assert 'overlapping world model' not in proc.output, proc.output[-3000:]
        assert proc.interrupt(timeout=30) == 0, proc.output[-3000:]
    finally:
        peer.close()


FLEET_COMMANDER = """
import math
import sys

from geometry_msgs.msg import PoseStamped
from nav2_simple_commander.robot_navigator import BasicNavigator, TaskResult
import rclpy


def pose(navigator, x, y, yaw):
    msg = PoseStamped()
    msg.header.frame_id = 'map'
    msg.header.stamp = navigator.get_clock().now().to_msg()
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.z, msg.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return msg


rclpy.init()
namespace, start, goal = sys.argv[1], sys.argv[2:5], sys.argv[5:8]
navigator = BasicNavigator(namespace=namespace)
navigator.setInitialPose(pose(navigator, *map(float, start)))
navigator.waitUntilNav2Active()
navigator.goToPose(pose(navigator, *map(float, goal)))
while not navigator.isTaskComplete():
    navigator.getFeedback()
result = navigator.getResult()
print('result:', result)
navigator.destroy_node()
rclpy.shutdown()
sys.exit(0 if result == TaskResult.SUCCEEDED else 1)
"""
"""A multi-robot nav2_simple_commander script: one robot's BasicNavigator by its namespace."""

FLEET_GOALS = {'r1': (0.5, 1.9, math.pi / 2), 'r2': (1.5, -1.55, -math.pi / 2)}
"""Each robot's goal in arena.sdf (map frame), through the gap of two pillars."""


def test_fleet_robots_navigate_at_once_each_with_its_nav2(procs, exe, ros_env, tmp_path):
    # nav2_bringup's multi-robot bring-up: map_server, AMCL and the servers of each robot in
    # its namespace (one container each), frames prefixed rI/, every AMCL in the one map
    # frame; both goals sent at once (r2's by a nav2_simple_commander script), each robot
    # reaches its own by ground truth
    pytest.importorskip('nav2_msgs.action')
    from action_msgs.msg import GoalStatus
    from geometry_msgs.msg import PolygonStamped
    from geometry_msgs.msg import PoseWithCovarianceStamped
    from nav2_msgs.action import NavigateToPose
    from rclpy.action import ActionClient
    from rclpy.qos import DurabilityPolicy
    from rclpy.qos import QoSProfile
    peer = FleetPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        amcl = {ns: [] for ns in FLEET_GOALS}
        footprints = {ns: [] for ns in FLEET_GOALS}
        for ns in FLEET_GOALS:
            peer.node.create_subscription(PolygonStamped,
                                          f'/{ns}/global_costmap/published_footprint',
                                          footprints[ns].append, 10)
            peer.node.create_subscription(
                PoseWithCovarianceStamped, f'/{ns}/amcl_pose', amcl[ns].append,
                QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        proc = procs.start([exe('ros2'), 'launch', 'amr_description', 'fleet.launch.py',
                            'robots:=2', 'world:=arena', 'navigation:=true', 'viewer:=false'],
                           ros_env)
        for ns in FLEET_GOALS:
            for manager in ('localization', 'navigation'):
                assert proc.wait_for_output(f'[{ns}.lifecycle_manager_{manager}]: Managed '
                                            'nodes are active', 240.0), proc.output[-3000:]
        assert proc.wait_for_output("Loaded component 'nav2_amcl::AmclNode' as '/r2/amcl'",
                                    10.0), proc.output[-3000:]
        # each AMCL starts at its robot's spawn (set_initial_pose), in the shared map frame
        assert peer.spin_until(lambda: all(amcl.values()), 120.0), proc.output[-3000:]
        for ns, (x, y) in STACK_ROBOTS.items():
            if ns in amcl:
                pose = amcl[ns][-1]
                assert pose.header.frame_id == 'map'
                assert (pose.pose.pose.position.x, pose.pose.pose.position.y) == \
                    pytest.approx((x, y), abs=0.1)
        assert peer.spin_until(lambda: all(('map', f'{ns}/odom') in peer.edges
                                           for ns in FLEET_GOALS), 60.0), peer.edges
        # the planner knows its robot's pose in map once the global costmap shows its footprint
        assert peer.spin_until(lambda: all(footprints.values()), 120.0), proc.output[-3000:]
        assert footprints['r2'][-1].header.frame_id == 'map'
        # r2 from a nav2_simple_commander script in upstream's multi-robot form
        # (BasicNavigator(namespace='r2'), its initial pose at the spawn), r1 by its action
        script = tmp_path / 'r2_commander.py'
        script.write_text(FLEET_COMMANDER)
        x, y, yaw = FLEET_GOALS['r2']
        commander = procs.start([sys.executable, str(script), 'r2', '2.0', '0.0', '0.0',
                                 str(x), str(y), str(yaw)], ros_env)
        handles = {}
        for ns, (x, y, yaw) in list(FLEET_GOALS.items())[:1]:
            client = ActionClient(peer.node, NavigateToPose, f'/{ns}/navigate_to_pose')
            assert client.wait_for_server(timeout_sec=60.0), ns
            goal = NavigateToPose.Goal()
            goal.pose.header.frame_id = 'map'
            goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
            goal.pose.pose.orientation.z = math.sin(yaw / 2.0)
            goal.pose.pose.orientation.w = math.cos(yaw / 2.0)
            sent = client.send_goal_async(goal)
            assert peer.spin_until(sent.done, 60.0) and sent.result().accepted, ns
            handles[ns] = sent.result().get_result_async()
        assert peer.spin_until(lambda: all(h.done() for h in handles.values()) and
                               commander.popen.poll() is not None, 400.0), proc.output[-3000:]
        result = handles['r1'].result()
        assert result.status == GoalStatus.STATUS_SUCCEEDED, (result.result.error_code,
                                                              proc.output[-3000:])
        assert commander.wait(10) == 0, commander.output + proc.output[-3000:]
        assert 'Nav2 is ready for use!' in commander.output, commander.output
        for ns, (x, y, yaw) in FLEET_GOALS.items():
            tx, ty, tyaw = _pose(peer.truth_of[ns][-1])
            print(f'{ns}: ground truth {math.hypot(tx - x, ty - y):.3f} m'
                  f' {abs(math.remainder(tyaw - yaw, math.tau)):.3f} rad from the goal')
            # Nav2's default tolerances (0.25 m, 0.25 rad) plus AMCL's error
            assert math.hypot(tx - x, ty - y) < 0.35, ns
            assert abs(math.remainder(tyaw - yaw, math.tau)) < 0.45, ns
        assert proc.interrupt(timeout=60) == 0, proc.output[-3000:]
    finally:
        peer.close()
