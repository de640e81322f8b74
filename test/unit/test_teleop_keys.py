# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Key map and speed scaling of the keyboard teleop (upstream teleop_twist_keyboard)."""

from amr_description.core.teleop_keys import apply_key
from amr_description.core.teleop_keys import BANNER
from amr_description.core.teleop_keys import check_parameters
from amr_description.core.teleop_keys import CTRL_C
from amr_description.core.teleop_keys import format_speeds
from amr_description.core.teleop_keys import TeleopState
import pytest


@pytest.mark.parametrize('key, expected', [
    ('i', (0.5, 0.0, 0.0, 0.0)),
    (',', (-0.5, 0.0, 0.0, 0.0)),
    ('j', (0.0, 0.0, 0.0, 1.0)),
    ('l', (0.0, 0.0, 0.0, -1.0)),
    ('u', (0.5, 0.0, 0.0, 1.0)),
    ('o', (0.5, 0.0, 0.0, -1.0)),
    ('m', (-0.5, 0.0, 0.0, -1.0)),
    ('.', (-0.5, 0.0, 0.0, 1.0)),
    ('I', (0.5, 0.0, 0.0, 0.0)),
    ('J', (0.0, 0.5, 0.0, 0.0)),
    ('L', (0.0, -0.5, 0.0, 0.0)),
    ('U', (0.5, 0.5, 0.0, 0.0)),
    ('O', (0.5, -0.5, 0.0, 0.0)),
    ('M', (-0.5, 0.5, 0.0, 0.0)),
    ('<', (-0.5, 0.0, 0.0, 0.0)),
    ('>', (-0.5, -0.5, 0.0, 0.0)),
    ('t', (0.0, 0.0, 0.5, 0.0)),
    ('b', (0.0, 0.0, -0.5, 0.0)),
])
def test_move_keys(key, expected):
    state = TeleopState()
    result = apply_key(state, key)
    assert result.publish and not result.finished and result.messages == ()
    assert state.twist() == pytest.approx(expected)


@pytest.mark.parametrize('key', ['k', 'K', 'a', ' ', '\x1b', ''])
def test_other_keys_stop(key):
    state = TeleopState()
    apply_key(state, 'u')
    result = apply_key(state, key)
    assert result.publish and not result.finished
    assert state.twist() == (0.0, 0.0, 0.0, 0.0)


def test_ctrl_c_quits_without_publishing():
    state = TeleopState()
    apply_key(state, 'i')
    result = apply_key(state, CTRL_C)
    assert result.finished and not result.publish
    assert state.twist() == (0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize('key, speed, turn', [
    ('q', 0.55, 1.1), ('z', 0.45, 0.9), ('w', 0.55, 1.0), ('x', 0.45, 1.0),
    ('e', 0.5, 1.1), ('c', 0.5, 0.9),
])
def test_speed_keys_scale_and_keep_direction(key, speed, turn):
    state = TeleopState()
    apply_key(state, 'u')
    result = apply_key(state, key)
    assert result.publish
    assert (state.speed, state.turn) == pytest.approx((speed, turn))
    assert state.twist() == pytest.approx((speed, 0.0, 0.0, turn))
    assert result.messages == (format_speeds(state.speed, state.turn),)


def test_speed_scaling_compounds():
    state = TeleopState(speed=1.0, turn=2.0)
    for _ in range(3):
        apply_key(state, 'q')
    assert state.speed == pytest.approx(1.1 ** 3)
    assert state.turn == pytest.approx(2.0 * 1.1 ** 3)


def test_banner_every_fifteen_speed_changes():
    state = TeleopState()
    shown = [i for i in range(30) if BANNER in apply_key(state, 'q').messages]
    assert shown == [14, 29]


def test_status_line_format():
    assert format_speeds(0.5, 1.0) == 'currently:\tspeed 0.5\tturn 1.0 '


def test_parameter_checks():
    check_parameters(False, '', 0.5, 1.0, 0.0)
    check_parameters(True, 'base_link', 0.5, 1.0, 0.5)
    with pytest.raises(ValueError, match="'frame_id' can only be set when 'stamped'"):
        check_parameters(False, 'base_link', 0.5, 1.0, 0.0)
    with pytest.raises(ValueError, match="'key_timeout' must be >= 0"):
        check_parameters(True, '', 0.5, 1.0, -1.0)
    with pytest.raises(ValueError, match="'speed' must be a number"):
        check_parameters(True, '', 'fast', 1.0, 0.0)
