# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Model checks beyond ``check_urdf``: physics, drive wheels, ros2_control and controllers.yaml.

``check_urdf`` (urdfdom) only proves the file parses into a tree. The checks here catch what
makes a robot fall through the floor, explode, or drive backwards in simulation:

- every non-root link has ``<collision>`` and ``<inertial>``; mass > 0; the inertia matrix is
  symmetric positive definite and its principal moments obey the triangle inequality
  (``I1 + I2 >= I3``, true of every real body); it is close to what the collision geometry and
  mass imply (solid box / cylinder / sphere formulas; warning only); a root link with inertia
  is flagged (KDL, hence robot_state_publisher, ignores it: warning);
- drive wheels: positive wheel speed must roll the base forward. With the axle ``a`` (the
  joint axis rotated into the base frame, ``R(rpy) @ axis``) and the wheel touching the ground
  below its centre, rolling without slipping moves the centre with ``v = w a x r`` where
  ``r = +z`` points from the contact to the centre, so the drive direction is ``a x z`` and
  forward needs ``(a x z) . x = a_y > 0``: the axle must point along base +y;
- the document itself goes through the package's one loader
  (:func:`amr_description.core.urdf_model.parse_urdf`): what it refuses (non-finite numbers,
  duplicate names, unknown joint types, broken trees, non-positive inertia on moving links)
  is an error naming the element that holds it, and no other check runs;
- every ``<ros2_control>`` ``<hardware><plugin>`` is a hardware plugin the package registers
  (entry-point group ``amr_description.hardware``, what mujoco_sim loads);
- the ``<ros2_control>`` block against controllers.yaml (ros2_control format): every wheel of
  ``diff_drive_controller`` is a joint of the block with a velocity command interface and
  position and velocity state interfaces; ``wheel_separation`` and ``wheel_radius`` match the
  URDF geometry within 1 mm;
- the ``<mujoco>`` simulator block (docs/architecture.md) names existing links and joints;
- the installed URDF (``share/amr_description/urdf``) is the source file or equal to it.

Pure logic except :func:`main` (the ``check_model`` command) and the optional ament index
lookup of the installed copy.
"""

import argparse
from dataclasses import dataclass
import filecmp
import os
import sys

from amr_description.core.mujoco_block import parse_mujoco_block
from amr_description.core.ros2_control_info import parse_ros2_control
from amr_description.core.urdf_model import parse_urdf_file
from amr_description.core.urdf_model import URDFError
from lxml import etree
import numpy as np
import yaml

ERROR = 'error'
WARNING = 'warning'
INFO = 'ok'
DIFF_DRIVE_TYPE = 'diff_drive_controller/DiffDriveController'
HARDWARE_GROUP = 'amr_description.hardware'
GEOMETRY_TOLERANCE = 1e-3  # m, wheel_separation and wheel_radius against the URDF
INERTIA_TOLERANCE = 0.1  # relative Frobenius distance tolerated from the geometric inertia


@dataclass
class Finding:
    """
    One result of a check.

    :param severity: ``'error'``, ``'warning'`` or ``'ok'`` (a passed check worth reporting).
    :param element: what it is about, e.g. ``"link 'base_link'"`` or ``"joint 'j'"``.
    :param message: what is wrong (or right), one line.
    :param expected: the expected value, as text ('' when not applicable).
    :param found: the value found, as text ('' when not applicable).
    """

    severity: str
    element: str
    message: str
    expected: str = ''
    found: str = ''

    def __str__(self):
        """Return the one-line report form of the finding."""
        text = f'{self.severity.upper():7} {self.element}: {self.message}'
        if self.expected or self.found:
            text += f' (expected {self.expected}, found {self.found})'
        return text


def _vec(v, digits=4):
    """Format a vector compactly, e.g. ``(0, 1, 0)``."""
    return '(' + ', '.join(f'{round(float(x), digits) + 0.0:g}' for x in v) + ')'


def _origin(origin):
    """Return a 4x4 matrix for a yourdfpy origin (None = identity)."""
    return np.eye(4) if origin is None else np.asarray(origin, dtype=float)


# ---------------------------------------------------------------------------------------------
# Inertia
# ---------------------------------------------------------------------------------------------

def box_inertia(mass, size):
    """
    Return the 3x3 inertia (kg m^2) of a solid box about its centre, box axes.

    :param mass: kg.
    :param size: (x, y, z) edge lengths, m.
    :returns: ``diag(m (y^2+z^2), m (x^2+z^2), m (x^2+y^2)) / 12``.
    """
    x, y, z = (float(v) for v in size)
    return np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * mass / 12.0


def cylinder_inertia(mass, radius, length):
    """
    Return the 3x3 inertia (kg m^2) of a solid cylinder about its centre, axis along z.

    :returns: ``diag(m (3 r^2 + h^2) / 12, same, m r^2 / 2)``.
    """
    side = mass * (3.0 * radius * radius + length * length) / 12.0
    return np.diag([side, side, mass * radius * radius / 2.0])


def sphere_inertia(mass, radius):
    """Return the 3x3 inertia (kg m^2) of a solid sphere: ``2/5 m r^2`` on the diagonal."""
    return np.eye(3) * 0.4 * mass * radius * radius


def geometry_inertia(geometry, mass):
    """
    Return the inertia of a yourdfpy ``Geometry`` primitive about its own frame, or None.

    :param geometry: yourdfpy ``Geometry`` (box, cylinder or sphere; meshes give None).
    :param mass: kg.
    :returns: 3x3 numpy array (kg m^2) or None.
    """
    if geometry is None:
        return None
    if geometry.box is not None:
        return box_inertia(mass, geometry.box.size)
    if geometry.cylinder is not None:
        return cylinder_inertia(mass, geometry.cylinder.radius, geometry.cylinder.length)
    if geometry.sphere is not None:
        return sphere_inertia(mass, geometry.sphere.radius)
    return None


def inertia_problems(inertia):
    """
    Return why a 3x3 inertia matrix is not physical, or [] when it is.

    :param inertia: 3x3 array, kg m^2.
    :returns: list of (message, expected, found) tuples: not symmetric, not positive definite
        (eigenvalues), principal moments breaking the triangle inequality.
    """
    inertia = np.asarray(inertia, dtype=float)
    problems = []
    if not np.allclose(inertia, inertia.T):
        problems.append(('inertia matrix is not symmetric', 'I == I^T', 'asymmetric'))
        return problems
    moments = np.linalg.eigvalsh(inertia)
    if moments[0] <= 0.0:
        problems.append(('inertia is not positive definite', 'principal moments > 0',
                         _vec(moments, 8)))
        return problems
    tolerance = 1e-9 * moments.sum()
    if moments[0] + moments[1] < moments[2] - tolerance:
        problems.append(('principal moments break the triangle inequality',
                         'I1 + I2 >= I3', _vec(moments, 8)))
    return problems


def check_links(model):
    """
    Check collision, inertial, mass and inertia of every link.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :returns: list of :class:`Finding`.
    """
    findings = []
    for name, link in model.links.items():
        element = f'link {name!r}'
        inertial = link.inertial
        if name == model.root:
            if inertial is not None and inertial.mass:
                findings.append(Finding(
                    WARNING, element,
                    'root link has an inertia, which KDL (robot_state_publisher) ignores; '
                    'add a dummy root link such as base_footprint', 'no <inertial>',
                    f'mass {inertial.mass:g} kg'))
            continue
        if not link.collisions:
            findings.append(Finding(ERROR, element, 'no <collision>: it cannot touch anything',
                                    '<collision>', 'none'))
        if inertial is None:
            findings.append(Finding(ERROR, element, 'no <inertial>: simulators drop the link',
                                    '<inertial>', 'none'))
            continue
        mass = inertial.mass if inertial.mass is not None else 0.0
        if mass <= 0.0:
            findings.append(Finding(ERROR, element, 'mass must be positive', 'mass > 0 kg',
                                    f'{mass:g} kg'))
            continue
        if inertial.inertia is None:
            findings.append(Finding(ERROR, element, 'no <inertia>', '<inertia>', 'none'))
            continue
        problems = inertia_problems(inertial.inertia)
        for message, expected, found in problems:
            findings.append(Finding(ERROR, element, message, expected, found))
        if not problems:
            findings.extend(_compare_geometry_inertia(element, link, mass))
    return findings


def _compare_geometry_inertia(element, link, mass):
    """Warn when a link's inertia is far from that of its single collision primitive."""
    if len(link.collisions) != 1:
        return []
    collision = link.collisions[0]
    body = geometry_inertia(collision.geometry, mass)
    if body is None:
        return []
    inertial = link.inertial
    T_inertial = _origin(inertial.origin)
    T_geometry = _origin(collision.origin)
    # Geometry inertia expressed in the inertial frame, about the inertial frame's origin
    # (parallel-axis theorem for an offset centre).
    T = np.linalg.inv(T_inertial) @ T_geometry
    R, d = T[:3, :3], T[:3, 3]
    expected = R @ body @ R.T + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))
    found = np.asarray(inertial.inertia, dtype=float)
    distance = np.linalg.norm(found - expected) / np.linalg.norm(expected)
    if distance > INERTIA_TOLERANCE:
        return [Finding(
            WARNING, element,
            f'inertia is {distance:.0%} away from that of its collision geometry and mass',
            'ixx iyy izz ~ ' + _vec(np.diag(expected), 6),
            'ixx iyy izz = ' + _vec(np.diag(found), 6))]
    return []


# ---------------------------------------------------------------------------------------------
# Drive wheels
# ---------------------------------------------------------------------------------------------

def drive_direction(axle):
    """
    Return the base velocity direction of positive wheel speed for an axle direction.

    :param axle: wheel axle (joint axis) in the base frame, 3 floats, REP 103 (z up).
    :returns: ``a x z`` normalized (numpy, 3 floats): the direction the wheel centre moves
        when the wheel turns positively while rolling on the ground below it; zero when the
        axle is vertical (the wheel cannot roll).
    """
    a = np.asarray(axle, dtype=float)
    a = a / np.linalg.norm(a)
    d = np.cross(a, [0.0, 0.0, 1.0])
    n = np.linalg.norm(d)
    return d / n if n > 1e-9 else np.zeros(3)


def wheel_radius(model, link_name, axis=None):
    """
    Return the wheel radius (m) of a link from its collision (else visual) geometry.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param link_name: the wheel link.
    :param axis: unused; kept for symmetry with the joint axis checks.
    :returns: the radius of the first cylinder or sphere, or None when there is none.
    """
    link = model.links[link_name]
    for element in list(link.collisions) + list(link.visuals):
        geometry = element.geometry
        if geometry is None:
            continue
        if geometry.cylinder is not None:
            return float(geometry.cylinder.radius)
        if geometry.sphere is not None:
            return float(geometry.sphere.radius)
    return None


def wheel_joints(model, controllers=None):
    """
    Return the names of the drive wheel joints.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param controllers: parsed controllers.yaml (dict) or None.
    :returns: the ``left_wheel_names + right_wheel_names`` of every diff_drive_controller in
        ``controllers`` that are URDF joints; without controllers, every continuous joint
        whose child link has a cylinder or sphere.
    """
    names = []
    for params in diff_drive_params(controllers or {}).values():
        for key in ('left_wheel_names', 'right_wheel_names'):
            names.extend(n for n in params.get(key) or [] if n in model.joints)
    if names or controllers:
        return list(dict.fromkeys(names))
    return [j.name for j in model.joints.values()
            if j.type == 'continuous' and wheel_radius(model, j.child) is not None]


def axle_in_frame(model, joint_name, frame):
    """
    Return a joint's axis expressed in link ``frame`` at zero joint positions.

    :returns: unit vector (numpy, 3 floats): ``R_frame^T R_parent R_origin axis``.
    """
    joint = model.joints[joint_name]
    T_parent = np.linalg.inv(model.link_pose(frame)) @ model.link_pose(joint.parent)
    R = (T_parent @ _origin(joint.origin))[:3, :3]
    a = R @ np.asarray(joint.axis, dtype=float)
    return a / np.linalg.norm(a)


def joint_position_in_frame(model, joint_name, frame):
    """Return the position (m, numpy 3) of a joint's frame in link ``frame`` at zero."""
    joint = model.joints[joint_name]
    T = np.linalg.inv(model.link_pose(frame)) @ model.link_pose(joint.parent)
    return (T @ _origin(joint.origin))[:3, 3]


def check_wheels(model, joints, base_frame):
    """
    Check that positive speed of each drive wheel rolls the base forward.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param joints: wheel joint names.
    :param base_frame: the base link (REP 105 ``base_link``; the root when absent).
    :returns: list of :class:`Finding`.
    """
    if base_frame not in model.links:
        base_frame = model.root
    findings = []
    for name in joints:
        joint = model.joints[name]
        element = f'joint {name!r}'
        if joint.type not in ('continuous', 'revolute'):
            findings.append(Finding(ERROR, element, 'a drive wheel joint must rotate',
                                    'continuous', joint.type))
            continue
        axle = axle_in_frame(model, name, base_frame)
        direction = drive_direction(axle)
        expected = f'axle along +y in {base_frame} (drives +x)'
        found = f'axle {_vec(axle)} drives {_vec(direction)}'
        if direction[0] > 0.7:
            findings.append(Finding(INFO, element, 'positive wheel speed drives forward'))
        elif direction[0] < -0.7:
            findings.append(Finding(
                ERROR, element, 'positive wheel speed drives the base BACKWARDS '
                '(reversed axle, e.g. rpy="1.5708 0 0" with axis "0 0 1")', expected, found))
        elif not direction.any():
            findings.append(Finding(ERROR, element, 'vertical axle: the wheel cannot roll',
                                    expected, found))
        else:
            findings.append(Finding(ERROR, element, 'positive wheel speed drives the base '
                                    'sideways', expected, found))
        radius = wheel_radius(model, joint.child)
        if radius is None:
            findings.append(Finding(ERROR, f'link {joint.child!r}',
                                    'wheel has no cylinder or sphere geometry', 'radius',
                                    'none'))
        else:
            findings.extend(_check_cylinder_axis(model, joint))
    return findings


def _check_cylinder_axis(model, joint):
    """Warn when a wheel cylinder's axis is not along the joint axis (it would not roll)."""
    link = model.links[joint.child]
    for collision in link.collisions:
        if collision.geometry is not None and collision.geometry.cylinder is not None:
            cyl_axis = _origin(collision.origin)[:3, :3] @ [0.0, 0.0, 1.0]
            axis = np.asarray(joint.axis, dtype=float)
            cosine = abs(cyl_axis @ axis) / np.linalg.norm(axis)
            if cosine < 0.99:
                return [Finding(WARNING, f'link {joint.child!r}',
                                'wheel cylinder axis is not along the joint axis',
                                _vec(axis), _vec(cyl_axis))]
    return []


# ---------------------------------------------------------------------------------------------
# ros2_control and controllers.yaml
# ---------------------------------------------------------------------------------------------

def node_parameters(controllers, name):
    """
    Return the ``ros__parameters`` of node ``name`` in a parameter file, or None.

    The section may be keyed by the plain name, the root-namespace name (``/name``) or the
    any-namespace wildcard (``/**/name``, what namespaced robots need, as upstream).

    :param controllers: the parsed YAML (dict).
    :param name: node name without namespace.
    """
    for key in (name, '/' + name, '/**/' + name):
        section = controllers.get(key)
        if isinstance(section, dict):
            return section.get('ros__parameters')
    return None


def diff_drive_params(controllers):
    """
    Return the ros__parameters of every diff_drive_controller in a controllers.yaml.

    :param controllers: the parsed YAML (dict), ros2_control format.
    :returns: dict controller name -> its ``ros__parameters`` dict (empty when absent).
    """
    cm = node_parameters(controllers, 'controller_manager') or {}
    result = {}
    for name, value in cm.items():
        if isinstance(value, dict) and value.get('type') == DIFF_DRIVE_TYPE:
            result[name] = dict(node_parameters(controllers, name) or {})
    return result


def hardware_plugins():
    """
    Return the hardware plugin names the installed package registers (a set).

    :returns: the entry-point names of group ``amr_description.hardware`` (e.g.
        ``'amr_description/MujocoSystem'``); empty when the package is not installed.
    """
    from importlib.metadata import entry_points
    return {entry.name for entry in entry_points(group=HARDWARE_GROUP)}


def check_ros2_control(model, urdf_xml, controllers=None):
    """
    Check the ``<ros2_control>`` blocks, and the diff_drive_controller against them.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param urdf_xml: the URDF text (for the ``<ros2_control>`` blocks).
    :param controllers: parsed controllers.yaml (dict) or None to skip the YAML checks.
    :returns: list of :class:`Finding`.
    """
    try:
        infos = parse_ros2_control(urdf_xml)
    except ValueError as exc:
        return [Finding(ERROR, '<ros2_control>', str(exc))]
    findings = []
    components = {}
    plugins = hardware_plugins()
    for info in infos:
        if plugins and info.plugin not in plugins:
            findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                    'unknown hardware plugin: mujoco_sim cannot load it',
                                    'one of ' + ', '.join(sorted(plugins)), info.plugin))
        for joint in info.joints:
            components[joint.name] = joint
            if joint.name not in model.joints:
                findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                        f'joint {joint.name!r} is not a URDF joint'))
            elif model.joints[joint.name].type == 'fixed':
                findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                        f'joint {joint.name!r} is fixed'))
    if controllers is None:
        return findings
    cm = node_parameters(controllers, 'controller_manager')
    if not isinstance(cm, dict):
        return findings + [Finding(ERROR, 'controllers.yaml',
                                   'no controller_manager.ros__parameters section')]
    for name, params in diff_drive_params(controllers).items():
        findings.extend(_check_diff_drive(model, components, name, params))
    return findings


def _check_diff_drive(model, components, name, params):
    """Check one diff_drive_controller's wheels and geometry against the URDF."""
    element = f'controllers.yaml {name}'
    findings = []
    sides = {}
    for side in ('left', 'right'):
        key = f'{side}_wheel_names'
        wheels = params.get(key) or []
        if not wheels:
            findings.append(Finding(ERROR, element, f'{key} is empty', 'joint names', '[]'))
        sides[side] = [w for w in wheels if w in model.joints]
        for wheel in wheels:
            findings.extend(_check_wheel_interfaces(
                element, wheel, components.get(wheel), model,
                params.get('position_feedback', True)))
    base = params.get('base_frame_id', 'base_link')
    if base not in model.links:
        findings.append(Finding(ERROR, element, 'base_frame_id is not a URDF link',
                                'a link name', repr(base)))
        base = model.root
    elif params.get('enable_odom_tf', True):
        parents = [j.parent for j in model.joints.values() if j.child == base]
        if parents:
            findings.append(Finding(
                WARNING, element,
                f'base_frame_id has a parent in the URDF ({parents[0]}): the odometry TF '
                f"odom -> {base} and robot_state_publisher's {parents[0]} -> {base} give it "
                'two parents (REP 105: odom -> the URDF root)', f'{model.root!r}', repr(base)))
    if sides['left'] and sides['right']:
        left_y = np.mean([joint_position_in_frame(model, w, base)[1] for w in sides['left']])
        right_y = np.mean([joint_position_in_frame(model, w, base)[1] for w in sides['right']])
        separation = left_y - right_y
        if separation <= 0.0:
            findings.append(Finding(ERROR, element, 'left wheels are not left of right wheels',
                                    'left y > right y', f'{left_y:g} <= {right_y:g}'))
        value = params.get('wheel_separation')
        if not isinstance(value, (int, float)) or abs(value - separation) > GEOMETRY_TOLERANCE:
            findings.append(Finding(ERROR, element, 'wheel_separation does not match the URDF',
                                    f'{separation:g} m (+-1 mm)', f'{value}'))
        else:
            findings.append(Finding(INFO, element, f'wheel_separation {value:g} m matches'))
        findings.extend(check_separation_multiplier(model, element, params, base, sides))
    value = params.get('wheel_radius')
    for wheel in sides['left'] + sides['right']:
        radius = wheel_radius(model, model.joints[wheel].child)
        if radius is None:
            continue
        if not isinstance(value, (int, float)) or abs(value - radius) > GEOMETRY_TOLERANCE:
            findings.append(Finding(ERROR, element,
                                    f'wheel_radius does not match the URDF wheel of {wheel}',
                                    f'{radius:g} m (+-1 mm)', f'{value}'))
            break
    else:
        if sides['left'] + sides['right']:
            findings.append(Finding(INFO, element, f'wheel_radius {value:g} m matches'))
    return findings


def check_separation_multiplier(model, element, params, base, sides):
    """
    Compare a skid-steer base's ``wheel_separation_multiplier`` with the Coulomb value.

    A base with wheels at different x on one side (skid steer) turning in place slips its
    wheels sideways; with equal wheel loads and Coulomb friction it turns at
    ``omega = v b / (a^2 + b^2)`` (:mod:`amr_description.core.skid_steer`), so odometry needs
    ``wheel_separation_multiplier = (a^2 + b^2) / b^2`` with ``b`` half the track and ``a``
    the mean distance of the wheels from their centre along x (half the wheelbase).

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param element: the controller's name in findings (str).
    :param params: its ``ros__parameters`` (dict).
    :param base: the base frame the wheel positions are expressed in.
    :param sides: dict ``'left'``/``'right'`` -> wheel joint names (URDF joints).
    :returns: list of :class:`Finding`: nothing for a two-wheeled base, else a warning when
        the multiplier is more than 10 % from the geometric value, an ``ok`` otherwise.
    """
    wheels = sides['left'] + sides['right']
    if not sides['left'] or not sides['right']:
        return []
    positions = np.array([joint_position_in_frame(model, w, base) for w in wheels])
    left_y = positions[:len(sides['left']), 1].mean()
    right_y = positions[len(sides['left']):, 1].mean()
    b = (left_y - right_y) / 2.0
    a = float(np.mean(np.abs(positions[:, 0] - positions[:, 0].mean())))
    if not b > 0.0 or a < GEOMETRY_TOLERANCE:
        return []  # not a skid-steer base (or already reported as broken)
    geometric = (a * a + b * b) / (b * b)
    value = params.get('wheel_separation_multiplier', 1.0)
    formula = (f'skid steer: (a^2 + b^2) / b^2 with half wheelbase a = {a:g} m, half track '
               f'b = {b:g} m')
    if not isinstance(value, (int, float)) or abs(value - geometric) > 0.1 * geometric:
        return [Finding(WARNING, element, 'wheel_separation_multiplier is far from the '
                        f'Coulomb-friction value, {formula}', f'{geometric:.3g} (+-10 %)',
                        f'{value}')]
    return [Finding(INFO, element,
                    f'wheel_separation_multiplier {value:g} matches {formula} = {geometric:.3g}')]


def _check_wheel_interfaces(element, wheel, component, model, position_feedback):
    """Check the ros2_control interfaces one diff_drive wheel needs."""
    if wheel not in model.joints:
        return [Finding(ERROR, element, f'wheel {wheel!r} is not a URDF joint')]
    if component is None:
        return [Finding(ERROR, element, f'wheel {wheel!r} is not in a <ros2_control> block')]
    findings = []
    commands = component.command_interface_names()
    states = component.state_interface_names()
    if 'velocity' not in commands:
        findings.append(Finding(ERROR, f'ros2_control joint {wheel!r}',
                                'diff_drive_controller needs a velocity command interface',
                                'velocity', ', '.join(commands) or 'none'))
    for state in ('position', 'velocity'):
        if state not in states:
            needed = (state == 'position') == bool(position_feedback)
            findings.append(Finding(
                ERROR if needed else WARNING, f'ros2_control joint {wheel!r}',
                f'missing {state} state interface', state, ', '.join(states) or 'none'))
    return findings


# ---------------------------------------------------------------------------------------------
# <mujoco> simulator block
# ---------------------------------------------------------------------------------------------

def check_mujoco_block(model, urdf_xml):
    """
    Check the ``<mujoco>`` extension block (format: docs/architecture.md).

    Values are read by :func:`amr_description.core.mujoco_block.parse_mujoco_block`, the
    reader the simulator's converter uses: what it refuses is reported here with its line.

    :returns: list of :class:`Finding`: a value the reader refuses, link/joint names that do
        not exist, actuators on joints without a velocity command interface.
    """
    if isinstance(urdf_xml, str):
        urdf_xml = urdf_xml.encode('utf-8')
    root = etree.fromstring(urdf_xml)
    blocks = root.findall('mujoco')
    if not blocks:
        return [Finding(WARNING, '<mujoco>', 'no simulator block; the simulator uses defaults')]
    findings = []
    try:
        parse_mujoco_block(root)
    except ValueError as exc:
        findings.append(Finding(ERROR, '<mujoco>', str(exc).replace('<mujoco>: ', '', 1)))
    commands = set()
    try:
        for info in parse_ros2_control(root):
            commands.update(j.name for j in info.joints if 'velocity' in
                            j.command_interface_names())
    except ValueError:
        pass
    for block in blocks:
        for element in block:
            if not isinstance(element.tag, str):
                continue
            findings.extend(_check_mujoco_names(model, element, commands))
    return findings


def _check_mujoco_names(model, element, commands):
    """Check the names one child of ``<mujoco>`` refers to."""
    where = f'<mujoco><{element.tag}>'
    findings = []
    if element.tag == 'ros2_control':
        if not element.get('parameters'):
            findings.append(Finding(ERROR, where, 'missing parameters attribute'))
    if element.tag == 'link' and element.get('name') not in model.links:
        findings.append(Finding(ERROR, where, 'names no URDF link', 'a link',
                                repr(element.get('name'))))
    if element.tag == 'actuator':
        joint = element.get('joint')
        if joint is not None and joint not in commands:
            findings.append(Finding(ERROR, where,
                                    'joint has no velocity command interface in <ros2_control>',
                                    'a ros2_control velocity joint', repr(joint)))
    return findings


# ---------------------------------------------------------------------------------------------
# Installed copy
# ---------------------------------------------------------------------------------------------

def compare_installed(source_path, installed_path):
    """
    Compare a source file with its installed copy (the stale-install lesson).

    :param source_path: the file in the source tree.
    :param installed_path: the file under ``share/<pkg>/...``, or None when not installed.
    :returns: a :class:`Finding`: ok when it is the same file (symlink install) or has the
        same bytes, warning when not installed, error when the contents differ.
    """
    element = f'installed {os.path.basename(source_path)}'
    if installed_path is None or not os.path.exists(installed_path):
        return Finding(WARNING, element, 'not installed; run colcon build', installed_path or
                       'share/amr_description/...', 'nothing')
    if os.path.samefile(source_path, installed_path):
        return Finding(INFO, element, f'{installed_path} is the source file (symlink install)')
    if filecmp.cmp(source_path, installed_path, shallow=False):
        return Finding(INFO, element, f'{installed_path} equals the source file')
    return Finding(ERROR, element,
                   'installed copy differs from the source: rebuild (colcon build) or nodes '
                   'load a stale model', source_path, installed_path)


def installed_counterpart(source_path, package='amr_description'):
    """
    Return the installed path of a source-tree file of ``package``, or None.

    Only files of the package's own source tree (``<src>/package.xml`` names ``package`` and
    the file is under ``<src>/urdf`` or ``<src>/config``) have a counterpart.

    :returns: ``<share>/<package>/<folder>/<name>`` through the ament index, or None.
    """
    folder_path = os.path.dirname(os.path.abspath(source_path))
    folder = os.path.basename(folder_path)
    package_xml = os.path.join(os.path.dirname(folder_path), 'package.xml')
    if folder not in ('urdf', 'config') or not os.path.isfile(package_xml):
        return None
    try:
        with open(package_xml) as f:
            if f'<name>{package}</name>' not in f.read():
                return None
        from ament_index_python.packages import get_package_share_directory
        share = get_package_share_directory(package)
    except Exception:  # not installed, or ament_index unavailable
        return os.path.join('share', package, folder, os.path.basename(source_path))
    return os.path.join(share, folder, os.path.basename(source_path))


# ---------------------------------------------------------------------------------------------
# All checks, CLI
# ---------------------------------------------------------------------------------------------

def check_model(model, urdf_xml, controllers=None):
    """
    Run every model check that needs no file system.

    :param model: :class:`~amr_description.core.urdf_model.RobotModel`.
    :param urdf_xml: the URDF text.
    :param controllers: parsed controllers.yaml (dict) or None.
    :returns: list of :class:`Finding`.
    """
    findings = check_links(model)
    base = 'base_link'
    for params in diff_drive_params(controllers or {}).values():
        base = params.get('base_frame_id', base)
    findings += check_wheels(model, wheel_joints(model, controllers), base)
    findings += check_ros2_control(model, urdf_xml, controllers)
    findings += check_mujoco_block(model, urdf_xml)
    return findings


def load_controllers(path):
    """
    Read a controllers.yaml.

    :returns: the parsed dict.
    :raises ValueError: one line naming ``path`` when unreadable or not a YAML mapping.
    """
    try:
        with open(path) as f:
            data = yaml.safe_load(f)
    except OSError as exc:
        raise ValueError(f'{path}: cannot read: {exc.strerror}') from None
    except yaml.YAMLError as exc:
        raise ValueError(f'{path}: invalid YAML: {" ".join(str(exc).split())}') from None
    if not isinstance(data, dict):
        raise ValueError(f'{path}: expected a YAML mapping of controller sections')
    return data


def main(argv=None):
    """
    Check a URDF (and optionally its controllers.yaml); print findings.

    ``ros2 run amr_description check_model [--controllers YAML] [--quiet] URDF``

    :param argv: arguments without the program name (default: ``sys.argv[1:]``).
    :returns: 0 when no errors, 1 when a check failed (including a rule of the URDF loader,
        reported as an error naming the element), 2 when a file cannot be read or is not a
        URDF document at all (malformed XML, no ``<robot>``).
    """
    parser = argparse.ArgumentParser(
        prog='check_model', description='Check a URDF beyond check_urdf: inertia, wheels, '
        'ros2_control block and controllers.yaml.')
    parser.add_argument('urdf', help='URDF file')
    parser.add_argument('--controllers', metavar='YAML',
                        help='controllers.yaml (ros2_control format) to check against the URDF')
    parser.add_argument('-q', '--quiet', action='store_true', help='print errors and warnings '
                        'only')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    model = None
    try:
        try:
            urdf_xml, model = parse_urdf_file(args.urdf)
        except URDFError as exc:
            if not exc.element:
                raise
            findings = [Finding(ERROR, exc.element, exc.problem)]
        controllers = load_controllers(args.controllers) if args.controllers else None
    except ValueError as exc:
        print(f'check_model: {exc}', file=sys.stderr)
        return 2
    if model is not None:
        findings = check_model(model, urdf_xml, controllers)
    for path in (args.urdf, args.controllers):
        installed = installed_counterpart(path) if path else None
        if installed is not None:
            findings.append(compare_installed(path, installed))
    for finding in findings:
        if not (args.quiet and finding.severity == INFO):
            print(finding)
    errors = sum(f.severity == ERROR for f in findings)
    warnings = sum(f.severity == WARNING for f in findings)
    if model is None:
        print(f'{args.urdf}: refused by the URDF loader: {errors} error(s), '
              f'{warnings} warning(s)')
    else:
        print(f'{args.urdf}: robot {model.name!r}, {len(model.links)} links, '
              f'{len(model.joints)} joints: {errors} error(s), {warnings} warning(s)')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
