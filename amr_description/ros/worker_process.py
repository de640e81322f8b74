# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A module's function called in a Python process of its own, off the caller's interpreter lock.

scikit-image's and SciPy's graph searches hold the interpreter lock while they run (0.1-0.25 s
for a 400 x 400 costmap on a 2-core machine), so in a composed Nav2 container every plan
stopped every other server's thread for that long, controller_server's 20 Hz loop included
(docs/navigation.md, "The planner's search and the controller's loop"). A
:class:`WorkerProcess` runs such calls in a child interpreter: the caller's thread waits on a
pipe, which releases the lock, and the other threads run meanwhile.

The child is ``python -m amr_description.ros.worker_process MODULE...``: it imports the
modules named (so the first call does not pay for them), then answers one call at a time
read from its stdin, ``(module, function, args, kwargs)`` pickled behind an 8-byte length, with
``('ok', value)`` or ``('raise', exception)`` on the stdout it keeps for itself (its fd 1
points at stderr, so that nothing printed corrupts the answers). It ignores SIGINT (a Ctrl-C
reaches the whole process group; the parent decides) and exits when its stdin closes (the
parent stopped it, exited or was killed) or when its parent process is gone.
"""

import importlib
import os
import pickle
import signal
import struct
import subprocess
import sys
import threading
import time

_HEADER = struct.Struct('<Q')


class WorkerError(RuntimeError):
    """The worker process could not be started, or died during a call."""


class WorkerProcess:
    """
    One child interpreter answering calls one at a time; thread-safe (calls are serialized).

    :param preload: module names the child imports as it starts.
    """

    def __init__(self, preload=()):
        """Keep the modules to preload; the child starts with :meth:`start` or the first call."""
        self._preload = tuple(preload)
        self._lock = threading.Lock()
        self._proc = None
        self._stopped = False

    def start(self):
        """Start the child if it is not running (it imports ``preload`` meanwhile)."""
        with self._lock:
            self._ensure()

    def _ensure(self):
        if self._stopped:
            raise WorkerError('the worker process was stopped')
        if self._proc is not None and self._proc.poll() is None:
            return
        try:
            self._proc = subprocess.Popen(
                [sys.executable, '-m', __name__, *self._preload],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        except OSError as exc:
            self._proc = None
            raise WorkerError(f'cannot start {sys.executable}: {exc}') from None

    def call(self, module, function, *args, **kwargs):
        """
        Return ``module.function(*args, **kwargs)`` computed in the child.

        The arguments and the result are pickled (numpy arrays and plain classes travel).

        :raises WorkerError: the child cannot be started, died before answering (the next
            call starts a new one) or was stopped (:meth:`stop`: no more calls).
        :raises Exception: whatever the function raised, re-raised here.
        """
        request = pickle.dumps((module, function, args, kwargs), pickle.HIGHEST_PROTOCOL)
        with self._lock:
            self._ensure()
            proc = self._proc
            try:
                proc.stdin.write(_HEADER.pack(len(request)) + request)
                proc.stdin.flush()
                answer = _read_message(proc.stdout)
            except (OSError, EOFError, ValueError) as exc:
                self._kill()
                raise WorkerError(f'the worker process ended: {exc or type(exc).__name__}') \
                    from None
        kind, value = pickle.loads(answer)
        if kind == 'raise':
            raise value
        return value

    def stop(self):
        """End the child (stdin closed, up to 2 s to exit, then killed); later calls fail."""
        with self._lock:
            self._stopped = True
            proc, self._proc = self._proc, None
        if proc is None:
            return
        try:
            proc.stdin.close()
            proc.wait(timeout=2.0)
        except (OSError, subprocess.TimeoutExpired):
            proc.kill()
            proc.wait()
        proc.stdout.close()

    def _kill(self):
        proc, self._proc = self._proc, None
        if proc is not None:
            proc.kill()
            proc.wait()
            for stream in (proc.stdin, proc.stdout):
                try:
                    stream.close()
                except OSError:
                    pass


def _read_message(stream):
    """Return one length-prefixed message read from ``stream``; EOFError when it closed."""
    header = stream.read(_HEADER.size)
    if len(header) < _HEADER.size:
        raise EOFError('no answer')
    (size,) = _HEADER.unpack(header)
    data = stream.read(size)
    if len(data) < size:
        raise EOFError('a cut answer')
    return data


def _watch_parent(parent):
    while True:
        time.sleep(0.5)
        if os.getppid() != parent:
            os._exit(0)


def _answer(request):
    module, function, args, kwargs = pickle.loads(request)
    try:
        value = ('ok', getattr(importlib.import_module(module), function)(*args, **kwargs))
    except Exception as exc:  # noqa: B902 - every error goes back to the caller
        value = ('raise', exc)
    try:
        return pickle.dumps(value, pickle.HIGHEST_PROTOCOL)
    except Exception as exc:  # noqa: B902 - an unpicklable result or exception
        return pickle.dumps(('raise', WorkerError(f'{function}: {exc}')))


def main(argv=None):
    """Serve calls on stdin until it closes (the child's side; see the module docstring)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_watch_parent, args=(os.getppid(),), daemon=True).start()
    requests = os.fdopen(os.dup(0), 'rb')
    answers = os.fdopen(os.dup(1), 'wb')
    os.dup2(2, 1)
    for module in (sys.argv[1:] if argv is None else argv):
        importlib.import_module(module)
    while True:
        try:
            request = _read_message(requests)
        except EOFError:
            return 0
        data = _answer(request)
        try:
            answers.write(_HEADER.pack(len(data)) + data)
            answers.flush()
        except BrokenPipeError:
            return 0  # the parent went away during the call


if __name__ == '__main__':
    sys.exit(main())
