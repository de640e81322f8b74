# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Path and Polygon: Nav2's plans and footprints as lines (RViz's Path and Polygon displays).

- **Path** (``nav_msgs/Path``: planner_server's ``/plan``, controller_server's ``/local_plan``):
  a line through the poses (RViz's ``Line Style: Lines``), each path in its
  ``header.frame_id``;
- **Polygon** (``geometry_msgs/PolygonStamped``: the costmaps' ``published_footprint``): the
  closed outline.

Colours are those of Nav2's ``nav2_default_view.rviz``: ``/plan`` (255, 0, 0), ``/local_plan``
(0, 12, 255), footprints (25, 255, 0); another Path is RViz's default (25, 255, 0). Lines are
raised 0.01 m above their frame's plane so that a map drawn there does not hide them. Both
subscribe with the sensor-data QoS (best effort hears the servers' reliable publishers).
"""

from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_segments
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
from geometry_msgs.msg import PolygonStamped
from nav_msgs.msg import Path
import numpy as np

GLOBAL_PLAN_COLOUR = (255, 0, 0)
LOCAL_PLAN_COLOUR = (0, 12, 255)
DEFAULT_COLOUR = (25, 255, 0)
"""RViz's Path and Polygon default, and Nav2's footprint colour."""
LIFT = 0.01
"""m above the frame's xy-plane."""
THICKNESS = 3.0
"""Pixels, the lines' width."""


def path_colour(topic):
    """Return the RGB colour of a Path topic (Nav2's RViz configuration's)."""
    name = topic.rstrip('/').rsplit('/', 1)[-1]
    colours = {'plan': GLOBAL_PLAN_COLOUR, 'local_plan': LOCAL_PLAN_COLOUR}
    return colours.get(name, DEFAULT_COLOUR)


def polyline_segments(points, closed=False):
    """
    Return the segments joining ``points`` in order: (M, 2, 3) float32.

    :param points: (N, 3) m.
    :param closed: join the last point to the first as well (a polygon).
    :raises ValueError: on a value that is not finite.
    """
    points = np.asarray(points, float).reshape(-1, 3)
    if not np.isfinite(points).all():
        raise ValueError('a point that is not finite (NaN or infinite values)')
    ends = np.roll(points, -1, axis=0) if closed else points[1:]
    starts = points if closed else points[:-1]
    if closed and len(points) < 2:
        starts = ends = points[:0]
    return np.stack([starts, ends], axis=1).astype(np.float32)


class PathDisplay(SensorTopicsDisplay):
    """The paths of ``path_topics`` (nav_msgs/Path) as lines."""

    message_type = Path
    label = 'Path'
    order = 66
    parameters = (('path_topics', [AUTO]),)
    topics_parameter = 'path_topics'
    rviz_classes = {'rviz_default_plugins/Path': 'path_topics'}

    def add_topic(self, topic):
        """Subscribe ``topic`` and choose its colour (:func:`path_colour`)."""
        self.__dict__.setdefault('colours', {})
        self.colours['/path/' + topic.strip('/').replace('/', '_')] = path_colour(topic)
        super().add_topic(topic)

    def render(self, name, msg, T, node):
        """Draw the line through the path's poses."""
        points = [(p.pose.position.x, p.pose.position.y, p.pose.position.z) for p in msg.poses]
        return draw_segments(self.server, name, polyline_segments(points), T,
                             self.colours.get(name, DEFAULT_COLOUR), node, THICKNESS, LIFT)


class PolygonDisplay(SensorTopicsDisplay):
    """The outlines of ``polygon_topics`` (geometry_msgs/PolygonStamped)."""

    message_type = PolygonStamped
    label = 'Polygon'
    order = 67
    parameters = (('polygon_topics', [AUTO]),)
    topics_parameter = 'polygon_topics'
    rviz_classes = {'rviz_default_plugins/Polygon': 'polygon_topics'}

    def render(self, name, msg, T, node):
        """Draw the closed outline."""
        points = [(p.x, p.y, p.z) for p in msg.polygon.points]
        return draw_segments(self.server, name, polyline_segments(points, closed=True), T,
                             DEFAULT_COLOUR, node, THICKNESS, LIFT)
