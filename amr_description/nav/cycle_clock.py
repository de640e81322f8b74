# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""A control loop's time step and lateness, measured from the times its cycles ran."""


class CycleClock:
    """
    A control loop's time step and lateness, from the times its cycles ran.

    Upstream's controller_server runs its loop on a thread of its own and Regulated Pure
    Pursuit takes ``1 / controller_frequency`` as the time between commands. Here the loop
    is a timer among the composed servers' Python threads, which ran over 0.1 s late at
    22-32 % of the cycles on a loaded 2-core machine (docs/navigation.md, "A late loop's
    turns"): each command then stays in force longer, so an in-place turn braked late and
    overshot. :meth:`tick` gives the step an acceleration limit may span and how late the
    loop has been lately; on time they are upstream's ``1 / frequency`` and 0.

    :param period: the nominal period (s), ``1 / frequency``.
    :param window: how many recent intervals the lateness is the largest of (10: 0.5 s at
        20 Hz).
    :param stall: s; a longer interval (the loop idle between goals, a paused clock) is not
        a late cycle and is ignored.
    """

    def __init__(self, period, window=10, stall=1.0):
        """Keep the period; no cycle yet."""
        self.period = float(period)
        self.window = int(window)
        self.stall = float(stall)
        self.reset()

    def reset(self):
        """Forget the cycles (the loop restarts)."""
        self._last = None
        self._intervals = []

    def tick(self, now):
        """
        Record a cycle at ``now`` (s, the node's clock) and return ``(dt, lateness)``.

        ``dt`` is the time since the previous cycle, at least ``period`` (``period`` after a
        stall or at the first cycle); ``lateness`` is the largest of the last ``window``
        intervals minus ``period``, at least 0.
        """
        elapsed = None if self._last is None else now - self._last
        self._last = now
        if elapsed is None or not 0.0 < elapsed <= self.stall:
            return self.period, self._lateness()
        self._intervals = (self._intervals + [elapsed])[-self.window:]
        return max(self.period, elapsed), self._lateness()

    def _lateness(self):
        return max([0.0] + [e - self.period for e in self._intervals])
