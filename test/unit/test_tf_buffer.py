# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The viewer's transform buffer against hand-computed transforms; the nodes' StampedQueue on it.

No ROS graph: nothing here starts rclpy.
"""

import math

from amr_description.core.tf_buffer import ConnectivityException
from amr_description.core.tf_buffer import ExtrapolationException
from amr_description.core.tf_buffer import LookupException
from amr_description.core.tf_buffer import slerp
from amr_description.core.tf_buffer import TransformBuffer
import numpy as np
import pytest

IDENTITY = (0.0, 0.0, 0.0, 1.0)


def yaw(angle):
    """Quaternion (x, y, z, w) of a rotation by ``angle`` about z."""
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


def robot_buffer():
    """Return a buffer: odom -> base_link (dynamic, t=1 and t=3), base_link -> wheel (static)."""
    buffer = TransformBuffer()
    buffer.set_transform('odom', 'base_link', 1.0, (1.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('odom', 'base_link', 3.0, (3.0, 2.0, 0.0), yaw(math.pi / 2))
    buffer.set_transform('base_link', 'wheel', 0.0, (0.0, 0.5, 0.0), IDENTITY, static=True)
    return buffer


def test_same_frame_is_identity():
    buffer = robot_buffer()
    T, _ = buffer.lookup('odom', 'odom')
    np.testing.assert_allclose(T, np.eye(4))


def test_latest_common_time_composes_newest_dynamic_with_static():
    buffer = robot_buffer()
    T, time = buffer.lookup('odom', 'wheel')
    assert time == 3.0
    # base_link at (3, 2) facing +y; the wheel 0.5 m to its left is 0.5 m along -x of odom
    np.testing.assert_allclose(T[:3, 3], [2.5, 2.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(T[:3, 0], [0.0, 1.0, 0.0], atol=1e-12)


def test_inverse_direction():
    buffer = robot_buffer()
    T, _ = buffer.lookup('wheel', 'odom')
    # the odom origin seen from the wheel: rotate (-2.5, -2, 0) by -90 deg about z
    np.testing.assert_allclose(T[:3, 3], [-2.0, 2.5, 0.0], atol=1e-12)


def test_interpolation_translation_linear_rotation_slerp():
    buffer = robot_buffer()
    T, time = buffer.lookup('odom', 'base_link', 2.0)
    assert time == 2.0
    np.testing.assert_allclose(T[:3, 3], [2.0, 1.0, 0.0], atol=1e-12)
    # halfway between yaw 0 and yaw 90 deg is yaw 45 deg
    np.testing.assert_allclose(T[:3, 0], [math.sqrt(0.5), math.sqrt(0.5), 0.0], atol=1e-12)


def test_latest_common_time_is_oldest_newest_of_the_chain():
    buffer = TransformBuffer()
    buffer.set_transform('odom', 'base_link', 5.0, (5.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('odom', 'base_link', 7.0, (7.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('base_link', 'wheel', 4.0, (0.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('base_link', 'wheel', 6.0, (0.0, 0.0, 1.0), IDENTITY)
    assert buffer.latest_common_time('odom', 'wheel') == 6.0
    T, time = buffer.lookup('odom', 'wheel')
    assert time == 6.0
    np.testing.assert_allclose(T[:3, 3], [6.0, 0.0, 1.0], atol=1e-12)


def test_static_chain_is_timeless():
    buffer = TransformBuffer()
    buffer.set_transform('base_footprint', 'base_link', 0.0, (0, 0, 0.1), IDENTITY, static=True)
    T, time = buffer.lookup('base_footprint', 'base_link', 123.0)
    assert time == 123.0
    np.testing.assert_allclose(T[:3, 3], [0.0, 0.0, 0.1])
    assert buffer.latest_common_time('base_footprint', 'base_link') == 0.0


def test_common_ancestor_between_branches():
    buffer = TransformBuffer()
    buffer.set_transform('base_link', 'left', 0.0, (0, 0.15, 0), IDENTITY, static=True)
    buffer.set_transform('base_link', 'right', 0.0, (0, -0.15, 0), yaw(math.pi), static=True)
    T, _ = buffer.lookup('right', 'left')
    # left's origin is 0.3 m along +y of base_link, i.e. along -y of the flipped right frame
    np.testing.assert_allclose(T[:3, 3], [0.0, -0.3, 0.0], atol=1e-12)


def test_extrapolation_errors():
    buffer = robot_buffer()
    with pytest.raises(ExtrapolationException, match='into the past'):
        buffer.lookup('odom', 'wheel', 0.5)
    with pytest.raises(ExtrapolationException, match='into the future'):
        buffer.lookup('odom', 'wheel', 3.5)


def test_single_sample_only_at_its_time():
    buffer = TransformBuffer()
    buffer.set_transform('a', 'b', 2.0, (1, 0, 0), IDENTITY)
    assert buffer.lookup('a', 'b', 2.0)[0][0, 3] == 1.0
    assert buffer.lookup('a', 'b')[1] == 2.0
    with pytest.raises(ExtrapolationException):
        buffer.lookup('a', 'b', 2.5)


def test_unknown_and_unconnected_frames():
    buffer = robot_buffer()
    buffer.set_transform('world', 'other', 0.0, (0, 0, 0), IDENTITY, static=True)
    with pytest.raises(LookupException, match='"map" passed to lookupTransform argument '
                                              'target_frame does not exist'):
        buffer.lookup('map', 'base_link')
    with pytest.raises(ConnectivityException, match='not part of the same tree'):
        buffer.lookup('odom', 'other')
    assert not buffer.can_transform('odom', 'other')
    assert buffer.can_transform('odom', 'wheel')
    assert buffer.root('wheel') == 'odom'
    assert buffer.root('other') == 'world'


def test_cache_time_prunes_old_samples_and_drops_old_data():
    buffer = TransformBuffer(cache_time=2.0)
    for t in range(10):
        buffer.set_transform('a', 'b', float(t), (float(t), 0, 0), IDENTITY)
    with pytest.raises(ExtrapolationException):
        buffer.lookup('a', 'b', 6.5)
    assert buffer.lookup('a', 'b', 7.5)[0][0, 3] == pytest.approx(7.5)
    buffer.set_transform('a', 'b', 1.0, (100.0, 0, 0), IDENTITY)  # too old: dropped
    with pytest.raises(ExtrapolationException):
        buffer.lookup('a', 'b', 1.0)


def test_out_of_order_insert_and_leading_slash():
    buffer = TransformBuffer()
    buffer.set_transform('/a', 'b', 3.0, (3, 0, 0), IDENTITY)
    buffer.set_transform('a', '/b', 1.0, (1, 0, 0), IDENTITY)
    assert buffer.lookup('a', 'b', 2.0)[0][0, 3] == pytest.approx(2.0)
    assert buffer.frames() == {'a', 'b'}
    assert buffer.parent('b') == 'a'


def test_bad_transforms_rejected():
    buffer = TransformBuffer()
    with pytest.raises(ValueError, match='empty frame id'):
        buffer.set_transform('', 'b', 0.0, (0, 0, 0), IDENTITY)
    with pytest.raises(ValueError, match='own parent'):
        buffer.set_transform('b', 'b', 0.0, (0, 0, 0), IDENTITY)
    with pytest.raises(ValueError, match='non-finite'):
        buffer.set_transform('a', 'b', 0.0, (math.nan, 0, 0), IDENTITY)
    with pytest.raises(ValueError, match='zero quaternion'):
        buffer.set_transform('a', 'b', 0.0, (0, 0, 0), (0, 0, 0, 0))
    assert buffer.frames() == set()


def test_quaternion_is_normalized_and_infinite_rotation_rejected():
    buffer = TransformBuffer()
    # (0, 0, 2, 2) is a quarter turn about z scaled by 2 * sqrt(2)
    buffer.set_transform('a', 'b', 1.0, (1, 2, 3), (0, 0, 2, 2))
    T, _ = buffer.lookup('a', 'b')
    expected = np.array([[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0],
                         [0.0, 0.0, 0.0, 1.0]])
    np.testing.assert_allclose(T, expected, atol=1e-12)
    with pytest.raises(ValueError, match='non-finite'):
        buffer.set_transform('a', 'c', 1.0, (0, 0, 0), (0, 0, math.inf, 1))
    assert buffer.frames() == {'a', 'b'}


def test_a_value_replaced_is_seen_by_the_next_lookup():
    buffer = robot_buffer()
    np.testing.assert_allclose(buffer.lookup('odom', 'wheel')[0][:3, 3], [2.5, 2.0, 0.0])
    # same stamp as the newest sample: replaces it
    buffer.set_transform('odom', 'base_link', 3.0, (4.0, 2.0, 0.0), yaw(math.pi / 2))
    np.testing.assert_allclose(buffer.lookup('odom', 'wheel')[0][:3, 3], [3.5, 2.0, 0.0])
    buffer.set_transform('base_link', 'wheel', 0.0, (0.0, 1.0, 0.0), IDENTITY, static=True)
    np.testing.assert_allclose(buffer.lookup('odom', 'wheel')[0][:3, 3], [3.0, 2.0, 0.0])
    buffer.set_transform('odom', 'base_link', 4.0, (0.0, 0.0, 0.0), IDENTITY)
    T, time = buffer.lookup('wheel', 'odom')
    assert time == 4.0
    np.testing.assert_allclose(T[:3, 3], [0.0, -1.0, 0.0])
    np.testing.assert_allclose(T @ buffer.lookup('odom', 'wheel')[0], np.eye(4), atol=1e-12)


def test_slerp_endpoints_and_shorter_arc():
    q0, q1 = np.array(yaw(0.0)), np.array(yaw(1.0))
    np.testing.assert_allclose(slerp(q0, q1, 0.0), q0, atol=1e-12)
    np.testing.assert_allclose(slerp(q0, q1, 1.0), q1, atol=1e-12)
    np.testing.assert_allclose(slerp(q0, q1, 0.5), yaw(0.5), atol=1e-12)
    # -q1 is the same rotation: the result must still be yaw 0.5
    half = slerp(q0, -q1, 0.5)
    np.testing.assert_allclose(abs(np.dot(half, yaw(0.5))), 1.0, atol=1e-12)


def test_clear_forgets_dynamic_transforms_and_keeps_static_ones_as_tf2():
    buffer = robot_buffer()
    buffer.clear()  # a backward jump of /clock: /tf_static is not published again
    T, _ = buffer.lookup('base_link', 'wheel')
    np.testing.assert_allclose(T[:3, 3], [0.0, 0.5, 0.0])
    with pytest.raises(LookupException):
        buffer.lookup('odom', 'wheel')
    # the dynamic transform comes back with the next /tf, older stamps included
    buffer.set_transform('odom', 'base_link', 0.5, (2.0, 0.0, 0.0), IDENTITY)
    T, _ = buffer.lookup('odom', 'wheel')
    np.testing.assert_allclose(T[:3, 3], [2.0, 0.5, 0.0])


def test_stamped_queue_waits_for_the_transform_at_each_stamp_in_arrival_order():
    from amr_description.ros.transforms import not_yet
    from amr_description.ros.transforms import StampedQueue
    buffer = TransformBuffer()
    buffer.set_transform('odom', 'base_link', 0.8, (0.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('odom', 'base_link', 1.0, (0.0, 0.0, 0.0), IDENTITY)
    used, dropped = [], []

    def use(stamp):
        try:
            T, _ = buffer.lookup('odom', 'base_link', stamp)
        except ExtrapolationException as exc:
            if not_yet(exc):
                return False
            dropped.append(stamp)
            return True
        used.append((stamp, T[0, 3]))
        return True

    queue = StampedQueue(3, use)
    queue.add(2.0)  # odometry only up to t=1: waits
    queue.add(2.5)
    assert not used and len(queue) == 2
    buffer.set_transform('odom', 'base_link', 3.0, (2.0, 0.0, 0.0), IDENTITY)
    queue.add(0.5)  # older than the buffer: dropped once it is the head, after the others
    assert used == [(2.0, 1.0), (2.5, 1.5)] and dropped == [0.5] and len(queue) == 0
    for stamp in (4.0, 5.0, 6.0, 7.0):  # a full queue drops its oldest
        queue.add(stamp)
    assert len(queue) == 3
    buffer.set_transform('odom', 'base_link', 8.0, (2.0, 0.0, 0.0), IDENTITY)
    queue.add(7.5)  # 4.0 and then 5.0 left the full queue unused
    assert [s for s, _ in used[2:]] == [6.0, 7.0, 7.5]


def test_a_frame_replaced_during_a_lookup_leaves_the_lookup_consistent(monkeypatch):
    # another thread replacing a frame (a transform under a new parent, or static after
    # dynamic) between the common time and the composition: the lookup keeps the frames it
    # read, as one consistent snapshot, instead of composing a time the new frame lacks
    from amr_description.core import tf_buffer
    buffer = TransformBuffer()
    buffer.set_transform('map', 'odom', 9.0, (1.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('map', 'odom', 10.0, (1.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('odom', 'base_link', 8.0, (0.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('odom', 'base_link', 12.0, (4.0, 0.0, 0.0), IDENTITY)
    latest = tf_buffer._latest_common

    def latest_then_replace(edges):
        time = latest(edges)
        buffer.set_transform('odom', 'base_link', 5.0, (0.0, 0.0, 0.0), IDENTITY, static=True)
        buffer.set_transform('odom', 'base_link', 4.0, (0.0, 0.0, 0.0), IDENTITY)
        buffer.set_transform('odom', 'base_link', 4.5, (0.0, 0.0, 0.0), IDENTITY)
        return time

    monkeypatch.setattr(tf_buffer, '_latest_common', latest_then_replace)
    T, time = buffer.lookup('map', 'base_link')
    assert time == 10.0
    assert T[0, 3] == pytest.approx(1.0 + 2.0)  # base_link at x 2 at t 10 (8 -> 12: 0 -> 4)


def test_a_new_frame_is_stored_with_its_first_transform():
    buffer = TransformBuffer()
    seen = []

    class Frames(dict):

        def __setitem__(self, key, frame):
            seen.append((frame.static, [s[0] for s in frame.samples]))
            super().__setitem__(key, frame)

    buffer._frames = Frames()
    buffer.set_transform('odom', 'base_link', 2.0, (0.0, 0.0, 0.0), IDENTITY)
    buffer.set_transform('base_link', 'wheel', 0.0, (0.0, 0.5, 0.0), IDENTITY, static=True)
    assert seen[0] == (None, [2.0]) and seen[1][0] is not None and seen[1][1] == []
