# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""navigate_job's lock-step: which tick owes a velocity command (no processes)."""

from amr_description.nodes.navigate_job.lockstep import Cadence


def _ticks(cadence, start, count, tick=0.05):
    """Return the ticks ``(t0, t1]`` from ``start`` in which ``cadence`` owes a message."""
    out = []
    for k in range(count):
        t0 = start + k * tick
        if cadence.owed(t0, t0 + tick):
            out.append(round(t0, 3))
    return out


def test_nothing_is_owed_before_a_cadence_is_known():
    cadence = Cadence()
    assert not cadence.owed(0.0, 0.05)
    cadence.heard(1.0)
    assert not cadence.owed(1.0, 1.05)


def test_a_20_hz_source_owes_one_message_per_tick_until_heard():
    cadence = Cadence()
    cadence.heard(1.02)
    cadence.heard(1.07)
    assert cadence.owed(1.10, 1.15)       # due at 1.12
    assert not cadence.owed(1.05, 1.10)   # heard at 1.07 in that tick
    cadence.heard(1.12)
    assert not cadence.owed(1.10, 1.15)   # paid
    assert cadence.owed(1.15, 1.20)       # next due at 1.17


def test_a_10_hz_source_owes_every_other_tick():
    cadence = Cadence()
    cadence.heard(2.0)
    cadence.heard(2.1)
    assert _ticks(cadence, 2.1, 4) == [2.15]   # due at 2.2, in (2.15, 2.2]


def test_a_stopped_source_is_owed_once_then_nothing():
    cadence = Cadence()
    cadence.heard(3.0)
    cadence.heard(3.05)
    assert _ticks(cadence, 3.05, 10) == [3.05]   # due at 3.1 only; never heard again


def test_an_older_or_repeated_stamp_does_not_change_the_cadence():
    cadence = Cadence()
    cadence.heard(4.0)
    cadence.heard(4.05)
    cadence.heard(4.01)
    cadence.heard(4.05)
    assert cadence.stamps == [4.0, 4.05]
    assert cadence.owed(4.05, 4.10)
