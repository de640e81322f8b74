# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Planar differential-drive odometry, as diff_drive_controller's ``Odometry`` class.

Pose ``(x, y, heading)`` of the base frame in the odometry frame (REP 105: metres, radians,
counter-clockwise positive); twist ``(linear, angular)`` in the base frame (m/s, rad/s).
Reproduced behaviour (ros2_controllers jazzy, diff_drive_controller odometry): exact arc
integration, second-order Runge-Kutta when a step turns by less than 1e-6 rad; updates
closer than 1e-4 s to the previous one are skipped; the reported twist is the rolling mean
over the last ``velocity_rolling_window_size`` velocity estimates.
"""

from collections import deque
import math

MIN_DT = 1e-4
"""Updates with a time step below this (seconds) are skipped."""

RK2_THRESHOLD = 1e-6
"""Below this absolute heading change (rad) the arc is integrated with Runge-Kutta 2."""


class RollingMean:
    """
    Mean of the last ``size`` values pushed (the mean of what there is while filling).

    :param size: window length, int >= 1.
    :raises ValueError: when ``size`` < 1.
    """

    def __init__(self, size):
        """Create an empty window (see the class docstring)."""
        if int(size) < 1:
            raise ValueError(f'rolling window size must be >= 1, got {size}')
        self._values = deque(maxlen=int(size))

    def push(self, value):
        """Add ``value`` (float), dropping the oldest when the window is full."""
        self._values.append(float(value))

    def mean(self):
        """Return the mean of the window, 0.0 when empty."""
        return sum(self._values) / len(self._values) if self._values else 0.0

    def clear(self):
        """Empty the window."""
        self._values.clear()


class Odometry:
    """
    Differential-drive dead reckoning from wheel positions or wheel travel.

    :param wheel_separation: distance between the left and right wheel contact lines (m, > 0).
    :param left_wheel_radius: left wheel radius (m, > 0).
    :param right_wheel_radius: right wheel radius (m, > 0).
    :param velocity_rolling_window_size: samples in the twist rolling mean (>= 1).
    """

    def __init__(self, wheel_separation=1.0, left_wheel_radius=1.0, right_wheel_radius=1.0,
                 velocity_rolling_window_size=10):
        """Create odometry at the origin (see the class docstring)."""
        self.wheel_separation = float(wheel_separation)
        self.left_wheel_radius = float(left_wheel_radius)
        self.right_wheel_radius = float(right_wheel_radius)
        self._linear_mean = RollingMean(velocity_rolling_window_size)
        self._angular_mean = RollingMean(velocity_rolling_window_size)
        self.timestamp = None
        self.reset_odometry()

    def init(self, time):
        """Start integrating at ``time`` (s): clear the twist means, keep the pose."""
        self._linear_mean.clear()
        self._angular_mean.clear()
        self.timestamp = float(time)
        self._left_prev = None
        self._right_prev = None

    def reset_odometry(self):
        """Set the pose to the origin and the twist to zero."""
        self.x = 0.0
        self.y = 0.0
        self.heading = 0.0
        self.linear = 0.0
        self.angular = 0.0
        self._left_prev = None
        self._right_prev = None
        self._linear_mean.clear()
        self._angular_mean.clear()

    def update(self, left_pos, right_pos, time):
        """
        Integrate from absolute wheel angles (rad), averaged per side.

        The first call only records the angles (no travel). A NaN angle leaves the pose
        unchanged and returns False.

        :param left_pos: left wheel angle (rad).
        :param right_pos: right wheel angle (rad).
        :param time: time of the measurement (s).
        :returns: True when the pose was updated, False when skipped (dt < 1e-4 s).
        """
        if math.isnan(left_pos) or math.isnan(right_pos):
            return False
        left = left_pos * self.left_wheel_radius
        right = right_pos * self.right_wheel_radius
        if self._left_prev is None:
            self._left_prev, self._right_prev = left, right
        if not self._step_allowed(time):
            return False
        dl, dr = left - self._left_prev, right - self._right_prev
        self._left_prev, self._right_prev = left, right
        return self._apply(dl, dr, time)

    def update_from_velocity(self, left_travel, right_travel, time):
        """
        Integrate wheel travel over the last step (m per side, e.g. ``omega * r * dt``).

        :param left_travel: left wheel rolling distance since the previous update (m).
        :param right_travel: right wheel rolling distance since the previous update (m).
        :param time: time of the measurement (s).
        :returns: True when the pose was updated, False when skipped (dt < 1e-4 s).
        """
        if not self._step_allowed(time):
            return False
        return self._apply(float(left_travel), float(right_travel), time)

    def update_open_loop(self, linear, angular, time):
        """
        Integrate the commanded twist (m/s, rad/s) over the time since the previous call.

        The reported twist is the command itself (no rolling mean), as upstream.

        :param linear: commanded forward speed (m/s).
        :param angular: commanded yaw rate (rad/s).
        :param time: current time (s).
        :returns: True.
        """
        dt = 0.0 if self.timestamp is None else float(time) - self.timestamp
        self.timestamp = float(time)
        self.linear = float(linear)
        self.angular = float(angular)
        self.integrate(linear * dt, angular * dt)
        return True

    def integrate(self, distance, dheading):
        """
        Advance the pose by ``distance`` (m) along an arc turning by ``dheading`` (rad).

        Exact arc when ``|dheading| >= 1e-6``, otherwise Runge-Kutta 2 (midpoint heading).
        """
        if abs(dheading) < RK2_THRESHOLD:
            direction = self.heading + 0.5 * dheading
            self.x += distance * math.cos(direction)
            self.y += distance * math.sin(direction)
            self.heading += dheading
            return
        radius = distance / dheading
        old = self.heading
        self.heading += dheading
        self.x += radius * (math.sin(self.heading) - math.sin(old))
        self.y -= radius * (math.cos(self.heading) - math.cos(old))

    def _step_allowed(self, time):
        if self.timestamp is None:
            self.timestamp = float(time)
            return False
        return float(time) - self.timestamp >= MIN_DT

    def _apply(self, dl, dr, time):
        dt = float(time) - self.timestamp
        distance = 0.5 * (dl + dr)
        dheading = (dr - dl) / self.wheel_separation
        self.integrate(distance, dheading)
        self.timestamp = float(time)
        self._linear_mean.push(distance / dt)
        self._angular_mean.push(dheading / dt)
        self.linear = self._linear_mean.mean()
        self.angular = self._angular_mean.mean()
        return True
