# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A planar pose graph solved by sparse non-linear least squares (no rclpy).

Nodes are poses ``(x, y, yaw)`` in the map frame; an edge ``(i, j, z, w)`` says "node j seen
from node i is at ``z``" with per-component weights ``w`` (1 / standard deviation). The
residual of an edge is ``w * (between(x_i, x_j) - z)`` with the yaw difference wrapped to
``(-pi, pi]`` (Grisetti et al., "A tutorial on graph-based SLAM", 2010, eq. 30 in 2-D). Node 0
is held fixed (the map frame's anchor); the rest are solved by
``scipy.optimize.least_squares`` (trust-region reflective) with the Jacobian's sparsity
given, so a graph of a few hundred nodes solves in tens of milliseconds.
"""

import math

import numpy as np
from scipy.optimize import least_squares
from scipy.sparse import lil_matrix


def wrap(angle):
    """Return ``angle`` (rad, scalar or array) wrapped to ``[-pi, pi)``."""
    return (np.asarray(angle) + math.pi) % (2.0 * math.pi) - math.pi


def between(a, b):
    """
    Return pose ``b`` expressed in pose ``a``'s frame: ``inverse(a) * b``.

    :param a: (..., 3) poses ``(x, y, yaw)``.
    :param b: (..., 3) poses.
    :returns: (..., 3), yaw wrapped.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    return np.stack([c * dx + s * dy, -s * dx + c * dy, wrap(b[..., 2] - a[..., 2])], axis=-1)


def compose(a, b):
    """Return the pose ``a * b`` of two ``(x, y, yaw)`` poses (arrays of shape (3,))."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array([a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1],
                     float(wrap(a[2] + b[2]))])


def inverse(pose):
    """Return the inverse of a planar pose ``(x, y, yaw)``, as an array (3,)."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return np.array([-c * pose[0] - s * pose[1], s * pose[0] - c * pose[1], -pose[2]])


class PoseGraph:
    """
    Poses and relative-pose constraints; :meth:`optimize` moves every node but the first.

    :ivar poses: (N, 3) array of ``(x, y, yaw)``.
    :ivar edges: list of ``(i, j, z (3,), w (3,), kind)``; kind is ``'link'`` or ``'loop'``.
    """

    def __init__(self):
        """Start empty."""
        self.poses = np.zeros((0, 3))
        self.edges = []

    def __len__(self):
        """Return the number of nodes."""
        return len(self.poses)

    def add_node(self, pose):
        """Append a node at ``pose``; return its index."""
        self.poses = np.vstack([self.poses, np.asarray(pose, dtype=float).reshape(1, 3)])
        return len(self.poses) - 1

    def add_edge(self, i, j, z, weights, kind='link'):
        """
        Add the constraint ``between(pose_i, pose_j) == z``.

        :param weights: (3,) 1 / standard deviation of x (1/m), y (1/m), yaw (1/rad).
        :raises IndexError: when i or j is not a node.
        """
        n = len(self.poses)
        if not (0 <= i < n and 0 <= j < n):
            raise IndexError(f'edge ({i}, {j}) names a node outside 0..{n - 1}')
        self.edges.append((i, j, np.asarray(z, dtype=float), np.asarray(weights, dtype=float),
                           kind))

    def residuals(self, poses=None):
        """Return the stacked weighted residuals, 3 per edge, at the given poses (default: now)."""
        poses = self.poses if poses is None else poses
        if not self.edges:
            return np.zeros(0)
        i = np.array([e[0] for e in self.edges])
        j = np.array([e[1] for e in self.edges])
        z = np.array([e[2] for e in self.edges])
        w = np.array([e[3] for e in self.edges])
        r = between(poses[i], poses[j]) - z
        r[:, 2] = wrap(r[:, 2])
        return (r * w).ravel()

    def optimize(self, max_nfev=50):
        """
        Solve for every node but node 0; return the final cost (half the sum of squares).

        :param max_nfev: most residual evaluations.
        """
        n = len(self.poses)
        if n < 2 or not self.edges:
            return 0.0
        anchor = self.poses[0].copy()

        def full(free):
            return np.vstack([anchor, free.reshape(-1, 3)])

        sparsity = lil_matrix((3 * len(self.edges), 3 * (n - 1)), dtype=int)
        for k, (i, j, *_) in enumerate(self.edges):
            for node in (i, j):
                if node > 0:
                    sparsity[3 * k:3 * k + 3, 3 * (node - 1):3 * node] = 1
        result = least_squares(lambda free: self.residuals(full(free)),
                               self.poses[1:].ravel(), jac_sparsity=sparsity,
                               method='trf', max_nfev=max_nfev, x_scale='jac')
        self.poses = full(result.x)
        self.poses[:, 2] = wrap(self.poses[:, 2])
        return float(result.cost)
