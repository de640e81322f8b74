# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""slam_toolbox's localization mode on a saved graph: the room of test_slam_engine."""

import math

from amr_description.nav import pose_graph
from amr_description.nav import slam
from amr_description.nav.slam_localization import Localizer
import numpy as np
import pytest
from test_slam_engine import _drive  # noqa: I100 - the SLAM tests' room and drive
from test_slam_engine import _loop
from test_slam_engine import scan_at


@pytest.fixture(scope='module')
def saved(tmp_path_factory):
    """Save a graph of the room's loop's first side (map frame = its first pose)."""
    mapper = slam.Mapper()
    truth = _loop()[:120]  # the first side, (0, -1) to (4, -1), and the turn at its end
    _drive(mapper, truth, odom_scale=(1.0, 1.0))
    stem = str(tmp_path_factory.mktemp('graph') / 'room')
    slam.save_graph(mapper, stem)
    return stem, truth


def _in_map(truth, pose):
    """Return ``pose`` (room frame) in the map frame, whose origin is the loop's start."""
    return pose_graph.between(truth[0], pose)


def test_localizes_near_a_given_pose_and_keeps_the_map(saved):
    stem, truth = saved
    loc = Localizer.from_mapper(slam.load_graph(stem))
    nodes, edges = len(loc.graph), len(loc.graph.edges)
    grid = loc.occupancy().data.copy()
    true_pose = _in_map(truth, (3.0, -1.0, 0.0))
    # the "2D Pose Estimate" 0.3 m and 10 deg off; the odometry starts at zero there
    loc.localize_at(true_pose + (0.2, -0.22, math.radians(10.0)))
    assert loc.process(np.zeros(3), scan_at((3.0, -1.0, 0.0)))
    error = pose_graph.between(true_pose, loc.pose(np.zeros(3)))
    assert math.hypot(error[0], error[1]) < 0.03 and abs(error[2]) < math.radians(1.0)
    # driving on with odometry 5 % long: each processed scan is matched to the map again
    odom = np.zeros(3)
    for x in np.arange(3.05, 4.0, 0.05):
        odom = odom + (0.05 * 1.05, 0.0, 0.0)
        loc.process(odom, scan_at((x, -1.0, 0.0)))
    error = pose_graph.between(_in_map(truth, (x, -1.0, 0.0)), loc.pose(odom))
    assert math.hypot(error[0], error[1]) < 0.03, error
    assert loc.localized == 3 and loc.matched == 3  # the start, then every 0.5 m of odometry
    # the graph and the map are as loaded
    assert (len(loc.graph), len(loc.graph.edges)) == (nodes, edges)
    assert np.array_equal(loc.occupancy().data, grid)


def test_without_a_match_the_odometry_carries_the_pose(saved):
    stem, truth = saved
    loc = Localizer.from_mapper(slam.load_graph(stem))
    start = _in_map(truth, (1.0, -1.0, 0.0))
    loc.localize_at(start)
    far = slam.Scan(np.full(360, np.inf), -math.pi, 2 * math.pi / 360, 0.1, 12.0)
    assert loc.process(np.zeros(3), far)  # nothing seen: the given pose is kept
    assert loc.matched == 0
    assert np.allclose(loc.pose((0.4, 0.0, 0.0)), pose_graph.compose(start, (0.4, 0.0, 0.0)))
    assert not loc.process((0.4, 0.0, 0.0), far)  # 0.4 m: below minimum_travel_distance


def test_no_graph_no_localization():
    loc = Localizer()
    assert not loc.process(np.zeros(3), scan_at((0.0, -1.0, 0.0)))
    assert np.array_equal(loc.map_to_odom(), np.zeros(3))
