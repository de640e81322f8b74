# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Helpers shared by ``ros2 bag record|play|info``, on top of ``rosbags`` (PyPI, Apache-2.0).

* :func:`typestore_for` gives a rosbags type store knowing every message type to record: the
  ROS 2 Jazzy store, plus any type found as a ``.msg`` file in the ament index (our own
  interface packages), with their dependencies;
* QoS conversions between rclpy profiles and rosbags' ``Qos`` (what metadata.yaml v9 stores
  as ``offered_qos_profiles``);
* :func:`open_reader` opens a bag, turning every failure into one line naming the path.
"""

import contextlib
import os
import signal
import sys

from amr_description.cli.common import CliError

MCAP_MAGIC = b'\x89MCAP0\r\n'


class StopRequest:
    """
    Turn SIGINT and SIGTERM into a flag the verb's loop polls (``bool(stop)``).

    rclpy installs no signal handler for a non-default context, and an exception raised in
    the middle of a bag write would leave the file inconsistent: the loop checks the flag
    between two spins instead, and closes the bag cleanly.
    """

    def __init__(self):
        """Install the handlers (main thread only)."""
        self.signum = None
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, self._handler)

    def _handler(self, signum, frame):
        self.signum = signum

    def __bool__(self):
        """Return True once a signal arrived."""
        return self.signum is not None


def typestore_for(msgtypes):
    """
    Return a rosbags type store that can describe every type of ``msgtypes``.

    :param msgtypes: iterable of ``pkg/msg/Type`` names.
    :returns: a :class:`rosbags.typesys.store.Typestore`.
    :raises CliError: naming a type whose definition cannot be found.
    """
    from rosbags.typesys import get_types_from_msg
    from rosbags.typesys import get_typestore
    from rosbags.typesys import Stores
    store = get_typestore(Stores.ROS2_JAZZY)
    pending = [t for t in msgtypes if t not in store.fielddefs]
    loaded = set()
    while pending:
        name = pending.pop()
        if name in store.fielddefs or name in loaded:
            continue
        text = _msg_text(name)
        types = get_types_from_msg(text, name)
        loaded.add(name)
        for _, fields in types.values():
            for _, descriptor in fields:
                pending.extend(t for t in _referenced(descriptor) if t not in store.fielddefs)
        store.register(types)
    return store


def _referenced(descriptor):
    """Yield the message type names a rosbags field descriptor refers to."""
    if isinstance(descriptor, tuple):
        for item in descriptor:
            if isinstance(item, str) and item.count('/') == 2:
                yield item
            elif isinstance(item, tuple):
                yield from _referenced(item)


def _msg_text(name):
    from amr_description.cli.interface import interface_path
    try:
        with open(interface_path(name), 'r') as f:
            return f.read()
    except (ValueError, LookupError, OSError) as exc:
        raise CliError(f"Cannot record type '{name}': {exc}") from None


def rosbags_qos(profile):
    """
    Convert an rclpy QoS profile into rosbags' ``Qos`` (metadata.yaml's offered profile).

    :param profile: an :class:`rclpy.qos.QoSProfile`.
    :returns: a :class:`rosbags.interfaces.Qos`.
    """
    from rosbags.interfaces import Qos
    from rosbags.interfaces import QosDurability
    from rosbags.interfaces import QosHistory
    from rosbags.interfaces import QosLiveliness
    from rosbags.interfaces import QosReliability
    from rosbags.interfaces import QosTime

    def duration(value):
        ns = value.nanoseconds
        return QosTime(ns // 10 ** 9, ns % 10 ** 9)
    return Qos(
        QosHistory(int(profile.history)), int(profile.depth),
        QosReliability(int(profile.reliability)), QosDurability(int(profile.durability)),
        duration(profile.deadline), duration(profile.lifespan),
        QosLiveliness(int(profile.liveliness)), duration(profile.liveliness_lease_duration),
        bool(profile.avoid_ros_namespace_conventions))


def rclpy_qos(qos, topic, depth=1000):
    """
    Return the profile ``ros2 bag play`` publishes a recorded topic with.

    Reliability and durability are those the recorded publisher offered (``/tf_static``
    is always reliable + transient local, depth 1, so late joiners get it); history is keep
    last with at least ``depth`` (no sample dropped while a reliable reader catches up).

    :param qos: the recorded rosbags ``Qos`` or None.
    :param topic: the topic name.
    :param depth: the least history depth.
    :returns: an :class:`rclpy.qos.QoSProfile`.
    """
    from rclpy.qos import QoSDurabilityPolicy
    from rclpy.qos import QoSProfile
    from rclpy.qos import QoSReliabilityPolicy
    if topic == '/tf_static':
        return QoSProfile(depth=1, reliability=QoSReliabilityPolicy.RELIABLE,
                          durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)
    profile = QoSProfile(depth=depth)
    if qos is not None:
        if qos.reliability.value in (1, 2):
            profile.reliability = QoSReliabilityPolicy(qos.reliability.value)
        if qos.durability.value in (1, 2):
            profile.durability = QoSDurabilityPolicy(qos.durability.value)
        if qos.durability.value == 1:
            profile.depth = max(1, qos.depth)
    return profile


@contextlib.contextmanager
def open_reader(path):
    """
    Open a rosbag2 directory (or a single ``.mcap``/``.db3`` file) for reading.

    :param path: the bag path.
    :returns: a context manager yielding an open :class:`rosbags.rosbag2.Reader`.
    :raises CliError: one line naming the path when it is missing, not a bag, or corrupt.
    """
    from rosbags.rosbag2 import Reader
    if not os.path.exists(path):
        raise CliError(f"'{path}': no such bag")
    try:
        reader = Reader(path)
        reader.open()
    except Exception as exc:  # noqa: B902 - rosbags raises many kinds for a bad bag
        error = exc
        reader = None
    if reader is None:
        repaired = [(f, repair_mcap(f)) for f in _mcap_files(path)]
        repaired = [(f, n) for f, n in repaired if n is not None]
        if not repaired:
            raise CliError(f"'{path}': cannot read bag: {_one_line(error)}") from None
        for name, dropped in repaired:
            print(f"'{name}' was not closed by its recorder: closed it after its last complete "
                  f'record ({dropped} byte(s) of an unfinished record dropped)', file=sys.stderr)
        try:
            reader = Reader(path)
            reader.open()
        except Exception as exc:  # noqa: B902 - rosbags raises many kinds for a bad bag
            raise CliError(f"'{path}': cannot read bag: {_one_line(exc)}") from None
    try:
        yield reader
    finally:
        with contextlib.suppress(Exception):
            reader.close()


def _mcap_files(path):
    if os.path.isdir(path):
        return sorted(os.path.join(path, f) for f in os.listdir(path) if f.endswith('.mcap'))
    return [path] if path.endswith('.mcap') else []


def repair_mcap(path):
    """
    Close an MCAP file whose writer was killed: keep every complete record, add the end.

    The file is cut after its last complete top-level record (a chunk is written whole, so
    every message flushed before the kill is kept) and a Data End record, a Footer without
    summary and the closing magic are appended; readers then index it by scanning, as for any
    MCAP file without a summary (MCAP specification: "Footer", "Summary Section").

    :param path: the ``.mcap`` file.
    :returns: the number of bytes dropped, or None when the file needs no repair or is not an
        MCAP file at all.
    :raises OSError: when the file cannot be read or written.
    """
    size = os.path.getsize(path)
    with open(path, 'r+b') as f:
        if f.read(8) != MCAP_MAGIC:
            return None
        f.seek(max(8, size - 8))
        if size >= 8 + 37 and f.read(8) == MCAP_MAGIC:
            return None
        good = pos = 8
        while pos + 9 <= size:
            f.seek(pos)
            head = f.read(9)
            opcode, length = head[0], int.from_bytes(head[1:9], 'little')
            if opcode in (0x02, 0x0F) or pos + 9 + length > size:
                break
            pos += 9 + length
            good = pos
        f.truncate(good)
        f.seek(good)
        f.write(b'\x0f' + (4).to_bytes(8, 'little') + bytes(4))  # Data End, crc 0
        f.write(b'\x02' + (20).to_bytes(8, 'little') + bytes(20))  # Footer, no summary
        f.write(MCAP_MAGIC)
    return size - good


def _one_line(exc):
    text = ' '.join(str(exc).split()) or type(exc).__name__
    return text
