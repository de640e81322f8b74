# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Work handed to the simulation thread: run between two cycles, answered to the caller.

Everything that changes the world (spawn, reset, pause, steps) is such a request, so the
simulation thread is the only one that touches MuJoCo's model and data.
"""

import collections
import threading


class Request:
    """A function to run in the simulation thread and its outcome."""

    __slots__ = ('function', 'done', 'result', 'error', 'callback')

    def __init__(self, function, callback=None):
        """Keep ``function`` and the optional ``callback(result, error)``."""
        self.function = function
        self.done = threading.Event()
        self.result = None
        self.error = None
        self.callback = callback

    def run(self):
        """Run the function, keep its result or the exception it raised, then finish."""
        try:
            self.result = self.function()
        except Exception as exc:  # noqa: B902 - reported to the caller, loop goes on
            self.error = exc
        self.finish()

    def finish(self):
        """Wake a waiting caller and call the callback (on the finishing thread)."""
        self.done.set()
        if self.callback is not None:
            self.callback(self.result, self.error)


class RequestQueue:
    """
    Requests waiting for the simulation thread.

    :param wake: the ``threading.Event`` the simulation thread waits on (set on each request).
    """

    def __init__(self, wake):
        """Start empty."""
        self._queue = collections.deque()
        self._wake = wake

    def __bool__(self):
        """Return True while a request waits."""
        return bool(self._queue)

    def put(self, request):
        """Queue ``request`` and wake the simulation thread."""
        self._queue.append(request)
        self._wake.set()

    def run_all(self):
        """Run every waiting request, oldest first (simulation thread)."""
        queue = self._queue
        while queue:
            queue.popleft().run()

    def fail_all(self):
        """Answer every waiting request with a ``RuntimeError`` (the thread stopped)."""
        queue = self._queue
        while queue:
            try:
                request = queue.popleft()
            except IndexError:
                break
            request.error = RuntimeError('the simulation thread stopped')
            request.finish()
