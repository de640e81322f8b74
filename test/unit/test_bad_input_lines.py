# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Bad input to the readers and the CLI: one line naming what is wrong (no process, no DDS)."""

import subprocess
import sys

from amr_description.cli.daemon import domain_id
from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.gazebo.sensors import parse_sensors
from amr_description.core.ros_names import topic_name_problem
from amr_description.core.rviz_config import read_rviz_config
from amr_description.core.xml_document import parse_text
import pytest


@pytest.mark.parametrize('value, expected', [('', 0), ('0', 0), ('232', 232), (' 7', 7)])
def test_domain_id_accepts_what_rcl_and_fast_dds_accept(monkeypatch, value, expected):
    monkeypatch.setenv('ROS_DOMAIN_ID', value)
    assert domain_id() == expected


@pytest.mark.parametrize('value', ['abc', '233', '-1', '1.5', '0x10'])
def test_domain_id_refuses_with_one_line(monkeypatch, value):
    monkeypatch.setenv('ROS_DOMAIN_ID', value)
    with pytest.raises(ValueError, match=f"ROS_DOMAIN_ID '{value}': expected an integer from 0 "
                       'to 232'):
        domain_id()


def test_ros2_with_a_bad_domain_id_is_one_line_and_exit_1():
    env_script = ('import os, sys; os.environ["ROS_DOMAIN_ID"] = "abc"; '
                  'from amr_description.cli.main import main; sys.exit(main(sys.argv[1:]))')
    run = subprocess.run([sys.executable, '-c', env_script, 'topic', 'list'],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 1
    assert run.stderr.strip() == "ROS_DOMAIN_ID 'abc': expected an integer from 0 to 232"
    assert run.stdout == ''


def _world(tmp_path, body, version='1.9'):
    path = tmp_path / 'w.sdf'
    path.write_text(f'<?xml version="1.0"?><sdf version="{version}"><world name="w">{body}'
                    '<model name="ok"><static>true</static><link name="l"><collision name="c">'
                    '<geometry><box><size>1 1 1</size></box></geometry></collision></link>'
                    '</model></world></sdf>')
    return read_world(str(path))


@pytest.mark.parametrize('step, used', [('1e-9', 1e-5), ('10', 0.01), ('0.004', 0.004)])
def test_physics_steps_that_cannot_work_are_clamped_with_a_line(tmp_path, step, used):
    world = _world(tmp_path, f'<physics type="ode"><max_step_size>{step}</max_step_size>'
                   '</physics>')
    assert world.physics_step == used
    clamped = [m for m in world.messages if '<max_step_size>' in m]
    assert clamped == ([] if float(step) == used else
                       [f'<physics><max_step_size> {float(step):g} s is out of 1e-05..0.01 s: '
                        f'{used:g} s used'])


def test_version_that_is_not_a_number_is_one_line(tmp_path):
    world = _world(tmp_path, '', version='one')
    assert world.messages[0].endswith('<sdf version="one"> is not a version number (expected '
                                      'MAJOR.MINOR); read as 1.11')
    assert [m.name for m in world.models] == ['ok']


def test_latitude_out_of_range_leaves_navsat_without_origin(tmp_path):
    world = _world(tmp_path, '<spherical_coordinates><latitude_deg>1000</latitude_deg>'
                   '</spherical_coordinates>')
    assert world.spherical_coordinates is None
    assert world.messages == ['<spherical_coordinates><latitude_deg>: expected -90..90 deg, '
                              'found 1000: navsat sensors have no origin']


def test_huge_size_leaves_that_shape_out(tmp_path):
    world = _world(tmp_path, '<model name="huge"><static>true</static><link name="l">'
                   '<collision name="c"><geometry><box><size>1e300 1 1</size></box></geometry>'
                   '</collision></link></model>')
    assert world.messages == ["model 'huge' link 'l' collision 'c': <box> sizes must be > 0 "
                              'and at most 100000, found 1e+300 1 1: skipped']


def test_include_chain_deeper_than_the_limit_is_one_line(tmp_path, monkeypatch):
    for i in range(40):
        folder = tmp_path / f'm{i}'
        folder.mkdir()
        inner = f'<include><uri>model://m{i + 1}</uri></include>' if i < 39 else (
            '<link name="l"><collision name="c"><geometry><box><size>1 1 1</size></box>'
            '</geometry></collision></link>')
        (folder / 'model.sdf').write_text(f'<sdf version="1.9"><model name="m{i}">{inner}'
                                          '</model></sdf>')
        (folder / 'model.config').write_text('<model><sdf>model.sdf</sdf></model>')
    monkeypatch.setenv('GZ_SIM_RESOURCE_PATH', str(tmp_path))
    world = _world(tmp_path, '<include><uri>model://m0</uri></include>')
    assert [m.name for m in world.models] == ['ok']
    assert len(world.messages) == 1
    assert world.messages[0].startswith('model://m32: more than 32 nested <include>s')


@pytest.mark.parametrize('name, problem', [
    ('scan', ''), ('/robot/scan', ''), ('~/scan', ''), ('{node}/scan', ''),
    ('my scan', "it holds ' '"), ('scan/', 'it ends with "/"'), ('a//b', 'it holds "//"'),
    ('a/~b', '"~" may only start it'), ('2d/scan', "its token '2d' starts with a digit"),
    ('', 'it is empty'), ('{a{b}}', 'nested')])
def test_topic_name_rules_are_rcls(name, problem):
    found = topic_name_problem(name)
    assert (found == '') if not problem else (problem in found), found


def test_sensor_topics_checked_up_front():
    root = parse_text(
        '<robot name="r"><link name="l"/><gazebo reference="l">'
        '<sensor name="front lidar" type="gpu_lidar"/>'
        '<sensor name="a" type="imu"><topic>my imu</topic></sensor>'
        '<sensor name="b" type="imu"><topic>imu</topic></sensor>'
        '<sensor name="c" type="gpu_lidar"><topic>/imu</topic></sensor>'
        '</gazebo></robot>')
    blocks = parse_sensors(root, {'l'})
    assert [b.name for b in blocks.sensors] == ['b']
    assert blocks.messages[0].startswith("sensor 'front lidar': its name makes no valid ROS "
                                         'topic')
    assert blocks.messages[1].startswith("sensor 'a': <topic>: 'my imu' is not a valid ROS "
                                         "topic name: it holds ' '")
    assert blocks.messages[2] == ("sensor 'c': <topic> '/imu' is already the topic of sensor "
                                  "'b' (one topic, one sensor); the sensor is skipped")


def test_rviz_configs_bad_values_are_one_line_each(tmp_path):
    path = tmp_path / 'bad.rviz'
    path.write_text('Visualization Manager:\n  Global Options:\n    Fixed Frame: [a, b]\n'
                    '  Displays:\n    - Class: rviz_default_plugins/LaserScan\n'
                    '      Name: scan\n      Topic:\n        Value: my scan\n')
    config = read_rviz_config(str(path), {'rviz_default_plugins/LaserScan': 'scan_topics'})
    assert config.fixed_frame == '' and config.topics == {'scan_topics': []}
    assert len(config.problems) == 2 and 'Fixed Frame: expected a frame name' in \
        config.problems[0] and "topic 'my scan' is not a valid ROS topic" in config.problems[1]


def test_rviz_alias_bomb_deep_nesting_and_non_utf8_are_refused(tmp_path):
    lines = ['a0: &a0 [{Class: rviz_common/Group, Displays: []}]']
    for i in range(1, 10):
        lines.append(f'a{i}: &a{i} [' + ', '.join(
            [f'{{Class: rviz_common/Group, Displays: *a{i - 1}}}'] * 9) + ']')
    bomb = tmp_path / 'bomb.rviz'
    bomb.write_text('\n'.join(lines) + '\nVisualization Manager:\n  Displays: *a9\n')
    deep = tmp_path / 'deep.rviz'
    deep.write_text('Visualization Manager:\n  Displays: ' + '[{Class: rviz_common/Group, '
                    'Displays: ' * 3000 + '[]' + '}]' * 3000 + '\n')
    latin = tmp_path / 'latin.rviz'
    latin.write_bytes(b'Visualization Manager:\n  Displays: []\n# caf\xe9\n')
    for path, words in ((bomb, 'more than 10000 displays'),
                        (deep, 'nested more than 100 levels deep'),
                        (latin, 'not UTF-8 text (byte 0xe9 at offset 43)')):
        with pytest.raises(ValueError) as info:
            read_rviz_config(str(path), {})
        assert str(info.value).startswith(f'{path}: ') and words in str(info.value)


def test_mujoco_compiler_errors_become_one_line_naming_the_element():
    from amr_description.sim.world import mujoco_error
    exc = ValueError("Error: inertia must satisfy A + B >= C; use 'balanceinertia' to fix\n"
                     "Element name 'amr/wheel_front_left', id 3")
    assert mujoco_error(exc) == ("inertia must satisfy A + B >= C; use 'balanceinertia' to fix "
                                 "(element 'amr/wheel_front_left')")
    assert mujoco_error(ValueError('Error: something')) == 'something'


def test_world_models_of_one_name_and_unphysical_inertia_leave_that_model_out(tmp_path):
    box = ('<collision name="c"><geometry><box><size>1 1 1</size></box></geometry>'
           '</collision>')
    world = _world(tmp_path, f'<model name="ok"><link name="l">{box}</link></model>'
                   '<model name="loose"><link name="link"><inertial><mass>1</mass><inertia>'
                   f'<ixx>1</ixx><iyy>1</iyy><izz>5</izz></inertia></inertial>{box}</link>'
                   '</model>')
    assert [m.name for m in world.models] == ['ok']
    assert world.messages == [
        "model 'loose' link 'link' <inertia>: principal moments break the triangle inequality "
        '(expected I1 + I2 >= I3, found (1, 1, 5)): the world loads without it',
        "model 'ok': a second model of that name: the world loads without it"]


@pytest.mark.parametrize('name, words', [
    ('foo_msgs/msg/Bar', "package 'foo_msgs' is not installed"),
    ('std_msgs/msg/Nope', "package 'std_msgs' has no msg 'Nope'")])
def test_unknown_message_type_names_the_type_and_why(name, words):
    from amr_description.core.message_yaml.utilities import get_message
    with pytest.raises(ValueError) as info:
        get_message(name)
    assert str(info.value) == f"Unknown interface type '{name}': {words}"


def test_parameter_files_refuse_aliases_and_deep_nesting_with_the_line(tmp_path):
    from amr_description.core.ros_param_file import load_yaml
    lines = ['a0: &a0 [x, x, x, x, x, x, x, x, x]']
    lines += [f'a{i}: &a{i} [' + ', '.join([f'*a{i - 1}'] * 9) + ']' for i in range(1, 9)]
    bomb = tmp_path / 'bomb.yaml'
    bomb.write_text('\n'.join(lines) + '\n/**:\n  ros__parameters:\n    p: *a8\n')
    deep = tmp_path / 'deep.yaml'
    deep.write_text('/**:\n  ros__parameters:\n    p: ' + '[' * 5000 + ']' * 5000 + '\n')
    with pytest.raises(ValueError) as info:
        load_yaml(str(bomb))
    assert str(info.value) == (f'parameter file {bomb} line 2: invalid YAML (aliases (*name) '
                               'are not allowed in this file)')
    with pytest.raises(ValueError) as info:
        load_yaml(str(deep))
    assert str(info.value) == (f'parameter file {deep} line 3: invalid YAML (nested more than '
                               '100 levels deep)')


def test_safe_load_reads_what_yaml_safe_load_reads():
    from amr_description.core.yaml_text import safe_load
    text = 'a: [1, 2.5, {b: c}]\nd: null\n'
    assert safe_load(text) == {'a': [1, 2.5, {'b': 'c'}], 'd': None}
    assert safe_load('x: &v 1\ny: *v\n', aliases=True) == {'x': 1, 'y': 1}


def test_bridge_config_refuses_a_bad_ros_topic_and_non_utf8_with_one_line(tmp_path):
    from amr_description.core.gazebo.bridge_config import parse_bridge_config
    from amr_description.core.gazebo.bridge_config import read_bridge_config
    text = ('- ros_topic_name: "my scan"\n  gz_topic_name: /scan\n'
            '  ros_type_name: sensor_msgs/msg/LaserScan\n  gz_type_name: gz.msgs.LaserScan\n')
    with pytest.raises(ValueError) as info:
        parse_bridge_config(text, 'bridge.yaml')
    assert str(info.value).startswith("bridge.yaml entry 1: ROS topic 'my scan' is not a valid "
                                      'ROS topic name')
    latin = tmp_path / 'bridge.yaml'
    latin.write_bytes(b'# caf\xe9\n')
    with pytest.raises(ValueError, match=r'not UTF-8 text \(byte 0xe9 at offset 5\)'):
        read_bridge_config(str(latin))


def test_yaml_files_that_are_not_utf8_are_one_line(tmp_path):
    from amr_description.core.model_check.controllers_yaml import load_controllers
    from amr_description.core.ros_param_file import load_yaml
    path = tmp_path / 'latin.yaml'
    path.write_bytes(b'/**:\n  ros__parameters:\n    a: caf\xe9\n')
    with pytest.raises(ValueError) as info:
        load_yaml(str(path))
    assert str(info.value) == (f'parameter file {path}: invalid YAML (not UTF-8 text (byte '
                               '0xe9 at offset 34))')
    with pytest.raises(ValueError, match='not UTF-8 text'):
        load_controllers(str(path))
