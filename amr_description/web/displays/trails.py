# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Odometry: the trail of every odometry topic in the fixed frame (RViz's Odometry display).

One colour per topic with a legend and a Clear button. A trail whose ``header.frame_id`` is
not in TF (the simulator's ``world``) is drawn as if that frame were the fixed frame, and the
legend says so.
"""

import math
import threading
import time

from amr_description.core.tf_buffer import TransformException
from amr_description.ros.cdr import odometry_position
from amr_description.ros.cdr import read
from amr_description.web.displays.base import Display
from amr_description.web.displays.base import moved
from amr_description.web.displays.base import Rate
from amr_description.web.displays.base import read_or_warn
from amr_description.web.displays.discovery import AUTO
from nav_msgs.msg import Odometry
import numpy as np

COLOURS = [((255, 140, 0), 'orange'), ((0, 170, 0), 'green'), ((200, 0, 200), 'magenta'),
           ((0, 160, 200), 'cyan')]
MIN_STEP = 0.01
"""Metres between two points of a trail."""
MAX_POINTS = 20000
"""Points of a trail before the older half is forgotten."""
CHUNK = 200
"""Points per scene node: only the newest chunk is sent again as points arrive."""
RATE = 10.0
"""Trail redraws per second at most."""
TOLERANCE = 1e-4
"""Largest move of a trail's frame in the fixed frame (pose entry) that is not redrawn."""


def _position(msg):
    p = msg.pose.pose.position
    return msg.header.frame_id, (p.x, p.y, p.z)


class _Trail:
    """The points of one odometry topic and the scene nodes drawing them."""

    def __init__(self, rgb, colour):
        self.rgb, self.colour = rgb, colour
        self.frame = ''
        self.points = []
        self.dirty = False
        self.reset = False
        self.chunks = []
        self.chunk_start = 0
        self.T = None
        self.fixed = None
        self.in_tf = True


class TrailsDisplay(Display):
    """
    The trails of ``topics`` (nav_msgs/Odometry, depth 10).

    :param topics: odometry topics; the first one's arrival rate is :attr:`rate`.
    :ivar rated_topic: the first topic (None when there is none).
    :ivar rate: its :class:`~amr_description.web.displays.base.Rate`.
    """

    order = 40
    parameters = (('odometry_topics', [AUTO]),)
    topics_parameter = 'odometry_topics'
    rviz_classes = {'rviz_default_plugins/Odometry': 'odometry_topics'}

    def __init__(self, node, server, frames, topics):
        """Subscribe every odometry topic."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._trails = {}
        self._next = 0.0
        self.rated_topic = None
        self.rate = Rate()
        for topic in self.take_topics(topics, [Odometry]):
            self.add_topic(topic, named=True)

    def add_topic(self, topic, named=False):
        """
        Subscribe an odometry topic (depth 10) and give it a colour.

        Named topics take the colours in their order. A topic found in the graph takes the
        first free colour from green on when it is ground truth, from orange on otherwise, so
        that ``/odom`` is orange and ``/ground_truth/odom`` green whichever is found first.
        The rated topic is the first one that is not ground truth.
        """
        truth = 'ground_truth' in topic
        with self._lock:
            used = {trail.colour for trail in self._trails.values()}
            start = 1 if truth and not named else 0
            order = [COLOURS[(start + i) % len(COLOURS)] for i in range(len(COLOURS))]
            rgb, colour = next((c for c in order if c[1] not in used),
                               COLOURS[len(self._trails) % len(COLOURS)])
            self._trails[topic] = _Trail(rgb, colour)
        if self.rated_topic is None or ('ground_truth' in self.rated_topic and not truth):
            self.rated_topic = topic
        self.node.create_subscription(  # serialized: only the frame and position are read
            Odometry, topic, lambda data, topic=topic: self._on_odometry(topic, data), 10,
            raw=True)

    def build(self, gui):
        """Add the ``Odometry trails`` checkbox, the legend and the Clear button."""
        self._show = gui.add_checkbox('Odometry trails', True)
        self._legend = gui.add_markdown('')
        clear = gui.add_button('Clear trails')
        clear.on_click(lambda _: self.clear())

    def _on_odometry(self, topic, data):
        if topic == self.rated_topic:
            self.rate.tick(time.monotonic())
        read_back = read_or_warn(
            self.node, topic, lambda: read(data, odometry_position, Odometry, _position))
        if read_back is None:
            return
        frame, point = read_back
        if not all(math.isfinite(v) for v in point):
            return
        trail = self._trails[topic]
        frame = frame.lstrip('/')
        if frame != trail.frame:
            trail.frame = frame
            trail.points = []
            trail.reset = True
        points = trail.points
        if points and math.dist(point, points[-1]) < MIN_STEP:
            return
        points.append(point)
        trail.dirty = True
        if len(points) > MAX_POINTS:  # forget the older half and redraw
            del points[:MAX_POINTS // 2]
            trail.reset = True

    def clear(self):
        """Forget every trail's points."""
        with self._lock:
            for trail in self._trails.values():
                trail.points = []
                trail.reset = True

    def draw(self, context):
        """
        Draw the trails in the fixed frame, at most :data:`RATE` times a second.

        A trail is drawn in chunks of :data:`CHUNK` points: only the newest chunk's points are
        sent again when points arrive (as new points of its scene node, not as a new node);
        every chunk is redrawn when the trail's frame moved in the fixed frame, the fixed frame
        changed or the trail was cleared.
        """
        now = time.monotonic()
        if now < self._next:
            return
        self._next = now + 1.0 / RATE
        fixed, show = context.fixed, self._show.value
        with self._lock:
            for topic, trail in self._trails.items():
                self._draw_trail(topic, trail, fixed, show)
        legend = '  \n'.join(
            f'{trail.colour}: `{topic}`' + (
                f' (frame `{trail.frame}` not in TF: drawn in {fixed})'
                if trail.frame and not trail.in_tf else '')
            for topic, trail in self._trails.items())
        if legend != self._legend.content:
            self._legend.content = legend

    def _draw_trail(self, topic, trail, fixed, show):
        T, trail.in_tf = np.eye(4), True
        if trail.frame and trail.frame != fixed:
            try:
                T, _ = self.frames.buffer.lookup(fixed, trail.frame)
            except TransformException:
                trail.in_tf = False
        if moved(trail.T, T, TOLERANCE) or trail.reset or trail.fixed != fixed:
            for node in trail.chunks:
                node.remove()
            trail.chunks, trail.chunk_start = [], 0
            trail.T, trail.fixed, trail.reset = T, fixed, False
            trail.dirty = True
        for node in trail.chunks:
            if node.visible != show:
                node.visible = show
        if not trail.dirty:
            return
        trail.dirty = False
        points = trail.points
        name = topic.strip('/').replace('/', '_')
        while len(points) - trail.chunk_start >= 2:
            start = trail.chunk_start
            chunk = np.asarray(points[start:start + CHUNK + 1], dtype=float)
            chunk = chunk @ T[:3, :3].T + T[:3, 3]
            index = start // CHUNK
            segments = np.stack([chunk[:-1], chunk[1:]], axis=1).astype(np.float32)
            if index < len(trail.chunks):  # the growing chunk: replace its points
                trail.chunks[index].points = segments
            else:
                trail.chunks.append(self.server.scene.add_line_segments(
                    f'/trails/{name}/{index}', segments, trail.rgb, thickness=3.0,
                    thickness_units='screen', visible=show))
            if len(chunk) < CHUNK + 1:
                break  # the newest chunk, still growing
            trail.chunk_start = start + CHUNK
