# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""static_transform_publisher's command line (tf2_ros' rules and error texts)."""

import math

from amr_description.core import kinematics
from amr_description.core import static_transform_args as sta
import numpy as np
import pytest


def test_flags_translation_and_identity_rotation():
    parsed = sta.parse(['--x', '2', '--y', '-1.5', '--frame-id', 'world',
                        '--child-frame-id', 'r1/odom'])
    assert parsed.translation == [2.0, -1.5, 0.0]
    assert parsed.rotation == [0.0, 0.0, 0.0, 1.0]
    assert (parsed.frame_id, parsed.child_frame_id) == ('world', 'r1/odom')
    assert not parsed.help and parsed.warnings == []


def test_yaw_quarter_turn():
    parsed = sta.parse(['--yaw', str(math.pi / 2), '--frame-id', 'a', '--child-frame-id', 'b'])
    assert parsed.rotation == pytest.approx([0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])


@pytest.mark.parametrize('rpy', [(0.3, -0.2, 1.1), (-1.0, 0.5, -2.5), (math.pi, 0.0, 0.0)])
def test_rpy_is_the_fixed_axis_rotation(rpy):
    # Rz(yaw) Ry(pitch) Rx(roll), the URDF/REP 103 convention of the package's kinematics
    q = np.array(sta.quaternion_from_rpy(*rpy))
    expected = kinematics.matrix_to_quaternion(kinematics.rpy_to_matrix(rpy))
    assert abs(np.dot(q, expected)) == pytest.approx(1.0)
    assert np.linalg.norm(q) == pytest.approx(1.0)


def test_quaternion_flags_are_taken_as_given():
    parsed = sta.parse(['--qz', '1', '--qw', '0', '--frame-id', 'a', '--child-frame-id', 'b'])
    assert parsed.rotation == [0.0, 0.0, 1.0, 0.0]


def test_old_style_arguments_with_warning():
    parsed = sta.parse(['1', '2', '3', str(math.pi / 2), '0', '0', 'a', 'b'])
    assert parsed.translation == [1.0, 2.0, 3.0]
    assert parsed.rotation == pytest.approx([0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])
    assert parsed.warnings == [sta.OLD_STYLE_WARNING]
    parsed = sta.parse(['1', '2', '3', '0', '0', '1', '0', 'a', 'b'])
    assert parsed.rotation == [0.0, 0.0, 1.0, 0.0] and parsed.child_frame_id == 'b'


def test_help():
    assert sta.parse(['--help']).help and sta.parse(['-h', '--x', '1']).help


@pytest.mark.parametrize('args,message', [
    ([], 'Frame id must not be empty'),
    (['--frame-id', 'a'], 'Child frame id must not be empty'),
    (['--x'], 'Not enough arguments for --x'),
    (['--x', 'one', '--frame-id', 'a', '--child-frame-id', 'b'],
     'Failed to parse --x argument as float'),
    (['--roll', '1', '--qw', '1', '--frame-id', 'a', '--child-frame-id', 'b'],
     'Cannot specify both quaternion and Euler rotations'),
    (['--x', '1', '1', '2', '3', '0', '0', '0', 'a', 'b'],
     'Cannot specify both new-style (flags) and old-style (arguments)'),
    (['--frame-id', 'a', '--child-frame-id', 'b', 'extra'],
     'Extra unparsed arguments on command-line'),
])
def test_errors_are_upstreams_lines(args, message):
    with pytest.raises(ValueError) as info:
        sta.parse(args)
    assert str(info.value) == message
