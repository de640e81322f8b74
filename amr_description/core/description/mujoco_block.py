# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``<mujoco>`` simulator block of a URDF: the one reader (format: docs/architecture.md).

The URDF -> MJCF converter (:mod:`amr_description.sim.urdf_to_mjcf`) builds the model from
what :func:`parse_mujoco_block` returns, and ``check_model``
(:mod:`amr_description.core.model_check`) reports what it refuses, so the two cannot disagree
on what a block means. Element tree of the standard library or lxml alike.
"""

from dataclasses import dataclass
from dataclasses import field
import math

#: contact parameters used when the ``<mujoco>`` block gives none
DEFAULT_CONTACT = {
    'friction': (1.0, 0.005, 0.0001),
    'solref': (0.02, 1.0),
    'solimp': (0.9, 0.95, 0.001, 0.5, 2.0),
    'condim': 3,
}
#: actuator parameters used when the ``<mujoco>`` block gives none
DEFAULT_ACTUATOR = {'kv': 5.0, 'kp': 100.0, 'ki': 0.0, 'armature': 0.0,
                    'forcerange': (-20.0, 20.0)}
#: contact shapes a ``<mujoco><link shape=...>`` may ask for
CONTACT_SHAPES = ('urdf', 'sphere', 'ellipsoid')
#: friction laws a ``<mujoco><link ground_friction=...>`` may ask for between the link and the
#: ground: MuJoCo's contact friction, or Coulomb's (amr_description/sim/wheel_friction.py)
GROUND_FRICTION = ('mujoco', 'coulomb')


@dataclass
class MujocoConfig:
    """
    The parsed ``<mujoco>`` block of a URDF.

    :param parameters: the ``<ros2_control parameters=...>`` URI (str) or None.
    :param contact: default contact attributes, dict with ``friction`` (3 floats),
        ``solref`` (2), ``solimp`` (5), ``condim`` (int).
    :param link_contact: dict link name -> dict of overriding contact attributes.
    :param actuator: default actuator attributes, dict with ``kv``, ``kp`` (float) and
        ``forcerange`` (2 floats, N or N m).
    :param joint_actuator: dict joint name -> dict of overriding actuator attributes.
    """

    parameters: str = None
    contact: dict = field(default_factory=lambda: dict(DEFAULT_CONTACT))
    link_contact: dict = field(default_factory=dict)
    actuator: dict = field(default_factory=lambda: dict(DEFAULT_ACTUATOR))
    joint_actuator: dict = field(default_factory=dict)
    present: bool = False


DRIVE_DEFAULTS = {'kv': 5.0, 'ki': 100.0, 'armature': 0.05}
"""The wheel drive of a description without ``<mujoco>``: the PI velocity servo, gains and
rotor inertia measured for the tutorial robot (docs/simulation.md, "Contact and actuators")."""

WHEEL_CONTACT_DEFAULTS = {'shape': 'ellipsoid'}
"""The wheel-ground contact of a description without ``<mujoco>``: one point below the axle
(MuJoCo's cylinder-plane contact puts two on the rim edges), the wheel no wider than its
cylinder (a sphere would be as wide as it is tall). Not the slower friction reference
of urdf/amr.urdf: without acceleration limits in the controllers YAML (the tutorial's has
none) it lets the wheels slip when a command steps (0.95 m driven for 1.00 m of odometry,
docs/gazebo.md)."""

DEFAULT_EFFORT = 20.0
"""N m (or N) a drive may exert when the URDF joint gives no ``<limit effort>``."""


def add_drive_defaults(config, model, hardware, simulator_systems, gazebo=()):
    """
    Give a description without a ``<mujoco>`` block the settings Gazebo users expect.

    Gazebo describes no contact shape or servo gains: its velocity command is a servo solved
    with the contacts, bounded by the joint's URDF ``<limit effort>``
    (docs/gazebo.md). For every joint with a velocity command interface in a
    ``<ros2_control>`` block of the simulator (``simulator_systems``), and every joint with a
    position command interface in a gz_ros2_control block (``gazebo``): the drive becomes
    :data:`DRIVE_DEFAULTS` with ``forcerange`` +-effort (:data:`DEFAULT_EFFORT` without
    one), and the child link of a velocity joint, when its collision is a cylinder (a wheel),
    touches the ground as :data:`WHEEL_CONTACT_DEFAULTS`. A description with a block is
    left as it is.

    :param config: the :class:`MujocoConfig` to complete (changed in place).
    :param model: the :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param hardware: the ``<ros2_control>`` blocks (``HardwareInfo`` list).
    :param simulator_systems: hardware plugin names of the simulator.
    :param gazebo: those of gz_ros2_control, whose position commands are velocity targets
        too: their joints get the same drive.
    """
    if config.present:
        return
    for info in hardware:
        if info.plugin not in simulator_systems:
            continue
        for component in info.joints:
            joint = model.joints.get(component.name)
            names = component.command_interface_names()
            servo = 'velocity' in names or ('position' in names and info.plugin in gazebo)
            if joint is None or not servo:
                continue
            effort = joint.limit.effort if joint.limit is not None and joint.limit.effort \
                else 0.0
            effort = effort if effort and effort > 0 else DEFAULT_EFFORT
            drive = dict(DRIVE_DEFAULTS, forcerange=(-effort, effort))
            config.joint_actuator.setdefault(component.name, drive)
            link = model.links.get(joint.child)
            if 'velocity' in names and link is not None and link.collisions and \
                    link.collisions[0].geometry.cylinder is not None:
                config.link_contact.setdefault(joint.child, dict(WHEEL_CONTACT_DEFAULTS))


_CONTACT_SIZES = {'friction': (1, 3), 'solref': (2, 2), 'solimp': (3, 5),
                  'solreffriction': (2, 2)}


def _floats(text, name, where, sizes):
    """Parse a space-separated float list of ``sizes[0]..sizes[1]`` entries."""
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        raise ValueError(f'<mujoco>: {where} {name}={text!r} must be numbers') from None
    if not sizes[0] <= len(values) <= sizes[1] or not all(map(math.isfinite, values)):
        raise ValueError(
            f'<mujoco>: {where} {name}={text!r} must be {sizes[0]}..{sizes[1]} finite numbers')
    return values


def _contact_attrs(element, where):
    """Return the contact attributes present on ``element`` as a dict."""
    attrs = {}
    for name, sizes in _CONTACT_SIZES.items():
        if element.get(name) is not None:
            attrs[name] = _floats(element.get(name), name, where, sizes)
    if min(attrs.get('friction', (0.0,))) < 0.0:
        raise ValueError(f'<mujoco>: {where} friction must be >= 0')
    if element.get('condim') is not None:
        if element.get('condim') not in ('1', '3', '4', '6'):
            raise ValueError(f'<mujoco>: {where} condim must be 1, 3, 4 or 6')
        attrs['condim'] = int(element.get('condim'))
    if element.get('shape') is not None:
        if element.get('shape') not in CONTACT_SHAPES:
            raise ValueError(f'<mujoco>: {where} shape must be one of {", ".join(CONTACT_SHAPES)}'
                             f', found {element.get("shape")!r}')
        attrs['shape'] = element.get('shape')
    if element.get('ground_friction') is not None:
        if element.get('ground_friction') not in GROUND_FRICTION:
            raise ValueError(f'<mujoco>: {where} ground_friction must be one of '
                             f'{", ".join(GROUND_FRICTION)}, found '
                             f'{element.get("ground_friction")!r}')
        attrs['ground_friction'] = element.get('ground_friction')
    return attrs


def _actuator_attrs(element, where):
    """Return the actuator attributes present on ``element`` as a dict."""
    attrs = {}
    for name in ('kv', 'kp', 'ki', 'armature'):
        if element.get(name) is not None:
            value = _floats(element.get(name), name, where, (1, 1))[0]
            if value < 0:
                raise ValueError(f'<mujoco>: {where} {name} must be >= 0')
            attrs[name] = value
    if element.get('forcerange') is not None:
        lo, hi = _floats(element.get('forcerange'), 'forcerange', where, (2, 2))
        if lo > hi:
            raise ValueError(f'<mujoco>: {where} forcerange must be "min max" with min <= max')
        attrs['forcerange'] = (lo, hi)
    return attrs


def parse_mujoco_block(root):
    """
    Read the ``<mujoco>`` child of a URDF ``<robot>`` element.

    :param root: the ``<robot>`` ``xml.etree.ElementTree.Element``.
    :returns: a :class:`MujocoConfig` (defaults when there is no block).
    :raises ValueError: one-line message for a malformed attribute.
    """
    config = MujocoConfig()
    for block in root.findall('mujoco'):
        config.present = True
        rc = block.find('ros2_control')
        if rc is not None and rc.get('parameters'):
            config.parameters = rc.get('parameters').strip()
        for element in block.findall('contact'):
            config.contact.update(_contact_attrs(element, '<contact>'))
        for element in block.findall('link'):
            name = element.get('name')
            if not name:
                raise ValueError('<mujoco>: <link> without a name')
            config.link_contact.setdefault(name, {}).update(
                _contact_attrs(element, f'<link name={name!r}>'))
        for element in block.findall('actuator'):
            joint = element.get('joint')
            if joint:
                config.joint_actuator.setdefault(joint, {}).update(
                    _actuator_attrs(element, f'<actuator joint={joint!r}>'))
            else:
                config.actuator.update(_actuator_attrs(element, '<actuator>'))
    return config
