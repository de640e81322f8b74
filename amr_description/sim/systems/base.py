# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The protocol of a gz-sim system run by the simulator (no rclpy)."""

from amr_description.core.description.ros2_control_info import ComponentInfo
from amr_description.core.description.ros2_control_info import HardwareInfo
from amr_description.core.description.ros2_control_info import InterfaceInfo
from amr_description.sim.mujoco_system import MujocoSystem
from amr_description.sim.sensors.base import Sensor

SYSTEM_RATE = 100.0
"""Hz of sim time at which a robot's gz-sim systems run (gz-sim: every physics step)."""


class Input:
    """
    A topic a system listens to: the ROS side subscribes ``callback`` to it.

    :param topic: absolute topic name.
    :param message_type: the ROS message class.
    :param callback: ``(message) -> None``; called on the ROS executor's thread, so it only
        stores what the next :meth:`ModelSystem.update` reads.
    """

    def __init__(self, topic, message_type, callback):
        """Keep the fields (see the class docstring)."""
        self.topic = topic
        self.message_type = message_type
        self.callback = callback


class Output(Sensor):
    """
    A topic a system publishes, as a sensor whose measurement the system makes.

    A :class:`~amr_description.sim.sensors.base.Sensor` whose :meth:`measure` is the
    system's ``measure(world, t)``.

    :param name: unique within the entity (str).
    :param topic: absolute topic name.
    :param message_type: the ROS message class ``measure`` returns.
    :param rate: Hz of sim time (> 0).
    :param measure: ``(world, t) -> message``.
    :param costly: True to skip measuring while nobody subscribes (stateless formatting).
    """

    def __init__(self, name, topic, message_type, rate, measure, costly=True):
        """Keep the fields (see the class docstring)."""
        self.name = name
        self.topic = topic
        self.gz_name = topic
        self.frame_id = ''
        self.message_type = message_type
        self.rate = float(rate)
        self.measure = measure
        self.costly = costly


class ModelSystem:
    """
    One gz-sim system of one spawned robot.

    :ivar rate: Hz of sim time the system needs to be updated at (its fastest output).
    :ivar outputs: list of :class:`Output`.
    :ivar inputs: list of :class:`Input`.
    :ivar hardware: the :class:`~amr_description.sim.mujoco_system.MujocoSystem` it reads
        and writes the joints through (rebound by the simulation when the model is
        recompiled), or None.
    """

    rate = 0.0

    def __init__(self):
        """Start with no outputs, inputs or hardware."""
        self.outputs = []
        self.inputs = []
        self.hardware = None

    def update(self, t, period):
        """Run one update at sim time ``t`` (s), ``period`` s after the previous one."""

    def reset(self):
        """Forget the state kept between updates (after a world reset)."""


def joint_hardware(world, entity, name, joints, commands=(), states=('position', 'velocity')):
    """
    Return a started MujocoSystem for ``joints`` of ``entity``, rebound with its others.

    :param world: the :class:`~amr_description.sim.world.World`.
    :param entity: the spawned entity (``robot.prefix``, ``systems``).
    :param name: the component's name in error messages.
    :param joints: URDF joint names.
    :param commands: command interface names of every joint (their actuators must exist:
        :meth:`~amr_description.core.gazebo.systems.GazeboSystems.hardware`).
    :param states: state interface names of every joint.
    :raises ValueError: one line naming a joint or actuator missing from the model.
    """
    info = HardwareInfo(name=name, type='system', plugin='amr_description/MujocoSystem',
                        joints=[ComponentInfo(joint, [InterfaceInfo(c) for c in commands],
                                              [InterfaceInfo(s) for s in states])
                                for joint in joints])
    system = MujocoSystem(world.model, world.data, prefix=entity.robot.prefix)
    system.on_init(info)
    entity.systems.append(system)
    return system
