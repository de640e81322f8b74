# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A node's work on threads of its own, off its executor: every period, or each time asked.

slam_toolbox sends ``map -> odom`` from a loop of its own (``publishTransformLoop``) and
builds its map on another (``publishVisualizations``), so neither waits for a scan being
matched nor holds one up. :class:`Periodic` and :class:`OnRequest` are those threads. An
error in the work is one log line (at most every 5 s) and the thread goes on; an error after
:meth:`stop` (the node's entities going away) ends it quietly.
"""

import threading


class _Worker:
    """A daemon thread running ``work`` until :meth:`stop`; errors logged as one line."""

    def __init__(self, name, work, logger, failure):
        self._work = work
        self._logger = logger
        self._failure = failure
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)

    def start(self):
        """Start the thread."""
        self._thread.start()

    def stop(self):
        """Stop the thread and wait for the work in progress to finish."""
        self._stop.set()
        self._wake()
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join()

    def _wake(self):
        """Wake a thread waiting for its next turn (a subclass's wait)."""

    def _call(self):
        """Run the work once; return False when the thread is to end."""
        try:
            self._work()
        except Exception as exc:  # noqa: B902 - one line, and the thread goes on
            if self._stop.is_set():
                return False  # the node is being destroyed
            self._logger.error(f'{self._failure}: {exc}', throttle_duration_sec=5.0)
        return True


class Periodic(_Worker):
    """
    ``work()`` every ``period`` wall seconds on a thread of its own (a ``WallRate`` loop).

    :param name: the thread's name.
    :param period: seconds between the ends of one call and the start of the next (> 0).
    :param work: callable without arguments.
    :param logger: an rclpy logger for the one-line errors.
    :param failure: what the error line says failed, e.g. ``map -> odom not published``.
    """

    def __init__(self, name, period, work, logger, failure):
        """Keep the work; the thread starts with :meth:`start`."""
        super().__init__(name, work, logger, failure)
        self._period = period

    def _run(self):
        while not self._stop.wait(self._period) and self._call():
            pass


class OnRequest(_Worker):
    """
    ``work()`` on a thread of its own each time :meth:`request` was called since its last run.

    Requests made while the work runs are served by one more run after it.

    :param name: the thread's name.
    :param work: callable without arguments.
    :param logger: an rclpy logger for the one-line errors.
    :param failure: what the error line says failed.
    """

    def __init__(self, name, work, logger, failure):
        """Keep the work; the thread starts with :meth:`start`."""
        super().__init__(name, work, logger, failure)
        self._asked = threading.Condition()
        self._due = False

    def request(self):
        """Ask for one run of the work (returns at once)."""
        with self._asked:
            self._due = True
            self._asked.notify()

    def _wake(self):
        with self._asked:
            self._asked.notify()

    def _run(self):
        while True:
            with self._asked:
                while not self._due and not self._stop.is_set():
                    self._asked.wait()
                if self._stop.is_set():
                    return
                self._due = False
            if not self._call():
                return
