# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The viewer's sensor displays: what they draw from a message, against closed forms."""

import array
import math

from amr_description.web.displays.imu import ACCEL_SCALE
from amr_description.web.displays.imu import GYRO_SCALE
from amr_description.web.displays.imu import imu_segments
from amr_description.web.displays.laser_scan import scan_points
from amr_description.web.displays.point_cloud import cloud_points
from amr_description.web.displays.sensor_topics import rainbow
import numpy as np
import pytest
from sensor_msgs.msg import Imu
from sensor_msgs.msg import LaserScan
from sensor_msgs.msg import PointCloud2
from sensor_msgs.msg import PointField


def test_scan_points_keep_the_valid_ranges_at_their_angles():
    msg = LaserScan(angle_min=-math.pi / 2, angle_increment=math.pi / 2, range_min=0.1,
                    range_max=5.0)
    msg.ranges = array.array('f', [1.0, math.inf, 2.0, -math.inf, 6.0, 0.05])
    points, ranges = scan_points(msg)
    assert ranges.tolist() == [1.0, 2.0]
    assert points == pytest.approx(np.array([[0.0, -1.0, 0.0], [0.0, 2.0, 0.0]]), abs=1e-6)


def test_cloud_points_read_gazebos_layout_and_drop_non_finite_points():
    data = np.zeros(3, dtype=np.dtype({'names': ['x', 'y', 'z', 'intensity', 'ring'],
                                       'formats': ['<f4', '<f4', '<f4', '<f4', '<u2'],
                                       'offsets': [0, 4, 8, 16, 24], 'itemsize': 32}))
    data['x'] = [1.0, np.inf, 3.0]
    data['y'] = [2.0, 0.0, -1.0]
    data['z'] = [0.5, 0.0, 0.25]
    msg = PointCloud2(height=1, width=3, point_step=32, row_step=96)
    msg.fields = [PointField(name=n, offset=o, datatype=PointField.FLOAT32, count=1)
                  for n, o in (('x', 0), ('y', 4), ('z', 8), ('intensity', 16))]
    msg.data = array.array('B', data.tobytes())
    assert cloud_points(msg).tolist() == [[1.0, 2.0, 0.5], [3.0, -1.0, 0.25]]
    msg.fields = msg.fields[1:]
    with pytest.raises(ValueError, match="without a float32 'x' field"):
        cloud_points(msg)


def test_imu_arrows_are_scaled_and_turned_into_the_fixed_frame():
    msg = Imu()
    msg.linear_acceleration.z = 9.8
    msg.angular_velocity.z = 1.0
    msg.linear_acceleration.x = math.nan
    T = np.eye(4)
    T[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]  # yaw 90 deg
    T[:3, 3] = [1.0, 2.0, 0.3]
    segments = imu_segments(msg, T)
    assert segments[0, 0] == pytest.approx([1.0, 2.0, 0.3])
    assert segments[0, 1] == pytest.approx([1.0, 2.0, 0.3 + 9.8 * ACCEL_SCALE])
    assert segments[1, 1] == pytest.approx([1.0, 2.0, 0.3 + GYRO_SCALE])
    msg.linear_acceleration.x, msg.linear_acceleration.z = 2.0, 0.0
    assert imu_segments(msg, T)[0, 1] == pytest.approx([1.0, 2.0 + 2 * ACCEL_SCALE, 0.3])


def test_rainbow_runs_from_red_to_blue():
    colours = rainbow([0.0, 0.5, 1.0], 0.0, 1.0)
    assert colours.tolist() == [[255, 0, 0], [0, 255, 0], [0, 0, 255]]
