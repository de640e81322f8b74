# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim 8's OdometryPublisher system: ground-truth odometry of the model, with its frames.

As gz-sim 8 ``src/systems/odometry_publisher`` with ros_gz_bridge's conversions: the pose is
the model's world pose (its root link's) composed with the offset
(``<xyz_offset>``, ``<rpy_offset>``: a pose in the robot frame), in ``odom_frame``; the twist
is in ``robot_base_frame``. With ``<dimensions>`` 2 the pose keeps x, y and yaw (z, roll and
pitch 0) and the twist ``linear.x``, ``linear.y`` and ``angular.z``. ``<gaussian_noise>``
(standard deviation, m, rad, m/s, rad/s) is added to every kept component, and the
covariance topic's message carries its square on the diagonal. Published at
``odom_publish_frequency``: ``nav_msgs/Odometry`` on ``odom_topic`` and, with covariance, on
``odom_covariance_topic``; one transform ``odom_frame`` -> ``robot_base_frame`` on
``tf_topic``. Difference: gz-sim differentiates the pose over the publish period (a rolling
mean); here the twist is MuJoCo's exact velocity of the root link.
"""

import math

from amr_description.core.gazebo.systems import frame_id_gz_to_ros
from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import fill_odometry
from amr_description.sim.systems.base import ModelSystem
from amr_description.sim.systems.base import Output
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
import numpy as np
from tf2_msgs.msg import TFMessage


def quaternion_from_rpy(roll, pitch, yaw):
    """Return the quaternion (x, y, z, w) of fixed-axis roll, pitch, yaw (rad; REP 103)."""
    cr, sr = math.cos(0.5 * roll), math.sin(0.5 * roll)
    cp, sp = math.cos(0.5 * pitch), math.sin(0.5 * pitch)
    cy, sy = math.cos(0.5 * yaw), math.sin(0.5 * yaw)
    return np.array([sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                     cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy])


def quaternion_multiply(a, b):
    """Return the Hamilton product ``a b`` of two quaternions (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz])


def rotate(q, v):
    """Return vector ``v`` (3,) rotated by quaternion ``q`` (x, y, z, w)."""
    u = np.array(q[:3])
    w = q[3]
    v = np.asarray(v, dtype=float)
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def yaw_of(q):
    """Return the yaw (rad) of quaternion ``q`` (x, y, z, w), REP 103."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class OdometryPublisher(ModelSystem):
    """
    One OdometryPublisher of one robot (see the module docstring).

    :param params: :class:`~amr_description.core.gazebo.systems.OdometryPublisherParams`
        with its defaults resolved.
    :param world: the :class:`~amr_description.sim.world.World`.
    :param entity: the spawned entity.
    :param rng: a ``numpy.random.Generator`` for the noise (default: a fresh one).
    """

    def __init__(self, params, world, entity, rng=None):
        """Prepare the messages (see the class docstring)."""
        super().__init__()
        self.params = params
        self.rate = float(params.odom_publish_frequency)
        self._entity_name = entity.name
        self._offset_position = np.array(params.xyz_offset, dtype=float)
        self._offset_rotation = quaternion_from_rpy(*params.rpy_offset)
        self._rng = rng or np.random.default_rng()
        frame, child = (frame_id_gz_to_ros(params.odom_frame),
                        frame_id_gz_to_ros(params.robot_base_frame))
        self._odometry = Odometry()
        self._covariance = Odometry()
        for msg in (self._odometry, self._covariance):
            msg.header.frame_id, msg.child_frame_id = frame, child
        variance = params.gaussian_noise ** 2
        kept = range(6) if params.dimensions == 3 else (0, 1, 5)
        for index in kept:
            self._covariance.pose.covariance[index * 7] = variance
            self._covariance.twist.covariance[index * 7] = variance
        self._tf = TFMessage(transforms=[TransformStamped()])
        self._tf.transforms[0].header.frame_id = frame
        self._tf.transforms[0].child_frame_id = child
        if self.rate > 0:
            self.outputs = [
                Output('odometry_publisher/odometry', params.odom_topic, Odometry, self.rate,
                       lambda world, t: self._fill(self._odometry, world, t)),
                Output('odometry_publisher/odometry_with_covariance',
                       params.odom_covariance_topic, Odometry, self.rate,
                       lambda world, t: self._fill(self._covariance, world, t)),
                Output('odometry_publisher/tf', params.tf_topic, TFMessage, self.rate,
                       self.tf_message)]

    def state(self, world):
        """
        Return the odometry of the model now, as published (noise included).

        :returns: ``(position (3,), quaternion xyzw (4,), linear (3,), angular (3,))``:
            pose in the odometry frame (m), twist in the robot frame (m/s, rad/s).
        """
        position, quaternion, linear, angular = world.ground_truth(self._entity_name)
        position = position + rotate(quaternion, self._offset_position)
        quaternion = quaternion_multiply(quaternion, self._offset_rotation)
        linear, angular = np.array(linear, dtype=float), np.array(angular, dtype=float)
        noise = self.params.gaussian_noise
        if self.params.dimensions == 2:
            yaw = yaw_of(quaternion)
            if noise > 0:
                position[:2] += self._rng.normal(0.0, noise, 2)
                yaw += self._rng.normal(0.0, noise)
                linear[:2] += self._rng.normal(0.0, noise, 2)
                angular[2] += self._rng.normal(0.0, noise)
            position[2] = 0.0
            quaternion = np.array([0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw)])
            linear[2] = angular[0] = angular[1] = 0.0
        elif noise > 0:
            position += self._rng.normal(0.0, noise, 3)
            linear += self._rng.normal(0.0, noise, 3)
            angular += self._rng.normal(0.0, noise, 3)
        return position, quaternion, linear, angular

    def _fill(self, msg, world, t):
        position, quaternion, linear, angular = self.state(world)
        return fill_odometry(msg, t, position, quaternion, linear, angular)

    def tf_message(self, world, t):
        """Return one transform ``odom_frame`` -> ``robot_base_frame`` at sim time ``t``."""
        position, quaternion, _, _ = self.state(world)
        transform = self._tf.transforms[0]
        set_stamp(transform.header.stamp, t)
        tr, rot = transform.transform.translation, transform.transform.rotation
        tr.x, tr.y, tr.z = (float(v) for v in position)
        rot.x, rot.y, rot.z, rot.w = (float(v) for v in quaternion)
        return self._tf
