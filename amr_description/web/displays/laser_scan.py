# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
LaserScan: the points of every scan topic in the fixed frame (RViz's LaserScan display).

The newest scan of each topic is drawn as square points (RViz's "Flat Squares", here 0.04 m)
placed with the transform of its ``header.frame_id`` into the fixed frame (the newest one in
TF), coloured by range from red (near) through green to blue (at ``range_max``), as RViz's
default "Rainbow" colour transformer. Ranges that are not finite or outside
[``range_min``, ``range_max``] (REP 117) are not drawn. Subscribed with the sensor-data QoS
(best effort, which also hears reliable publishers). A scan whose frame is not in TF is left
out and named in the status (``missing``).
"""

import math
import threading
import time

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import Rate
import numpy as np
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan

RATE = 10.0
"""Scan redraws per second at most."""
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


class _Scan:

    def __init__(self):
        self.msg = None
        self.drawn = None
        self.node = None
        self.rate = Rate()


class LaserScanDisplay(Display):
    """
    The scans of ``topics`` (sensor_msgs/LaserScan).

    :param topics: scan topics ('' entries are ignored).
    """

    def __init__(self, node, server, frames, topics):
        """Subscribe every scan topic."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._scans = {}
        self._next = 0.0
        for topic in (t for t in topics if t):
            self._scans[topic] = _Scan()
            node.create_subscription(LaserScan, topic,
                                     lambda msg, topic=topic: self._on_scan(topic, msg),
                                     qos_profile_sensor_data)

    def build(self, gui):
        """Add the ``LaserScan`` checkbox."""
        self._show = gui.add_checkbox('LaserScan', True)

    def rates(self):
        """Return ``[(topic, Rate)]`` of the scan topics (for the status)."""
        return [(topic, scan.rate) for topic, scan in self._scans.items()]

    def _on_scan(self, topic, msg):
        scan = self._scans[topic]
        scan.rate.tick(time.monotonic())
        with self._lock:
            scan.msg = msg

    def draw(self, context):
        """Draw the newest scan of each topic, at most :data:`RATE` times a second."""
        now = time.monotonic()
        if now < self._next:
            return
        self._next = now + 1.0 / RATE
        show = self._show.value
        for topic, scan in self._scans.items():
            with self._lock:
                msg = scan.msg
            if scan.node is not None and scan.node.visible != show:
                scan.node.visible = show
            if msg is None or not show:
                continue
            frame = msg.header.frame_id.lstrip('/')
            T = context.pose(frame) if frame != context.fixed else np.eye(4)
            if T is None:
                context.missing.append(frame)
                continue
            if scan.drawn is msg:
                continue
            points, ranges = scan_points(msg)
            points = (points @ T[:3, :3].T + T[:3, 3]).astype(np.float32)
            colours = rainbow(ranges, msg.range_min, msg.range_max if
                              math.isfinite(msg.range_max) else max(ranges, default=1.0))
            if len(points) == 0:  # viser needs one point: an invisible one
                points = np.zeros((1, 3), np.float32)
                colours = np.zeros((1, 3), np.uint8)
            if scan.node is None:
                scan.node = self.server.scene.add_point_cloud(
                    '/laser_scan/' + topic.strip('/').replace('/', '_'), points, colours,
                    point_size=POINT_SIZE, point_shape='square', precision='float32')
            else:
                scan.node.points = points
                scan.node.colors = colours
            scan.drawn = msg
