# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
LaserScan: the points of every scan topic in the fixed frame (RViz's LaserScan display).

The newest scan of each topic is drawn as square points (RViz's "Flat Squares", here 0.04 m)
coloured by range from red (near) through green to blue (at ``range_max``), as RViz's
"Rainbow" colour transformer. Ranges that are not finite or outside [``range_min``,
``range_max``] (REP 117) are not drawn. Topics, QoS, rates and frames:
:mod:`~amr_description.web.displays.sensor_topics`.
"""

import math

from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_points
from amr_description.web.displays.sensor_topics import rainbow
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
import numpy as np
from sensor_msgs.msg import LaserScan

POINT_SIZE = 0.04
"""m, the side of a drawn point."""


def scan_points(msg):
    """
    Return the points of a LaserScan in its frame and their ranges.

    :param msg: ``sensor_msgs/LaserScan``.
    :returns: ``(points (N, 3) float32 m, ranges (N,) m)`` of the valid readings: finite and
        within [``range_min``, ``range_max``] (REP 117).
    """
    ranges = np.asarray(msg.ranges, dtype=np.float64)
    angles = msg.angle_min + msg.angle_increment * np.arange(len(ranges))
    valid = np.isfinite(ranges) & (ranges >= msg.range_min) & (ranges <= msg.range_max)
    r, a = ranges[valid], angles[valid]
    points = np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(r)], axis=1)
    return points.astype(np.float32), r


class LaserScanDisplay(SensorTopicsDisplay):
    """The scans of ``topics`` (sensor_msgs/LaserScan)."""

    message_type = LaserScan
    label = 'LaserScan'
    order = 50
    parameters = (('scan_topics', [AUTO]),)
    topics_parameter = 'scan_topics'
    rviz_classes = {'rviz_default_plugins/LaserScan': 'scan_topics'}

    def render(self, name, msg, T, node):
        """Draw the scan's valid points in the fixed frame, coloured by range."""
        points, ranges = scan_points(msg)
        points = (points @ T[:3, :3].T + T[:3, 3]).astype(np.float32)
        high = msg.range_max if math.isfinite(msg.range_max) else max(ranges, default=1.0)
        return draw_points(self.server, name, points, rainbow(ranges, msg.range_min, high),
                           node, POINT_SIZE)
