# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Unit tests of the scripted course, its follower and the per-leg table."""

import math

from amr_description.core.course import closure_error
from amr_description.core.course import CourseFollower
from amr_description.core.course import format_leg_table
from amr_description.core.course import Leg
from amr_description.core.course import leg_delta
from amr_description.core.course import square_course
from amr_description.core.course import wrap_angle
import pytest


def test_wrap_angle():
    assert wrap_angle(0.0) == 0.0
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap_angle(-math.pi) == pytest.approx(math.pi)
    assert wrap_angle(7 * math.pi) == pytest.approx(math.pi)


def test_square_course_legs():
    legs = square_course(side=1.0, speed=0.3, turn_rate=0.6)
    assert [leg.kind for leg in legs] == ['straight', 'turn'] * 4
    assert sum(leg.target for leg in legs if leg.kind == 'turn') == pytest.approx(2 * math.pi)
    assert all(leg.target == 1.0 for leg in legs if leg.kind == 'straight')
    cw = square_course(counter_clockwise=False)
    assert cw[1].target == pytest.approx(-math.pi / 2)


@pytest.mark.parametrize('kind, target, speed', [
    ('hop', 1.0, 1.0), ('straight', float('nan'), 1.0), ('turn', 1.0, 0.0)])
def test_leg_rejects_bad_values(kind, target, speed):
    with pytest.raises(ValueError):
        Leg(kind, target, speed)


def _simulate(follower, dt=0.01, steps=20000):
    """Integrate the unicycle model exactly under the follower's commands."""
    x = y = yaw = 0.0
    ends = [(x, y, yaw)]
    for _ in range(steps):
        v, w, finished = follower.step((x, y, yaw))
        if finished is not None:
            ends.append((x, y, yaw))
        if follower.done:
            break
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw = wrap_angle(yaw + w * dt)
    return ends


def test_follower_closes_square_on_ideal_robot():
    legs = square_course(side=1.0, speed=0.25, turn_rate=0.5)
    follower = CourseFollower(legs)
    ends = _simulate(follower)
    assert follower.done
    assert len(ends) == len(legs) + 1
    # first corner: 1 m along +x, then facing +y
    assert ends[1][0] == pytest.approx(1.0, abs=0.01)
    assert ends[2][2] == pytest.approx(math.pi / 2, abs=0.02)
    position, heading = closure_error(ends)
    assert position < 0.03
    assert heading < 0.03
    assert follower.step(ends[-1]) == (0.0, 0.0, None)


def test_follower_ramps_up_and_down_at_constant_acceleration():
    follower = CourseFollower([Leg('straight', 1.0, 0.5)], acceleration=(0.5, 1.0),
                              min_fraction=0.1)
    # v = min(cruise, sqrt(v0^2 + 2 a done), sqrt(v0^2 + 2 a remaining)), v0 = 0.05 m/s
    assert follower.step((0.0, 0.0, 0.0))[0] == pytest.approx(0.05)
    assert follower.step((0.09, 0.0, 0.0))[0] == pytest.approx(math.sqrt(0.0025 + 0.09))
    assert follower.step((0.5, 0.0, 0.0))[0] == pytest.approx(0.5)
    assert follower.step((0.96, 0.0, 0.0))[0] == pytest.approx(math.sqrt(0.0025 + 0.04))
    assert follower.step((0.9985, 0.0, 0.0))[0] == pytest.approx(math.sqrt(0.0025 + 0.0015))
    assert follower.step((-0.1, 0.0, 0.0))[0] == pytest.approx(0.05)  # never below v0
    assert follower.step((0.9995, 0.0, 0.0)) == (0.0, 0.0, 0)
    turn = CourseFollower([Leg('turn', -math.pi / 2, 0.5)], acceleration=(0.5, 1.0))
    assert turn.step((0.0, 0.0, 0.0))[1] == pytest.approx(-0.05)
    assert turn.step((0.0, 0.0, -0.06))[1] == pytest.approx(-math.sqrt(0.0025 + 0.12))
    with pytest.raises(ValueError, match='acceleration'):
        CourseFollower([], acceleration=(0.0, 1.0))


def test_leg_delta_and_table():
    assert leg_delta((0, 0, 0), (3, 4, math.pi / 2)) == pytest.approx((5.0, math.pi / 2))
    legs = [Leg('straight', 1.0, 0.2), Leg('turn', math.pi / 2, 0.5)]
    odom = [(0, 0, 0), (1.0, 0, 0), (1.0, 0, math.pi / 2)]
    truth = [(0, 0, 0), (0.98, 0, 0), (0.98, 0, math.radians(85.0))]
    table = format_leg_table(legs, odom, truth).splitlines()
    assert 'odom dist' in table[0] and 'true hdg' in table[0]
    assert table[2].split() == ['1', 'straight', '1.000', '1.000', '0.980', '0.0', '0.0',
                                '0.0']
    assert table[3].split()[-3:] == ['90.0', '90.0', '85.0']
    with pytest.raises(ValueError, match='need 3 poses'):
        format_leg_table(legs, odom[:2], truth)


def test_a_turn_takes_back_what_the_turn_before_overshot():
    quarter = math.pi / 2
    legs = [Leg('turn', quarter, 0.5), Leg('straight', 1.0, 0.5), Leg('turn', quarter, 0.5)]
    follower = CourseFollower(legs, tolerance=(0.001, 0.001))
    assert follower.step((0.0, 0.0, 0.0))[1] > 0.0
    assert follower.step((0.0, 0.0, math.pi / 2))[2] == 0  # the first turn ends at 90 deg
    # it overshoots 0.01 rad after its stop; the straight starts there, then the second turn
    # ends at 180 deg, having turned 90 deg less the 0.01 rad
    assert follower.step((0.0, 0.0, math.pi / 2 + 0.01))[2] is None
    assert follower.step((0.0, 1.0, math.pi / 2 + 0.01))[2] == 1
    assert follower.step((0.0, 1.0, math.pi / 2 + 0.01))[1] > 0.0
    assert follower.step((0.0, 1.0, math.pi - 0.0005))[2] == 2
    assert follower.done


def test_turns_across_the_wrap_end_at_the_course_heading():
    three = 3 * math.pi / 4
    follower = CourseFollower([Leg('turn', three, 0.5), Leg('turn', three, 0.5)])
    assert follower.step((0.0, 0.0, 0.0))[1] > 0.0
    assert follower.step((0.0, 0.0, three + 0.0005))[2] == 0  # 0.0005 rad past 135 deg
    # the yaw wraps to -pi on the way: still turning left, towards 270 deg (-90 deg) less
    # the first turn's 0.0005 rad
    assert follower.step((0.0, 0.0, -math.pi + 0.1))[1] > 0.0
    assert follower.step((0.0, 0.0, -math.pi / 2 - 0.0015))[2] is None
    assert follower.step((0.0, 0.0, -math.pi / 2 - 0.0009))[2] == 1
