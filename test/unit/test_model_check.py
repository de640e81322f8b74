# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The model check passes urdf/amr.urdf and finds each defect in broken copies of it."""

import os
import re
import shutil
import warnings as python_warnings

from amr_description.core import model_check as mc
from amr_description.core.description.urdf_model import parse_urdf
from amr_description.core.model_check import controllers as controller_checks
from amr_description.core.model_check import controllers_yaml
from amr_description.core.model_check import installed
from amr_description.core.model_check import links
from amr_description.core.model_check import wheels
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING
from amr_description.nodes import check_model as check_model_command
import numpy as np
import pytest
import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')
YAML_PATH = os.path.join(ROOT, 'config', 'controllers.yaml')


@pytest.fixture(scope='module')
def urdf_xml():
    with open(URDF_PATH) as f:
        return f.read()


@pytest.fixture(scope='module')
def controllers():
    return controllers_yaml.load_controllers(YAML_PATH)


def tutorial_urdf(urdf_xml):
    """Return the tutorial's original variant: every wheel mounted with rpy="1.5708 0 0"."""
    assert urdf_xml.count('rpy="-1.5708 0 0"/>') == 4
    text = urdf_xml.replace('rpy="-1.5708 0 0"/>', 'rpy="1.5708 0 0"/>')
    return text


def run(xml, controllers=None):
    return mc.check_model(parse_urdf(xml), xml, controllers)


def errors(findings):
    return [f for f in findings if f.severity == ERROR]


def warnings(findings):
    return [f for f in findings if f.severity == WARNING]


def link_block(xml, name):
    start = xml.index(f'<link name="{name}">')
    return start, xml.index('</link>', start) + len('</link>')


def edit_link(xml, name, old, new):
    start, end = link_block(xml, name)
    block = xml[start:end]
    assert old in block
    return xml[:start] + block.replace(old, new, 1) + xml[end:]


def remove_element(xml, link, tag):
    start, end = link_block(xml, link)
    block = re.sub(rf'\s*<{tag}>.*?</{tag}>', '', xml[start:end], count=1, flags=re.S)
    return xml[:start] + block + xml[end:]


def test_amr_passes_with_zero_errors_and_warnings(urdf_xml, controllers):
    findings = run(urdf_xml, controllers)
    assert errors(findings) == [] and warnings(findings) == []
    ok = [str(f) for f in findings if f.severity == INFO]
    assert sum('drives forward' in line for line in ok) == 4
    assert any('wheel_separation 0.3 m matches' in line for line in ok)
    assert any('wheel_radius 0.1 m matches' in line for line in ok)
    assert any('wheel_separation_multiplier 2.78 matches' in line for line in ok)


def test_reversed_axle_of_the_tutorial_is_an_error(urdf_xml, controllers):
    found = errors(run(tutorial_urdf(urdf_xml), controllers))
    assert len(found) == 4
    assert all('BACKWARDS' in f.message for f in found)
    sides = ('front_left', 'front_right', 'back_left', 'back_right')
    assert {f.element for f in found} == {f"joint 'joint_wheel_{s}'" for s in sides}
    assert '(0, -1, 0)' in found[0].found


def test_sideways_axle(urdf_xml):
    xml = urdf_xml.replace('rpy="-1.5708 0 0"/>', 'rpy="0 1.5708 0"/>', 1)
    found = errors(run(xml))
    assert len(found) == 1 and 'sideways' in found[0].message


def test_missing_inertial(urdf_xml):
    found = errors(run(remove_element(urdf_xml, 'wheel_front_left', 'inertial')))
    assert [(f.element, f.expected) for f in found] == [
        ("link 'wheel_front_left'", '<inertial>')]


def test_missing_collision(urdf_xml):
    findings = run(remove_element(urdf_xml, 'base_link', 'collision'))
    assert errors(findings) == []
    found = [f for f in findings if f.expected == '<collision>']
    # the chassis (5 of 7 kg) cannot touch anything: a warning
    assert [(f.severity, f.element) for f in found] == [(WARNING, "link 'base_link'")]
    # a light link on a fixed joint (a sensor frame) needs none
    light = urdf_xml.replace('</robot>', '<link name="imu_link"><inertial><mass value="0.01"/>'
                             '<inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="0" ixz="0" '
                             'iyz="0"/></inertial></link><joint name="imu_joint" type="fixed">'
                             '<parent link="base_link"/><child link="imu_link"/></joint>'
                             '</robot>')
    assert [f for f in run(light) if 'imu_link' in f.element] == []


def test_driven_wheel_without_collision_is_an_error(tmp_path, capsys, urdf_xml, controllers):
    xml = remove_element(urdf_xml, 'wheel_front_left', 'collision')
    for given in (None, controllers):  # its velocity command interface is enough
        found = [f for f in run(xml, given) if f.expected == '<collision>']
        assert [(f.severity, f.element) for f in found] == [(ERROR, "link 'wheel_front_left'")]
        assert "joint 'joint_wheel_front_left'" in found[0].message
        assert 'velocity command interface' in found[0].message
    broken = tmp_path / 'no_wheel_collision.urdf'
    broken.write_text(xml)
    assert check_model_command.main(['--controllers', YAML_PATH, str(broken)]) == 1
    out = capsys.readouterr().out
    assert "ERROR   link 'wheel_front_left': no <collision> on the link driven by joint " \
        "'joint_wheel_front_left'" in out
    assert '1 error(s)' in out
    # named as a wheel by the controllers YAML only (no command interface in the block)
    no_command = xml.replace('<command_interface name="velocity">', '<command_interface '
                             'name="position">')
    found = [f for f in run(no_command, controllers) if f.expected == '<collision>']
    assert [f.severity for f in found] == [ERROR]
    assert 'a wheel in the controllers YAML' in found[0].message
    # another moving link without collision (a caster, a flap) keeps the warning
    caster = urdf_xml.replace('</robot>', '<link name="flap"><inertial><mass value="0.1"/>'
                              '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" '
                              'iyz="0"/></inertial></link><joint name="flap_joint" '
                              'type="continuous"><parent link="base_link"/><child link="flap"/>'
                              '<axis xyz="0 0 1"/></joint></robot>')
    found = [f for f in run(caster, controllers) if f.expected == '<collision>']
    assert [(f.severity, f.element) for f in found] == [(WARNING, "link 'flap'")]


@pytest.mark.parametrize('mass', ['-0.5', '0'])
def test_non_positive_mass(urdf_xml, mass):
    # on base_link (fixed joint); on a wheel the loader itself refuses it (test_urdf_model)
    xml = edit_link(urdf_xml, 'base_link', '<mass value="5.0"/>', f'<mass value="{mass}"/>')
    found = errors(run(xml))
    assert len(found) == 1 and found[0].message == 'mass must be positive'
    assert found[0].found == f'{float(mass):g} kg'


def test_inertia_not_positive_definite(urdf_xml):
    xml = edit_link(urdf_xml, 'base_link', 'izz="0.14166666666666666"', 'izz="-0.1"')
    found = errors(run(xml))
    assert len(found) == 1 and 'positive definite' in found[0].message


def test_inertia_triangle_inequality(urdf_xml):
    # 0.0417 + 0.1083 < 0.5: positive definite but no real body has it.
    xml = edit_link(urdf_xml, 'base_link', 'izz="0.14166666666666666"', 'izz="0.5"')
    found = errors(run(xml))
    assert len(found) == 1 and 'triangle inequality' in found[0].message


def test_inertia_far_from_geometry_is_a_warning(urdf_xml):
    # Swapping the wheel's axial and diametral moments: physical, but not this cylinder.
    xml = edit_link(urdf_xml, 'wheel_front_right', 'izz="0.0025"', 'izz="0.0005"')
    findings = run(xml)
    assert errors(findings) == []
    found = warnings(findings)
    assert len(found) == 1 and 'collision geometry' in found[0].message
    assert '0.0025' in found[0].expected


def test_root_link_with_inertia_is_a_warning(urdf_xml):
    xml = urdf_xml.replace(
        '<link name="base_footprint"/>',
        '<link name="base_footprint"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>')
    found = warnings(run(xml))
    assert len(found) == 1 and 'KDL' in found[0].message


def test_closed_form_inertias():
    np.testing.assert_allclose(np.diag(links.box_inertia(5.0, (0.5, 0.3, 0.1))),
                               [5 * 0.1 / 12, 5 * 0.26 / 12, 5 * 0.34 / 12])
    np.testing.assert_allclose(np.diag(links.cylinder_inertia(0.5, 0.1, 0.04)),
                               [0.5 * 0.0316 / 12, 0.5 * 0.0316 / 12, 0.0025])
    np.testing.assert_allclose(links.sphere_inertia(2.0, 0.5), np.eye(3) * 0.2)


def test_drive_direction_closed_form():
    np.testing.assert_allclose(wheels.drive_direction((0, 1, 0)), [1, 0, 0])
    np.testing.assert_allclose(wheels.drive_direction((0, -1, 0)), [-1, 0, 0])
    np.testing.assert_allclose(wheels.drive_direction((1, 0, 0)), [0, -1, 0])
    np.testing.assert_allclose(wheels.drive_direction((0, 0, 1)), [0, 0, 0])


@pytest.mark.parametrize('key, value, words', [
    ('wheel_separation', 0.35, 'wheel_separation does not match'),
    ('wheel_radius', 0.12, 'wheel_radius does not match'),
    ('left_wheel_names', ['joint_wheel_front_left', 'joint_nope'], "'joint_nope' is not"),
])
def test_controllers_yaml_mismatch(tmp_path, urdf_xml, key, value, words):
    with open(YAML_PATH) as f:
        data = yaml.safe_load(f)
    data['/**/diff_drive_controller']['ros__parameters'][key] = value
    path = tmp_path / 'controllers.yaml'
    path.write_text(yaml.safe_dump(data))
    found = errors(run(urdf_xml, controllers_yaml.load_controllers(str(path))))
    assert len(found) == 1 and words in str(found[0]), [str(f) for f in found]


def test_separation_within_one_millimetre(urdf_xml, controllers):
    data = yaml.safe_load(yaml.safe_dump(controllers))
    data['/**/diff_drive_controller']['ros__parameters']['wheel_separation'] = 0.3009
    assert errors(run(urdf_xml, data)) == []


@pytest.mark.parametrize('multiplier, severity', [
    (4.2, WARNING), (1.0, WARNING), (2.6, INFO),
    (25.0 / 9.0, INFO)])
def test_separation_multiplier_against_coulomb_value(urdf_xml, controllers, multiplier,
                                                     severity):
    data = yaml.safe_load(yaml.safe_dump(controllers))
    params = data['/**/diff_drive_controller']['ros__parameters']
    params['wheel_separation_multiplier'] = multiplier
    found = [f for f in run(urdf_xml, data) if 'wheel_separation_multiplier' in f.message]
    assert len(found) == 1 and found[0].severity == severity, [str(f) for f in found]
    # the message names the formula and the geometry it used: a = 0.2 m, b = 0.15 m -> 2.78
    assert '(a^2 + b^2) / b^2' in found[0].message and 'a = 0.2 m' in found[0].message
    assert 'b = 0.15 m' in found[0].message
    if severity == WARNING:
        assert found[0].expected == '2.78 (+-10 %)' and found[0].found == str(multiplier)


def test_two_wheeled_base_has_no_multiplier_finding(urdf_xml, controllers):
    data = yaml.safe_load(yaml.safe_dump(controllers))
    params = data['/**/diff_drive_controller']['ros__parameters']
    params['left_wheel_names'] = ['joint_wheel_front_left']
    params['right_wheel_names'] = ['joint_wheel_front_right']
    assert not [f for f in run(urdf_xml, data) if 'wheel_separation_multiplier' in f.message]


def test_wheel_without_velocity_command_or_position_state(urdf_xml, controllers):
    old = '<joint name="joint_wheel_back_left">\n      <command_interface name="velocity">'
    assert old in urdf_xml
    xml = urdf_xml.replace(old, old.replace('velocity', 'effort'))
    xml = xml.replace('<state_interface name="position"/>', '', 1)
    found = [str(f) for f in errors(run(xml, controllers))]
    assert any('back_left' in f and 'velocity command' in f for f in found), found
    assert any('front_left' in f and 'missing position state' in f for f in found), found
    # the <mujoco> actuator of back_left now drives a joint without a velocity command
    assert any('<actuator>' in f and 'joint_wheel_back_left' in f for f in found), found


def test_mujoco_block_unknown_link(urdf_xml):
    xml = urdf_xml.replace('<link name="wheel_front_left" friction', '<link name="wheel_x" '
                           'friction')
    found = errors(run(xml))
    assert len(found) == 1 and "'wheel_x'" in found[0].found


def test_installed_copy(tmp_path):
    source = tmp_path / 'src.urdf'
    source.write_text('<robot name="a"/>')
    assert installed.compare_installed(str(source), str(source)).severity == INFO
    copy = tmp_path / 'copy.urdf'
    shutil.copy(source, copy)
    assert installed.compare_installed(str(source), str(copy)).severity == INFO
    copy.write_text('<robot name="b"/>')
    assert installed.compare_installed(str(source), str(copy)).severity == ERROR
    assert installed.compare_installed(str(source), None).severity == WARNING


def test_cli_exit_codes(tmp_path, capsys, urdf_xml):
    assert check_model_command.main(['--controllers', YAML_PATH, URDF_PATH]) == 0
    out = capsys.readouterr().out
    assert "robot 'amr', 6 links, 5 joints: 0 error(s), 0 warning(s)" in out
    broken = tmp_path / 'tutorial.urdf'
    broken.write_text(tutorial_urdf(urdf_xml))
    assert check_model_command.main(['-q', str(broken)]) == 1
    assert 'BACKWARDS' in capsys.readouterr().out
    bad = tmp_path / 'bad.urdf'
    bad.write_text('<robot name="x"><link name="a">')
    assert check_model_command.main([str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f'check_model: {bad}: not well-formed XML') and '\n' not in err
    assert check_model_command.main([str(tmp_path / 'missing.urdf')]) == 2
    assert check_model_command.main(['--controllers', str(bad), URDF_PATH]) == 2


@pytest.mark.parametrize('old, new, element, words', [
    ('<origin xyz="0 0 0.1" rpy="0 0 0"/>', '<origin xyz="0 0 nan" rpy="0 0 0"/>',
     "joint 'base_joint'", 'xyz="0 0 nan" is not finite'),
    ('<mass value="0.5"/>', '<mass value="inf"/>', "link 'wheel_front_left'",
     'value="inf" is not finite'),
    ('<joint name="base_joint" type="fixed">', '<joint name="base_joint" type="hinge">',
     "joint 'base_joint'", "unknown joint type 'hinge'"),
])
def test_cli_reports_what_the_loader_refuses(tmp_path, capsys, urdf_xml, old, new, element,
                                             words):
    bad = tmp_path / 'bad.urdf'
    bad.write_text(urdf_xml.replace(old, new, 1))
    with python_warnings.catch_warnings():
        python_warnings.simplefilter('error')  # a numpy RuntimeWarning fails the test
        assert check_model_command.main([str(bad)]) == 1
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert lines[0].startswith(f'ERROR   {element}: ') and words in lines[0], out
    assert 'wheel' not in lines[0] or 'wheel' in element
    assert lines[1] == f'{bad}: refused by the URDF loader: 1 error(s), 0 warning(s)'
    assert err == ''


def test_unknown_hardware_plugin(urdf_xml):
    assert 'amr_description/MujocoSystem' in controller_checks.hardware_plugins()
    xml = urdf_xml.replace('<plugin>amr_description/MujocoSystem</plugin>',
                           '<plugin>acme_robotics/CanBusSystem</plugin>')
    found = errors(run(xml))
    assert len(found) == 1, [str(f) for f in found]
    assert found[0].element.startswith('ros2_control ')
    assert 'unknown hardware plugin' in found[0].message
    assert found[0].found == 'acme_robotics/CanBusSystem'


@pytest.mark.parametrize('base, odom_tf, warned', [
    ('base_link', True, True), ('base_link', False, False), ('base_footprint', True, False)])
def test_odometry_frame_with_a_urdf_parent_is_a_warning(urdf_xml, controllers, base, odom_tf,
                                                        warned):
    # the tutorial's base_frame_id: base_link under a base_footprint root gives base_link two
    # TF parents (odom from diff_drive_controller, base_footprint from robot_state_publisher)
    data = yaml.safe_load(yaml.safe_dump(controllers))
    params = data['/**/diff_drive_controller']['ros__parameters']
    params['base_frame_id'] = base
    params['enable_odom_tf'] = odom_tf
    found = [f for f in warnings(run(urdf_xml, data)) if 'two parents' in f.message]
    assert len(found) == int(warned), [str(f) for f in found]
    if warned:
        assert found[0].found == "'base_link'" and found[0].expected == "'base_footprint'"
        assert 'odom -> base_link' in found[0].message
        assert 'base_footprint -> base_link' in found[0].message
