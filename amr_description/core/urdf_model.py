# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
A URDF kinematic tree parsed with yourdfpy, with tree queries and link poses (no rclpy).

yourdfpy parses the elements; this module adds what yourdfpy leaves out when it does not
build a scene graph: the root link, the joint above each link, the checks that make a tree
(one root, every parent/child link exists, no link with two parents), material colours and
mimic-joint resolution. Poses are 4x4 numpy matrices (see :mod:`.kinematics`).
"""

from dataclasses import dataclass
import io

from lxml import etree
import numpy as np

from .kinematics import chain_transform
from .kinematics import mimic_position
from .kinematics import MOVING_JOINT_TYPES


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
    """

    name: str
    root: str
    links: dict
    joints: dict
    parent_joint: dict
    materials: dict
    urdf: object

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


def _one_line(text):
    """Return ``text`` collapsed onto a single line."""
    return ' '.join(str(text).split())


def parse_urdf(urdf_xml, source='robot_description'):
    """
    Parse a URDF document into a :class:`RobotModel`.

    :param urdf_xml: the URDF, str or bytes.
    :param source: what to name in error messages (a file path or parameter name).
    :returns: the :class:`RobotModel`.
    :raises ValueError: one line naming ``source`` when the XML is malformed, yourdfpy rejects
        an element, or the links and joints do not form one tree.
    """
    if isinstance(urdf_xml, str):
        urdf_xml = urdf_xml.encode('utf-8')
    if not urdf_xml.strip():
        raise ValueError(f'{source}: empty URDF')
    try:
        root_element = etree.fromstring(urdf_xml)
    except etree.XMLSyntaxError as exc:
        raise ValueError(f'{source}: not well-formed XML: {_one_line(exc)}') from None
    if root_element.tag != 'robot':
        raise ValueError(f'{source}: root element must be <robot>, found <{root_element.tag}>')
    if not root_element.get('name'):
        raise ValueError(f'{source}: <robot> has no name attribute')
    # imported here, not at module level: it pulls in trimesh (~1 s), whose imports swallow
    # exceptions, so a Ctrl-C during a node's start-up must reach it only after main()
    # installed the clean-shutdown signal handling (amr_description.nodes.shutdown)
    import yourdfpy
    try:
        urdf = yourdfpy.URDF.load(
            io.BytesIO(urdf_xml), build_scene_graph=False, load_meshes=False)
    except Exception as exc:  # yourdfpy raises KeyError/ValueError/AttributeError alike
        kind = type(exc).__name__
        raise ValueError(f'{source}: invalid URDF ({kind}: {_one_line(exc)})') from None
    robot = urdf.robot
    links = {link.name: link for link in robot.links}
    joints = {joint.name: joint for joint in robot.joints}
    if not links:
        raise ValueError(f'{source}: the robot has no links')
    if len(links) != len(robot.links):
        raise ValueError(f'{source}: duplicate link names')
    if len(joints) != len(robot.joints):
        raise ValueError(f'{source}: duplicate joint names')
    parent_joint = {}
    for joint in robot.joints:
        for role, link in (('parent', joint.parent), ('child', joint.child)):
            if link not in links:
                raise ValueError(
                    f'{source}: joint {joint.name!r} {role} link {link!r} does not exist')
        if joint.child in parent_joint:
            raise ValueError(f'{source}: link {joint.child!r} is the child of two joints')
        if joint.type in MOVING_JOINT_TYPES and (
                joint.axis is None or not np.any(joint.axis)):
            raise ValueError(f'{source}: joint {joint.name!r} has a zero axis')
        parent_joint[joint.child] = joint
    roots = [name for name in links if name not in parent_joint]
    if len(roots) != 1:
        found = ', '.join(roots) if roots else 'none (a cycle)'
        raise ValueError(f'{source}: expected exactly one root link, found {found}')
    model = RobotModel(
        name=robot.name, root=roots[0], links=links, joints=joints,
        parent_joint=parent_joint,
        materials={m.name: np.asarray(m.color.rgba, dtype=float) for m in robot.materials
                   if m.color is not None and m.color.rgba is not None},
        urdf=urdf)
    for link in links:
        try:
            model.chain(link)
        except ValueError:
            raise ValueError(f'{source}: the joints above link {link!r} form a cycle') from None
    return model


def parse_urdf_file(path):
    """
    Read and parse a URDF file.

    :param path: file path.
    :returns: ``(urdf_xml str, RobotModel)``.
    :raises ValueError: one line naming ``path`` when the file cannot be read or parsed.
    """
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as exc:
        raise ValueError(f'{path}: cannot read: {exc.strerror}') from None
    return data.decode('utf-8', errors='replace'), parse_urdf(data, source=path)
