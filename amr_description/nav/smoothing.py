# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
nav2_velocity_smoother's per-tick limits, as a plain function.

Velocities are ``(vx, vy, wz)`` (m/s, m/s, rad/s). Source:
``nav2_velocity_smoother/src/velocity_smoother.cpp`` (``smoothVelocity``, ``applyConstraints``).
"""

import numpy as np


def smooth(current, command, dt, max_velocity, min_velocity, max_accel, max_decel,
           deadband=(0.0, 0.0, 0.0)):
    """
    Return the next velocity from ``current`` towards ``command`` within the limits.

    The command is clamped to ``[min_velocity, max_velocity]`` per axis and values inside the
    deadband become 0; each axis then changes by at most ``max_accel * dt`` while speeding up
    (same sign and a larger magnitude) and ``|max_decel| * dt`` otherwise.

    :param dt: the smoothing period, ``1 / smoothing_frequency`` (s).
    :returns: ``(3,)`` array.
    """
    cur = np.asarray(current, float)
    cmd = np.clip(np.asarray(command, float), min_velocity, max_velocity)
    cmd = np.where(np.abs(cmd) < np.asarray(deadband, float), 0.0, cmd)
    speeding_up = (np.abs(cmd) >= np.abs(cur)) & (cmd * cur >= 0.0)
    step = np.where(speeding_up, np.abs(max_accel), np.abs(max_decel)) * dt
    return cur + np.clip(cmd - cur, -step, step)
