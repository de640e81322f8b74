# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Pacing of the simulation thread to a real-time factor, with the achieved factor watched.

The thread sleeps so that sim time advances at ``factor`` times wall time from an anchor (a
wall instant and its sim time); far behind (a spawn, a pause) it re-anchors instead of
catching up. Every :data:`RTF_WINDOW` s it measures the achieved factor and warns once when it
stays below :data:`RTF_SHORTFALL` of the target with robots in the world.
"""

import time

RTF_WINDOW = 5.0
"""Seconds (wall) over which the achieved real-time factor is measured."""

RTF_SHORTFALL = 0.9
"""Warn (once) when the achieved real-time factor is below this fraction of the target."""

CATCH_UP_LIMIT = 0.25
"""Seconds (wall) behind the target after which the pacer re-anchors instead of catching up."""


class Pacer:
    """
    Sleep to a real-time factor (see the module docstring).

    :param logger: ``logging``-like object for the one shortfall warning.
    """

    def __init__(self, logger):
        """Start unanchored."""
        self.logger = logger
        self._anchor = None
        self._window = None
        self._warned = False

    def reset(self):
        """Forget the anchor (after a pause, a reset or a fast-forward stretch)."""
        self._anchor = None

    def pace(self, t, factor, entities):
        """
        Sleep so that sim time ``t`` (s) advances at ``factor`` times wall time.

        :param entities: number of robots in the world (named in the warning; none: no warning).
        """
        now = time.perf_counter()
        window = self._window
        if window is None or self._anchor is None:
            self._window = (now, t)
        elif now - window[0] >= RTF_WINDOW:
            achieved = (t - window[1]) / (now - window[0])
            self._window = (now, t)
            if achieved < RTF_SHORTFALL * factor and entities and not self._warned:
                self._warned = True
                self.logger.warning(
                    f'real-time factor achieved {achieved:.2f} < real_time_factor '
                    f'{factor:g} with {entities} entities: more robots than this '
                    'machine simulates in real time')
        if self._anchor is None:
            self._anchor = (now, t)
            return
        target = self._anchor[0] + (t - self._anchor[1]) / factor
        if target > now:
            time.sleep(target - now)
        elif now - target > CATCH_UP_LIMIT:  # far behind (e.g. a spawn): do not try to catch up
            self._anchor = (now, t)
