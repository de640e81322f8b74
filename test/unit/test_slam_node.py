# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
slam_toolbox's ``map -> odom`` stamp: the newest scan placed with TF, used by the mapper or not.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes; the node is driven
through its scan callback and transform timer directly.
"""

import math

import pytest

rclpy = pytest.importorskip('rclpy')
pytest.importorskip('slam_toolbox.srv')

from conftest import next_domain_id  # noqa: E402, I100 - after the skip
from conftest import release_domain_id  # noqa: E402


@pytest.fixture
def slam_node(monkeypatch):
    """Yield a configured, inactive ``slam_toolbox`` node whose /tf publisher records."""
    from amr_description.nodes.slam_toolbox import SlamToolbox
    domain = next_domain_id()
    monkeypatch.setenv('ROS_DOMAIN_ID', str(domain))
    monkeypatch.setenv('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    rclpy.init()
    node = SlamToolbox()
    try:
        node.configure()
        sent = []
        recorder = type('Recorder', (), {'publish': lambda self, msg: sent.append(msg)})
        node._tf_pub = recorder()
        node._pose_pub = type('Dropper', (), {'publish': lambda self, msg: None})()
        yield node, sent
    finally:
        node.destroy_node()
        rclpy.shutdown()
        release_domain_id(domain)


def _scan(stamp):
    from sensor_msgs.msg import LaserScan
    msg = LaserScan()
    msg.header.frame_id = 'lidar_link'
    msg.header.stamp.sec = int(stamp)
    msg.header.stamp.nanosec = int(round((stamp - int(stamp)) * 1e9))
    msg.angle_min, msg.angle_increment = -math.pi, 2.0 * math.pi / 360
    msg.angle_max = msg.angle_min + 359 * msg.angle_increment
    msg.range_min, msg.range_max = 0.1, 12.0
    msg.ranges = [3.0] * 360  # a round room
    return msg


def _odometry_until(tf, end):
    for k in range(0, int(round(end * 20)) + 1):  # base standing still, 20 Hz
        tf.set_transform('odom', 'base_footprint', k / 20.0, (0.0, 0.0, 0.0),
                         (0.0, 0.0, 0.0, 1.0))


def _stamp(node, sent):
    node._publish_tf()
    stamp = sent[-1].transforms[0].header.stamp
    return round(stamp.sec + stamp.nanosec * 1e-9, 6)


def test_map_to_odom_follows_every_scan_the_mapper_skips_as_slam_toolbox_scan_header(
        slam_node):
    node, sent = slam_node
    timeout = node.p['transform_timeout']
    assert node.p['minimum_time_interval'] == 0.5  # scans 0.1 s apart are skipped
    node.tf_buffer.set_transform('base_footprint', 'lidar_link', 0.0, (0.0, 0.0, 0.2),
                                 (0.0, 0.0, 0.0, 1.0), static=True)
    _odometry_until(node.tf_buffer, 1.25)
    node._publish_tf()
    assert sent == []  # nothing before the first scan
    node._on_scan(_scan(1.0))
    assert len(node.mapper.keyframes) == 1 and _stamp(node, sent) == 1.0 + timeout
    node._on_scan(_scan(1.1))  # too soon for the mapper: it still stamps the transform
    node._on_scan(_scan(1.2))
    assert len(node.mapper.keyframes) == 1 and _stamp(node, sent) == 1.2 + timeout
    node._paused = True  # pause_new_measurements: not mapped, still stamped
    node._on_scan(_scan(1.25))
    assert _stamp(node, sent) == 1.25 + timeout
    node._paused = False
    node._on_scan(_scan(1.7))  # its odometry has not arrived: it waits, and stamps nothing
    assert _stamp(node, sent) == 1.25 + timeout
    _odometry_until(node.tf_buffer, 1.8)
    node._on_scan(_scan(1.8))  # both used now, in order
    assert _stamp(node, sent) == 1.8 + timeout
    assert len(node._pending) == 0
