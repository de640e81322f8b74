# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim systems a robot description names in ``<gazebo><plugin>`` (no rclpy).

gz-sim runs a model's systems (DiffDrive, JointStatePublisher, OdometryPublisher; parameters
read by :mod:`amr_description.core.gazebo.systems`) at every physics step. Here a robot's
systems are one :class:`SystemGroup` that the
:class:`~amr_description.sim.simulation.Simulation` steps like a controller manager, at
:data:`~amr_description.sim.systems.base.SYSTEM_RATE` Hz of sim time (or faster when a system
publishes faster), between the physics steps. Each system hands the ROS side its
:attr:`~ModelSystem.outputs` (sensor-like publishers, published by the ``mujoco_sim`` node as
the sensors are) and its :attr:`~ModelSystem.inputs` (subscriptions). Topics are gz topics:
as there is no ros_gz_bridge here, each is the ROS topic of the same name, carrying what the
bridge would deliver (docs/gazebo.md).
"""

import copy

from amr_description.core.gazebo.systems import resolve_defaults
from amr_description.sim.systems.base import SYSTEM_RATE
from amr_description.sim.systems.diff_drive import DiffDrive
from amr_description.sim.systems.joint_state_publisher import JointStatePublisher
from amr_description.sim.systems.odometry_publisher import OdometryPublisher


class SystemGroup:
    """
    The gz-sim systems of one spawned robot, stepped together.

    :param systems: list of :class:`~amr_description.sim.systems.base.ModelSystem`.
    :ivar update_rate: Hz of sim time:
        :data:`~amr_description.sim.systems.base.SYSTEM_RATE`, or the fastest system's rate.
    """

    def __init__(self, systems):
        """Keep the systems and choose the update rate (see the class docstring)."""
        self.systems = list(systems)
        self.update_rate = max([SYSTEM_RATE] + [s.rate for s in self.systems])

    def update(self, t, period):
        """Run every system's update at sim time ``t`` (s), ``period`` s after the last."""
        for system in self.systems:
            system.update(t, period)

    def reset(self):
        """Reset every system's state (the world was reset to its spawn poses)."""
        for system in self.systems:
            system.reset()


def make_systems(entity, world, world_name):
    """
    Return the systems of ``entity`` (a list; empty without any).

    :param entity: the spawned :class:`~amr_description.sim.entity.Entity`
        (``description.gz_systems``, ``name``, ``robot.root``, ``robot.prefix``).
    :param world: the :class:`~amr_description.sim.world.World` holding it.
    :param world_name: the world's name, for ``/world/<world>/model/<model>/...`` topics.
    :raises ValueError: one line from a system that cannot bind to the model.
    """
    parsed = entity.description.gz_systems
    if not parsed:
        return []
    params = resolve_defaults(copy.deepcopy(parsed), entity.name, entity.robot.root,
                              world_name)
    systems = [DiffDrive(p, world, entity) for p in params.diff_drives]
    systems += [JointStatePublisher(p, world, entity) for p in params.joint_state_publishers]
    systems += [OdometryPublisher(p, world, entity) for p in params.odometry_publishers]
    return systems
