# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The navigation displays' geometry and texts, the world's true map and the navigation stack."""

import os

from action_msgs.msg import GoalStatus
from amr_description.web.displays.nav_panel import feedback_lines
from amr_description.web.displays.path import DEFAULT_COLOUR
from amr_description.web.displays.path import GLOBAL_PLAN_COLOUR
from amr_description.web.displays.path import LOCAL_PLAN_COLOUR
from amr_description.web.displays.path import path_colour
from amr_description.web.displays.path import polyline_segments
from builtin_interfaces.msg import Duration
from nav2_msgs.action import NavigateToPose
import numpy as np
import pytest


def test_polyline_joins_points_in_order_and_a_polygon_closes():
    pts = [(0, 0, 0), (1, 0, 0), (1, 2, 0)]
    assert polyline_segments(pts).tolist() == [[[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [1, 2, 0]]]
    closed = polyline_segments(pts, closed=True)
    assert closed.shape == (3, 2, 3) and closed[-1].tolist() == [[1, 2, 0], [0, 0, 0]]
    assert polyline_segments([(1, 1, 1)]).shape == (0, 2, 3)
    assert polyline_segments([(1, 1, 1)], closed=True).shape == (0, 2, 3)
    with pytest.raises(ValueError):
        polyline_segments([(0, 0, 0), (float('nan'), 0, 0)])


def test_path_colours_are_nav2_rviz_configs():
    assert path_colour('/plan') == GLOBAL_PLAN_COLOUR == (255, 0, 0)
    assert path_colour('/r1/local_plan') == LOCAL_PLAN_COLOUR == (0, 12, 255)
    assert path_colour('/my_path') == DEFAULT_COLOUR == (25, 255, 0)


def test_panel_feedback_lines():
    assert feedback_lines(None, None) == ['Feedback: **inactive**']
    fb = NavigateToPose.Feedback(distance_remaining=2.345, number_of_recoveries=3,
                                 estimated_time_remaining=Duration(sec=12, nanosec=600000000),
                                 navigation_time=Duration(sec=4))
    assert feedback_lines(GoalStatus.STATUS_EXECUTING, fb) == [
        'Feedback: **active**', 'ETA: 13 s', 'Distance remaining: 2.35 m', 'Time taken: 4 s',
        'Recoveries: 3']
    assert feedback_lines(GoalStatus.STATUS_SUCCEEDED, None) == ['Feedback: **reached**']
    assert feedback_lines(GoalStatus.STATUS_CANCELED, None) == ['Feedback: **canceled**']


def test_arena_true_map_has_its_walls_pillars_and_margin():
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.nav.world_map import world_map
    grid = world_map(load_world('arena'), resolution=0.05, margin=0.5)
    # walls from x -1.3 to 3.3 and y -2.3 to 2.8, plus 0.5 m
    assert grid.origin == pytest.approx((-1.8, -2.8, 0.0))
    assert (grid.width, grid.height) == (112, 122)

    def cell(x, y):
        return grid.data[int((y - grid.origin[1]) / 0.05), int((x - grid.origin[0]) / 0.05)]

    assert cell(1.0, 0.0) == 100  # the centre pillar (r 0.15) is filled
    assert cell(1.0, 0.12) == 100
    assert cell(1.0, 0.25) == 0 and cell(0.0, 0.0) == 0
    assert cell(-1.25, 0.0) == 100 and cell(-1.6, 0.0) == 0  # a wall, then the margin
    assert set(np.unique(grid.data)) == {0, 100}
    with pytest.raises(ValueError):
        world_map(load_world('arena'), resolution=0.0)


def test_navigation_stack_runs_sim_bringup_and_starts_amcl_at_the_spawn(tmp_path, monkeypatch):
    from amr_description.launch import registry
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    actions = registry.describe('navigation.launch.py', ['world:=arena', 'x:=0.5', 'yaw:=1.0',
                                                         'viewer:=false'])
    names = [getattr(a, 'executable', None) for a in actions]
    for exe in ('mujoco_sim', 'map_server', 'amcl', 'controller_server', 'bt_navigator',
                'waypoint_follower'):
        assert exe in names, names
    map_server = actions[names.index('map_server')]
    yaml_path = map_server.parameters[-1]['yaml_filename']
    assert yaml_path == os.path.join(str(tmp_path), 'amr_description', 'maps', 'arena.yaml')
    assert os.path.isfile(yaml_path)
    amcl = actions[names.index('amcl')]
    assert amcl.parameters[-1] == {'set_initial_pose': True, 'initial_pose.x': 0.5,
                                   'initial_pose.y': 0.0, 'initial_pose.yaw': 1.0}
    given = registry.describe('navigation', ['world:=arena', f'map:={yaml_path}',
                                             'viewer:=false'])
    assert any(getattr(a, 'executable', None) == 'map_server' for a in given)
