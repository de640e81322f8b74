# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The MuJoCo world: an empty ground plane into which robots are spawned (no rclpy).

Frames: the world frame is ENU (REP 103/105: x forward, z up, gravity -z). Every spawned
robot is a free-floating body tree whose names are prefixed ``<robot name>/``.
Physics: ``implicitfast`` integrator (the default Euler integrator goes unstable with
velocity actuators on light wheels, see /work/shared/reference/environment.md) and a fixed
step (default 1 ms).
"""

from dataclasses import dataclass
import math

from amr_description.sim.sdf_to_mjcf import add_world
from amr_description.sim.sdf_to_mjcf import GROUND_BODY
from amr_description.sim.sdf_to_mjcf import make_world_spec
from amr_description.sim.sdf_to_mjcf import SEPARATOR
from amr_description.sim.urdf_to_mjcf import GROUND_CONTACT_PREFIX
from amr_description.sim.wheel_friction import CoulombWheels
import mujoco
import numpy as np

__all__ = ['Robot', 'World', 'make_world_spec']


def mujoco_error(exc):
    """
    Return MuJoCo's compiler error as one line naming the element it is about.

    MuJoCo writes ``Error: <what>`` then, on the next line, ``Element name '<name>', id N``;
    this gives ``<what> (element '<name>')``, the element being the scoped world name
    (``model::link``) or the robot's (``<robot>/<link>``).

    :param exc: the ``ValueError`` of ``MjSpec.compile``.
    """
    text = ' '.join(str(exc).split())
    text = text[len('Error: '):] if text.startswith('Error: ') else text
    what, _, element = text.partition(' Element name ')
    if element:
        element = element.rsplit(', id ', 1)[0]
        return f'{what} (element {element})'
    return what


def _mj_step(model, data, nstep):
    """Advance ``nstep`` steps with MuJoCo's own friction everywhere."""
    mujoco.mj_step(model, data, nstep=nstep)


@dataclass
class Robot:
    """
    A robot spawned into a :class:`World`.

    :param name: entity name (unique in the world).
    :param prefix: name prefix of its bodies, joints and actuators (``'<name>/'``).
    :param root: URDF root link name (e.g. ``'base_footprint'``); the free joint has the
        same name.
    :param urdf_xml: the URDF it was built from (str).
    """

    name: str
    prefix: str
    root: str
    urdf_xml: str = ''


class World:
    """
    A MuJoCo world holding spawned robots, its compiled model and its data.

    ``model`` and ``data`` are replaced by :meth:`spawn` and :meth:`remove` (the state of the
    bodies already present is kept); holders of the old objects must re-read them.

    :param physics_step: physics time step in seconds (default 1 ms).
    :param description: an SDF world (:class:`~amr_description.core.gazebo.sdf_elements.World`)
        whose models and gravity are added (:func:`~amr_description.sim.sdf_to_mjcf.add_world`);
        None: the empty world (gravity -9.81 m/s^2).
    :ivar name: the world's name in gz topics (``/world/<name>/...``): the SDF ``<world
        name>``, ``'empty'`` without one (the empty world of the Gazebo tutorials, gz-sim's
        ``empty.sdf``).
    :ivar messages: one-line messages about world shapes that could not be built.
    :raises ValueError: one line when MuJoCo cannot compile the world.
    """

    def __init__(self, physics_step=0.001, description=None):
        """Build and compile the world (see the class docstring)."""
        self.description = description
        self.name = 'empty' if description is None else description.name
        self.spec = make_world_spec(
            physics_step, (0.0, 0.0, -9.81) if description is None else description.gravity)
        self.messages = [] if description is None else add_world(self.spec, description)
        try:
            self.model = self.spec.compile()
        except ValueError as exc:
            source = description.source if description is not None else 'the empty world'
            raise ValueError(f'{source}: MuJoCo cannot build it: {mujoco_error(exc)}') from None
        self.data = mujoco.MjData(self.model)
        self.wheels = CoulombWheels()  # Coulomb friction of the pairs it flags
        self._coulomb_pairs = set()  # names of the wheel-ground pairs with Coulomb friction
        self.robots = {}
        self._initial_joints = {}  # joint (prefixed) -> (position or None, velocity or None)
        mujoco.mj_forward(self.model, self.data)
        self._poses_current = True  # poses match the state until the next step

    @property
    def physics_step(self):
        """Return the physics time step in seconds (float)."""
        return float(self.model.opt.timestep)

    @property
    def time(self):
        """Return the simulation time in seconds (float)."""
        return float(self.data.time)

    def spawn(self, robot_spec, name, urdf_xml='', self_collide=None):
        """
        Add a robot (from :func:`~amr_description.sim.urdf_to_mjcf.urdf_to_spec`).

        The world is recompiled; bodies already present keep their state and the
        simulation time is unchanged.

        :param robot_spec: a ``mujoco.MjSpec`` whose worldbody has exactly one body.
        :param name: entity name, unique in this world (str, non-empty, no ``/``).
        :param urdf_xml: the URDF text, kept for reference.
        :param self_collide: links (URDF names) that collide with the robot's other links;
            None: every link does (MuJoCo's rule); a collection: SDF's rule, whose
            ``self_collide`` is false by default (:meth:`_exclude_self_collisions`).
        :returns: the :class:`Robot`.
        :raises ValueError: when the name is taken or invalid, or MuJoCo cannot compile the
            result (the world is left unchanged).
        """
        if not name or '/' in name:
            raise ValueError(f'entity name must be non-empty without "/", found {name!r}')
        if name in self.robots:
            raise ValueError(f'an entity named {name!r} already exists')
        root = robot_spec.worldbody.first_body()
        if root is None:
            raise ValueError('robot spec has no body')
        root_name = root.name
        prefix = f'{name}/'
        frame = self.spec.worldbody.add_frame()
        self.spec.attach(robot_spec, prefix=prefix, frame=frame)
        # a robot never sleeps, even unactuated and at rest: its sensors measure every step
        self.spec.body(prefix + root_name).sleep = mujoco.mjtSleepPolicy.mjSLEEP_NEVER
        try:
            self._add_ground_pairs(prefix)
            if self_collide is not None:
                self._exclude_self_collisions(prefix, self.spec.body(prefix + root_name),
                                              self_collide)
            self._recompile()
        except Exception as exc:
            body = self.spec.body(prefix + root_name)
            self._delete_robot_elements(prefix, body)
            self.spec.delete(frame)
            self._recompile()
            raise ValueError(f'cannot compile robot {name!r}: {mujoco_error(exc)}') from None
        robot = Robot(name=name, prefix=prefix, root=root_name, urdf_xml=urdf_xml)
        self.robots[name] = robot
        if self._place_mimic_joints(prefix):
            mujoco.mj_forward(self.model, self.data)
        return robot

    def _place_mimic_joints(self, prefix=''):
        """
        Put each joint tied by a joint equality (a mimic joint) where its leader puts it.

        :param prefix: only the equalities of names starting so (a robot's ``'<name>/'``).
        :returns: True when a joint was placed (the caller then runs ``mj_forward``).
        """
        placed = False
        model, data = self.model, self.data
        for index in range(model.neq):
            if int(model.eq_type[index]) != mujoco.mjtEq.mjEQ_JOINT or \
                    not model.eq(index).name.startswith(prefix) or model.eq_obj2id[index] < 0:
                continue
            follower = model.jnt_qposadr[model.eq_obj1id[index]]
            leader = model.jnt_qposadr[model.eq_obj2id[index]]
            x = data.qpos[leader] - model.qpos0[leader]
            data.qpos[follower] = model.qpos0[follower] + sum(
                float(model.eq_data[index, k]) * x ** k for k in range(5))
            placed = True
        return placed

    def _add_ground_pairs(self, prefix):
        """
        Turn a robot's ``ground_contact/<geom>`` requests into explicit ground contact pairs.

        :func:`~amr_description.sim.urdf_to_mjcf.urdf_to_spec` records, for the collision
        geoms of links with a ``solreffriction`` in the URDF's ``<mujoco>`` block, a text
        element ``ground_contact/<geom>`` = ``'solreffriction <timeconst> <dampratio>'``.
        MuJoCo sets ``solreffriction`` only on explicit ``<pair>`` contacts, so each such geom
        gets a pair with the ground plane carrying the values the dynamic contact would have
        (friction: the element-wise maximum of both geoms; solref, solimp, condim: the
        robot geom's, the ground using MuJoCo's defaults) plus the friction reference, and the
        dynamic contact of its body with the ground's body is excluded (MuJoCo's
        ``<exclude>`` leaves explicit pairs alone); the link still collides with every other
        world geom (walls, shelves, boxes), as in Gazebo.

        :param prefix: the robot's name prefix (``'<name>/'``).
        """
        ground = self.spec.geom('ground_plane')
        if ground is None:
            return  # a world without a ground: no wheel-ground pairs
        marker = prefix + GROUND_CONTACT_PREFIX
        excluded = set()
        for text in list(self.spec.texts):
            if not text.name.startswith(marker):
                continue
            geom = self.spec.geom(prefix + text.name[len(marker):])
            values = text.data.split()
            coulomb = values == ['coulomb']
            if geom is None or not coulomb and (len(values) != 3 or
                                                values[0] != 'solreffriction'):
                raise ValueError(f'malformed ground contact request {text.name!r}')
            friction = [max(a, b) for a, b in zip(geom.friction, ground.friction)]
            name = f'{prefix}ground_pair/{geom.name[len(prefix):]}'
            self.spec.add_pair(
                name=name, geomname1=ground.name, geomname2=geom.name,
                # Coulomb: MuJoCo's contact keeps the normal force only, the friction
                # coefficient stays in the pair for amr_description/sim/wheel_friction.py
                condim=1 if coulomb else geom.condim,
                friction=[friction[0], friction[0], friction[1], friction[2], friction[2]],
                solref=list(geom.solref), solimp=list(geom.solimp),
                solreffriction=[0.0, 0.0] if coulomb else [float(values[1]), float(values[2])])
            if coulomb:
                self._coulomb_pairs.add(name)
            body = self._geom_body(geom.name)
            if body not in excluded:
                excluded.add(body)
                self.spec.add_exclude(name=f'{prefix}ground_exclude/{body[len(prefix):]}',
                                      bodyname1=GROUND_BODY, bodyname2=body)

    def _exclude_self_collisions(self, prefix, root, self_collide):
        """
        Keep the links of one robot from colliding with each other, as Gazebo does.

        SDF's ``<link><self_collide>`` is false by default: two links of one model collide
        only when one of them sets it (URDF ``<gazebo reference><selfCollide>``). MuJoCo
        collides every pair of bodies but a parent and its child; each pair of the robot's
        bodies with collision geoms, neither in ``self_collide``, gets an ``<exclude>``.

        :param prefix: the robot's name prefix.
        :param root: its root body in the spec.
        :param self_collide: URDF link names that collide with the other links.
        """
        bodies = []

        def walk(body):
            if any(g.contype or g.conaffinity for g in body.geoms) and \
                    body.name[len(prefix):] not in self_collide:
                bodies.append(body.name)
            for child in body.bodies:
                walk(child)
        walk(root)
        for i, first in enumerate(bodies):
            for second in bodies[i + 1:]:
                self.spec.add_exclude(name=f'{prefix}self_exclude/{len(self.spec.excludes)}',
                                      bodyname1=first, bodyname2=second)

    def _geom_body(self, geom_name):
        """Return the name of the body holding a geom of the spec."""
        for body in self.spec.bodies:
            if any(g.name == geom_name for g in body.geoms):
                return body.name
        raise ValueError(f'geom {geom_name!r} has no body')

    def _delete_robot_elements(self, prefix, body):
        """Delete the elements named ``prefix*`` and the body tree ``body`` from the spec."""
        for actuator in list(self.spec.actuators):
            if actuator.name.startswith(prefix):
                self.spec.delete(actuator)
        for group in (self.spec.pairs, self.spec.excludes, self.spec.texts):
            for element in list(group):
                if element.name.startswith(prefix):
                    self.spec.delete(element)
        self._coulomb_pairs = {n for n in self._coulomb_pairs if not n.startswith(prefix)}
        if body is not None:
            self.spec.delete(body)

    def overlapping_models(self, name):
        """
        Return the world models a robot's collision geoms touch now (sorted names).

        From MuJoCo's contacts of the last ``mj_forward`` (a spawn runs one); the ground
        plane does not count.

        :param name: entity name.
        :raises KeyError: when no such robot exists.
        """
        prefix = self.robots[name].prefix
        model, data = self.model, self.data
        found = set()
        for contact in data.contact[:data.ncon]:
            pair = (contact.geom1, contact.geom2)
            ours = [model.body(model.geom_bodyid[g]).name.startswith(prefix) for g in pair]
            if ours[0] != ours[1]:
                other = model.geom(pair[1] if ours[0] else pair[0]).name
                if SEPARATOR in other:
                    found.add(other.split(SEPARATOR)[0])
        return sorted(found)

    def remove(self, name):
        """
        Remove a spawned robot; the other bodies keep their state.

        :param name: entity name.
        :raises KeyError: when no such robot exists.
        """
        robot = self.robots.pop(name)
        self._delete_robot_elements(robot.prefix, self.spec.body(robot.prefix + robot.root))
        self._initial_joints = {joint: state for joint, state in self._initial_joints.items()
                                if not joint.startswith(robot.prefix)}
        self._recompile()

    def set_initial_joint_state(self, joint, position=None, velocity=None):
        """
        Start a joint at ``position`` (rad or m) and ``velocity`` (rad/s or m/s), now and on reset.

        gz_ros2_control's ``initial_value`` of a position or velocity state interface
        (``JointPositionReset`` / ``JointVelocityReset`` at start-up); :meth:`reset`
        returns to it.

        :param joint: the joint's name in the world (``'<entity>/<joint>'``).
        :param position: float or None (unchanged).
        :param velocity: float or None (unchanged).
        :raises ValueError: when the joint is not in the world or is not a hinge or slide.
        """
        try:
            found = self.model.joint(joint)
        except KeyError:
            raise ValueError(f'joint {joint!r} is not in the simulated world') from None
        if int(found.type[0]) not in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
            raise ValueError(f'joint {joint!r}: an initial value needs a revolute, continuous '
                             'or prismatic joint')
        self._initial_joints[joint] = (position, velocity)
        self._apply_initial_joint_states([joint])
        self._place_mimic_joints(joint.split('/')[0] + '/' if '/' in joint else '')
        mujoco.mj_forward(self.model, self.data)

    def _apply_initial_joint_states(self, joints):
        # not through qpos0: MuJoCo's joint equalities (mimic joints) are relative to it
        for joint in joints:
            position, velocity = self._initial_joints[joint]
            found = self.model.joint(joint)
            if position is not None:
                self.data.qpos[found.qposadr[0]] = position
            if velocity is not None:
                self.data.qvel[found.dofadr[0]] = velocity

    def _recompile(self):
        """Recompile the spec keeping the state; refresh ``model`` and ``data``."""
        self.model, self.data = self.spec.recompile(self.model, self.data)
        mujoco.mj_forward(self.model, self.data)
        self.wheels.configure(self.model, self._coulomb_pairs)
        self._poses_current = True

    def reset(self):
        """Reset every robot to its spawn pose, controls to zero, time to 0 s."""
        mujoco.mj_resetData(self.model, self.data)
        self.wheels.reset()
        self._apply_initial_joint_states(self._initial_joints)
        self._place_mimic_joints()
        mujoco.mj_forward(self.model, self.data)
        self._poses_current = True

    def step(self, nstep=1):
        """
        Advance the physics by ``nstep`` steps (a batch of ``mj_step`` or of Coulomb wheels).

        The batch is ``mujoco.mj_step``'s, or the loop of
        :class:`~amr_description.sim.wheel_friction.CoulombWheels` while a wheel has Coulomb
        friction with the ground.

        MuJoCo's sensors (the IMUs' accelerometer, gyro and orientation) are computed in the
        last step only: the steps before it run with ``mjDSBL_SENSOR``, which skips
        ``mj_sensorPos/Vel/Acc`` and nothing else (the trajectory is the same). A cycle ends
        where a measurement is due, so ``data.sensordata`` is what every step would have left
        there, without the accelerometer's ``mj_rnePostConstraint`` at every physics step.

        :param nstep: number of physics steps (int >= 1).
        """
        model, data, nstep = self.model, self.data, int(nstep)
        step = self.wheels.step if self.wheels.active else _mj_step
        if nstep > 1 and model.nsensor:
            flags = model.opt.disableflags
            model.opt.disableflags = flags | mujoco.mjtDisableBit.mjDSBL_SENSOR
            try:
                step(model, data, nstep - 1)
            finally:
                model.opt.disableflags = flags
            nstep = 1
        step(model, data, nstep)
        self._poses_current = False

    def update_kinematics(self):
        """
        Bring body, geom and site poses up to the current state (once per state).

        ``mj_step`` integrates after computing the poses, so after it ``xpos``/``xmat`` are
        those of the previous step; a sensor that reads poses (a lidar's ray origin, the
        geoms it hits) calls this first. ``mj_kinematics`` only writes derived poses, so the
        trajectory is the same with or without the call.
        """
        if not self._poses_current:
            mujoco.mj_kinematics(self.model, self.data)
            self._poses_current = True

    def free_joint_address(self, name):
        """
        Return (qpos address, qvel address) of a robot's root free joint.

        :param name: entity name.
        :returns: tuple of two ints (indices into ``data.qpos`` and ``data.qvel``).
        :raises KeyError: when no such robot exists.
        """
        robot = self.robots[name]
        joint = self.model.joint(robot.prefix + robot.root)
        return int(joint.qposadr[0]), int(joint.dofadr[0])

    def world_free_bodies(self):
        """
        Return the names of the world's moving bodies (links of non-static SDF models).

        :returns: list of ``'<model>::<link>'`` (gz-sim's scoped names), in model order;
            robots' bodies are not included.
        """
        model = self.model
        prefixes = tuple(robot.prefix for robot in self.robots.values())
        names = []
        for joint in range(model.njnt):
            if int(model.jnt_type[joint]) != mujoco.mjtJoint.mjJNT_FREE:
                continue
            name = model.body(int(model.jnt_bodyid[joint])).name
            if '::' in name and not name.startswith(prefixes):
                names.append(name)
        return names

    def body_pose(self, name):
        """
        Return the pose of a body in the world frame.

        :param name: the body's name in the world.
        :returns: ``(position (3,) m, quaternion (x, y, z, w))`` (ROS order).
        :raises KeyError: when no such body exists.
        """
        body = self.model.body(name).id
        w, x, y, z = self.data.xquat[body]
        return self.data.xpos[body].copy(), (float(x), float(y), float(z), float(w))

    def ground_truth(self, name):
        """
        Return the pose and twist of a robot's root link (for ``nav_msgs/Odometry``).

        :param name: entity name.
        :returns: ``(position, orientation, linear, angular)``: position (3,) m in the world
            frame; orientation (4,) quaternion (x, y, z, w) world <- root link (ROS order);
            linear (3,) m/s and angular (3,) rad/s velocity of the root link expressed in the
            root link frame (the Odometry ``child_frame_id`` convention).
        :raises KeyError: when no such robot exists.
        """
        qadr, vadr = self.free_joint_address(name)
        return free_joint_ground_truth(self.data.qpos[qadr:qadr + 7],
                                       self.data.qvel[vadr:vadr + 6])


def free_joint_ground_truth(qpos, qvel):
    """
    Convert a MuJoCo free joint's qpos/qvel to pose and body-frame twist.

    MuJoCo's free joint stores position (3) and quaternion (w, x, y, z) in ``qpos``, and in
    ``qvel`` the linear velocity in the world frame followed by the angular velocity in the
    body frame (MuJoCo documentation, "Floating objects").

    :param qpos: array (7,).
    :param qvel: array (6,).
    :returns: ``(position (3,), quaternion xyzw (4,), linear body (3,), angular body (3,))``.
    """
    w, x, y, z = (float(v) for v in qpos[3:7])
    norm = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / norm, x / norm, y / norm, z / norm
    vx, vy, vz = (float(v) for v in qvel[0:3])
    # v_body = R^T v_world, with R the rotation matrix of (w, x, y, z); plain floats: this
    # runs in the simulation loop, where small numpy calls cost more than the arithmetic
    linear = np.array([
        (1 - 2 * (y * y + z * z)) * vx + 2 * (x * y + w * z) * vy + 2 * (x * z - w * y) * vz,
        2 * (x * y - w * z) * vx + (1 - 2 * (x * x + z * z)) * vy + 2 * (y * z + w * x) * vz,
        2 * (x * z + w * y) * vx + 2 * (y * z - w * x) * vy + (1 - 2 * (x * x + y * y)) * vz])
    position = np.array(qpos[0:3], dtype=float)
    angular = np.array(qvel[3:6], dtype=float)
    return position, np.array([x, y, z, w]), linear, angular
