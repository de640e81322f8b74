# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
diff_drive_controller: ``TwistStamped`` commands to wheel velocities, odometry and TF.

Reproduced from ros2_controllers' diff_drive_controller (jazzy); parameters, defaults and
topics as upstream:

- subscribes ``~/cmd_vel`` (geometry_msgs/TwistStamped; ``linear.x`` m/s and ``angular.z``
  rad/s of ``base_frame_id`` are used). A zero stamp is replaced by "now" (warned once); a
  message older than ``cmd_vel_timeout`` is dropped with a warning; a NaN/inf command is
  ignored with a warning. When the last command is older than ``cmd_vel_timeout`` (s, 0
  disables) the controller brakes (commands zero).
- commands (after speed limits ``linear.x.*``/``angular.z.*``, see :mod:`core.speed_limiter`)
  every wheel ``<name>/velocity`` (rad/s): ``(v -+ w*s/2)/r`` per side, with
  ``s = wheel_separation * wheel_separation_multiplier`` and ``r = wheel_radius *
  {left,right}_wheel_radius_multiplier``. Before the first command nothing is written;
  deactivation writes zero to every wheel.
- odometry from ``<name>/position`` (``position_feedback``) or ``<name>/velocity`` states,
  averaged per side, or from the command (``open_loop``); published at ``publish_rate`` Hz on
  ``~/odom`` (nav_msgs/Odometry, ``odom_frame_id`` -> ``base_frame_id``, covariance diagonals
  at indices 0, 7, ..., 35) and on ``/tf`` when ``enable_odom_tf``; frame ids get the
  ``tf_frame_prefix`` (or the node namespace when empty) when ``tf_frame_prefix_enable``.
- ``~/cmd_vel_out`` (TwistStamped) carries the limited command when
  ``publish_limited_velocity``.
- a NaN wheel state makes ``update`` fail: the controller manager deactivates the controller.

``update`` runs in the simulation loop: configuration is read into attributes at configure
time, and the odometry/TF messages are built once and only their changing fields are written
before each publication.
"""

import math

from amr_description.control.controller_interface import ControllerInterface
from amr_description.control.controller_interface import TransitionCallbackReturn
from amr_description.control.parameter_table import at_least_one
from amr_description.control.parameter_table import attribute
from amr_description.control.parameter_table import not_empty
from amr_description.control.parameter_table import not_negative
from amr_description.control.parameter_table import Parameter
from amr_description.control.parameter_table import ParameterTable
from amr_description.control.parameter_table import positive
from amr_description.control.parameter_table import size
from amr_description.core.odometry import Odometry
from amr_description.core.speed_limiter import PARAMETER_NAMES as LIMIT_NAMES
from amr_description.core.speed_limiter import SpeedLimiter
from amr_description.ros.stamps import has_subscribers
from amr_description.ros.stamps import msg_to_time
from amr_description.ros.stamps import set_stamp
from amr_description.ros.stamps import time_to_msg
from geometry_msgs.msg import TransformStamped
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry as OdometryMsg
from rclpy.qos import DurabilityPolicy
from rclpy.qos import HistoryPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from tf2_msgs.msg import TFMessage


# QoS of tf2_ros::TransformBroadcaster (jazzy): reliable, volatile, keep last 100
TF_QOS = QoSProfile(depth=100, history=HistoryPolicy.KEEP_LAST,
                    reliability=ReliabilityPolicy.RELIABLE,
                    durability=DurabilityPolicy.VOLATILE)

PARAMETERS = ParameterTable('DiffDriveParameters', [
    Parameter('left_wheel_names', [''], 'Names of the joints of the left-side wheels',
              not_empty),
    Parameter('right_wheel_names', [''], 'Names of the joints of the right-side wheels',
              not_empty),
    Parameter('wheel_separation', 0.0, 'Distance between the left and right wheels (m); a '
              'wrong value makes the robot turn more or less than commanded', positive),
    Parameter('wheel_radius', 0.0, 'Wheel radius (m), converting linear speed to wheel '
              'rotation; a wrong value makes the robot faster or slower than commanded',
              positive),
    Parameter('wheel_separation_multiplier', 1.0, 'Correction factor of wheel_separation',
              positive),
    Parameter('left_wheel_radius_multiplier', 1.0,
              'Correction factor of the left wheel radius', positive),
    Parameter('right_wheel_radius_multiplier', 1.0,
              'Correction factor of the right wheel radius', positive),
    Parameter('tf_frame_prefix_enable', True, 'Prefix the odometry frames with tf_frame_prefix'),
    Parameter('tf_frame_prefix', '', 'Prefix of the odometry frames; empty: the node namespace'),
    Parameter('odom_frame_id', 'odom', 'Frame of the odometry (parent of the published TF)'),
    Parameter('base_frame_id', 'base_link',
              'Frame of the robot base (child of the published TF)'),
    Parameter('pose_covariance_diagonal', [0.0] * 6, 'Diagonal of the pose covariance of the '
              'odometry message (x, y, z, rx, ry, rz)', size(6)),
    Parameter('twist_covariance_diagonal', [0.0] * 6, 'Diagonal of the twist covariance of '
              'the odometry message (x, y, z, rx, ry, rz)', size(6)),
    Parameter('open_loop', False,
              'Integrate the odometry from the commands, not the wheel states'),
    Parameter('position_feedback', True,
              'Compute the odometry from wheel positions (true) or velocities (false)'),
    Parameter('enable_odom_tf', True, 'Publish the odometry as a transform on /tf'),
    Parameter('cmd_vel_timeout', 0.5, 'Time (s) after the last command before the robot is '
              'stopped; 0 disables', not_negative),
    Parameter('publish_limited_velocity', False,
              'Publish the limited command on ~/cmd_vel_out'),
    Parameter('velocity_rolling_window_size', 10, 'Number of samples of the rolling mean of '
              'the odometry twist', at_least_one),
    Parameter('publish_rate', 50.0, 'Rate of the odometry and TF messages (Hz)', positive),
] + [Parameter(f'{channel}.{limit}', math.nan, f'Limit {limit} of {channel}; NaN: no limit')
     for channel in ('linear.x', 'angular.z') for limit in LIMIT_NAMES])
"""The parameters of upstream's diff_drive_controller (jazzy), names and defaults as its
generate_parameter_library YAML, with the checks its ``on_configure`` makes."""


class DiffDriveController(ControllerInterface):
    """Differential-drive controller (see the module docstring)."""

    def on_init(self):
        """Declare every upstream parameter with its default (:data:`PARAMETERS`)."""
        PARAMETERS.declare(self)
        self.params = None  # the frozen values, read by on_configure
        self.wheel_names = ([], [])
        self._odom_pub = self._tf_pub = self._limited_pub = self._cmd_sub = None
        self._last_cmd = None
        self._subscriber_active = False
        self._zero_stamp_warned = False
        self._wheels = ([], [])
        self._feedback = ((), ())
        self._commands = ((), ())
        return True

    # ------------------------------------------------------------------ configure
    def _read_params(self):
        """
        Return the validated parameters and what follows from them.

        :returns: ``(params, wheels, limiters, frames)``: the frozen :data:`PARAMETERS`
            values; ``(left, right)`` wheel joint names; the ``linear.x`` and ``angular.z``
            :class:`SpeedLimiter`; ``(odom frame, base frame)`` with the TF prefix.
        :raises ValueError: one line naming the parameter.
        """
        params = PARAMETERS.read(self)
        left = [n for n in params.left_wheel_names if n]
        right = [n for n in params.right_wheel_names if n]
        if len(left) != len(right):
            raise ValueError(
                f'The number of left wheels [{len(left)}] and the number of right '
                f'wheels [{len(right)}] are different')
        limiters = []
        for channel in ('linear.x', 'angular.z'):
            limits = {lim: getattr(params, attribute(f'{channel}.{lim}')) for lim in LIMIT_NAMES}
            try:
                limiters.append(SpeedLimiter(**limits))
            except ValueError as exc:
                raise ValueError(f'parameter {channel}.{exc}') from None
        prefix = ''
        if params.tf_frame_prefix_enable:
            prefix = (params.tf_frame_prefix or self.get_namespace()).lstrip('/')
            if prefix and not prefix.endswith('/'):
                prefix += '/'
        frames = (prefix + params.odom_frame_id, prefix + params.base_frame_id)
        return params, (left, right), tuple(limiters), frames

    def on_configure(self, state):
        """Validate parameters, create odometry, limiters, publishers and the subscriber."""
        try:
            params, self.wheel_names, self._limiters, frames = self._read_params()
        except ValueError as exc:
            self.get_logger().error(str(exc))
            return TransitionCallbackReturn.FAILURE
        self.params = params
        self.odom_frame, self.base_frame = frames
        self.odometry = Odometry(
            params.wheel_separation * params.wheel_separation_multiplier,
            params.wheel_radius * params.left_wheel_radius_multiplier,
            params.wheel_radius * params.right_wheel_radius_multiplier,
            params.velocity_rolling_window_size)
        self._cmd_vel_timeout = params.cmd_vel_timeout
        self._open_loop = params.open_loop
        self._position_feedback = params.position_feedback
        self._publish_period = 1.0 / params.publish_rate
        self._reset_buffers()
        qos = QoSProfile(depth=10)
        if self._odom_pub is None:
            self._odom_pub = self.create_publisher(OdometryMsg, '~/odom', qos)
        if params.enable_odom_tf and self._tf_pub is None:
            self._tf_pub = self.create_publisher(TFMessage, '/tf', TF_QOS)
        if params.publish_limited_velocity and self._limited_pub is None:
            self._limited_pub = self.create_publisher(TwistStamped, '~/cmd_vel_out', qos)
        if self._cmd_sub is None:
            self._cmd_sub = self.create_subscription(
                TwistStamped, '~/cmd_vel', self._on_cmd_vel, qos)
        self._build_messages(params)
        return TransitionCallbackReturn.SUCCESS

    def _build_messages(self, params):
        """Create the Odometry and TF messages reused by every publication."""
        msg = OdometryMsg()
        msg.header.frame_id = self.odom_frame
        msg.child_frame_id = self.base_frame
        pose_cov = [0.0] * 36
        twist_cov = [0.0] * 36
        for i in range(6):
            pose_cov[7 * i] = params.pose_covariance_diagonal[i]
            twist_cov[7 * i] = params.twist_covariance_diagonal[i]
        msg.pose.covariance = pose_cov
        msg.twist.covariance = twist_cov
        self._odom_msg = msg
        self._odom_stamp = msg.header.stamp
        self._odom_position = msg.pose.pose.position
        self._odom_orientation = msg.pose.pose.orientation
        self._odom_linear = msg.twist.twist.linear
        self._odom_angular = msg.twist.twist.angular
        self._tf_msg = None
        if self._tf_pub is not None and params.enable_odom_tf:
            tf = TransformStamped()
            tf.header.frame_id = self.odom_frame
            tf.child_frame_id = self.base_frame
            self._tf_msg = TFMessage(transforms=[tf])
            self._tf_stamp = tf.header.stamp
            self._tf_translation = tf.transform.translation
            self._tf_rotation = tf.transform.rotation

    def _reset_buffers(self):
        self._last_cmd = None
        self._previous = [(0.0, 0.0), (0.0, 0.0)]  # [second to last, last] limited commands
        self._previous_publish = None
        self.odometry.reset_odometry()
        self.odometry.timestamp = None

    def on_cleanup(self, state):
        """Forget the last command and the odometry."""
        self._reset_buffers()
        return TransitionCallbackReturn.SUCCESS

    # ------------------------------------------------------------------ interfaces
    def command_interface_configuration(self):
        """Return ``<wheel>/velocity`` for every left then right wheel."""
        if self.params is None:
            return []
        return [f'{w}/velocity' for w in self.wheel_names[0] + self.wheel_names[1]]

    def state_interface_configuration(self):
        """Return ``<wheel>/position`` (or ``/velocity`` without position feedback)."""
        if self.params is None:
            return []
        iface = 'position' if self.params.position_feedback else 'velocity'
        return [f'{w}/{iface}' for w in self.wheel_names[0] + self.wheel_names[1]]

    def on_activate(self, state):
        """Look up the wheel handles; fails naming every wheel without its interfaces."""
        iface = 'position' if self.params.position_feedback else 'velocity'
        missing = []
        sides = []
        for side in self.wheel_names:
            wheels = []
            for wheel in side:
                cmd = self.command_interfaces.get(f'{wheel}/velocity')
                fb = self.state_interfaces.get(f'{wheel}/{iface}')
                if cmd is None:
                    missing.append(f'{wheel}/velocity (command)')
                if fb is None and not self.params.open_loop:
                    missing.append(f'{wheel}/{iface} (state)')
                wheels.append((cmd, fb))
            sides.append(wheels)
        if missing:
            self.get_logger().error(
                f'Unable to obtain wheel interfaces: {", ".join(missing)}')
            return TransitionCallbackReturn.FAILURE
        self._wheels = tuple(sides)
        self._feedback = tuple(tuple(fb for _, fb in side) for side in sides)
        self._commands = tuple(tuple(cmd for cmd, _ in side) for side in sides)
        self._subscriber_active = True
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state):
        """Stop accepting commands and command zero to every wheel."""
        self._subscriber_active = False
        self._halt()
        self._wheels = ([], [])
        self._feedback = ((), ())
        self._commands = ((), ())
        self._last_cmd = None
        return TransitionCallbackReturn.SUCCESS

    def _halt(self):
        for side in self._wheels:
            for cmd, _ in side:
                if cmd is not None:
                    cmd.value = 0.0

    # ------------------------------------------------------------------ commands
    def _on_cmd_vel(self, msg):
        log = self.get_logger()
        if not self._subscriber_active:
            log.warn("Can't accept new commands. subscriber is inactive")
            return
        now = self.now_seconds()
        linear, angular = msg.twist.linear.x, msg.twist.angular.z
        if not (math.isfinite(linear) and math.isfinite(angular)):
            log.warn(f'Ignoring the received command because it is not finite '
                     f'(linear.x={linear}, angular.z={angular})')
            return
        stamp = msg_to_time(msg.header.stamp)
        if msg.header.stamp.sec == 0 and msg.header.stamp.nanosec == 0:
            if not self._zero_stamp_warned:
                self._zero_stamp_warned = True
                log.warn('Received TwistStamped with zero timestamp, setting it to current '
                         'time, this message will only be shown once')
            stamp = now
        age = now - stamp
        timeout = self.params.cmd_vel_timeout
        if timeout != 0.0 and age >= timeout:
            log.warn(f'Ignoring the received message (timestamp {stamp:.10f}) because it is '
                     f'older than the current time by {age:.10f} seconds, which exceeds the '
                     f'allowed timeout ({timeout:.4f})')
            return
        self._last_cmd = (stamp, linear, angular)

    # ------------------------------------------------------------------ update
    def update(self, time, period):
        """Odometry, publishing, limits and wheel commands for one step (see module doc)."""
        self.last_update_time = time
        last = self._last_cmd
        if last is None:
            linear = angular = 0.0
        else:
            stamp, linear, angular = last
            timeout = self._cmd_vel_timeout
            if timeout > 0.0 and time - stamp > timeout:
                linear = angular = 0.0
        odometry = self.odometry
        if self._open_loop:
            odometry.update_open_loop(linear, angular, time)
        else:
            left_side, right_side = self._feedback
            left = 0.0
            for handle in left_side:
                left += handle.value
            right = 0.0
            for handle in right_side:
                right += handle.value
            if left != left or right != right:  # NaN: find and report the wheel
                if self._report_nan_feedback():
                    return False
            left /= len(left_side)
            right /= len(right_side)
            if self._position_feedback:
                odometry.update(left, right, time)
            else:
                odometry.update_from_velocity(left * odometry.left_wheel_radius * period,
                                              right * odometry.right_wheel_radius * period,
                                              time)
        self._maybe_publish(time)
        if last is None:
            return True  # before the first command nothing is written
        (l1, a1), (l0, a0) = self._previous
        linear = self._limiters[0].limit(linear, l0, l1, period)
        angular = self._limiters[1].limit(angular, a0, a1, period)
        self._previous = [(l0, a0), (linear, angular)]
        if self._limited_pub is not None:
            out = TwistStamped()
            out.header.stamp = time_to_msg(time)
            out.header.frame_id = self.self.base_frame
            out.twist.linear.x = linear
            out.twist.angular.z = angular
            self._limited_pub.publish(out)
        half_turn = angular * odometry.wheel_separation / 2.0
        left = (linear - half_turn) / odometry.left_wheel_radius
        right = (linear + half_turn) / odometry.right_wheel_radius
        left_commands, right_commands = self._commands
        for cmd in left_commands:
            cmd.value = left
        for cmd in right_commands:
            cmd.value = right
        return True

    def _report_nan_feedback(self):
        """Log the first NaN wheel state (left side first); returns True when one exists."""
        for side_name, names, side in zip(('left', 'right'), self.wheel_names, self._feedback):
            for index, handle in enumerate(side):
                if math.isnan(handle.value):
                    kind = 'position' if self.params.position_feedback else 'velocity'
                    self.get_logger().error(
                        f'Either the left or right wheel {kind} is invalid for index '
                        f'[{index}] ({side_name} wheel {names[index]})')
                    return True
        return False

    def _maybe_publish(self, time):
        publish_period = self._publish_period
        previous = self._previous_publish
        if previous is None or time < previous:
            self._previous_publish = time
        elif previous + publish_period <= time + 1e-9:
            previous += publish_period
            if time - previous > publish_period:
                previous = time  # fell behind (paused): do not burst
            self._previous_publish = previous
        else:
            return
        odom_heard = has_subscribers(self._odom_pub)
        tf_heard = self._tf_msg is not None and has_subscribers(self._tf_pub)
        if not (odom_heard or tf_heard):
            return  # volatile topics nobody has matched: nothing to deliver
        odom = self.odometry
        half_heading = 0.5 * odom.heading
        qz, qw = math.sin(half_heading), math.cos(half_heading)
        x, y = odom.x, odom.y
        set_stamp(self._odom_stamp, time)
        position = self._odom_position
        position.x = x
        position.y = y
        orientation = self._odom_orientation
        orientation.z = qz
        orientation.w = qw
        self._odom_linear.x = odom.linear
        self._odom_angular.z = odom.angular
        if odom_heard:
            self._odom_pub.publish(self._odom_msg)
        if tf_heard:
            set_stamp(self._tf_stamp, time)
            translation = self._tf_translation
            translation.x = x
            translation.y = y
            rotation = self._tf_rotation
            rotation.z = qz
            rotation.w = qw
            self._tf_pub.publish(self._tf_msg)
