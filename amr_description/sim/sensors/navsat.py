# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A navigation-satellite (GPS) receiver: ``navsat`` sensor blocks.

The sensor's position in the world (its site, at the measured instant) goes to latitude,
longitude and altitude through the world's ``<spherical_coordinates>``
(:func:`~amr_description.core.geodesy.local_to_geodetic`, as gz-sim's NavSat system); the
``<position_sensing>`` noise is added as gz-sensors 8's ``NavSatSensor::Update`` adds it
(horizontal: to the latitude and to the longitude in degrees; vertical: to the altitude in m).
What reaches ROS is what ros_gz_bridge makes of it (``convert/sensor_msgs.cpp``):
``sensor_msgs/NavSatFix`` with ``status.status`` STATUS_FIX, ``status.service`` 0,
``position_covariance_type`` COVARIANCE_TYPE_UNKNOWN and a zero covariance. Default gz topic
``.../sensor/<name>/navsat``.

A navsat sensor in a world without ``<spherical_coordinates>`` is skipped with one line
(``settings['messages']``); the robot keeps its other sensors.
"""

from amr_description.core.geodesy import local_to_geodetic
from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
from amr_description.sim.sensors.mount import site_name
from amr_description.sim.sensors.noise import generator
from amr_description.sim.sensors.noise import NoiseModel
from sensor_msgs.msg import NavSatFix
from sensor_msgs.msg import NavSatStatus


class NavSat(Sensor):
    """The NavSatFix of one navsat block (module docstring)."""

    message_type = NavSatFix

    def __init__(self, prefix, block, topics, frame_id, rate, origin, rng):
        """Bind the noise and prepare the reused message."""
        self.name = block.name
        self.topic, self.gz_name = topics
        self.frame_id = frame_id
        self.rate = float(rate)
        self.origin = origin
        self._site = prefix + site_name(block)
        self._horizontal = NoiseModel(block.navsat.horizontal, rng)
        self._vertical = NoiseModel(block.navsat.vertical, rng)
        msg = NavSatFix()
        msg.header.frame_id = frame_id
        msg.status.status = NavSatStatus.STATUS_FIX
        msg.position_covariance_type = NavSatFix.COVARIANCE_TYPE_UNKNOWN
        self._msg = msg

    def measure(self, world, t):
        """Return the NavSatFix of sim time ``t`` (s)."""
        world.update_kinematics()
        x, y, z = (float(v) for v in world.data.site(self._site).xpos)
        latitude, longitude, altitude = local_to_geodetic(self.origin, x, y, z)
        msg = self._msg
        set_stamp(msg.header.stamp, t)
        msg.latitude = float(self._horizontal.apply(latitude))
        msg.longitude = float(self._horizontal.apply(longitude))
        msg.altitude = float(self._vertical.apply(altitude))
        return msg

    def advance(self, world, t):
        """Draw the noise of the instant ``t`` nobody hears; no message."""
        self._horizontal.skip(1)
        self._horizontal.skip(1)
        self._vertical.skip(1)


def create(entity, settings):
    """
    Return the sensors of every navsat block of ``entity``.

    :param entity: the spawned entity.
    :param settings: dict; ``seed``, ``physics_step``, ``world`` as the lidar's;
        ``spherical_coordinates`` (the world's, or None) and ``messages`` (a list one line is
        appended to per sensor skipped).
    """
    sensors = []
    origin = settings.get('spherical_coordinates')
    for block in entity.description.sensors.sensors:
        if block.kind != 'navsat':
            continue
        if origin is None:
            settings.setdefault('messages', []).append(
                f'sensor {block.name!r}: the world has no <spherical_coordinates> (the origin '
                'of latitude and longitude); the sensor is skipped')
            continue
        sensors.append(NavSat(entity.robot.prefix, block,
                              sensor_topic(entity, block, settings.get('world', 'empty')),
                              sensor_frame(entity, block),
                              sensor_rate(block, float(settings.get('physics_step', 0.001))),
                              origin, generator(settings.get('seed', 0), entity.name,
                                                block.name)))
    return sensors
