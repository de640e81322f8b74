# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A 2-D lidar's scans placed in the world and compared with the world's true geometry (no rclpy).

The true geometry is the horizontal section of an SDF world's collision shapes at the lidar's
height (:func:`world_sections`): upright boxes give rectangles, upright cylinders, capsules
and spheres give circles. A scan point's error is its distance to the nearest section
boundary (:func:`surface_distance`); the main job counts the points within 3 stddev + 1 cm.
"""

import math

import numpy as np


def _pose_in_world(model, link, shape):
    return model.pose @ link.pose @ shape.pose


def world_sections(world, height):
    """
    Return the sections of a world's collision shapes with the plane ``z = height``.

    :param world: a :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :param height: m, in the world frame.
    :returns: list of ``('box', (x, y), yaw, (half x, half y))`` and
        ``('circle', (x, y), radius)``; shapes whose axis is not upright, or that the plane
        misses, are left out.
    """
    sections = []
    for model in world.models:
        for link in model.links:
            for shape in link.collisions:
                T = _pose_in_world(model, link, shape)
                if abs(T[2, 2]) < 1.0 - 1e-6:
                    continue  # tilted: no simple section
                z, centre, yaw = T[2, 3], (T[0, 3], T[1, 3]), math.atan2(T[1, 0], T[0, 0])
                if shape.kind == 'box':
                    hx, hy, hz = (0.5 * s for s in shape.size[:3])
                    if abs(height - z) <= hz:
                        sections.append(('box', centre, yaw, (hx, hy)))
                elif shape.kind in ('cylinder', 'capsule'):
                    radius, length = shape.size[:2]
                    reach = 0.5 * length + (radius if shape.kind == 'capsule' else 0.0)
                    if abs(height - z) <= reach:
                        cap = abs(height - z) - 0.5 * length
                        r = radius if cap <= 0 else math.sqrt(max(radius ** 2 - cap ** 2, 0))
                        sections.append(('circle', centre, r))
                elif shape.kind == 'sphere':
                    radius = shape.size[0]
                    if abs(height - z) < radius:
                        sections.append(('circle', centre,
                                         math.sqrt(radius ** 2 - (height - z) ** 2)))
    return sections


def surface_distance(points, sections):
    """
    Return each point's distance to the nearest section boundary.

    :param points: (N, 2) m in the world frame.
    :param sections: :func:`world_sections`.
    :returns: (N,) m; +inf for every point when there is no section.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    best = np.full(len(points), np.inf)
    for section in sections:
        if section[0] == 'box':
            _, (cx, cy), yaw, (hx, hy) = section
            c, s = math.cos(yaw), math.sin(yaw)
            dx, dy = points[:, 0] - cx, points[:, 1] - cy
            local = np.abs(np.stack([c * dx + s * dy, -s * dx + c * dy], axis=1))
            over = local - (hx, hy)
            outside = np.linalg.norm(np.maximum(over, 0.0), axis=1)
            inside = np.minimum(-over[:, 0], -over[:, 1])
            d = np.where(np.any(over > 0, axis=1), outside, inside)
        else:
            _, (cx, cy), r = section
            d = np.abs(np.hypot(points[:, 0] - cx, points[:, 1] - cy) - r)
        best = np.minimum(best, d)
    return best


def compose(a, b):
    """Return the planar pose ``a * b`` of two ``(x, y, yaw)`` poses."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def inverse(a):
    """Return the inverse of a planar pose ``(x, y, yaw)``."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2])


def interpolate(samples, t):
    """
    Return the planar pose at time ``t`` from ``(time, (x, y, yaw))`` samples in time order.

    Linear between the two samples around ``t`` (yaw along the shorter way); None when ``t``
    is outside the samples.
    """
    times = [s[0] for s in samples]
    i = int(np.searchsorted(times, t))
    if i == len(samples) or (i == 0 and t < times[0]):
        return None
    if times[i] == t or i == 0:
        return samples[i][1]
    (t0, a), (t1, b) = samples[i - 1], samples[i]
    f = (t - t0) / (t1 - t0) if t1 > t0 else 0.0
    dyaw = math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2]))
    return (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * dyaw)


def scan_to_world(ranges, angle_min, angle_increment, pose):
    """
    Return the finite points of a scan in the world frame.

    :param ranges: (N,) m (REP 117 +-inf are left out).
    :param angle_min: rad; ``angle_increment`` rad.
    :param pose: ``(x, y, yaw)`` of the scan's frame in the world.
    :returns: (M, 2) m.
    """
    ranges = np.asarray(ranges, dtype=float)
    angles = angle_min + angle_increment * np.arange(len(ranges)) + pose[2]
    keep = np.isfinite(ranges)
    r, a = ranges[keep], angles[keep]
    return np.stack([pose[0] + r * np.cos(a), pose[1] + r * np.sin(a)], axis=1)
