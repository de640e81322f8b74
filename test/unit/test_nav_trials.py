# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""amr_description.nav.trials: goals, lengths, clearance and the time bound, in closed form."""

import math

from amr_description.nav.map_io import GridMap
from amr_description.nav.trials import clearance_at
from amr_description.nav.trials import clearance_grid
from amr_description.nav.trials import footprint_clearance
from amr_description.nav.trials import path_length
from amr_description.nav.trials import sample_goals
from amr_description.nav.trials import time_bound
import numpy as np
import pytest


def _two_rooms():
    """10 x 4 m at 0.1 m: a wall at x 5.0 .. 5.2 splits it; border cells occupied."""
    data = np.zeros((40, 100), np.int8)
    data[0, :] = data[-1, :] = data[:, 0] = data[:, -1] = 100
    data[:, 50:52] = 100
    return GridMap(data, 0.1, (0.0, 0.0, 0.0))


def test_clearance_is_the_distance_between_cell_centres():
    grid = GridMap(np.zeros((1, 6), np.int8), 0.5)
    grid.data[0, 0] = 100
    assert clearance_grid(grid)[0].tolist() == [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]
    grid.data[0, 5] = -1  # unknown is not free
    assert clearance_grid(grid)[0].tolist() == [0.0, 0.5, 1.0, 1.0, 0.5, 0.0]
    assert clearance_at(grid, clearance_grid(grid), [[1.25, 0.2], [9.0, 0.0]]).tolist() == \
        [1.0, 0.0]  # outside the grid: 0


def test_goals_are_seeded_reachable_clear_and_spaced():
    grid = _two_rooms()
    goals = sample_goals([grid], (1.0, 2.0), 20, seed=7, clearance=0.45, spacing=1.5)
    assert goals == sample_goals([grid], (1.0, 2.0), 20, seed=7, clearance=0.45, spacing=1.5)
    assert goals != sample_goals([grid], (1.0, 2.0), 20, seed=8, clearance=0.45, spacing=1.5)
    xy = np.array([g[:2] for g in goals])
    # the start's room: x < 5.0 - 0.45, y within 0.1 + 0.45 of the border cells' centres
    assert (xy[:, 0] <= 5.0 - 0.45 + 1e-9).all() and (xy[:, 0] >= 0.1 + 0.45 - 1e-9).all()
    assert (xy[:, 1] >= 0.55 - 1e-9).all() and (xy[:, 1] <= 3.45 + 1e-9).all()
    steps = np.hypot(*np.diff(np.vstack([[1.0, 2.0], xy]), axis=0).T)
    assert steps.min() >= 1.5
    assert all(-math.pi <= g[2] < math.pi for g in goals)
    # a second map that blocks the room's left half leaves only its right half
    other = _two_rooms()
    other.data[:, :30] = -1
    right = sample_goals([grid, other], (4.0, 2.0), 10, seed=1, clearance=0.45, spacing=0.5)
    assert min(g[0] for g in right) >= 3.0 + 0.45 - 1e-9


def test_goals_stay_where_two_maps_agree():
    # two SLAM maps of one world differ in a few cells: goals drawn away from them are the
    # same (a different candidate count shifted every later goal of an index-based draw)
    grid = _two_rooms()
    other = _two_rooms()
    other.data[30:33, 10:13] = 100  # a 0.3 m blob in the first room, centred (1.15, 3.15)
    goals = sample_goals([grid], (1.0, 2.0), 10, seed=1, clearance=0.45, spacing=1.5)
    moved = sample_goals([other], (1.0, 2.0), 10, seed=1, clearance=0.45, spacing=1.5)
    assert goals == moved
    # none near it: the blob's 0.15 m half size and the 0.45 m clearance
    assert min(math.hypot(g[0] - 1.15, g[1] - 3.15) for g in goals) > 0.15 + 0.45


def test_goals_go_through_a_door_narrower_than_their_clearance():
    grid = _two_rooms()
    grid.data[15:25, 50:52] = 0  # a 1.0 m door: 0.5 m clear at its middle, under 0.45 apart
    goals = sample_goals([grid], (1.0, 2.0), 40, seed=3, clearance=0.45, spacing=1.5)
    assert max(g[0] for g in goals) > 5.2 + 0.45 - 1e-9  # in the far room too
    shut = sample_goals([grid], (1.0, 2.0), 40, seed=3, clearance=0.45, spacing=1.5,
                        passage=0.55)
    assert max(g[0] for g in shut) < 5.0  # all in the start's room


def test_a_start_that_is_not_clear_is_refused():
    with pytest.raises(ValueError, match=r'start \(5.10, 2.00\) is not 0.3 m clear'):
        sample_goals([_two_rooms()], (5.1, 2.0), 1, seed=0)


def test_path_length_and_time_bound():
    assert path_length([[0, 0], [3, 4], [3, 4], [3, 5]]) == 6.0
    assert path_length([[1, 1]]) == 0.0
    # 2 m along +x from yaw 0 to yaw pi/2: 4 s of driving and a quarter turn at 1.8 rad/s
    bound = time_bound([[0, 0], [1, 0], [2, 0]], 0.0, math.pi / 2, 0.5, 1.8)
    assert bound == pytest.approx(1.5 * (4.0 + (math.pi / 2) / 1.8))
    # facing -x at the start: a half turn first
    assert time_bound([[0, 0], [2, 0]], math.pi, 0.0, 0.5, 1.8, slack=1.0) == \
        pytest.approx(4.0 + math.pi / 1.8)
    # a goal where the base already stands: its turn only
    assert time_bound([[1, 1], [1, 1]], 0.0, -1.0, 0.5, 1.8, slack=1.0) == \
        pytest.approx(1.0 / 1.8)


def test_rest_to_rest_and_the_fastest_time_to_a_goal():
    from amr_description.nav.trials import fastest_time
    from amr_description.nav.trials import rest_to_rest
    # 2 m at 0.5 m/s and 2 m/s^2: 0.25 s (0.0625 m) to speed, as long to brake, 3.75 s between
    assert rest_to_rest(2.0, 0.5, 2.0) == pytest.approx(0.25 + 3.75 + 0.25)
    # 0.1 m never reaches 0.5 m/s (it takes 0.125 m): 0.05 m speeding up in sqrt(0.05) s
    assert rest_to_rest(0.1, 0.5, 2.0) == pytest.approx(2.0 * math.sqrt(0.05))
    assert rest_to_rest(0.125, 0.5, 2.0) == pytest.approx(0.5)  # both forms meet there
    assert rest_to_rest(-0.125, 0.5, 2.0) == pytest.approx(0.5)
    assert rest_to_rest(0.0, 0.5, 2.0) == 0.0
    # a quarter turn at 1.8 rad/s and 2 rad/s^2 (1.62 rad to reach 1.8): 2 sqrt(pi / 4) s;
    # a half turn reaches it: pi / 1.8 + 0.9 s
    quarter, half = 2.0 * math.sqrt(math.pi / 4), math.pi / 1.8 + 0.9
    assert fastest_time([[0, 0], [1, 0], [2, 0]], math.pi / 2, 0.0, 0.5, 1.8, 2.0, 2.0) == \
        pytest.approx(quarter + 4.25)
    assert fastest_time([[0, 0], [2, 0]], math.pi, -math.pi / 2, 0.5, 1.8, 2.0, 2.0) == \
        pytest.approx(half + 4.25 + quarter)
    # the bends cost nothing: an L of 1 + 1 m takes as long as a straight 2 m
    assert fastest_time([[0, 0], [1, 0], [1, 1]], 0.0, math.pi / 2, 0.5, 1.8, 2.0, 2.0) == \
        pytest.approx(4.25)
    # the yardstick is below the bound of the same goal at these limits
    assert fastest_time([[0, 0], [2, 0]], math.pi, 0.0, 0.5, 1.8, 2.0, 2.0) < \
        time_bound([[0, 0], [2, 0]], math.pi, 0.0, 0.5, 1.8)


def test_footprint_clearance_to_a_box():
    square = [[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5], [-0.5, 0.5]]
    box = [('box', (3.0, 0.0), 0.0, (0.5, 0.7))]  # x 2.5 .. 3.5, y -0.7 .. 0.7
    gaps = footprint_clearance([[0, 0, 0], [1.5, 0, 0], [2.3, 0, 0], [0, 0, math.pi / 4]],
                               square, box)
    assert gaps[0] == pytest.approx(2.0)
    assert gaps[1] == pytest.approx(0.5)
    assert gaps[2] == pytest.approx(-0.3)  # the front edge 0.3 m into the box
    assert gaps[3] == pytest.approx(2.5 - math.sqrt(0.5), abs=0.01)  # a corner ahead
    circle = [('circle', (0.0, 2.0), 0.25)]
    assert footprint_clearance([[0, 0, 0]], square, circle)[0] == pytest.approx(1.25)
    post = [('circle', (0.1, 0.0), 0.05)]  # wholly inside the footprint: 0.35 m from its edge
    assert footprint_clearance([[0, 0, 0]], square, post)[0] == pytest.approx(-0.35)
    assert footprint_clearance([[0, 0, 0]], square, [])[0] == math.inf


def test_the_jobs_robot_params_and_table(tmp_path):
    from amr_description.nodes.navigate_job.report import format_table
    from amr_description.nodes.navigate_job.report import robot_params
    import os
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
    robot = robot_params(os.path.join(root, 'config', 'nav2_params.yaml'))
    assert robot == {'footprint': [(0.3, 0.17), (0.3, -0.17), (-0.3, -0.17), (-0.3, 0.17)],
                     'speed': 0.5, 'turn_rate': 1.8, 'accel': 2.0, 'angular_accel': 4.0}
    bare = tmp_path / 'bare.yaml'
    bare.write_text('local_costmap:\n  local_costmap:\n    ros__parameters:\n'
                    '      robot_radius: 0.22\n')
    round_robot = robot_params(str(bare))
    assert (round_robot['speed'], round_robot['turn_rate']) == (0.5, 1.8)  # RPP's defaults
    assert (round_robot['accel'], round_robot['angular_accel']) == (2.5, 3.2)  # the smoother's
    wrong = tmp_path / 'wrong.yaml'
    wrong.write_text('velocity_smoother:\n  ros__parameters:\n    max_accel: 2.5\n')
    with pytest.raises(ValueError, match="velocity_smoother max_accel '2.5': expected"):
        robot_params(str(wrong))
    assert np.hypot(*np.array(round_robot['footprint']).T) == pytest.approx([0.22] * 16)
    # a 2 m drive along +x in 5 s, 1 m from a wall at y = 1.5 (wall half-thickness 0.1)
    wall = [('box', (1.0, 1.6), 0.0, (5.0, 0.1))]
    truth = [(10.0 + 0.05 * i, 0.02 * i, 0.0, 0.0) for i in range(101)]
    row = {'goal': (2.1, 0.0, 0.1), 'start': (0.0, 0.0, 0.0), 'result': 'SUCCEEDED',
           'planned': [(0.0, 0.0), (2.1, 0.0)], 'truth': truth}
    text, ok = format_table([row], truth, wall, robot)
    assert ok
    assert 'mapping route: 2.00 m driven in 5.0 s of sim time, closest approach to the ' \
        'world 1.330 m' in text  # 1.5 - 0.17
    bound = 1.5 * (2.1 / 0.5 + 0.1 / 1.8)
    assert f'  SUCCEEDED     5.0 {bound:7.1f}     2.10    2.00   0.100      5.7    1.330' \
        in text, text
    assert "1 of 1 goals SUCCEEDED; the ground truth ended within Nav2's default " \
        'tolerances (0.25 m, 0.25 rad) at 1' in text
    assert 'time to goal within its bound (1.5 x (planned length / desired_linear_vel + ' \
        f"in-place turns / rotate_to_heading_angular_vel)) at 1; 5.0 s against the bounds' " \
        f'{bound:.1f} s ({5.0 / bound:.2f})' in text, text
    assert "where the goals' time went (ground truth): 0.0 s turning in place, 5.0 s at " \
        '0.40 m/s or more (80 % of desired_linear_vel), 0.0 s slower, 0.0 s standing' in text
    # 2.1 m from rest to rest at 0.5 m/s and 2 m/s^2, then 0.1 rad at 4 rad/s^2
    fastest = 2.1 / 0.5 + 0.25 + 2.0 * math.sqrt(0.1 / 4.0)
    assert 'the fastest a base within these limits could reach them (in-place turns and ' \
        'planned length, each from rest to rest within desired_linear_vel, ' \
        "rotate_to_heading_angular_vel and velocity_smoother's max_accel): " \
        f'{fastest:.1f} s; the goals took {5.0 / fastest:.2f} x that, the bounds allow ' \
        f'{bound / fastest:.2f} x' in text, text
    slow = dict(row, truth=[(10.0 + 0.2 * i, 0.02 * i, 0.0, 0.0) for i in range(101)])
    slow_text = format_table([slow], truth, wall, robot)[0]
    assert f"at 0; 20.0 s against the bounds' {bound:.1f} s" in slow_text
    assert '0.0 s turning in place, 0.0 s at 0.40 m/s or more (80 % of desired_linear_vel), ' \
        '20.0 s slower, 0.0 s standing' in slow_text
    # the time runs from the goal's sending to its result, not to the last ground truth
    settled = dict(row, span=(10.0, 14.0))
    assert f'  SUCCEEDED     4.0 {bound:7.1f}' in format_table([settled], truth, wall, robot)[0]
    touching = dict(row, truth=[(t, x, 1.35, yaw) for t, x, _, yaw in truth])
    assert format_table([row, touching], truth, wall, robot)[1] is False  # 0.02 m into it
    assert format_table([dict(row, result='ABORTED')], truth, wall, robot)[1] is False


def test_time_budget_splits_a_drive_by_the_speeds_of_its_ground_truth():
    from amr_description.nav.trials import time_budget
    # 1 s standing, 2 s turning in place at 1 rad/s through +-pi (wrapped), 2 s at 0.45 m/s,
    # 3 s at 0.2 m/s, sampled every 0.02 s
    truth, t, x, yaw = [(0.0, 0.0, 0.0, 3.0)], 0.0, 0.0, 3.0
    for steps, v, w in ((50, 0.0, 0.0), (100, 0.0, 1.0), (100, 0.45, 0.0), (150, 0.2, 0.0)):
        for _ in range(steps):
            t, x = t + 0.02, x + v * 0.02
            yaw = math.atan2(math.sin(yaw + w * 0.02), math.cos(yaw + w * 0.02))
            truth.append((t, x, 0.0, yaw))
    budget = time_budget(truth, 0.5)
    assert budget == pytest.approx({'standing': 1.0, 'turning': 2.0, 'at_speed': 2.0,
                                    'slower': 3.0})
    # only the span counts; a repeated stamp is skipped, not divided by
    assert time_budget(truth, 0.5, span=(0.99, 3.01)) == pytest.approx(
        {'standing': 0.0, 'turning': 2.0, 'at_speed': 0.0, 'slower': 0.0})
    assert time_budget([(0.0, 0, 0, 0), (0.0, 1, 0, 0), (1.0, 1, 0, 0)], 0.5) == \
        {'standing': 1.0, 'turning': 0.0, 'at_speed': 0.0, 'slower': 0.0}
    # at 0.45 m/s a 1.0 m/s follower is slower; no samples, no time
    assert time_budget(truth, 1.0)['slower'] == pytest.approx(5.0)
    assert time_budget([], 0.5) == {'standing': 0.0, 'turning': 0.0, 'at_speed': 0.0,
                                    'slower': 0.0}


def test_the_jobs_real_time_factor_is_a_factor_or_0_for_lock_step(capsys):
    from amr_description.nodes.navigate_job.main import _parse
    assert _parse(['--rtf', '2']).rtf == 2.0
    assert _parse(['--rtf', '0']).rtf == 0.0
    for bad in ('-1', 'nan'):
        with pytest.raises(SystemExit) as exit_info:
            _parse(['--rtf', bad])
        assert exit_info.value.code == 2
        assert 'argument --rtf: must be >= 0 (0: lock-step)' in capsys.readouterr().err


def test_the_jobs_amcl_error_is_against_the_ground_truth_at_amcls_stamp():
    import math

    from amr_description.nodes.navigate_job.main import Recorder

    recorder = object.__new__(Recorder)  # no node: the subscriptions are not under test
    recorder.samples, recorder.amcl = [], None
    assert recorder.amcl_error() is None
    recorder.samples = [(0.02 * i, 0.01 * i, 0.0, 0.001 * i) for i in range(1000)]
    recorder.amcl = (4.005, 2.03, 0.04, 0.25)  # nearest sample: 4.00
    distance, yaw = recorder.amcl_error()
    assert distance == pytest.approx(math.hypot(0.03, 0.04))   # truth at 4.00: (2.00, 0)
    assert yaw == pytest.approx(0.05)
