# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Ground truth: the exact pose and twist of a robot's root link (gz-sim's OdometryPublisher role).

Publishes ``nav_msgs/Odometry`` on ``<namespace>/ground_truth/odom`` at ``ground_truth_rate``
Hz of sim time (default 50): pose of the root link in frame ``world``, twist in the root link
frame (the Odometry convention, REP 105), child frame the root link with the entity's frame
prefix (``base_footprint``, ``r1/base_footprint``). The values are MuJoCo's state of the
robot's free joint (:meth:`~amr_description.sim.world.World.ground_truth`).
"""

from amr_description.sim.sensors.base import fill_odometry
from amr_description.sim.sensors.base import Sensor
from nav_msgs.msg import Odometry

DEFAULT_RATE = 50.0
"""Hz of sim time, the ``ground_truth_rate`` parameter's default."""


class GroundTruth(Sensor):
    """
    The ground-truth odometry of one entity.

    :param entity: the spawned entity (``name``, ``namespace``, ``frame_prefix``,
        ``robot.root``).
    :param rate: Hz of sim time (> 0).
    """

    message_type = Odometry
    costly = True  # no state; skipping an unheard message saves its conversion (fleets)

    def __init__(self, entity, rate=DEFAULT_RATE):
        """Keep the entity's name and prepare the reused message (see the class docstring)."""
        self.name = 'ground_truth'
        self.topic = f'{entity.namespace}/ground_truth/odom'
        self.frame_id = 'world'
        self.rate = float(rate)
        self._entity_name = entity.name
        self._msg = Odometry()
        self._msg.header.frame_id = 'world'
        self._msg.child_frame_id = entity.frame_prefix + entity.robot.root

    def measure(self, world, t):
        """Return the Odometry of the root link at sim time ``t`` (s) (module docstring)."""
        position, quat, linear, angular = world.ground_truth(self._entity_name)
        return fill_odometry(self._msg, t, position, quat, linear, angular)


def create(entity, settings):
    """
    Return ``[GroundTruth]`` for every entity, or ``[]`` when switched off.

    :param entity: the spawned entity.
    :param settings: dict; ``publish_ground_truth`` (bool, default True) and
        ``ground_truth_rate`` (Hz, default 50; <= 0 switches it off, as before).
    """
    rate = float(settings.get('ground_truth_rate', DEFAULT_RATE))
    if not settings.get('publish_ground_truth', True) or not rate > 0:
        return []
    return [GroundTruth(entity, rate)]
