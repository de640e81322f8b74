# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""robot_state_publisher over real DDS: description, static and moving transforms, bad input."""

import math
import os
import time

import pytest
import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')
WHEELS = ['joint_wheel_front_left', 'joint_wheel_front_right', 'joint_wheel_back_left',
          'joint_wheel_back_right']


class Peer:
    """A test-process node on the test's domain: subscribes to RSP outputs, publishes joints."""

    def __init__(self, domain_id):
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        from sensor_msgs.msg import JointState
        from std_msgs.msg import String
        from tf2_msgs.msg import TFMessage

        os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
        self.rclpy = rclpy
        self.JointState = JointState
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('rsp_test_peer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.description = []
        self.static = []
        self.tf = []
        self.node.create_subscription(String, 'robot_description', self.description.append,
                                      latched)
        self.node.create_subscription(TFMessage, '/tf_static', self.static.append, latched)
        self.node.create_subscription(TFMessage, '/tf', self.tf.append, 100)
        self.joint_pub = self.node.create_publisher(JointState, 'joint_states', 10)

    def spin_until(self, predicate, timeout=60.0, action=None, period=0.1):
        """Spin until ``predicate()``; call ``action()`` every ``period`` s meanwhile."""
        deadline = time.monotonic() + timeout
        next_action = 0.0
        while time.monotonic() < deadline:
            if predicate():
                return True
            if action is not None and time.monotonic() >= next_action:
                action()
                next_action = time.monotonic() + period
            self.executor.spin_once(timeout_sec=0.02)
        return predicate()

    def joint_state(self, sec, names, positions):
        msg = self.JointState()
        msg.header.stamp.sec = sec
        msg.name = list(names)
        msg.position = [float(p) for p in positions]
        return msg

    def close(self):
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


def transforms(messages):
    """Return {(parent, child): TransformStamped} of the latest of each pair."""
    return {(t.header.frame_id, t.child_frame_id): t for m in messages for t in m.transforms}


@pytest.fixture
def rsp(procs, exe, ros_env, tmp_path):
    with open(URDF_PATH) as f:
        description = f.read()
    params = tmp_path / 'rsp.yaml'
    params.write_text(yaml.safe_dump(
        {'robot_state_publisher': {'ros__parameters': {'robot_description': description}}}))
    proc = procs.start([exe('robot_state_publisher'), '--ros-args', '--params-file',
                        str(params)], ros_env)
    assert proc.wait_for_output('got segment wheel_back_right', 15.0), proc.output
    peer = Peer(int(ros_env['ROS_DOMAIN_ID']))
    yield proc, peer, description
    peer.close()


def test_late_subscriber_gets_description_static_and_tf(rsp):
    proc, peer, description = rsp
    assert peer.spin_until(lambda: peer.description and peer.static)
    assert peer.description[-1].data == description
    static = transforms(peer.static)
    assert list(static) == [('base_footprint', 'base_link')]
    t = static[('base_footprint', 'base_link')].transform
    assert (t.translation.x, t.translation.y, t.translation.z) == (0.0, 0.0, 0.1)
    assert t.rotation.w == 1.0

    stamp = [100]

    def publish():
        stamp[0] += 1
        peer.joint_pub.publish(peer.joint_state(stamp[0], WHEELS, [math.pi / 2, 0, 0, 0]))

    def have_all():
        return all(('base_link', w.replace('joint_', '')) in transforms(peer.tf) for w in WHEELS)

    assert peer.spin_until(have_all, action=publish), proc.output
    tf = transforms(peer.tf)
    front_left = tf[('base_link', 'wheel_front_left')]
    assert front_left.header.stamp.sec > 100
    tr, q = front_left.transform.translation, front_left.transform.rotation
    assert (tr.x, tr.y, tr.z) == pytest.approx((0.2, 0.15, 0.0))
    # Rx(-90 deg) then a quarter turn about the wheel z: q = (-1/2, 1/2, 1/2, 1/2).
    assert (q.x, q.y, q.z, q.w) == pytest.approx((-0.5, 0.5, 0.5, 0.5), abs=1e-4)
    back_right = tf[('base_link', 'wheel_back_right')].transform
    assert (back_right.translation.x, back_right.translation.y) == pytest.approx((-0.2, -0.15))


def test_malformed_joint_state_is_rejected_and_node_keeps_running(rsp):
    proc, peer, _ = rsp
    stamp = [200]

    def publish_bad():
        stamp[0] += 1
        peer.joint_pub.publish(peer.joint_state(stamp[0], WHEELS, [0.0, 0.0]))

    expected = 'Ignored an invalid JointState message on /joint_states: 4 names but 2 positions'
    assert peer.spin_until(lambda: expected in proc.output, action=publish_bad), proc.output
    assert '[ERROR]' in proc.output and 'Traceback' not in proc.output
    assert peer.tf == []

    def publish_good():
        stamp[0] += 1
        peer.joint_pub.publish(peer.joint_state(stamp[0], WHEELS[:1], [0.0]))

    assert peer.spin_until(lambda: peer.tf, action=publish_good), proc.output
    assert proc.popen.poll() is None


def test_empty_description_exits_1(procs, exe, ros_env):
    proc = procs.start([exe('robot_state_publisher')], ros_env)
    assert proc.wait(60.0) == 1
    assert 'robot_description parameter must not be empty' in proc.output
    assert 'Traceback' not in proc.output
