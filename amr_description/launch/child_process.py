# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Tie a child process's life to the process that started it (Linux ``PR_SET_PDEATHSIG``).

Used by the orchestrator (``ros2 launch``) and ``ros2 run``, so that no node outlives its
starter whatever signal reaches the starter, SIGKILL included (see ``prctl(2)``).
"""

import ctypes
import os
import signal

_PR_SET_PDEATHSIG = 1


def tie_to_parent(parent_pid, default_signals=(signal.SIGINT, signal.SIGTERM)):
    """
    Return a ``preexec_fn`` for :class:`subprocess.Popen` tying the child to ``parent_pid``.

    Between fork and exec the child asks the kernel for SIGKILL when its parent dies
    (``prctl(PR_SET_PDEATHSIG, SIGKILL)``), exits with code 1 at once when the parent already
    died before that call, and gives ``default_signals`` their default disposition, unblocked,
    whatever the parent set for itself.

    :param parent_pid: pid of the starting process (``os.getpid()`` before ``Popen``).
    :param default_signals: signals reset to ``SIG_DFL`` and unblocked in the child.
    :returns: a callable run in the child between fork and exec.
    """
    def setup():
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except Exception:  # noqa: B902 - never fail a start because prctl is missing
            pass
        if os.getppid() != parent_pid:
            os._exit(1)  # the parent died between fork and prctl
        signal.pthread_sigmask(signal.SIG_UNBLOCK, default_signals)
        for signum in default_signals:
            signal.signal(signum, signal.SIG_DFL)
    return setup
