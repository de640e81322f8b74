# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
mujoco_sim with several robots over real DDS: namespaces, graph leaks, clocks, two simulators.

Two namespaced robots in one simulator are driven independently (one forward, one turning),
each odometry following its own ground truth; a rejected spawn leaves the ROS graph exactly as
it was; a second simulator refuses to start next to a /clock publisher unless it follows it
(``clock_source:=external``), and then steps its own robot in the first one's time.
"""

import math
import os
import subprocess
import time

import pytest

pytest.importorskip('rclpy')

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


def _stamp(msg):
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def _yaw(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


class Peer:
    """Test node: /clock, ground truth and odometry per namespace, spawn clients, cmd_vel."""

    def __init__(self, domain_id):
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rosgraph_msgs.msg import Clock

        self.rclpy = rclpy
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('fleet_test_peer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.clock = []
        self.node.create_subscription(
            Clock, '/clock', lambda m: self.clock.append(m.clock.sec + m.clock.nanosec * 1e-9),
            100)
        self.topics = {}
        self._publishers = {}

    def listen(self, topic):
        from nav_msgs.msg import Odometry
        self.topics[topic] = []
        self.node.create_subscription(Odometry, topic, self.topics[topic].append, 100)

    def spin_until(self, predicate, timeout=60.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if predicate():
                return True
            self.executor.spin_once(timeout_sec=0.02)
        return predicate()

    def spawn(self, service, namespace, x, y, urdf=None, name=None):
        from simulation_interfaces import srv
        client = self.node.create_client(srv.SpawnEntity, service)
        assert client.wait_for_service(timeout_sec=30), f'no {service}'
        request = srv.SpawnEntity.Request()
        request.name = name or namespace or 'amr'
        request.entity_namespace = namespace
        if urdf is None:
            request.entity_resource.uri = URDF_PATH
        else:
            request.entity_resource.resource_string = urdf
        request.initial_pose.pose.position.x = float(x)
        request.initial_pose.pose.position.y = float(y)
        request.initial_pose.pose.position.z = 0.05
        request.initial_pose.pose.orientation.w = 1.0
        future = client.call_async(request)
        assert self.spin_until(future.done, 60), 'spawn: no answer'
        self.node.destroy_client(client)
        return future.result()

    def drive(self, topic, linear, angular):
        from geometry_msgs.msg import TwistStamped
        if topic not in self._publishers:
            self._publishers[topic] = self.node.create_publisher(TwistStamped, topic, 10)
        msg = TwistStamped()
        msg.twist.linear.x = float(linear)
        msg.twist.angular.z = float(angular)
        self._publishers[topic].publish(msg)

    def close(self):
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


@pytest.fixture
def peer(ros_env):
    p = Peer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def _node_list(exe, env):
    result = subprocess.run([exe('ros2'), 'node', 'list'], env=env, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    return sorted(line for line in result.stdout.split() if line != '/fleet_test_peer')


def _settled_node_list(exe, env, expected, timeout=90.0):
    """
    Return ``ros2 node list`` once it equals ``expected``, or the last one after ``timeout``.

    Discovery of a node can lag on a loaded machine (a first list may be empty); a node that
    leaked stays in the graph, so it still shows after the deadline.
    """
    deadline = time.monotonic() + timeout
    while True:
        nodes = _node_list(exe, env)
        if nodes == expected or time.monotonic() > deadline:
            return nodes


def _spawner(procs, exe, env, cm):
    spawner = procs.start([exe('spawner'), 'joint_state_broadcaster', 'diff_drive_controller',
                           '-c', cm, '--controller-manager-timeout', '60'], env)
    assert spawner.wait(120) == 0, spawner.output
    return spawner


def _drive_until(peer, commands, predicate, timeout=60.0):
    """Publish ``commands`` {topic: (v, w)} every ~20 ms until ``predicate()`` or timeout."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not predicate():
        for topic, (v, w) in commands.items():
            peer.drive(topic, v, w)
        peer.spin_until(lambda: False, 0.02)
    return predicate()


def test_two_namespaced_robots_driven_independently(procs, exe, ros_env, peer):
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=1.0'], ros_env)
    assert peer.spin_until(lambda: peer.clock, 30), sim.output
    assert _settled_node_list(exe, ros_env, ['/mujoco_sim']) == ['/mujoco_sim']
    # a rejected robot (unknown hardware plugin) leaves nothing behind in the graph
    with open(URDF_PATH) as f:
        bad = f.read().replace('amr_description/MujocoSystem', 'acme/NoSuchSystem')
    result = peer.spawn('/mujoco_sim/spawn_entity', 'r9', 0, 5, urdf=bad)
    assert result.result.result != 1 and 'NoSuchSystem' in result.result.error_message
    assert _settled_node_list(exe, ros_env, ['/mujoco_sim']) == ['/mujoco_sim'], sim.output

    for ns, y in (('r1', 0.0), ('r2', 2.0)):
        result = peer.spawn('/mujoco_sim/spawn_entity', ns, 0.0, y)
        assert result.result.result == 1, result.result.error_message
        assert result.entity_name == ns
    # same namespace again: refused, the first keeps running
    again = peer.spawn('/mujoco_sim/spawn_entity', 'r1', 4.0, 4.0, name='other')
    assert again.result.result != 1 and "namespace '/r1' is already used" in \
        again.result.error_message
    invalid = peer.spawn('/mujoco_sim/spawn_entity', '1r', 4.0, 4.0, name='x')
    assert 'not a valid ROS namespace' in invalid.result.error_message
    for ns in ('r1', 'r2'):
        _spawner(procs, exe, ros_env, f'/{ns}/controller_manager')
    expected = sorted([
        '/mujoco_sim', '/r1/controller_manager', '/r1/joint_state_broadcaster',
        '/r1/diff_drive_controller', '/r2/controller_manager', '/r2/joint_state_broadcaster',
        '/r2/diff_drive_controller'])
    assert _settled_node_list(exe, ros_env, expected) == expected

    for topic in ('/r1/ground_truth/odom', '/r2/ground_truth/odom',
                  '/r1/diff_drive_controller/odom', '/r2/diff_drive_controller/odom'):
        peer.listen(topic)
    assert peer.spin_until(lambda: all(peer.topics.values()), 30)
    gt1, gt2 = peer.topics['/r1/ground_truth/odom'], peer.topics['/r2/ground_truth/odom']
    assert gt1[-1].child_frame_id == 'r1/base_footprint'
    start1, start2 = gt1[-1].pose.pose, gt2[-1].pose.pose
    _drive_until(peer, {'/r1/diff_drive_controller/cmd_vel': (0.3, 0.0),
                        '/r2/diff_drive_controller/cmd_vel': (0.0, 0.8)},
                 lambda: gt1[-1].pose.pose.position.x - start1.position.x > 0.5 and
                 abs(_yaw(gt2[-1].pose.pose.orientation) - _yaw(start2.orientation)) > 1.0)
    end1, end2 = gt1[-1].pose.pose, gt2[-1].pose.pose
    # r1 went forward along +x, r2 turned in place near (0, 2)
    assert end1.position.x - start1.position.x > 0.3
    assert abs(end1.position.y - start1.position.y) < 0.1
    assert abs(_yaw(end2.orientation) - _yaw(start2.orientation)) > 0.5
    assert math.hypot(end2.position.x - start2.position.x,
                      end2.position.y - start2.position.y) < 0.15
    # each odometry follows its own robot (odometry starts at its spawn pose: compare motion)
    odom1 = peer.topics['/r1/diff_drive_controller/odom']
    odom2 = peer.topics['/r2/diff_drive_controller/odom']
    assert odom1[-1].pose.pose.position.x > 0.3
    assert abs(odom2[-1].pose.pose.position.x) < 0.15
    assert abs(_yaw(odom2[-1].pose.pose.orientation)) > 0.3
    assert sim.popen.poll() is None and 'Traceback' not in sim.output


def test_second_simulator_refused_unless_external(procs, exe, ros_env, peer):
    first = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=1.0'],
                        ros_env)
    # past its own 10 s watch for other /clock publishers (sim time runs at most at wall time)
    assert peer.spin_until(lambda: peer.clock and peer.clock[-1] > 10.5, 60), first.output
    second = procs.start([exe('mujoco_sim'), '--ros-args', '-r',
                          'mujoco_sim:__node:=mujoco_sim_b'], ros_env)
    assert second.wait(60) == 1, second.output
    errors = [line for line in second.output.splitlines() if 'ERROR' in line]
    assert len(errors) == 1 and 'another node already publishes /clock' in errors[0]
    assert 'clock_source:=external' in errors[0] and 'Traceback' not in second.output

    follower = procs.start([exe('mujoco_sim'), '--ros-args', '-r',
                            'mujoco_sim:__node:=mujoco_sim_b', '-p', 'clock_source:=external'],
                           ros_env)
    peer.listen('/a/ground_truth/odom')
    peer.listen('/b/ground_truth/odom')
    assert peer.spawn('/mujoco_sim/spawn_entity', 'a', 0, 0).result.result == 1
    result = peer.spawn('/mujoco_sim_b/spawn_entity', 'b', 0, 3)
    assert result.result.result == 1, result.result.error_message + follower.output
    _spawner(procs, exe, ros_env, '/b/controller_manager')
    gt_a, gt_b = peer.topics['/a/ground_truth/odom'], peer.topics['/b/ground_truth/odom']
    assert peer.spin_until(lambda: gt_a and gt_b, 30)
    start, start_time = gt_b[-1].pose.pose.position.x, _stamp(gt_b[-1])
    _drive_until(peer, {'/b/diff_drive_controller/cmd_vel': (0.3, 0.0)},
                 lambda: gt_b[-1].pose.pose.position.x - start > 0.3 and
                 _stamp(gt_b[-1]) > start_time + 2.0)
    # b drove, in the time of the first simulator (it lags when the machine is loaded)
    assert gt_b[-1].pose.pose.position.x - start > 0.3
    assert abs(_stamp(gt_a[-1]) - _stamp(gt_b[-1])) < 10.0
    # never ahead of it: with the clock source paused, b stops at (or before) its time
    from simulation_interfaces import msg
    from simulation_interfaces import srv
    client = peer.node.create_client(srv.SetSimulationState, '/mujoco_sim/set_simulation_state')
    assert client.wait_for_service(timeout_sec=30)
    request = srv.SetSimulationState.Request()
    request.state.state = msg.SimulationState.STATE_PAUSED
    future = client.call_async(request)
    assert peer.spin_until(future.done, 30) and future.result().result.result == 1
    peer.spin_until(lambda: False, 1.0)  # /clock messages sent before the pause arrive
    paused_at = peer.clock[-1]
    assert peer.spin_until(lambda: _stamp(gt_b[-1]) >= paused_at - 0.02, 30)
    peer.spin_until(lambda: False, 1.0)
    assert paused_at - 0.02 <= _stamp(gt_b[-1]) <= paused_at + 1e-9
    assert peer.clock[-1] == paused_at
    assert first.popen.poll() is None and follower.popen.poll() is None
    assert 'Traceback' not in first.output + follower.output
