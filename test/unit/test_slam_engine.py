# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The SLAM engine against closed forms: pose graph, scan matching, rays, mapping, files.

Scans are cast analytically in a 6 x 4 m room with a 0.4 m box (ray against segment), so the
true pose of every scan and the true walls are known exactly.
"""

import math

from amr_description.nav import pose_graph
from amr_description.nav import slam
from amr_description.nav.scan_matcher import correlative_search
from amr_description.nav.scan_matcher import icp
from amr_description.nav.scan_matcher import positional_variance
from amr_description.nav.scan_matcher import Reference
from amr_description.nav.scan_matcher import transform_points
import numpy as np
import pytest

ROOM = [((-1, -2), (5, -2)), ((5, -2), (5, 2)), ((5, 2), (-1, 2)), ((-1, 2), (-1, -2)),
        ((2.0, 0.6), (2.4, 0.6)), ((2.4, 0.6), (2.4, 1.0)), ((2.4, 1.0), (2.0, 1.0)),
        ((2.0, 1.0), (2.0, 0.6))]
"""Wall segments (m): the room and a box in it."""

N = 360
ANGLE_MIN = -math.pi
INCREMENT = 2 * math.pi / N


def cast(pose):
    """Return the N ranges (m) of a lidar at ``pose`` (x, y, yaw) in :data:`ROOM`."""
    angles = pose[2] + ANGLE_MIN + INCREMENT * np.arange(N)
    d = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    best = np.full(N, np.inf)
    o = np.array(pose[:2])
    for a, b in ROOM:
        a, b = np.array(a, float), np.array(b, float)
        e = b - a
        den = d[:, 0] * (-e[1]) - d[:, 1] * (-e[0])
        with np.errstate(divide='ignore', invalid='ignore'):
            w = a - o
            t = (w[0] * (-e[1]) - w[1] * (-e[0])) / den
            s = (d[:, 0] * w[1] - d[:, 1] * w[0]) / den
        hit = (np.abs(den) > 1e-12) & (t > 0) & (s >= 0) & (s <= 1)
        best = np.where(hit & (t < best), t, best)
    return best


def scan_at(pose):
    return slam.Scan(cast(pose), ANGLE_MIN, INCREMENT, 0.1, 12.0)


def test_between_and_compose_are_inverse():
    a, b = np.array([1.0, -2.0, 0.7]), np.array([0.3, 0.4, -2.9])
    assert np.allclose(pose_graph.compose(a, pose_graph.between(a, b)), b)
    assert np.allclose(pose_graph.between(a, a), 0.0)
    # b seen from a: a at (1, 0) facing +y, b at (1, 1) facing +y -> (1, 0, 0)
    assert np.allclose(pose_graph.between([1, 0, math.pi / 2], [1, 1, math.pi / 2]), [1, 0, 0])


def test_pose_graph_square_with_a_loop_edge_is_restored():
    truth = np.array([[0, 0, 0], [2, 0, math.pi / 2], [2, 2, math.pi], [0, 2, -math.pi / 2]])
    graph = pose_graph.PoseGraph()
    rng = np.random.default_rng(1)
    for k, pose in enumerate(truth):
        graph.add_node(pose + (rng.normal(0, 0.2, 3) if k else 0))
    for i, j in ((0, 1), (1, 2), (2, 3), (3, 0)):
        graph.add_edge(i, j, pose_graph.between(truth[i], truth[j]), (10, 10, 20),
                       kind='loop' if j == 0 else 'link')
    assert graph.residuals().dot(graph.residuals()) > 1.0
    cost = graph.optimize()
    assert cost < 1e-12
    assert np.allclose(graph.poses, truth, atol=1e-6)
    with pytest.raises(IndexError):
        graph.add_edge(0, 9, (0, 0, 0), (1, 1, 1))


def test_scan_matcher_recovers_a_known_offset():
    true_pose = (0.5, -0.3, 0.2)
    reference = Reference(transform_points(slam.scan_rays(scan_at((0, 0, 0)), 25)[1], (0, 0, 0)))
    _, ends, hits = slam.scan_rays(scan_at(true_pose), 25.0)
    points = ends[hits]
    prior = (0.62, -0.38, 0.33)  # 14 cm and 7.4 deg off
    coarse, score = correlative_search(reference, points, prior, 0.25, 0.05, 0.349, 0.0349, 0.1)
    assert score > 0.5
    refined = icp(reference, points, coarse)
    assert np.allclose(refined[:2], true_pose[:2], atol=0.005)
    assert abs(refined[2] - true_pose[2]) < 0.002
    assert reference.response(points, refined, 0.03) > 0.9
    assert reference.response(points, prior, 0.03) < 0.3


def test_positional_variance_closed_forms():
    res = 0.2
    one = np.zeros((5, 5))
    one[2, 2] = 0.5  # a single peak at the centre: the floor 0.1 res^2, over the response
    assert positional_variance(one, (0.0, 0.0), res, 0.5) == pytest.approx(
        (0.1 * res ** 2 / 0.5, 0.1 * res ** 2 / 0.5))
    two = one.copy()
    two[4, 2] = 0.45  # a look-alike 0.4 m along x within 0.1 of the best
    var_xx, var_yy = positional_variance(two, (0.0, 0.0), res, 0.5)
    assert var_xx == pytest.approx(0.4 ** 2 * 0.45 / 0.95 / 0.5)
    assert var_yy == pytest.approx(0.1 * res ** 2 / 0.5)
    two[4, 2] = 0.39  # more than 0.1 below the best: not counted
    assert positional_variance(two, (0.0, 0.0), res, 0.5)[0] == pytest.approx(0.008)
    assert positional_variance(one, (0.0, 0.0), res, 0.0) == (500.0, 500.0)  # Karto's max


def test_a_row_of_look_alike_pillars_has_a_large_coarse_variance():
    # pillars (0.2 m squares) every 2 m along x: a scan among them fits as well 2 m further
    pillars = np.vstack([np.array([(x + dx, y) for dx in np.linspace(-0.1, 0.1, 5)]
                                  + [(x, y + dy) for dy in np.linspace(-0.1, 0.1, 5)])
                         for x in np.arange(-10.0, 10.1, 2.0) for y in (-1.0, 1.0)])
    reference = Reference(pillars)
    near = pillars[np.abs(pillars[:, 0]) < 3.5]
    surface = []
    pose, score = correlative_search(reference, near, (0.0, 0.0, 0.0), 4.0, 0.2, 0.0, 0.1,
                                     0.2, surface)
    assert surface[0].shape == (41, 41) and surface[0].max() == pytest.approx(score)
    var_xx, var_yy = positional_variance(surface[0], pose[:2], 0.2, score)
    assert var_xx > 3.0 > var_yy  # refused by slam_toolbox's loop_match_maximum_variance_coarse
    # a room's scan has one best place
    points = slam.scan_rays(scan_at((1.0, 0.0, 0.0)), 25.0)[1]
    room = Reference(transform_points(points, (1.0, 0.0, 0.0)))
    surface = []
    pose, score = correlative_search(room, points, (1.3, 0.2, 0.0), 4.0, 0.2, 0.0, 0.1, 0.2,
                                     surface)
    assert max(positional_variance(surface[0], np.subtract(pose[:2], (1.3, 0.2)), 0.2,
                                   score)) < 0.05


def test_scan_rays_drop_bad_readings_and_clip_no_returns():
    scan = slam.Scan(np.array([1.0, np.nan, -1.0, 0.05, 30.0, np.inf, 8.0]), 0.0, 0.1, 0.1, 20.0,
                     sensor_pose=(0.1, 0.0, 0.0))
    origin, ends, hits = slam.scan_rays(scan, 5.0)
    assert np.allclose(origin, (0.1, 0.0))
    # kept: 1.0 (hit), +inf (no return, 5 m), 8.0 (beyond max_laser_range: 5 m, no hit)
    assert hits.tolist() == [True, False, False]
    assert np.allclose(np.hypot(*(ends - origin).T), [1.0, 5.0, 5.0])


def _drive(mapper, truth, odom_scale=(1.03, 1.03 / 0.9)):
    """Feed scans along ``truth`` with odometry scaled wrongly; return pose errors."""
    odom = np.zeros(3)
    errors = []
    for k, pose in enumerate(truth):
        if k:
            step = pose_graph.between(truth[k - 1], pose)
            odom = pose_graph.compose(odom, (step[0] * odom_scale[0], step[1] * odom_scale[0],
                                             step[2] * odom_scale[1]))
        mapper.process(odom, scan_at(pose), k * 0.1)
        estimate = mapper.pose(odom)
        diff = pose_graph.between(pose_graph.between(truth[0], pose), estimate)
        errors.append((math.hypot(diff[0], diff[1]), abs(diff[2])))
    return np.array(errors), odom


def _loop():
    """Return the poses of a 4 x 2.5 m rectangle round the box, twice (0.05 m, 0.08 rad steps)."""
    poses = []
    corners = [(0, -1), (4, -1), (4, 1.5), (0.5, 1.5)] * 2 + [(0, -1)]
    yaw = 0.0
    for (ax, ay), (bx, by) in zip(corners, corners[1:]):
        heading = math.atan2(by - ay, bx - ax)
        while abs(math.remainder(heading - yaw, math.tau)) > 0.08:
            yaw += math.copysign(0.08, math.remainder(heading - yaw, math.tau))
            poses.append((ax, ay, yaw))
        yaw = heading
        n = int(math.hypot(bx - ax, by - ay) / 0.05)
        poses += [(ax + (bx - ax) * f, ay + (by - ay) * f, yaw) for f in np.arange(n) / n]
    return np.array(poses)


def test_mapper_corrects_wrong_odometry_and_maps_the_room(tmp_path):
    truth = _loop()
    mapper = slam.Mapper()
    errors, odom = _drive(mapper, truth)
    odom_end = pose_graph.between(pose_graph.between(truth[0], truth[-1]), odom)
    assert math.hypot(odom_end[0], odom_end[1]) > 0.3  # odometry alone is lost
    assert np.sqrt(np.mean(errors[:, 0] ** 2)) < 0.02
    assert np.sqrt(np.mean(errors[:, 1] ** 2)) < math.radians(2.0)
    grid = mapper.occupancy()
    res = grid.resolution

    def cell(x, y):  # map frame == the start pose (0, -1, 0)
        col = int((x - 0 - grid.origin[0]) // res)
        row = int((y + 1 - grid.origin[1]) // res)
        return grid.data[row, col]
    assert cell(4.99, 0.0) == 100 and cell(2.2, 0.61) == 100  # a wall, the box's face
    assert cell(1.0, 0.0) == 0 and cell(3.0, -1.5) == 0  # free floor
    assert cell(2.2, 0.8) == -1  # inside the box: never seen
    # save and load: the same graph and map
    slam.save_graph(mapper, str(tmp_path / 'room'))
    loaded = slam.load_graph(str(tmp_path / 'room'))
    assert np.allclose(loaded.graph.poses, mapper.graph.poses)
    assert len(loaded.graph.edges) == len(mapper.graph.edges)
    assert np.array_equal(loaded.occupancy().data, grid.data)


def test_restart_on_a_loaded_graph_continues_the_map(tmp_path):
    truth = _loop()[:200]
    mapper = slam.Mapper()
    _drive(mapper, truth)
    slam.save_graph(mapper, str(tmp_path / 'g'))
    loaded = slam.load_graph(str(tmp_path / 'g'))
    nodes = len(loaded.graph)
    # a new session starting at a known map pose, its odometry starting from zero
    start = pose_graph.between(truth[0], truth[50])
    loaded.restart_at(start)
    assert loaded.process(np.zeros(3), scan_at(truth[50]))
    assert len(loaded.graph) == nodes + 1
    assert np.allclose(loaded.graph.poses[-1][:2], start[:2], atol=0.02)
    assert loaded.graph.edges[-1][0] != nodes - 1 or nodes == 1  # linked to a near node


def test_load_graph_names_the_file(tmp_path):
    (tmp_path / 'x.posegraph').write_text('not a graph')
    with pytest.raises(ValueError, match=r'x\.posegraph / .*x\.data: not a pose graph'):
        slam.load_graph(str(tmp_path / 'x'))


def test_occupancy_counts_passes_and_hits_and_follows_a_moved_keyframe():
    # one ray 1 m along +x from the sensor, ending in a return; min_pass_through 2 needs three
    # keyframes' passes before a cell counts as seen
    mapper = slam.Mapper()
    ray = slam.Keyframe(np.zeros(3), np.zeros(2), np.array([[1.0, 0.0]]), np.array([True]))
    for _ in range(3):
        mapper.keyframes.append(ray)
        mapper.graph.add_node((0.0, 0.01, 0.0))
    grid = mapper.occupancy()
    res = grid.resolution

    def at(x, y):
        return grid.data[int((y - grid.origin[1]) // res), int((x - grid.origin[0]) // res)]
    assert at(0.5, 0.01) == 0 and at(1.01, 0.01) == 100  # free along the ray, its end hit
    assert at(0.5, -0.02) == -1  # the margin row below the ray: never passed
    # the graph moves every keyframe 0.5 m up: the grid follows (the cached rays are redone)
    mapper.graph.poses[:, 1] += 0.5
    grid = mapper.occupancy()
    assert at(0.5, 0.51) == 0 and at(1.01, 0.51) == 100
    assert grid.origin[1] == pytest.approx(0.45)  # a cell below the lowest ray, as before
