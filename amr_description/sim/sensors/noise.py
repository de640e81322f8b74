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

    :param noise: :class:`~amr_description.core.gazebo.sensors.Noise`.
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

    def skip(self, count):
        """
        Draw the gaussian numbers of :meth:`apply` on ``count`` values and discard them.

        numpy's ``normal(mean, stddev, n)`` takes n standard normals from the generator, as
        ``standard_normal(n)`` does, so the following draws are those after an ``apply``.
        """
        if self.active and self.noise.stddev > 0:
            self.rng.standard_normal(int(count))


class AxesNoise:
    """
    Several SDF ``<noise>`` elements, one per axis, applied to a vector in one draw.

    Each axis behaves as a :class:`NoiseModel` of its ``<noise>`` (its own bias drawn once);
    the gaussian draws of all axes come from one call of the generator, so that an IMU's six
    axes cost one draw per measurement.

    :param noises: list of :class:`~amr_description.core.gazebo.sensors.Noise`, one per axis.
    :param rng: numpy ``Generator``.
    """

    def __init__(self, noises, rng):
        """Draw each axis's bias once and stack the parameters."""
        models = [NoiseModel(noise, rng) for noise in noises]
        self.rng = rng
        self.active = any(m.active for m in models)
        self.offset = np.array([m.bias + (m.noise.mean if m.active else 0.0) for m in models])
        self.stddev = np.array([m.noise.stddev if m.active else 0.0 for m in models])
        self.precision = np.array([m.noise.precision if m.active and
                                   m.noise.type == 'gaussian_quantized' else 0.0
                                   for m in models])
        self._quantized = bool(np.any(self.precision > 0))
        self._draw = bool(np.any(self.stddev > 0))

    def apply(self, values):
        """Return ``values`` ((n,) array, one per axis) with each axis's noise."""
        if not self.active:
            return values
        noisy = values + self.offset
        if self._draw:
            noisy = noisy + self.stddev * self.rng.standard_normal(len(self.stddev))
        if self._quantized:
            step = np.where(self.precision > 0, self.precision, 1.0)
            noisy = np.where(self.precision > 0, np.round(noisy / step) * step, noisy)
        return noisy

    def skip(self):
        """Draw the gaussian numbers of one :meth:`apply` and discard them."""
        if self.active and self._draw:
            self.rng.standard_normal(len(self.stddev))
