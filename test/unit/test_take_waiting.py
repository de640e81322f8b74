# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``take_waiting``: a callback takes every message waiting in a queue, oldest first.

In-process rclpy (conftest's ``ros``: own ROS_DOMAIN_ID, localhost discovery), no processes;
the executor is never spun.
"""

import time

import pytest

rclpy = pytest.importorskip('rclpy')

from amr_description.ros.subscriptions import take_waiting  # noqa: E402, I100
from std_msgs.msg import Int32  # noqa: E402


def _collect(subscription, count, timeout=30.0):
    """Take until ``count`` messages came (the middleware delivers them asynchronously)."""
    got = []
    deadline = time.monotonic() + timeout
    while len(got) < count and time.monotonic() < deadline:
        got += take_waiting(subscription)
        time.sleep(0.01)
    return got


def test_takes_every_waiting_message_oldest_first_and_not_the_callback(ros):
    node = ros[0]('take_waiting_test')  # its executor never spins here
    heard = []
    sub = node.create_subscription(Int32, 'numbers', heard.append, 10)
    pub = node.create_publisher(Int32, 'numbers', 10)
    deadline = time.monotonic() + 30.0
    while pub.get_subscription_count() < 1 and time.monotonic() < deadline:
        time.sleep(0.01)
    for value in (3, 1, 4, 1, 5):
        pub.publish(Int32(data=value))
    got = _collect(sub, 5)
    assert [m.data for m in got] == [3, 1, 4, 1, 5]
    assert take_waiting(sub) == []  # nothing left waiting
    assert heard == []  # the callback is not called: the caller handles what it took


def test_a_destroyed_subscription_gives_nothing(ros):
    node = ros[0]('take_waiting_test')
    sub = node.create_subscription(Int32, 'numbers', lambda msg: None, 10)
    node.destroy_subscription(sub)
    assert take_waiting(sub) == []
