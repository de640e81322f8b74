# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""mujoco_sim + create over real DDS: clock, spawn and settle, pause/step/reset, bad input."""

import os
import time

import pytest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


class Peer:
    """A test-process node on the test's domain: /clock, ground truth, simulator services."""

    def __init__(self, domain_id):
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from simulation_interfaces import msg
        from simulation_interfaces import srv

        os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
        self.rclpy = rclpy
        self.msg = msg
        self.srv = srv
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('sim_test_peer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.clock = []
        self.odom = []
        self.node.create_subscription(Clock, '/clock', self._on_clock, 10)
        self.node.create_subscription(Odometry, '/ground_truth/odom', self.odom.append, 100)
        self.clients = {
            'reset': self.node.create_client(srv.ResetSimulation,
                                             '/mujoco_sim/reset_simulation'),
            'state': self.node.create_client(srv.SetSimulationState,
                                             '/mujoco_sim/set_simulation_state'),
            'step': self.node.create_client(srv.StepSimulation, '/mujoco_sim/step_simulation'),
        }

    def _on_clock(self, msg):
        self.clock.append(msg.clock.sec + msg.clock.nanosec * 1e-9)

    @property
    def now(self):
        """Return the latest /clock time in s (None before the first message)."""
        return self.clock[-1] if self.clock else None

    def spin_until(self, predicate, timeout=60.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if predicate():
                return True
            self.executor.spin_once(timeout_sec=0.02)
        return predicate()

    def spin_for(self, seconds):
        self.spin_until(lambda: False, timeout=seconds)

    def call(self, name, request, timeout=60.0):
        client = self.clients[name]
        assert client.wait_for_service(timeout_sec=timeout), f'no service {name}'
        future = client.call_async(request)
        assert self.spin_until(future.done, timeout), f'{name}: no answer'
        return future.result()

    def set_state(self, state):
        """
        Set the simulation state; once paused, wait until :attr:`now` is the paused time.

        /clock messages sent before the pause may still be queued when the answer comes (a
        fast-forwarding world sends many): the paused simulator repeats its unchanged time at
        10 Hz (wall), so two equal times received after the answer mean the queue is drained.
        """
        request = self.srv.SetSimulationState.Request()
        request.state.state = state
        result = self.call('state', request).result
        if state == request.state.STATE_PAUSED and result.result == result.RESULT_OK:
            seen = len(self.clock)
            assert self.spin_until(lambda: len(self.clock) > seen + 1
                                   and self.clock[-1] == self.clock[-2], 30), \
                'no unchanged /clock after the pause'
        return result

    def close(self):
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


@pytest.fixture
def peer(ros_env):
    p = Peer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def _sim(procs, exe, ros_env, *params):
    args = [exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0.0']
    for param in params:
        args += ['-p', param]
    return procs.start(args, ros_env)


def test_clock_spawn_settle_pause_step_reset(procs, exe, ros_env, peer):
    sim = _sim(procs, exe, ros_env)
    # /clock runs before any robot exists, fast-forward
    assert peer.spin_until(lambda: peer.now is not None and peer.now > 1.0, 60), sim.output
    create = procs.start([exe('create'), '-file', URDF_PATH, '-name', 'amr', '-z', '0.2'],
                         ros_env)
    assert create.wait(40) == 0, create.output + sim.output
    assert 'OK creation of entity [amr].' in create.output
    # dropped from 0.2 m, comes to rest on its wheels: base_footprint on the ground
    spawned_at = peer.now
    assert peer.spin_until(lambda: peer.odom and peer.now > spawned_at + 3.0, 60)
    rest = peer.odom[-1]
    assert rest.header.frame_id == 'world' and rest.child_frame_id == 'base_footprint'
    assert abs(rest.pose.pose.position.z) < 0.005
    assert abs(rest.twist.twist.linear.x) < 1e-3
    x0, y0 = rest.pose.pose.position.x, rest.pose.pose.position.y
    assert abs(x0) < 1e-3 and abs(y0) < 1e-3
    # no bounce: after 1 s from the first contact, z stays within 1 cm of rest
    after = [m.pose.pose.position.z for m in peer.odom
             if m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 > spawned_at + 1.0]
    assert max(after) - min(after) < 0.01

    PLAYING, PAUSED = peer.msg.SimulationState.STATE_PLAYING, \
        peer.msg.SimulationState.STATE_PAUSED
    assert peer.set_state(PAUSED).result == peer.msg.Result.RESULT_OK
    assert peer.set_state(PAUSED).result == \
        peer.srv.SetSimulationState.Response.ALREADY_IN_TARGET_STATE
    peer.spin_for(0.3)
    paused_at = peer.now
    peer.spin_for(0.5)
    assert peer.now == paused_at
    step = peer.srv.StepSimulation.Request()
    step.steps = 250
    assert peer.call('step', step).result.result == peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: peer.now >= paused_at + 0.25 - 1e-9, 60)
    assert peer.now == pytest.approx(paused_at + 0.25, abs=1e-6)

    assert peer.call('reset', peer.srv.ResetSimulation.Request()).result.result == \
        peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: peer.now == 0.0, 60)
    assert peer.spin_until(lambda: peer.odom[-1].pose.pose.position.z > 0.19, 60)
    assert peer.set_state(PLAYING).result == peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: peer.now > 1.0, 60)
    step.steps = 1
    assert peer.call('step', step).result.result == peer.msg.Result.RESULT_OPERATION_FAILED
    assert sim.popen.poll() is None


def test_bad_input_keeps_simulator_running(procs, exe, ros_env, peer, tmp_path):
    sim = _sim(procs, exe, ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    with open(URDF_PATH) as f:
        good = f.read()
    cases = [
        ('<robot name="x"><link name="a"/>', 'not well-formed'),
        (good.replace('<child link="wheel_back_left"/>', '<child link="nowhere"/>'),
         "'nowhere' does not exist"),
        (good.replace('<joint name="joint_wheel_back_left">\n      <command',
                      '<joint name="joint_ghost">\n      <command'), 'joint_ghost'),
        (good.replace('amr_description/MujocoSystem', 'acme/NoSuchSystem'), 'NoSuchSystem'),
    ]
    for urdf, message in cases:
        create = procs.start([exe('create'), '-string', urdf], ros_env)
        assert create.wait(40) == 1, create.output
        errors = [line for line in create.output.splitlines() if '[ERROR]' in line]
        assert len(errors) == 1 and message in errors[0], create.output
        assert 'Traceback' not in sim.output
    before = peer.now
    assert peer.spin_until(lambda: peer.now > before + 0.5, 60)
    # the simulator is still usable: the good robot spawns, a second one with that name not
    create = procs.start([exe('create'), '-file', URDF_PATH], ros_env)
    assert create.wait(40) == 0, create.output + sim.output
    assert 'OK creation of entity [amr].' in create.output
    again = procs.start([exe('create'), '-file', URDF_PATH], ros_env)
    assert again.wait(40) == 1
    assert 'already exists' in again.output
    missing = procs.start([exe('create'), '-file', str(tmp_path / 'none.urdf')], ros_env)
    assert missing.wait(60) == 1
    assert 'cannot read -file' in missing.output
    assert sim.interrupt(10) == 0
    assert 'Traceback' not in sim.output


def test_create_times_out_without_simulator(procs, exe, ros_env):
    create = procs.start([exe('create'), '-file', URDF_PATH, '-timeout', '1'], ros_env)
    assert create.wait(30) == 1
    assert 'service /mujoco_sim/spawn_entity not available after 1 s' in create.output


def test_create_from_topic_with_pose(procs, exe, ros_env, peer):
    from rclpy.qos import DurabilityPolicy
    from rclpy.qos import QoSProfile
    from std_msgs.msg import String

    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    description = peer.node.create_publisher(String, 'robot_description', latched)
    with open(URDF_PATH) as f:
        description.publish(String(data=f.read()))
    sim = _sim(procs, exe, ros_env)
    create = procs.start([exe('create'), '-topic', 'robot_description', '-x', '1.0', '-y',
                          '-2.0', '-z', '0.2', '-Y', '1.5707963'], ros_env)
    # the latched description reaches create while the test spins its publisher
    assert peer.spin_until(lambda: create.popen.poll() is not None, 60), create.output
    assert create.popen.returncode == 0, create.output + sim.output
    assert 'Waiting messages on topic [robot_description].' in create.output
    # ground truth can arrive before the first /clock (peer.now still None)
    assert peer.spin_until(lambda: peer.odom and peer.now is not None and peer.now > 2.0 and
                           peer.odom[-1].header.stamp.sec >= 2, 60)
    pose = peer.odom[-1].pose.pose
    assert pose.position.x == pytest.approx(1.0, abs=2e-3)
    assert pose.position.y == pytest.approx(-2.0, abs=2e-3)
    assert abs(pose.position.z) < 0.005
    # yaw 90 degrees: quaternion (0, 0, sin 45, cos 45)
    assert pose.orientation.z == pytest.approx(0.7071, abs=2e-3)
    assert pose.orientation.w == pytest.approx(0.7071, abs=2e-3)


def test_start_paused_clock_and_step(procs, exe, ros_env, peer):
    sim = _sim(procs, exe, ros_env, 'paused:=true', 'physics_step:=0.002')
    assert peer.spin_until(lambda: len(peer.clock) >= 3, 60), sim.output
    assert set(peer.clock) == {0.0}
    step = peer.srv.StepSimulation.Request()
    step.steps = 5
    assert peer.call('step', step).result.result == peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: peer.now == pytest.approx(0.01, abs=1e-9), 60)
    peer.spin_for(0.3)
    assert peer.now == pytest.approx(0.01, abs=1e-9)
