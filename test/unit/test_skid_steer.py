# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The Coulomb skid-steer model against its closed forms."""

import math

from amr_description.core.skid_steer import contact_forces
from amr_description.core.skid_steer import geometric_separation_multiplier
from amr_description.core.skid_steer import integrate_skid_steer
from amr_description.core.skid_steer import steady_twist
from amr_description.core.skid_steer import turn_in_place_rate
import pytest

A, B = 0.2, 0.15  # half wheelbase, half track of urdf/amr.urdf (m)
MASS, IZZ = 7.0, 0.3  # kg, kg m^2


def test_closed_forms():
    # omega = v b / (a^2 + b^2) = 0.15 / 0.0625 v = 2.4 v
    assert turn_in_place_rate(0.5, A, B) == pytest.approx(1.2)
    assert turn_in_place_rate(-1.0, A, B) == pytest.approx(-2.4)
    # (a^2 + b^2) / b^2 = 0.0625 / 0.0225
    assert geometric_separation_multiplier(A, B) == pytest.approx(25.0 / 9.0)
    assert geometric_separation_multiplier(0.0, B) == 1.0  # wheels on one axle: no slip
    with pytest.raises(ValueError, match='half_track'):
        turn_in_place_rate(1.0, A, 0.0)
    with pytest.raises(ValueError, match='half_wheelbase'):
        geometric_separation_multiplier(-0.1, B)


def test_yaw_moment_vanishes_at_closed_form_rate():
    v = 0.7
    omega = turn_in_place_rate(v, A, B)
    _, force, moment, _ = contact_forces((0.0, 0.0, omega), (-v, -v, v, v), A, B, 17.0, 1.0,
                                         slip_epsilon=0.0 + 1e-12)
    assert moment == pytest.approx(0.0, abs=1e-9)
    assert force == pytest.approx([0.0, 0.0], abs=1e-9)
    # turning faster than the closed form is braked, slower is driven
    assert contact_forces((0, 0, 1.1 * omega), (-v, -v, v, v), A, B, 17.0, 1.0)[2] < 0
    assert contact_forces((0, 0, 0.9 * omega), (-v, -v, v, v), A, B, 17.0, 1.0)[2] > 0


@pytest.mark.parametrize('v, mu', [(0.01, 1.0), (0.1, 0.5), (1.0, 1.0)])
def test_integrated_turn_in_place_matches_closed_form(v, mu):
    vx, vy, omega = steady_twist(-v, v, A, B, MASS, IZZ, mu=mu)
    assert omega == pytest.approx(turn_in_place_rate(v, A, B), rel=1e-3)
    assert abs(vx) < 1e-6 and abs(vy) < 1e-6
    # mirrored wheel speeds turn the other way
    assert steady_twist(v, -v, A, B, MASS, IZZ, mu=mu)[2] == pytest.approx(-omega, rel=1e-6)


def test_straight_and_pose():
    times, twists, poses = integrate_skid_steer(0.5, 0.5, A, B, MASS, IZZ, duration=2.0)
    assert twists[-1] == pytest.approx([0.5, 0.0, 0.0], abs=1e-6)
    # from rest the base accelerates at mu g until it rolls: 0.5 m/s after 0.5 / 9.81 s
    rolling_at = 0.5 / 9.81
    assert poses[-1][0] == pytest.approx(0.5 * (times[-1] - rolling_at / 2), rel=0.01)
    assert poses[-1][1] == pytest.approx(0.0, abs=1e-9)


def test_wheels_on_one_axle_is_a_differential_drive():
    # a = 0: no lateral slip needed to turn, omega = (v_r - v_l) / (2 b), v = mean
    vx, vy, omega = steady_twist(0.1, 0.3, 0.0, B, MASS, IZZ)
    assert omega == pytest.approx(0.2 / (2 * B), rel=2e-3)
    assert vx == pytest.approx(0.2, rel=2e-3)


def test_arc_turns_at_the_coulomb_ratio_and_closes_a_circle():
    vl, vr = 0.2, 0.5
    vx, vy, omega = steady_twist(vl, vr, A, B, MASS, IZZ)
    # slow arcs keep the turn-in-place ratio b^2 / (a^2 + b^2) of the two-wheel rate
    assert omega == pytest.approx((vr - vl) / (2 * B) / geometric_separation_multiplier(A, B),
                                  rel=0.01)
    assert vx == pytest.approx((vl + vr) / 2, rel=0.01)
    _, _, poses = integrate_skid_steer(vl, vr, A, B, MASS, IZZ,
                                       duration=2 * math.pi / omega, dt=0.02)
    # one revolution draws a circle of radius vx / omega: its diameter is the farthest point
    assert max(math.hypot(x, y) for x, y, _ in poses) == pytest.approx(2 * vx / omega, rel=0.01)
    assert poses[-1][2] == pytest.approx(2 * math.pi, rel=0.01)


def test_bad_parameters():
    with pytest.raises(ValueError, match='mass'):
        integrate_skid_steer(0.1, 0.2, A, B, 0.0, IZZ)
    with pytest.raises(ValueError, match='mu'):
        integrate_skid_steer(0.1, 0.2, A, B, MASS, IZZ, mu=-1.0)
