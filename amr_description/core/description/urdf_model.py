# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
A URDF kinematic tree parsed with yourdfpy, with tree queries and link poses (no rclpy).

This is the one URDF loader of the package: robot_state_publisher, joint_state_publisher,
``create`` and mujoco_sim's spawn path (through :mod:`amr_description.sim.urdf_to_mjcf`),
``render`` and ``check_model`` all load a robot through :func:`parse_urdf`, so the same robot
is accepted or refused everywhere. yourdfpy parses the elements; this module adds what
yourdfpy leaves out when it does not build a scene graph, and refuses, with one line naming
the element (:class:`URDFError`):

- a number that is not finite (``nan``, ``inf``) in any attribute of a ``<link>``,
  ``<joint>`` or ``<material>`` (origins, axes, inertia, mass, limits, dynamics, geometry,
  colours);
- two links or two joints with the same name;
- a joint type that is not one of URDF's six (revolute, continuous, prismatic, fixed,
  floating, planar);
- a joint whose parent or child link does not exist, a link that is the child of two joints,
  no single root link, joints forming a cycle;
- a zero axis on a revolute, continuous or prismatic joint;
- on a moving link (the child of a non-fixed joint), a non-positive mass or a non-positive
  principal moment (``ixx``, ``iyy``, ``izz``) in its ``<inertial>``.

A link with no ``<inertial>`` is accepted (display-only URDFs of the tutorial have none, and
upstream robot_state_publisher loads them); ``check_model`` reports it. The rest of the module:
the root link, the joint above each link, material colours and mimic-joint resolution. Poses
are 4x4 numpy matrices (see :mod:`.kinematics`).
"""

from dataclasses import dataclass
import math

from amr_description.core.kinematics import chain_transform
from amr_description.core.kinematics import mimic_position
from amr_description.core.kinematics import MOVING_JOINT_TYPES
from amr_description.core.xml_document import parse_text
from amr_description.core.xml_document import XMLError
import numpy as np


@dataclass
class RobotModel:
    """
    A parsed URDF.

    :param name: the robot name.
    :param root: name of the root link (the link that is no joint's child).
    :param links: dict link name -> yourdfpy ``Link``, document order.
    :param joints: dict joint name -> yourdfpy ``Joint``, document order.
    :param parent_joint: dict child link name -> the yourdfpy ``Joint`` above it.
    :param materials: dict material name -> rgba (numpy, 4 floats) of the top-level materials.
    :param urdf: the yourdfpy ``URDF`` object.
    :param element: the parsed ``<robot>`` element (lxml) it was read from, for readers of
        the other blocks (``<ros2_control>``, ``<gazebo>``, ``<mujoco>``) without a second parse.
    """

    name: str
    root: str
    links: dict
    joints: dict
    parent_joint: dict
    materials: dict
    urdf: object
    element: object = None

    def chain(self, link):
        """
        Return the joints from the root down to ``link``, root first (a list).

        :raises KeyError: when ``link`` is not a link of the model.
        :raises ValueError: when the joints above ``link`` form a cycle.
        """
        if link not in self.links:
            raise KeyError(link)
        joints = []
        while link in self.parent_joint:
            joint = self.parent_joint[link]
            joints.append(joint)
            if len(joints) > len(self.joints):
                raise ValueError('the joints form a cycle')
            link = joint.parent
        return joints[::-1]

    def link_pose(self, link, positions=None):
        """
        Return the pose of ``link`` in the root frame, shape (4, 4).

        :param link: link name.
        :param positions: dict joint name -> position (rad or m); missing joints are at 0,
            mimic joints follow their parent (see :meth:`resolve_mimic`).
        """
        return chain_transform(self.chain(link), self.resolve_mimic(positions or {}))

    def moving_joints(self):
        """Return the revolute, continuous and prismatic joints, document order (a list)."""
        return [j for j in self.joints.values() if j.type in MOVING_JOINT_TYPES]

    def fixed_joints(self):
        """Return the fixed joints, document order (a list)."""
        return [j for j in self.joints.values() if j.type == 'fixed']

    def resolve_mimic(self, positions):
        """
        Return ``positions`` plus the positions of mimic joints whose parent is known.

        :param positions: dict joint name -> position.
        :returns: a new dict; a mimic joint gets ``multiplier * parent + offset`` (URDF
            ``<mimic>``), overriding any value given for it.
        """
        resolved = dict(positions)
        for joint in self.joints.values():
            mimic = joint.mimic
            if mimic is not None and mimic.joint in positions:
                resolved[joint.name] = mimic_position(
                    positions[mimic.joint],
                    1.0 if mimic.multiplier is None else mimic.multiplier,
                    0.0 if mimic.offset is None else mimic.offset)
        return resolved

    def visual_rgba(self, visual):
        """Return the rgba (numpy, 4 floats) of a yourdfpy ``Visual``, or None when unset."""
        material = visual.material
        if material is None:
            return None
        if material.color is not None and material.color.rgba is not None:
            return np.asarray(material.color.rgba, dtype=float)
        return self.materials.get(material.name)


URDF_JOINT_TYPES = ('revolute', 'continuous', 'prismatic', 'fixed', 'floating', 'planar')
"""The joint types of the URDF specification (urdfdom's ``parseJoint``)."""

_TEXT_ATTRIBUTES = frozenset(('name', 'link', 'joint', 'type', 'filename', 'reference'))
"""Attributes holding names or paths, never numbers (skipped by the non-finite scan)."""


class URDFError(ValueError):
    """
    A URDF the loader refuses: one line ``<source>: <element>: <problem>``.

    :param source: the file path or parameter name the URDF came from.
    :param element: the element holding the problem, e.g. ``"joint 'base_joint'"``, or ''
        when it is about the whole document.
    :param problem: what is wrong, one line.
    """

    def __init__(self, source, element, problem):
        """Store the parts; the message is ``source: element: problem``."""
        self.source = source
        self.element = element
        self.problem = problem
        parts = [source, element, problem] if element else [source, problem]
        super().__init__(': '.join(parts))


def _one_line(text):
    """Return ``text`` collapsed onto a single line."""
    return ' '.join(str(text).split())


def _non_finite(value):
    """Return True when a whitespace-separated token of ``value`` is a non-finite number."""
    for token in value.split():
        try:
            number = float(token)
        except ValueError:
            continue
        if not math.isfinite(number):
            return True
    return False


def _check_elements(root_element, source):
    """
    Check the document before yourdfpy reads it (names, joint types, non-finite numbers).

    :raises URDFError: on a duplicate link/joint name, an unknown joint type, or an attribute
        holding a non-finite number (naming the ``<link>``/``<joint>``/``<material>`` that
        holds it and the attribute).
    """
    seen = {'link': set(), 'joint': set()}
    for element in root_element:
        kind = element.tag
        if kind not in ('link', 'joint', 'material'):
            continue
        name = element.get('name')
        owner = f'{kind} {name!r}'
        if kind in seen and name is not None:
            if name in seen[kind]:
                raise URDFError(source, owner, f'duplicate {kind} name')
            seen[kind].add(name)
        if kind == 'joint':
            joint_type = element.get('type')
            if joint_type not in URDF_JOINT_TYPES:
                raise URDFError(source, owner, f'unknown joint type {joint_type!r} (expected '
                                f'one of {", ".join(URDF_JOINT_TYPES)})')
        for node in element.iter():
            if not isinstance(node.tag, str):
                continue  # comments, processing instructions
            for attribute, value in node.attrib.items():
                if attribute in _TEXT_ATTRIBUTES or not _non_finite(value):
                    continue
                where = '' if node is element else f'<{node.tag}> '
                raise URDFError(source, owner, f'{where}{attribute}="{_one_line(value)}" '
                                'is not finite (expected finite numbers)')


def _check_moving_links(model, source):
    """
    Check the ``<inertial>`` of every moving link (the child of a non-fixed joint).

    :raises URDFError: when its mass or a principal moment ixx/iyy/izz is not positive.
    """
    for joint in model.joints.values():
        if joint.type == 'fixed':
            continue
        inertial = model.links[joint.child].inertial
        if inertial is None:
            continue
        owner = f'link {joint.child!r}'
        mass = inertial.mass
        if mass is None or not float(mass) > 0.0:
            raise URDFError(source, owner, f'<inertial> mass must be positive on a link moved '
                            f'by joint {joint.name!r}, found {mass}')
        inertia = np.asarray(inertial.inertia, dtype=float)
        for axis, index in (('ixx', 0), ('iyy', 1), ('izz', 2)):
            if not inertia[index, index] > 0.0:
                raise URDFError(source, owner, f'<inertial> {axis} must be positive on a link '
                                f'moved by joint {joint.name!r}, found {inertia[index, index]:g}')


def entity_name(name, urdf_xml):
    """
    Return the name a simulator gives a spawned robot: ``name``, else the ``<robot>`` name.

    :param name: the requested entity name ('' for none).
    :param urdf_xml: the URDF, str or bytes (only read when ``name`` is empty).
    :returns: the name, a non-empty str.
    :raises ValueError: the URDF is not well-formed XML, or neither names the robot.
    """
    if name:
        return name
    try:
        name = parse_text(urdf_xml).get('name') or ''
    except XMLError as exc:
        raise ValueError(f'URDF is not well-formed XML: {exc}') from None
    if not name:
        raise ValueError('no entity name given and the URDF <robot> has no name')
    return name


def parse_xml(urdf_xml, source='robot_description'):
    """
    Parse a URDF document's XML once: the ``<robot>`` element, comments removed.

    The parser is the package's one (:mod:`amr_description.core.xml_document`: lxml, as
    yourdfpy's ``URDF.load``, blank text removed), so the element can be handed to yourdfpy
    without a second parse.

    :param urdf_xml: the URDF, str or bytes.
    :param source: what to name in error messages (a file path or parameter name).
    :returns: the lxml ``<robot>`` element.
    :raises URDFError: empty document, malformed XML, another root element, no robot name.
    """
    if isinstance(urdf_xml, str):
        urdf_xml = urdf_xml.encode('utf-8')
    if not urdf_xml.strip():
        raise URDFError(source, '', 'empty URDF')
    try:
        root_element = parse_text(urdf_xml, remove_blank_text=True)
    except XMLError as exc:
        raise URDFError(source, '', f'not well-formed XML: {_one_line(exc)}') from None
    if root_element.tag != 'robot':
        raise URDFError(source, '', f'root element must be <robot>, found <{root_element.tag}>')
    if not root_element.get('name'):
        raise URDFError(source, '<robot>', 'no name attribute')
    return root_element


def parse_urdf(urdf_xml, source='robot_description'):
    """
    Parse a URDF document into a :class:`RobotModel`.

    :param urdf_xml: the URDF, str or bytes.
    :param source: what to name in error messages (a file path or parameter name).
    :returns: the :class:`RobotModel`.
    :raises URDFError: (a ValueError) one line naming ``source`` and the element when the
        XML is malformed, yourdfpy rejects an element, or a rule of the module docstring is
        broken.
    """
    return model_from_element(parse_xml(urdf_xml, source), source)


def model_from_element(root_element, source='robot_description'):
    """
    Return the :class:`RobotModel` of a ``<robot>`` element from :func:`parse_xml`.

    :raises URDFError: as :func:`parse_urdf`, for everything after the XML parse.
    """
    _check_elements(root_element, source)
    # imported here, not at module level: it pulls in trimesh (~1 s), whose imports swallow
    # exceptions, so a Ctrl-C during a node's start-up must reach it only after main()
    # installed the clean-shutdown signal handling (amr_description.ros.shutdown)
    import yourdfpy
    try:
        # what yourdfpy's URDF.load does after its own parse (same parser options)
        urdf = yourdfpy.URDF(robot=yourdfpy.URDF._parse_robot(xml_element=root_element),
                             build_scene_graph=False, load_meshes=False)
    except Exception as exc:  # yourdfpy raises KeyError/ValueError/AttributeError alike
        kind = type(exc).__name__
        raise URDFError(source, '', f'invalid URDF ({kind}: {_one_line(exc)})') from None
    robot = urdf.robot
    links = {link.name: link for link in robot.links}
    joints = {joint.name: joint for joint in robot.joints}
    if not links:
        raise URDFError(source, '', 'the robot has no links')
    if len(links) != len(robot.links):
        raise URDFError(source, '', 'duplicate link names')
    if len(joints) != len(robot.joints):
        raise URDFError(source, '', 'duplicate joint names')
    parent_joint = {}
    for joint in robot.joints:
        for role, link in (('parent', joint.parent), ('child', joint.child)):
            if link not in links:
                raise URDFError(source, f'joint {joint.name!r}',
                                f'{role} link {link!r} does not exist')
        if joint.child in parent_joint:
            raise URDFError(source, f'link {joint.child!r}', 'is the child of two joints')
        if joint.type in MOVING_JOINT_TYPES and (
                joint.axis is None or not np.any(joint.axis)):
            raise URDFError(source, f'joint {joint.name!r}', 'zero axis')
        parent_joint[joint.child] = joint
    roots = [name for name in links if name not in parent_joint]
    if len(roots) != 1:
        found = ', '.join(roots) if roots else 'none (a cycle)'
        raise URDFError(source, '', f'expected exactly one root link, found {found}')
    model = RobotModel(
        name=robot.name, root=roots[0], links=links, joints=joints,
        parent_joint=parent_joint,
        materials={m.name: np.asarray(m.color.rgba, dtype=float) for m in robot.materials
                   if m.color is not None and m.color.rgba is not None},
        urdf=urdf, element=root_element)
    for link in links:
        try:
            model.chain(link)
        except ValueError:
            raise URDFError(source, f'link {link!r}', 'the joints above it form a cycle') from None
    _check_moving_links(model, source)
    return model


def parse_urdf_file(path):
    """
    Read and parse a URDF file (a ``.xacro`` file is expanded first).

    :param path: file path, ``package://`` or ``$(find pkg)`` URI.
    :returns: ``(urdf_xml str, RobotModel)``.
    :raises ValueError: one line naming ``path`` when the file cannot be read or parsed.
    """
    from amr_description.core.description.files import read_description
    try:
        text = read_description(path)
    except ValueError as exc:
        raise URDFError(path, '', str(exc).partition(f'{path}: ')[2] or str(exc)) from None
    return text, parse_urdf(text, source=path)
