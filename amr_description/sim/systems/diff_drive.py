# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim 8's DiffDrive system: Twist in, wheel velocities out, wheel odometry and TF out.

Reproduced from gz-sim 8 ``src/systems/diff_drive/DiffDrive.cc`` (behaviour, not code):

- the command topic carries ``geometry_msgs/Twist`` (ros_gz_bridge's ``gz.msgs.Twist``); only
  ``linear.x`` and ``angular.z`` are used; ``/model/<model>/enable`` (``std_msgs/Bool``)
  false stops the robot and ignores commands until true;
- every update the target is limited (gz-math's SpeedLimiter: jerk, then acceleration, then
  velocity; :class:`~amr_description.core.speed_limiter.SpeedLimiter` with symmetric
  limits), then every left joint gets ``(v - w s / 2) / r`` rad/s and every right joint
  ``(v + w s / 2) / r`` (``s`` = wheel_separation, ``r`` = wheel_radius) as a velocity
  command: the joint's velocity servo, bounded by its URDF ``<limit effort>``, as gz's
  ``JointVelocityCmd``;
- odometry is dead-reckoned at ``odom_publish_frequency`` from the first left and first right
  joint's angle (gz-math's DiffDriveOdometry: exact arcs, twist a rolling mean of 10
  samples; :class:`~amr_description.core.odometry.Odometry`), not ground truth; it is
  published as ``nav_msgs/Odometry`` (pose x, y, yaw; twist ``linear.x``, ``angular.z``) and
  as a ``tf2_msgs/TFMessage`` of one transform ``frame_id`` -> ``child_frame_id``, with
  ``::`` in frame ids turned into ``/`` (ros_gz_bridge).
"""

import math

from amr_description.core.gazebo.systems import frame_id_gz_to_ros
from amr_description.core.odometry import Odometry
from amr_description.core.speed_limiter import SpeedLimiter
from amr_description.ros.stamps import set_stamp
from amr_description.sim.systems.base import Input
from amr_description.sim.systems.base import joint_hardware
from amr_description.sim.systems.base import ModelSystem
from amr_description.sim.systems.base import Output
from geometry_msgs.msg import TransformStamped
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry as OdometryMsg
from std_msgs.msg import Bool
from tf2_msgs.msg import TFMessage

ODOMETRY_WINDOW = 10
"""Samples of gz-math DiffDriveOdometry's velocity rolling mean."""


def gz_limiter(limits, where):
    """
    Return a SpeedLimiter acting as gz-math's for one channel, or None without limits.

    gz-math clamps the velocity to ``[min_velocity, max_velocity]``, its change over ``dt``
    to ``[min_acceleration, max_acceleration] * dt`` whatever the direction, and the change
    of that change as the jerk; an absent bound is infinite.

    :param limits: dict with any of ``min_/max_`` + ``velocity``/``acceleration``/``jerk``.
    :param where: the plugin, for the error message.
    :raises ValueError: one line when a bound has the wrong sign (e.g. ``max_velocity < 0``).
    """
    if not limits:
        return None
    inf = math.inf
    low_acc = limits.get('min_acceleration', -inf)
    high_acc = limits.get('max_acceleration', inf)
    try:
        return SpeedLimiter(max_velocity=limits.get('max_velocity', inf),
                            min_velocity=limits.get('min_velocity', -inf),
                            max_acceleration=high_acc, max_deceleration_reverse=high_acc,
                            max_deceleration=low_acc, max_acceleration_reverse=low_acc,
                            max_jerk=limits.get('max_jerk', inf),
                            min_jerk=limits.get('min_jerk', -inf))
    except ValueError as exc:
        raise ValueError(f'{where}: {exc}') from None


class DiffDrive(ModelSystem):
    """
    One DiffDrive system of one robot (see the module docstring).

    :param params: :class:`~amr_description.core.gazebo.systems.DiffDriveParams` with its
        defaults resolved.
    :param world: the :class:`~amr_description.sim.world.World`.
    :param entity: the spawned entity.
    :raises ValueError: one line when a wheel joint has no velocity actuator or a limit has
        the wrong sign.
    """

    def __init__(self, params, world, entity):
        """Bind the wheel joints and prepare the topics (see the class docstring)."""
        super().__init__()
        where = f'entity {entity.name!r} DiffDrive'
        self.params = params
        self.rate = float(params.odom_publish_frequency)
        self._linear_limiter = gz_limiter(params.linear, f'{where} linear limits')
        self._angular_limiter = gz_limiter(params.angular, f'{where} angular limits')
        self.hardware = joint_hardware(world, entity, where, params.joints(), ('velocity',))
        self._left = [self.hardware.command_handles[f'{j}/velocity']
                      for j in params.left_joints]
        self._right = [self.hardware.command_handles[f'{j}/velocity']
                       for j in params.right_joints]
        self._left_position = self.hardware.state_handles[f'{params.left_joints[0]}/position']
        self._right_position = self.hardware.state_handles[
            f'{params.right_joints[0]}/position']
        self._odometry_period = 1.0 / self.rate if self.rate > 0 else 0.0
        self._odom_msg = OdometryMsg()
        self._odom_msg.header.frame_id = frame_id_gz_to_ros(params.frame_id)
        self._odom_msg.child_frame_id = frame_id_gz_to_ros(params.child_frame_id)
        self._tf_msg = TFMessage(transforms=[TransformStamped()])
        self._tf_msg.transforms[0].header.frame_id = self._odom_msg.header.frame_id
        self._tf_msg.transforms[0].child_frame_id = self._odom_msg.child_frame_id
        model = f'/model/{entity.name}'
        self.inputs = [Input(params.topic, Twist, self.on_command),
                       Input(f'{model}/enable', Bool, self.on_enable)]
        if self.rate > 0:
            self.outputs = [
                Output('diff_drive/odometry', params.odom_topic, OdometryMsg, self.rate,
                       self.odometry_message),
                Output('diff_drive/tf', params.tf_topic, TFMessage, self.rate,
                       self.tf_message)]
        self.reset()

    def reset(self):
        """Stop: zero target and limiter history, odometry back at the origin."""
        self._target = (0.0, 0.0)
        self._enabled = True
        self._last = ((0.0, 0.0), (0.0, 0.0))  # (last command, the one before)
        self.odometry = Odometry(self.params.wheel_separation, self.params.wheel_radius,
                                 self.params.wheel_radius, ODOMETRY_WINDOW)
        self._next_odometry = None

    # ---------------------------------------------------------------- inputs (ROS thread)
    def on_command(self, msg):
        """Take ``linear.x`` (m/s) and ``angular.z`` (rad/s) of a Twist as the target."""
        linear, angular = float(msg.linear.x), float(msg.angular.z)
        if self._enabled and math.isfinite(linear) and math.isfinite(angular):
            self._target = (linear, angular)

    def on_enable(self, msg):
        """Enable (true) or stop and disable (false) the system."""
        self._enabled = bool(msg.data)
        if not self._enabled:
            self._target = (0.0, 0.0)

    # ---------------------------------------------------------------- update (sim thread)
    def wheel_speeds(self, linear, angular):
        """Return (left, right) wheel speeds in rad/s for a twist (m/s, rad/s)."""
        half = 0.5 * angular * self.params.wheel_separation
        radius = self.params.wheel_radius
        return (linear - half) / radius, (linear + half) / radius

    def limited(self, target, period):
        """Return the target twist limited as gz-math's SpeedLimiter over ``period`` s."""
        (last0, last1) = self._last
        linear, angular = target
        if self._linear_limiter is not None:
            linear = self._linear_limiter.limit(linear, last0[0], last1[0], period)
        if self._angular_limiter is not None:
            angular = self._angular_limiter.limit(angular, last0[1], last1[1], period)
        self._last = ((linear, angular), last0)
        return linear, angular

    def update(self, t, period):
        """Command the wheels, then update the odometry when it is due (module docstring)."""
        left, right = self.wheel_speeds(*self.limited(self._target, period))
        for handle in self._left:
            handle.value = left
        for handle in self._right:
            handle.value = right
        self.hardware.write(t, period)
        if self._next_odometry is None or t >= self._next_odometry - 1e-9:
            self._next_odometry = t + self._odometry_period
            self.hardware.read(t, period)
            self.odometry.update(self._left_position.value, self._right_position.value, t)

    # ---------------------------------------------------------------- outputs (sim thread)
    def odometry_message(self, world, t):
        """Return the wheel odometry as ``nav_msgs/Odometry`` stamped ``t`` (s)."""
        msg = self._odom_msg
        set_stamp(msg.header.stamp, t)
        odometry = self.odometry
        msg.pose.pose.position.x = odometry.x
        msg.pose.pose.position.y = odometry.y
        msg.pose.pose.orientation.z = math.sin(0.5 * odometry.heading)
        msg.pose.pose.orientation.w = math.cos(0.5 * odometry.heading)
        msg.twist.twist.linear.x = odometry.linear
        msg.twist.twist.angular.z = odometry.angular
        return msg

    def tf_message(self, world, t):
        """Return the odometry as one transform ``frame_id`` -> ``child_frame_id``."""
        transform = self._tf_msg.transforms[0]
        set_stamp(transform.header.stamp, t)
        odometry = self.odometry
        transform.transform.translation.x = odometry.x
        transform.transform.translation.y = odometry.y
        transform.transform.rotation.z = math.sin(0.5 * odometry.heading)
        transform.transform.rotation.w = math.cos(0.5 * odometry.heading)
        return self._tf_msg
