# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Imu: the linear acceleration and angular velocity of every IMU topic as arrows.

As rviz_imu_plugin (imu_tools) draws them: from the origin of the message's frame, the
linear acceleration (red, :data:`ACCEL_SCALE` m per m/s^2: gravity is a 0.5 m arrow up at
rest) and the angular velocity (green, :data:`GYRO_SCALE` m per rad/s), both given in the
IMU frame and drawn in the fixed frame. Topics, QoS, rates and frames:
:mod:`~amr_description.web.displays.sensor_topics`.
"""


from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
import numpy as np
from sensor_msgs.msg import Imu

ACCEL_SCALE = 0.05
"""m of arrow per m/s^2."""
GYRO_SCALE = 0.5
"""m of arrow per rad/s."""
COLOURS = np.array([[[220, 30, 30]] * 2, [[30, 180, 30]] * 2], dtype=np.uint8)
"""(2, 2, 3): the acceleration red, the angular velocity green (both ends)."""


def imu_segments(msg, T):
    """
    Return the (2, 2, 3) float32 segments (acceleration, angular velocity) in the fixed frame.

    Non-finite values give zero-length segments.
    """
    a, w = msg.linear_acceleration, msg.angular_velocity
    vectors = np.array([[a.x, a.y, a.z], [w.x, w.y, w.z]], dtype=float)
    vectors[~np.isfinite(vectors)] = 0.0
    vectors *= np.array([[ACCEL_SCALE], [GYRO_SCALE]])
    origin = T[:3, 3]
    ends = origin + vectors @ T[:3, :3].T
    return np.stack([np.stack([origin, origin]), ends], axis=1).astype(np.float32)


class ImuDisplay(SensorTopicsDisplay):
    """The IMUs of ``topics`` (sensor_msgs/Imu)."""

    message_type = Imu
    label = 'Imu'
    order = 52
    parameters = (('imu_topics', [AUTO]),)
    topics_parameter = 'imu_topics'
    rviz_classes = {'rviz_imu_plugin/Imu': 'imu_topics'}

    def render(self, name, msg, T, node):
        """Draw the two arrows of the newest sample (module docstring)."""
        segments = imu_segments(msg, T)
        if node is None:
            return self.server.scene.add_line_segments(name, segments, COLOURS,
                                                       thickness=4.0,
                                                       thickness_units='screen')
        node.points = segments
        return node
