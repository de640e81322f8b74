# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
AMCL's laser models as Nav2's ``amcl`` (Jazzy) has them, in numpy (no rclpy).

The map as the models read it (:class:`LikelihoodMap`: ``src/map/map.c``, ``map_cspace.cpp``,
``map_range.c``), the beams taken from a scan (:func:`select_beams`, ``amcl_node.cpp``'s
``laserReceived``) and each particle's weight factor (:func:`weight_factors`). Particles are
planar ``(x, y, yaw)`` poses of the base in the map frame (m, m, rad); a beam is a row ``(x, y,
yaw, range)`` of the sensor in the base frame and its reading (m, m, rad, m).
``laser_model_type`` (``src/sensors/laser/``; ``createLaserObject``: any other value is
``likelihood_field``):

- ``likelihood_field`` (``likelihood_field_model.cpp``): ``max_beams`` evenly spaced beams
  (step ``(n - 1) // (max_beams - 1)``); a beam at or beyond range_max, or NaN, is skipped;
  for each other beam ``pz = z_hit exp(-d^2 / (2 sigma_hit^2)) + z_rand / range_max`` with
  ``d`` the end point's obstacle distance, and the particle's weight is multiplied by ``1 +
  sum(pz^3)``.
- ``beam`` (``beam_model.cpp``): the same beams, those at range_max kept; the range the map
  gives along each beam from each particle's sensor pose (:meth:`LikelihoodMap.cast`), ``z =
  range - map range``, ``pz = z_hit exp(-z^2 / (2 sigma_hit^2)) + [z < 0] z_short lambda_short
  exp(-lambda_short range) + [range = range_max] z_max + [range < range_max] z_rand /
  range_max``, weight times ``1 + sum(pz^3)`` (a reading beyond range_max, +inf, adds 0).
- ``likelihood_field_prob`` (``likelihood_field_model_prob.cpp``): beams at step ``ceil(n /
  max_beams)``, ``pz`` as the likelihood field's, weight times ``exp(sum(log pz))`` (Thrun et
  al., Probabilistic Robotics, 6.3.4). With ``do_beamskip``, once the filter has converged: a
  beam is used only if more than ``beam_skip_threshold`` of the particles see its end point
  within ``beam_skip_distance`` of an obstacle, unless at least ``beam_skip_error_threshold``
  of ``max_beams`` would be skipped (then all are used).
"""

import math

import numpy as np
from scipy import ndimage

LASER_MODELS = ('likelihood_field', 'beam', 'likelihood_field_prob')
"""``laser_model_type`` values; upstream runs ``likelihood_field`` for any other."""


class LikelihoodMap:
    """
    The map as AMCL reads it: free cells and each cell's distance to an obstacle.

    ``src/map/map.c``, ``map_cspace.cpp``: 0 free, 100 occupied, anything else unknown; the
    distance (m) from each cell to the nearest occupied one, capped at
    ``laser_likelihood_max_dist`` (``scipy.ndimage.distance_transform_edt``); the origin's yaw
    is ignored, as upstream does.

    :param grid: :class:`~amr_description.nav.map_io.GridMap`.
    :param max_dist: m, the distance cap (``laser_likelihood_max_dist``).
    :param downsample: ``freespace_downsampling``: global localization draws from every
        other free cell in x and y (``createFreeSpaceVector``).
    """

    def __init__(self, grid, max_dist, downsample=False):
        """Compute the distance field."""
        self.resolution = float(grid.resolution)
        self.origin = np.array(grid.origin[:2], dtype=float)
        data = np.asarray(grid.data)
        self.shape = data.shape  # (rows = y, columns = x)
        self.max_dist = float(max_dist)
        occupied = data == 100
        self.free = np.argwhere(data == 0)  # (row, col)
        if downsample:
            self.free = self.free[(self.free[:, 0] % 2 == 0) & (self.free[:, 1] % 2 == 0)]
        if occupied.any():
            d = ndimage.distance_transform_edt(~occupied) * self.resolution
        else:
            d = np.full(self.shape, np.inf)
        self.distance = np.minimum(d, self.max_dist)
        self._is_free = data == 0
        self._clearance = None

    def _cells(self, points):
        """Return the (..., 2) cells (column, row) of points (..., 2) and which are on the map."""
        cells = np.floor((points - self.origin) / self.resolution).astype(np.int64)
        col, row = cells[..., 0], cells[..., 1]
        inside = (row >= 0) & (row < self.shape[0]) & (col >= 0) & (col < self.shape[1])
        return cells, inside

    def lookup(self, points, with_inside=False):
        """
        Return the obstacle distance (m) at each point (..., 2); ``max_dist`` off the map.

        :param with_inside: also return which points are on the map, (...,) bool.
        """
        cells, inside = self._cells(points)
        out = np.full(points.shape[:-1], self.max_dist)
        out[inside] = self.distance[cells[..., 1][inside], cells[..., 0][inside]]
        return (out, inside) if with_inside else out

    def cast(self, origins, angles, max_range):
        """
        Return the range the map gives along each ray, as ``map_range.c``'s ``map_calc_range``.

        A ray stops in the first cell that is not free (occupied, unknown or off the map); the
        range is the distance between the centres of the origin's cell and that cell, or
        ``max_range`` when no such cell lies within it. Upstream walks the cells with
        Bresenham's line (one cell per step along the major axis); here a ray far from any
        cell that is not free jumps by its clearance (a Euclidean distance transform) and near
        one walks every cell it crosses (Amanatides and Woo, "A fast voxel traversal algorithm
        for ray tracing", 1987), so where a ray only clips a cell's corner it can stop one
        cell before Bresenham's line would.

        :param origins: (R, 2) ray origins in the map frame (m).
        :param angles: (R,) directions in the map frame (rad).
        :param max_range: m.
        :returns: (R,) ranges (m).
        """
        if self._clearance is None:
            # cells to the nearest cell not free, 0 on those, with a border of them round the map
            padded = np.pad(self._is_free, 1, constant_values=False)
            self._clearance = ndimage.distance_transform_edt(padded).ravel()
        rows, cols = self.shape[0] + 2, self.shape[1] + 2
        origins = np.asarray(origins, dtype=float).reshape(-1, 2)
        angles = np.asarray(angles, dtype=float).reshape(-1)
        out = np.full(len(origins), float(max_range))
        # in cells of the padded grid: a ray's point is g + t d, its cell floor(g + t d)
        g = (origins - self.origin) / self.resolution + 1.0
        start = np.floor(g)
        d = np.column_stack([np.cos(angles), np.sin(angles)])
        ahead = (d >= 0.0).astype(float)  # the next boundary: cell + 1 ahead, cell behind
        with np.errstate(divide='ignore'):
            inverse = np.where(d != 0.0, 1.0 / d, 1e30)
        limit = max_range / self.resolution
        todo = np.arange(len(origins))
        t = np.zeros(len(origins))
        while len(todo):
            point = g + t[:, None] * d
            cell = np.floor(point)
            col = np.clip(cell[:, 0], 0, cols - 1).astype(np.int64)
            row = np.clip(cell[:, 1], 0, rows - 1).astype(np.int64)
            clearance = self._clearance[row * cols + col]
            hit = clearance == 0.0
            out[todo[hit]] = np.hypot(*(cell[hit] - start[hit]).T) * self.resolution
            # to the next cell boundary; or, far from any cell not free, by the clearance (a
            # point in its cell is within sqrt(2) / 2 of the centre, and so is the other's)
            advance = ((cell + ahead - point) * inverse).min(axis=1) + 1e-6
            t = t + np.maximum(advance, clearance - math.sqrt(2.0))
            keep = ~hit & (t <= limit)
            todo, g, start, d, ahead, inverse, t = (
                todo[keep], g[keep], start[keep], d[keep], ahead[keep], inverse[keep], t[keep])
        return out

    def random_free_poses(self, count, rng):
        """Return ``count`` poses uniformly over the free cells, any heading, (count, 3)."""
        if len(self.free) == 0:
            raise ValueError('the map has no free cell to place particles in')
        pick = self.free[rng.integers(0, len(self.free), count)]
        xy = self.origin + (pick[:, ::-1] + rng.random((count, 2))) * self.resolution
        return np.column_stack([xy, rng.uniform(-math.pi, math.pi, count)])


def select_beams(params, ranges, angle_min, angle_increment, range_min, range_max,
                 sensor_pose):
    """
    Return the laser model's beams, (M, 4) rows of x, y, yaw, range, and its range limit (m).

    ``laser_min_range`` / ``laser_max_range`` replace the scan's limits when above 0 (max)
    or 0 (min); readings at or below range_min become range_max (``amcl_node.cpp``'s
    ``laserReceived``). ``max_beams`` evenly spaced beams: step ``(n - 1) / (max_beams - 1)``,
    or ``ceil(n / max_beams)`` for ``likelihood_field_prob``. NaN and readings beyond range_max
    are left out (they add nothing to the beam model's sum; upstream would carry a NaN into the
    weights); so are readings at range_max except in the beam model.

    :param params: :class:`~amr_description.nav.amcl.AmclParameters`.
    :param ranges: (n,) the scan's readings (m).
    :param sensor_pose: ``(x, y, yaw)`` of the scan's frame in the base frame.
    """
    p = params
    ranges = np.asarray(ranges, dtype=float)
    rmax = min(range_max, p.laser_max_range) if p.laser_max_range > 0 else range_max
    rmin = max(range_min, p.laser_min_range) if p.laser_min_range > 0 else range_min
    n = len(ranges)
    if p.laser_model_type == 'likelihood_field_prob':
        step = max(1, math.ceil(n / max(1, p.max_beams)))
    else:
        step = max(1, (n - 1) // max(1, p.max_beams - 1)) if n > 1 else 1
    idx = np.arange(0, n, step)
    r = np.where(ranges[idx] <= rmin, rmax, ranges[idx])
    keep = np.isfinite(r) & (r > 0.0) & ((r <= rmax) if p.laser_model_type == 'beam'
                                         else (r < rmax))
    idx, r = idx[keep], r[keep]
    yaw = sensor_pose[2] + angle_min + angle_increment * idx
    beams = np.column_stack([np.full(len(r), sensor_pose[0]), np.full(len(r), sensor_pose[1]),
                             yaw, r])
    return beams, rmax


def weight_factors(params, particles, likelihood_map, beams, range_max, converged=False):
    """
    Return what each particle's weight is multiplied by for a scan, (N,) (module docstring).

    :param params: :class:`~amr_description.nav.amcl.AmclParameters` (``laser_model_type``
        and the models' parameters).
    :param particles: (N, 3) base poses in the map frame.
    :param likelihood_map: :class:`LikelihoodMap`.
    :param beams: (M, 4) from :func:`select_beams`.
    :param range_max: m, the limit :func:`select_beams` returned.
    :param converged: whether the filter has converged (beam skipping only).
    """
    if params.laser_model_type == 'beam':
        return _beam_model(params, particles, likelihood_map, beams, range_max)
    if params.laser_model_type == 'likelihood_field_prob':
        return _likelihood_field_prob(params, particles, likelihood_map, beams, range_max,
                                      converged)
    pz = _field_pz(params, particles, likelihood_map, beams, range_max)[0]
    return 1.0 + np.sum(pz ** 3, axis=1)


def _in_map(particles, points):
    """Return the base-frame points (M, 2) placed at every particle, (N, M, 2) in the map."""
    c, s = np.cos(particles[:, 2:3]), np.sin(particles[:, 2:3])
    x, y = points[:, 0], points[:, 1]
    return np.stack([particles[:, 0:1] + c * x - s * y,
                     particles[:, 1:2] + s * x + c * y], axis=-1)


def _field_pz(params, particles, likelihood_map, beams, range_max):
    """Return each beam's ``pz`` (N, M), its end point's distance and if it is on the map."""
    p = params
    ends = beams[:, 0:2] + beams[:, 3:4] * np.column_stack([np.cos(beams[:, 2]),
                                                            np.sin(beams[:, 2])])
    d, inside = likelihood_map.lookup(_in_map(particles, ends), with_inside=True)
    pz = p.z_hit * np.exp(-d * d / (2.0 * p.sigma_hit ** 2)) + p.z_rand / range_max
    return pz, d, inside


def _beam_model(params, particles, likelihood_map, beams, range_max):
    """Return the beam model's weight factor of each particle, (N,) (module docstring)."""
    p = params
    origins = _in_map(particles, beams[:, 0:2])  # (N, M, 2): the sensor at each particle
    angles = particles[:, 2:3] + beams[:, 2]
    expected = likelihood_map.cast(origins.reshape(-1, 2), angles.reshape(-1),
                                   range_max).reshape(angles.shape)
    r = beams[:, 3]
    z = r - expected
    pz = p.z_hit * np.exp(-z * z / (2.0 * p.sigma_hit ** 2))
    pz += np.where(z < 0.0, p.z_short * p.lambda_short * np.exp(-p.lambda_short * r), 0.0)
    pz += np.where(r == range_max, p.z_max, 0.0) + np.where(r < range_max,
                                                            p.z_rand / range_max, 0.0)
    return 1.0 + np.sum(pz ** 3, axis=1)


def _likelihood_field_prob(params, particles, likelihood_map, beams, range_max, converged):
    """Return ``likelihood_field_prob``'s weight factor of each particle, (N,)."""
    p = params
    pz, d, inside = _field_pz(params, particles, likelihood_map, beams, range_max)
    if p.do_beamskip and converged:
        agree = np.count_nonzero(inside & (d < p.beam_skip_distance), axis=0)
        used = agree / len(particles) > p.beam_skip_threshold
        # upstream counts the beams a scan lacks (fewer than max_beams) as skipped
        if p.max_beams - np.count_nonzero(used) < p.max_beams * p.beam_skip_error_threshold:
            pz = pz[:, used]
    return np.exp(np.sum(np.log(pz), axis=1))
