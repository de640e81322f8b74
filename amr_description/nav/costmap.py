# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Nav2's 2-D costmap as arrays: cost values, footprints, static, obstacle and inflation layers.

A :class:`Costmap` is a ``(height, width)`` ``uint8`` array of Nav2 costs, row ``j`` and
column ``i`` being cell ``(mx=i, my=j)``, whose corner (cell (0, 0)'s outer corner) sits at
``origin`` (m) in the costmap's global frame, ``resolution`` m per cell, as
``nav2_costmap_2d::Costmap2D``: ``mx = floor((wx - origin_x) / resolution)`` and a cell's
centre is ``origin + (m + 0.5) * resolution``.

Cost values (``nav2_costmap_2d/cost_values.hpp``): 0 free, 1..252 inflated, 253 inscribed,
254 lethal, 255 unknown. :func:`to_occupancy` is ``costmap_2d_publisher.cpp``'s translation to
an OccupancyGrid. :func:`static_costs` is ``StaticLayer::interpretValue``; :func:`inflate` is
``InflationLayer``'s cost formula over the Euclidean distance to the nearest lethal cell
(scipy's exact distance transform instead of Nav2's wavefront, which gives the same distances
between cell centres); :func:`raytrace` and :meth:`Costmap.mark` are ``ObstacleLayer``'s
clearing and marking. Footprints follow ``nav2_costmap_2d/src/footprint.cpp``.
"""

import collections
import math

from amr_description.core.tf_buffer import TransformException
# imported here, not in the functions: composed Nav2 servers call them from threads of their
# own, and two threads importing one package at once can see it half initialised (two
# costmaps updating at once saw matplotlib without 'rcParams', which stopped the container)
from matplotlib.path import Path
import numpy as np
from scipy import ndimage
from skimage.draw import line

FREE_SPACE = 0
MAX_NON_OBSTACLE = 252
INSCRIBED_INFLATED_OBSTACLE = 253
LETHAL_OBSTACLE = 254
NO_INFORMATION = 255


def occupancy_table():
    """
    Return the 256-entry table from Nav2 costs to OccupancyGrid values (int8).

    0 -> 0, 1..252 -> ``1 + 97 * (c - 1) // 251`` (1..98), 253 -> 99, 254 -> 100, 255 -> -1.
    Source: ``nav2_costmap_2d/src/costmap_2d_publisher.cpp``.
    """
    table = np.empty(256, np.int8)
    table[0] = 0
    costs = np.arange(1, 253)
    table[1:253] = 1 + (97 * (costs - 1)) // 251
    table[253], table[254], table[255] = 99, 100, -1
    return table


_OCCUPANCY = occupancy_table()


def to_occupancy(costs):
    """Return Nav2 costs (uint8 array, any shape) as OccupancyGrid values (int8)."""
    return _OCCUPANCY[np.asarray(costs, np.uint8)]


def static_costs(occupancy, track_unknown_space=False, lethal_cost_threshold=100,
                 trinary_costmap=True, unknown_cost_value=255):
    """
    Return the static layer's costs for an OccupancyGrid's values.

    :param occupancy: int array of OccupancyGrid values (-1 unknown, 0..100).
    :param track_unknown_space: unknown stays NO_INFORMATION (else FREE).
    :param lethal_cost_threshold: values at or above it are LETHAL.
    :param trinary_costmap: other values are FREE (else scaled ``v / threshold * 254``).
    :param unknown_cost_value: the value read as unknown (255 is -1 read as unsigned).
    :returns: uint8 costs of the same shape.
    Source: ``StaticLayer::interpretValue`` (``nav2_costmap_2d/plugins/static_layer.cpp``).
    """
    values = np.asarray(occupancy).astype(np.int16) & 0xFF  # -1 -> 255, as Nav2 reads it
    if trinary_costmap:
        out = np.zeros(values.shape, np.uint8)
    else:
        scaled = np.floor(values / float(lethal_cost_threshold) * LETHAL_OBSTACLE)
        out = np.clip(scaled, 0, LETHAL_OBSTACLE).astype(np.uint8)
    out[values >= lethal_cost_threshold] = LETHAL_OBSTACLE
    unknown = values == unknown_cost_value
    out[unknown] = NO_INFORMATION if track_unknown_space else FREE_SPACE
    return out


def footprint_from_radius(radius):
    """Return the 16-gon Nav2 makes of ``robot_radius`` (m): a ``(16, 2)`` array, base frame."""
    angles = np.arange(16) * (2.0 * math.pi / 16)
    return np.column_stack((np.cos(angles), np.sin(angles))) * float(radius)


def parse_footprint(text):
    """
    Return the ``footprint`` parameter (``"[[x1, y1], [x2, y2], ...]"``) as an ``(n, 2)`` array.

    :raises ValueError: (one line) for text that is not at least 3 [x, y] pairs of numbers.
    Source: ``makeFootprintFromString`` (``nav2_costmap_2d/src/footprint.cpp``).
    """
    import yaml
    try:
        points = np.array(yaml.safe_load(text), dtype=float)
    except (yaml.YAMLError, TypeError, ValueError):
        points = np.zeros((0,))
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 3 or \
            not np.all(np.isfinite(points)):
        raise ValueError(f'footprint: expected a list of at least 3 [x, y] points, got {text!r}')
    return points


def pad_footprint(points, padding):
    """Return the footprint moved out by ``padding`` (m) along x and y (``padFootprint``)."""
    points = np.asarray(points, float)
    return points + np.sign(points) * float(padding)


def footprint_radii(points):
    """
    Return ``(inscribed, circumscribed)`` radii (m) of a footprint polygon about its origin.

    Inscribed: the smallest distance from the origin to an edge; circumscribed: the largest to a
    vertex (``calculateMinAndMaxDistances``).
    """
    p = np.asarray(points, float)
    q = np.roll(p, -1, axis=0)
    d = q - p
    t = np.clip(-(p * d).sum(1) / np.maximum((d * d).sum(1), 1e-18), 0.0, 1.0)
    closest = p + t[:, None] * d
    return float(np.hypot(*closest.T).min()), float(np.hypot(*p.T).max())


def inflate(costs, resolution, inflation_radius=0.55, cost_scaling_factor=10.0,
            inscribed_radius=0.0, inflate_unknown=False, inflate_around_unknown=False):
    """
    Return ``costs`` with Nav2's inflation layer applied (a new uint8 array).

    For a cell at distance ``d`` (m, between cell centres) from the nearest lethal cell, within
    ``ceil(inflation_radius / resolution)`` cells: 254 at 0, 253 up to ``inscribed_radius``,
    else ``int(252 * exp(-cost_scaling_factor * (d - inscribed_radius)))``; combined by maximum,
    an unknown cell taking only 253 and above (any cost with ``inflate_unknown``).
    Source: ``InflationLayer::computeCost`` and ``updateCosts``
    (``nav2_costmap_2d/plugins/inflation_layer.cpp``).
    """
    costs = np.asarray(costs, np.uint8)
    sources = costs == LETHAL_OBSTACLE
    if inflate_around_unknown:
        sources |= costs == NO_INFORMATION
    if not sources.any():
        return costs.copy()
    cells = ndimage.distance_transform_edt(~sources)
    reach = math.ceil(inflation_radius / resolution)
    d = cells * resolution
    new = np.floor(MAX_NON_OBSTACLE * np.exp(-cost_scaling_factor * (d - inscribed_radius)))
    new = np.clip(new, 0, MAX_NON_OBSTACLE)
    new[d <= inscribed_radius] = INSCRIBED_INFLATED_OBSTACLE
    new[cells == 0] = LETHAL_OBSTACLE
    new[cells > reach] = 0
    new = new.astype(np.uint8)
    out = np.maximum(costs, new)
    unknown = costs == NO_INFORMATION
    takes = (new > 0) if inflate_unknown else (new >= INSCRIBED_INFLATED_OBSTACLE)
    out[unknown & takes] = new[unknown & takes]
    return out


def scan_rays(ranges, angle_min, angle_increment, range_min, range_max, inf_is_valid=False,
              inf_range=0.0):
    """
    Return the end points of a LaserScan's rays in the scan's frame, and which ones are hits.

    Finite readings within ``[range_min, range_max]`` (REP 117) are hits; with
    ``inf_is_valid``, infinite readings are rays of ``inf_range`` m that hit nothing (they only
    clear); the rest are dropped. ``angle_min`` and ``angle_increment`` are in rad.

    :returns: ``(points (n, 2) m, hit (n,) bool)``.
    """
    r = np.asarray(ranges, float)
    a = angle_min + angle_increment * np.arange(len(r))
    hit = np.isfinite(r) & (r >= range_min) & (r <= range_max)
    keep = hit | (np.isinf(r) & bool(inf_is_valid))
    d = np.where(hit, r, inf_range)[keep]
    a = a[keep]
    return np.column_stack((d * np.cos(a), d * np.sin(a))), hit[keep]


class Costmap:
    """
    A grid of Nav2 costs placed in a frame.

    :param costs: ``(height, width)`` uint8 costs.
    :param resolution: m per cell.
    :param origin: ``(x, y)`` of cell (0, 0)'s outer corner, m, in ``frame``.
    :param frame: the costmap's global frame.
    """

    def __init__(self, costs, resolution, origin=(0.0, 0.0), frame='map'):
        """Keep the array (not copied)."""
        self.costs = np.asarray(costs, np.uint8)
        self.resolution = float(resolution)
        self.origin = (float(origin[0]), float(origin[1]))
        self.frame = frame

    @classmethod
    def empty(cls, width_m, height_m, resolution, origin=(0.0, 0.0), frame='map',
              value=FREE_SPACE):
        """Return a costmap of ``width_m`` x ``height_m`` metres filled with ``value``."""
        shape = (int(round(height_m / resolution)), int(round(width_m / resolution)))
        return cls(np.full(shape, value, np.uint8), resolution, origin, frame)

    @property
    def shape(self):
        """``(height, width)`` in cells."""
        return self.costs.shape

    def world_to_map(self, x, y):
        """
        Return the cell ``(mx, my)`` holding world point ``(x, y)``, or None outside the map.

        Source: ``Costmap2D::worldToMap``.
        """
        if not (math.isfinite(x) and math.isfinite(y)):
            return None
        mx = math.floor((x - self.origin[0]) / self.resolution)
        my = math.floor((y - self.origin[1]) / self.resolution)
        h, w = self.costs.shape
        if x < self.origin[0] or y < self.origin[1] or mx >= w or my >= h:
            return None
        return mx, my

    def map_to_world(self, mx, my):
        """Return the world ``(x, y)`` of cell ``(mx, my)``'s centre (arrays accepted)."""
        return (self.origin[0] + (np.asarray(mx) + 0.5) * self.resolution,
                self.origin[1] + (np.asarray(my) + 0.5) * self.resolution)

    def cost_at(self, x, y):
        """Return the cost under world point ``(x, y)``, or None outside the map."""
        cell = self.world_to_map(x, y)
        return None if cell is None else int(self.costs[cell[1], cell[0]])

    def cells_of(self, points):
        """
        Return the cells of world points and which of them are inside the map.

        :param points: ``(n, 2)`` world points, m.
        :returns: ``(mx, my, inside)`` int arrays and a bool mask.
        """
        p = np.asarray(points, float).reshape(-1, 2)
        m = np.floor((p - np.array(self.origin)) / self.resolution).astype(np.int64)
        h, w = self.costs.shape
        inside = (m[:, 0] >= 0) & (m[:, 1] >= 0) & (m[:, 0] < w) & (m[:, 1] < h)
        return m[:, 0], m[:, 1], inside

    def raytrace(self, sensor, points, max_range=3.0, min_range=0.0):
        """
        Clear (to FREE) the cells from ``sensor`` towards each point, the end cell excluded.

        :param sensor: ``(x, y)`` of the sensor origin in the costmap frame, m.
        :param points: ``(n, 2)`` end points, m; rays are cut at ``max_range``.
        :param max_range: ``raytrace_max_range``, m. :param min_range: ``raytrace_min_range``.
        Source: ``ObstacleLayer::raytraceFreespace`` (it clears up to, not including, the cell
        of the end point).
        """
        p = np.asarray(points, float).reshape(-1, 2)
        if not len(p):
            return
        s = np.asarray(sensor, float)
        v = p - s
        length = np.hypot(v[:, 0], v[:, 1])
        reach = np.minimum(length, max_range)
        step = self.resolution * 0.5
        n = int(math.ceil(max(reach.max(), 0.0) / step)) + 1
        t = np.arange(n) * step  # distances along each ray
        unit = v / np.maximum(length, 1e-12)[:, None]
        along = (t[None, :] >= min_range) & (t[None, :] < reach[:, None])
        xs = s[0] + unit[:, :1] * t[None, :]
        ys = s[1] + unit[:, 1:] * t[None, :]
        mx, my, inside = self.cells_of(np.column_stack((xs[along], ys[along])))
        ex, ey, _ = self.cells_of(p)
        per_ray = along.sum(1)
        keep = inside & ((mx != np.repeat(ex, per_ray)) | (my != np.repeat(ey, per_ray)))
        self.costs[my[keep], mx[keep]] = FREE_SPACE

    def mark(self, points, sensor=None, max_range=2.5, min_range=0.0):
        """
        Mark LETHAL the cells of the points within ``[min_range, max_range]`` of ``sensor``.

        Source: ``ObstacleLayer::updateBounds`` (``obstacle_max_range``, ``obstacle_min_range``).
        """
        p = np.asarray(points, float).reshape(-1, 2)
        if sensor is not None and len(p):
            d = np.hypot(*(p - np.asarray(sensor, float)).T)
            p = p[(d <= max_range) & (d >= min_range)]
        mx, my, inside = self.cells_of(p)
        self.costs[my[inside], mx[inside]] = LETHAL_OBSTACLE

    def clear_square(self, x, y, side, value, invert=False):
        """
        Write ``value`` into the cells of a square of ``side`` m centred on ``(x, y)`` (m).

        As ``ClearCostmapService::clearLayerRegion`` and ``Costmap2D::clearArea``: the
        square's corners go to cells clamped to the map (``worldToMapEnforceBounds``) and the
        cells strictly between them are cleared, or, with ``invert``, all the others.

        :param value: the layer's default (NO_INFORMATION when it tracks unknown space, else
            FREE_SPACE).
        """
        h, w = self.costs.shape

        def cell(v, origin, size):
            return int(min(max(math.floor((v - origin) / self.resolution), 0), size - 1))

        x0, x1 = (cell(v, self.origin[0], w) for v in (x - side / 2, x - side / 2 + side))
        y0, y1 = (cell(v, self.origin[1], h) for v in (y - side / 2, y - side / 2 + side))
        cols, rows = np.arange(w), np.arange(h)
        inside = ((rows > y0) & (rows < y1))[:, None] & ((cols > x0) & (cols < x1))[None, :]
        self.costs[inside != invert] = value

    def clear_polygon(self, polygon):
        """
        Set FREE the cells whose centres lie inside ``polygon``.

        :param polygon: ``(n, 2)`` vertices in the costmap's frame, m (the placed footprint).
        Source: ``ObstacleLayer``'s ``footprint_clearing_enabled`` (``setConvexPolygonCost``
        with FREE_SPACE over the footprint's cells).
        """
        poly = np.asarray(polygon, float).reshape(-1, 2)
        h, w = self.costs.shape
        mx, my, _ = self.cells_of(poly)
        i0, i1 = np.clip([mx.min(), mx.max() + 1], 0, w)
        j0, j1 = np.clip([my.min(), my.max() + 1], 0, h)
        if i0 >= i1 or j0 >= j1:
            return
        ii, jj = np.meshgrid(np.arange(i0, i1), np.arange(j0, j1))
        cx, cy = self.map_to_world(ii, jj)
        inside = Path(poly).contains_points(np.column_stack((cx.ravel(), cy.ravel())))
        self.costs[jj.ravel()[inside], ii.ravel()[inside]] = FREE_SPACE

    def paint(self, master, other):
        """
        Copy ``other``'s costs into ``master`` (this costmap's geometry) where they overlap.

        :param master: ``(height, width)`` uint8 array of this costmap's shape, written.
        :param other: a :class:`Costmap` in the same frame (the static layer's map), sampled at
            this costmap's cell centres; cells outside it keep their value.
        """
        if other.costs.shape == self.shape and other.origin == self.origin and \
                other.resolution == self.resolution:
            master[:] = other.costs  # the global costmap: the map's own geometry
            return
        h, w = self.shape
        ii, jj = np.meshgrid(np.arange(w), np.arange(h))
        cx, cy = self.map_to_world(ii, jj)
        mx, my, inside = other.cells_of(np.column_stack((cx.ravel(), cy.ravel())))
        flat = master.reshape(-1)
        flat[inside] = other.costs[my[inside], mx[inside]]

    def rolled(self, layer, pose, unknown=NO_INFORMATION):
        """
        Return this rolling window centred on ``pose`` and ``layer`` moved with it.

        :param layer: ``(height, width)`` uint8 costs kept in this costmap's cells (the
            obstacle layer's).
        :param pose: ``(x, y, ...)`` of the robot in the costmap's frame, m.
        :param unknown: the value of the cells that enter the window.
        :returns: ``(Costmap, layer)``: the window's origin snapped to whole cells, as
            ``Costmap2D::updateOrigin``, and the layer's costs shifted by the same cells.
        """
        res = self.resolution
        h, w = self.shape
        ox = math.floor((pose[0] - w * res / 2.0) / res) * res
        oy = math.floor((pose[1] - h * res / 2.0) / res) * res
        dx = int(round((ox - self.origin[0]) / res))
        dy = int(round((oy - self.origin[1]) / res))
        if dx or dy:
            moved = np.full_like(layer, unknown)
            src = layer[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)]
            moved[max(-dy, 0):max(-dy, 0) + src.shape[0],
                  max(-dx, 0):max(-dx, 0) + src.shape[1]] = src
            layer = moved
        return Costmap(self.costs, res, (ox, oy), self.frame), layer


class ScanQueue(collections.deque):
    """
    Scans of one observation source waiting for TF at their own stamps, oldest first.

    As the tf2 MessageFilter in front of Nav2's observation buffers: a scan waits for the
    transform at its own stamp, and the buffer keeps the newest one transformed. Taking the
    latest transform instead (up to ``transform_tolerance``, 0.3 s, old) could turn the rays
    of a robot turning at 1.8 rad/s 0.54 rad and mark obstacles where there are none.

    :param size: the most scans kept (the oldest go first).
    """

    def __init__(self, size):
        """Start empty; ``dropped`` is the reason the last :meth:`take` dropped a scan."""
        super().__init__(maxlen=size)
        self.dropped = None

    def take(self, tf, global_frame, sensor_frame=''):
        """
        Return ``(scan, T)``: the newest scan TF can place in ``global_frame``, or None.

        That scan and the older ones leave the queue; newer ones, still waiting, stay. The
        oldest scan leaves too when TF will never place it (older than its cache), its error
        kept in ``dropped``.

        :param tf: a :class:`amr_description.core.tf_buffer.TransformBuffer`.
        :param sensor_frame: the frame to use instead of the scans' ``header.frame_id``.
        :returns: the scan and its ``(4, 4)`` transform ``global_frame <- sensor`` at its stamp.
        """
        self.dropped = None
        for k in range(len(self) - 1, -1, -1):
            scan = self[k]
            frame = sensor_frame or scan.header.frame_id
            stamp = scan.header.stamp.sec + scan.header.stamp.nanosec * 1e-9
            try:
                T, _ = tf.lookup(global_frame, frame, stamp)
            except TransformException as exc:
                if k == 0 and not self._pending(tf, global_frame, frame, stamp):
                    self.dropped = str(exc).strip()
                    self.popleft()  # it never will be
                continue
            for _ in range(k + 1):
                self.popleft()
            return scan, T
        return None

    @staticmethod
    def _pending(tf, global_frame, frame, stamp):
        """Return True when TF's latest ``global_frame <- frame`` is older than ``stamp``."""
        try:
            _, latest = tf.lookup(global_frame, frame)
        except TransformException:
            return True  # not connected yet: wait for it too
        return latest < stamp


def place_footprint(footprint, pose):
    """
    Return a footprint's vertices placed at ``pose`` (``orientAndTransformFootprint``).

    :param footprint: ``(n, 2)`` vertices in the robot frame, m.
    :param pose: ``(x, y, yaw)`` of the robot (m, rad).
    :returns: ``(n, 2)`` vertices in the pose's frame, m.
    """
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    return np.asarray(footprint, float) @ np.array([[c, s], [-s, c]]) + (x, y)


def footprint_cost(costmap, footprint, pose):
    """
    Return the highest cost under a footprint's outline placed at ``pose``.

    :param costmap: a :class:`Costmap`.
    :param footprint: ``(n, 2)`` polygon in the robot frame, m (n >= 3), or ``(1, 2)`` for a
        point.
    :param pose: ``(x, y, yaw)`` of the robot in the costmap's frame (m, rad).
    :returns: 0..255; LETHAL_OBSTACLE when a vertex is off the map.
    Source: ``FootprintCollisionChecker::footprintCost`` (the cells of the lines between
    consecutive vertices, closing the polygon).
    """
    pts = place_footprint(footprint, pose)
    mx, my, inside = costmap.cells_of(pts)
    if not inside.all():
        return LETHAL_OBSTACLE
    if len(pts) == 1:
        return int(costmap.costs[my[0], mx[0]])
    best = 0
    for k in range(len(pts)):
        rr, cc = line(int(my[k - 1]), int(mx[k - 1]), int(my[k]), int(mx[k]))
        best = max(best, int(costmap.costs[rr, cc].max()))
    return best
