# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The navigation displays' geometry and texts, the world's true map and the navigation stack."""

import math
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
    from amr_description.launch.nav_stacks import described_nodes
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    actions = registry.describe('navigation.launch.py', ['world:=arena', 'x:=0.5', 'yaw:=1.0',
                                                         'viewer:=false'])
    # nav2_bringup's default: localization and the servers composed in nav2_container
    containers = [a for a in actions
                  if getattr(a, 'executable', None) == 'component_container_isolated']
    assert [c.node_name for c in containers] == ['nav2_container']
    assert [(n.plugin, n.node_name) for n in containers[0].composable_node_descriptions] == [
        ('nav2_map_server::MapServer', 'map_server'), ('nav2_amcl::AmclNode', 'amcl'),
        ('nav2_lifecycle_manager::LifecycleManager', 'lifecycle_manager_localization'),
        ('nav2_controller::ControllerServer', 'controller_server'),
        ('nav2_planner::PlannerServer', 'planner_server'),
        ('behavior_server::BehaviorServer', 'behavior_server'),
        ('nav2_velocity_smoother::VelocitySmoother', 'velocity_smoother'),
        ('nav2_bt_navigator::BtNavigator', 'bt_navigator'),
        ('nav2_waypoint_follower::WaypointFollower', 'waypoint_follower'),
        ('nav2_lifecycle_manager::LifecycleManager', 'lifecycle_manager_navigation')]
    nodes = {getattr(n, 'node_name', None): n for n in described_nodes(actions)}
    assert 'mujoco_sim' in [getattr(a, 'executable', None) for a in actions]
    yaml_path = nodes['map_server'].parameters[-1]['yaml_filename']
    assert yaml_path == os.path.join(str(tmp_path), 'amr_description', 'maps', 'arena.yaml')
    assert os.path.isfile(yaml_path)
    assert nodes['amcl'].parameters[-1] == {'set_initial_pose': True, 'initial_pose.x': 0.5,
                                            'initial_pose.y': 0.0, 'initial_pose.yaw': 1.0}
    assert ('cmd_vel_smoothed', 'diff_drive_controller/cmd_vel') in \
        nodes['velocity_smoother'].remappings
    given = registry.describe('navigation', ['world:=arena', f'map:={yaml_path}',
                                             'viewer:=false', 'use_composition:=False'])
    processes = {getattr(a, 'executable', None): a for a in given}
    for exe in ('map_server', 'amcl', 'controller_server', 'bt_navigator', 'waypoint_follower',
                'lifecycle_manager'):
        assert exe in processes, sorted(processes)
    assert 'component_container_isolated' not in processes
    assert processes['amcl'].parameters[-1]['set_initial_pose'] is True


def test_panel_cancel_waits_for_a_navigator_not_yet_matched():
    # a request sent before the cancel service matched is lost: the panel once logged
    # "cancel requested" while asking nothing of a navigator started just before the click
    from amr_description.web.displays import nav_panel

    class Client:

        def __init__(self, ready_after_wait):
            self.ready_after_wait, self.sent = ready_after_wait, []
            self.service_name = '/navigate_to_pose/_action/cancel_goal'

        def wait_for_service(self, timeout):
            assert timeout == nav_panel.CANCEL_WAIT
            return self.ready_after_wait

        def call_async(self, request):
            self.sent.append(request)

    class Log:

        def __init__(self):
            self.lines = []

        def info(self, text):
            self.lines.append(('info', text))

        def warning(self, text):
            self.lines.append(('warning', text))

    log = Log()
    panel = object.__new__(nav_panel.NavigationPanelDisplay)
    panel.node = type('Node', (), {'get_logger': lambda self: log})()
    panel._cancel = [Client(True), Client(False)]
    panel._send_cancel()
    assert [len(c.sent) for c in panel._cancel] == [1, 0]
    assert log.lines == [('info', 'Navigation 2 panel: cancel requested')]
    panel._cancel = [Client(False), Client(False)]
    panel._send_cancel()
    assert log.lines[-1][0] == 'warning' and 'cancel not sent' in log.lines[-1][1]


def test_pose_tool_publishes_a_drag_whose_end_comes_before_its_start():
    # viser runs a plain drag callback in a thread pool, where the drag's "end" may run first;
    # the tool once waited for a "start" that came late and published nothing (CI, 2026-11-29)
    import asyncio
    from types import SimpleNamespace

    from amr_description.web.displays import pose_tool

    class Handle:

        def __init__(self, drawn, name):
            self.drawn, self.name = drawn, name
            drawn.append(name)

        def on_drag(self, callback):
            assert asyncio.iscoroutinefunction(callback)  # awaited in order by viser
            self.drag = callback

        def on_click(self, callback):
            self.click = callback

        def remove(self):
            self.drawn.remove(self.name)

    drawn, published = [], []
    scene = SimpleNamespace(
        add_mesh_simple=lambda name, *a, **k: Handle(drawn, name),
        add_arrows=lambda name, *a, **k: Handle(drawn, name))
    clock = SimpleNamespace(now=lambda: SimpleNamespace(to_msg=lambda: None))
    node = SimpleNamespace(
        create_publisher=lambda kind, topic, depth: SimpleNamespace(
            topic_name=topic, publish=published.append),
        get_clock=lambda: clock, get_logger=lambda: SimpleNamespace(info=lambda text: None))
    tool = pose_tool.PoseToolDisplay(node, SimpleNamespace(scene=scene), None, '/initialpose',
                                     '/goal_pose')
    tool.draw(SimpleNamespace(fixed='map'))
    tool._activate('initial')
    plane = tool._plane
    camera = SimpleNamespace(position=(1.0, 2.0, 10.0))

    def event(phase, end):  # pressed at (1, 2), the pointer now over the ground at ``end``
        return SimpleNamespace(phase=phase, start_position=(1.0, 2.0, 0.005),
                               end_position=end, client=SimpleNamespace(camera=camera))

    asyncio.run(plane.drag(event('end', (1.0, 3.0, 0.0))))  # straight up the map: +y
    assert len(published) == 1 and drawn == []  # the plane and any arrow removed
    msg = published[0]
    assert msg.header.frame_id == 'map'
    assert (msg.pose.pose.position.x, msg.pose.pose.position.y) == (1.0, 2.0)
    assert 2 * math.atan2(msg.pose.pose.orientation.z, msg.pose.pose.orientation.w) == \
        pytest.approx(math.pi / 2)
    asyncio.run(plane.drag(event('start', (1.0, 2.5, 0.0))))  # late: draws and sends nothing
    asyncio.run(plane.drag(event('update', (1.0, 2.5, 0.0))))
    assert len(published) == 1 and drawn == []
