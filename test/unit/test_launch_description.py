# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Node command lines built as launch_ros builds them; launch arguments as ros2 launch."""

import os

from amr_description.launch import registry
from amr_description.launch import stacks
from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import format_arguments
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import OnProcessExit
from amr_description.launch.actions import parse_launch_arguments
from amr_description.launch.actions import Process
import pytest
import yaml


def _node(**kwargs):
    return Node('pkg', 'exe', exe_path='/opt/pkg/lib/pkg/exe', **kwargs)


def test_plain_node_gets_ros_args_only():
    node = _node()
    assert node.build_cmd() == ['/opt/pkg/lib/pkg/exe', '--ros-args']
    assert node.name == 'exe'


def test_name_namespace_arguments_remappings_order():
    node = _node(name='talker', namespace='robot1', arguments=['-topic', 'robot_description'],
                 remappings=[('/a', '/b'), ('c', 'd')])
    assert node.build_cmd() == [
        '/opt/pkg/lib/pkg/exe', '-topic', 'robot_description', '--ros-args',
        '-r', '__node:=talker', '-r', '__ns:=/robot1', '-r', '/a:=/b', '-r', 'c:=d']


def test_absolute_namespace_kept():
    assert '__ns:=/a/b' in _node(namespace='/a/b').build_cmd()


def test_parameter_dicts_and_files(tmp_path):
    params_file = tmp_path / 'controllers.yaml'
    params_file.write_text('x: 1\n')
    node = _node(name='n', parameters=[{'use_sim_time': True, 'rate': 2.5, 'name': 'a b'},
                                       str(params_file), {'robot_description': '<robot/>'}])
    cmd = node.build_cmd(params_dir=str(tmp_path))
    assert cmd[:5] == ['/opt/pkg/lib/pkg/exe', '--ros-args', '-r', '__node:=n', '--params-file']
    files = [cmd[i + 1] for i, part in enumerate(cmd) if part == '--params-file']
    assert len(files) == 3 and files[1] == str(params_file)
    assert all(os.path.basename(f).startswith('launch_params_') for f in (files[0], files[2]))
    with open(files[0]) as f:
        assert yaml.safe_load(f) == {
            '/**': {'ros__parameters': {'use_sim_time': True, 'rate': 2.5, 'name': 'a b'}}}
    with open(files[2]) as f:
        assert yaml.safe_load(f) == {'/**': {'ros__parameters': {'robot_description': '<robot/>'}}}
    assert node.temp_files() == [files[0], files[2]]


@pytest.mark.parametrize('name, namespace, key', [
    ('n', None, '/**'), (None, 'r1', '/**'), ('n', '/', '/n'), ('n', 'r1', '/r1/n'),
    ('n', '/a/b', '/a/b/n')])
def test_parameter_dicts_are_keyed_by_the_full_node_name_only_when_fully_specified(
        tmp_path, name, namespace, key):
    # as launch_ros' Node: name and namespace given -> the node's name, else every node
    cmd = _node(name=name, namespace=namespace, parameters=[{'rate': 2}]).build_cmd(
        params_dir=str(tmp_path))
    with open(cmd[cmd.index('--params-file') + 1]) as f:
        assert yaml.safe_load(f) == {key: {'ros__parameters': {'rate': 2}}}


def test_params_before_remappings():
    cmd = _node(parameters=['/p.yaml'], remappings=[('a', 'b')]).build_cmd()
    assert cmd[-4:] == ['--params-file', '/p.yaml', '-r', 'a:=b']


def test_bad_parameters_type():
    with pytest.raises(LaunchError, match='expected dicts or file paths'):
        _node(parameters=[42])


def test_missing_executable():
    with pytest.raises(LaunchError, match="package 'no_such_package_xyz' not found"):
        Node('no_such_package_xyz', 'exe').build_cmd()


def test_process_defaults():
    proc = Process(['/bin/echo', 'hi'])
    assert proc.name == 'echo' and proc.build_cmd() == ['/bin/echo', 'hi']
    assert not proc.respawn and not proc.required and proc.output == 'screen'


def test_launch_arguments():
    declared = [DeclareLaunchArgument('rtf', '1.0', 'Real-time factor'),
                DeclareLaunchArgument('mode', 'a', 'Mode', choices=['a', 'b'])]
    assert parse_launch_arguments(declared, []) == {'rtf': '1.0', 'mode': 'a'}
    assert parse_launch_arguments(declared, ['rtf:=0', 'rtf:=2']) == {'rtf': '2', 'mode': 'a'}
    with pytest.raises(LaunchError, match="malformed launch argument 'rtf', expected format"):
        parse_launch_arguments(declared, ['rtf'])
    with pytest.raises(LaunchError, match="unknown launch argument 'foo'"):
        parse_launch_arguments(declared, ['foo:=1'])
    with pytest.raises(LaunchError, match="provided value 'c' is not valid"):
        parse_launch_arguments(declared, ['mode:=c'])
    text = format_arguments(declared)
    assert text.startswith("Arguments (pass arguments as '<name>:=<value>'):\n\n    'rtf':\n"
                           "        Real-time factor\n        (default: '1.0')\n")


def test_stack_names():
    assert registry.stack_name('sim') == 'sim'
    assert registry.stack_name('sim.launch.py') == 'sim'
    assert registry.stack_name('display.launch.py') == 'display'
    with pytest.raises(LaunchError, match="file 'nope' was not found"):
        registry.stack_name('nope')


def test_sim_stack_layout(monkeypatch):
    urdf = '<robot name="amr"><ros2_control name="s" type="system"/></robot>'
    monkeypatch.setattr(stacks, 'read_urdf', lambda path=None, xacro_args='': urdf)
    args = registry.resolve('sim', ['rtf:=0', 'robot:=r2', 'x:=1', 'yaw:=1.57', 'viewer:=false'])
    mujoco_sim, rsp, create, on_create = stacks.sim(args)
    assert mujoco_sim.executable == 'mujoco_sim'
    assert mujoco_sim.parameters == [{'real_time_factor': 0.0, 'headless': True,
                                      'bridge_config': '', 'world': 'empty'}]
    assert mujoco_sim.remappings == [('/diff_drive_controller/odom', '/odom')]
    assert rsp.parameters == [{'robot_description': urdf, 'use_sim_time': True}]
    assert create.arguments == ['-topic', 'robot_description', '-name', 'r2', '-x', '1.0',
                                '-y', '0.0', '-z', '0.2', '-Y', '1.57']
    assert isinstance(on_create, OnProcessExit) and on_create.target_action is create
    assert on_create.only_on_success
    spawner = on_create.on_exit[0]
    assert spawner.executable == 'spawner'
    assert spawner.arguments == ['joint_state_broadcaster', 'diff_drive_controller']
    with pytest.raises(LaunchError, match="launch argument 'rtf': expected a number"):
        stacks.sim(registry.resolve('sim', ['rtf:=fast']))
    with pytest.raises(LaunchError, match="launch argument 'headless': expected true or false"):
        stacks.sim(registry.resolve('sim', ['headless:=maybe']))
    *_, viewer = stacks.sim(registry.resolve('sim', ['viewer_port:=18080']))
    assert viewer.executable == 'viewer'
    assert viewer.parameters == [{'use_sim_time': True, 'fixed_frame': 'odom', 'port': 18080,
                                  'world': 'empty'}]
    with pytest.raises(LaunchError, match="launch argument 'viewer_port': expected a TCP port"):
        stacks.sim(registry.resolve('sim', ['viewer_port:=http']))


def test_display_stack_layout(monkeypatch):
    monkeypatch.setattr(stacks, 'read_urdf',
                        lambda path=None, xacro_args='': '<robot name="amr"/>')
    rsp, jsp = stacks.display(registry.resolve('display', ['gui:=false', 'viewer:=false']))
    assert (rsp.executable, jsp.executable) == ('robot_state_publisher', 'joint_state_publisher')
    assert rsp.parameters == [{'robot_description': '<robot name="amr"/>',
                               'use_sim_time': False}]
    # ports left at their defaults: each page takes 8081 / 8080 or the next free port
    rsp, gui, viewer = stacks.display(registry.resolve('display'))
    assert gui.executable == 'joint_state_publisher_gui'
    assert gui.parameters == [{'use_sim_time': False}]
    assert viewer.executable == 'viewer'
    assert viewer.parameters == [{'use_sim_time': False, 'fixed_frame': 'base_footprint'}]
    # given, even with the default's value: exactly that port
    rsp, gui, viewer = stacks.display(registry.resolve('display', ['gui_port:=8081',
                                                                   'viewer_port:=8080']))
    assert gui.parameters == [{'use_sim_time': False, 'port': 8081}]
    assert viewer.parameters[0]['port'] == 8080


@pytest.mark.parametrize('name', sorted(registry.STACKS))
def test_a_port_left_at_its_default_is_not_passed_as_chosen(name):
    declared = {d.name for d in registry.STACKS[name][1]}
    ports = {arg for arg in declared if arg.endswith('_port')}
    argv = ['robots:=2'] if 'robots' in declared else []
    pages = [a for a in registry.describe(name, argv)
             if getattr(a, 'executable', None) in ('viewer', 'joint_state_publisher_gui')]
    assert bool(ports) == bool(pages), (name, ports, pages)
    for page in pages:
        assert 'port' not in page.parameters[0], (name, page.executable, page.parameters)


def test_unreadable_urdf(tmp_path):
    with pytest.raises(LaunchError, match="cannot read URDF '.*missing.urdf'"):
        stacks.read_urdf(str(tmp_path / 'missing.urdf'))
