# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The viewer's navigation displays and pose tool: what they draw, against closed forms."""

import math

from amr_description.web.displays.map import grid_picture
from amr_description.web.displays.map import grid_placement
from amr_description.web.displays.map import palette
from amr_description.web.displays.map import scheme_of
from amr_description.web.displays.particle_cloud import flat_arrows
from amr_description.web.displays.particle_cloud import particle_lengths
from amr_description.web.displays.particle_cloud import pose_arrays
from amr_description.web.displays.pose_covariance import covariance_ellipse
from amr_description.web.displays.pose_covariance import ellipse_mesh
from amr_description.web.displays.pose_covariance import yaw_wedge
from amr_description.web.displays.pose_tool import goal_pose_message
from amr_description.web.displays.pose_tool import ground_point
from amr_description.web.displays.pose_tool import initial_pose_message
from amr_description.web.displays.pose_tool import pose_from_drag
from builtin_interfaces.msg import Time
from geometry_msgs.msg import Pose
from nav_msgs.msg import OccupancyGrid
import numpy as np
import pytest


def test_palettes_are_rvizs():
    m = palette('map')
    assert m[0].tolist() == [255, 255, 255, 255] and m[100].tolist() == [0, 0, 0, 255]
    assert m[50].tolist() == [128, 128, 128, 255]  # 255 - 255 * 50 // 100
    assert m[255].tolist() == [0x70, 0x89, 0x86, 255]  # -1, unknown
    assert m[120].tolist() == [0, 255, 0, 255]  # 101..127 are not occupancy
    assert m[128].tolist() == [255, 0, 0, 255] and m[254].tolist() == [255, 255, 0, 255]
    c = palette('costmap')
    assert c[0][3] == 0  # free space is transparent
    assert c[1].tolist() == [2, 0, 253, 255] and c[98].tolist() == [249, 0, 6, 255]
    assert c[99].tolist() == [0, 255, 255, 255] and c[100].tolist() == [255, 0, 255, 255]
    assert c[255].tolist() == m[255].tolist()
    with pytest.raises(ValueError, match="unknown colour scheme 'raw2'"):
        palette('raw2')
    assert scheme_of('/global_costmap/costmap') == 'costmap' and scheme_of('/map') == 'map'


def _grid(width, height, data, resolution=0.5, x=0.0, y=0.0, yaw=0.0):
    msg = OccupancyGrid()
    msg.info.width, msg.info.height, msg.info.resolution = width, height, resolution
    msg.info.origin.position.x, msg.info.origin.position.y = x, y
    msg.info.origin.orientation.z = math.sin(yaw / 2)
    msg.info.origin.orientation.w = math.cos(yaw / 2)
    msg.data = data
    return msg


def test_the_picture_keeps_the_grids_rows_and_applies_rvizs_alpha():
    msg = _grid(3, 2, [100, 0, -1, 0, 0, 0])  # cell (0, 0) occupied, (2, 0) unknown
    picture = grid_picture(msg, 'map')
    assert picture.shape == (2, 3, 4)
    assert picture[0, 0].tolist() == [0, 0, 0, 178]  # 255 * 0.7
    assert picture[0, 2, :3].tolist() == [0x70, 0x89, 0x86]
    assert picture[1].tolist() == [[255, 255, 255, 178]] * 3
    with pytest.raises(ValueError, match='5 cells for a 3 x 2 grid'):
        grid_picture(_grid(3, 2, [0] * 5), 'map')


def test_the_picture_lies_on_its_cells_from_a_turned_origin_in_a_moved_frame():
    msg = _grid(4, 2, [0] * 8, resolution=0.5, x=1.0, y=2.0, yaw=math.pi / 2)
    T = np.eye(4)
    T[:3, 3] = (10.0, 0.0, 0.0)
    position, wxyz, size = grid_placement(msg.info, T, height=0.0)
    assert size == (2.0, 1.0)
    # 2 m along the origin's x (world +y) and 1 m along its y (world -x), halved
    assert position == pytest.approx([10.0 + 1.0 - 0.5, 2.0 + 1.0, 0.0])
    assert wxyz == pytest.approx([math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)])


def test_flat_arrows_and_particle_lengths_are_nav2s():
    pose = Pose()
    pose.position.x, pose.position.y = 1.0, 2.0
    pose.orientation.z, pose.orientation.w = math.sin(math.pi / 4), math.cos(math.pi / 4)
    positions, rotations = pose_arrays([pose, Pose()])  # an unset orientation faces +x
    segments = flat_arrows(positions, rotations, [0.2, 0.1])
    assert segments.shape == (6, 2, 3)
    assert segments[0] == pytest.approx(np.array([[1, 2, 0], [1, 2.2, 0]]), abs=1e-6)  # +y
    assert segments[1][1] == pytest.approx([1.0 - 0.04, 2.15, 0.0], abs=1e-6)  # 0.75, 0.2
    assert segments[3] == pytest.approx(np.array([[0, 0, 0], [0.1, 0, 0]]), abs=1e-6)
    assert particle_lengths([0.0, 0.5, 1.0, 2.0]) == pytest.approx([0.02, 0.16, 0.3, 0.3])
    pose.position.x = math.nan
    with pytest.raises(ValueError, match='not finite'):
        pose_arrays([pose])


def test_the_covariance_ellipse_has_one_standard_deviation_along_its_axes():
    cov = np.zeros(36)
    cov[0], cov[7] = 0.04, 0.25  # sigma x 0.2 m, sigma y 0.5 m
    radii, angle = covariance_ellipse(cov)
    assert sorted(radii) == pytest.approx([0.2, 0.5])
    axis = np.array([math.cos(angle), math.sin(angle)])
    assert abs(axis @ [1.0, 0.0]) == pytest.approx(1.0 if radii[0] < 0.3 else 0.0, abs=1e-9)
    # turned 30 deg: [[a, b], [b, c]] of the same ellipse
    t = math.radians(30.0)
    R = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    C = R @ np.diag([0.04, 0.25]) @ R.T
    cov[0], cov[1], cov[6], cov[7] = C[0, 0], C[0, 1], C[1, 0], C[1, 1]
    radii, angle = covariance_ellipse(cov)
    big = angle if radii[0] > radii[1] else angle + math.pi / 2
    assert math.remainder(big - (t + math.pi / 2), math.pi) == pytest.approx(0.0, abs=1e-9)
    cov[0] = -1.0
    assert covariance_ellipse(cov) is None  # not positive semidefinite: not drawn
    vertices, faces = ellipse_mesh((1.0, 2.0, 0.0), (0.2, 0.5), 0.0, segments=4)
    assert vertices[1:] == pytest.approx(np.array(
        [[1.2, 2.0, 0.0], [1.0, 2.5, 0.0], [0.8, 2.0, 0.0], [1.0, 1.5, 0.0]]), abs=1e-6)
    assert faces.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]
    vertices, _ = yaw_wedge((0.0, 0.0, 0.0), 0.0, math.radians(10.0), segments=2)
    assert vertices[1][:2] == pytest.approx([math.cos(math.radians(-10)),
                                             math.sin(math.radians(-10))], abs=1e-6)
    vertices, _ = yaw_wedge((0.0, 0.0, 0.0), 0.0, 10.0, segments=2)  # held under 89 deg
    assert math.degrees(math.atan2(vertices[3][1], vertices[3][0])) == pytest.approx(89.0)


def test_the_pose_tool_meets_the_ground_and_sends_rvizs_messages():
    # a camera 2 m up looking down 45 deg through (1, 0, 1): the ground at (2, 0)
    assert ground_point((0.0, 0.0, 2.0), (1.0, 0.0, 1.0)) == pytest.approx([2.0, 0.0, 0.0])
    assert ground_point((0.0, 0.0, 2.0), (1.0, 0.0, 3.0)) is None  # pointing at the sky
    assert ground_point((0.0, 0.0, 2.0), (1.0, 0.0, 2.0)) is None  # level
    assert pose_from_drag((1.0, 1.0), (1.0, 2.0)) == pytest.approx((1.0, 1.0, math.pi / 2))
    assert pose_from_drag((1.0, 1.0), (1.0, 1.0)) == (1.0, 1.0, 0.0)  # a click faces +x
    msg = initial_pose_message(1.0, 2.0, math.pi, 'map', Time(sec=5))
    assert msg.header.frame_id == 'map' and msg.header.stamp.sec == 5
    assert msg.pose.pose.orientation.z == pytest.approx(1.0)
    cov = list(msg.pose.covariance)
    assert (cov[0], cov[7], cov[35]) == pytest.approx((0.25, 0.25, 0.06853891945200942))
    assert sum(abs(v) for v in cov) == pytest.approx(0.25 + 0.25 + 0.06853891945200942)
    goal = goal_pose_message(1.0, 2.0, 0.0, 'map', Time(sec=5))
    assert goal.pose.position.y == 2.0 and goal.pose.orientation.w == 1.0
