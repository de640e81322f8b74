# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The viewer's teleop pad: held controls -> velocity command, with a dead-man (pure, no rclpy).

Controls are the pad's buttons and keys while the page has focus: arrows or
``teleop_twist_keyboard``'s ``i`` (forward), ``,`` (back), ``j`` (turn left), ``l`` (turn
right); ``k`` or the stop button releases everything. Several held controls add up (forward +
left drives an arc), each factor clamped to -1..1; the command is ``linear.x = x * speed``
(m/s) and ``angular.z = th * turn`` (rad/s) in the base frame (REP 103: x forward, positive yaw
counter-clockwise).

Dead-man: a command is published at the pad rate while at least one control is held, and
exactly one zero command when the last one is released. A held control that is not refreshed
by the page within ``hold_timeout`` (the page was closed, lost focus or its connection
dropped) counts as released, so the robot never runs on without someone holding a control.
"""

#: control -> (x, th) direction factors.
DIRECTIONS = {
    'forward': (1, 0),
    'back': (-1, 0),
    'left': (0, 1),
    'right': (0, -1),
}

#: key (``KeyboardEvent.key`` of the browser) -> control; 'stop' releases everything.
KEYS = {
    'ArrowUp': 'forward',
    'i': 'forward',
    'ArrowDown': 'back',
    ',': 'back',
    'ArrowLeft': 'left',
    'j': 'left',
    'ArrowRight': 'right',
    'l': 'right',
    'k': 'stop',
}

DEFAULT_HOLD_TIMEOUT = 0.5
"""Seconds a held control stays held without a refresh from the page."""


def _clamp(value):
    return max(-1, min(1, value))


class DeadMan:
    """
    Held-control bookkeeping of the teleop pad (see the module docstring).

    :param hold_timeout: default seconds after which a held control that was not refreshed
        is released (0 = never).
    """

    def __init__(self, hold_timeout=DEFAULT_HOLD_TIMEOUT):
        """Start with nothing held and nothing owed."""
        self.hold_timeout = float(hold_timeout)
        self._held = {}  # control -> time (s) at which it counts as released
        self._owe_zero = False

    def press(self, control, now, hold=None):
        """
        Hold (or refresh) ``control``; ``'stop'`` releases everything.

        :param control: a key of :data:`DIRECTIONS` or ``'stop'``.
        :param now: time in seconds (monotonic).
        :param hold: seconds this press holds the control without a refresh (default
            ``hold_timeout``; 0 = until released).
        :raises KeyError: for an unknown control.
        """
        if control == 'stop':
            self.release_all()
            return
        if control not in DIRECTIONS:
            raise KeyError(control)
        hold = self.hold_timeout if hold is None else float(hold)
        self._held[control] = now + hold if hold > 0 else float('inf')
        self._owe_zero = True

    def release(self, control):
        """Release ``control`` (no-op when it is not held)."""
        self._held.pop(control, None)

    def release_all(self):
        """Release every control (page closed or lost focus, stop pressed)."""
        self._held.clear()

    def held(self, now):
        """Return the held controls at ``now`` after dropping the stale ones (a set)."""
        for control, expiry in list(self._held.items()):
            if now > expiry:
                del self._held[control]
        return set(self._held)

    def command(self, now, speed, turn):
        """
        Return the command to publish at this pad tick.

        :param now: time in seconds (monotonic, same clock as :meth:`press`).
        :param speed: linear speed in m/s for a full factor.
        :param turn: yaw rate in rad/s for a full factor.
        :returns: ``(linear_x, angular_z)`` while a control is held, ``(0.0, 0.0)`` once
            after the last release, else None (publish nothing).
        """
        held = self.held(now)
        if held:
            x = _clamp(sum(DIRECTIONS[c][0] for c in held))
            th = _clamp(sum(DIRECTIONS[c][1] for c in held))
            return x * float(speed), th * float(turn)
        if self._owe_zero:
            self._owe_zero = False
            return 0.0, 0.0
        return None
