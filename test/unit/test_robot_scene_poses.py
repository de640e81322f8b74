# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Poses of the browser scene as viser takes them, against hand-computed quaternions."""

import math

from amr_description.web.robot_scene import wxyz_position
from amr_description.web.robot_scene import wxyzs_positions
import numpy as np


def pose(yaw, position):
    """Return the 4x4 pose of a rotation by ``yaw`` about z at ``position``."""
    T = np.eye(4)
    T[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    T[:3, 3] = position
    return T


def test_single_pose_is_wxyz_and_position():
    wxyz, position = wxyz_position(pose(math.pi / 2, (1.0, 2.0, 3.0)))
    half = math.sqrt(0.5)
    np.testing.assert_allclose(wxyz, [half, 0.0, 0.0, half], atol=1e-12)
    np.testing.assert_allclose(position, [1.0, 2.0, 3.0])


def test_batched_poses_row_per_pose_in_float32():
    wxyzs, positions = wxyzs_positions(np.stack([np.eye(4), pose(math.pi, (0.5, 0.0, 0.0))]))
    assert wxyzs.dtype == np.float32 and positions.dtype == np.float32
    assert wxyzs.shape == (2, 4) and positions.shape == (2, 3)
    np.testing.assert_allclose(wxyzs, [[1, 0, 0, 0], [0, 0, 0, 1]], atol=1e-7)
    np.testing.assert_allclose(positions, [[0, 0, 0], [0.5, 0, 0]])


def test_no_poses_gives_empty_arrays_of_the_right_width():
    wxyzs, positions = wxyzs_positions(np.zeros((0, 4, 4)))
    assert wxyzs.shape == (0, 4) and positions.shape == (0, 3)
