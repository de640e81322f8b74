# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Odometry against closed-form motions (straight line, rotation in place, arc)."""

import math

from amr_description.core.odometry import Odometry
from amr_description.core.odometry import RollingMean
import pytest

S, R = 0.4, 0.1


def _drive(odom, wl, wr, duration, dt=0.01, feedback='position'):
    """Drive with constant wheel speeds (rad/s) for ``duration`` s from t=0."""
    steps = int(round(duration / dt))
    odom.init(0.0)
    if feedback == 'position':
        odom.update(0.0, 0.0, 0.0)
    for k in range(1, steps + 1):
        t = k * dt
        if feedback == 'position':
            odom.update(wl * t, wr * t, t)
        else:
            odom.update_from_velocity(wl * R * dt, wr * R * dt, t)


@pytest.mark.parametrize('feedback', ['position', 'velocity'])
def test_straight_line(feedback):
    odom = Odometry(S, R, R)
    _drive(odom, 5.0, 5.0, 2.0, feedback=feedback)  # 0.5 m/s for 2 s
    assert odom.x == pytest.approx(1.0, abs=1e-9)
    assert odom.y == pytest.approx(0.0, abs=1e-12)
    assert odom.heading == pytest.approx(0.0, abs=1e-12)
    assert odom.linear == pytest.approx(0.5)
    assert odom.angular == pytest.approx(0.0, abs=1e-12)


def test_rotation_in_place():
    odom = Odometry(S, R, R)
    w = 1.0  # rad/s of the base
    wheel = w * S / 2 / R
    _drive(odom, -wheel, wheel, 1.5)
    assert odom.heading == pytest.approx(1.5, abs=1e-9)
    assert odom.x == pytest.approx(0.0, abs=1e-9)
    assert odom.y == pytest.approx(0.0, abs=1e-9)
    assert odom.angular == pytest.approx(1.0)


def test_arc_matches_circle():
    odom = Odometry(S, R, R)
    v, w = 0.5, 0.5  # radius 1 m
    wl, wr = (v - w * S / 2) / R, (v + w * S / 2) / R
    T = 2.0
    _drive(odom, wl, wr, T, dt=0.1)  # coarse steps: exact arc must still be exact
    radius = v / w
    assert odom.heading == pytest.approx(w * T, abs=1e-9)
    assert odom.x == pytest.approx(radius * math.sin(w * T), abs=1e-9)
    assert odom.y == pytest.approx(radius * (1 - math.cos(w * T)), abs=1e-9)


def test_tiny_dt_skipped():
    odom = Odometry(S, R, R)
    odom.init(0.0)
    odom.update(0.0, 0.0, 0.0)
    assert not odom.update(1.0, 1.0, 5e-5)
    assert odom.x == 0.0
    # the skipped travel is not lost: it counts at the next accepted update
    assert odom.update(1.0, 1.0, 0.01)
    assert odom.x == pytest.approx(0.1)


def test_rk2_for_tiny_angular():
    odom = Odometry(S, R, R)
    odom.integrate(1.0, 1e-7)
    assert odom.x == pytest.approx(math.cos(0.5e-7))
    assert odom.y == pytest.approx(math.sin(0.5e-7))


def test_open_loop():
    odom = Odometry(S, R, R)
    odom.init(0.0)
    odom.update_open_loop(0.5, 0.0, 0.0)
    for k in range(1, 101):
        odom.update_open_loop(0.5, 0.0, k * 0.01)
    assert odom.x == pytest.approx(0.5)
    assert odom.linear == 0.5


def test_nan_position_is_rejected():
    odom = Odometry(S, R, R)
    odom.init(0.0)
    assert not odom.update(math.nan, 0.0, 0.1)
    assert odom.x == 0.0


def test_rolling_mean():
    mean = RollingMean(3)
    for value in (1, 2, 3, 4):
        mean.push(value)
    assert mean.mean() == pytest.approx(3.0)
    with pytest.raises(ValueError):
        RollingMean(0)
