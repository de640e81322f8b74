# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
slam_toolbox's localization mode on a saved pose graph (``localization_slam_toolbox_node``).

:class:`Localizer` is a :class:`~amr_description.nav.slam.Mapper` whose graph and map stay as
they were loaded: each processed scan (the mapper's travel rule, ``minimum_travel_distance`` or
``minimum_travel_heading`` since the last one) is matched against the map's nearest keyframes
(up to ``scan_buffer_size`` within ``scan_buffer_maximum_scan_distance`` of the predicted pose)
and sets the ``map -> odom`` transform; between scans the pose follows the odometry. A pose to
localize near (slam_toolbox's ``/initialpose`` and ``map_start_pose``, its
``PROCESS_NEAR_REGION``) makes the next scan processed at once and searched for in a window
:data:`~amr_description.nav.slam.WIDE_SEARCH` times the mapper's. A match whose response stays
below ``link_match_minimum_response_fine`` leaves the predicted pose (odometry alone).

slam_toolbox adds each localized scan to the graph for a while (a rolling buffer of
``scan_buffer_size`` scans, then removed); here the scans are matched against the map's own
keyframes and never added, so the map and the graph do not change.
"""

import math

from amr_description.nav.pose_graph import between
from amr_description.nav.pose_graph import compose
from amr_description.nav.pose_graph import inverse
from amr_description.nav.slam import Keyframe
from amr_description.nav.slam import Mapper
from amr_description.nav.slam import scan_rays
from amr_description.nav.slam import WIDE_SEARCH
import numpy as np


class Localizer(Mapper):
    """
    Localization on a loaded graph (module docstring).

    :param params: :class:`~amr_description.nav.slam.SlamParameters`.
    :ivar localized: scans localized so far (matched or not).
    :ivar matched: scans whose match was kept.
    """

    def __init__(self, params=None):
        """Start with no graph, no pose."""
        super().__init__(params)
        self._map_to_odom = None
        self._odom = None  # odometry pose of the last processed scan
        self._near = None  # the next scan is localized near this map pose
        self.localized = self.matched = 0

    @classmethod
    def from_mapper(cls, mapper):
        """Return a Localizer on ``mapper``'s graph and keyframes (a loaded graph)."""
        loc = cls(mapper.params)
        loc.graph, loc.keyframes, loc.loop_closures = (mapper.graph, mapper.keyframes,
                                                       mapper.loop_closures)
        return loc

    def localize_at(self, pose):
        """Localize the next scan near map pose ``(x, y, yaw)`` (``/initialpose``)."""
        self._near = np.asarray(pose, dtype=float)

    def map_to_odom(self):
        """Return ``(x, y, yaw)`` of the odom frame in the map frame (identity before a scan)."""
        return np.zeros(3) if self._map_to_odom is None else self._map_to_odom

    def should_process(self, odom_pose):
        """Return True when a scan at ``odom_pose`` would be localized."""
        if self._near is not None or self._odom is None:
            return True
        d = between(self._odom, odom_pose)
        p = self.params
        return (math.hypot(d[0], d[1]) >= p.minimum_travel_distance
                or abs(d[2]) >= p.minimum_travel_heading)

    def process(self, odom_pose, scan, stamp=0.0):
        """
        Localize a scan taken at ``odom_pose``; return True when it was processed.

        Nothing happens without a graph, or when the robot has not moved enough.

        :param odom_pose: ``(x, y, yaw)`` of the base frame in the odom frame.
        :param scan: :class:`~amr_description.nav.slam.Scan`.
        :param stamp: s (unused; the mapper's signature).
        """
        odom_pose = np.asarray(odom_pose, dtype=float)
        if not self.keyframes or not self.should_process(odom_pose):
            return False
        near = self._near
        prior = near if near is not None else self.pose(odom_pose)
        origin, ends, hits = scan_rays(scan, self.params.max_laser_range)
        points = Keyframe(odom_pose, origin, ends, hits, stamp).points
        pose = self._match_map(points, prior, WIDE_SEARCH if near is not None else 1.0)
        self.localized += 1
        if pose is None:
            pose = prior
        else:
            self.matched += 1
        self._map_to_odom = compose(pose, inverse(odom_pose))
        self._odom = odom_pose
        self._near = None
        return True

    def _match_map(self, points, prior, widen):
        """Return the pose matched against the map's keyframes near ``prior``, or None."""
        p = self.params
        self.last_response = None
        d = np.hypot(*(self.graph.poses[:, :2] - prior[:2]).T)
        nearest = [int(k) for k in np.argsort(d)[:p.scan_buffer_size]
                   if d[k] <= p.scan_buffer_maximum_scan_distance]
        reference = self._reference(nearest) if nearest and len(points) >= 3 else None
        if reference is None or not p.use_scan_matching:
            return None
        response, pose = self._search(reference, points, prior, widen)
        if response < p.link_match_minimum_response_fine and widen == 1.0:
            response, pose = self._search(reference, points, prior, WIDE_SEARCH)
        self.last_response = response
        return np.array(pose) if response >= p.link_match_minimum_response_fine else None
