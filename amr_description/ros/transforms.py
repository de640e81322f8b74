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

from amr_description.ros.cdr import read
from amr_description.ros.cdr import tf_message_entries
from amr_description.ros.take_loop import TakeLoop
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


_SPINNING = weakref.WeakSet()  # listeners and hubs with a thread of their own, not destroyed

_HUBS = {}
"""id(context) -> :class:`_Hub` of the sharing listeners (after :func:`share_listener_threads`)."""

_HUBS_LOCK = threading.Lock()

_sharing = []


def share_listener_threads():
    """
    From now on, let the ``spin_thread`` listeners of this process share one node and thread.

    For a container (Nav2's composed bring-up): every server's listener then gets each ``/tf``
    message from one subscription, taken and converted once, instead of one subscription,
    thread and wake-up per server. Each listener still fills its own buffer, as each rclcpp
    node's tf2 buffer is its own.
    """
    _sharing.append(True)


def stop_listener_threads():
    """
    Destroy every :class:`TransformListener` (and shared hub) still spinning a thread.

    :func:`amr_description.ros.shutdown.shutdown` calls it before rclpy shuts down: a listener
    thread left to the interpreter's exit was still inside the middle layer's wait, and the
    process aborted ("terminate called without an active exception", exit -6).
    """
    for listener in list(_SPINNING):
        listener.destroy()


class _OwnThread:
    """
    ``/tf`` and ``/tf_static`` taken serialized on a node and :class:`TakeLoop` of their own.

    :param context: the rclpy context.
    :param store: ``f(entries, static)`` with the transforms of each message (as
        :func:`_entries`).
    """

    def __init__(self, context, store):
        from rclpy.node import Node as RclpyNode
        from rclpy.parameter import Parameter
        name = f'transform_listener_impl_{id(self):x}'
        # a node-local __node remap wins over the process's ``-r __node:=<server>``, which
        # would otherwise give this node the server's name too (as tf2_ros avoids)
        # use_sim_time false whatever the process's arguments say: the node's own /clock
        # subscription would never be taken (nothing spins this node), yet DDS fills it
        self.node = RclpyNode(name, context=context, start_parameter_services=False,
                              cli_args=['--ros-args', '-r', f'__node:={name}'],
                              parameter_overrides=[Parameter('use_sim_time', value=False)])
        self.loop = TakeLoop(self.node, name)
        self.loop.subscribe(TFMessage, '/tf', 100,
                            lambda data: store(read_tf_message(data), False))
        self.loop.subscribe(TFMessage, '/tf_static', STATIC_QOS,
                            lambda data: store(read_tf_message(data), True))
        self.loop.start()

    def destroy(self):
        self.loop.stop()
        self.node.destroy_node()


def read_tf_message(data):
    """
    Return the transforms of a serialized TFMessage (rclpy reads what is not plain CDR).

    :returns: ``[(parent, child, stamp s, (x, y, z), (qx, qy, qz, qw))]``, as
        :func:`amr_description.ros.cdr.tf_message_entries`.
    :raises ValueError: a message that ends inside a field.
    """
    return read(data, tf_message_entries, TFMessage, _entries)


def _entries(msg):
    """Return a TFMessage's transforms as ``(parent, child, stamp s, xyz, xyzw)`` tuples."""
    out = []
    for t in msg.transforms:
        tr, q = t.transform.translation, t.transform.rotation
        out.append((t.header.frame_id, t.child_frame_id, stamp_seconds(t.header.stamp),
                    (tr.x, tr.y, tr.z), (q.x, q.y, q.z, q.w)))
    return out


def _subscribe(node, store, callback_group):
    return [node.create_subscription(TFMessage, '/tf', lambda m: store(_entries(m), False),
                                     100, callback_group=callback_group),
            node.create_subscription(TFMessage, '/tf_static',
                                     lambda m: store(_entries(m), True), STATIC_QOS,
                                     callback_group=callback_group)]


class _Hub:
    """
    One :class:`_OwnThread` handing every message to the listeners that share it.

    ``/tf_static`` is transient local: a listener subscribing on its own gets every static
    transform published before it started. The hub's one subscription got them once, so it
    keeps the latest static transform of each child frame and hands them to a listener that
    joins later (a composed server configured after the robot_state_publisher's statics came).
    Each message's transforms are read out of it once for all the listeners.
    """

    def __init__(self, context):
        self.key = id(context)
        self.listeners = ()  # replaced, never changed in place: read without a lock
        self.statics = {}  # child frame -> its latest static transform, as :func:`_entries`
        self.static_lock = threading.Lock()
        self.own = _OwnThread(context, self._store)
        _SPINNING.add(self)

    def _store(self, entries, static):
        # each message is read once, whatever the number of listeners
        if not static:
            for listener in self.listeners:
                listener._fill(entries, static)
            return
        with self.static_lock:  # a listener joins before or after this message, not during
            self.statics.update((entry[1], entry) for entry in entries)
            for listener in self.listeners:
                listener._fill(entries, static)

    @staticmethod
    def join(listener):
        """Hand the messages to ``listener`` too, from its context's hub (made if none)."""
        with _HUBS_LOCK:
            hub = _HUBS.get(id(listener.node.context))
            if hub is None:
                hub = _HUBS[id(listener.node.context)] = _Hub(listener.node.context)
            with hub.static_lock:
                hub.listeners = hub.listeners + (listener,)
                listener._fill(list(hub.statics.values()), True)
        return hub

    def remove(self, listener):
        """Stop handing messages to ``listener``; the last one out destroys the hub."""
        with _HUBS_LOCK:
            self.listeners = tuple(x for x in self.listeners if x is not listener)
            last = not self.listeners
            if last and _HUBS.get(self.key) is self:
                del _HUBS[self.key]
        if last:
            self.destroy()

    def destroy(self):
        with _HUBS_LOCK:
            if _HUBS.get(self.key) is self:
                del _HUBS[self.key]
        if self.own is not None:
            own, self.own = self.own, None
            own.destroy()
            _SPINNING.discard(self)


class TransformListener:
    """
    Fill ``buffer`` from ``/tf`` and ``/tf_static``.

    A transform the buffer refuses (``ValueError``: a NaN, a frame naming itself) is logged
    as one warning line (at most every 5 s) and dropped. With ``spin_thread``, as tf2_ros'
    ``TransformListener(..., spin_thread=True)``, the subscriptions belong to a node of their
    own (``transform_listener_impl_<id>``) whose messages are taken serialized and read on a
    thread of their own (:class:`amr_description.ros.take_loop.TakeLoop`, no executor): the
    hundreds of ``/tf`` messages a second then wake neither the node's whole set of services
    and timers (in the SLAM node that wake-up, not the mapping, was the larger part of its
    CPU) nor an rclpy executor. After :func:`share_listener_threads`, the process's
    ``spin_thread`` listeners share one such node and thread.

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
        self._own = self._hub = None
        self._subs = []
        if spin_thread and _sharing:
            self._hub = _Hub.join(self)
        elif spin_thread:
            self._own = _OwnThread(node.context, self._fill)
            _SPINNING.add(self)
        else:
            self._subs = _subscribe(node, self._fill, callback_group)

    def _fill(self, entries, static):
        for parent, child, stamp, translation, rotation in entries:
            try:
                self.buffer.set_transform(parent, child, stamp, translation, rotation,
                                          static=static)
            except ValueError as exc:
                self.node.get_logger().warning(
                    f"{'/tf_static' if static else '/tf'}: {exc}", throttle_duration_sec=5.0)

    def destroy(self):
        """Remove the subscriptions (and the listener's own node, and join its thread)."""
        if self._hub is not None:
            hub, self._hub = self._hub, None
            hub.remove(self)
        elif self._own is not None:
            own, self._own = self._own, None
            own.destroy()
            _SPINNING.discard(self)
        else:
            for sub in self._subs:
                self.node.destroy_subscription(sub)
        self._subs = []
