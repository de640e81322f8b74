# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Velocity, acceleration and jerk limiting of one command channel.

Reproduced behaviour: diff_drive_controller (ros2_controllers jazzy) limits ``linear.x`` and
``angular.z`` with control_toolbox's rate limiter. Every limit is optional: NaN disables it.
Parameters follow the diff_drive_controller names (units of the channel: m/s or rad/s):

- ``max_velocity`` >= 0, ``min_velocity`` <= 0 (NaN min: ``-max_velocity``);
- ``max_acceleration`` >= 0 (speeding up forwards), ``max_acceleration_reverse`` <= 0
  (speeding up backwards; NaN: ``-max_acceleration``), ``max_deceleration`` <= 0 (slowing
  down forwards; NaN: ``max_acceleration_reverse``), ``max_deceleration_reverse`` >= 0
  (slowing down backwards; NaN: ``max_acceleration``), i.e. symmetric limits as
  control_toolbox's rate limiter; acceleration limits are active when ``max_acceleration``
  is set;
- ``max_jerk`` >= 0, ``min_jerk`` <= 0 (NaN min: ``-max_jerk``).
"""

import math

PARAMETER_NAMES = ('max_velocity', 'min_velocity', 'max_acceleration', 'max_deceleration',
                   'max_acceleration_reverse', 'max_deceleration_reverse', 'max_jerk',
                   'min_jerk')


def _nan(value):
    return value is None or math.isnan(value)


def _clamp(value, low, high):
    return min(max(value, low), high)


class SpeedLimiter:
    """
    Limit a velocity command given the two previous (limited) commands.

    Keyword parameters are those of :data:`PARAMETER_NAMES` (float or NaN).

    :raises ValueError: naming the parameter when a limit has the wrong sign or
        ``min_velocity > max_velocity``.
    """

    def __init__(self, **limits):
        """Validate and store the limits (see the class docstring)."""
        unknown = set(limits) - set(PARAMETER_NAMES)
        if unknown:
            raise ValueError(f'unknown speed limit parameter(s): {sorted(unknown)}')
        p = {name: float(limits.get(name, math.nan)) for name in PARAMETER_NAMES}
        for name in ('max_velocity', 'max_acceleration', 'max_deceleration_reverse',
                     'max_jerk'):
            if not _nan(p[name]) and p[name] < 0.0:
                raise ValueError(f'{name} must be >= 0 or NaN, got {p[name]}')
        for name in ('min_velocity', 'max_deceleration', 'max_acceleration_reverse',
                     'min_jerk'):
            if not _nan(p[name]) and p[name] > 0.0:
                raise ValueError(f'{name} must be <= 0 or NaN, got {p[name]}')
        self.has_velocity_limits = not _nan(p['max_velocity'])
        self.max_velocity = p['max_velocity']
        self.min_velocity = p['min_velocity']
        if self.has_velocity_limits and _nan(self.min_velocity):
            self.min_velocity = -self.max_velocity
        self.has_acceleration_limits = not _nan(p['max_acceleration'])
        acc = p['max_acceleration']
        self.max_acceleration = acc
        self.max_acceleration_reverse = (-acc if _nan(p['max_acceleration_reverse'])
                                         else p['max_acceleration_reverse'])
        self.max_deceleration = (self.max_acceleration_reverse if _nan(p['max_deceleration'])
                                 else p['max_deceleration'])
        self.max_deceleration_reverse = (acc if _nan(p['max_deceleration_reverse'])
                                         else p['max_deceleration_reverse'])
        self.has_jerk_limits = not _nan(p['max_jerk'])
        self.max_jerk = p['max_jerk']
        self.min_jerk = -p['max_jerk'] if _nan(p['min_jerk']) else p['min_jerk']

    def limit(self, v, v0, v1, dt):
        """
        Return ``v`` limited by jerk, then acceleration, then velocity.

        :param v: requested command (channel units).
        :param v0: previous limited command.
        :param v1: the command before ``v0``.
        :param dt: time step (s, > 0; with dt <= 0 only the velocity limit applies).
        :returns: the limited command (float).
        """
        v = float(v)
        if dt > 0.0:
            v = self.limit_jerk(v, v0, v1, dt)
            v = self.limit_acceleration(v, v0, dt)
        return self.limit_velocity(v)

    def limit_velocity(self, v):
        """Clamp ``v`` to ``[min_velocity, max_velocity]`` when velocity limits are set."""
        if self.has_velocity_limits:
            return _clamp(v, self.min_velocity, self.max_velocity)
        return v

    def limit_acceleration(self, v, v0, dt):
        """
        Limit the change ``v - v0`` over ``dt`` (s) by the direction-dependent limits.

        Moving forwards (``v0 > 0``): ``[max_deceleration, max_acceleration] * dt``;
        backwards (``v0 < 0``): ``[max_acceleration_reverse, max_deceleration_reverse] * dt``;
        at rest: ``[max_acceleration_reverse, max_acceleration] * dt``.
        """
        if not self.has_acceleration_limits:
            return v
        if v0 > 0.0:
            low, high = self.max_deceleration, self.max_acceleration
        elif v0 < 0.0:
            low, high = self.max_acceleration_reverse, self.max_deceleration_reverse
        else:
            low, high = self.max_acceleration_reverse, self.max_acceleration
        return v0 + _clamp(v - v0, low * dt, high * dt)

    def limit_jerk(self, v, v0, v1, dt):
        """Limit the change of ``v - v0`` versus ``v0 - v1`` by ``[min_jerk, max_jerk]*2*dt^2``."""
        if not self.has_jerk_limits:
            return v
        dv, dv0 = v - v0, v0 - v1
        dt2 = 2.0 * dt * dt
        return v0 + dv0 + _clamp(dv - dv0, self.min_jerk * dt2, self.max_jerk * dt2)
