# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Reading the few serialized messages that arrive hundreds of times a second, without rclpy.

rclpy converts each message it takes into Python objects (ten for one ``TransformStamped``),
and that conversion was a sixth of a TF listener's CPU. These readers take the serialized
bytes (a subscription's ``raw=True``) and return plain values.

The layout is plain CDR (OMG DDS-XTypes 1.3, 7.4.3, "XCDR1"), what rmw_fastrtps writes for
ROS 2 types: a 4-byte encapsulation header (``00 00`` big endian or ``00 01`` little endian,
then two option bytes), then the fields in order, each aligned to its own size (at most 8)
counting from the end of the header; a string is a uint32 length counting its terminating
NUL, then its bytes; a sequence is a uint32 count, then its elements. Any other
encapsulation raises ``ValueError``; :func:`read` then lets rclpy deserialize the bytes.
"""

import collections
import struct

import numpy as np

_ENDIAN = {b'\x00\x00': '>', b'\x00\x01': '<'}

BondStatus = collections.namedtuple(
    'BondStatus', 'id instance_id active heartbeat_timeout heartbeat_period')
"""The fields of a ``bond/msg/Status`` a bond uses (its header is skipped)."""


class _Reader:
    """A cursor over one CDR stream (see the module's docstring)."""

    def __init__(self, data):
        if len(data) < 4 or bytes(data[:2]) not in _ENDIAN:
            raise ValueError(f'not a plain CDR stream (encapsulation {bytes(data[:2]).hex()})')
        self.data = data
        self.end = _ENDIAN[bytes(data[:2])]
        self.pos = 4
        self._u32 = struct.Struct(self.end + 'I')
        self._time = struct.Struct(self.end + 'iI')
        self._seven = struct.Struct(self.end + '7d')
        self._six = struct.Struct(self.end + '6d')
        self._bool = struct.Struct(self.end + '?')
        self._two_floats = struct.Struct(self.end + '2f')

    def _align(self, size):
        self.pos += (-(self.pos - 4)) % size

    def _take(self, layout, size):
        self._align(size)
        if self.pos + layout.size > len(self.data):
            raise ValueError(f'CDR stream ends at byte {len(self.data)}, inside a field at '
                             f'byte {self.pos}')
        values = layout.unpack_from(self.data, self.pos)
        self.pos += layout.size
        return values

    def uint32(self):
        return self._take(self._u32, 4)[0]

    def stamp(self):
        """Return a ``builtin_interfaces/Time`` as ``(sec, nanosec)`` (ints)."""
        return self._take(self._time, 4)

    def time(self):
        """Return a ``builtin_interfaces/Time`` as seconds (float)."""
        sec, nanosec = self.stamp()
        return sec + nanosec * 1e-9

    def string(self):
        size = self.uint32()
        if size == 0 or self.pos + size > len(self.data):
            raise ValueError(f'CDR string of {size} bytes at byte {self.pos} does not fit '
                             f'in {len(self.data)}')
        text = bytes(self.data[self.pos:self.pos + size - 1]).decode('utf-8')
        self.pos += size
        return text

    def seven_doubles(self):
        return self._take(self._seven, 8)

    def skip_doubles(self, count):
        self._align(8)
        self.pos += 8 * count

    def doubles(self):
        """Return a sequence of float64 as a tuple of floats."""
        count = self.uint32()
        return self._take(struct.Struct(f'{self.end}{count}d'), 8) if count else ()

    def double_records(self, width):
        """Return a sequence of records of ``width`` float64 as an (N, width) float array."""
        count = self.uint32()
        self._align(8)
        end = self.pos + 8 * width * count
        if end > len(self.data):
            raise ValueError(f'CDR sequence of {count} records of {width} doubles at byte '
                             f'{self.pos} does not fit in {len(self.data)}')
        records = np.frombuffer(self.data, self.end + 'f8', width * count, self.pos)
        self.pos = end
        return records.reshape(count, width).astype(float)


def tf_message_entries(data):
    """
    Return the transforms of a serialized ``tf2_msgs/TFMessage``.

    :param data: the message's CDR bytes (bytes, bytearray or memoryview).
    :returns: list of ``(parent, child, stamp, (x, y, z), (qx, qy, qz, qw))``: frame ids
        (str), stamp in seconds (float), the child's origin in the parent frame (m) and the
        rotation quaternion, as the message holds them (not checked or normalized).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    entries = []
    for _ in range(reader.uint32()):
        stamp = reader.time()
        parent = reader.string()
        child = reader.string()
        values = reader.seven_doubles()
        entries.append((parent, child, stamp, values[:3], values[3:]))
    return entries


def clock_nanoseconds(data):
    """
    Return the time of a serialized ``rosgraph_msgs/Clock`` in nanoseconds (int).

    :raises ValueError: when ``data`` is not plain CDR, or is too short.
    """
    sec, nanosec = _Reader(data).stamp()
    return sec * 1_000_000_000 + nanosec


def odometry_twist(data):
    """
    Return the twist of a serialized ``nav_msgs/Odometry``.

    :param data: the message's CDR bytes.
    :returns: ``(vx, vy, vz, wx, wy, wz)``: ``twist.twist``'s linear (m/s) and angular (rad/s)
        velocity in the child frame, as the message holds them (not checked).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    reader.time()  # header.stamp
    reader.string()  # header.frame_id
    reader.string()  # child_frame_id
    reader.skip_doubles(7 + 36)  # pose.pose, pose.covariance
    return reader._take(reader._six, 8)


def joint_state(data):
    """
    Return the stamp, names and positions of a serialized ``sensor_msgs/JointState``.

    :param data: the message's CDR bytes.
    :returns: ``((sec, nanosec), names, positions)``: ``header.stamp``, the ``name`` list
        (str) and the ``position`` tuple (rad or m), as the message holds them (their lengths
        are not compared; ``velocity`` and ``effort`` are not read).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    stamp = reader.stamp()
    reader.string()  # header.frame_id
    names = [reader.string() for _ in range(reader.uint32())]
    return stamp, names, reader.doubles()


def odometry_position(data):
    """
    Return the frame and position of a serialized ``nav_msgs/Odometry``.

    :param data: the message's CDR bytes.
    :returns: ``(frame_id, (x, y, z))``: ``header.frame_id`` and ``pose.pose.position`` (m),
        as the message holds them (not checked).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    reader.time()  # header.stamp
    frame_id = reader.string()
    reader.string()  # child_frame_id
    return frame_id, reader.seven_doubles()[:3]


def bond_status(data):
    """
    Return the fields of a serialized ``bond/msg/Status`` that a bond uses.

    :param data: the message's CDR bytes.
    :returns: :data:`BondStatus` (``active`` a bool, the heartbeat times in seconds).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    reader.time()  # header.stamp
    reader.string()  # header.frame_id
    bond_id = reader.string()
    instance_id = reader.string()
    active = reader._take(reader._bool, 1)[0]
    timeout, period = reader._take(reader._two_floats, 4)
    return BondStatus(bond_id, instance_id, active, timeout, period)


def read(data, reader, msg_type, convert=None):
    """
    Return ``reader(data)``, or ``convert`` of rclpy's message when ``data`` is not plain CDR.

    :param data: a message's serialized bytes (a raw subscription's or ``TakeLoop``'s).
    :param reader: one of this module's readers, e.g. :func:`odometry_twist`.
    :param msg_type: the message's class, for ``rclpy.serialization.deserialize_message``.
    :param convert: turns that message into what ``reader`` returns (None: the message as
        it is, whose fields ``reader``'s result names alike).
    :raises ValueError: never from ``reader``; rclpy's errors for bytes it cannot read pass.
    """
    try:
        return reader(data)
    except ValueError:
        from rclpy.serialization import deserialize_message
        msg = deserialize_message(data, msg_type)
        return msg if convert is None else convert(msg)


def stamped_poses(data, width):
    """
    Return the frame and the poses of a serialized PoseArray or ParticleCloud.

    A ``geometry_msgs/PoseArray`` (``width`` 7) and a ``nav2_msgs/ParticleCloud`` (``width``
    8: each pose followed by its weight) are a ``std_msgs/Header`` then a sequence of
    fixed-size records of float64: a ``Pose`` (position x y z, orientation x y z w) and, in a
    ``Particle``, its ``weight``.
    Reading them here takes microseconds where rclpy builds thousands of Python objects
    (23 ms for a cloud of 2,000 particles on this machine, docs/navigation.md).

    :param data: the message's CDR bytes.
    :param width: 7 or 8 (see above).
    :returns: ``(frame_id, records)``: the header's frame (str) and an (N, width) float array,
        as the message holds it (not checked or normalized).
    :raises ValueError: when ``data`` is not plain CDR, or ends inside a field.
    """
    reader = _Reader(data)
    reader.time()  # header.stamp
    frame_id = reader.string()
    return frame_id, reader.double_records(width)
