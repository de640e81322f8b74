# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The viewer's teleop pad: held controls -> command, dead-man release (pure)."""

from amr_description.core.teleop_pad import DeadMan
from amr_description.core.teleop_pad import KEYS
import pytest


def test_nothing_held_publishes_nothing():
    assert DeadMan().command(0.0, 0.5, 1.0) is None


def test_held_control_then_one_zero_on_release():
    pad = DeadMan(hold_timeout=0.25)
    pad.press('forward', 0.0)
    assert pad.command(0.05, 0.5, 1.0) == (0.5, 0.0)
    pad.press('forward', 0.1)  # the page refreshes the hold
    assert pad.command(0.3, 0.5, 1.0) == (0.5, 0.0)
    pad.release('forward')
    assert pad.command(0.35, 0.5, 1.0) == (0.0, 0.0)
    assert pad.command(0.40, 0.5, 1.0) is None


def test_hold_not_refreshed_times_out_with_one_zero():
    pad = DeadMan(hold_timeout=0.25)
    pad.press('left', 0.0)
    assert pad.command(0.2, 0.5, 1.0) == (0.0, 1.0)
    assert pad.command(0.3, 0.5, 1.0) == (0.0, 0.0)  # page closed: no refresh since 0.0
    assert pad.command(0.4, 0.5, 1.0) is None


def test_per_press_hold_and_stop():
    pad = DeadMan(hold_timeout=0.25)
    pad.press('back', 0.0, hold=0.6)
    assert pad.command(0.5, 0.4, 1.0) == (-0.4, 0.0)
    pad.press('stop', 0.55)
    assert pad.command(0.56, 0.4, 1.0) == (0.0, 0.0)
    assert pad.command(0.57, 0.4, 1.0) is None


def test_controls_add_up_and_clamp():
    pad = DeadMan()
    pad.press('forward', 0.0)
    pad.press('right', 0.0)
    assert pad.command(0.1, 0.5, 2.0) == (0.5, -2.0)
    pad.press('left', 0.0)
    assert pad.command(0.1, 0.5, 2.0) == (0.5, 0.0)
    pad.press('back', 0.0)
    assert pad.command(0.1, 0.5, 2.0) == (0.0, 0.0)


def test_release_all_and_unknown_control():
    pad = DeadMan()
    pad.press('forward', 0.0)
    pad.release_all()
    assert pad.command(0.01, 0.5, 1.0) == (0.0, 0.0)
    with pytest.raises(KeyError):
        pad.press('jump', 0.0)


def test_keys_match_teleop_twist_keyboard():
    assert KEYS['i'] == 'forward' and KEYS[','] == 'back'
    assert KEYS['j'] == 'left' and KEYS['l'] == 'right' and KEYS['k'] == 'stop'
    assert KEYS['ArrowUp'] == 'forward' and KEYS['ArrowLeft'] == 'left'
