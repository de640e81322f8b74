# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
An IMU: ``imu`` sensor blocks, from MuJoCo's own accelerometer, gyro and framequat.

As gz-sensors 8 ``ImuSensor`` through ros_gz_bridge: ``sensor_msgs/Imu`` on ``<topic>`` with
the orientation of the sensor frame in the world frame (all zero when
``<enable_orientation>`` is false), the angular velocity (rad/s) and the linear acceleration
including gravity (m/s^2; +9.81 on z at rest, REP 103) in the sensor frame, covariance
diagonals the noise stddev squared per axis, orientation covariance 0. Noise per axis as
:mod:`~amr_description.sim.sensors.noise`. The values are MuJoCo's sensor stage of the last
physics step (``mj_step`` computes sensors before it integrates), i.e. of the state one
physics step (1 ms by default) before the stamp.
"""

from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
from amr_description.sim.sensors.mount import imu_sensor_names
from amr_description.sim.sensors.noise import AxesNoise
from amr_description.sim.sensors.noise import generator
import numpy as np
from sensor_msgs.msg import Imu as ImuMessage


class Imu(Sensor):
    """
    One IMU of one entity (module docstring); measured at every due instant.

    :param prefix: the entity's name prefix in the world (``<entity>/``).
    :param block: the :class:`~amr_description.core.gazebo.sensors.SensorBlock`.
    :param topics: ``(ROS topic, gz topic)``.
    :param frame_id: ``header.frame_id``.
    :param rate: Hz of sim time.
    :param rng: numpy ``Generator`` of its noise.
    """

    message_type = ImuMessage

    def __init__(self, prefix, block, topics, frame_id, rate, rng):
        """Bind the noise models and prepare the reused message."""
        self.name = block.name
        self.topic, self.gz_name = topics
        self.frame_id = frame_id
        self.rate = float(rate)
        self._names = tuple(prefix + n for n in imu_sensor_names(block))
        self._orientation = block.imu.enable_orientation
        # one draw per measurement for the six axes: linear acceleration x y z, then angular
        # velocity x y z
        self._noise = AxesNoise(list(block.imu.linear_acceleration)
                                + list(block.imu.angular_velocity), rng)
        msg = ImuMessage()
        msg.header.frame_id = frame_id
        for i, noise in enumerate(block.imu.angular_velocity):
            msg.angular_velocity_covariance[4 * i] = noise.stddev ** 2
        for i, noise in enumerate(block.imu.linear_acceleration):
            msg.linear_acceleration_covariance[4 * i] = noise.stddev ** 2
        self._msg = msg
        self._model = None

    def measure(self, world, t):
        """Return the Imu message of sim time ``t`` (s) (module docstring)."""
        model, data = world.model, world.data
        if self._model is not model:
            accel, gyro, quat = (int(model.sensor(n).adr[0]) for n in self._names)
            self._axes = np.r_[accel:accel + 3, gyro:gyro + 3]
            self._quat = quat
            self._model = model
        values = data.sensordata
        ax, ay, az, wx, wy, wz = self._noise.apply(values[self._axes]).tolist()
        msg = self._msg
        set_stamp(msg.header.stamp, t)
        a, w = msg.linear_acceleration, msg.angular_velocity
        a.x, a.y, a.z = ax, ay, az
        w.x, w.y, w.z = wx, wy, wz
        if self._orientation:
            q = msg.orientation
            q.w, q.x, q.y, q.z = values[self._quat:self._quat + 4].tolist()
        return msg

    def advance(self, world, t):
        """Draw the noise of the measurement at ``t`` (s) that nobody hears; no message."""
        self._noise.skip()


def create(entity, settings):
    """
    Return the sensors of every IMU block of ``entity`` (settings as the lidar's ``create``).

    :param entity: the spawned entity.
    :param settings: dict; ``seed``, ``physics_step``, ``world``.
    """
    sensors = []
    for block in entity.description.sensors.sensors:
        if block.kind != 'imu':
            continue
        sensors.append(Imu(entity.robot.prefix, block,
                           sensor_topic(entity, block, settings.get('world', 'empty')),
                           sensor_frame(entity, block),
                           sensor_rate(block, float(settings.get('physics_step', 0.001))),
                           generator(settings.get('seed', 0), entity.name, block.name)))
    return sensors
