# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``velocity_smoother``: nav2_velocity_smoother (Jazzy), a managed (lifecycle) node.

Takes ``cmd_vel`` (Twist, or TwistStamped with ``enable_stamped_cmd_vel``) and publishes
``cmd_vel_smoothed`` (reliable, depth 1) at ``smoothing_frequency`` (20.0 Hz), each axis clamped
to ``[min_velocity, max_velocity]`` ([-0.5, 0, -2.5] .. [0.5, 0, 2.5]) and its change limited by
``max_accel`` ([2.5, 0, 3.2]) and ``max_decel`` ([-2.5, 0, -3.2]) (OPEN_LOOP feedback: from the
last smoothed command); ``deadband_velocity`` ([0, 0, 0]); with no command for
``velocity_timeout`` (1.0 s) it brakes to zero and then stops publishing. ``feedback``
CLOSED_LOOP is said in one line and runs open loop. Configure refuses, with upstream's lines,
limits that are not 3 values, a positive ``max_decel``, a negative ``max_accel``, a
``min_velocity`` above ``max_velocity`` and a ``feedback`` other than OPEN_LOOP or CLOSED_LOOP.
While active, ``ros2 param set`` changes ``smoothing_frequency`` (the timer's period),
``velocity_timeout``, ``odom_duration``, ``odom_topic``, ``feedback`` and the five limits at
the next tick; a limit that is not 3 values, a negative ``max_accel``, a positive ``max_decel``
or another ``feedback`` is refused with upstream's warning and nothing changes (upstream's
callback keeps a refused acceleration limit all the same). Arithmetic:
:mod:`amr_description.nav.smoothing`. Source: ``nav2_velocity_smoother/src/velocity_smoother.cpp``.
"""

from amr_description.nav.smoothing import smooth
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.twist_io import subscribe_twist
from amr_description.ros.twist_io import TwistPublisher
import numpy as np
from rcl_interfaces.msg import SetParametersResult

LIMITS = ('max_velocity', 'min_velocity', 'max_accel', 'max_decel', 'deadband_velocity')
FEEDBACK = ('OPEN_LOOP', 'CLOSED_LOOP')
DYNAMIC = LIMITS + ('smoothing_frequency', 'velocity_timeout', 'odom_duration', 'odom_topic',
                    'feedback')
"""The parameters upstream's ``dynamicParametersCallback`` takes."""


class VelocitySmoother(ManagedNode):
    """Node ``velocity_smoother``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters (``kwargs``: rclpy's node options)."""
        super().__init__('velocity_smoother', **kwargs)
        d = self.declare_parameter
        self.p = {k: d(k, v).value for k, v in {
            'smoothing_frequency': 20.0, 'feedback': 'OPEN_LOOP', 'scale_velocities': False,
            'max_velocity': [0.5, 0.0, 2.5], 'min_velocity': [-0.5, 0.0, -2.5],
            'max_accel': [2.5, 0.0, 3.2], 'max_decel': [-2.5, 0.0, -3.2],
            'odom_topic': 'odom', 'odom_duration': 0.1,
            'deadband_velocity': [0.0, 0.0, 0.0], 'velocity_timeout': 1.0,
            'enable_stamped_cmd_vel': False, 'use_realtime_priority': False,
            'stamp_smoothed_velocity_with_smoothing_time': False}.items()}
        self._entities = []
        self._pub = None
        self.current = np.zeros(3)
        self.command = None
        self.last_command = None

    def configure(self):
        """Check the limits' shapes and signs."""
        self.get_logger().info('Configuring velocity smoother')
        p = self.p
        if any(len(p[key]) != 3 for key in LIMITS):
            raise ValueError('Invalid setting of kinematic and/or deadband limits! All limits '
                             'must be size of 3 representing (x, y, theta).')
        if any(d > 0.0 for d in p['max_decel']):
            raise ValueError('Positive values set of deceleration! These should be negative to '
                             'slow down!')
        if any(a < 0.0 for a in p['max_accel']):
            raise ValueError('Negative values set of acceleration! These should be positive to '
                             'speed up!')
        if any(lo > hi for lo, hi in zip(p['min_velocity'], p['max_velocity'])):
            raise ValueError('Min velocities are higher than max velocities!')
        if p['feedback'] not in FEEDBACK:
            raise ValueError('Invalid feedback_type, options are OPEN_LOOP and CLOSED_LOOP.')
        self._say_feedback(p['feedback'])

    def _say_feedback(self, feedback):
        if feedback == 'CLOSED_LOOP':
            self.get_logger().info('feedback CLOSED_LOOP: the smoother runs open loop here')

    def activate(self):
        """Subscribe, publish and start the smoothing timer."""
        self.get_logger().info('Activating')
        stamped = self.p['enable_stamped_cmd_vel']
        self._pub = TwistPublisher(self, 'cmd_vel_smoothed', stamped)
        self._timer = self.create_timer(1.0 / max(self.p['smoothing_frequency'], 1e-3),
                                        self._tick)
        self._entities = [self._pub.pub,
                          subscribe_twist(self, 'cmd_vel', stamped, self._on_command),
                          self._timer]
        self.watch_parameters(self._on_set_parameters)

    def deactivate(self):
        """Stop smoothing."""
        self.get_logger().info('Deactivating')
        self.unwatch_parameters()
        self.destroy_entities(self._entities)
        self._entities = []
        self._pub = None
        self.command = None
        self.current = np.zeros(3)

    def _on_set_parameters(self, parameters):
        """Take ``ros2 param set`` values at the next tick; see the module docstring."""
        for parameter in parameters:
            name, value = parameter.name, parameter.value
            line = None
            if name in LIMITS and len(value) != 3:
                line = f'Invalid size of parameter {name}. Must be size 3'
            elif name == 'max_accel' and any(a < 0.0 for a in value):
                line = 'Negative values set of acceleration! These should be positive to speed up!'
            elif name == 'max_decel' and any(d > 0.0 for d in value):
                line = ('Positive values set of deceleration! These should be negative to slow '
                        'down!')
            elif name == 'feedback' and value not in FEEDBACK:
                line = 'Invalid feedback_type, options are OPEN_LOOP and CLOSED_LOOP.'
            elif name == 'smoothing_frequency' and not value > 0.0:
                line = f'smoothing_frequency must be above 0 Hz, got {value}'  # upstream: none
            if line is not None:
                self.get_logger().warning(line)
                return SetParametersResult(successful=False, reason=line)
        for parameter in parameters:
            name, value = parameter.name, parameter.value
            if name not in DYNAMIC:
                continue
            self.p[name] = list(value) if name in LIMITS else value
            if name == 'smoothing_frequency':
                self._timer.timer_period_ns = int(1e9 / value)
                self._timer.reset()
            elif name == 'feedback':
                self._say_feedback(value)
        return SetParametersResult(successful=True)

    def _now(self):
        return self.get_clock().now().nanoseconds * 1e-9

    def _on_command(self, vx, vy, wz):
        self.command = np.array([vx, vy, wz])
        self.last_command = self._now()

    def _tick(self):
        if self.command is None:
            return
        timed_out = self._now() - self.last_command > self.p['velocity_timeout']
        if timed_out:
            if not self.current.any():
                self.command = None  # braked: stop publishing
                return
            target = np.zeros(3)
        else:
            target = self.command
        p = self.p
        self.current = smooth(self.current, target, 1.0 / p['smoothing_frequency'],
                              p['max_velocity'], p['min_velocity'], p['max_accel'],
                              p['max_decel'], p['deadband_velocity'])
        self._pub.publish(self.current[0], self.current[2], self.current[1])


def main(args=None):
    """
    Run the velocity smoother until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(VelocitySmoother, args)


if __name__ == '__main__':
    main()
