# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Costmap layers, the GridBased planner and Regulated Pure Pursuit against closed forms."""

import math

from amr_description.nav import costmap as cm
from amr_description.nav.checkers import PoseProgressChecker
from amr_description.nav.checkers import SimpleGoalChecker
from amr_description.nav.checkers import SimpleProgressChecker
from amr_description.nav.checkers import StoppedGoalChecker
from amr_description.nav.cycle_clock import CycleClock
from amr_description.nav.planner import cell_gradient
from amr_description.nav.planner import invalid_poses
from amr_description.nav.planner import make_plan
from amr_description.nav.planner import path_length
from amr_description.nav.planner import PlanError
from amr_description.nav.pure_pursuit import carrot
from amr_description.nav.pure_pursuit import checked_params
from amr_description.nav.pure_pursuit import circle_collides
from amr_description.nav.pure_pursuit import cusp_distance
from amr_description.nav.pure_pursuit import NoValidControl
from amr_description.nav.pure_pursuit import RegulatedPurePursuit
import numpy as np
import pytest


def test_occupancy_translation_is_nav2s():
    assert list(cm.to_occupancy([0, 1, 252, 253, 254, 255])) == [0, 1, 98, 99, 100, -1]
    assert cm.to_occupancy([127])[0] == 1 + 97 * 126 // 251


def test_static_layer_reads_values_as_nav2():
    grid = np.array([-1, 0, 50, 99, 100])
    assert list(cm.static_costs(grid)) == [0, 0, 0, 0, 254]
    assert list(cm.static_costs(grid, track_unknown_space=True)) == [255, 0, 0, 0, 254]
    assert list(cm.static_costs(grid, trinary_costmap=False)) == [0, 0, 127, 251, 254]


def test_footprints_and_their_radii():
    square = cm.parse_footprint('[[0.25, 0.15], [0.25, -0.15], [-0.25, -0.15], [-0.25, 0.15]]')
    inscribed, circumscribed = cm.footprint_radii(square)
    assert inscribed == pytest.approx(0.15)
    assert circumscribed == pytest.approx(math.hypot(0.25, 0.15))
    padded = cm.footprint_radii(cm.pad_footprint(square, 0.01))
    assert padded[0] == pytest.approx(0.16)
    # a 16-gon of r: the edge midpoints are at r cos(pi / 16)
    assert cm.footprint_radii(cm.footprint_from_radius(0.22))[0] == \
        pytest.approx(0.22 * math.cos(math.pi / 16))
    with pytest.raises(ValueError, match='footprint: expected'):
        cm.parse_footprint('[[1, 2], [3]]')


def test_inflation_follows_nav2s_formula():
    costs = np.zeros((41, 41), np.uint8)
    costs[20, 20] = cm.LETHAL_OBSTACLE
    out = cm.inflate(costs, 0.05, inflation_radius=0.55, cost_scaling_factor=3.0,
                     inscribed_radius=0.1)
    assert out[20, 20] == 254 and out[20, 22] == 253  # 0.10 m: inscribed
    assert out[20, 24] == int(252 * math.exp(-3.0 * 0.1))  # 0.20 m
    assert out[23, 24] == int(252 * math.exp(-3.0 * 0.15))  # 5 cells on the diagonal
    assert out[20, 31] == int(252 * math.exp(-3.0 * 0.45))  # 11 cells = ceil(0.55 / 0.05)
    assert out[20, 32] == 0  # beyond the inflation radius
    unknown = costs.copy()
    unknown[20, 22] = unknown[20, 26] = cm.NO_INFORMATION
    out = cm.inflate(unknown, 0.05, 0.55, 3.0, 0.1)
    assert out[20, 22] == 253 and out[20, 26] == 255  # only inscribed costs overwrite unknown


def test_obstacle_layer_clears_along_rays_and_marks_their_ends():
    grid = cm.Costmap(np.full((10, 10), cm.LETHAL_OBSTACLE, np.uint8), 0.1)
    grid.raytrace((0.05, 0.55), [(0.95, 0.55)], max_range=3.0)
    assert list(grid.costs[5]) == [0] * 9 + [254]  # the end cell is not cleared
    assert (grid.costs[4] == 254).all()
    grid.costs[:] = 0
    grid.mark([(0.95, 0.55), (0.95, 0.05)], sensor=(0.05, 0.55), max_range=0.95)
    assert grid.costs[5, 9] == 254 and grid.costs[0, 9] == 0  # the second is 1.03 m away
    assert grid.world_to_map(-0.01, 0.5) is None and grid.world_to_map(0.99, 0.0) == (9, 0)


def test_scan_rays_hits_and_clearing_only_rays():
    ranges = [1.0, float('inf'), 0.05, float('nan'), 2.0]
    points, hit = cm.scan_rays(ranges, 0.0, math.pi / 2, 0.1, 1.5)
    assert points == pytest.approx(np.array([[1.0, 0.0]])) and list(hit) == [True]
    points, hit = cm.scan_rays(ranges, 0.0, math.pi / 2, 0.1, 1.5, inf_is_valid=True,
                               inf_range=3.0)
    assert points == pytest.approx(np.array([[1.0, 0.0], [0.0, 3.0]]))
    assert list(hit) == [True, False]


def _room(width=5.0, height=5.0, res=0.05):
    return cm.Costmap.empty(width, height, res)


def test_plan_on_free_ground_is_the_straight_line():
    path = make_plan(_room(), (0.5, 0.5), (4.5, 0.5, 1.0))
    assert path_length(path) == pytest.approx(4.0, abs=1e-9)
    assert path[-1, 2] == 1.0 and np.isnan(path[0, 2])
    diagonal = make_plan(_room(), (0.525, 0.525), (3.525, 3.525, 0.0))
    assert path_length(diagonal) == pytest.approx(3.0 * math.sqrt(2), abs=1e-9)


def test_cell_gradient_points_down_the_potential_and_out_of_walls():
    ramp = np.tile(np.arange(5.0) * 2.0, (3, 1))  # potential rising with the column
    assert cell_gradient(ramp, 1, 2) == pytest.approx((0.0, -1.0))
    assert cell_gradient(ramp, 0, 0) == pytest.approx((0.0, -1.0))  # one-sided at the edge
    ramp[1, 2] = math.inf  # unreachable: towards the reachable side neighbours before it
    assert cell_gradient(ramp, 1, 2) == pytest.approx((-math.sqrt(0.5), -math.sqrt(0.5)))
    assert cell_gradient(np.full((3, 3), math.inf), 1, 1) == (0.0, 0.0)


def test_a_replanned_path_is_the_rest_of_the_last_one():
    # NavFn's descent on one potential of the goal: the plan from a point on the path follows
    # it (a path traced back cell by cell put its diagonal steps elsewhere after each replan)
    room = _room(10.0, 5.0)
    goal = (8.525, 2.525, 0.0)
    path = make_plan(room, (0.525, 0.525), goal)
    assert path_length(path) < 1.02 * math.hypot(8.0, 2.0)
    for k in (20, 40, 100):
        rest = make_plan(room, tuple(path[k, :2]), goal)
        gaps = np.hypot(*(rest[:, None, :2] - path[None, :, :2]).T).min(axis=0)
        assert gaps.max() < 0.05
    # poses half a cell apart, turning gradually: no 45 degree kinks of a cell path
    steps = np.diff(path[:-1, :2], axis=0)
    assert np.hypot(*steps.T) == pytest.approx(0.025)
    turns = np.diff(np.arctan2(steps[:, 1], steps[:, 0]))
    assert np.abs(turns).max() < 0.1


def test_plan_goes_through_the_gap_of_a_wall():
    room = _room()
    room.costs[:80, 50] = cm.LETHAL_OBSTACLE  # x = 2.5 m, from y = 0 to 4 m
    room.costs = cm.inflate(room.costs, 0.05, 0.3, 10.0, 0.1)
    path = make_plan(room, (0.5, 0.5), (4.5, 0.5, 0.0))
    shortest = 2 * math.hypot(2.0, 4.0 + 0.1 - 0.5)  # around the inscribed end of the wall
    # 8-connected steps are up to 8.2 % longer than the straight line (1 / cos(22.5 deg)), and
    # NavFn's costs keep the path off the inflated cells
    assert shortest < path_length(path) < 1.15 * shortest
    assert path[:, 1].max() > 4.0
    cells = [room.world_to_map(x, y) for x, y in path[:, :2]]
    assert all(room.costs[my, mx] < 253 for mx, my in cells)


def test_plan_errors_and_tolerance():
    room = _room()
    with pytest.raises(PlanError) as e:
        make_plan(room, (0.5, 0.5), (5.5, 0.5, 0.0))
    assert e.value.code == 'GOAL_OUTSIDE_MAP'
    with pytest.raises(PlanError) as e:
        make_plan(room, (-0.5, 0.5), (1.5, 0.5, 0.0))
    assert e.value.code == 'START_OUTSIDE_MAP'
    room.costs[40:61, 40:61] = cm.LETHAL_OBSTACLE  # a 1.05 m block from 2.0 to 3.05 m
    with pytest.raises(PlanError) as e:
        make_plan(room, (0.5, 0.5), (2.5, 2.5, 0.0), tolerance=0.0)
    assert e.value.code == 'GOAL_OCCUPIED'
    near = make_plan(room, (0.5, 0.5), (2.1, 2.5, 0.0), tolerance=0.5)
    assert near[-1, 0] == pytest.approx(1.975) and near[-1, 1] == pytest.approx(2.525)
    with pytest.raises(PlanError) as e:
        make_plan(room, (0.5, 0.5), (2.5, 2.5, 0.0), tolerance=0.3)
    assert e.value.code == 'NO_VALID_PATH'


def test_unknown_space_only_when_allowed():
    room = _room()
    room.costs[:, 50] = cm.NO_INFORMATION
    assert len(make_plan(room, (0.5, 0.5), (4.5, 0.5, 0.0), allow_unknown=True))
    with pytest.raises(PlanError) as e:
        make_plan(room, (0.5, 0.5), (4.5, 0.5, 0.0), allow_unknown=False, tolerance=0.0)
    assert e.value.code == 'NO_VALID_PATH'


def _line(y=0.0, length=3.0, step=0.05):
    xs = np.arange(0.0, length + 1e-9, step)
    return np.column_stack((xs, np.full_like(xs, y), np.zeros_like(xs)))


def test_carrot_is_on_the_lookahead_circle():
    assert carrot(_line()[:, :2], 0.6) == pytest.approx([0.6, 0.0])
    c = carrot(_line(0.3)[:, :2], 0.6)
    assert c == pytest.approx([math.sqrt(0.27), 0.3])
    assert carrot(_line(length=0.3)[:, :2], 0.6) == pytest.approx([0.3, 0.0])


def test_rpp_speeds():
    rpp = RegulatedPurePursuit()
    assert rpp.compute(_line()) == pytest.approx((0.5, 0.0))
    # carrot (sqrt(0.27), 0.3): curvature 0.6 / 0.36; radius 0.6 < 0.9 slows to 0.5 * 2 / 3
    v, w = rpp.compute(_line(0.3))
    assert v == pytest.approx(0.5 * (1 - 0.3 / 0.9)) and w == pytest.approx(v * 0.6 / 0.36)
    # cost 200 near an obstacle: d = (3 r - ln 200 + ln 253) / 3
    rpp = RegulatedPurePursuit(inscribed_radius=0.2255)
    d = (3 * 0.2255 - math.log(200) + math.log(253)) / 3
    assert rpp.compute(_line(), cost=200)[0] == pytest.approx(0.5 * d / 0.6)
    # approach: 0.3 m of path left scales by 0.3 / 0.6
    assert rpp.compute(_line(length=0.3))[0] == pytest.approx(0.25)


def test_carrot_past_the_goal_carries_the_last_segment_on():
    # a path ending 0.3 m ahead on the x axis: with interpolation the 0.6 m point is (0.6, 0)
    assert carrot(_line(length=0.3)[:, :2], 0.6, True) == pytest.approx([0.6, 0.0])
    # ending at (0.3, 0.3) going +y: the ray x = 0.3 leaves the 0.6 m circle at y sqrt(0.27)
    path = np.array([[0.3, 0.0], [0.3, 0.1], [0.3, 0.2], [0.3, 0.3]])
    assert carrot(path, 0.6, True) == pytest.approx([0.3, math.sqrt(0.27)])
    assert carrot(path[-1:], 0.6, True) == pytest.approx([0.3, 0.3])  # one pose: itself


def test_rpp_fixed_curvature_lookahead_regulates_and_steers_by_its_own_point():
    # y = 0.3 offset: the carrot at 0.6 m gives radius 0.6 (slowed); with the curvature
    # taken at 1.5 m, the point (sqrt(2.16), 0.3) gives radius 2.25 / 0.6 = 3.75: full speed,
    # and w = v x 0.6 / 2.25 (upstream steers by the regulation curvature too)
    plain = RegulatedPurePursuit()
    assert plain.compute(_line(0.3))[0] < 0.5
    fixed = RegulatedPurePursuit({'use_fixed_curvature_lookahead': True,
                                  'curvature_lookahead_dist': 1.5})
    v, w = fixed.compute(_line(0.3))
    assert v == pytest.approx(0.5) and w == pytest.approx(0.5 * 0.6 / 2.25)
    # the rotation to the path looks at that point too: the carrot at 0.6 m is 90 deg off
    # (a path from (0, 0.6) to the left); the curvature point (1.2, 0.6) is 26.6 deg off
    path = np.array([[x, 0.6, 0.0] for x in np.arange(0.0, 3.0, 0.05)])
    assert plain.compute(path)[0] == 0.0  # rotating in place
    fixed = RegulatedPurePursuit({'use_fixed_curvature_lookahead': True,
                                  'curvature_lookahead_dist': math.hypot(1.2, 0.6)})
    v, w = fixed.compute(path)
    assert v > 0.0 and w == pytest.approx(v * 2 * 0.6 / (1.2 ** 2 + 0.6 ** 2))


def test_rpp_parameters_checked_as_upstream_s_handler():
    p, lines = checked_params({'allow_reversing': True,
                               'interpolate_curvature_after_goal': True,
                               'inflation_cost_scaling_factor': 0.0,
                               'max_robot_pose_search_dist': -1.0})
    assert not p['allow_reversing'] and not p['interpolate_curvature_after_goal']
    assert not p['use_cost_regulated_linear_velocity_scaling']
    assert p['max_robot_pose_search_dist'] == math.inf
    assert len(lines) == 4 and lines[0].startswith('Disabling reversing.')
    assert checked_params({})[1] == []
    # cost regulation off: no division by the factor 0
    rpp = RegulatedPurePursuit({'inflation_cost_scaling_factor': 0.0}, inscribed_radius=0.2)
    assert rpp.compute(_line(), cost=200) == pytest.approx((0.5, 0.0))


def test_rpp_reverses_towards_a_carrot_behind_and_stops_at_the_cusp():
    params = {'allow_reversing': True, 'use_rotate_to_heading': False}
    rpp = RegulatedPurePursuit(params)
    v, w = rpp.compute(-_line())  # the path runs backwards: full speed in reverse
    assert v == pytest.approx(-0.5) and w == pytest.approx(0.0)
    # backwards 0.4 m to a cusp at (-0.4, 0), then forwards again: the lookahead stops at the
    # cusp, 0.4 m behind, and the robot reverses to it; without that limit the 0.6 m carrot
    # would lie on the forward leg ahead (x 0.6) and the robot would drive forwards
    there = np.column_stack((-np.arange(0.0, 0.41, 0.05), np.zeros(9), np.zeros(9)))
    back = np.column_stack((-0.4 + np.arange(0.05, 2.0, 0.05), np.full(39, 0.05),
                            np.zeros(39)))
    path = np.vstack((there, back))
    assert cusp_distance(path) == pytest.approx(0.4)
    assert cusp_distance(_line()) == math.inf
    v, w = rpp.compute(path)
    assert v == pytest.approx(-0.5) and w == pytest.approx(0.0)


def test_rpp_cancel_deceleration_slows_from_the_odometry_s_speed():
    rpp = RegulatedPurePursuit()
    assert rpp.cancel()  # off (upstream's default): at once
    rpp = RegulatedPurePursuit({'use_cancel_deceleration': True, 'cancel_deceleration': 2.0})
    assert not rpp.cancel()
    v, w = rpp.compute(_line(), speed=(0.5, 0.0), dt=0.05)  # 0.5 - 2.0 x 0.05
    assert v == pytest.approx(0.4) and w == 0.0 and not rpp.cancel()
    assert rpp.compute(_line(), speed=(0.08, 0.0), dt=0.05)[0] == 0.0  # would cross 0
    assert rpp.cancel()


def test_rpp_rotates_in_place_with_its_acceleration_limit():
    rpp = RegulatedPurePursuit()
    behind = -_line()
    assert rpp.compute(behind, speed=(0.0, 0.0), dt=0.05) == pytest.approx((0.0, 0.16))
    assert rpp.compute(behind, speed=(0.0, 1.8), dt=0.05) == pytest.approx((0.0, 1.8))
    # at the goal position: turn to the goal's heading, then keep turning (stateful)
    at_goal = np.array([[0.1, 0.0, -1.0]])
    v, w = rpp.compute(at_goal, speed=(0.0, -1.8))
    assert v == 0.0 and w == pytest.approx(-1.8)
    assert rpp.rotating_to_goal


def test_rpp_reverses_a_turn_that_overshot_the_heading_as_upstream():
    # rotateToHeading: still turning at 1.0 rad/s with the heading 0.1 rad behind, the rate
    # within the acceleration limit is 1.0 - 3.2 x 0.05 = 0.84, above the stopping rate
    # sqrt(2 x 3.2 x 0.1) = 0.8: the command is that rate towards the heading, -0.8 (kept at
    # +0.8, the base turned on away from the heading and spun for minutes)
    rpp = RegulatedPurePursuit()
    v, w = rpp.compute(np.array([[0.05, 0.0, -0.1]]), speed=(0.0, 1.0), dt=0.05)
    assert v == 0.0 and w == pytest.approx(-math.sqrt(0.64))
    # before the heading the same rate brakes the turn, in its own direction
    assert rpp.compute(np.array([[0.05, 0.0, 0.1]]), speed=(0.0, 1.0))[1] == \
        pytest.approx(math.sqrt(0.64))


def test_a_late_loop_brakes_the_turn_in_place_earlier():
    # turning at 1.8 rad/s, 0.5 rad before the goal's heading, max_angular_accel 1.5: on time
    # the stopping rate is upstream's sqrt(2 x 1.5 x 0.5) = 1.2247; with the next command up
    # to 0.2 s late it is the w that turns w x 0.2 + w^2 / (2 x 1.5) = 0.5 rad in all:
    # 1.5 x (sqrt(0.04 + 2 x 0.5 / 1.5) - 0.2) = 0.9270
    at_goal = np.array([[0.05, 0.0, 0.5]])
    rpp = RegulatedPurePursuit({'max_angular_accel': 1.5})
    assert rpp.compute(at_goal, speed=(0.0, 1.8))[1] == pytest.approx(math.sqrt(1.5))
    w = rpp.compute(at_goal, speed=(0.0, 1.8), lateness=0.2)[1]
    assert w == pytest.approx(1.5 * (math.sqrt(0.04 + 1.0 / 1.5) - 0.2))
    assert w * 0.2 + w * w / 3.0 == pytest.approx(0.5)
    # the acceleration limit spans the step given: from rest, 1.5 x 0.2 = 0.3 rad/s
    rpp = RegulatedPurePursuit({'max_angular_accel': 1.5})
    assert rpp.compute(-_line(), speed=(0.0, 0.0), dt=0.2) == pytest.approx((0.0, 0.3))


def test_the_cycle_clock_gives_the_step_and_the_lateness():
    clock = CycleClock(0.05, window=3, stall=1.0)
    assert clock.tick(10.0) == (0.05, 0.0)  # the first cycle: the nominal step
    assert clock.tick(10.05) == pytest.approx((0.05, 0.0))  # on time: upstream's
    assert clock.tick(10.30) == pytest.approx((0.25, 0.20))  # 0.2 s late
    assert clock.tick(10.31) == pytest.approx((0.05, 0.20))  # early: the nominal step
    assert clock.tick(10.36) == pytest.approx((0.05, 0.20))
    assert clock.tick(10.41) == pytest.approx((0.05, 0.0))  # out of the last 3 intervals
    assert clock.tick(15.0) == pytest.approx((0.05, 0.0))  # idle between goals: no lateness
    clock.reset()
    assert clock.tick(15.5) == (0.05, 0.0)


def test_a_new_path_restarts_the_goal_latches_as_nav2s_set_planner_path():
    # Nav2's ControllerServer::setPlannerPath resets the goal checker and RPP's setPlan its
    # has_reached_xy_tolerance_: with RPP's latch kept, a replan that moved the goal out of
    # the reset checker's reach left the robot turning in place until "Failed to make
    # progress" (docs/navigation.md)
    import logging
    from types import SimpleNamespace

    from amr_description.nodes.controller_server import ControllerServer
    from geometry_msgs.msg import PoseStamped
    from nav2_msgs.action import FollowPath
    from nav_msgs.msg import Path
    rpp = RegulatedPurePursuit({'stateful': True}, 0.1)
    rpp.compute(np.array([[0.05, 0.0, 1.0]]))
    checker = SimpleGoalChecker(0.1, 0.1, stateful=True)
    assert not checker.is_goal_reached((0.0, 0.0, 0.0), (0.05, 0.0, 1.0))
    assert rpp.rotating_to_goal and checker.xy_reached
    server = SimpleNamespace(
        run={'cid': 'FollowPath', 'rpp': rpp, 'goal': checker},
        _pick=lambda table, name, what: 'FollowPath', controllers={}, goal_checkers={},
        progress_checkers={}, get_logger=lambda: logging.getLogger('controller_server'),
        costmap=SimpleNamespace(p={'global_frame': 'odom'}))
    goal = FollowPath.Goal(path=Path(poses=[PoseStamped()]))
    goal.path.header.frame_id = 'map'
    ControllerServer._on_goal(server, SimpleNamespace(request=goal))
    assert not rpp.rotating_to_goal and not checker.xy_reached
    assert server.run['frame'] == 'map' and server.run['path'].shape == (1, 3)


def test_rpp_refuses_an_arc_into_an_obstacle():
    local = cm.Costmap.empty(3.0, 3.0, 0.05, origin=(-1.5, -1.5), frame='odom')
    # a wall 0.45 m ahead: at 0.5 m/s, steps of 0.1 s (one 5 cm cell) while i * 0.1 < 1 s
    # reach 0.45 m (upstream's loop), so a wall at 0.5 m is not yet in collision
    local.costs[:, 39] = cm.LETHAL_OBSTACLE
    rpp = RegulatedPurePursuit()
    with pytest.raises(NoValidControl):
        rpp.compute(_line(), collision=lambda x, y, yaw: circle_collides(local, x, y))
    local.costs[:] = 0
    assert rpp.compute(_line(), collision=lambda x, y, yaw: circle_collides(local, x, y))[0] == 0.5


def _wall_beside(wall_y):
    """Return ``collision(x, y, yaw)``: the 0.6 x 0.34 m footprint's outline at y >= wall_y."""
    t = np.linspace(-1.0, 1.0, 41)
    outline = np.concatenate([np.column_stack((0.3 * t, np.full_like(t, 0.17))),
                              np.column_stack((0.3 * t, np.full_like(t, -0.17))),
                              np.column_stack((np.full_like(t, 0.3), 0.17 * t)),
                              np.column_stack((np.full_like(t, -0.3), 0.17 * t))])
    checked = []

    def collision(x, y, yaw):
        checked.append((x, y, yaw))
        return bool((y + outline[:, 0] * math.sin(yaw) + outline[:, 1] * math.cos(yaw)
                     >= wall_y).any())

    return collision, checked


def test_rpp_checks_a_rotation_in_place_for_collision():
    # a path to the left: RPP turns in place at 1.8 rad/s; the footprint's corners sweep the
    # circumscribed radius hypot(0.3, 0.17) = 0.345 m, so a wall 0.25 m to the side (the
    # robot's side 0.08 m from it) is hit within 1 s of turning and one 0.40 m away is not
    left = np.column_stack((np.zeros(61), np.arange(61) * 0.05, np.full(61, math.pi / 2)))
    for wall, hit in ((0.25, True), (0.40, False)):
        rpp = RegulatedPurePursuit(circumscribed_radius=math.hypot(0.3, 0.17))
        collision, checked = _wall_beside(wall)
        if hit:
            with pytest.raises(NoValidControl):
                rpp.compute(left, speed=(0.0, 1.8), collision=collision)
        else:
            assert rpp.compute(left, speed=(0.0, 1.8), collision=collision) == (0.0, 1.8)
        # the pose now first, then steps of 2 sin(0.025 / 0.345) / 1.8 = 0.0805 rad / 1.8
        step = 2.0 * math.sin(0.025 / math.hypot(0.3, 0.17))
        assert checked[0] == (0.0, 0.0, 0.0) and checked[1][2] == pytest.approx(step)
        assert all(x == y == 0.0 for x, y, _ in checked) and checked[-1][2] < 1.8 * 1.0


def test_rpp_refuses_to_move_a_footprint_already_in_collision():
    collision, checked = _wall_beside(0.15)  # the side at y 0.17 is past the wall
    with pytest.raises(NoValidControl):
        RegulatedPurePursuit().compute(_line(), collision=collision)
    assert checked == [(0.0, 0.0, 0.0)]  # the pose now, before any step


def test_goal_and_progress_checkers():
    goal = SimpleGoalChecker()
    assert not goal.is_goal_reached((0.3, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert not goal.is_goal_reached((0.2, 0.0, 1.0), (0.0, 0.0, 0.0))  # xy now latched
    assert goal.is_goal_reached((0.3, 0.0, 0.2), (0.0, 0.0, 0.0))
    progress = SimpleProgressChecker()
    assert progress.check((0.0, 0.0), 0.0) and progress.check((0.4, 0.0), 9.0)
    assert progress.check((0.6, 0.0), 10.5)  # moved 0.6 m: a new baseline at 10.5 s
    assert progress.check((0.7, 0.0), 20.5) and not progress.check((0.7, 0.0), 20.6)


def test_stopped_goal_checker_waits_for_the_robot_to_stop():
    goal = (1.0, 2.0, 0.5)
    at_goal = (1.1, 2.0, 0.6)  # 0.1 m and 0.1 rad away, within the default 0.25 and 0.25
    assert SimpleGoalChecker().is_goal_reached(at_goal, goal, (0.0, 1.0))  # speed not checked
    checker = StoppedGoalChecker()  # 0.25 m, 0.25 rad, stopped below 0.25 rad/s and 0.25 m/s
    assert not checker.is_goal_reached(at_goal, goal, (0.0, 0.26))  # still turning
    assert not checker.is_goal_reached(at_goal, goal, (-0.26, 0.0))  # still backing up
    assert checker.is_goal_reached((1.3, 2.0, 0.6), goal, (0.0, 0.25))  # xy latched, stopped
    checker = StoppedGoalChecker(0.25, 0.25, True, rot_stopped_velocity=0.1,
                                 trans_stopped_velocity=0.05)
    assert not checker.is_goal_reached(at_goal, goal, (0.06, 0.0))
    assert checker.is_goal_reached(at_goal, goal, (0.05, -0.1))


def test_pose_progress_checker_counts_a_turn_in_place():
    simple, pose = SimpleProgressChecker(), PoseProgressChecker()  # 0.5 m, 10 s, 0.5 rad
    for checker in (simple, pose):
        assert checker.check((1.0, 2.0, 3.0), 0.0)
    # turning in place 0.6 rad (across +-pi: 3.0 -> -2.683) by 9 s, then standing until 19.5 s
    assert simple.check((1.0, 2.0, 3.6 - 2 * math.pi), 9.0)
    assert pose.check((1.0, 2.0, 3.6 - 2 * math.pi), 9.0)  # turned 0.6 > 0.5: a new baseline
    assert not simple.check((1.0, 2.0, 3.6 - 2 * math.pi), 10.5)  # 10.5 s without 0.5 m
    assert pose.check((1.0, 2.0, 3.6 - 2 * math.pi), 19.0)  # 10.0 s since the turn
    assert not pose.check((1.0, 2.0, 3.5 - 2 * math.pi), 19.1)  # 0.1 rad back is not enough
    assert pose.check((1.6, 2.0, 3.5 - 2 * math.pi), 19.2)  # 0.6 m counts as before


def test_controller_server_reads_the_checker_plugins_parameters():
    from types import SimpleNamespace

    from amr_description.nodes.controller_server import ControllerServer
    declared = {}

    def declare_parameter(name, default):
        declared[name] = overrides.get(name, default)
        return SimpleNamespace(value=declared[name])

    node = SimpleNamespace(declare_parameter=declare_parameter)
    overrides = {'pc.plugin': 'nav2_controller::PoseProgressChecker',
                 'pc.required_movement_angle': 0.3, 'pc.movement_time_allowance': 5.0}
    assert ControllerServer._progress_params(node, 'pc') == {
        'plugin': 'nav2_controller::PoseProgressChecker', 'radius': 0.5, 'time': 5.0,
        'angle': 0.3}
    overrides = {}
    declared.clear()
    assert ControllerServer._progress_params(node, 'pc') == {
        'plugin': 'nav2_controller::SimpleProgressChecker', 'radius': 0.5, 'time': 10.0}
    assert 'pc.required_movement_angle' not in declared  # upstream declares it for Pose only
    overrides = {'gc.plugin': 'nav2_controller::StoppedGoalChecker',
                 'gc.rot_stopped_velocity': 0.1, 'gc.xy_goal_tolerance': 0.15}
    assert ControllerServer._goal_params(node, 'gc') == {
        'plugin': 'nav2_controller::StoppedGoalChecker', 'xy': 0.15, 'yaw': 0.25,
        'stateful': True, 'rot_stopped': 0.1, 'trans_stopped': 0.25}
    overrides = {}
    declared.clear()
    assert ControllerServer._goal_params(node, 'gc') == {
        'plugin': 'nav2_controller::SimpleGoalChecker', 'xy': 0.25, 'yaw': 0.25,
        'stateful': True}
    assert 'gc.rot_stopped_velocity' not in declared
    # RPP's max_robot_pose_search_dist: half the local costmap's getSizeInMetersX(),
    # (60 cells - 0.5) x 0.05 m / 2 for a 3 m wide rolling window
    overrides = {'FollowPath.plugin': 'nav2_regulated_pure_pursuit_controller::'
                                      'RegulatedPurePursuitController'}
    node.costmap = SimpleNamespace(p={'width': 3, 'resolution': 0.05})
    params = ControllerServer._controller_params(node, 'FollowPath')['params']
    assert params['max_robot_pose_search_dist'] == pytest.approx(1.4875)


def test_search_stops_near_the_robot_and_paths_match_the_whole_potential():
    # NavFn's propagation stops at the robot: the cut-short potential must give the same path
    # as the potential of the whole map, and leave the cells beyond the robot unsearched
    from amr_description.nav import planner as planner_module
    from skimage.graph import MCP_Geometric
    room = _room(4.0, 3.0)  # 80 x 60 cells
    room.costs[10:50, 40] = cm.LETHAL_OBSTACLE  # a wall with a way round at both ends
    start, goal = (1.5, 1.5), (3.5, 1.4, 0.0)
    path = make_plan(room, start, goal, tolerance=0.0)
    travel = planner_module.travel_costs(room.costs)
    s, g = room.world_to_map(*start), room.world_to_map(*goal[:2])
    s_rc, g_rc = (s[1], s[0]), (g[1], g[0])
    whole, _ = MCP_Geometric(travel, fully_connected=True).find_costs([g_rc])
    cells = planner_module.descend(whole, s_rc, g_rc)
    x, y = room.map_to_world(cells[:, 1], cells[:, 0])
    assert np.allclose(path[:, :2], np.column_stack((x, y)))
    near = planner_module._passable_around(travel, s_rc, planner_module.DESCENT_WINDOW)
    assert len(near) == (2 * planner_module.DESCENT_WINDOW + 1) ** 2
    search = MCP_Geometric(travel, fully_connected=True)
    cut, _ = search.find_costs([g_rc], near, find_all_ends=True)
    assert np.isfinite(cut[s_rc]) and cut[s_rc] == whole[s_rc]
    assert np.isinf(cut[:, :10]).all()  # the map's west end, beyond the robot: unsearched
    assert np.isfinite(whole[:, :10]).all()


def test_clear_square_writes_the_cells_strictly_inside_its_corner_cells():
    # Costmap2D::clearArea between the cells of (x - d/2, y - d/2) and (x + d/2, y + d/2):
    # on a 0.1 m grid, d = 1.0 around (2.05, 2.05) puts the corners in cells 15 and 25, so
    # cells 16..24 on each axis, 9 x 9 of them, are cleared; invert clears the other 400 - 81
    c = cm.Costmap(np.full((20, 40), cm.LETHAL_OBSTACLE), 0.1)
    c.clear_square(2.05, 1.05, 1.0, cm.NO_INFORMATION)
    cleared = np.argwhere(c.costs == cm.NO_INFORMATION)
    assert len(cleared) == 81
    assert cleared[:, 0].min() == 6 and cleared[:, 0].max() == 14  # rows: cells 5 and 15
    assert cleared[:, 1].min() == 16 and cleared[:, 1].max() == 24
    d = cm.Costmap(np.full((20, 40), cm.LETHAL_OBSTACLE), 0.1)
    d.clear_square(2.05, 1.05, 1.0, cm.FREE_SPACE, invert=True)
    assert np.count_nonzero(d.costs == cm.FREE_SPACE) == 800 - 81
    # a square past the map's edge is clamped to its last cell: nothing beyond is written
    e = cm.Costmap(np.full((20, 40), cm.LETHAL_OBSTACLE), 0.1)
    e.clear_square(0.0, 0.0, 100.0, cm.FREE_SPACE)
    assert np.count_nonzero(e.costs == cm.FREE_SPACE) == 38 * 18  # cells 1..38 x 1..18


def test_invalid_poses_start_at_the_pose_nearest_the_robot():
    # isPathValid: a lethal cell at x = 1.05 and one at x = 3.05 on a straight path along
    # y = 0.05; the robot stands at x = 2.0, so the pose on the first (passed) is not checked
    costs = np.zeros((10, 50), np.uint8)
    costs[0, 10] = cm.LETHAL_OBSTACLE
    costs[0, 30] = cm.INSCRIBED_INFLATED_OBSTACLE
    c = cm.Costmap(costs, 0.1)
    path = [(0.05 + 0.1 * i, 0.05, 0.0) for i in range(45)]
    assert invalid_poses(c, path, (2.0, 0.0)) == [30]
    assert invalid_poses(c, path, (0.0, 0.0)) == [10, 30]
    assert invalid_poses(c, path + [(9.0, 0.05, 0.0)], (0.0, 0.0)) == [10, 30, 45]  # off map
    assert invalid_poses(c, path, None) == []  # no robot pose: nothing checked, as upstream
    # with a 0.3 m square footprint only its outline counts (footprintCostAtPose): the
    # sides x +- 0.15 cross the lethal cell (1.0 <= x < 1.1) at poses 8 (x = 0.85) and 11
    # (x = 1.15); at 9 and 10 the cell lies inside the outline; pose 0's outline leaves the
    # map (x < 0), which counts as lethal
    square = np.array([[0.15, 0.15], [0.15, -0.15], [-0.15, -0.15], [-0.15, 0.15]])
    c2 = cm.Costmap(np.pad(costs, ((5, 0), (0, 0))), 0.1, (0.0, -0.5))
    bad = invalid_poses(c2, path[:20], (0.0, 0.0), square)
    assert bad == [0, 8, 11]
