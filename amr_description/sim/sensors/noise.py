# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
SDF noise applied as gz-sensors 8 applies it, from a seeded generator (no rclpy).

``GaussianNoiseModel`` of gz-sensors 8: at creation a bias is drawn from
N(``bias_mean``, ``bias_stddev``) and given a random sign; every value becomes
``value + bias + N(mean, stddev)``; ``gaussian_quantized`` then rounds to a multiple of
``precision``. Generators are numpy ``Generator``s seeded from the simulator's ``seed``, the
entity name and the sensor name (:func:`generator`), so one seed gives the same sequence in
every run.
"""

import zlib

import numpy as np


def generator(seed, *names):
    """
    Return a numpy ``Generator`` seeded from an integer seed and names (stable across runs).

    :param seed: int >= 0 (the ``seed`` parameter of ``mujoco_sim``).
    :param names: strings (entity, sensor) that make one sensor's stream its own.
    """
    return np.random.default_rng([int(seed)] + [zlib.crc32(n.encode()) for n in names])


class NoiseModel:
    """
    One SDF ``<noise>`` bound to a generator.

    :param noise: :class:`~amr_description.core.gazebo_sensors.Noise`.
    :param rng: numpy ``Generator``.
    """

    def __init__(self, noise, rng):
        """Draw the bias once (see the module docstring)."""
        self.noise = noise
        self.rng = rng
        self.active = noise.active
        self.bias = 0.0
        if self.active and (noise.bias_mean != 0.0 or noise.bias_stddev > 0.0):
            bias = rng.normal(noise.bias_mean, noise.bias_stddev) if noise.bias_stddev > 0 \
                else noise.bias_mean
            self.bias = -bias if rng.uniform() < 0.5 else bias

    def apply(self, values):
        """
        Return ``values`` (float or numpy array) with noise; unchanged without noise.

        Non-finite values are left as they are (REP 117 readings stay +-inf).
        """
        if not self.active:
            return values
        noise = self.noise
        values = np.asarray(values, dtype=float)
        noisy = values + self.bias + (self.rng.normal(noise.mean, noise.stddev, values.shape)
                                      if noise.stddev > 0 else noise.mean)
        if noise.type == 'gaussian_quantized' and noise.precision > 0:
            noisy = np.round(noisy / noise.precision) * noise.precision
        return np.where(np.isfinite(values), noisy, values)
