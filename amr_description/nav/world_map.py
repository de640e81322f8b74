# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A world's true occupancy map, drawn from its collision shapes (a map with no SLAM error).

The sections of the world's upright shapes (:func:`amr_description.core.scan_map.world_sections`)
are taken at several heights, so that a shelf's low plinth and its posts are both in the map;
a cell is occupied (100) when its centre lies inside a section or within half a cell's
diagonal of its boundary, free (0) otherwise. The map covers every section plus ``margin``.
"""

import math

from amr_description.core.scan_map import surface_distance
from amr_description.core.scan_map import world_sections
from amr_description.nav.map_io import GridMap
import numpy as np

HEIGHTS = (0.05, 0.25)
"""m above the ground: a low obstacle's height and the tutorial robot's lidar range."""


def inside_section(points, section):
    """
    Return which points lie inside (or on) a section.

    :param points: (N, 2) m in the world frame.
    :param section: one of :func:`amr_description.core.scan_map.world_sections`.
    :returns: (N,) bool.
    """
    if section[0] == 'box':
        _, (cx, cy), yaw, (hx, hy) = section
        c, s = math.cos(yaw), math.sin(yaw)
        dx, dy = points[:, 0] - cx, points[:, 1] - cy
        return (np.abs(c * dx + s * dy) <= hx) & (np.abs(-s * dx + c * dy) <= hy)
    _, (cx, cy), radius = section
    return np.hypot(points[:, 0] - cx, points[:, 1] - cy) <= radius


def _extent(section):
    if section[0] == 'box':
        _, (cx, cy), yaw, (hx, hy) = section
        c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
        rx, ry = c * hx + s * hy, s * hx + c * hy
    else:
        _, (cx, cy), rx = section
        ry = rx
    return cx - rx, cy - ry, cx + rx, cy + ry


def world_map(world, resolution=0.05, heights=HEIGHTS, margin=0.5):
    """
    Return the world's occupancy as a :class:`~amr_description.nav.map_io.GridMap`.

    :param world: a :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :param resolution: m per cell.
    :param heights: m above the world's z = 0 at which shapes are cut.
    :param margin: m of free cells around the sections' bounds.
    :returns: GridMap in the world frame (map = world); for a world without upright shapes a
        free 10 x 10 m map centred on the origin.
    :raises ValueError: a resolution or margin that is not positive.
    """
    if not resolution > 0.0 or not margin >= 0.0:
        raise ValueError(f'world_map: resolution {resolution} and margin {margin}: expected '
                         'resolution > 0 and margin >= 0')
    sections = [s for h in heights for s in world_sections(world, h)]
    if sections:
        ext = np.array([_extent(s) for s in sections])
        lo = ext[:, :2].min(axis=0) - margin
        hi = ext[:, 2:].max(axis=0) + margin
    else:
        lo, hi = np.array([-5.0, -5.0]), np.array([5.0, 5.0])
    width, rows = (int(math.ceil(v)) for v in (hi - lo) / resolution)
    cols, rws = np.meshgrid(np.arange(width), np.arange(rows))
    centres = np.stack([lo[0] + (cols + 0.5) * resolution, lo[1] + (rws + 0.5) * resolution],
                       axis=-1).reshape(-1, 2)
    occupied = np.zeros(len(centres), bool)
    for section in sections:
        occupied |= inside_section(centres, section)
    if sections:
        occupied |= surface_distance(centres, sections) <= resolution * math.sqrt(0.5)
    data = np.where(occupied, 100, 0).astype(np.int8).reshape(rows, width)
    return GridMap(data, float(resolution), (float(lo[0]), float(lo[1]), 0.0))
