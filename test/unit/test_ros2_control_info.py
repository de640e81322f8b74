# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Unit tests of amr_description.core.description.ros2_control_info (pure, no rclpy)."""

import os

from amr_description.core.description.ros2_control_info import parse_ros2_control
import pytest

URDF_PATH = os.path.join(os.path.dirname(__file__), '..', '..', 'urdf', 'amr.urdf')

SAMPLE = """<?xml version="1.0"?>
<robot name="r">
  <link name="a"/>
  <ros2_control name="Sys" type="system">
    <hardware>
      <plugin>mock_components/GenericSystem</plugin>
      <param name="calculate_dynamics">true</param>
    </hardware>
    <joint name="j1">
      <command_interface name="velocity">
        <param name="min">-10</param>
        <param name="max">10.5</param>
      </command_interface>
      <state_interface name="position">
        <param name="initial_value">0.25</param>
      </state_interface>
      <state_interface name="velocity" data_type="float"/>
      <param name="gear">3</param>
    </joint>
    <joint name="j2">
      <state_interface name="position"/>
    </joint>
    <sensor name="imu">
      <state_interface name="orientation.x"/>
    </sensor>
  </ros2_control>
  <ros2_control name="Other" type="actuator">
    <hardware><plugin>pkg/Act</plugin></hardware>
  </ros2_control>
</robot>
"""


def test_sample_parses_every_field():
    infos = parse_ros2_control(SAMPLE)
    assert [i.name for i in infos] == ['Sys', 'Other']
    sys_info = infos[0]
    assert sys_info.type == 'system'
    assert sys_info.plugin == 'mock_components/GenericSystem'
    assert sys_info.parameters == {'calculate_dynamics': 'true'}
    assert [j.name for j in sys_info.joints] == ['j1', 'j2']
    j1 = sys_info.joint('j1')
    assert j1.command_interface_names() == ['velocity']
    cmd = j1.command_interfaces[0]
    assert (cmd.min, cmd.max, cmd.initial_value, cmd.data_type) == (-10.0, 10.5, None, 'double')
    assert j1.state_interface_names() == ['position', 'velocity']
    assert j1.state_interfaces[0].initial_value == 0.25
    assert j1.state_interfaces[1].data_type == 'float'
    assert j1.parameters == {'gear': '3'}
    assert sys_info.joint('j2').command_interfaces == []
    assert sys_info.joint('missing') is None
    assert [s.name for s in sys_info.sensors] == ['imu']
    assert infos[1].type == 'actuator' and infos[1].joints == []


def test_no_block_gives_empty_list():
    assert parse_ros2_control('<robot name="r"><link name="a"/></robot>') == []


def test_bytes_input():
    assert len(parse_ros2_control(SAMPLE.encode())) == 2


@pytest.mark.parametrize('xml, words', [
    ('<robot name="r"', 'well-formed'),
    ('<model/>', '<robot>'),
    ('<robot><ros2_control type="system"><hardware><plugin>p</plugin></hardware>'
     '</ros2_control></robot>', 'without a name'),
    ('<robot><ros2_control name="S" type="bogus"><hardware><plugin>p</plugin></hardware>'
     '</ros2_control></robot>', "found 'bogus'"),
    ('<robot><ros2_control name="S" type="system"></ros2_control></robot>', '<hardware>'),
    ('<robot><ros2_control name="S" type="system"><hardware/></ros2_control></robot>',
     '<plugin>'),
    ('<robot><ros2_control name="S" type="system"><hardware><plugin>p</plugin></hardware>'
     '<joint name="j"><command_interface/></joint></ros2_control></robot>', 'without a name'),
    ('<robot><ros2_control name="S" type="system"><hardware><plugin>p</plugin></hardware>'
     '<joint name="j"><command_interface name="velocity"><param name="min">low</param>'
     '</command_interface></joint></ros2_control></robot>', "'min' must be a number"),
    ('<robot><ros2_control name="S" type="system"><hardware><plugin>p</plugin></hardware>'
     '<joint name="j"/><joint name="j"/></ros2_control></robot>', 'listed twice'),
])
def test_malformed_raises_one_line_value_error(xml, words):
    with pytest.raises(ValueError) as err:
        parse_ros2_control(xml)
    message = str(err.value)
    assert words in message
    assert '\n' not in message


@pytest.mark.skipif(not os.path.isfile(URDF_PATH), reason='urdf/amr.urdf not written yet')
def test_amr_urdf_block():
    with open(URDF_PATH) as f:
        infos = parse_ros2_control(f.read())
    assert len(infos) == 1
    info = infos[0]
    assert (info.name, info.type, info.plugin) == (
        'AmrSystem', 'system', 'amr_description/MujocoSystem')
    names = [j.name for j in info.joints]
    assert sorted(names) == sorted(
        f'joint_wheel_{s}' for s in ('front_left', 'front_right', 'back_left', 'back_right'))
    for joint in info.joints:
        assert joint.command_interface_names() == ['velocity']
        assert joint.state_interface_names() == ['position', 'velocity']
