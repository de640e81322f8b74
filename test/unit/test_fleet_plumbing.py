# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The fleet stack's description, the main job's robot table and the benchmark's plumbing."""

import math
import os
import re

from amr_description.core.course import square_course
from amr_description.launch import registry
from amr_description.launch import stacks
from amr_description.launch.actions import ComposableNodeContainer
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import OnProcessExit
from amr_description.nodes import create
from amr_description.nodes.drive_square import driver
from amr_description.nodes.drive_square import report as drive_report
from amr_description.tools.benchmark import common
from amr_description.tools.benchmark import report
import pytest


def test_fleet_grid_fills_rows_of_ceil_sqrt():
    assert stacks.fleet_grid(1, 2.0) == [(0.0, 0.0)]
    assert stacks.fleet_grid(4, 2.0) == [(0.0, 0.0), (2.0, 0.0), (0.0, 2.0), (2.0, 2.0)]
    grid = stacks.fleet_grid(5, 1.5)
    assert len(grid) == 5 and grid[3] == (0.0, 1.5) and grid[4] == (1.5, 1.5)
    assert len(set(stacks.fleet_grid(32, 2.0))) == 32


def _actions(argv):
    return registry.describe('fleet', argv)


def test_fleet_stack_namespaces_every_robot():
    actions = _actions(['robots:=3', 'spacing:=3.0', 'rtf:=0'])
    nodes = [a for a in actions if isinstance(a, Node)]
    sim = [n for n in nodes if n.executable == 'mujoco_sim']
    assert len(sim) == 1
    cmd = sim[0].build_cmd()
    for ns in ('r1', 'r2', 'r3'):
        assert f'/{ns}/diff_drive_controller/odom:=/{ns}/odom' in cmd
    # the robot_state_publishers are composed in one container process
    assert not [n for n in nodes if n.executable == 'robot_state_publisher']
    containers = [n for n in nodes if isinstance(n, ComposableNodeContainer)]
    assert len(containers) == 1
    composed = containers[0].composable_node_descriptions
    rsp = [n for n in composed if n.plugin == 'amr_description::RobotStatePublisher']
    assert [n.namespace for n in rsp] == ['/r1', '/r2', '/r3']
    # each robot's odom frame joined to the simulator's world at its grid position
    static = [n for n in composed if n.plugin == 'amr_description::StaticTransformBroadcasterNode']
    assert len(rsp) + len(static) == len(composed)
    assert [(n.namespace, n.node_name) for n in static] == [
        (f'/r{i}', 'static_transform_publisher') for i in (1, 2, 3)]
    assert [(p['frame_id'], p['child_frame_id'], p['translation.x'], p['translation.y'])
            for p in (n.parameters[0] for n in static)] == [
        ('world', 'r1/odom', 0.0, 0.0), ('world', 'r2/odom', 3.0, 0.0),
        ('world', 'r3/odom', 0.0, 3.0)]
    assert [n.parameters[0]['frame_prefix'] for n in rsp] == ['r1/', 'r2/', 'r3/']
    creates = [n for n in nodes if n.executable == 'create']
    assert creates[1].arguments == ['-topic', '/r2/robot_description', '-name', 'r2',
                                    '-robot_namespace', 'r2', '-x', '3.0', '-y', '0.0',
                                    '-z', '0.2']
    handlers = [a for a in actions if isinstance(a, OnProcessExit)]
    assert len(handlers) == 3
    spawner = handlers[2].on_exit[0]
    assert spawner.arguments == ['-c', '/r3/controller_manager', 'joint_state_broadcaster',
                                 'diff_drive_controller']


def test_fleet_stack_without_composition():
    nodes = [a for a in _actions(['robots:=2', 'use_composition:=false', 'spacing:=1.5'])
             if isinstance(a, Node)]
    assert not [n for n in nodes if isinstance(n, ComposableNodeContainer)]
    rsp = [n for n in nodes if n.executable == 'robot_state_publisher']
    assert [n.namespace for n in rsp] == ['/r1', '/r2']
    static = [n for n in nodes if n.executable == 'static_transform_publisher']
    assert [n.namespace for n in static] == ['/r1', '/r2']
    assert static[1].arguments == ['--x', '1.5', '--y', '0.0', '--frame-id', 'world',
                                   '--child-frame-id', 'r2/odom']


def test_fleet_viewer_shows_every_robot_in_world():
    nodes = [a for a in _actions(['robots:=3', 'viewer_port:=8099']) if isinstance(a, Node)]
    viewer = [n for n in nodes if n.executable == 'viewer']
    assert len(viewer) == 1
    params = viewer[0].parameters[0]
    assert params['fixed_frame'] == 'world' and params['port'] == 8099
    assert params['robot_description_topics'] == [f'/r{i}/robot_description' for i in (1, 2, 3)]
    assert params['odometry_topics'] == [f'/r{i}/ground_truth/odom' for i in (1, 2, 3)]
    assert params['cmd_vel_topic'] == '/r1/diff_drive_controller/cmd_vel'
    assert viewer[0].remappings == [('/joint_states', '/r1/joint_states')]
    no_viewer = [a for a in _actions(['robots:=3', 'viewer:=false']) if isinstance(a, Node)]
    assert not [n for n in no_viewer if n.executable == 'viewer']


def test_container_command_line(tmp_path):
    import yaml
    container = [a for a in _actions(['robots:=2']) if isinstance(a, ComposableNodeContainer)][0]
    cmd = container.build_cmd(str(tmp_path))
    assert cmd[1] == '--nodes' and cmd[2] in container.temp_files()
    assert cmd[3:6] == ['--ros-args', '-r', '__node:=robot_state_publisher_container']
    with open(cmd[2]) as f:
        entries = yaml.safe_load(f)
    assert [e['plugin'] for e in entries] == ['amr_description::RobotStatePublisher'] * 2 + \
        ['amr_description::StaticTransformBroadcasterNode'] * 2
    args = entries[1]['ros_args']
    assert args[:3] == ['--ros-args', '-r', '__ns:=/r2'] and args[3] == '--params-file'
    with open(args[4]) as f:
        params = yaml.safe_load(f)['/**']['ros__parameters']
    assert params['frame_prefix'] == 'r2/' and '<robot' in params['robot_description']
    # every file written is handed back for removal
    assert set(container.temp_files()) == {str(p) for p in tmp_path.iterdir()}


@pytest.mark.parametrize('argv,field', [(['robots:=0'], 'robots'), (['robots:=two'], 'robots'),
                                        (['spacing:=0'], 'spacing'), (['rtf:=-1'], 'rtf'),
                                        (['use_composition:=maybe'], 'use_composition'),
                                        (['viewer:=maybe'], 'viewer'),
                                        (['viewer_port:=0'], 'viewer_port')])
def test_fleet_stack_rejects_bad_arguments(argv, field):
    with pytest.raises(LaunchError, match=f"'{field}'"):
        _actions(argv)


def test_sim_stack_keeps_the_robot_without_namespace():
    nodes = [a for a in registry.describe('sim', []) if isinstance(a, Node)]
    assert all(n.namespace in (None, '', '/') for n in nodes)
    create_node = [n for n in nodes if n.executable == 'create'][0]
    assert '-robot_namespace' not in create_node.arguments


def test_create_accepts_robot_namespace():
    opts = create.build_parser().parse_args(['-topic', '/r1/robot_description',
                                             '-robot_namespace', 'r1', '-x', '2'])
    assert opts.robot_namespace == 'r1' and opts.x == 2.0
    assert create.build_parser().parse_args(['-file', 'a.urdf']).robot_namespace == ''


def test_robot_namespaces():
    assert driver.robot_namespaces(1) == ['']
    assert driver.robot_namespaces(3) == ['r1', 'r2', 'r3']
    with pytest.raises(ValueError):
        driver.robot_namespaces(0)


def _square_marks(origin, side=1.0, error=0.0):
    """Poses at the start and after each leg of a square, from ``origin``."""
    x, y, yaw = origin
    marks = [(x, y, yaw)]
    for _ in range(4):
        x, y = x + side * math.cos(yaw), y + side * math.sin(yaw)
        marks.append((x, y, yaw))
        yaw += math.pi / 2
        marks.append((x, y, yaw))
    last = marks[-1]
    marks[-1] = (last[0] + error, last[1], last[2])
    return marks


def test_robot_table_one_row_per_robot_and_leg_summary():
    legs = square_course(1.0)
    robots = [('r1', _square_marks((0, 0, 0)), _square_marks((0, 0, 0), error=0.01), 0),
              ('r2', _square_marks((2, 0, 0)), _square_marks((2, 0, 0), error=0.03), 2)]
    text = drive_report.format_robot_table(legs, robots)
    rows = [line.split() for line in text.splitlines() if re.match(r'r\d', line)]
    assert [r[0] for r in rows] == ['r1', 'r2']
    assert float(rows[0][1]) == pytest.approx(0.0, abs=1e-9)
    assert float(rows[0][5]) == pytest.approx(0.01, abs=1e-3)
    assert float(rows[1][5]) == pytest.approx(0.03, abs=1e-3) and rows[1][-1] == '2'
    legs_rows = [line.split() for line in text.splitlines()
                 if line.strip()[:1].isdigit()]
    assert len(legs_rows) == 8
    assert legs_rows[0][1] == 'straight' and float(legs_rows[0][4]) == pytest.approx(1.0)
    assert legs_rows[1][1] == 'turn' and float(legs_rows[1][4]) == pytest.approx(90.0)


def test_fleet_plot_draws_every_robot(tmp_path):
    robots = []
    for i, (x, y) in enumerate(stacks.fleet_grid(2, 2.0)):
        marks = _square_marks((x, y, 0.0))
        robots.append({'name': f'r{i + 1}', 'odom_path': [(m[0] - x, m[1] - y) for m in marks],
                       'truth_path': [m[:2] for m in marks], 'odom_origin': (0.0, 0.0, 0.0),
                       'truth_origin': (x, y, 0.0)})
    path = tmp_path / 'path.png'
    drive_report.write_fleet_plot(str(path), robots, 1.0)
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_benchmark_wheel_speeds_closed_form(tmp_path):
    config = tmp_path / 'controllers.yaml'
    config.write_text('diff_drive_controller:\n  ros__parameters:\n    wheel_separation: 0.3\n'
                      '    wheel_separation_multiplier: 4.2\n    wheel_radius: 0.1\n')
    left, right = common.wheel_speeds((0.3, 0.5), str(config))
    assert left == pytest.approx((0.3 - 0.5 * 1.26 / 2) / 0.1)
    assert right == pytest.approx((0.3 + 0.5 * 1.26 / 2) / 0.1)


def test_benchmark_report_keeps_text_outside_the_markers(tmp_path):
    doc = tmp_path / 'benchmark.md'
    doc.write_text('# notes\nkept\n')
    report.write_report(str(doc), 'first')
    assert doc.read_text().count('first') == 1 and 'kept' in doc.read_text()
    report.write_report(str(doc), 'second')
    text = doc.read_text()
    assert 'first' not in text and text.count('second') == 1 and 'kept' in text


def test_world_cost_rows_and_targets_in_the_report():
    from amr_description.tools.benchmark import world_cost
    text, ok = world_cost.format_rows([('empty', 0.003, 40000.0, 1.0),
                                       ('warehouse', 0.03, 35000.0, 0.875)])
    assert not ok and text.splitlines()[3] == '| warehouse | 0.0300 | 35,000 | 0.875 |'
    assert text.endswith('step rate >= 90% of empty: FAIL')
    assert world_cost.format_rows([('empty', 0.003, 40000.0, 1.0),
                                   ('arena', 0.01, 37000.0, 0.925)])[1]
    row = {'robots': 1, 'startup': 1.0, 'rtf': 1.0, 'cpu_sim': 0.1, 'cpu_stack': 0.2,
           'fast': 50.0, 'cost_rel': None, 'raw': 60.0, 'load': (1.0, 1.0)}
    page = report.report([row], 10.0, ['--robots', '1'], text)
    assert '## World cost' in page and '| warehouse | 0.0300 | 35,000 | 0.875 |' in page


def test_benchmark_failure_is_not_a_figure(tmp_path, monkeypatch, capsys):
    doc = tmp_path / 'benchmark.md'
    doc.write_text('untouched\n')

    def failing_run(*args, **kwargs):
        raise common.BenchmarkError('start-up, 2 robots, rtf 0',
                                    'create-3 exited with code 1',
                                    '[create-3] Failed request to create entity: boom')
    monkeypatch.setattr(report, 'run', failing_run)
    assert report.main(['--robots', '2', '--output', str(doc)]) == 1
    err = capsys.readouterr().err
    assert 'FAILED at start-up, 2 robots, rtf 0: create-3 exited with code 1' in err
    assert 'boom' in err
    assert doc.read_text() == 'untouched\n'


def test_benchmark_robot_list_argument():
    assert report._robot_list('1,2,4') == [1, 2, 4]
    for bad in ('', '0', 'a,b'):
        with pytest.raises(Exception):
            report._robot_list(bad)


def test_benchmark_targets_only_for_counts_run():
    rows = [{'robots': 1, 'rtf': 1.0, 'fast': 60.0, 'raw': 100.0, 'startup': 1.5,
             'cost_rel': 1.0},
            {'robots': 16, 'rtf': 0.8, 'fast': 3.0, 'raw': 6.0, 'startup': 12.0,
             'cost_rel': 1.25}]
    result = {d: ok for d, _, ok in report.targets(rows)}
    assert result['1 robot, fast: >= 60 % of raw mj_step'] is True
    assert result['16 robots, real time: rtf >= 1.0 (paced to 1.0, 1 % tolerance)'] is False
    assert result['16 robots, fast: cost per robot-second <= 1.3x linear'] is True
    assert result['16 robots: all controllers active < 10 s'] is False
    assert report.targets(rows[:1])[0][0].startswith('1 robot')


def test_robot_params_namespace_the_file_and_prefix_the_robot_frames():
    from amr_description.launch.nav_stacks import robot_params
    params = {
        'amcl': {'ros__parameters': {'base_frame_id': 'base_footprint', 'global_frame_id': 'map',
                                     'odom_frame_id': 'odom', 'scan_topic': 'scan',
                                     'alpha1': 0.2}},
        'bt_navigator': {'ros__parameters': {'odom_topic': '/odom',
                                             'robot_base_frame': 'base_link'}},
        'local_costmap': {'local_costmap': {'ros__parameters': {
            'global_frame': 'odom', 'robot_base_frame': 'r1/base_link',
            'voxel_layer': {'scan': {'topic': '/scan', 'sensor_frame': ''}}}}},
        'global_costmap': {'global_costmap': {'ros__parameters': {
            'global_frame': '/map', 'static_layer': {'map_topic': '/r1/map'}}}},
    }
    out = robot_params(params, 'r1', 'r1/')
    assert list(out) == ['r1']
    amcl = out['r1']['amcl']['ros__parameters']
    # robot frames prefixed, the shared map frame and relative topics kept
    assert amcl == {'base_frame_id': 'r1/base_footprint', 'global_frame_id': 'map',
                    'odom_frame_id': 'r1/odom', 'scan_topic': 'scan', 'alpha1': 0.2}
    assert out['r1']['bt_navigator']['ros__parameters'] == {
        'odom_topic': '/r1/odom', 'robot_base_frame': 'r1/base_link'}
    local = out['r1']['local_costmap']['local_costmap']['ros__parameters']
    assert local['global_frame'] == 'r1/odom'
    assert local['robot_base_frame'] == 'r1/base_link'  # already prefixed: once
    assert local['voxel_layer']['scan'] == {'topic': '/r1/scan', 'sensor_frame': ''}
    glob = out['r1']['global_costmap']['global_costmap']['ros__parameters']
    assert glob['global_frame'] == '/map' and glob['static_layer']['map_topic'] == '/r1/map'
    assert params['amcl']['ros__parameters']['base_frame_id'] == 'base_footprint'  # a copy


def test_fleet_navigation_gives_every_robot_its_nav2(monkeypatch, tmp_path):
    import yaml
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    actions = _actions(['robots:=2', 'world:=arena', 'navigation:=true', 'viewer:=false'])
    containers = [a for a in actions if isinstance(a, ComposableNodeContainer)]
    nav = [c for c in containers if c.node_name == 'nav2_container']
    assert [c.namespace for c in nav] == ['/r1', '/r2']
    names = [n.node_name for n in nav[1].composable_node_descriptions]
    assert names == ['map_server', 'amcl', 'lifecycle_manager_localization',
                     'controller_server', 'planner_server', 'behavior_server',
                     'velocity_smoother', 'bt_navigator', 'waypoint_follower',
                     'lifecycle_manager_navigation']
    assert {n.namespace for n in nav[1].composable_node_descriptions} == {'/r2'}
    amcl = nav[1].composable_node_descriptions[1]
    params_file, initial = amcl.parameters[0], amcl.parameters[-1]
    assert initial == {'set_initial_pose': True, 'initial_pose.x': 2.0, 'initial_pose.y': 0.0,
                       'initial_pose.yaw': 0.0}  # r2's spawn on the grid
    assert params_file.startswith(str(tmp_path / 'amr_description' / 'params'))
    with open(params_file) as f:
        rewritten = yaml.safe_load(f)
    assert rewritten['r2']['amcl']['ros__parameters']['odom_frame_id'] == 'r2/odom'
    map_server = nav[1].composable_node_descriptions[0]
    assert map_server.parameters[1]['yaml_filename'] == str(
        tmp_path / 'amr_description' / 'maps' / 'arena.yaml')  # the world's true map
    # AMCL joins every robot's odom to the one map: no world -> rI/odom, one world -> map
    rsp = [c for c in containers if c.node_name == 'robot_state_publisher_container'][0]
    assert {n.plugin for n in rsp.composable_node_descriptions} == {
        'amr_description::RobotStatePublisher'}
    static = [a for a in actions if isinstance(a, Node) and
              a.executable == 'static_transform_publisher']
    assert [s.arguments for s in static] == [['--frame-id', 'world', '--child-frame-id', 'map']]
    # the same content, the same file: describing again writes nothing new
    again = _actions(['robots:=2', 'world:=arena', 'navigation:=true', 'viewer:=false'])
    assert len(os.listdir(tmp_path / 'amr_description' / 'params')) == 2
    assert again
    without = _actions(['robots:=2'])
    assert not [a for a in without if getattr(a, 'node_name', None) == 'nav2_container']


def test_fleet_navigation_viewer_tools_act_on_r1(monkeypatch, tmp_path):
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    viewer = [a for a in _actions(['robots:=2', 'navigation:=true'])
              if isinstance(a, Node) and a.executable == 'viewer'][0]
    merged = {k: v for p in viewer.parameters for k, v in p.items()}
    assert merged['goal_pose_topic'] == '/r1/goal_pose'
    assert merged['initial_pose_topic'] == '/r1/initialpose'
    assert merged['fixed_frame'] == 'world'
