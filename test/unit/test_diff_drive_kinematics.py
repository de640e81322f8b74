# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Wheel kinematics of the differential drive against closed form."""

from amr_description.core.diff_drive_kinematics import body_twist
from amr_description.core.diff_drive_kinematics import side_mean
from amr_description.core.diff_drive_kinematics import wheel_velocities
import pytest


def test_straight():
    assert wheel_velocities(0.5, 0.0, 0.4, 0.1, 0.1) == pytest.approx((5.0, 5.0))


def test_turn_in_place_ccw():
    left, right = wheel_velocities(0.0, 1.0, 0.4, 0.1, 0.1)
    assert left == pytest.approx(-2.0)
    assert right == pytest.approx(2.0)


def test_radius_multipliers_and_roundtrip():
    left, right = wheel_velocities(0.3, -0.7, 0.5, 0.1, 0.12)
    assert body_twist(left, right, 0.5, 0.1, 0.12) == pytest.approx((0.3, -0.7))


def test_bad_geometry_and_mean():
    with pytest.raises(ValueError, match='wheel_separation'):
        wheel_velocities(1.0, 0.0, 0.0, 0.1, 0.1)
    assert side_mean([1.0, 3.0]) == 2.0
    with pytest.raises(ValueError):
        side_mean([])
