# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The one URDF loader refuses each broken robot with one line naming the element."""

import os

from amr_description.core.description.urdf_model import parse_urdf
from amr_description.core.description.urdf_model import parse_urdf_file
from amr_description.core.description.urdf_model import URDFError
import pytest

URDF_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'urdf',
                         'amr.urdf')


@pytest.fixture(scope='module')
def urdf_xml():
    with open(URDF_PATH) as f:
        return f.read()


def block(xml, kind, name):
    """Return (start, end) of the ``<kind name="name" ...>...</kind>`` element."""
    start = xml.index(f'<{kind} name="{name}"')
    return start, xml.index(f'</{kind}>', start) + len(f'</{kind}>')


def edit(xml, kind, name, old, new):
    """Replace ``old`` by ``new`` once inside one element."""
    start, end = block(xml, kind, name)
    text = xml[start:end]
    assert old in text, (old, text)
    return xml[:start] + text.replace(old, new, 1) + xml[end:]


def refused(xml):
    """Return the URDFError the loader raises for ``xml`` (fails when it accepts it)."""
    with pytest.raises(URDFError) as info:
        parse_urdf(xml, source='amr.urdf')
    message = str(info.value)
    assert '\n' not in message and message.startswith('amr.urdf: '), message
    return info.value


def test_shipped_urdf_loads(urdf_xml):
    model = parse_urdf(urdf_xml)
    assert model.root == 'base_footprint'
    assert len(model.links) == 6 and len(model.joints) == 5


@pytest.mark.parametrize('kind, name, old, new, where', [
    # origin of a fixed joint: the error names that joint, not its children
    ('joint', 'base_joint', 'xyz="0 0 ', 'xyz="nan 0 ', "joint 'base_joint'"),
    ('joint', 'joint_wheel_front_left', 'rpy="-1.5708 0 0"', 'rpy="-inf 0 0"',
     "joint 'joint_wheel_front_left'"),
    ('joint', 'joint_wheel_back_right', '<axis xyz="0 0 1"', '<axis xyz="0 0 NaN"',
     "joint 'joint_wheel_back_right'"),
    ('link', 'wheel_front_right', '<mass value="0.5"/>', '<mass value="inf"/>',
     "link 'wheel_front_right'"),
    ('link', 'base_link', 'izz="0.14166666666666666"', 'izz="Infinity"', "link 'base_link'"),
    ('link', 'wheel_back_left', 'radius="0.1"', 'radius="nan"', "link 'wheel_back_left'"),
    ('link', 'base_link', 'size="0.5 0.3 0.1"', 'size="0.5 inf 0.1"', "link 'base_link'"),
])
def test_non_finite_number_names_its_element(urdf_xml, kind, name, old, new, where):
    error = refused(edit(urdf_xml, kind, name, old, new))
    assert error.element == where
    assert 'not finite' in error.problem


def test_non_finite_limit(urdf_xml):
    xml = edit(urdf_xml, 'joint', 'joint_wheel_front_left', '<axis xyz="0 0 1"/>',
               '<axis xyz="0 0 1"/><limit effort="nan" velocity="10"/>')
    error = refused(xml)
    assert error.element == "joint 'joint_wheel_front_left'"
    assert '<limit> effort="nan"' in error.problem


def test_names_holding_nan_are_not_numbers(urdf_xml):
    # a link called "nan" is a name, not a number
    xml = urdf_xml.replace('"wheel_front_left"', '"nan"')
    assert 'nan' in parse_urdf(xml).links


@pytest.mark.parametrize('kind', ['link', 'joint'])
def test_duplicate_names(urdf_xml, kind):
    name = 'wheel_back_left' if kind == 'link' else 'joint_wheel_back_left'
    start, end = block(urdf_xml, kind, name)
    copy = urdf_xml[start:end]
    if kind == 'joint':
        copy = copy.replace('<child link="wheel_back_left"/>', '<child link="wheel_x"/>')
        xml = urdf_xml[:end] + '<link name="wheel_x"/>' + copy + urdf_xml[end:]
    else:
        xml = urdf_xml[:end] + copy + urdf_xml[end:]
    error = refused(xml)
    assert error.element == f'{kind} {name!r}'
    assert error.problem == f'duplicate {kind} name'


def test_unknown_joint_type(urdf_xml):
    xml = urdf_xml.replace('<joint name="base_joint" type="fixed">',
                           '<joint name="base_joint" type="hinge">')
    error = refused(xml)
    assert error.element == "joint 'base_joint'"
    assert "unknown joint type 'hinge'" in error.problem


def test_missing_link(urdf_xml):
    xml = edit(urdf_xml, 'joint', 'joint_wheel_front_left', 'child link="wheel_front_left"',
               'child link="ghost"')
    error = refused(xml)
    assert error.element == "joint 'joint_wheel_front_left'"
    assert "child link 'ghost' does not exist" in error.problem


def test_cycle(urdf_xml):
    # base_link becomes the child of its own wheel: base_footprint is left alone as the root
    xml = urdf_xml.replace('<parent link="base_footprint"/>', '<parent link="wheel_back_left"/>')
    error = refused(xml)
    assert error.problem == 'the joints above it form a cycle'
    # and a two-link loop with no root at all
    xml = ('<robot name="r"><link name="a"/><link name="b"/>'
           '<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>'
           '<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>')
    assert 'none (a cycle)' in refused(xml).problem


def test_two_parents(urdf_xml):
    xml = edit(urdf_xml, 'joint', 'joint_wheel_front_left', 'child link="wheel_front_left"',
               'child link="wheel_back_left"')
    assert 'child of two joints' in str(refused(xml))


@pytest.mark.parametrize('old, new, words', [
    ('<mass value="0.5"/>', '<mass value="0"/>', 'mass must be positive'),
    ('<mass value="0.5"/>', '<mass value="-0.5"/>', 'mass must be positive'),
    ('izz="0.0025"', 'izz="0"', 'izz must be positive'),
    ('ixx="', 'ixx="-', 'ixx must be positive'),
])
def test_non_positive_inertia_on_a_moving_link(urdf_xml, old, new, words):
    error = refused(edit(urdf_xml, 'link', 'wheel_front_right', old, new))
    assert error.element == "link 'wheel_front_right'"
    assert words in error.problem and "joint 'joint_wheel_front_right'" in error.problem


def test_non_positive_mass_on_a_fixed_link_is_left_to_check_model(urdf_xml):
    # base_link hangs on a fixed joint: robot_state_publisher can show it
    xml = edit(urdf_xml, 'link', 'base_link', '<mass value="5.0"/>', '<mass value="0"/>')
    assert parse_urdf(xml).links['base_link'].inertial.mass == 0.0


def test_link_without_inertial_is_accepted():
    xml = ('<robot name="r"><link name="a"/><link name="b"/>'
           '<joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
           '<axis xyz="0 0 1"/></joint></robot>')
    assert parse_urdf(xml).root == 'a'


def test_zero_axis(urdf_xml):
    xml = edit(urdf_xml, 'joint', 'joint_wheel_front_left', '<axis xyz="0 0 1"/>',
               '<axis xyz="0 0 0"/>')
    assert refused(xml).element == "joint 'joint_wheel_front_left'"


@pytest.mark.parametrize('xml, words', [
    ('', 'empty URDF'),
    ('<robot name="x"><link name="a">', 'not well-formed XML'),
    ('<robt name="x"/>', 'root element must be <robot>'),
])
def test_not_a_urdf(xml, words):
    error = refused(xml)
    assert error.element == '' and words in error.problem


def test_file_errors_name_the_file(tmp_path):
    with pytest.raises(URDFError, match='missing.urdf: cannot read'):
        parse_urdf_file(str(tmp_path / 'missing.urdf'))


def test_entity_name():
    from amr_description.core.description.urdf_model import entity_name
    assert entity_name('r1', '<not xml') == 'r1'
    assert entity_name('', '<robot name="amr"><link name="a"/></robot>') == 'amr'
    assert entity_name('', b'<?xml version="1.0"?><robot name="b"/>') == 'b'
    with pytest.raises(ValueError, match='not well-formed XML'):
        entity_name('', '<robot')
    with pytest.raises(ValueError, match='has no name'):
        entity_name('', '<robot/>')
