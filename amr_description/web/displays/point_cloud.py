# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
PointCloud2: the points of every cloud topic in the fixed frame (RViz's PointCloud2 display).

The ``x``, ``y``, ``z`` fields (float32, found by name at their offsets, any ``point_step``)
of the newest cloud of each topic are drawn as 0.03 m squares coloured by height (z in the
fixed frame, Rainbow from the lowest to the highest point); points that are not finite are
not drawn. Topics, QoS, rates and frames: :mod:`~amr_description.web.displays.sensor_topics`.
"""

from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_points
from amr_description.web.displays.sensor_topics import rainbow
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
import numpy as np
from sensor_msgs.msg import PointCloud2
from sensor_msgs.msg import PointField

POINT_SIZE = 0.03
"""m, the side of a drawn point."""


def cloud_points(msg):
    """
    Return the finite ``x y z`` points of a PointCloud2 as (N, 3) float32, in its frame.

    :raises ValueError: one line when x, y or z is missing or not float32, or the data is
        shorter than ``point_step * width * height``.
    """
    fields = {f.name: f for f in msg.fields}
    for axis in 'xyz':
        if axis not in fields or fields[axis].datatype != PointField.FLOAT32:
            raise ValueError(f'PointCloud2 without a float32 {axis!r} field')
    count = msg.width * msg.height
    if len(msg.data) < count * msg.point_step:
        raise ValueError(f'PointCloud2 data has {len(msg.data)} bytes, expected '
                         f'{count * msg.point_step}')
    element = '>f4' if msg.is_bigendian else '<f4'
    dtype = np.dtype({'names': ['x', 'y', 'z'], 'formats': [element] * 3,
                      'offsets': [fields[a].offset for a in 'xyz'],
                      'itemsize': msg.point_step})
    raw = np.frombuffer(bytes(msg.data[:count * msg.point_step]), dtype=dtype, count=count)
    points = np.stack([raw['x'], raw['y'], raw['z']], axis=1).astype(np.float32)
    return points[np.all(np.isfinite(points), axis=1)]


class PointCloudDisplay(SensorTopicsDisplay):
    """The clouds of ``topics`` (sensor_msgs/PointCloud2)."""

    message_type = PointCloud2
    label = 'PointCloud2'
    order = 51
    parameters = (('point_cloud_topics', [AUTO]),)
    topics_parameter = 'point_cloud_topics'
    rviz_classes = {'rviz_default_plugins/PointCloud2': 'point_cloud_topics'}

    def render(self, name, msg, T, node):
        """Draw the cloud's finite points in the fixed frame, coloured by height."""
        try:
            points = cloud_points(msg)
        except ValueError as exc:
            self.node.get_logger().warning(f'{name}: {exc}', throttle_duration_sec=5.0)
            return node
        points = (points @ T[:3, :3].T + T[:3, 3]).astype(np.float32)
        z = points[:, 2]
        colours = rainbow(z, float(z.min(initial=0.0)), float(z.max(initial=1.0)))
        return draw_points(self.server, name, points, colours, node, POINT_SIZE)
