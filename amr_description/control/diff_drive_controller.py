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
"""

import math

from amr_description.control.controller_interface import ControllerInterface
from amr_description.control.controller_interface import msg_to_time
from amr_description.control.controller_interface import time_to_msg
from amr_description.control.controller_interface import TransitionCallbackReturn
from amr_description.core.odometry import Odometry
from amr_description.core.speed_limiter import PARAMETER_NAMES as LIMIT_NAMES
from amr_description.core.speed_limiter import SpeedLimiter
from geometry_msgs.msg import TransformStamped
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry as OdometryMsg
from rclpy.qos import DurabilityPolicy
from rclpy.qos import HistoryPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy

try:
    from tf2_msgs.msg import TFMessage
except ImportError:  # built by scripts/setup; without it no TF is published
    TFMessage = None

# QoS of tf2_ros::TransformBroadcaster (jazzy): reliable, volatile, keep last 100
TF_QOS = QoSProfile(depth=100, history=HistoryPolicy.KEEP_LAST,
                    reliability=ReliabilityPolicy.RELIABLE,
                    durability=DurabilityPolicy.VOLATILE)

NAN = math.nan


def _yaw_quaternion(yaw):
    return 0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw)


class DiffDriveController(ControllerInterface):
    """Differential-drive controller (see the module docstring)."""

    def on_init(self):
        """Declare every upstream parameter with its default; returns True."""
        d = self.auto_declare
        d('left_wheel_names', [''])
        d('right_wheel_names', [''])
        d('wheel_separation', 0.0)
        d('wheel_radius', 0.0)
        d('wheel_separation_multiplier', 1.0)
        d('left_wheel_radius_multiplier', 1.0)
        d('right_wheel_radius_multiplier', 1.0)
        d('tf_frame_prefix_enable', True)
        d('tf_frame_prefix', '')
        d('odom_frame_id', 'odom')
        d('base_frame_id', 'base_link')
        d('pose_covariance_diagonal', [0.0] * 6)
        d('twist_covariance_diagonal', [0.0] * 6)
        d('open_loop', False)
        d('position_feedback', True)
        d('enable_odom_tf', True)
        d('cmd_vel_timeout', 0.5)
        d('publish_limited_velocity', False)
        d('velocity_rolling_window_size', 10)
        d('publish_rate', 50.0)
        for channel in ('linear.x', 'angular.z'):
            for limit in LIMIT_NAMES:
                d(f'{channel}.{limit}', NAN)
        self._odom_pub = self._tf_pub = self._limited_pub = self._cmd_sub = None
        self._last_cmd = None
        self._subscriber_active = False
        self._zero_stamp_warned = False
        self._wheels = ([], [])
        return True

    # ------------------------------------------------------------------ configure
    def _read_params(self):
        p = self.param
        cfg = {
            'left': [n for n in p('left_wheel_names', ['']) if n],
            'right': [n for n in p('right_wheel_names', ['']) if n],
        }
        if not cfg['left']:
            raise ValueError("parameter 'left_wheel_names' is empty: wheel names are required")
        if not cfg['right']:
            raise ValueError("parameter 'right_wheel_names' is empty: wheel names are required")
        if len(cfg['left']) != len(cfg['right']):
            raise ValueError(
                f"The number of left wheels [{len(cfg['left'])}] and the number of right "
                f"wheels [{len(cfg['right'])}] are different")
        for name in ('wheel_separation', 'wheel_radius', 'wheel_separation_multiplier',
                     'left_wheel_radius_multiplier', 'right_wheel_radius_multiplier',
                     'publish_rate'):
            value = p(name, 0.0)
            if not value > 0.0:
                raise ValueError(f"parameter '{name}' must be > 0, got {value}")
            cfg[name] = value
        for name in ('pose_covariance_diagonal', 'twist_covariance_diagonal'):
            values = p(name, [0.0] * 6)
            if len(values) != 6:
                raise ValueError(f"parameter '{name}' must have 6 elements, got {len(values)}")
            cfg[name] = values
        window = p('velocity_rolling_window_size', 10)
        if window < 1:
            raise ValueError(
                f"parameter 'velocity_rolling_window_size' must be >= 1, got {window}")
        cfg['window'] = window
        timeout = p('cmd_vel_timeout', 0.5)
        if timeout < 0.0:
            raise ValueError(f"parameter 'cmd_vel_timeout' must be >= 0, got {timeout}")
        cfg['cmd_vel_timeout'] = timeout
        for name in ('open_loop', 'position_feedback', 'enable_odom_tf',
                     'publish_limited_velocity', 'tf_frame_prefix_enable'):
            cfg[name] = p(name, False)
        for channel in ('linear.x', 'angular.z'):
            limits = {lim: p(f'{channel}.{lim}', NAN) for lim in LIMIT_NAMES}
            try:
                cfg[channel] = SpeedLimiter(**limits)
            except ValueError as exc:
                raise ValueError(f'parameter {channel}.{exc}') from None
        prefix = ''
        if cfg['tf_frame_prefix_enable']:
            prefix = p('tf_frame_prefix', '') or self.get_namespace()
            prefix = prefix.lstrip('/')
            if prefix and not prefix.endswith('/'):
                prefix += '/'
        cfg['odom_frame'] = prefix + p('odom_frame_id', 'odom')
        cfg['base_frame'] = prefix + p('base_frame_id', 'base_link')
        return cfg

    def on_configure(self, state):
        """Validate parameters, create odometry, limiters, publishers and the subscriber."""
        try:
            cfg = self._read_params()
        except ValueError as exc:
            self.get_logger().error(str(exc))
            return TransitionCallbackReturn.FAILURE
        self.cfg = cfg
        self.odometry = Odometry(
            cfg['wheel_separation'] * cfg['wheel_separation_multiplier'],
            cfg['wheel_radius'] * cfg['left_wheel_radius_multiplier'],
            cfg['wheel_radius'] * cfg['right_wheel_radius_multiplier'], cfg['window'])
        self._limiters = (cfg['linear.x'], cfg['angular.z'])
        self._reset_buffers()
        qos = QoSProfile(depth=10)
        if self._odom_pub is None:
            self._odom_pub = self.create_publisher(OdometryMsg, '~/odom', qos)
        if cfg['enable_odom_tf'] and self._tf_pub is None:
            if TFMessage is None:
                self.get_logger().warn('tf2_msgs is not installed: odom TF is not published')
            else:
                self._tf_pub = self.create_publisher(TFMessage, '/tf', TF_QOS)
        if cfg['publish_limited_velocity'] and self._limited_pub is None:
            self._limited_pub = self.create_publisher(TwistStamped, '~/cmd_vel_out', qos)
        if self._cmd_sub is None:
            self._cmd_sub = self.create_subscription(
                TwistStamped, '~/cmd_vel', self._on_cmd_vel, qos)
        return TransitionCallbackReturn.SUCCESS

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
        cfg = getattr(self, 'cfg', None)
        if cfg is None:
            return []
        return [f'{w}/velocity' for w in cfg['left'] + cfg['right']]

    def state_interface_configuration(self):
        """Return ``<wheel>/position`` (or ``/velocity`` without position feedback)."""
        cfg = getattr(self, 'cfg', None)
        if cfg is None:
            return []
        iface = 'position' if cfg['position_feedback'] else 'velocity'
        return [f'{w}/{iface}' for w in cfg['left'] + cfg['right']]

    def on_activate(self, state):
        """Look up the wheel handles; fails naming every wheel without its interfaces."""
        cfg = self.cfg
        iface = 'position' if cfg['position_feedback'] else 'velocity'
        missing = []
        sides = []
        for side in ('left', 'right'):
            wheels = []
            for wheel in cfg[side]:
                cmd = self.command_interfaces.get(f'{wheel}/velocity')
                fb = self.state_interfaces.get(f'{wheel}/{iface}')
                if cmd is None:
                    missing.append(f'{wheel}/velocity (command)')
                if fb is None and not cfg['open_loop']:
                    missing.append(f'{wheel}/{iface} (state)')
                wheels.append((cmd, fb))
            sides.append(wheels)
        if missing:
            self.get_logger().error(
                f'Unable to obtain wheel interfaces: {", ".join(missing)}')
            return TransitionCallbackReturn.FAILURE
        self._wheels = tuple(sides)
        self._subscriber_active = True
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state):
        """Stop accepting commands and command zero to every wheel."""
        self._subscriber_active = False
        self._halt()
        self._wheels = ([], [])
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
        timeout = self.cfg['cmd_vel_timeout']
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
        cfg = self.cfg
        last = self._last_cmd
        if last is None:
            linear = angular = 0.0
        else:
            stamp, linear, angular = last
            if cfg['cmd_vel_timeout'] > 0.0 and time - stamp > cfg['cmd_vel_timeout']:
                linear = angular = 0.0
        if cfg['open_loop']:
            self.odometry.update_open_loop(linear, angular, time)
        else:
            means = []
            for side_name, side in zip(('left', 'right'), self._wheels):
                values = [fb.value for _, fb in side]
                for index, value in enumerate(values):
                    if math.isnan(value):
                        kind = 'position' if cfg['position_feedback'] else 'velocity'
                        self.get_logger().error(
                            f'Either the left or right wheel {kind} is invalid for index '
                            f'[{index}] ({side_name} wheel {cfg[side_name][index]})')
                        return False
                means.append(sum(values) / len(values))
            if cfg['position_feedback']:
                self.odometry.update(means[0], means[1], time)
            else:
                self.odometry.update_from_velocity(
                    means[0] * self.odometry.left_wheel_radius * period,
                    means[1] * self.odometry.right_wheel_radius * period, time)
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
            out.header.frame_id = cfg['base_frame']
            out.twist.linear.x = linear
            out.twist.angular.z = angular
            self._limited_pub.publish(out)
        separation = self.odometry.wheel_separation
        left = (linear - angular * separation / 2.0) / self.odometry.left_wheel_radius
        right = (linear + angular * separation / 2.0) / self.odometry.right_wheel_radius
        for cmd, _ in self._wheels[0]:
            cmd.value = left
        for cmd, _ in self._wheels[1]:
            cmd.value = right
        return True

    def _maybe_publish(self, time):
        publish_period = 1.0 / self.cfg['publish_rate']
        if self._previous_publish is None or time < self._previous_publish:
            self._previous_publish = time
        elif self._previous_publish + publish_period <= time + 1e-9:
            self._previous_publish += publish_period
            if time - self._previous_publish > publish_period:
                self._previous_publish = time  # fell behind (paused): do not burst
        else:
            return
        cfg = self.cfg
        odom = self.odometry
        stamp = time_to_msg(time)
        qx, qy, qz, qw = _yaw_quaternion(odom.heading)
        msg = OdometryMsg()
        msg.header.stamp = stamp
        msg.header.frame_id = cfg['odom_frame']
        msg.child_frame_id = cfg['base_frame']
        msg.pose.pose.position.x = odom.x
        msg.pose.pose.position.y = odom.y
        msg.pose.pose.orientation.x, msg.pose.pose.orientation.y = qx, qy
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = qz, qw
        pose_cov = [0.0] * 36
        twist_cov = [0.0] * 36
        for i in range(6):
            pose_cov[7 * i] = cfg['pose_covariance_diagonal'][i]
            twist_cov[7 * i] = cfg['twist_covariance_diagonal'][i]
        msg.pose.covariance = pose_cov
        msg.twist.covariance = twist_cov
        msg.twist.twist.linear.x = odom.linear
        msg.twist.twist.angular.z = odom.angular
        self._odom_pub.publish(msg)
        if self._tf_pub is not None and cfg['enable_odom_tf']:
            tf = TransformStamped()
            tf.header.stamp = stamp
            tf.header.frame_id = cfg['odom_frame']
            tf.child_frame_id = cfg['base_frame']
            tf.transform.translation.x = odom.x
            tf.transform.translation.y = odom.y
            r = tf.transform.rotation
            r.x, r.y, r.z, r.w = qx, qy, qz, qw
            self._tf_pub.publish(TFMessage(transforms=[tf]))
