# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""SpeedLimiter against closed-form limits (velocity, acceleration per direction, jerk)."""

import math

from amr_description.core.speed_limiter import SpeedLimiter
import pytest


def test_no_limits_passes_through():
    limiter = SpeedLimiter()
    assert limiter.limit(123.0, 0.0, 0.0, 0.01) == 123.0


def test_velocity_clamp_symmetric_default():
    limiter = SpeedLimiter(max_velocity=1.0)
    assert limiter.limit(2.0, 0.0, 0.0, 0.01) == 1.0
    assert limiter.limit(-2.0, 0.0, 0.0, 0.01) == -1.0
    limiter = SpeedLimiter(max_velocity=1.0, min_velocity=-0.2)
    assert limiter.limit(-2.0, 0.0, 0.0, 0.01) == -0.2


def test_acceleration_ramp_reaches_target_in_closed_form_time():
    limiter = SpeedLimiter(max_acceleration=2.0)
    v0 = v1 = 0.0
    dt = 0.01
    for _ in range(25):
        v = limiter.limit(1.0, v0, v1, dt)
        v0, v1 = v, v0
    assert v0 == pytest.approx(0.5)  # 2 m/s^2 * 0.25 s


def test_direction_dependent_limits():
    limiter = SpeedLimiter(max_acceleration=2.0, max_deceleration=-4.0,
                           max_acceleration_reverse=-8.0, max_deceleration_reverse=10.0)
    dt = 0.1
    assert limiter.limit(5.0, 1.0, 1.0, dt) == pytest.approx(1.2)    # accelerate fwd
    assert limiter.limit(-5.0, 1.0, 1.0, dt) == pytest.approx(0.6)   # decelerate fwd
    assert limiter.limit(-5.0, -1.0, -1.0, dt) == pytest.approx(-1.8)  # accelerate rev
    assert limiter.limit(5.0, -1.0, -1.0, dt) == pytest.approx(0.0)  # decelerate rev
    assert limiter.limit(-5.0, 0.0, 0.0, dt) == pytest.approx(-0.8)  # from rest, reverse


def test_defaults_of_asymmetric_limits():
    limiter = SpeedLimiter(max_acceleration=2.0)
    assert limiter.max_deceleration == -2.0
    assert limiter.max_acceleration_reverse == -2.0
    assert limiter.max_deceleration_reverse == 2.0


def test_jerk():
    limiter = SpeedLimiter(max_jerk=1.0)
    dt = 0.1
    # from rest: dv - dv0 limited to 1 * 2 * dt^2 = 0.02
    assert limiter.limit(1.0, 0.0, 0.0, dt) == pytest.approx(0.02)


def test_nan_disables_and_bad_signs_raise():
    assert SpeedLimiter(max_velocity=math.nan).limit(9.0, 0, 0, 0.1) == 9.0
    with pytest.raises(ValueError, match='max_deceleration'):
        SpeedLimiter(max_acceleration=1.0, max_deceleration=1.0)
    with pytest.raises(ValueError, match='max_velocity'):
        SpeedLimiter(max_velocity=-1.0)
