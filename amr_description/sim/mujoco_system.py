# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
MuJoCo hardware component: ros2_control handles <-> ``MjData`` (the gz_ros2_control role).

State interfaces read the joint's ``qpos`` (``position``: rad or m), ``qvel`` (``velocity``:
rad/s or m/s) and actuator force (``effort``: N m or N). Command interfaces write the
``ctrl`` of the actuator named ``<joint>/<interface>`` created by
:func:`amr_description.sim.urdf_to_mjcf.urdf_to_spec`. Commands are clamped to the
interface's ``min``/``max``; a NaN command means "no command": a velocity actuator then
holds zero velocity, an effort actuator applies zero, a position actuator holds the current
position.

A velocity interface with ``ki`` in the ``<mujoco>`` block is a PI servo of two actuators
that get the same command: ``<joint>/velocity`` (torque ``kv (command - qdot)``) and
``<joint>/velocity/integral`` (MuJoCo ``intvelocity``: its activation integrates the command,
torque ``ki (act - q)``); the joint's actuator force range limits their sum. Anti-windup, as
in a motor drive: at every write the activation is kept where the total torque it asks for
stays inside that range (``lo <= kv (command - qdot) + ki (act - q) <= hi``), so a blocked
or overloaded wheel does not store up a run-away.

As gz_ros2_control's ``GazeboSimSystem`` (``gazebo`` given: the robot's
:class:`~amr_description.core.gazebo.tags.ControlPlugin`; gz_ros2_control ``gz_system.cpp``
``write``), a joint's command is what a controller claims now (learnt through
:meth:`perform_command_mode_switch`): a claimed ``velocity`` is the velocity servo's target; a
claimed ``position`` is a velocity target too, ``position_proportional_gain * (command - q) /
period`` (gz: the gain times the error times the update rate; its actuator is a velocity
servo, built so by :func:`amr_description.sim.urdf_to_mjcf.urdf_to_spec`); a claimed
``effort`` is the motor's force. With nothing claimed the joint is held at velocity 0
(``hold_joints``, default) or left free. The actuators a joint does not use at the moment
are switched off (MuJoCo actuator group :data:`IDLE_GROUP`, disabled through
``opt.disableactuator``), so they exert no force at all.
"""

import math

from amr_description.control.hardware_interface import SystemInterface

_STATE_KINDS = ('position', 'velocity', 'effort')
IDLE_GROUP = 30
"""MuJoCo actuator group of the actuators a gz_ros2_control joint does not use now."""
_COMMAND_KINDS = ('position', 'velocity', 'effort')


class MujocoSystem(SystemInterface):
    """
    A ``SystemInterface`` whose joints live in a MuJoCo model.

    :param model: the compiled ``mujoco.MjModel`` holding the robot.
    :param data: its ``mujoco.MjData``.
    :param prefix: name prefix of the robot's joints and actuators in the model
        (``'<entity name>/'`` when spawned by :class:`amr_description.sim.world.World`).
    :param gazebo: gz_ros2_control's plugin settings
        (:class:`~amr_description.core.gazebo.tags.ControlPlugin`: ``hold_joints``,
        ``position_proportional_gain``) for a ``gz_ros2_control/GazeboSimSystem`` component,
        None for ``amr_description/MujocoSystem`` (NaN command = hold).
    """

    def __init__(self, model=None, data=None, prefix='', gazebo=None):
        """Keep the model and data; addresses are resolved by :meth:`on_init`."""
        super().__init__()
        self.model = model
        self.data = data
        self.prefix = prefix
        self._states = []    # (handle, array, index): array is a view into self.data
        self._commands = []  # (handle, actuator id, lo, hi, kind, qpos address)
        # PI velocity servos: (handle, command lo, hi, qpos address, _integral_of(actuator))
        self._integrals = []
        self.gazebo = gazebo
        self.active = set()  # claimed command interfaces (full names)
        self._active_handles = set()  # their handles (the control update compares these)
        self._gz_joints = []  # gazebo: per joint, its commands by kind (see _resolve)

    def on_init(self, info):
        """
        Create the handles and resolve every joint's addresses once.

        :param info: the ``HardwareInfo`` of this component.
        :returns: True.
        :raises ValueError: one line when the model is missing, a joint is not in the model,
            an interface is not position/velocity/effort, or a command interface has no
            actuator.
        """
        super().on_init(info)
        if self.model is None or self.data is None:
            raise ValueError(
                f'hardware component {self.name!r}: MujocoSystem needs the simulator '
                '(run the robot in mujoco_sim)')
        self._resolve()
        self.read(0.0, 0.0)
        return True

    def rebind(self, model, data):
        """
        Point at a recompiled model/data (after another entity was spawned) and re-resolve.

        :param model: the new ``mujoco.MjModel``.
        :param data: the new ``mujoco.MjData``.
        :raises ValueError: as :meth:`on_init`.
        """
        self.model = model
        self.data = data
        self._resolve()

    def _resolve(self):
        """Fill the state/command address tables from the model."""
        states, commands = [], []
        for joint_info in self.info.joints:
            name = self.prefix + joint_info.name
            try:
                joint = self.model.joint(name)
            except KeyError:
                raise ValueError(
                    f'hardware component {self.name!r}: joint {joint_info.name!r} is not in '
                    'the simulated model') from None
            qadr, dadr = int(joint.qposadr[0]), int(joint.dofadr[0])
            for iface in joint_info.state_interfaces:
                if iface.name not in _STATE_KINDS:
                    raise ValueError(
                        f'hardware component {self.name!r}: joint {joint_info.name!r} state '
                        f'interface {iface.name!r} is not one of {", ".join(_STATE_KINDS)}')
                handle = self.state_handles[f'{joint_info.name}/{iface.name}']
                array, index = {'position': (self.data.qpos, qadr),
                                'velocity': (self.data.qvel, dadr),
                                'effort': (self.data.qfrc_actuator, dadr)}[iface.name]
                states.append((handle, array, index))
            for iface in joint_info.command_interfaces:
                actuator_name = f'{name}/{iface.name}'
                try:
                    actuator = int(self.model.actuator(actuator_name).id)
                except KeyError:
                    raise ValueError(
                        f'hardware component {self.name!r}: no actuator {actuator_name!r} for '
                        f'command interface {joint_info.name}/{iface.name}') from None
                lo = -math.inf if iface.min is None else float(iface.min)
                hi = math.inf if iface.max is None else float(iface.max)
                handle = self.command_handles[f'{joint_info.name}/{iface.name}']
                commands.append((handle, actuator, lo, hi, iface.name, qadr))
        self._states = states
        self._commands = commands
        integrals = []
        for handle, actuator, lo, hi, kind, qadr in commands:
            integral = self._integral_of(actuator) if kind == 'velocity' else None
            if integral is not None:
                integrals.append((handle, lo, hi, qadr, integral))
        self._integrals = integrals
        self._ctrl = self.data.ctrl
        self._qpos = self.data.qpos
        if self.gazebo is not None:
            self._resolve_gazebo(commands)

    def _integral_of(self, actuator):
        """
        Return the I part of the PI velocity servo whose P part is ``actuator``, or None.

        :returns: ``(integral actuator id, its act address, dof address, kv, ki, joint force
            lo, hi)``.
        """
        model = self.model
        try:
            integral = model.actuator(model.actuator(actuator).name + '/integral')
        except KeyError:
            return None
        jid = int(model.actuator_trnid[actuator, 0])
        flo, fhi = (float(v) for v in model.jnt_actfrcrange[jid])
        if not model.jnt_actfrclimited[jid]:
            flo, fhi = -math.inf, math.inf
        return (int(integral.id), int(integral.actadr[0]), int(model.jnt_dofadr[jid]),
                float(model.actuator_gainprm[actuator, 0]), float(integral.gainprm[0]),
                flo, fhi)

    def _drive_integral(self, target, qadr, integral):
        """Give the I part ``target`` and keep its torque inside the joint's force range."""
        index, actadr, dadr, kv, ki, flo, fhi = integral
        self._ctrl[index] = target
        proportional = kv * (target - self.data.qvel[dadr])
        position = self._qpos[qadr]
        act = self.data.act
        act[actadr] = min(max(act[actadr], position + (flo - proportional) / ki),
                          position + (fhi - proportional) / ki)

    def _resolve_gazebo(self, commands):
        """Group the commands per joint for gz_ros2_control's write; switch off idle ones."""
        model = self.model
        joints = {}
        for handle, actuator, lo, hi, kind, qadr in commands:
            integral = self._integral_of(actuator)
            joint = joints.setdefault(int(model.actuator_trnid[actuator, 0]),
                                      {'qadr': qadr, 'actuators': []})
            joint[kind] = (handle, actuator, lo, hi, integral)
            joint['actuators'] += [actuator] + ([integral[0]] if integral else [])
        self._gz_joints = list(joints.values())
        model.opt.disableactuator |= 1 << IDLE_GROUP
        for joint in self._gz_joints:
            for actuator in joint['actuators']:
                model.actuator_group[actuator] = IDLE_GROUP

    def perform_command_mode_switch(self, start_interfaces, stop_interfaces):
        """
        Record the command interfaces controllers claim and release (gz_ros2_control's).

        :param start_interfaces: full names now claimed.
        :param stop_interfaces: full names now released.
        :returns: True.
        """
        self.active = (self.active - set(stop_interfaces)) | set(start_interfaces)
        self._active_handles = {self.command_handles[name] for name in self.active}
        return True

    def read(self, time, period):
        """
        Copy joint positions, velocities and efforts from ``MjData`` into the state handles.

        :param time: sim time in s (unused).
        :param period: s since the last read (unused).
        :returns: True.
        """
        for handle, array, index in self._states:
            handle.value = array.item(index)
        return True

    def write(self, time, period):
        """
        Copy the command handles into the actuators' ``ctrl`` (clamped; NaN = hold).

        :param time: sim time in s (unused).
        :param period: s since the last write (unused).
        :returns: True.
        """
        if self.gazebo is not None:
            self._write_gazebo(period)
            return True
        ctrl = self._ctrl
        qpos = self._qpos
        for handle, actuator, lo, hi, kind, qadr in self._commands:
            value = handle.value
            if value != value:  # NaN: no command
                value = qpos[qadr] if kind == 'position' else 0.0
            ctrl[actuator] = min(max(value, lo), hi)
        for handle, lo, hi, qadr, integral in self._integrals:
            value = handle.value
            self._drive_integral(0.0 if value != value else min(max(value, lo), hi), qadr,
                                 integral)
        return True

    def _write_gazebo(self, period):
        """gz_ros2_control's write: the claimed command of each joint, else hold or free."""
        ctrl, qpos = self._ctrl, self._qpos
        groups = self.model.actuator_group
        gain = self.gazebo.position_proportional_gain
        active = self._active_handles
        for joint in self._gz_joints:
            kind = next((k for k in ('velocity', 'position', 'effort')
                         if k in joint and joint[k][0] in active), None)
            target = 0.0  # unclaimed, held: velocity 0; a NaN command: the same
            if kind is None:
                kind = next((k for k in ('velocity', 'position') if k in joint), None) \
                    if self.gazebo.hold_joints else None
            elif joint[kind][0].value == joint[kind][0].value:
                handle, _, lo, hi, _ = joint[kind]
                target = min(max(handle.value, lo), hi)
                if kind == 'position':
                    target = gain * (target - qpos[joint['qadr']]) / period if period > 0 \
                        else 0.0
            used = ()
            if kind is not None:
                _, actuator, _, _, integral = joint[kind]
                ctrl[actuator] = target
                used = (actuator,)
                if integral is not None:
                    used = (actuator, integral[0])
                    self._drive_integral(target, joint['qadr'], integral)
            for actuator in joint['actuators']:
                groups[actuator] = 0 if actuator in used else IDLE_GROUP

    def on_deactivate(self):
        """
        Stop the joints: velocity and effort commands to zero, positions held.

        :returns: True.
        """
        for handle, actuator, lo, hi, kind, qadr in self._commands:
            self.data.ctrl[actuator] = self.data.qpos[qadr] if kind == 'position' else 0.0
        for *_, integral in self._integrals:
            self.data.ctrl[integral[0]] = 0.0
        return True
