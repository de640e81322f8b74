# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""MuJoCo's own viewer window (``headless:=false``), synced by the simulation thread."""

import os
import time

SYNC_PERIOD = 1 / 30
"""Seconds (wall) between two syncs of the window."""


class PassiveViewer:
    """
    ``mujoco.viewer.launch_passive`` on the simulation's world; optional, never fatal.

    :param world: the :class:`~amr_description.sim.world.World` (its ``model`` and ``data``).
    :param logger: rclpy logger for the warnings.
    """

    def __init__(self, world, logger):
        """Open the window when a display exists (else warn once and stay closed)."""
        self._world = world
        self._logger = logger
        self._viewer = None
        self._stale = False
        self._last_sync = 0.0
        self._open()

    @property
    def is_open(self):
        """Return True while a window is open."""
        return self._viewer is not None

    def _open(self):
        if not os.environ.get('DISPLAY') and not os.environ.get('WAYLAND_DISPLAY'):
            self._logger.warning('headless:=false but no display; running headless')
            return
        try:
            import mujoco.viewer
            self._viewer = mujoco.viewer.launch_passive(self._world.model, self._world.data)
        except Exception as exc:  # noqa: B902 - the viewer is optional
            self._logger.warning(f'cannot open the MuJoCo viewer: {exc}')
            self._viewer = None

    def model_changed(self):
        """Reopen the window at the next sync (a spawn recompiled the model)."""
        self._stale = self._viewer is not None

    def sync(self, t=None):
        """Sync (or after a spawn reopen) the window, at most 30 Hz (simulation thread)."""
        if self._viewer is None:
            return
        now = time.monotonic()
        if now - self._last_sync < SYNC_PERIOD:
            return
        self._last_sync = now
        if self._stale:
            self._stale = False
            self.close()
            self._open()
            return
        if not self._viewer.is_running():
            self._viewer = None
            return
        self._viewer.sync()

    def close(self):
        """Close the window (any thread; no-op when closed)."""
        if self._viewer is not None:
            try:
                self._viewer.close()
            except Exception:  # noqa: B902 - the viewer is optional
                pass
            self._viewer = None
