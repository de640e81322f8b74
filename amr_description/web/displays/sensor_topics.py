# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What the sensor displays share: the newest message of each topic, drawn in the fixed frame.

A :class:`SensorTopicsDisplay` subscribes its topics with the sensor-data QoS (best effort,
which also hears reliable publishers), counts each topic's rate for the status, and at most
:data:`RATE` times a second draws the newest message of each topic placed with the newest
transform of its ``header.frame_id`` into the fixed frame. A message whose frame is not in TF
is left out and named in the status (``missing``); one that cannot be read or drawn is one
throttled warning, and the viewer keeps running. A subclass sets ``message_type`` and
``label`` and implements :meth:`~SensorTopicsDisplay.render`.

The messages are taken serialized and only the newest one is read, when it is drawn: an
IMU's 100 Hz or a path's 20 Hz cost the viewer one reading per redraw, not one per message
(rclpy's reading of a 2,000-particle cloud takes 23 ms; docs/navigation.md, "The viewer's
readings").
"""

import threading
import time

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import Rate
from amr_description.web.displays.base import read_or_warn
import numpy as np
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rclpy.serialization import deserialize_message

RATE = 10.0
"""Redraws per second at most."""
BEST_AVAILABLE = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_AVAILABLE,
                            durability=DurabilityPolicy.BEST_AVAILABLE)
"""The QoS of a display of latched data (maps, poses): the publishers' own, found at
subscription (transient local from map_server; volatile or best effort from others)."""


class _Topic:

    def __init__(self):
        self.data = None  # the newest message as taken (serialized, or as rclpy read it)
        self.read_from = None  # the data self.msg was read from
        self.msg = None
        self.drawn = None
        self.node = None
        self.rate = Rate()


class SensorTopicsDisplay(Display):
    """
    The newest message of each of ``topics`` ('' entries are ignored), drawn in the fixed frame.

    ``'*'`` among ``topics`` adds every topic of ``message_type`` that gains a publisher
    (:mod:`~amr_description.web.displays.discovery`).

    :cvar message_type: the ROS message class.
    :cvar label: the checkbox label (RViz's display name).
    :cvar default_frame: the frame of messages without ``header.frame_id`` (drawn as the
        fixed frame when TF does not have it); '' for none.
    :cvar qos: the subscriptions' QoS profile (sensor data: best effort, volatile).
    :cvar placed: True when a drawn message follows its frame between messages
        (:meth:`place` moves it; a map under ``map -> odom``), False when the next message
        redraws it.
    :cvar serialized: True: messages are taken serialized and the newest is read by
        :meth:`read` when drawn; False: rclpy reads each one as it arrives.
    """

    message_type = None
    label = ''
    default_frame = ''
    qos = qos_profile_sensor_data
    placed = False
    serialized = True

    def __init__(self, node, server, frames, topics):
        """Subscribe every named topic; with ``'*'``, every one found of ``message_type``."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._topics = {}
        self._next = 0.0
        for topic in self.take_topics(topics, [self.message_type]):
            self.add_topic(topic)

    def add_topic(self, topic):
        """Subscribe ``topic`` (:attr:`qos`)."""
        self._topics[topic] = _Topic()
        self.node.create_subscription(self.message_type, topic,
                                      lambda msg, topic=topic: self._on_message(topic, msg),
                                      self.qos, raw=self.serialized)

    def build(self, gui):
        """Add the display's checkbox."""
        self._show = gui.add_checkbox(self.label, True)

    def rates(self):
        """Return ``[(topic, Rate)]`` of the topics (for the status)."""
        return [(topic, item.rate) for topic, item in list(self._topics.items())]

    def _on_message(self, topic, msg):
        item = self._topics[topic]
        item.rate.tick(time.monotonic())
        with self._lock:
            item.data = msg

    def read(self, data):
        """
        Return what :meth:`render` draws of the serialized message ``data``.

        The message itself here (rclpy's reading); a subclass may read only what it draws. The
        result has ``header.frame_id``.

        :raises Exception: whatever rclpy or the reader raises on bytes it cannot read.
        """
        return deserialize_message(data, self.message_type)

    def _newest(self, topic, item):
        """Return the newest message of ``item`` as :meth:`render` takes it, or None."""
        with self._lock:
            data = item.data
        if data is not item.read_from:
            item.read_from = data
            item.msg = data if not self.serialized else read_or_warn(
                self.node, f'{self.label} {topic}', lambda: self.read(data))
        return item.msg

    def draw(self, context):
        """Draw the newest message of each topic, at most :data:`RATE` times a second."""
        now = time.monotonic()
        if now < self._next:
            return
        self._next = now + 1.0 / RATE
        show = self._show.value
        for topic, item in list(self._topics.items()):
            msg = self._newest(topic, item) if show else item.msg
            if item.node is not None and item.node.visible != show:
                item.node.visible = show
            if msg is None or not show or (item.drawn is msg and not self.placed):
                continue
            frame = msg.header.frame_id.lstrip('/') or self.default_frame
            T = context.pose(frame) if frame != context.fixed else np.eye(4)
            if T is None and frame == self.default_frame:
                T = np.eye(4)  # the simulator's world, not in TF: drawn as the fixed frame
            if T is None:
                context.missing.append(frame)
                continue
            if item.drawn is msg:
                self.place(item.node, msg, T)
                continue
            name = f'/{self.label.lower()}/' + topic.strip('/').replace('/', '_')
            item.drawn = msg
            try:
                item.node = self.render(name, msg, T, item.node)
            except (ValueError, TypeError, AssertionError) as exc:  # a message we cannot draw
                self.node.get_logger().warning(f'{self.label} {topic}: cannot draw: {exc}',
                                               throttle_duration_sec=5.0)

    def render(self, name, msg, T, node):
        """
        Draw ``msg`` placed with ``T`` (4x4, its frame in the fixed frame); return the node.

        :param name: scene node name of this topic.
        :param node: the node drawn last time for this topic, or None.
        """
        raise NotImplementedError

    def place(self, node, msg, T):
        """
        Move the drawn ``node`` of ``msg`` to ``T`` (its frame in the fixed frame, 4x4).

        Called on every redraw of an unchanged message when :attr:`placed` is True.
        """


def rainbow(values, low, high):
    """
    Return (N, 3) uint8 colours of ``values`` from red at ``low`` to blue at ``high``.

    The hue runs over 240 degrees (red, yellow, green, cyan, blue), as RViz's Rainbow.
    """
    span = high - low if high > low else 1.0
    x = np.clip((np.asarray(values, dtype=float) - low) / span, 0.0, 1.0) * 4.0
    r = np.clip(2.0 - x, 0.0, 1.0)
    g = np.clip(np.minimum(x, 4.0 - x), 0.0, 1.0)
    b = np.clip(x - 2.0, 0.0, 1.0)
    return (np.stack([r, g, b], axis=1) * 255).astype(np.uint8)


def draw_points(server, name, points, colours, node, size):
    """
    Create or update a point cloud node of (N, 3) float32 points and (N, 3) uint8 colours.

    Viser needs at least one point: an empty cloud is one black point at the origin.
    """
    if len(points) == 0:
        points = np.zeros((1, 3), np.float32)
        colours = np.zeros((1, 3), np.uint8)
    if node is None:
        return server.scene.add_point_cloud(name, points, colours, point_size=size,
                                            point_shape='square', precision='float32')
    node.points = points
    node.colors = colours
    return node


def draw_segments(server, name, segments, T, colour, node, thickness=2.0, lift=0.0):
    """
    Create or update a line-segment node of (M, 2, 3) ``segments`` placed with ``T`` (4x4).

    :param colour: RGB of every line, or (M, 3) RGB, one per segment.
    :param thickness: pixels on screen.
    :param lift: m added to z after placing (above a map drawn in the same plane).
    """
    colour = np.asarray(colour, np.uint8)
    if len(segments) == 0:
        segments = np.zeros((1, 2, 3), np.float32)  # viser needs one segment
        colour = colour if colour.ndim == 1 else np.zeros(3, np.uint8)
    points = np.asarray(segments, float) @ T[:3, :3].T + T[:3, 3]
    points[..., 2] += lift
    points = points.astype(np.float32)
    if colour.ndim == 2:
        colour = colour[:, None, :]
    colours = np.broadcast_to(colour, points.shape).copy()
    if node is None:
        return server.scene.add_line_segments(name, points, colours, thickness=thickness,
                                              thickness_units='screen')
    node.points = points
    node.colors = colours
    return node
