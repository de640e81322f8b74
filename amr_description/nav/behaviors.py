# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Nav2's recovery behaviours' arithmetic (``nav2_behaviors``, Jazzy): speeds and look-ahead poses.

Poses are ``(x, y, yaw)`` in the behaviour's local frame (odom), m and rad, REP 103.
Sources: ``nav2_behaviors/plugins/spin.cpp`` and ``drive_on_heading.hpp``.
"""

import math

import numpy as np


def angle_diff(a, b):
    """Return ``a - b`` wrapped to ``(-pi, pi]`` (rad)."""
    return math.atan2(math.sin(a - b), math.cos(a - b))


def spin_velocity(remaining, acc_lim=3.2, min_vel=0.4, max_vel=1.0):
    """
    Return the magnitude of Spin's angular command (rad/s) with ``remaining`` rad to turn.

    ``clamp(sqrt(2 * acc_lim * remaining), min_vel, max_vel)``: the speed from which the
    rotational acceleration limit stops the robot at the target (``Spin::onCycleUpdate``).
    """
    return min(max(math.sqrt(2.0 * acc_lim * abs(remaining)), min_vel), max_vel)


def spin_poses(pose, w, remaining, horizon, frequency):
    """
    Return the poses Spin checks for collision: turning at ``w`` for ``horizon`` s.

    One pose per cycle (``1 / frequency`` s), stopping at the remaining angle.
    Source: ``Spin::isCollisionFree``.

    :returns: ``(k, 3)`` poses.
    """
    n = int(math.ceil(horizon * frequency))
    turns = np.minimum(np.arange(1, n + 1) * abs(w) / frequency, abs(remaining))
    yaw = pose[2] + math.copysign(1.0, w) * turns
    return np.column_stack((np.full(n, pose[0]), np.full(n, pose[1]), yaw))


def drive_poses(pose, speed, remaining, horizon, frequency):
    """
    Return the poses DriveOnHeading and BackUp check: straight at ``speed`` for ``horizon`` s.

    One pose per cycle, stopping at the remaining distance ``remaining`` (m).
    Source: ``DriveOnHeading::isCollisionFree``.

    :returns: ``(k, 3)`` poses.
    """
    n = int(math.ceil(horizon * frequency))
    d = np.minimum(np.arange(1, n + 1) * abs(speed) / frequency, abs(remaining))
    d *= math.copysign(1.0, speed)
    return np.column_stack((pose[0] + d * math.cos(pose[2]), pose[1] + d * math.sin(pose[2]),
                            np.full(n, pose[2])))


def drive_goal_error(target_x, target_y, target_z, speed, backup):
    """
    Return why a BackUp or DriveOnHeading goal is invalid, or None.

    Both need ``target.y == target.z == 0``; DriveOnHeading also needs ``target.x`` and
    ``speed`` of the same sign (BackUp takes their magnitudes and drives backwards).
    """
    if target_y != 0.0 or target_z != 0.0:
        return 'only a target with y and z equal to 0 is supported'
    values = (target_x, speed)
    if not all(math.isfinite(v) for v in values):
        return 'the target distance and speed must be finite'
    if not backup and target_x * speed < 0.0:
        return 'the speed and the target distance must have the same sign'
    return None
