# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
TF in and out for nodes: a listener filling a transform buffer, planar transforms and poses.

:class:`TransformListener` subscribes ``/tf`` (depth 100) and ``/tf_static`` (reliable,
transient local, depth 100) as tf2_ros' ``TransformListener`` does and hands every transform
to a buffer's ``set_transform(parent, child, time, translation, rotation, static)`` (the
project's :class:`amr_description.core.tf_buffer.TransformBuffer`, which nodes pass in). Times
are seconds (float); planar poses are ``(x, y, yaw)`` in m, m, rad (REP 103).
"""

import collections
import math
import threading
import weakref

from geometry_msgs.msg import TransformStamped
import numpy as np
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from tf2_msgs.msg import TFMessage

STATIC_QOS = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE,
                        durability=DurabilityPolicy.TRANSIENT_LOCAL)
"""tf2_ros' ``/tf_static`` QoS."""


def stamp_seconds(stamp):
    """Return seconds (float) of a ``builtin_interfaces/Time``."""
    return stamp.sec + stamp.nanosec * 1e-9


def yaw_of(q):
    """Return the rotation about z (rad) of a quaternion with fields x, y, z, w."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def set_yaw(q, yaw):
    """Write the quaternion of a rotation ``yaw`` (rad) about z into ``q`` (in place)."""
    q.x, q.y, q.z, q.w = 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def planar_pose(T):
    """Return ``(x, y, yaw)`` (array (3,)) of a 4x4 homogeneous transform (rotation about z)."""
    return np.array([T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])])


def transform_planar(T, pose):
    """
    Return ``(x, y, yaw)`` of a geometry_msgs/Pose moved by a 4x4 transform (rotation about z).

    :param T: the transform from the pose's frame to the target frame (4x4 array).
    :param pose: a geometry_msgs/Pose; only its x, y and yaw are used.
    """
    x, y = T[:2, :2] @ (pose.position.x, pose.position.y) + T[:2, 3]
    return float(x), float(y), yaw_of(pose.orientation) + math.atan2(T[1, 0], T[0, 0])


def planar_transform(parent, child, stamp, pose):
    """
    Return a ``geometry_msgs/TransformStamped`` of ``child`` in ``parent``.

    :param stamp: ``builtin_interfaces/Time``.
    :param pose: ``(x, y, yaw)`` of ``child`` in ``parent``.
    """
    t = TransformStamped()
    t.header.frame_id = parent
    t.header.stamp = stamp
    t.child_frame_id = child
    t.transform.translation.x = float(pose[0])
    t.transform.translation.y = float(pose[1])
    set_yaw(t.transform.rotation, float(pose[2]))
    return t


class StampedQueue:
    """
    Messages waiting, in arrival order, for the transforms at their stamps.

    tf2_ros' ``MessageFilter`` behaviour, without its polling: each new message lets the
    waiting ones try again. A message leaves the queue when ``use`` is done with it (used or
    dropped), or when the queue is full (the oldest).

    :param size: how many messages may wait.
    :param use: ``f(msg) -> bool``: True when done with ``msg``, False while its transform
        has not arrived (see :func:`not_yet`).
    """

    def __init__(self, size, use):
        """Keep the size and the callable."""
        self._queue = collections.deque(maxlen=size)
        self._use = use

    def __len__(self):
        """Return how many messages wait."""
        return len(self._queue)

    def add(self, msg):
        """Queue ``msg`` and use every waiting message whose transform has arrived."""
        self._queue.append(msg)
        while self._queue and self._use(self._queue[0]):
            self._queue.popleft()

    def clear(self):
        """Forget the waiting messages."""
        self._queue.clear()


def not_yet(exc):
    """Return True when a lookup's ``TransformException`` asked for a time not yet received."""
    return 'into the future' in str(exc)


_SPINNING = weakref.WeakSet()  # listeners with a thread of their own, not yet destroyed


def stop_listener_threads():
    """
    Destroy every :class:`TransformListener` still spinning a thread of its own.

    :func:`amr_description.ros.shutdown.shutdown` calls it before rclpy shuts down: a listener
    thread left to the interpreter's exit was still inside the middle layer's wait, and the
    process aborted ("terminate called without an active exception", exit -6).
    """
    for listener in list(_SPINNING):
        listener.destroy()


class TransformListener:
    """
    Fill ``buffer`` from ``/tf`` and ``/tf_static``.

    A transform the buffer refuses (``ValueError``: a NaN, a frame naming itself) is logged
    as one warning line (at most every 5 s) and dropped. With ``spin_thread``, as tf2_ros'
    ``TransformListener(..., spin_thread=True)``, the subscriptions belong to a node of their
    own (``transform_listener_impl_<id>``) spun by a single-threaded executor in a daemon
    thread: the hundreds of ``/tf`` messages a second then wake a wait set of two
    subscriptions, not the node's whole set of services and timers (in the SLAM node that
    wake-up, not the mapping, was the larger part of its CPU).

    :param node: the rclpy node that subscribes (or whose context the listener's node uses).
    :param buffer: an object with ``set_transform(parent, child, time, translation,
        rotation, static)``.
    :param callback_group: the subscriptions' callback group, or None (not with
        ``spin_thread``).
    :param spin_thread: subscribe on a node and thread of the listener's own.
    """

    def __init__(self, node, buffer, callback_group=None, spin_thread=False):
        """Subscribe both topics (on the listener's own node with ``spin_thread``)."""
        self.node = node
        self.buffer = buffer
        self._own = self._executor = self._thread = None
        if spin_thread:
            from rclpy.executors import SingleThreadedExecutor
            from rclpy.node import Node as RclpyNode
            name = f'transform_listener_impl_{id(self):x}'
            # a node-local __node remap wins over the process's ``-r __node:=<server>``, which
            # would otherwise give this node the server's name too (as tf2_ros avoids)
            self._own = RclpyNode(name, context=node.context, start_parameter_services=False,
                                  cli_args=['--ros-args', '-r', f'__node:={name}'])
            self._executor = SingleThreadedExecutor(context=node.context)
            self._executor.add_node(self._own)
            self._thread = threading.Thread(target=self._spin, daemon=True)
            self._thread.start()
            _SPINNING.add(self)
        subscriber = self._own or node
        self._subs = [
            subscriber.create_subscription(TFMessage, '/tf', lambda m: self._store(m, False),
                                           100, callback_group=callback_group),
            subscriber.create_subscription(TFMessage, '/tf_static',
                                           lambda m: self._store(m, True), STATIC_QOS,
                                           callback_group=callback_group)]

    def _spin(self):
        from rclpy.executors import ExternalShutdownException
        try:
            self._executor.spin()
        except (ExternalShutdownException, RuntimeError):  # the context or executor stopped
            pass

    def _store(self, msg, static):
        for t in msg.transforms:
            tr, q = t.transform.translation, t.transform.rotation
            try:
                self.buffer.set_transform(t.header.frame_id, t.child_frame_id,
                                          stamp_seconds(t.header.stamp), (tr.x, tr.y, tr.z),
                                          (q.x, q.y, q.z, q.w), static=static)
            except ValueError as exc:
                self.node.get_logger().warning(
                    f"{'/tf_static' if static else '/tf'}: {exc}", throttle_duration_sec=5.0)

    def destroy(self):
        """Remove the subscriptions (and the listener's own node, and join its thread)."""
        if self._own is not None:
            own, self._own = self._own, None
            self._executor.shutdown(timeout_sec=1.0)
            own.destroy_node()
            if self._thread is not threading.current_thread():
                self._thread.join(timeout=2.0)
            _SPINNING.discard(self)
        else:
            for sub in self._subs:
                self.node.destroy_subscription(sub)
        self._subs = []
