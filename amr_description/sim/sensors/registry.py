# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Sensor factories registered in the entry-point group ``amr_description.sensors``.

A factory is ``factory(entity, settings) -> list of Sensor``: it reads what it needs from the
entity's description (``entity.description``) and from the simulator-wide ``settings`` (a
dict of the ``mujoco_sim`` parameters that concern sensors, e.g. ``publish_ground_truth``,
``ground_truth_rate``) and returns the entity's sensors of its type (none when the entity
declares none). As upstream mujoco_ros2_control keeps one file per sensor, each type is one
module with one entry point in setup.py.
"""

import functools
from importlib.metadata import entry_points

SENSOR_GROUP = 'amr_description.sensors'


@functools.lru_cache(maxsize=None)
def _registered():
    found = {ep.name: ep for ep in entry_points(group=SENSOR_GROUP)}
    return tuple((name, found[name].load()) for name in sorted(found))


def sensor_factories():
    """Return the registered sensor factories, dict entry-point name -> factory, by name."""
    return dict(_registered())


def make_sensors(entity, settings, factories=None):
    """
    Return every sensor of ``entity``, from every registered factory in name order.

    :param entity: the spawned :class:`~amr_description.sim.simulation.Entity`.
    :param settings: dict of simulator-wide sensor settings.
    :param factories: dict name -> factory (default: :func:`sensor_factories`).
    :raises ValueError: one line naming the sensor and the field, from a factory.
    """
    sensors = []
    for factory in (sensor_factories() if factories is None else factories).values():
        sensors += list(factory(entity, settings))
    return sensors
