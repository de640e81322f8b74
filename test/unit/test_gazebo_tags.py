# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The Gazebo dialect read without a simulator: xacro files, gz_ros2_control's plugin."""

import os
import xml.etree.ElementTree as ET

from amr_description.core.description.files import parse_xacro_args
from amr_description.core.description.files import read_description
from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.tags import parse_control_plugin
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, 'test', 'data', 'gz_tutorial')


def _plugin(children, filename='libgz_ros2_control-system.so'):
    return ET.fromstring(
        f'<robot name="r"><gazebo><plugin filename="{filename}" '
        f'name="gz_ros2_control::GazeboSimROS2ControlPlugin">{children}</plugin></gazebo>'
        '</robot>')


def test_every_child_of_the_plugin_in_text_and_value_form():
    plugin = parse_control_plugin(_plugin(
        '<parameters>/a.yaml</parameters><parameters value="/b.yaml"/>'
        '<controller_manager_name>cm</controller_manager_name>'
        '<ros><namespace>r1</namespace><remapping>/tf:=tf</remapping>'
        '<remapping>/tf_static:=tf_static</remapping></ros>'
        '<hold_joints>false</hold_joints>'
        '<position_proportional_gain value="0.5"/>'))
    assert plugin.parameters == ['/a.yaml', '/b.yaml']
    assert (plugin.controller_manager_name, plugin.namespace) == ('cm', '/r1')
    assert plugin.remappings == ['/tf:=tf', '/tf_static:=tf_static']
    assert (plugin.hold_joints, plugin.position_proportional_gain) == (False, 0.5)


@pytest.mark.parametrize('filename', ['gz_ros2_control-system', 'libgz_ros2_control-system.so',
                                      'libign_ros2_control-system.so'])
def test_plugin_file_names_and_defaults(filename):
    plugin = parse_control_plugin(_plugin('<parameters>/a.yaml</parameters>', filename))
    assert (plugin.controller_manager_name, plugin.namespace, plugin.remappings) == \
        ('controller_manager', '', [])
    assert (plugin.hold_joints, plugin.position_proportional_gain) == (True, 0.1)


def test_no_plugin_and_other_plugins():
    assert parse_control_plugin(ET.fromstring('<robot name="r"/>')) is None
    other = ET.fromstring('<robot name="r"><gazebo><plugin filename="gz-sim-diff-drive-system" '
                          'name="gz::sim::systems::DiffDrive"/></gazebo></robot>')
    assert parse_control_plugin(other) is None


@pytest.mark.parametrize('children, words', [
    ('', r'<parameters> \(the controllers YAML\) is required'),
    ('<parameters> </parameters>', 'must not be empty'),
    ('<parameters>/a.yaml</parameters><hold_joints>maybe</hold_joints>', 'true or false'),
    ('<parameters>/a.yaml</parameters><position_proportional_gain>x'
     '</position_proportional_gain>', 'expected a number'),
])
def test_a_plugin_missing_or_with_a_bad_element_is_one_line(children, words):
    with pytest.raises(ValueError, match=words) as refused:
        parse_control_plugin(_plugin(children))
    assert '\n' not in str(refused.value) and '<gazebo><plugin' in str(refused.value)


def test_xacro_arguments():
    assert parse_xacro_args('prefix:=r1_ "label:=a b"') == {'prefix': 'r1_', 'label': 'a b'}
    assert parse_xacro_args('') == {}
    with pytest.raises(ValueError, match="'prefix' is not name:=value"):
        parse_xacro_args('prefix')


def test_the_tutorial_xacro_expands_with_find_and_arguments(tmp_path):
    include = tmp_path / 'robot.urdf.xacro'
    include.write_text(
        '<robot name="outer" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="tag" default="x"/>'
        '<xacro:include filename="$(find amr_description)/urdf/amr.urdf"/>'
        '<link name="$(arg tag)_extra"/><joint name="mast" type="fixed">'
        '<parent link="base_link"/><child link="$(arg tag)_extra"/></joint></robot>')
    text = read_description(str(include), {'tag': 'mast'})
    description = RobotDescription(text)
    assert 'mast_extra' in description.model.links
    assert 'wheel_front_left' in description.model.links  # from the included file


def test_a_xacro_file_named_urdf_is_expanded_as_its_launch_file_would(tmp_path):
    """Courses name xacro files robot.urdf and run xacro on them; read raw, includes are lost."""
    gazebo = tmp_path / 'robot.gazebo'
    gazebo.write_text('<robot><gazebo reference="base_link"><sensor name="imu" type="imu"/>'
                      '</gazebo></robot>')
    robot = tmp_path / 'robot.urdf'
    robot.write_text(
        '<robot name="course" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:include filename="{gazebo}"/>'
        '<link name="base_link"/></robot>')
    description = RobotDescription(read_description(str(robot)))
    assert [b.name for b in description.sensors.sensors] == ['imu']
    plain = read_description(os.path.join(ROOT, 'urdf', 'amr.urdf'))
    assert plain.startswith('<?xml') and 'xacro' not in plain  # a plain URDF is read as it is


def test_the_tutorial_gazebo_robot_gets_the_drive_defaults():
    description = RobotDescription(read_description(
        os.path.join(DATA, 'robot.urdf.xacro'), {'controllers': '/c.yaml'}))
    assert [h.plugin for h in description.hardware] == ['gz_ros2_control/GazeboSimSystem']
    assert description.parameters_files() == ['/c.yaml']
    assert not description.mujoco.present
    drive = description.mujoco.joint_actuator['front_left_wheel_joint']
    assert (drive['kv'], drive['ki'], drive['forcerange']) == (5.0, 100.0, (-20.0, 20.0))
    assert description.mujoco.link_contact['front_left_wheel'] == {'shape': 'ellipsoid'}
    assert 'base_link' not in description.mujoco.link_contact


@pytest.mark.parametrize('content, words', [
    ('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a">\n</robot>',
     'xacro: XML parsing error: mismatched tag'),
    ('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">'
     '<xacro:include filename="$(find nosuchpkg)/x.urdf"/></robot>',
     r"\$\(find nosuchpkg\): package 'nosuchpkg' is not in the ament index"),
    ('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">'
     '<link name="${nothing}"/></robot>', "name 'nothing' is not defined"),
])
def test_a_xacro_error_is_one_line_naming_the_file(tmp_path, content, words):
    path = tmp_path / 'bad.urdf.xacro'
    path.write_text(content)
    with pytest.raises(ValueError, match=words) as refused:
        read_description(str(path))
    assert str(refused.value).startswith(f'{path}: xacro: ') and '\n' not in str(refused.value)


def test_stacks_take_a_xacro_description_its_arguments_and_the_controllers():
    from amr_description.launch import registry
    from amr_description.launch import stacks
    from amr_description.launch.actions import LaunchError
    controllers = os.path.join(DATA, 'controllers.yaml')
    args = registry.resolve('sim', [f'description:={DATA}/robot.urdf.xacro',
                                    f'xacro_args:=controllers:={controllers} prefix:=',
                                    'controllers:=joint_state_broadcaster', 'viewer:=false'])
    mujoco_sim, rsp, create, on_create = stacks.sim(args)
    description = rsp.parameters[0]['robot_description']
    assert 'tutorial_bot' in description and controllers in description
    assert on_create.on_exit[0].arguments == ['joint_state_broadcaster']
    display = stacks.display(registry.resolve('display', [f'model:={DATA}/robot.urdf.xacro']))
    assert 'tutorial_bot' in display[0].parameters[0]['robot_description']
    # a robot driven by gz-sim systems (no <ros2_control>) gets no spawner; bridge_config
    caster = os.path.join(ROOT, 'test', 'data', 'gz_diff_drive', 'robot.urdf.xacro')
    actions = stacks.sim(registry.resolve('sim', [f'description:={caster}', 'viewer:=false',
                                                  'bridge_config:=/b.yaml']))
    assert [a.executable for a in actions] == ['mujoco_sim', 'robot_state_publisher', 'create']
    assert actions[0].parameters[0]['bridge_config'] == '/b.yaml'
    with pytest.raises(LaunchError, match="launch argument 'controllers'"):
        stacks.sim(registry.resolve('sim', ['controllers:= , ']))
    with pytest.raises(LaunchError, match="cannot read URDF '/nothing.urdf.xacro'"):
        stacks.sim(registry.resolve('sim', ['description:=/nothing.urdf.xacro']))


def test_check_model_reads_the_dialect(tmp_path, capsys):
    from amr_description.nodes import check_model
    urdf = tmp_path / 'robot.urdf'
    text = read_description(os.path.join(DATA, 'robot.urdf.xacro'),
                            {'controllers': os.path.join(DATA, 'controllers.yaml')})
    text = text.replace('</robot>', '<gazebo reference="front_left_wheel"><mu1>0.8</mu1>'
                        '<kp>1e6</kp><selfCollide>true</selfCollide>'
                        '<material>Gazebo/Orange</material><turnGravityOff>1</turnGravityOff>'
                        '</gazebo><gazebo reference="base_link"><material>Gazebo/Wood'
                        '</material><gravity>nope</gravity></gazebo><gazebo>'
                        '<plugin filename="gz-sim-sensors-system" '
                        'name="gz::sim::systems::Sensors"/><plugin '
                        'filename="gz-sim-pose-publisher-system" '
                        'name="gz::sim::systems::PosePublisher"/></gazebo></robot>')
    urdf.write_text(text)
    assert check_model.main([str(urdf)]) == 1
    out = capsys.readouterr().out
    assert 'OK      <gazebo><plugin gz_ros2_control::GazeboSimROS2ControlPlugin>: ' \
        'gz_ros2_control: starts the controller manager' in out
    assert 'OK      <gazebo reference="front_left_wheel"><mu1>: contact friction 0.8' in out
    assert 'OK      <gazebo reference="front_left_wheel"><kp>: ignored' in out
    assert 'OK      <gazebo reference="front_left_wheel"><selfCollide>: collides with the ' \
        "robot's other links" in out
    assert 'OK      <gazebo reference="front_left_wheel"><material>: the link\'s visuals are ' \
        'drawn 1 0.5088 0.0468 1 (rgba)' in out
    assert 'OK      <gazebo reference="front_left_wheel"><turnGravityOff>: no gravity' in out
    assert "WARNING <gazebo reference=\"base_link\"><material>: 'Gazebo/Wood' is not a solid " \
        'Gazebo material' in out
    assert 'ERROR   <gazebo reference="base_link"><gravity>: expected true or false, found ' \
        "'nope'" in out
    assert 'WARNING <gazebo><plugin gz::sim::systems::PosePublisher>: system plugin not ' \
        'simulated' in out
    assert 'OK      <gazebo><plugin gz::sim::systems::Sensors>: not needed' in out
    # the controllers YAML came from <parameters>: the wheels of diff_drive_controller
    assert 'unknown hardware plugin' not in out
    assert 'diff_drive_controller: wheel_radius 0.1 m matches' in out
