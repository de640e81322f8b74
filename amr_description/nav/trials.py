# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Navigation trials measured against the true world: goals, path lengths, clearance, time bound.

What ``./scripts/main --navigate`` (:mod:`amr_description.nodes.navigate_job`) judges a run
by, as pure functions of grids, poses and the world's shapes (no rclpy):

- :func:`sample_goals`: seeded random goals, reachable from the start and clear of every
  obstacle of every given map by ``clearance``;
- :func:`path_length` of a polyline;
- :func:`footprint_clearance`: the signed distance from the robot's footprint polygon to the
  world's collision shapes at each ground-truth pose (negative: overlapping; a contact);
- :func:`time_bound`: the issue's target time to a goal, ``slack`` x (path length / desired
  speed + in-place turns / rotate-to-heading speed);
- :func:`fastest_time`: the least time a base within given speed and acceleration limits could
  take by the same path and turns (:func:`rest_to_rest` for each);
- :func:`time_budget`: where a drive's time went (standing, turning in place, at speed,
  slower), from its ground truth.
"""

import math

from amr_description.core.course import wrap_angle
from amr_description.core.scan_map import surface_distance
from amr_description.nav.world_map import inside_section
import numpy as np


def clearance_grid(grid):
    """
    Return each cell's distance to the nearest cell that is not free (occupied or unknown).

    :param grid: :class:`~amr_description.nav.map_io.GridMap`; only occupancy 0 is free (a
        trinary map's free cells).
    :returns: (height, width) float array, m, between cell centres.
    """
    from scipy import ndimage
    free = grid.data == 0
    if free.all():
        return np.full(free.shape, np.inf)
    return ndimage.distance_transform_edt(free) * grid.resolution


def _cells(grid, xy):
    """Return (rows, cols, inside) of map-frame points ``xy`` (N, 2) on ``grid``."""
    ox, oy, yaw = grid.origin
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = xy[:, 0] - ox, xy[:, 1] - oy
    cols = np.floor((c * dx + s * dy) / grid.resolution).astype(int)
    rows = np.floor((-s * dx + c * dy) / grid.resolution).astype(int)
    inside = (cols >= 0) & (rows >= 0) & (cols < grid.width) & (rows < grid.height)
    return rows, cols, inside


def clearance_at(grid, clearance, xy):
    """
    Return the clearance of map-frame points, 0 outside the grid.

    :param grid: GridMap of ``clearance``.
    :param clearance: :func:`clearance_grid` of ``grid``.
    :param xy: (N, 2) m in the map frame.
    :returns: (N,) m.
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    rows, cols, inside = _cells(grid, xy)
    out = np.zeros(len(xy))
    out[inside] = clearance[rows[inside], cols[inside]]
    return out


MAX_DRAWS = 100000
"""Draws :func:`sample_goals` makes for one goal before it gives up."""


def sample_goals(grids, start, count, seed, clearance=0.45, spacing=1.5, passage=0.3):
    """
    Return ``count`` seeded random goals the robot can reach from ``start``.

    Candidates are the cell centres of ``grids[0]`` at least ``clearance`` from anything
    not free in every grid (room to turn in place for a robot of circumscribed radius below
    it), connected to ``start`` through cells at least ``passage`` clear (4-connected; room to
    drive through for a robot of half width below it). Each goal is at least ``spacing`` from
    the one before (the first from ``start``); yaws are uniform in [-pi, pi).

    Goals are drawn by rejection: a point uniform over ``grids[0]``'s extent and a yaw, kept
    (as its cell's centre) when its cell is a candidate ``spacing`` away. Each draw's fate
    depends on the maps at that point only, so maps that differ in a few cells (two SLAM runs
    of one world) give the same goals wherever they agree.

    :param grids: list of GridMap in one map frame (e.g. the true map and a SLAM map).
    :param start: ``(x, y)`` m, the robot's position.
    :param count: number of goals.
    :param seed: seed of numpy's default generator (the same seed, the same goals).
    :param clearance: m.
    :param spacing: m.
    :param passage: m.
    :returns: list of ``(x, y, yaw)`` (m, m, rad).
    :raises ValueError: ``start`` not ``passage`` clear, or no candidate ``spacing`` from a
        goal (none in :data:`MAX_DRAWS` draws).
    """
    from scipy import ndimage
    base = grids[0]
    rows, cols = np.indices(base.data.shape).reshape(2, -1)
    ox, oy, yaw = base.origin
    u, v = (cols + 0.5) * base.resolution, (rows + 0.5) * base.resolution
    centres = np.stack([ox + math.cos(yaw) * u - math.sin(yaw) * v,
                        oy + math.sin(yaw) * u + math.cos(yaw) * v], axis=1)
    room = np.full(len(centres), np.inf)
    for grid in grids:
        room = np.minimum(room, clearance_at(grid, clearance_grid(grid), centres))
    labels, _ = ndimage.label((room >= passage).reshape(base.data.shape))
    srow, scol, inside = _cells(base, np.array([start], dtype=float))
    if not inside[0] or labels[srow[0], scol[0]] == 0:
        raise ValueError(f'sample_goals: start ({start[0]:.2f}, {start[1]:.2f}) is not '
                         f'{passage} m clear of every obstacle')
    reachable = (labels == labels[srow[0], scol[0]]).ravel()
    candidate = reachable & (room >= clearance)
    height, width = base.data.shape
    rng = np.random.default_rng(seed)
    goals, here = [], np.asarray(start, dtype=float)
    for _ in range(count):
        for _ in range(MAX_DRAWS):
            u, v, turn = rng.uniform((0.0, 0.0, -math.pi), (width, height, math.pi))
            k = min(int(v), height - 1) * width + min(int(u), width - 1)
            if candidate[k] and math.hypot(*(centres[k] - here)) >= spacing:
                break
        else:
            raise ValueError(f'sample_goals: no reachable cell {spacing} m from '
                             f'({here[0]:.2f}, {here[1]:.2f})')
        here = centres[k]
        goals.append((float(here[0]), float(here[1]), float(turn)))
    return goals


def path_length(xy):
    """
    Return the length of a polyline.

    :param xy: (N, 2) m.
    :returns: m (0 for fewer than two points).
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    return float(np.hypot(*np.diff(xy, axis=0).T).sum()) if len(xy) > 1 else 0.0


def footprint_samples(footprint, step=0.01):
    """
    Return points on the boundary of a footprint polygon, ``step`` apart at most.

    :param footprint: list of ``(x, y)`` vertices in the robot's base frame, m (Nav2's
        ``footprint`` parameter).
    :param step: m.
    :returns: (N, 2) m in the base frame.
    """
    corners = np.asarray(footprint, dtype=float)
    points = []
    for a, b in zip(corners, np.roll(corners, -1, axis=0)):
        n = max(1, int(math.ceil(np.hypot(*(b - a)) / step)))
        points.append(a + np.outer(np.arange(n) / n, b - a))
    return np.concatenate(points)


def footprint_clearance(poses, footprint, sections, step=0.01):
    """
    Return the signed clearance between the footprint at each pose and the world's shapes.

    :param poses: (N, 3) ``(x, y, yaw)`` of the base frame in the world frame, m and rad.
    :param footprint: footprint polygon vertices in the base frame (convex), m.
    :param sections: :func:`amr_description.core.scan_map.world_sections` (one or more
        heights concatenated).
    :param step: m between boundary samples; a shape's corner can reach up to ``step`` / 2
        into the polygon unseen.
    :returns: (N,) m: the smallest distance from the footprint's boundary to a shape's
        boundary; negative when they overlap (the robot touches the world): minus the depth
        of the deepest boundary sample inside a shape, or minus the gap to a shape wholly
        inside the polygon; +inf without shapes.
    """
    poses = np.asarray(poses, dtype=float).reshape(-1, 3)
    local = footprint_samples(footprint, step)
    out = np.full(len(poses), np.inf)
    if not sections:
        return out
    corners = np.asarray(footprint, dtype=float)
    edges = np.roll(corners, -1, axis=0) - corners
    centres = np.array([section[1] for section in sections], dtype=float)
    for i, (x, y, yaw) in enumerate(poses):
        c, s = math.cos(yaw), math.sin(yaw)
        world = np.stack([x + c * local[:, 0] - s * local[:, 1],
                          y + s * local[:, 0] + c * local[:, 1]], axis=1)
        gaps = surface_distance(world, sections)
        within = np.zeros(len(world), bool)
        for section in sections:
            within |= inside_section(world, section)
        if within.any():
            out[i] = -float(gaps[within].max())
            continue
        # a shape wholly inside the polygon: its centre is on one side of every edge
        dx, dy = centres[:, 0] - x, centres[:, 1] - y
        base = np.stack([c * dx + s * dy, -s * dx + c * dy], axis=1)
        rel = base[:, None, :] - corners[None, :, :]
        cross = edges[None, :, 0] * rel[..., 1] - edges[None, :, 1] * rel[..., 0]
        enclosed = bool(((cross >= 0).all(axis=1) | (cross <= 0).all(axis=1)).any())
        out[i] = -float(gaps.min()) if enclosed else float(gaps.min())
    return out


def _turns(xy, start_yaw, goal_yaw):
    """Return the in-place turns (rad) to a path's first heading and from its last."""
    steps = np.diff(xy, axis=0)
    steps = steps[np.hypot(*steps.T) > 1e-9] if len(steps) else steps
    if not len(steps):
        return abs(wrap_angle(goal_yaw - start_yaw)), 0.0
    first = math.atan2(steps[0][1], steps[0][0])
    last = math.atan2(steps[-1][1], steps[-1][0])
    return abs(wrap_angle(first - start_yaw)), abs(wrap_angle(goal_yaw - last))


def time_bound(path, start_yaw, goal_yaw, speed, turn_rate, slack=1.5):
    """
    Return the target time to a goal: ``slack`` x (length / speed + turns / turn rate).

    The turns are in place: from ``start_yaw`` to the path's first heading and from its last
    heading to ``goal_yaw`` (Regulated Pure Pursuit's rotate-to-heading).

    :param path: (N, 2) m, the shortest (planned) path.
    :param start_yaw: rad.
    :param goal_yaw: rad.
    :param speed: m/s (``desired_linear_vel``).
    :param turn_rate: rad/s (``rotate_to_heading_angular_vel``).
    :param slack: the issue's factor (1.5).
    :returns: s.
    """
    xy = np.asarray(path, dtype=float).reshape(-1, 2)
    return slack * (path_length(xy) / speed + sum(_turns(xy, start_yaw, goal_yaw)) / turn_rate)


def rest_to_rest(distance, top, accel):
    """
    Return the shortest time to move ``distance`` from rest to rest within a speed and accel.

    Bang-bang with a cruise: ``distance / top + top / accel`` when the base reaches ``top``
    (``distance >= top^2 / accel``), else ``2 sqrt(distance / accel)`` (accelerate half-way,
    brake the rest).

    :param distance: m (or rad), >= 0.
    :param top: m/s (rad/s), > 0.
    :param accel: m/s^2 (rad/s^2), > 0, the same for speeding up and braking.
    :returns: s.
    """
    distance = abs(float(distance))
    if distance >= top * top / accel:
        return distance / top + top / accel
    return 2.0 * math.sqrt(distance / accel)


def fastest_time(path, start_yaw, goal_yaw, speed, turn_rate, accel, angular_accel):
    """
    Return the least time a base within these limits could take to a goal by this path.

    The turns of :func:`time_bound` in place and the path's length, each from rest to rest
    (:func:`rest_to_rest`); the path's bends are taken as free (turning while driving costs
    nothing), so no base with these limits is faster. A yardstick for :func:`time_bound`,
    which does not count speeding up and braking.

    :param path: (N, 2) m, the shortest (planned) path.
    :param start_yaw: rad.
    :param goal_yaw: rad.
    :param speed: m/s, the top speed on the path (``desired_linear_vel``).
    :param turn_rate: rad/s, the top turn rate in place (``rotate_to_heading_angular_vel``).
    :param accel: m/s^2 (velocity_smoother's ``max_accel`` in x).
    :param angular_accel: rad/s^2 (its ``max_accel`` in theta).
    :returns: s.
    """
    xy = np.asarray(path, dtype=float).reshape(-1, 2)
    before, after = _turns(xy, start_yaw, goal_yaw)
    return (rest_to_rest(before, turn_rate, angular_accel) +
            rest_to_rest(path_length(xy), speed, accel) +
            rest_to_rest(after, turn_rate, angular_accel))


def time_budget(truth, speed, span=None, still=0.03, turning=0.1, cruise=0.8):
    """
    Return where a drive's time went, from its ground truth.

    Each interval between two samples counts by the base's speeds over it, taken as finite
    differences (``|delta (x, y)| / delta t`` and the wrapped ``delta yaw / delta t``):
    turning in place when it translates slower than ``still`` and turns at ``turning`` or
    faster; standing when both are slower; at speed from ``cruise`` x ``speed``; slower
    otherwise (accelerating, braking, regulated on an arc or near the goal).

    :param truth: (N, 4) samples ``t`` (s), ``x``, ``y`` (m, world), ``yaw`` (rad).
    :param speed: m/s, the follower's desired speed (``desired_linear_vel``).
    :param span: ``(t0, t1)`` s: only intervals within it count (default: all).
    :param still: m/s below which the base is not translating.
    :param turning: rad/s from which a base not translating is turning in place.
    :param cruise: the fraction of ``speed`` counted as at speed.
    :returns: dict ``standing``, ``turning``, ``at_speed``, ``slower`` (s).
    """
    samples = np.asarray(truth, dtype=float).reshape(-1, 4)
    if span is not None:
        t0, t1 = span
        samples = samples[(samples[:, 0] >= t0) & (samples[:, 0] <= t1)]
    dt = np.diff(samples[:, 0])
    keep = dt > 0.0
    dt = dt[keep]
    v = (np.hypot(*np.diff(samples[:, 1:3], axis=0).T)[keep] / dt) if len(dt) else dt
    w = np.abs(np.arctan2(np.sin(np.diff(samples[:, 3])), np.cos(np.diff(samples[:, 3]))))
    w = w[keep] / dt if len(dt) else dt
    moving = v >= still
    fast = v >= cruise * speed - 1e-9  # a sampled 0.4 m/s is at 0.8 x 0.5, not just under
    return {'standing': float(dt[~moving & (w < turning)].sum()),
            'turning': float(dt[~moving & (w >= turning)].sum()),
            'at_speed': float(dt[fast].sum()),
            'slower': float(dt[moving & ~fast].sum())}
