# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The CDR readers give back what rclpy serialized, and refuse what they cannot read."""

import struct

from amr_description.ros.cdr import bond_status
from amr_description.ros.cdr import BondStatus
from amr_description.ros.cdr import clock_nanoseconds
from amr_description.ros.cdr import joint_state
from amr_description.ros.cdr import odometry_position
from amr_description.ros.cdr import odometry_twist
from amr_description.ros.cdr import read
from amr_description.ros.cdr import tf_message_entries
from bond.msg import Status
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
import pytest
from rclpy.serialization import serialize_message
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

pytestmark = pytest.mark.unit


def _transform(parent, child, sec, nanosec, xyz, xyzw):
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = parent, child
    t.header.stamp.sec, t.header.stamp.nanosec = sec, nanosec
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = xyzw
    return t


def test_transforms_read_back_with_every_padding():
    # frame ids of 0-8 characters: every alignment of the next string and of the doubles
    transforms = [_transform('p' * n, 'c' * (8 - n), n, 500_000_000 + n,
                             (float(n), -2.5 * n, 0.125), (0.0, 0.0, 0.6, 0.8))
                  for n in range(9)]
    entries = tf_message_entries(serialize_message(TFMessage(transforms=transforms)))
    assert len(entries) == 9
    for n, (parent, child, stamp, xyz, xyzw) in enumerate(entries):
        assert (parent, child) == ('p' * n, 'c' * (8 - n))
        assert stamp == pytest.approx(n + 0.5 + n * 1e-9, abs=1e-12)
        assert xyz == (n, -2.5 * n, 0.125) and xyzw == (0.0, 0.0, 0.6, 0.8)


def test_an_empty_message_and_a_big_endian_stream():
    assert tf_message_entries(serialize_message(TFMessage())) == []
    # by hand, big endian: one transform 'a' -> 'bc' at 3 s, (1, 2, 3), (0, 0, 0, 1)
    body = struct.pack('>IiII2s2xI3s', 1, 3, 0, 2, b'a\0', 3, b'bc\0')  # 27 bytes
    data = b'\x00\x00\x00\x00' + body + bytes(5) + struct.pack('>7d', 1, 2, 3, 0, 0, 0, 1)
    assert tf_message_entries(data) == [('a', 'bc', 3.0, (1.0, 2.0, 3.0),
                                         (0.0, 0.0, 0.0, 1.0))]


def test_the_clock():
    msg = Clock()
    msg.clock.sec, msg.clock.nanosec = 12, 345
    assert clock_nanoseconds(serialize_message(msg)) == 12_000_000_345


@pytest.mark.parametrize('data', [b'', b'\x00\x07\x00\x00' + bytes(8), b'\x00\x01\x00\x00\x01'])
def test_what_cannot_be_read_is_a_value_error(data):
    with pytest.raises(ValueError):
        tf_message_entries(data)


def test_a_truncated_message_is_a_value_error():
    data = serialize_message(TFMessage(transforms=[_transform('map', 'odom', 1, 2, (0.0, 0.0, 0.0),
                                                              (0.0, 0.0, 0.0, 1.0))]))
    for end in (8, 20, len(data) - 1):
        with pytest.raises(ValueError):
            tf_message_entries(data[:end])


@pytest.mark.parametrize('frame', ['', 'o', 'odom', 'r12/odom_'])
def test_the_twist_of_an_odometry(frame):
    msg = Odometry()
    msg.header.frame_id, msg.child_frame_id = frame, frame + 'base_footprint'
    msg.pose.pose.position.x = 7.0
    msg.pose.covariance[35] = 9.0
    t = msg.twist.twist
    t.linear.x, t.linear.y, t.linear.z = 0.5, -0.25, 0.125
    t.angular.x, t.angular.y, t.angular.z = 1.0, 2.0, -0.75
    assert odometry_twist(serialize_message(msg)) == (0.5, -0.25, 0.125, 1.0, 2.0, -0.75)
    assert odometry_position(serialize_message(msg)) == (frame, (7.0, 0.0, 0.0))
    with pytest.raises(ValueError):
        odometry_position(serialize_message(msg)[:20])
    with pytest.raises(ValueError):
        odometry_twist(serialize_message(msg)[:-300])


@pytest.mark.parametrize('bond_id', ['', 'a', 'amcl', 'controller_server'])
@pytest.mark.parametrize('active', [True, False])
def test_a_bond_status(bond_id, active):
    msg = Status(id=bond_id, instance_id='1b4e28ba-2fa1-11d2-883f-0016d3cca427' + bond_id,
                 active=active, heartbeat_timeout=4.0, heartbeat_period=0.1)
    msg.header.frame_id = bond_id[:3]
    status = bond_status(serialize_message(msg))
    assert status == BondStatus(bond_id, msg.instance_id, active, 4.0,
                                pytest.approx(0.1, abs=1e-7))
    with pytest.raises(ValueError):
        bond_status(serialize_message(msg)[:-2])


def _refuse(data):
    raise ValueError('not plain CDR')


def test_read_falls_back_to_rclpy_only_for_what_the_reader_refuses():
    msg = Clock()
    msg.clock.sec, msg.clock.nanosec = 3, 4
    data = serialize_message(msg)
    seconds = (lambda m: m.clock.sec * 1_000_000_000 + m.clock.nanosec)
    assert read(data, clock_nanoseconds, Clock, pytest.fail) == 3_000_000_004
    assert read(data, _refuse, Clock, seconds) == 3_000_000_004
    assert read(data, _refuse, Clock) == msg


@pytest.mark.parametrize('frame', ['', 'b', 'base_link'])
@pytest.mark.parametrize('names', [[], ['a'], ['left_wheel_joint', 'r', 'xyz']])
def test_a_joint_state(frame, names):
    msg = JointState(name=names, position=[0.5 * i - 1.0 for i in range(len(names))],
                     velocity=[2.0] * len(names))
    msg.header.frame_id = frame
    msg.header.stamp.sec, msg.header.stamp.nanosec = 1_700_000_000, 999_999_999
    assert joint_state(serialize_message(msg)) == (
        (1_700_000_000, 999_999_999), names, tuple(msg.position))
    msg.position = [1.0]  # lengths are the caller's to compare
    assert joint_state(serialize_message(msg))[1:] == (names, (1.0,))
    with pytest.raises(ValueError):
        joint_state(serialize_message(msg)[:10 + len(frame)])
