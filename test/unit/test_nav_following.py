# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Path following, behaviours, smoothing and the navigator's rules, against closed forms."""

import math

from amr_description.nav import behaviors as bh
from amr_description.nav import navigation_logic as logic
from amr_description.nav import pure_pursuit as rpp
from amr_description.nav.costmap import Costmap
from amr_description.nav.costmap import footprint_cost
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.smoothing import smooth
import numpy as np
import pytest


def test_spin_speed_is_the_stopping_speed_within_the_limits():
    assert bh.spin_velocity(0.1) == pytest.approx(math.sqrt(2 * 3.2 * 0.1))  # 0.8 rad/s
    assert bh.spin_velocity(0.01) == 0.4  # sqrt(0.064) = 0.25, raised to min_rotational_vel
    assert bh.spin_velocity(1.0) == 1.0  # sqrt(6.4) = 2.53, cut to max_rotational_vel


def test_look_ahead_poses_stop_at_the_target():
    poses = bh.spin_poses((1.0, 2.0, 0.0), -1.0, 0.5, 2.0, 10.0)
    assert poses.shape == (20, 3)
    assert poses[0, 2] == pytest.approx(-0.1) and poses[-1, 2] == pytest.approx(-0.5)
    assert np.all(poses[:, :2] == (1.0, 2.0))
    back = bh.drive_poses((0.0, 0.0, math.pi / 2), -0.05, 0.3, 2.0, 10.0)
    assert back.shape == (20, 3)
    assert back[-1, :2] == pytest.approx((0.0, -0.1), abs=1e-12)  # 20 cycles at 5 mm
    ahead = bh.drive_poses((0.0, 0.0, 0.0), 0.5, 0.3, 2.0, 10.0)
    assert ahead[-1, 0] == pytest.approx(0.3)  # cut at the remaining distance


def test_drive_goals_are_checked_as_upstream():
    assert bh.drive_goal_error(0.3, 0.0, 0.0, 0.05, backup=True) is None
    assert bh.drive_goal_error(0.3, 0.0, 0.0, -0.05, backup=True) is None  # magnitudes
    assert 'same sign' in bh.drive_goal_error(0.3, 0.0, 0.0, -0.05, backup=False)
    assert 'y and z' in bh.drive_goal_error(0.3, 0.1, 0.0, 0.05, backup=False)
    assert 'finite' in bh.drive_goal_error(math.nan, 0.0, 0.0, 0.05, backup=True)


def test_smoother_limits_acceleration_and_deceleration():
    lim = {'max_velocity': [0.5, 0.0, 2.0], 'min_velocity': [-0.5, 0.0, -2.0],
           'max_accel': [2.5, 0.0, 3.2], 'max_decel': [-2.5, 0.0, -3.2]}
    # from rest towards 1 m/s (clamped to 0.5): 2.5 m/s^2 * 0.05 s
    assert smooth([0, 0, 0], [1.0, 0, 1.0], 0.05, **lim) == pytest.approx([0.125, 0, 0.16])
    # braking uses max_decel
    assert smooth([0.5, 0, 0], [0.0, 0, 0], 0.05, **lim)[0] == pytest.approx(0.375)
    # reversing is braking too, then the command is reached
    assert smooth([0.1, 0, 0], [-0.5, 0, 0], 0.05, **lim)[0] == pytest.approx(-0.025)
    assert smooth([0.45, 0, 0], [0.5, 0, 0], 0.05, **lim)[0] == pytest.approx(0.5)
    assert smooth([0.2, 0, 0], [0.05, 0, 0], 0.05, deadband=[0.1, 0, 0], **lim)[0] == \
        pytest.approx(0.075)  # 0.05 is in the deadband: brake towards 0


def test_navigator_rules():
    assert logic.error_code([0, 0]) == 0
    assert logic.error_code([106, 208]) == 106  # the smallest non-zero wins
    assert logic.error_code([0, 204]) == 204
    assert logic.recovery_could_help(208, 0) and logic.recovery_could_help(0, 105)
    assert not logic.recovery_could_help(204, 0) and not logic.recovery_could_help(0, 103)
    path = [(0, 0), (1, 0), (2, 0), (2, 1)]
    assert logic.remaining_distance(path, (1.1, 0.2)) == pytest.approx(2.0)
    assert logic.remaining_distance([], (0, 0)) == 0.0
    assert logic.time_remaining(2.0, -0.5) == pytest.approx(4.0)
    assert logic.time_remaining(2.0, 0.005) == 0.0 and logic.time_remaining(0.05, 0.5) == 0.0
    goals = [(0, 0), (0.3, 0), (3, 0)]
    assert logic.passed_goals(goals, (0.2, 0.1)) == 2
    assert logic.passed_goals(goals, (3.0, 0.0)) == 0  # the first is 3 m away
    assert logic.passed_goals([(0, 0)], (0, 0)) == 0  # the last goal stays


def test_footprint_cost_is_the_outline_s_highest_cost():
    grid = Costmap(np.zeros((40, 40), np.uint8), 0.05, (-1.0, -1.0))
    square = [(0.2, 0.2), (0.2, -0.2), (-0.2, -0.2), (-0.2, 0.2)]
    assert footprint_cost(grid, square, (0.0, 0.0, 0.0)) == 0
    grid.costs[20, 20] = LETHAL_OBSTACLE  # the cell of (0.0, 0.0): inside, not on the outline
    assert footprint_cost(grid, square, (0.0, 0.0, 0.0)) == 0
    assert footprint_cost(grid, square, (-0.2, 0.0, 0.0)) == LETHAL_OBSTACLE  # front edge
    grid.costs[20, 20] = 100
    assert footprint_cost(grid, square, (0.0, 0.2, math.pi / 2)) == 100  # rotated: an edge
    assert footprint_cost(grid, square, (0.9, 0.0, 0.0)) == LETHAL_OBSTACLE  # off the map


def test_path_in_the_robot_frame_and_the_closest_pose():
    path = np.array([[1.0, 0.0, 0.0], [2.0, 0.0, math.pi / 2]])
    local = rpp.to_robot_frame(path, (1.0, 1.0, -math.pi / 2))
    assert local[0] == pytest.approx([1.0, 0.0, math.pi / 2])
    assert local[1] == pytest.approx([1.0, 1.0, -math.pi], abs=1e-9) or \
        local[1] == pytest.approx([1.0, 1.0, math.pi])
    line = np.column_stack((np.arange(0.0, 10.0, 0.5), np.zeros(20), np.zeros(20)))
    assert rpp.closest_pose(line, (3.1, 0.4), 10.0) == 6
    assert rpp.closest_pose(line, (3.1, 0.4), 1.0) == 2  # the search stops after 1 m
    assert rpp.closest_pose(line, (9.1, 0.4), -1.0) == 18  # negative: the whole path
