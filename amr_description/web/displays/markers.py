# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
MarkerArray: visualization_msgs markers as points and lines (RViz's MarkerArray display).

Each topic's markers are kept as RViz keeps them, by ``(ns, id)``: ``ADD`` (and ``MODIFY``)
puts a marker, ``DELETE`` removes one, ``DELETEALL`` removes every marker of the topic, in
the array's order (:func:`apply`); a ``lifetime`` is not counted. What is kept is drawn
(:func:`geometry`), in each marker's pose, with its ``color`` or its per-point ``colors``:

- ``SPHERE``, ``CUBE``, ``CYLINDER``: a point at the marker's position, ``scale.x`` wide;
- ``POINTS``, ``SPHERE_LIST``, ``CUBE_LIST``: a point per entry of ``points``;
- ``LINE_LIST``: a segment per pair of ``points``; ``LINE_STRIP``: a line through them;
- ``ARROW``: a segment from ``points[0]`` to ``points[1]``, or ``scale.x`` along the
  marker's x axis;
- ``TEXT_VIEW_FACING``, ``MESH_RESOURCE``, ``TRIANGLE_LIST``: not drawn.

Points are drawn as one cloud per topic, as wide as the widest point marker; lines 3 pixels
wide; both 0.01 m above their frame's plane (as the Path display). A topic's markers are
drawn in the frame of its first marker; a marker in another frame is left out with one
throttled warning. Subscribed with the sensor-data QoS, as the other displays (best effort
hears reliable publishers). slam_toolbox's
``slam_toolbox/graph_visualization`` is such a topic (amr_description/nav/graph_markers.py).
"""

import time

from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_points
from amr_description.web.displays.sensor_topics import draw_segments
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
import numpy as np
from std_msgs.msg import Header
from visualization_msgs.msg import Marker
from visualization_msgs.msg import MarkerArray

POINT_TYPES = (Marker.SPHERE, Marker.CUBE, Marker.CYLINDER)
LIST_TYPES = (Marker.POINTS, Marker.SPHERE_LIST, Marker.CUBE_LIST)
THICKNESS = 3.0
"""Pixels, the lines' width."""
LIFT = 0.01
"""m added to z after placing, so that a map drawn in the same plane does not hide them."""
EMPTY_SIZE = 0.001
"""m, the size of the one point viser needs in a cloud when no marker is a point."""


def apply(kept, array):
    """
    Apply a MarkerArray's actions in order to ``kept`` (dict ``(ns, id)`` -> Marker).

    :param kept: the topic's markers, changed in place.
    :param array: visualization_msgs/MarkerArray.
    """
    for marker in array.markers:
        key = (marker.ns, marker.id)
        if marker.action == Marker.DELETEALL:
            kept.clear()
        elif marker.action == Marker.DELETE:
            kept.pop(key, None)
        else:  # ADD, and MODIFY (the same value)
            kept[key] = marker


def _rotation(q):
    """Return the 3x3 rotation of a geometry_msgs Quaternion (identity for all zeros)."""
    x, y, z, w = q.x, q.y, q.z, q.w
    n = x * x + y * y + z * z + w * w
    if n == 0.0:
        return np.eye(3)
    s = 2.0 / n
    return np.array([
        [1 - s * (y * y + z * z), s * (x * y - z * w), s * (x * z + y * w)],
        [s * (x * y + z * w), 1 - s * (x * x + z * z), s * (y * z - x * w)],
        [s * (x * z - y * w), s * (y * z + x * w), 1 - s * (x * x + y * y)]])


def _colours(marker, count):
    """Return (count, 3) uint8: per-point ``colors`` when there is one per point."""
    if marker.colors and len(marker.colors) == count:
        rgb = [(c.r, c.g, c.b) for c in marker.colors]
    else:
        rgb = [(marker.color.r, marker.color.g, marker.color.b)] * count
    return (np.clip(np.asarray(rgb, float).reshape(-1, 3), 0.0, 1.0) * 255).astype(np.uint8)


def geometry(markers):
    """
    Return what ``markers`` draw, in their frame (see the module docstring).

    :param markers: iterable of visualization_msgs/Marker.
    :returns: ``(points (N, 3), point colours (N, 3) uint8, point size m, segments (M, 2, 3),
        segment colours (M, 3) uint8)``; sizes 0.0 when there are no points.
    :raises ValueError: on a value that is not finite.
    """
    points, colours, segments, seg_colours, size = [], [], [], [], 0.0
    for m in markers:
        R = _rotation(m.pose.orientation)
        t = np.array([m.pose.position.x, m.pose.position.y, m.pose.position.z])
        local = np.array([(p.x, p.y, p.z) for p in m.points], float).reshape(-1, 3)
        placed = local @ R.T + t
        if m.type in POINT_TYPES:
            points.append(t.reshape(1, 3))
            colours.append(_colours(m, 1))
            size = max(size, m.scale.x)
        elif m.type in LIST_TYPES:
            points.append(placed)
            colours.append(_colours(m, len(placed)))
            size = max(size, m.scale.x)
        elif m.type in (Marker.LINE_LIST, Marker.LINE_STRIP, Marker.ARROW):
            if m.type == Marker.LINE_LIST:
                pairs = placed[:len(placed) // 2 * 2].reshape(-1, 2, 3)
                rgb = _colours(m, len(placed))[:len(pairs) * 2:2]
            elif m.type == Marker.LINE_STRIP:
                pairs = np.stack([placed[:-1], placed[1:]], axis=1)
                rgb = _colours(m, len(placed))[:len(pairs)]
            else:
                tip = placed[1] if len(placed) >= 2 else t + R[:, 0] * m.scale.x
                pairs = np.stack([placed[0] if len(placed) >= 2 else t, tip]).reshape(1, 2, 3)
                rgb = _colours(m, 1)
            segments.append(pairs)
            seg_colours.append(rgb)
    points = np.concatenate(points) if points else np.zeros((0, 3))
    segments = np.concatenate(segments) if segments else np.zeros((0, 2, 3))
    if not (np.isfinite(points).all() and np.isfinite(segments).all()):
        raise ValueError('a point that is not finite (NaN or infinite values)')
    return (points, np.concatenate(colours) if colours else np.zeros((0, 3), np.uint8), size,
            segments, np.concatenate(seg_colours) if seg_colours else np.zeros((0, 3), np.uint8))


class _Kept:
    """A topic's kept markers in one frame, drawn as one message (``header.frame_id``)."""

    def __init__(self, frame_id, markers):
        self.header = Header(frame_id=frame_id)
        self.markers = markers


class MarkerArrayDisplay(SensorTopicsDisplay):
    """The markers of ``marker_array_topics`` (visualization_msgs/MarkerArray)."""

    message_type = MarkerArray
    label = 'MarkerArray'
    order = 68
    parameters = (('marker_array_topics', [AUTO]),)
    topics_parameter = 'marker_array_topics'
    rviz_classes = {'rviz_default_plugins/MarkerArray': 'marker_array_topics'}
    serialized = False  # every array is applied, not only the newest

    def add_topic(self, topic):
        """Subscribe ``topic`` with nothing kept yet."""
        self.__dict__.setdefault('kept', {})[topic] = {}
        super().add_topic(topic)

    def _on_message(self, topic, msg):
        """Apply the array to the topic's kept markers; the next redraw draws them."""
        item = self._topics[topic]
        with self._lock:
            kept = self.kept[topic]
            apply(kept, msg)
            markers = list(kept.values())
            frame = markers[0].header.frame_id if markers else ''
            same = [m for m in markers if m.header.frame_id == frame]
            item.data = _Kept(frame, same)
        item.rate.tick(time.monotonic())
        if len(same) < len(markers):
            self.node.get_logger().warning(
                f'MarkerArray {topic}: markers in frames other than {frame!r} are not drawn',
                throttle_duration_sec=5.0)

    def render(self, name, msg, T, node):
        """Draw the kept markers' points and lines, placed with ``T``."""
        points, colours, size, segments, seg_colours = geometry(msg.markers)
        if node is None:
            node = (None, None)
        cloud, lines = node
        placed = points @ T[:3, :3].T + T[:3, 3] + (0.0, 0.0, LIFT)
        size = size if len(points) else EMPTY_SIZE  # viser's one point of an empty cloud
        cloud = draw_points(self.server, name + '/points', placed.astype(np.float32), colours,
                            cloud, size)
        cloud.point_size = size
        lines = draw_segments(self.server, name + '/lines', segments, T, seg_colours, lines,
                              THICKNESS, LIFT)
        return _Nodes(cloud, lines)


class _Nodes(tuple):
    """The (cloud, lines) scene nodes of a topic; hidden and shown together."""

    def __new__(cls, cloud, lines):
        """Hold both nodes."""
        return super().__new__(cls, (cloud, lines))

    @property
    def visible(self):
        """Return whether the nodes are shown."""
        return self[0].visible

    @visible.setter
    def visible(self, value):
        for child in self:
            child.visible = value
