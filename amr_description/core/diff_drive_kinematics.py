# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Differential-drive wheel kinematics (REP 103: x forward, z up, CCW positive).

Reproduced behaviour (diff_drive_controller, ros2_controllers jazzy): every wheel of a side
gets that side's speed ``v_left = (v - w*s/2) / r_left``, ``v_right = (v + w*s/2) / r_right``;
feedback is the mean over the wheels of a side.
"""


def wheel_velocities(linear, angular, wheel_separation, left_wheel_radius, right_wheel_radius):
    """
    Return ``(left, right)`` wheel angular velocities (rad/s) for a body twist.

    :param linear: forward speed of the base (m/s).
    :param angular: yaw rate of the base (rad/s, CCW positive).
    :param wheel_separation: effective track width (m, > 0).
    :param left_wheel_radius: effective left radius (m, > 0).
    :param right_wheel_radius: effective right radius (m, > 0).
    :returns: tuple of two floats (rad/s).
    :raises ValueError: when a geometry value is not positive.
    """
    for name, value in (('wheel_separation', wheel_separation),
                        ('left_wheel_radius', left_wheel_radius),
                        ('right_wheel_radius', right_wheel_radius)):
        if not value > 0.0:
            raise ValueError(f'{name} must be > 0, got {value}')
    half = 0.5 * angular * wheel_separation
    return (linear - half) / left_wheel_radius, (linear + half) / right_wheel_radius


def body_twist(left_velocity, right_velocity, wheel_separation, left_wheel_radius,
               right_wheel_radius):
    """Return ``(linear, angular)`` (m/s, rad/s) of the base from wheel speeds (rad/s)."""
    left = left_velocity * left_wheel_radius
    right = right_velocity * right_wheel_radius
    return 0.5 * (left + right), (right - left) / wheel_separation


def side_mean(values):
    """
    Return the mean of the feedback values of one side, NaN if any is NaN.

    :param values: sequence of floats, non-empty.
    :returns: float.
    :raises ValueError: when ``values`` is empty.
    """
    values = list(values)
    if not values:
        raise ValueError('no wheel on this side')
    return sum(values) / len(values)
