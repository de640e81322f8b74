# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Rigid transforms and URDF joint forward kinematics (pure numpy, no rclpy).

Conventions (URDF specification, REP 103):

- A pose is a 4x4 homogeneous matrix ``T`` (float64) mapping child-frame coordinates to
  parent-frame coordinates: ``p_parent = T @ [p_child, 1]``. Lengths in metres, angles in rad.
- ``<origin rpy="r p y">`` means fixed-axis roll about x, then pitch about y, then yaw about z:
  ``R = Rz(y) @ Ry(p) @ Rx(r)``.
- A joint's transform parent -> child at position ``q`` is ``T_origin @ T_motion(q)``; the axis
  is expressed in the joint frame (= the child frame at ``q = 0``). Revolute and continuous
  joints rotate ``q`` rad about the axis, prismatic joints translate ``q`` m along it; fixed,
  floating and planar joints contribute no motion here (robot_state_publisher treats floating
  and planar joints as not driven by ``/joint_states``).
- Quaternions are ``(x, y, z, w)`` as in geometry_msgs, normalized, with ``w >= 0``.
"""

import math

import numpy as np

MOVING_JOINT_TYPES = ('revolute', 'continuous', 'prismatic')


def rot_x(angle):
    """Return the 3x3 rotation about x by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle):
    """Return the 3x3 rotation about y by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle):
    """Return the 3x3 rotation about z by ``angle`` rad."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rpy_to_matrix(rpy):
    """
    Return the 3x3 rotation of a URDF ``rpy`` triple.

    :param rpy: (roll, pitch, yaw) in rad.
    :returns: ``Rz(yaw) @ Ry(pitch) @ Rx(roll)`` (URDF fixed-axis convention), shape (3, 3).
    """
    roll, pitch, yaw = (float(v) for v in rpy)
    return rot_z(yaw) @ rot_y(pitch) @ rot_x(roll)


def origin_to_matrix(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)):
    """
    Return the 4x4 pose of a URDF ``<origin xyz rpy>``.

    :param xyz: translation (m), 3 floats.
    :param rpy: rotation (rad), 3 floats, see :func:`rpy_to_matrix`.
    :returns: homogeneous matrix, shape (4, 4).
    """
    T = np.eye(4)
    T[:3, :3] = rpy_to_matrix(rpy)
    T[:3, 3] = np.asarray(xyz, dtype=float)
    return T


def axis_angle_matrix(axis, angle):
    """
    Return the 3x3 rotation by ``angle`` rad about ``axis`` (Rodrigues' formula).

    :param axis: rotation axis, 3 floats, any non-zero length (normalized here).
    :param angle: rad, right-hand rule.
    :returns: rotation matrix, shape (3, 3).
    :raises ValueError: when the axis has zero length.
    """
    a = np.asarray(axis, dtype=float)
    norm = np.linalg.norm(a)
    if norm == 0.0:
        raise ValueError('joint axis must not be zero')
    x, y, z = a / norm
    K = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def joint_motion(joint_type, axis, position):
    """
    Return the 4x4 motion a joint adds after its origin.

    :param joint_type: URDF joint type string.
    :param axis: joint axis in the joint frame, 3 floats (ignored for non-moving types).
    :param position: joint position, rad (revolute, continuous) or m (prismatic).
    :returns: homogeneous matrix, shape (4, 4); identity for fixed, floating and planar.
    :raises ValueError: for an unknown joint type or a zero axis of a moving joint.
    """
    T = np.eye(4)
    if joint_type in ('revolute', 'continuous'):
        T[:3, :3] = axis_angle_matrix(axis, position)
    elif joint_type == 'prismatic':
        a = np.asarray(axis, dtype=float)
        norm = np.linalg.norm(a)
        if norm == 0.0:
            raise ValueError('joint axis must not be zero')
        T[:3, 3] = a / norm * float(position)
    elif joint_type not in ('fixed', 'floating', 'planar'):
        raise ValueError(f'unknown joint type {joint_type!r}')
    return T


def joint_transform(origin, joint_type, axis, position=0.0):
    """
    Return the parent -> child pose of a URDF joint at ``position``.

    :param origin: the joint's ``<origin>`` as a 4x4 matrix (None = identity).
    :param joint_type: URDF joint type string.
    :param axis: joint axis in the joint frame, 3 floats.
    :param position: joint position (rad or m).
    :returns: ``origin @ joint_motion(...)``, shape (4, 4).
    """
    base = np.eye(4) if origin is None else np.asarray(origin, dtype=float)
    return base @ joint_motion(joint_type, axis, position)


def matrix_to_quaternion(R):
    """
    Return the unit quaternion (x, y, z, w) of a rotation matrix.

    Shepperd's method: pick the largest of w, x, y, z to divide by, for numerical stability.

    :param R: rotation, shape (3, 3) (the upper-left block of a 4x4 matrix is accepted too).
    :returns: numpy array ``[x, y, z, w]`` with ``w >= 0``.
    """
    m = np.asarray(R, dtype=float)[:3, :3]
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0.0:
        s = 2.0 * math.sqrt(1.0 + trace)
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s,
             0.25 * s]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s,
             (m[2, 1] - m[1, 2]) / s]
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s,
             (m[0, 2] - m[2, 0]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s,
             (m[1, 0] - m[0, 1]) / s]
    q = np.array(q)
    q /= np.linalg.norm(q)
    if q[3] < 0.0:
        q = -q
    return q


def quaternion_to_matrix(q):
    """
    Return the 3x3 rotation of one quaternion, as :func:`quaternions_to_matrices` does.

    In scalar arithmetic: every TF lookup composes these, and the vectorized form costs
    about 50 times as much for one quaternion (docs/navigation.md, "The bonds' and the
    odometry's threads"); a unit test holds the two equal.

    :param q: (x, y, z, w), normalized here; all zero (an unset orientation) is the identity.
    :returns: numpy array, shape (3, 3).
    """
    x, y, z, w = map(float, q)
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if n == 0.0:
        return np.eye(3)
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def quaternions_to_matrices(quaternions):
    """
    Return the rotations of N quaternions at once.

    :param quaternions: (N, 4) quaternions (x, y, z, w), normalized here; an all-zero one (an
        unset orientation) is the identity.
    :returns: (N, 3, 3) rotation matrices.
    """
    q = np.array(quaternions, dtype=float).reshape(-1, 4)
    q[~q.any(axis=1)] = (0.0, 0.0, 0.0, 1.0)
    x, y, z, w = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1)],
        axis=1)


def matrix_to_translation_quaternion(T):
    """
    Split a 4x4 pose into translation and quaternion.

    :param T: homogeneous matrix, shape (4, 4).
    :returns: ``(translation [x, y, z] in m, quaternion [x, y, z, w])``, numpy arrays.
    """
    T = np.asarray(T, dtype=float)
    return T[:3, 3].copy(), matrix_to_quaternion(T[:3, :3])


def mimic_position(parent_position, multiplier=1.0, offset=0.0):
    """Return a mimic joint's position: ``multiplier * parent_position + offset`` (URDF spec)."""
    return multiplier * parent_position + offset


def chain_transform(joints, positions=None):
    """
    Compose the poses of a chain of joints, root first.

    :param joints: iterable of objects with ``origin`` (4x4 or None), ``type``, ``axis`` and
        ``name`` attributes (e.g. yourdfpy joints).
    :param positions: dict joint name -> position; missing joints are at 0.
    :returns: pose of the last child in the first parent's frame, shape (4, 4).
    """
    positions = positions or {}
    T = np.eye(4)
    for joint in joints:
        position = positions.get(joint.name, 0.0)
        T = T @ joint_transform(joint.origin, joint.type, joint.axis, position)
    return T
