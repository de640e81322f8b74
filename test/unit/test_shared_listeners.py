# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A container's TF listeners share one node and thread; each still fills its own buffer.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes.
"""

import os
import threading
import time

from conftest import next_domain_id
import pytest

rclpy = pytest.importorskip('rclpy')

import rclpy.node  # noqa: E402, I100

from amr_description.core.tf_buffer import TransformBuffer  # noqa: E402, I100
from amr_description.ros import transforms  # noqa: E402
from geometry_msgs.msg import TransformStamped  # noqa: E402
from tf2_msgs.msg import TFMessage  # noqa: E402


def _transform(stamp, x):
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = 'odom', 'base_footprint'
    t.header.stamp.sec = stamp
    t.transform.translation.x = x
    t.transform.rotation.w = 1.0
    return TFMessage(transforms=[t])


def _wait(condition, timeout=30.0):
    deadline = time.monotonic() + timeout
    while not condition() and time.monotonic() < deadline:
        time.sleep(0.02)
    return condition()


@pytest.fixture
def sharing(monkeypatch):
    """Three nodes on a fresh context with listener sharing on; the listeners made go at end."""
    os.environ['ROS_DOMAIN_ID'] = str(next_domain_id())
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    monkeypatch.setattr(transforms, '_sharing', [])
    monkeypatch.setattr(transforms, '_HUBS', {})
    context = rclpy.context.Context()
    rclpy.init(context=context)
    nodes = [rclpy.node.Node(name, context=context) for name in ('a', 'b', 'pub')]
    listeners = []
    try:
        yield nodes, listeners
    finally:
        for listener in listeners:
            listener.destroy()
        for node in nodes:
            node.destroy_node()
        rclpy.shutdown(context=context)


def test_listeners_share_one_thread_and_fill_their_own_buffers(sharing):
    nodes, listeners = sharing
    threads_before = threading.active_count()
    transforms.share_listener_threads()
    buffers = [TransformBuffer(), TransformBuffer()]
    listeners += [transforms.TransformListener(node, buf, spin_thread=True)
                  for node, buf in zip(nodes, buffers)]
    assert threading.active_count() == threads_before + 1  # one thread for both
    assert len(transforms._HUBS) == 1
    publisher = nodes[2].create_publisher(TFMessage, '/tf', 100)

    def seen(buf, stamp):
        try:
            return float(buf.lookup('odom', 'base_footprint', float(stamp))[0][0, 3])
        except Exception:  # noqa: B902 - not there yet
            return None

    assert _wait(lambda: publisher.get_subscription_count() == 1)  # one subscription
    publisher.publish(_transform(1, 0.5))
    assert _wait(lambda: all(seen(b, 1) == 0.5 for b in buffers))
    listeners[0].destroy()  # the other one keeps hearing
    publisher.publish(_transform(2, 0.7))
    assert _wait(lambda: seen(buffers[1], 2) == 0.7)
    assert len(transforms._HUBS) == 1
    listeners[1].destroy()  # the last one out stops the thread
    assert transforms._HUBS == {}
    assert _wait(lambda: threading.active_count() == threads_before)


def test_a_listener_joining_later_gets_the_static_transforms_heard_before(sharing):
    # /tf_static is transient local: a listener of its own would get the earlier statics from
    # its subscription, so one joining the shared hub later gets them from the hub
    nodes, listeners = sharing
    transforms.share_listener_threads()
    first, late = TransformBuffer(), TransformBuffer()
    listeners.append(transforms.TransformListener(nodes[0], first, spin_thread=True))
    publisher = nodes[2].create_publisher(TFMessage, '/tf_static', transforms.STATIC_QOS)
    msg = _transform(0, 0.25)
    msg.transforms[0].header.frame_id, msg.transforms[0].child_frame_id = 'a', 'b'
    publisher.publish(msg)
    msg.transforms[0].transform.translation.x = 0.5  # the latest of a child frame wins
    publisher.publish(msg)

    def x_of(buf):
        try:
            return float(buf.lookup('a', 'b')[0][0, 3])
        except Exception:  # noqa: B902 - not there yet
            return None

    assert _wait(lambda: x_of(first) == 0.5)
    listeners.append(transforms.TransformListener(nodes[1], late, spin_thread=True))
    assert x_of(late) == 0.5  # at once, from the hub


def test_a_listener_of_its_own_reads_tf_and_goes_on_after_garbage(sharing):
    nodes, listeners = sharing
    buf = TransformBuffer()
    listeners.append(transforms.TransformListener(nodes[0], buf, spin_thread=True))
    tf_pub = nodes[2].create_publisher(TFMessage, '/tf', 100)
    assert _wait(lambda: tf_pub.get_subscription_count() == 1)
    tf_pub.publish(b'\x00\x01\x00\x00\x01\x00')  # garbage: a warning, the thread goes on
    tf_pub.publish(_transform(3, 1.5))
    assert _wait(lambda: buf.can_transform('odom', 'base_footprint', 3.0))
    assert float(buf.lookup('odom', 'base_footprint', 3.0)[0][0, 3]) == 1.5


def test_a_nodes_clock_taken_on_a_thread_sets_its_clocks_without_an_executor(sharing):
    nodes, _ = sharing
    from amr_description.ros import sim_time
    from rclpy.parameter import Parameter
    from rosgraph_msgs.msg import Clock
    node = nodes[0]
    assert not sim_time.take_clock_on_thread(node)  # not on sim time: left alone
    node.set_parameters([Parameter('use_sim_time', Parameter.Type.BOOL, True)])
    assert node._time_source._clock_sub is not None  # rclpy's own subscription
    try:
        assert sim_time.take_clock_on_thread(node)
        assert not sim_time.take_clock_on_thread(node)  # once per node
        assert node._time_source._clock_sub is None
        taken = [sub for sub in node.subscriptions if sub.topic_name == '/clock']
        assert len(taken) == 1 and not taken[0].callback_group.can_execute(taken[0])
        clock_pub = nodes[2].create_publisher(Clock, '/clock', 1)
        assert _wait(lambda: clock_pub.get_subscription_count() == 1)
        msg = Clock()
        msg.clock.sec, msg.clock.nanosec = 42, 5
        assert _wait(lambda: node.get_clock().now().nanoseconds == 42_000_000_005 or
                     clock_pub.publish(msg))
    finally:
        sim_time.stop_clock_threads()
    assert not [sub for sub in node.subscriptions if sub.topic_name == '/clock']


def test_an_odometry_twist_on_a_thread_goes_on_after_garbage_and_stops_with_its_node(sharing):
    nodes, _ = sharing
    from amr_description.ros.node import Node
    from amr_description.ros.odometry_twist import TwistListener
    from nav_msgs.msg import Odometry
    node = Node('odom_listener', context=nodes[0].context)
    heard = []
    try:
        TwistListener(node, 'odom', heard.append)
        pub = nodes[2].create_publisher(Odometry, 'odom', 10)
        assert _wait(lambda: pub.get_subscription_count() == 1)
        pub.publish(b'\x00\x01\x00\x00\x01\x00')  # garbage: a warning, the thread goes on
        msg = Odometry()
        msg.child_frame_id = 'base_footprint'
        msg.twist.twist.linear.x, msg.twist.twist.angular.z = 0.4, -0.3
        assert _wait(lambda: heard or pub.publish(msg))
        assert heard[-1] == (0.4, 0.0, 0.0, 0.0, 0.0, -0.3)
        assert [t.name for t in threading.enumerate()].count('odom_listener_odometry') == 1
    finally:
        node.destroy_node()  # the Node base stops and joins the node's take loops first
    assert 'odom_listener_odometry' not in [t.name for t in threading.enumerate()]
