# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Planar scan matching: a correlative search, then point-to-line ICP (no rclpy).

A scan's points (robot frame, m) are placed against reference points (map frame, m), as
Karto's ``ScanMatcher`` (slam_toolbox's ``lib/karto_sdk``) does in two stages, written here
with scipy:

1. **correlative search** over a window of ``(x, y, yaw)`` around a prior pose: a likelihood
   grid ``exp(-d^2 / (2 sigma^2))`` of the distance ``d`` to the nearest reference point
   (``scipy.ndimage.distance_transform_edt``) is read at every transformed point, and the
   offset with the highest mean wins (Olson, "Real-time correlative scan matching", ICRA 2009);
2. **point-to-line ICP** from there: each point's nearest reference point
   (``scipy.spatial.cKDTree``) and that point's line normal (the principal axis of its
   neighbours), and the linearised least-squares step of ``sum(((R p + t - q) . n)^2)``
   (Censi, "An ICP variant using a point-to-line metric", ICRA 2008).

The **response** of a pose is the mean over the scan's points of
``exp(-d^2 / (2 sigma^2))``, ``d`` the distance to the nearest reference point's line: 1 when every
point lies on the reference, 0 when none is near. It plays the part of Karto's correlation
response (its ``link_match_minimum_response_fine`` and loop thresholds).
"""

import math

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree


def rotation(yaw):
    """Return the 2x2 rotation matrix of ``yaw`` (rad)."""
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s], [s, c]])


def transform_points(points, pose):
    """
    Return ``points`` (N, 2) placed at the planar pose ``(x, y, yaw)``.

    :param points: (N, 2) m in the pose's frame.
    :param pose: ``(x, y, yaw)`` m, m, rad.
    :returns: (N, 2) m in the frame the pose is expressed in.
    """
    return np.asarray(points, dtype=float) @ rotation(pose[2]).T + np.asarray(pose[:2])


class Reference:
    """
    Reference points (map frame) prepared for matching: a k-d tree and line normals.

    :param points: (N, 2) m, N >= 3.
    :param neighbours: points used for each normal (the principal axis of the nearest ones).
    :raises ValueError: with fewer than 3 points.
    """

    def __init__(self, points, neighbours=6):
        """Build the tree and the normals."""
        self.points = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(self.points) < 3:
            raise ValueError(f'a reference needs at least 3 points, got {len(self.points)}')
        self.tree = cKDTree(self.points)
        k = min(neighbours, len(self.points))
        _, idx = self.tree.query(self.points, k=k)
        nb = self.points[idx] - self.points[idx].mean(axis=1, keepdims=True)
        cov = np.einsum('nki,nkj->nij', nb, nb)
        _, vectors = np.linalg.eigh(cov)
        self.normals = vectors[:, :, 0]  # smallest eigenvalue: across the line

    def distances(self, points, line_gate=0.3):
        """
        Return each point's distance to the reference, (N,) m.

        Within ``line_gate`` (m) of its nearest reference point a point's distance is to that
        point's line (so that the spacing of the reference's points does not count), beyond
        it the distance to the point.
        """
        d, idx = self.tree.query(points)
        idx = np.minimum(idx, len(self.points) - 1)
        across = np.abs(np.einsum('ni,ni->n', points - self.points[idx], self.normals[idx]))
        return np.where(d <= line_gate, across, d)

    def response(self, points, pose, sigma):
        """
        Return how well the points (robot frame) placed at a pose fit: the response, 0..1.

        :param sigma: m, the smear deviation.
        """
        if len(points) == 0:
            return 0.0
        d = self.distances(transform_points(points, pose))
        return float(np.mean(np.exp(-0.5 * (d / sigma) ** 2)))

    def likelihood_grid(self, resolution, sigma, margin):
        """
        Return ``(grid, origin)``: ``exp(-d^2 / (2 sigma^2))`` on cells of ``resolution``.

        :param margin: m added around the points' bounding box.
        :returns: grid (W, H) indexed ``[ix, iy]``, origin (2,) m of cell (0, 0)'s centre.
        """
        lo = self.points.min(axis=0) - margin
        hi = self.points.max(axis=0) + margin
        shape = np.ceil((hi - lo) / resolution).astype(int) + 1
        occupied = np.ones(shape, dtype=bool)
        cells = np.round((self.points - lo) / resolution).astype(int)
        occupied[cells[:, 0], cells[:, 1]] = False
        d = ndimage.distance_transform_edt(occupied) * resolution
        return np.exp(-0.5 * (d / sigma) ** 2), lo


def correlative_search(reference, points, prior, half_width, resolution, half_angle,
                       angle_step, sigma, surface=None):
    """
    Return ``(pose, score)``: the best pose on a grid of offsets around ``prior``.

    :param reference: :class:`Reference`.
    :param points: (N, 2) m, robot frame.
    :param prior: ``(x, y, yaw)`` where the search is centred.
    :param half_width: m, the window is ``prior +- half_width`` in x and y.
    :param resolution: m between offsets (also the likelihood grid's cell).
    :param half_angle: rad, the window is ``prior.yaw +- half_angle``.
    :param angle_step: rad between yaw offsets.
    :param sigma: m, the likelihood's smear deviation.
    :param surface: a list, or None; when given, the (2n+1, 2n+1) array of each ``(x, y)``
        offset's best score over the yaw offsets is appended to it, indexed ``[ix, iy]`` from
        ``-n`` to ``n`` (``n = round(half_width / resolution)``; Karto's search space
        probabilities, read by :func:`positional_variance`).
    :returns: pose ``(x, y, yaw)`` and its mean likelihood (0..1); ``(prior, 0.0)`` with no
        points.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    n = int(round(half_width / resolution))
    best_xy = None
    if surface is not None:  # only the loop search asks; the link search skips the work
        best_xy = np.zeros((2 * n + 1) ** 2)
        surface.append(best_xy.reshape(2 * n + 1, 2 * n + 1))
    if len(points) == 0:
        return tuple(prior), 0.0
    reach = float(np.max(np.hypot(points[:, 0], points[:, 1])))
    grid, origin = reference.likelihood_grid(resolution, max(sigma, resolution),
                                             margin=1.0)
    offsets = np.arange(-n, n + 1)
    dx, dy = np.meshgrid(offsets, offsets, indexing='ij')
    dx, dy = dx.ravel(), dy.ravel()
    steps = int(round(half_angle / angle_step)) if angle_step > 0 else 0
    best = (-1.0, tuple(prior))
    shape = np.array(grid.shape)
    padded = np.pad(grid, n + int(math.ceil(reach / resolution)) + 2)
    pad = n + int(math.ceil(reach / resolution)) + 2
    for k in range(-steps, steps + 1):
        yaw = prior[2] + k * angle_step
        placed = transform_points(points, (prior[0], prior[1], yaw))
        cells = np.round((placed - origin) / resolution).astype(int) + pad
        inside = np.all((cells >= n) & (cells < shape + 2 * pad - n), axis=1)
        cells = cells[inside]
        if len(cells) == 0:
            continue
        scores = padded[cells[None, :, 0] + dx[:, None], cells[None, :, 1] + dy[:, None]]
        scores = scores.sum(axis=1) / len(points)
        if best_xy is not None:
            np.maximum(best_xy, scores, out=best_xy)
        i = int(np.argmax(scores))
        if scores[i] > best[0]:
            best = (float(scores[i]), (prior[0] + dx[i] * resolution,
                                       prior[1] + dy[i] * resolution, yaw))
    return best[1], max(best[0], 0.0)


def positional_variance(surface, offset, resolution, response):
    """
    Return ``(var_xx, var_yy)`` (m^2) of a coarse search's best position, as Karto's.

    Karto's ``ScanMatcher::ComputePositionalCovariance`` (slam_toolbox's
    ``lib/karto_sdk/src/Mapper.cpp``): the offsets whose best score over yaw is at least
    ``response - 0.1`` are weighted by their score, the weighted mean square distance from the
    best offset along x and along y is taken, each at least ``0.1 resolution^2``, then divided
    by ``response`` (poorer matches are less certain). A look-alike place inside the window
    (a second aisle) scoring nearly as well as the best spreads the weight and raises the
    variance; Karto refuses a loop closure whose variance reaches
    ``loop_match_maximum_variance_coarse``.

    :param surface: (2n+1, 2n+1) scores indexed ``[ix, iy]`` (:func:`correlative_search`).
    :param offset: ``(dx, dy)`` m, the best position minus the search's centre.
    :param resolution: m between offsets.
    :param response: the best score (0..1).
    :returns: ``(var_xx, var_yy)`` m^2; Karto's ``MAX_VARIANCE`` (500) for a response of 0.
    """
    surface = np.asarray(surface, dtype=float)
    if response <= 1e-9 or surface.size == 0:
        return 500.0, 500.0
    n = (surface.shape[0] - 1) // 2
    coords = np.arange(-n, n + 1) * resolution
    x, y = np.meshgrid(coords, coords, indexing='ij')
    keep = surface >= response - 0.1
    w = surface[keep]
    norm = float(np.sum(w))
    if norm <= 1e-9:
        return 500.0, 500.0
    floor = 0.1 * resolution ** 2
    var_xx = max(float(np.sum((x[keep] - offset[0]) ** 2 * w)) / norm, floor) / response
    var_yy = max(float(np.sum((y[keep] - offset[1]) ** 2 * w)) / norm, floor) / response
    return var_xx, var_yy


def icp(reference, points, pose, iterations=20, max_distance=0.3):
    """
    Refine ``pose`` by point-to-line ICP; return the refined ``(x, y, yaw)``.

    Each iteration pairs points with their nearest reference point within ``max_distance``
    (halved after every 5 iterations, down to 0.05 m) and solves the linearised 3x3 normal
    equations of the point-to-line error; it stops when the step is below 1e-5.

    :param reference: :class:`Reference`.
    :param points: (N, 2) m, robot frame.
    :param pose: the starting ``(x, y, yaw)``.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    x, y, yaw = (float(v) for v in pose)
    for it in range(iterations):
        gate = max(max_distance * 0.5 ** (it // 5), 0.05)
        placed = transform_points(points, (x, y, yaw))
        d, idx = reference.tree.query(placed, distance_upper_bound=gate)
        keep = np.isfinite(d)
        if np.count_nonzero(keep) < 6:
            break
        p, q, nrm = placed[keep], reference.points[idx[keep]], reference.normals[idx[keep]]
        # error e = (p - q) . n; d e / d(tx, ty, dyaw) with p rotated about the pose origin
        rel = p - (x, y)
        jac = np.stack([nrm[:, 0], nrm[:, 1],
                        -rel[:, 1] * nrm[:, 0] + rel[:, 0] * nrm[:, 1]], axis=1)
        err = np.einsum('ni,ni->n', p - q, nrm)
        h = jac.T @ jac + 1e-9 * np.eye(3)
        step = -np.linalg.solve(h, jac.T @ err)
        c, s = math.cos(step[2]), math.sin(step[2])
        x, y = c * x - s * y + step[0], s * x + c * y + step[1]
        yaw += step[2]
        if np.max(np.abs(step)) < 1e-5:
            break
    return x, y, yaw
