# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What every display shares: the frame manager (TF buffer, fixed frame, time) and rates.

Times are seconds; ``time.monotonic()`` for rates and page refreshes, sim time (or wall time
without ``/clock``) for stamps.
"""

import collections
import time

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.ros.transforms import read_tf_message
from amr_description.web.displays.discovery import split_topics
from amr_description.web.displays.discovery import TopicFinder
import numpy as np
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock as ClockMsg
from tf2_msgs.msg import TFMessage

RATE_WINDOW = 2.0
"""Seconds (wall) over which topic rates and the real-time factor are measured."""

POSE_TOLERANCE = 1e-5
"""Largest change of a pose matrix entry (m, or rotation entry) not sent to the page."""


def read_or_warn(node, what, reading):
    """
    Return ``reading()``, or None after one warning ``<what>: cannot read: <error>``.

    The warning is throttled to one per 5 s; the viewer keeps running on bytes it cannot read.

    :param node: the viewer node (its logger).
    :param what: the topic (and display) named in the warning.
    :param reading: a callable reading a serialized message (rclpy raises its own types).
    """
    try:
        return reading()
    except Exception as exc:  # noqa: B902 - rclpy raises its own types on bad bytes
        node.get_logger().warning(f'{what}: cannot read: {exc}', throttle_duration_sec=5.0)
        return None


def moved(last, T, tolerance):
    """Return True when ``last`` is None or a 4x4 pose entry differs by more than tolerance."""
    return last is None or float(np.max(np.abs(last - T))) > tolerance


class Rate:
    """Arrival rate of a topic over the last :data:`RATE_WINDOW` seconds (wall clock)."""

    def __init__(self):
        """Start with no arrival."""
        self.times = collections.deque()

    def tick(self, now):
        """Count one arrival at ``now`` (monotonic s)."""
        self.times.append(now)

    def hz(self, now):
        """Return the rate (Hz) at ``now``; 0 with fewer than two arrivals in the window."""
        while self.times and now - self.times[0] > RATE_WINDOW:
            self.times.popleft()
        if len(self.times) < 2:
            return 0.0
        return (len(self.times) - 1) / max(self.times[-1] - self.times[0], 1e-9)


class FrameManager:
    """
    The viewer's TF buffer from ``/tf`` and ``/tf_static``, its fixed frame and its time.

    A backward jump of ``/clock`` (a reset or restarted simulation, ``ros2 bag play --clock``
    beside a running one) clears the buffer's dynamic transforms, as tf2_ros' ``Buffer`` does
    on a jump back of its clock (static ones stay, as in tf2); the robot is drawn again from
    the next ``/tf``. Each jump is logged once (INFO, as RViz's "Detected jump back in time")
    and kept in :attr:`last_jump` for the status text.

    :param node: the viewer node (subscriptions, logger).
    :ivar buffer: the :class:`~amr_description.core.tf_buffer.TransformBuffer`.
    :ivar sim_time: the last ``/clock`` time (s), or None.
    :ivar clock_samples: ``(wall, sim)`` pairs of the last :data:`RATE_WINDOW` s.
    :ivar rates: ``{'/clock': Rate, '/tf': Rate}``.
    :ivar jumps: backward jumps of ``/clock`` seen (int).
    :ivar last_jump: ``(wall s, from sim s, to sim s)`` of the last one, or None.
    :ivar message_frames: frames named by messages (a map's ``header.frame_id``) that may be
        the fixed frame before TF has them, as RViz lets a map's frame be.
    """

    def __init__(self, node):
        """Subscribe ``/tf``, ``/tf_static`` (transient local) and ``/clock``."""
        self.node = node
        self.buffer = TransformBuffer()
        self.sim_time = None
        self.clock_samples = collections.deque()
        self.rates = {'/clock': Rate(), '/tf': Rate()}
        self.jumps = 0
        self.last_jump = None
        self.message_frames = set()
        static_qos = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        # taken serialized and read without rclpy's objects (ros/cdr.py): hundreds a second
        node.create_subscription(TFMessage, '/tf', self._on_tf, 100, raw=True)
        node.create_subscription(TFMessage, '/tf_static', self._on_tf_static, static_qos,
                                 raw=True)
        node.create_subscription(ClockMsg, '/clock', self._on_clock, 10)

    def _store(self, data, static):
        topic = '/tf_static' if static else '/tf'
        entries = read_or_warn(self.node, topic, lambda: read_tf_message(data))
        for parent, child, stamp, xyz, xyzw in entries or ():
            try:
                self.buffer.set_transform(parent, child, stamp, xyz, xyzw, static=static)
            except ValueError as exc:
                self.node.get_logger().warning(f'{topic}: {exc}', throttle_duration_sec=5.0)

    def _on_tf(self, data):
        self.rates['/tf'].tick(time.monotonic())
        self._store(data, False)

    def _on_tf_static(self, data):
        self._store(data, True)

    def _on_clock(self, msg):
        now = time.monotonic()
        self.rates['/clock'].tick(now)
        sim = msg.clock.sec + msg.clock.nanosec * 1e-9
        if self.sim_time is not None and sim < self.sim_time:
            self.clock_samples.clear()
            self.buffer.clear()
            self.jumps += 1
            self.last_jump = (now, self.sim_time, sim)
            self.node.get_logger().info(
                f'/clock jumped back in time ({self.sim_time:.3f} s -> {sim:.3f} s): '
                'transforms cleared', throttle_duration_sec=5.0)
        self.sim_time = sim
        self.clock_samples.append((now, sim))
        while self.clock_samples and now - self.clock_samples[0][0] > RATE_WINDOW:
            self.clock_samples.popleft()


class DrawContext:
    """
    One scene update: the fixed frame and the poses looked up in it so far.

    :param frames: the :class:`FrameManager`.
    :param fixed: the fixed frame of this update.
    :param note: why it differs from the one asked for ('' when it does not).
    :ivar missing: frames a display could not place (for the status).
    """

    def __init__(self, frames, fixed, note=''):
        """Start with no pose looked up."""
        self.frames = frames
        self.fixed = fixed
        self.note = note
        self.missing = []
        self._poses = {}

    def pose(self, frame):
        """Return the pose of ``frame`` in the fixed frame (4x4) or None, looked up once."""
        if frame not in self._poses:
            try:
                self._poses[frame] = self.frames.buffer.lookup(self.fixed, frame)[0]
            except TransformException:
                self._poses[frame] = None
        return self._poses[frame]


class Display:
    """
    A display of the viewer: controls on the page, subscriptions, drawing.

    A display is found through the entry-point group ``amr_description.displays``
    (:mod:`amr_description.web.displays.registry`); its class says what the viewer needs:

    :cvar order: its place in every scene update (and in the page's Displays folder);
        lower first.
    :cvar panel_order: its place among the controls above the Displays folder (None: as
        ``order``).
    :cvar parameters: ``((name, default), ...)``: the viewer parameters it reads (a list
        default declares a string array).
    :cvar topics_parameter: the parameter of ``parameters`` holding its topic list, handed to
        the constructor by :meth:`create` (None: the constructor takes no topics).
    :cvar rviz_classes: ``{RViz display class: parameter}``: an enabled display of that class
        in an ``.rviz`` file sets that topic-list parameter.
    :param node: the viewer node (subscriptions, parameters, logger).
    :param server: the viser server (``scene``, ``gui``).
    :param frames: the shared :class:`FrameManager`.
    """

    order = 50
    panel_order = None
    parameters = ()
    topics_parameter = None
    rviz_classes = {}
    finder = None

    def __init__(self, node, server, frames):
        """Keep the shared parts; a subclass subscribes here."""
        self.node = node
        self.server = server
        self.frames = frames

    def take_topics(self, topics, types, suffix='', key=None):
        """
        Return the named topics of a topic list; with :data:`.discovery.AUTO` in it, find more.

        The display's :meth:`add_topic` is then called for each topic of ``types`` that gains
        a publisher (:class:`~amr_description.web.displays.discovery.TopicFinder`).

        :param topics: the topic-list parameter's value.
        :param types: message classes looked for.
        :param suffix: only topic names ending with it.
        :param key: sort key of topics found together (default: the name).
        """
        named, auto = split_topics(topics)
        if auto:
            self.finder = TopicFinder(types, suffix, named, key)
        return named

    def discover(self, graph):
        """Take the topics that gained a publisher (viewer's timer, every few seconds)."""
        if self.finder is not None:
            for topic in self.finder.new_topics(graph, self.node.count_publishers):
                self.add_topic(topic)

    def add_topic(self, topic):
        """Subscribe a topic found in the graph (displays that use :meth:`take_topics`)."""

    @classmethod
    def create(cls, viewer, settings):
        """
        Make the display for a viewer (override when the constructor takes more).

        :param viewer: the viewer node (``server``, ``frames``, ``displays`` made so far).
        :param settings: dict parameter -> value (an ``.rviz`` file's topics applied).
        """
        if cls.topics_parameter is not None:
            return cls(viewer, viewer.server, viewer.frames, settings[cls.topics_parameter])
        return cls(viewer, viewer.server, viewer.frames)

    def build_panel(self, gui):
        """Add controls at the top of the page's panel, above the Displays folder."""

    def build(self, gui):
        """Add this display's controls to the page's Displays folder."""

    def build_footer(self, gui):
        """Add controls below the Displays folder."""

    def draw(self, context):
        """Bring the scene up to date for one :class:`DrawContext` (inside the batch)."""

    def hidden(self):
        """No page is open (called instead of :meth:`draw`): stop costly subscriptions."""
