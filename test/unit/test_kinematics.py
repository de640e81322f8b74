# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Forward kinematics against hand-computed transforms (pure, no rclpy)."""

import math
from types import SimpleNamespace

from amr_description.core import kinematics as k
import numpy as np
import pytest

H = math.sqrt(0.5)


def test_rpy_single_axes():
    np.testing.assert_allclose(
        k.rpy_to_matrix((math.pi / 2, 0, 0)), [[1, 0, 0], [0, 0, -1], [0, 1, 0]], atol=1e-12)
    np.testing.assert_allclose(
        k.rpy_to_matrix((0, math.pi / 2, 0)), [[0, 0, 1], [0, 1, 0], [-1, 0, 0]], atol=1e-12)
    np.testing.assert_allclose(
        k.rpy_to_matrix((0, 0, math.pi / 2)), [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)


def test_rpy_order_is_fixed_axis_xyz():
    # roll 90 then yaw 90 (fixed axes): x -> x -> y; y -> z -> z; z -> -y -> x.
    R = k.rpy_to_matrix((math.pi / 2, 0, math.pi / 2))
    np.testing.assert_allclose(R @ [1, 0, 0], [0, 1, 0], atol=1e-12)
    np.testing.assert_allclose(R @ [0, 1, 0], [0, 0, 1], atol=1e-12)
    np.testing.assert_allclose(R @ [0, 0, 1], [1, 0, 0], atol=1e-12)


def test_origin_matrix():
    T = k.origin_to_matrix((1, 2, 3), (0, 0, math.pi))
    np.testing.assert_allclose(T @ [1, 0, 0, 1], [0, 2, 3, 1], atol=1e-12)


def test_axis_angle_matches_single_axis_rotations():
    np.testing.assert_allclose(k.axis_angle_matrix((0, 0, 2), 0.3), k.rot_z(0.3), atol=1e-12)
    np.testing.assert_allclose(k.axis_angle_matrix((1, 0, 0), -1.1), k.rot_x(-1.1), atol=1e-12)
    with pytest.raises(ValueError):
        k.axis_angle_matrix((0, 0, 0), 1.0)


def test_quaternion_closed_forms():
    np.testing.assert_allclose(k.matrix_to_quaternion(np.eye(3)), [0, 0, 0, 1])
    np.testing.assert_allclose(k.matrix_to_quaternion(k.rot_z(math.pi / 2)), [0, 0, H, H])
    np.testing.assert_allclose(k.matrix_to_quaternion(k.rot_x(-math.pi / 2)), [-H, 0, 0, H])
    # 180 deg about y: the w = 0 branch.
    np.testing.assert_allclose(k.matrix_to_quaternion(k.rot_y(math.pi)), [0, 1, 0, 0],
                               atol=1e-12)


@pytest.mark.parametrize('rpy', [(0.1, -0.7, 2.9), (3.0, 0.2, -3.0), (-1.5708, 0, 0)])
def test_quaternion_roundtrip(rpy):
    R = k.rpy_to_matrix(rpy)
    np.testing.assert_allclose(k.quaternion_to_matrix(k.matrix_to_quaternion(R)), R, atol=1e-12)


def test_revolute_and_prismatic_motion():
    T = k.joint_transform(k.origin_to_matrix((0.2, 0.15, 0)), 'continuous', (0, 0, 1),
                          math.pi / 2)
    np.testing.assert_allclose(T @ [1, 0, 0, 1], [0.2, 1.15, 0, 1], atol=1e-12)
    T = k.joint_transform(None, 'prismatic', (0, 0, 2), 0.5)
    np.testing.assert_allclose(T[:3, 3], [0, 0, 0.5])
    np.testing.assert_allclose(k.joint_transform(None, 'fixed', (1, 0, 0), 3.0), np.eye(4))
    with pytest.raises(ValueError):
        k.joint_motion('helical', (0, 0, 1), 0.0)


def test_amr_wheel_frame_by_hand():
    # joint_wheel_front_left: origin xyz (0.2, 0.15, 0), rpy (-pi/2, 0, 0), axis z.
    # Rx(-pi/2) maps the wheel z axis (axle) onto base +y; base_link sits 0.1 above
    # base_footprint.
    base = SimpleNamespace(name='base_joint', type='fixed', axis=(0, 0, 1),
                           origin=k.origin_to_matrix((0, 0, 0.1)))
    wheel = SimpleNamespace(name='w', type='continuous', axis=(0, 0, 1),
                            origin=k.origin_to_matrix((0.2, 0.15, 0), (-math.pi / 2, 0, 0)))
    T = k.chain_transform([base, wheel])
    xyz, q = k.matrix_to_translation_quaternion(T)
    np.testing.assert_allclose(xyz, [0.2, 0.15, 0.1], atol=1e-12)
    np.testing.assert_allclose(q, [-H, 0, 0, H], atol=1e-12)
    np.testing.assert_allclose(T[:3, :3] @ [0, 0, 1], [0, 1, 0], atol=1e-12)
    # Quarter turn of the wheel: its x axis (initially base +x) turns about +y to base -z.
    T = k.chain_transform([base, wheel], {'w': math.pi / 2})
    np.testing.assert_allclose(T[:3, :3] @ [1, 0, 0], [0, 0, -1], atol=1e-12)
    np.testing.assert_allclose(T[:3, 3], [0.2, 0.15, 0.1], atol=1e-12)


def test_mimic_position():
    assert k.mimic_position(2.0, -0.5, 0.25) == -0.75
    assert k.mimic_position(1.5) == 1.5


def test_one_quaternion_in_scalar_arithmetic_is_the_vectorized_rotation():
    rng = np.random.default_rng(7)
    quaternions = [*rng.normal(size=(200, 4)), (0.0, 0.0, 0.0, 0.0), (0, 0, 3, 4),
                   np.array([0.0, 0.0, 0.6, 0.8])]
    many = k.quaternions_to_matrices(quaternions)
    for q, R in zip(quaternions, many):
        np.testing.assert_array_equal(k.quaternion_to_matrix(q), R)
    np.testing.assert_array_equal(k.quaternion_to_matrix((0, 0, 0, 0)), np.eye(3))
    np.testing.assert_allclose(k.quaternion_to_matrix((0, 0, 3, 4)),
                               [[0.28, -0.96, 0], [0.96, 0.28, 0], [0, 0, 1]], atol=1e-15)
    assert np.isnan(k.quaternion_to_matrix((math.nan, 0, 0, 1))).all()
