# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Graph SLAM from a 2-D lidar and odometry, as slam_toolbox's Karto mapper does it (no rclpy).

:class:`Mapper` keeps one pose-graph node per *processed* scan (a keyframe):

- a scan is processed when the robot moved ``minimum_travel_distance`` (m) or turned
  ``minimum_travel_heading`` (rad) in odometry since the last one (Karto's ``Mapper::Process``
  test; the first scan always is);
- its pose is predicted from the last keyframe and the odometry since, then, with
  ``use_scan_matching``, matched (:mod:`.scan_matcher`) against the running buffer: the last
  ``scan_buffer_size`` keyframes within ``scan_buffer_maximum_scan_distance``; the match is
  kept when its response reaches ``link_match_minimum_response_fine``, else the prediction;
- a *link* edge ties it to the previous keyframe;
- with ``do_loop_closing``, the keyframes within ``loop_search_maximum_distance`` that are at
  least ``loop_match_minimum_chain_size`` keyframes older are matched against: a coarse
  correlative search in ``loop_search_space_dimension`` (whose response must reach
  ``loop_match_minimum_response_coarse`` and whose positional variance, Karto's
  ``ComputePositionalCovariance``, must stay below ``loop_match_maximum_variance_coarse``:
  a look-alike place in the window that fits nearly as well refuses the match) then ICP
  (``loop_match_minimum_response_fine``); a *loop* edge is added and the graph
  (:mod:`.pose_graph`) is optimised.

The occupancy grid (:meth:`Mapper.occupancy`) is rebuilt from every keyframe at its optimised
pose as Karto's ``OccupancyGrid::CreateFromScans``: each ray passes through the cells from
the sensor to its end point and hits its end point (a reading beyond ``max_laser_range``, or a
REP 117 ``+inf``, passes up to ``max_laser_range`` and hits nothing); a cell crossed more than
``min_pass_through`` times is occupied (100) when ``hits / passes > occupancy_threshold``,
else free (0); other cells are unknown (-1).

Poses are planar ``(x, y, yaw)`` (m, m, rad): keyframe poses in the map frame, odometry in
the odom frame, both of the base frame (``base_footprint``).
"""

from dataclasses import dataclass
from dataclasses import fields
import math

from amr_description.nav.map_io import GridMap
from amr_description.nav.pose_graph import between
from amr_description.nav.pose_graph import compose
from amr_description.nav.pose_graph import inverse
from amr_description.nav.pose_graph import PoseGraph
from amr_description.nav.scan_matcher import correlative_search
from amr_description.nav.scan_matcher import icp
from amr_description.nav.scan_matcher import positional_variance
from amr_description.nav.scan_matcher import Reference
from amr_description.nav.scan_matcher import transform_points
import numpy as np

LINK_SIGMA = (0.02, 0.02, 0.01)
"""Standard deviation (m, m, rad) given to a matched link or loop edge."""

ODOM_SIGMA = (0.1, 0.1, 0.05)
"""Standard deviation (m, m, rad) of a link edge from odometry alone (no match)."""

WIDE_SEARCH = 4.0
"""A failed link match is searched again in a window this many times wider (and coarser):
wheels slipping against an obstacle move odometry by more than Karto's 0.5 m window."""

LOOP_DRIFT = (0.3, 0.1)
"""A loop closure may move the new keyframe by at most ``0.3 m + 0.1 x`` the path driven since
the matched keyframe (m), and turn it by at most ``coarse_search_angle_offset``: a larger jump
is a look-alike place (the arena's grid of pillars), not drift."""


@dataclass
class SlamParameters:
    """
    slam_toolbox's mapper parameters this mapper uses, with slam_toolbox 2.8.3's code defaults.

    Source: ``src/slam_mapper.cpp`` and ``src/laser_utils.cpp`` of slam_toolbox (the
    defaults where ``config/mapper_params_online_async.yaml`` differs are the code's).
    """

    resolution: float = 0.05
    max_laser_range: float = 25.0
    use_scan_matching: bool = True
    minimum_travel_distance: float = 0.5
    minimum_travel_heading: float = 0.5
    scan_buffer_size: int = 10
    scan_buffer_maximum_scan_distance: float = 10.0
    link_match_minimum_response_fine: float = 0.1
    link_scan_maximum_distance: float = 1.5
    do_loop_closing: bool = True
    loop_search_maximum_distance: float = 3.0
    loop_match_minimum_chain_size: int = 10
    loop_match_maximum_variance_coarse: float = 3.0
    loop_match_minimum_response_coarse: float = 0.35
    loop_match_minimum_response_fine: float = 0.45
    correlation_search_space_dimension: float = 0.5
    correlation_search_space_resolution: float = 0.01
    correlation_search_space_smear_deviation: float = 0.1
    loop_search_space_dimension: float = 8.0
    loop_search_space_resolution: float = 0.05
    loop_search_space_smear_deviation: float = 0.03
    coarse_search_angle_offset: float = 0.349
    coarse_angle_resolution: float = 0.0349
    min_pass_through: int = 2
    occupancy_threshold: float = 0.1

    @classmethod
    def names(cls):
        """Return the parameter names, in declaration order."""
        return [f.name for f in fields(cls)]


@dataclass
class Scan:
    """
    One planar scan as sensor_msgs/LaserScan holds it, with the sensor's pose on the robot.

    :param ranges: (N,) m; NaN, values below ``range_min`` or above ``range_max`` are
        invalid, ``+inf`` is "no return" (REP 117).
    :param angle_min: rad of ``ranges[0]``; ``angle_increment`` rad between readings.
    :param sensor_pose: ``(x, y, yaw)`` of the scan's frame in the base frame.
    """

    ranges: np.ndarray
    angle_min: float
    angle_increment: float
    range_min: float
    range_max: float
    sensor_pose: tuple = (0.0, 0.0, 0.0)


@dataclass
class Keyframe:
    """
    A processed scan: its odometry pose and its rays in the base frame.

    :param odom: ``(x, y, yaw)`` in the odom frame when the scan was taken.
    :param origin: (2,) m, the sensor in the base frame.
    :param ends: (N, 2) m, the rays' end points in the base frame.
    :param hits: (N,) bool, True where the end point is a return.
    :param stamp: s, the scan's stamp.
    """

    odom: np.ndarray
    origin: np.ndarray
    ends: np.ndarray
    hits: np.ndarray
    stamp: float = 0.0

    @property
    def points(self):
        """Return the returns (M, 2), base frame."""
        return self.ends[self.hits]


def scan_rays(scan, max_laser_range):
    """
    Return ``(origin, ends, hits)`` of a scan in the base frame (see :class:`Keyframe`).

    Readings that are NaN, ``-inf``, below ``range_min`` or (finite and) above ``range_max``
    are dropped; ``+inf`` and readings beyond ``max_laser_range`` become rays of length
    ``min(max_laser_range, range_max)`` with no hit.
    """
    ranges = np.asarray(scan.ranges, dtype=float)
    reach = min(max_laser_range, scan.range_max)
    angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
    valid = (ranges >= scan.range_min) & ((ranges <= scan.range_max) | np.isposinf(ranges))
    valid &= ~np.isnan(ranges)
    hits = valid & (ranges <= reach)
    r = np.where(hits, ranges, reach)[valid]
    a = angles[valid]
    local = np.stack([r * np.cos(a), r * np.sin(a)], axis=1)
    ends = transform_points(local, scan.sensor_pose)
    return np.array(scan.sensor_pose[:2], dtype=float), ends, hits[valid]


def moved_enough(previous, odom_pose, params):
    """
    Return True when the robot moved enough since ``previous`` for a new keyframe.

    :param previous: ``(x, y, yaw)`` odometry pose of the last kept scan (m, rad).
    :param odom_pose: ``(x, y, yaw)`` odometry pose of the new scan.
    :param params: :class:`SlamParameters` (``minimum_travel_distance`` m,
        ``minimum_travel_heading`` rad).
    """
    d = between(previous, odom_pose)
    return (math.hypot(d[0], d[1]) >= params.minimum_travel_distance
            or abs(d[2]) >= params.minimum_travel_heading)


class Mapper:
    """
    The SLAM back end: keyframes, the pose graph and the map (see the module docstring).

    :param params: :class:`SlamParameters`.
    :ivar graph: the :class:`~amr_description.nav.pose_graph.PoseGraph`.
    :ivar keyframes: list of :class:`Keyframe`, one per graph node.
    :ivar loop_closures: number of loop edges added.
    :ivar last_response: response of the last scan match (0..1), or None.
    """

    def __init__(self, params=None):
        """Start with an empty graph."""
        self.params = params or SlamParameters()
        self.graph = PoseGraph()
        self.keyframes = []
        self.loop_closures = 0
        self.last_response = None
        self._session = []  # keyframes of this session (the running buffer's candidates)
        self._traced = {}  # keyframe index -> (keyframe, pose bytes) + trace_cells(...)
        self._restart_pose = None
        self._restart_odom = None

    # --- the pose ---------------------------------------------------------------------------
    def map_to_odom(self):
        """Return the ``(x, y, yaw)`` of the odom frame in the map frame (identity at first)."""
        if not self._session:
            if self._restart_pose is not None and self._restart_odom is not None:
                return compose(self._restart_pose, inverse(self._restart_odom))
            return np.zeros(3)
        k = self._session[-1]
        return compose(self.graph.poses[k], inverse(self.keyframes[k].odom))

    def pose(self, odom_pose):
        """Return the base frame's ``(x, y, yaw)`` in the map frame for an odometry pose."""
        return compose(self.map_to_odom(), np.asarray(odom_pose, dtype=float))

    # --- processing -------------------------------------------------------------------------
    def should_process(self, odom_pose):
        """Return True when a scan taken at ``odom_pose`` would become a keyframe."""
        if not self._session:
            return True
        return moved_enough(self.keyframes[self._session[-1]].odom, odom_pose, self.params)

    def process(self, odom_pose, scan, stamp=0.0):
        """
        Add a scan taken at ``odom_pose`` if the robot moved enough; return True if added.

        :param odom_pose: ``(x, y, yaw)`` of the base frame in the odom frame.
        :param scan: :class:`Scan`.
        :param stamp: s, kept with the keyframe.
        """
        odom_pose = np.asarray(odom_pose, dtype=float)
        if not self.should_process(odom_pose):
            return False
        if self._restart_pose is not None and self._restart_odom is None:
            self._restart_odom = odom_pose  # the first scan after a restart is at its pose
        origin, ends, hits = scan_rays(scan, self.params.max_laser_range)
        frame = Keyframe(odom_pose, origin, ends, hits, stamp)
        prior = self.pose(odom_pose)
        pose, matched, link_to = self._match_local(frame.points, prior)
        index = self.graph.add_node(pose)
        self.keyframes.append(frame)
        if link_to is not None:
            sigma = LINK_SIGMA if matched else ODOM_SIGMA
            self.graph.add_edge(link_to, index, between(self.graph.poses[link_to], pose),
                                1.0 / np.asarray(sigma))
        self._session.append(index)
        self._restart_pose = None
        if self.params.do_loop_closing:
            self._close_loop(index)
        return True

    def _running_buffer(self, prior):
        p = self.params
        if self._session:
            chosen = self._session[-p.scan_buffer_size:]
        else:  # a restart on a loaded graph: the nearest keyframes
            d = np.hypot(*(self.graph.poses[:, :2] - prior[:2]).T) if len(self.graph) else []
            chosen = [int(i) for i in np.argsort(d)[:p.scan_buffer_size]]
        return [k for k in chosen if math.hypot(*(self.graph.poses[k, :2] - prior[:2]))
                <= p.scan_buffer_maximum_scan_distance]

    def _reference(self, indices):
        clouds = [transform_points(self.keyframes[k].points, self.graph.poses[k])
                  for k in indices]
        clouds = [c for c in clouds if len(c)]
        if not clouds:
            return None
        points = np.vstack(clouds)
        return Reference(points) if len(points) >= 3 else None

    def _match_local(self, points, prior):
        """Return ``(pose, matched, node to link to)`` for a new keyframe."""
        p = self.params
        self.last_response = None
        buffer = self._running_buffer(prior)
        link_to = self._session[-1] if self._session else (buffer[0] if buffer else None)
        if not p.use_scan_matching or not buffer or len(points) < 3:
            return prior, False, link_to
        reference = self._reference(buffer)
        if reference is None:
            return prior, False, link_to
        response, pose = self._search(reference, points, prior, 1.0)
        if response < p.link_match_minimum_response_fine:  # slipping wheels: look wider
            response, pose = self._search(reference, points, prior, WIDE_SEARCH)
        self.last_response = response
        if response < p.link_match_minimum_response_fine:
            return prior, False, link_to
        if not self._session:  # restart: link to the nearest keyframe
            near = np.hypot(*(self.graph.poses[buffer, :2] - np.asarray(pose[:2])).T)
            link_to = buffer[int(np.argmin(near))]
        return np.array(pose), True, link_to

    def _search(self, reference, points, prior, widen):
        """Return ``(response, pose)`` of a correlative search ``widen`` times Karto's, + ICP."""
        p = self.params
        step = max(p.correlation_search_space_resolution, p.resolution) * widen
        pose, _ = correlative_search(
            reference, points, prior, widen * p.correlation_search_space_dimension / 2.0, step,
            p.coarse_search_angle_offset, p.coarse_angle_resolution,
            max(p.correlation_search_space_smear_deviation, step))
        pose = icp(reference, points, pose)
        return reference.response(points, pose, p.correlation_search_space_smear_deviation), pose

    def _close_loop(self, index):
        p = self.params
        pose = self.graph.poses[index]
        old = index - p.loop_match_minimum_chain_size
        if old <= 0:
            return False
        d = np.hypot(*(self.graph.poses[:old, :2] - pose[:2]).T)
        candidates = [int(k) for k in np.nonzero(d <= p.loop_search_maximum_distance)[0]]
        if len(candidates) < 2:
            return False
        reference = self._reference(candidates)
        points = self.keyframes[index].points
        if reference is None or len(points) < 3:
            return False
        half = p.loop_search_space_dimension / 2.0
        step = max(p.loop_search_space_resolution, half / 20.0)
        surface = []
        coarse, best = correlative_search(
            reference, points, pose, half, step, p.coarse_search_angle_offset,
            p.coarse_angle_resolution, max(p.loop_search_space_smear_deviation, step), surface)
        coarse_response = reference.response(points, coarse, max(step, 0.05))
        if coarse_response < p.loop_match_minimum_response_coarse:
            return False
        variance = positional_variance(surface[0], np.subtract(coarse[:2], pose[:2]), step,
                                       best)
        if max(variance) >= p.loop_match_maximum_variance_coarse:
            return False  # a look-alike place in the window scores nearly as well
        fine = np.array(icp(reference, points, coarse))
        if reference.response(points, fine, max(p.loop_search_space_smear_deviation, 0.03)) \
                < p.loop_match_minimum_response_fine:
            return False
        near = candidates[int(np.argmin(np.hypot(
            *(self.graph.poses[candidates, :2] - fine[:2]).T)))]
        correction = between(pose, fine)
        travelled = np.sum(np.hypot(*np.diff(self.graph.poses[near:index + 1, :2], axis=0).T))
        if (math.hypot(correction[0], correction[1]) > LOOP_DRIFT[0] + LOOP_DRIFT[1] * travelled
                or abs(correction[2]) > p.coarse_search_angle_offset):
            return False  # more than drift explains: a look-alike place
        self.graph.add_edge(near, index, between(self.graph.poses[near], fine),
                            1.0 / np.asarray(LINK_SIGMA), kind='loop')
        self.graph.optimize()
        self.loop_closures += 1
        return True

    # --- restart on a loaded graph ----------------------------------------------------------
    def restart_at(self, pose, odom_pose=None):
        """
        Continue a loaded graph with the robot at map pose ``pose``.

        The next scan is matched near ``pose`` against the nearest keyframes and linked to
        the nearest one (slam_toolbox's ``deserialize_map`` with ``START_AT_GIVEN_POSE``, or
        ``START_AT_FIRST_NODE`` with node 0's pose).

        :param pose: ``(x, y, yaw)`` in the map frame.
        :param odom_pose: the odometry pose now, if known (the map -> odom transform places it
            at ``pose``); else the next scan's odometry pose is taken as being at ``pose``.
        """
        self._session = []
        self._restart_pose = np.asarray(pose, dtype=float)
        self._restart_odom = None if odom_pose is None else np.asarray(odom_pose, dtype=float)

    # --- the map ----------------------------------------------------------------------------
    def occupancy(self):
        """
        Return the :class:`~amr_description.nav.map_io.GridMap` of every keyframe, or None.

        The grid covers every ray (cell (0, 0)'s corner on a multiple of the resolution);
        values -1 / 0 / 100 as slam_toolbox publishes. Like slam_toolbox's, the grid is made
        again from every keyframe's rays each time; a keyframe's cells are traced once per
        pose of it (kept until the graph moves it).
        """
        if not self.keyframes:
            return None
        res = self.params.resolution
        cache = {}
        for i, (frame, pose) in enumerate(zip(self.keyframes, self.graph.poses)):
            at = np.asarray(pose, dtype=float).tobytes()
            traced = self._traced.get(i)
            if traced is None or traced[0] is not frame or traced[1] != at:
                traced = (frame, at) + trace_cells(frame, pose, res)
            cache[i] = traced
        self._traced = cache
        lo_cell = np.min([t[2] for t in cache.values()], axis=0) - 1
        hi = np.max([t[3] for t in cache.values()], axis=0) + 2 * res
        lo = lo_cell * res
        width, height = (int(v) for v in np.ceil((hi - lo) / res))
        size = width * height

        def counts(column):
            cells = np.concatenate([t[column] for t in cache.values()]).astype(np.int64)
            flat = (cells[:, 1] - lo_cell[1]) * width + (cells[:, 0] - lo_cell[0])
            return np.bincount(flat, minlength=size)

        passes, hit_count = counts(4), counts(5)
        data = np.full(size, -1, dtype=np.int8)
        seen = passes > self.params.min_pass_through
        ratio = np.divide(hit_count, passes, out=np.zeros(size), where=passes > 0)
        data[seen] = np.where(ratio[seen] > self.params.occupancy_threshold, 100, 0)
        return GridMap(data.reshape(height, width), res, (float(lo[0]), float(lo[1]), 0.0))


def trace_cells(frame, pose, res):
    """
    Return the cells of one keyframe's rays at ``pose``, on the grid of cells ``res`` wide.

    A ray passes each cell it crosses once; a ray that hit something ends in a hit. Cells are
    integer ``(column, row)`` pairs counted from the map frame's origin (``floor(x / res)``).

    :param frame: a :class:`Keyframe`.
    :param pose: ``(x, y, yaw)`` of the keyframe in the map frame.
    :param res: m per cell.
    :returns: ``(low, high, pass_cells, hit_cells)``: the lowest cell (2,) int, the highest
        point (2,) m, a cell (N, 2) int32 per ray and cell it passes, one (M, 2) per hit.
    """
    origin = transform_points(frame.origin[None], pose)[0]
    ends = transform_points(frame.ends, pose)
    every = np.vstack([ends, origin[None]])
    low = np.floor(every.min(axis=0) / res).astype(np.int64)
    high = every.max(axis=0)
    if len(ends) == 0:
        return low, high, np.zeros((0, 2), np.int32), np.zeros((0, 2), np.int32)
    delta = ends - origin
    length = np.hypot(delta[:, 0], delta[:, 1])
    samples = int(np.ceil(length.max() / (0.5 * res))) + 1
    t = np.linspace(0.0, 1.0, samples)
    cells = np.floor((origin + delta[:, None, :] * t[None, :, None]) / res).astype(np.int32)
    first = np.ones(cells.shape[:2], dtype=bool)
    first[:, 1:] = (cells[:, 1:] != cells[:, :-1]).any(axis=2)
    hit_cells = np.floor(ends[frame.hits] / res).astype(np.int32)
    return low, high, cells[first], hit_cells


def save_graph(mapper, stem):
    """
    Write ``<stem>.posegraph`` (nodes and edges) and ``<stem>.data`` (the keyframes' rays).

    Both are numpy ``.npz`` archives under slam_toolbox's file names (its own are boost
    archives of Karto objects, readable by nothing else either).

    :raises OSError: when a file cannot be written.
    """
    edges = mapper.graph.edges
    with open(stem + '.posegraph', 'wb') as f:
        np.savez(f, poses=mapper.graph.poses,
                 ij=np.array([(e[0], e[1]) for e in edges], dtype=np.int64).reshape(-1, 2),
                 z=np.array([e[2] for e in edges]).reshape(-1, 3),
                 w=np.array([e[3] for e in edges]).reshape(-1, 3),
                 loop=np.array([e[4] == 'loop' for e in edges], dtype=bool),
                 resolution=mapper.params.resolution)
    frames = mapper.keyframes
    with open(stem + '.data', 'wb') as f:
        np.savez(f, odom=np.array([k.odom for k in frames]).reshape(-1, 3),
                 origin=np.array([k.origin for k in frames]).reshape(-1, 2),
                 counts=np.array([len(k.ends) for k in frames], dtype=np.int64),
                 ends=np.vstack([k.ends for k in frames] or [np.zeros((0, 2))]),
                 hits=np.concatenate([k.hits for k in frames] or [np.zeros(0, bool)]),
                 stamps=np.array([k.stamp for k in frames]))


def load_graph(stem, params=None):
    """
    Return a :class:`Mapper` holding the graph written by :func:`save_graph` at ``stem``.

    :raises ValueError: one line naming the file, when it is missing or not such a graph.
    """
    mapper = Mapper(params)
    try:
        with np.load(stem + '.posegraph') as g, np.load(stem + '.data') as d:
            mapper.graph.poses = np.array(g['poses'], dtype=float).reshape(-1, 3)
            for (i, j), z, w, loop in zip(g['ij'], g['z'], g['w'], g['loop']):
                mapper.graph.add_edge(int(i), int(j), z, w, 'loop' if loop else 'link')
            bounds = np.concatenate([[0], np.cumsum(d['counts'])])
            for k in range(len(d['odom'])):
                part = slice(bounds[k], bounds[k + 1])
                mapper.keyframes.append(Keyframe(
                    np.array(d['odom'][k]), np.array(d['origin'][k]), np.array(d['ends'][part]),
                    np.array(d['hits'][part]), float(d['stamps'][k])))
    except (OSError, KeyError, ValueError, IndexError) as exc:
        raise ValueError(f'{stem}.posegraph / {stem}.data: not a pose graph this node wrote '
                         f'({exc})') from None
    if len(mapper.keyframes) != len(mapper.graph):
        raise ValueError(f'{stem}.data: {len(mapper.keyframes)} scans for '
                         f'{len(mapper.graph)} graph nodes')
    mapper.loop_closures = sum(1 for e in mapper.graph.edges if e[4] == 'loop')
    return mapper
