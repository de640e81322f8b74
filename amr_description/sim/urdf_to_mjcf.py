# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Convert a URDF (with its ``<ros2_control>`` and ``<mujoco>`` blocks) into a ``mujoco.MjSpec``.

Mapping (URDF -> MuJoCo, units SI, REP 103 axes):

- every ``<link>`` becomes a body; the body frame is the URDF link frame. The root link gets a
  free joint (a floating robot, as Gazebo spawns it), children hang off their parent body at
  the joint ``<origin>``; ``fixed`` joints keep the child as a welded body (no joint).
- ``<inertial>`` is copied exactly: ``mass``, the full inertia tensor including off-diagonal
  terms (rotated by the inertial ``rpy`` into the link frame and given to MuJoCo as
  ``fullinertia``) and the inertial origin (``ipos``). Links without ``<inertial>`` have zero
  mass; inertia is never derived from geoms.
- ``<collision>`` boxes, cylinders, spheres (and meshes whose file resolves: any format
  trimesh reads, made usable by :mod:`amr_description.core.description.meshes`) become
  colliding geoms in group 3; ``<visual>`` ones become non-colliding geoms
  (``contype = conaffinity = 0``) in group 2 with the material colour.
- ``continuous`` -> unlimited hinge, ``revolute`` -> limited hinge, ``prismatic`` -> slide,
  ``floating`` -> free; ``<axis>``, ``<limit>`` and ``<dynamics damping friction>`` are kept.
  ``planar`` joints are rejected.
- each joint command interface listed in ``<ros2_control>`` gets one actuator named
  ``<joint>/<interface>``: ``velocity`` -> velocity actuator (``kv``); with ``ki > 0`` a PI
  velocity servo: that actuator plus ``<joint>/velocity/integral``, MuJoCo's
  ``intvelocity`` actuator whose activation integrates the command (torque
  ``kv (command - qdot) + ki (integral of command - q)``, no steady-state speed error under
  load, the sum limited by the joint's actuator force range); ``effort`` -> motor,
  ``position`` -> position actuator (``kp``, ``kv`` damping), force range from ``<mujoco>``;
  ``armature`` (kg m^2, the motor's rotor inertia reflected through its gearbox) is added to
  the joint.
- contact ``friction`` (and optional ``solref``, ``solimp``, ``condim``) from ``<mujoco>``;
  per link, ``shape="ellipsoid"`` replaces its collision cylinders by ellipsoids with the
  cylinder's radius in the cylinder's cross-section and half its length along its axis, at the
  same origin (a wheel then touches the ground in one point below its axle, as a tyre with a
  rounded profile, and is no wider than its cylinder), ``shape="sphere"`` by spheres of the
  cylinder's radius (one point below the axle too, but as wide as the wheel is tall: it
  touches walls and pillars the cylinder clears), and ``solreffriction`` (time constant s,
  damping ratio) is the reference of the friction directions of the contacts between the
  link and the ground plane, or ``ground_friction="coulomb"`` gives those contacts Coulomb's
  friction instead of MuJoCo's (:mod:`amr_description.sim.wheel_friction`)
  (:class:`amr_description.sim.world.World` makes them explicit contact pairs; a text element
  ``ground_contact/<geom>`` of the spec carries the request: ``solreffriction T D`` or
  ``coulomb``).

The ``<mujoco>`` block (see docs/architecture.md)::

    <mujoco>
      <ros2_control parameters="package://amr_description/config/controllers.yaml"/>
      <contact friction="1.0 0.005 0.0001" solref="0.02 1" solimp="0.9 0.95 0.001"/>
      <link name="wheel_front_left" friction="1.0 0.005 0.0001" shape="ellipsoid"
            ground_friction="coulomb"/>
      <actuator kv="5.0" ki="100" armature="0.05" forcerange="-20 20"/>
      <actuator joint="joint_wheel_front_left" kv="5.0" forcerange="-20 20"/>
    </mujoco>
"""

import logging
import math
import os

from amr_description.core.description.files import resolve_uri
from amr_description.core.description.meshes import usable_mesh
from amr_description.core.description.mujoco_block import DEFAULT_CONTACT
from amr_description.core.description.robot_description import MOVING_TYPES
from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.tags import GAZEBO_SYSTEMS
from amr_description.sim.sensors.mount import add_mounts
import mujoco
import numpy as np

_LOG = logging.getLogger(__name__)

#: prefix of the spec text elements asking the world for an explicit ground contact pair
GROUND_CONTACT_PREFIX = 'ground_contact/'

COLLISION_GROUP = 3
VISUAL_GROUP = 2
_DEFAULT_RGBA = (0.7, 0.7, 0.7, 1.0)


def _mat_to_quat(rotation):
    """Return the MuJoCo quaternion (w, x, y, z) of a 3x3 rotation matrix."""
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(rotation, dtype=float).reshape(9))
    return quat


def rpy_to_quat(roll, pitch, yaw):
    """
    Return the quaternion (w, x, y, z) of URDF fixed-axis roll, pitch, yaw (rad).

    Rotation = Rz(yaw) Ry(pitch) Rx(roll), as in the URDF specification.

    :returns: numpy array of shape (4,).
    """
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return np.array([
        cr * cp * cy + sr * sp * sy,
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy])


def _pad(values, default):
    """Return ``values`` as a list completed with the trailing entries of ``default``."""
    return list(values) + list(default[len(values):])


def _set_frame(element, origin):
    """Set ``pos``/``quat`` of a spec element from a 4x4 homogeneous transform (or None)."""
    if origin is None:
        return
    origin = np.asarray(origin, dtype=float)
    element.pos = origin[:3, 3]
    element.quat = _mat_to_quat(origin[:3, :3])


def add_mesh(spec, vertices, faces):
    """
    Add triangles to a spec's assets as the mesh ``mesh_<N>``; return it.

    Its inertia is MuJoCo's ``shell`` (surface) model: an open or thin mesh has no volume to
    refuse, and no geom's inertia is taken from a mesh here (``inertiafromgeom`` false).

    :param spec: the ``mujoco.MjSpec``.
    :param vertices: ``(N, 3)`` floats, metres.
    :param faces: ``(M, 3)`` ints.
    """
    mesh = spec.add_mesh(name=f'mesh_{len(spec.meshes)}',
                         uservert=np.asarray(vertices, dtype=float).ravel(),
                         userface=np.asarray(faces, dtype=int).ravel())
    mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
    return mesh


def add_mesh_asset(spec, path, scale=None, notes=None):
    """
    Add a mesh file to a spec's assets, made usable for MuJoCo.

    As :func:`amr_description.core.description.meshes.usable_mesh` does: any format trimesh
    reads (STL binary or ASCII, OBJ, COLLADA, ...); non-finite and zero-area triangles left
    out, decimated over 200,000 triangles, a flat mesh thickened.

    :param spec: the ``mujoco.MjSpec``.
    :param path: an existing mesh file.
    :param scale: None, a number or 3 numbers (the URDF/SDF mesh ``scale``).
    :param notes: None, or a list that gets the one-line remarks on what was changed.
    :returns: the spec's mesh (named ``mesh_<N>``).
    :raises ValueError: one line naming the file when it cannot be used.
    """
    mesh = usable_mesh(path, scale)
    if notes is not None:
        notes.extend(mesh.notes)
    return add_mesh(spec, mesh.vertices, mesh.faces)


def _add_geometry(spec, body, geometry, origin, where):
    """Add one geom for a URDF ``<geometry>``; return it, or None when unsupported."""
    geom = None
    if geometry.box is not None:
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX,
                             size=np.asarray(geometry.box.size, dtype=float) / 2.0)
    elif geometry.cylinder is not None:
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                             size=[geometry.cylinder.radius, geometry.cylinder.length / 2.0, 0])
    elif geometry.sphere is not None:
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE,
                             size=[geometry.sphere.radius, 0, 0])
    elif geometry.mesh is not None:
        filename = geometry.mesh.filename
        try:
            path = resolve_uri(filename)
        except ValueError as exc:
            _LOG.warning('%s: mesh skipped: %s', where, exc)
            return None
        if not os.path.isfile(path):
            _LOG.warning('%s: mesh %r skipped: no file %r', where, filename, path)
            return None
        notes = []
        try:
            mesh = add_mesh_asset(spec, path, geometry.mesh.scale, notes)
        except ValueError as exc:
            _LOG.warning('%s: mesh %r skipped: %s', where, filename, exc)
            return None
        for note in notes:
            _LOG.warning('%s: %s', where, note)
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=mesh.name)
    else:
        _LOG.warning('%s: geometry without box/cylinder/sphere/mesh skipped', where)
        return None
    _set_frame(geom, origin)
    return geom


def _rgba(visual, materials):
    """Return the RGBA of a URDF visual: its own colour, else the named robot material."""
    material = visual.material
    if material is None:
        return _DEFAULT_RGBA
    if material.color is not None and material.color.rgba is not None:
        return tuple(float(c) for c in material.color.rgba)
    named = materials.get(material.name)
    if named is not None and named.color is not None and named.color.rgba is not None:
        return tuple(float(c) for c in named.color.rgba)
    return _DEFAULT_RGBA


def _set_inertial(body, inertial):
    """Copy a URDF ``<inertial>`` (or None) to a spec body exactly."""
    body.explicitinertial = True
    if inertial is None:
        body.mass = 0.0
        body.inertia = [0.0, 0.0, 0.0]
        return
    origin = np.eye(4) if inertial.origin is None else np.asarray(inertial.origin, dtype=float)
    rotation = origin[:3, :3]
    tensor = rotation @ np.asarray(inertial.inertia, dtype=float) @ rotation.T
    body.mass = float(inertial.mass)
    body.ipos = origin[:3, 3]
    body.fullinertia = [tensor[0, 0], tensor[1, 1], tensor[2, 2],
                        tensor[0, 1], tensor[0, 2], tensor[1, 2]]


def _add_joint(body, joint):
    """Add the MuJoCo joint for a URDF joint to the child ``body`` (nothing for ``fixed``)."""
    if joint.type == 'fixed':
        return None
    if joint.type == 'floating':
        return body.add_freejoint(name=joint.name)
    if joint.type not in ('continuous', 'revolute', 'prismatic'):
        raise ValueError(f'URDF joint {joint.name!r}: type {joint.type!r} is not supported')
    axis = np.array([1.0, 0.0, 0.0]) if joint.axis is None else np.asarray(joint.axis, float)
    norm = np.linalg.norm(axis)
    if not norm > 0:
        raise ValueError(f'URDF joint {joint.name!r}: axis must be non-zero')
    kind = mujoco.mjtJoint.mjJNT_SLIDE if joint.type == 'prismatic' \
        else mujoco.mjtJoint.mjJNT_HINGE
    mj_joint = body.add_joint(name=joint.name, type=kind, axis=axis / norm)
    if joint.type != 'continuous' and joint.limit is not None \
            and joint.limit.lower is not None and joint.limit.upper is not None \
            and joint.limit.lower < joint.limit.upper:
        mj_joint.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        mj_joint.range = [joint.limit.lower, joint.limit.upper]
    else:
        mj_joint.limited = mujoco.mjtLimited.mjLIMITED_FALSE
    if joint.dynamics is not None:
        mj_joint.damping = [float(joint.dynamics.damping or 0.0), 0.0, 0.0]
        mj_joint.frictionloss = float(joint.dynamics.friction or 0.0)
    return mj_joint


def _add_actuators(spec, joint_types, hardware, config):
    """Add one actuator per joint command interface of every ``<ros2_control>`` block."""
    for info in hardware:
        for joint in info.joints:
            if joint.name not in joint_types:
                raise ValueError(
                    f'ros2_control {info.name!r}: joint {joint.name!r} is not in the URDF')
            if joint_types[joint.name] in ('fixed', 'floating'):
                raise ValueError(
                    f'ros2_control {info.name!r}: joint {joint.name!r} is '
                    f'{joint_types[joint.name]} and cannot be actuated')
            params = dict(config.actuator)
            params.update(config.joint_actuator.get(joint.name, {}))
            if params.get('armature', 0.0) > 0.0:
                spec.joint(joint.name).armature = params['armature']
            for iface in joint.command_interfaces:
                actuator = spec.add_actuator(
                    name=f'{joint.name}/{iface.name}', target=joint.name,
                    trntype=mujoco.mjtTrn.mjTRN_JOINT)
                servo = iface.name == 'velocity' or \
                    (iface.name == 'position' and info.plugin in GAZEBO_SYSTEMS)
                if servo and params.get('ki', 0.0) > 0.0:
                    _add_integral_velocity(spec, joint, iface, actuator, params)
                    continue
                if servo:  # gz_ros2_control: a position command is a velocity target
                    actuator.set_to_velocity(kv=params['kv'])
                elif iface.name == 'position':
                    actuator.set_to_position(kp=params['kp'], kv=0.0)
                elif iface.name == 'effort':
                    actuator.set_to_motor()
                else:
                    raise ValueError(
                        f'ros2_control {info.name!r}: joint {joint.name!r} command interface '
                        f'{iface.name!r} is not one of position, velocity, effort')
                actuator.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
                actuator.forcerange = list(params['forcerange'])
                if iface.min is not None and iface.max is not None and iface.min < iface.max:
                    actuator.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
                    actuator.ctrlrange = [iface.min, iface.max]


def _add_integral_velocity(spec, joint, iface, actuator, params):
    """
    Make ``actuator`` the P part of a PI velocity servo and add its I part.

    ``<joint>/velocity``: velocity actuator, torque ``kv (command - qdot)``;
    ``<joint>/velocity/integral``: MuJoCo ``intvelocity`` actuator without damping, whose
    activation integrates the command: torque ``ki (act - q)`` = ``ki`` times the integral of
    the speed error. Both take the same command (MujocoSystem writes both); their sum is
    limited by the joint's actuator force range (``forcerange``), not per actuator.
    """
    actuator.set_to_velocity(kv=params['kv'])
    integral = spec.add_actuator(name=f'{joint.name}/{iface.name}/integral', target=joint.name,
                                 trntype=mujoco.mjtTrn.mjTRN_JOINT)
    integral.set_to_intvelocity(kp=params['ki'], kv=0.0)
    integral.actlimited = mujoco.mjtLimited.mjLIMITED_FALSE
    for element in (actuator, integral):
        element.forcelimited = mujoco.mjtLimited.mjLIMITED_FALSE
        if iface.min is not None and iface.max is not None and iface.min < iface.max:
            element.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
            element.ctrlrange = [iface.min, iface.max]
    mj_joint = spec.joint(joint.name)
    mj_joint.actfrclimited = mujoco.mjtLimited.mjLIMITED_TRUE
    mj_joint.actfrcrange = list(params['forcerange'])


def _add_mimic_constraints(spec, joints):
    """
    Tie every URDF ``<mimic>`` joint to its leader: ``q = offset + multiplier * q_leader``.

    A MuJoCo joint equality (``polycoef`` offset, multiplier) named ``<joint>/mimic``, solved
    with the contacts. gz_ros2_control drives a mimic joint with a velocity command
    ``-(q - multiplier * q_leader) * update_rate`` (``gz_system.cpp``), which ignores the
    offset; the URDF's meaning (and robot_state_publisher's) keeps it.

    :raises ValueError: one line when a mimic joint or its leader is not a moving joint.
    """
    types = {joint.name: joint.type for joint in joints}
    for joint in joints:
        mimic = joint.mimic
        if mimic is None:
            continue
        for name in (joint.name, mimic.joint):
            if types.get(name) not in MOVING_TYPES:
                raise ValueError(f'joint {joint.name!r} <mimic joint="{mimic.joint}">: '
                                 f'{name!r} is not a revolute, continuous or prismatic joint')
        multiplier = 1.0 if mimic.multiplier is None else float(mimic.multiplier)
        offset = 0.0 if mimic.offset is None else float(mimic.offset)
        spec.add_equality(name=f'{joint.name}/mimic', type=mujoco.mjtEq.mjEQ_JOINT,
                          name1=joint.name, name2=mimic.joint,
                          data=[offset, multiplier] + [0.0] * 10)


def _root_link(robot):
    """Return the name of the single link that is no joint's child."""
    links = [link.name for link in robot.links]
    if not links:
        raise ValueError('URDF has no <link>')
    known = set(links)
    for joint in robot.joints:
        for role in ('parent', 'child'):
            if getattr(joint, role) not in known:
                raise ValueError(
                    f'URDF joint {joint.name!r}: {role} link {getattr(joint, role)!r} '
                    'does not exist')
    children = {joint.child for joint in robot.joints}
    roots = [name for name in links if name not in children]
    if len(roots) != 1:
        raise ValueError(f'URDF must have exactly one root link, found {roots}')
    return roots[0]


def _round_wheel(geom, shape):
    """
    Replace a collision cylinder by the ``<mujoco><link shape=...>`` asked for, in place.

    MuJoCo's cylinder size is ``(radius, half length)`` along the geom's z; an ellipsoid's is
    its three semi-axes along the geom's x, y and z, so ``(r, r, half length)`` keeps the
    cylinder's cross-section circle (where a wheel rolls) and its width.

    :param geom: a ``mujoco.MjsGeom`` of type cylinder.
    :param shape: 'sphere', 'ellipsoid', or anything else for the cylinder unchanged.
    """
    radius, half_length = float(geom.size[0]), float(geom.size[1])
    if shape == 'sphere':
        geom.type = mujoco.mjtGeom.mjGEOM_SPHERE
        geom.size = [radius, 0.0, 0.0]
    elif shape == 'ellipsoid':
        geom.type = mujoco.mjtGeom.mjGEOM_ELLIPSOID
        geom.size = [radius, radius, half_length]


def urdf_to_spec(urdf_xml, name='amr', pose=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), free=True):
    """
    Build a MuJoCo spec holding the robot described by a URDF.

    :param urdf_xml: the URDF document (str or bytes), with optional ``<ros2_control>``
        and ``<mujoco>`` blocks, or its
        :class:`~amr_description.core.description.robot_description.RobotDescription` (parsed
        once by the caller).
    :param name: the model name (``spec.modelname``), str.
    :param pose: initial pose of the root link in the world frame: (x, y, z) in m then
        either (roll, pitch, yaw) in rad (URDF fixed-axis convention) or a quaternion
        (qx, qy, qz, qw), normalised here.
    :param free: True to give the root body a free joint named ``<root link>`` (floating
        robot), False to weld it to the world.
    :returns: a ``mujoco.MjSpec`` whose worldbody holds the robot (body names = link names,
        joint names = URDF joint names, actuators ``<joint>/<interface>``); compile with
        ``spec.compile()`` or attach into a world with :mod:`amr_description.sim.world`.
    :raises ValueError: one-line message when the URDF is malformed (XML, links, joints,
        unsupported joint type), a ``<ros2_control>`` joint is missing from the URDF, the
        ``<mujoco>`` block is malformed, or the pose is not 6/7 finite numbers.
    """
    description = urdf_xml if isinstance(urdf_xml, RobotDescription) else \
        RobotDescription(urdf_xml, source='URDF')
    robot = description.model.urdf.robot
    config = description.mujoco
    hardware = description.hardware + description.system_hardware
    root_name = _root_link(robot)
    pose = [float(v) for v in pose]
    if len(pose) not in (6, 7) or not all(math.isfinite(v) for v in pose):
        raise ValueError(
            'pose must be 6 (x y z R P Y) or 7 (x y z qx qy qz qw) finite numbers, '
            f'found {pose!r}')
    if len(pose) == 6:
        root_quat = rpy_to_quat(*pose[3:])
    else:
        root_quat = np.array([pose[6], pose[3], pose[4], pose[5]])
        if not np.linalg.norm(root_quat) > 1e-9:
            raise ValueError('pose quaternion must be non-zero')
        root_quat /= np.linalg.norm(root_quat)

    spec = mujoco.MjSpec()
    spec.modelname = name
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.compiler.autolimits = True
    spec.compiler.degree = False

    links = {link.name: link for link in robot.links}
    materials = {m.name: m for m in robot.materials}
    children = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint)

    def add_link(parent_body, link_name, joint):
        link = links[link_name]
        body = parent_body.add_body(name=link_name)
        if joint is None:
            body.pos = pose[:3]
            body.quat = root_quat
            if free:
                body.add_freejoint(name=link_name)
        else:
            _set_frame(body, joint.origin)
            _add_joint(body, joint)
        _set_inertial(body, link.inertial)
        if link_name in description.weightless_links:
            body.gravcomp = 1.0  # <gazebo reference><gravity>false / <turnGravityOff>
        contact = dict(config.contact)
        contact.update(config.link_contact.get(link_name, {}))
        for index, collision in enumerate(link.collisions):
            geom = _add_geometry(spec, body, collision.geometry, collision.origin,
                                 f'link {link_name!r} collision {index}')
            if geom is None:
                continue
            geom.name = f'{link_name}/{collision.name or f"collision_{index}"}'
            if geom.type == mujoco.mjtGeom.mjGEOM_CYLINDER:
                _round_wheel(geom, contact.get('shape'))
            if contact.get('ground_friction') == 'coulomb':
                spec.add_text(name=GROUND_CONTACT_PREFIX + geom.name, data='coulomb')
            elif 'solreffriction' in contact:
                spec.add_text(name=GROUND_CONTACT_PREFIX + geom.name, data='solreffriction ' +
                              ' '.join(repr(float(v)) for v in contact['solreffriction']))
            geom.group = COLLISION_GROUP
            geom.contype = 1
            geom.conaffinity = 1
            geom.friction = _pad(contact['friction'], DEFAULT_CONTACT['friction'])
            geom.solref = list(contact['solref'])
            geom.solimp = _pad(contact['solimp'], DEFAULT_CONTACT['solimp'])
            geom.condim = contact['condim']
            geom.priority = int(contact.get('priority', 0))  # Gazebo friction tags win
            geom.rgba = [0.5, 0.5, 0.9, 0.4]
        for index, visual in enumerate(link.visuals):
            geom = _add_geometry(spec, body, visual.geometry, visual.origin,
                                 f'link {link_name!r} visual {index}')
            if geom is None:
                continue
            geom.name = f'{link_name}/{visual.name or f"visual_{index}"}'
            geom.group = VISUAL_GROUP
            geom.contype = 0
            geom.conaffinity = 0
            geom.rgba = list(description.link_colours.get(link_name) or
                             _rgba(visual, materials))
        return body

    pending = [(spec.worldbody, root_name, None)]
    while pending:  # depth first, in the URDF's order, without recursion (a long chain)
        parent_body, link_name, joint = pending.pop()
        body = add_link(parent_body, link_name, joint)
        pending.extend((body, j.child, j) for j in reversed(children.get(link_name, [])))
    _add_mimic_constraints(spec, robot.joints)
    add_mounts(spec, description.sensors.sensors)
    _add_actuators(spec, {j.name: j.type for j in robot.joints}, hardware, config)
    return spec
