# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
amr_description.ros.worker_process: calls answered by a child interpreter, and its end.

The planner server makes its plans this way (amr_description/nodes/planner_server.py): the
plan from the child is the one made in this process, PlanError comes back with its code, the
child is another process, a child that dies is one WorkerError and the next call starts a
new one, and no child outlives its parent, stopped or killed.
"""

import os
import signal
import subprocess
import sys
import textwrap
import time

from amr_description.nav.costmap import Costmap
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.planner import make_plan
from amr_description.nav.planner import PlanError
from amr_description.ros.worker_process import WorkerError
from amr_description.ros.worker_process import WorkerProcess
import numpy as np
import pytest

PLANNER = 'amr_description.nav.planner'


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f'/proc/{pid}/stat') as f:
        return f.read().split(') ')[-1][0] != 'Z'


def _wait_gone(pid, deadline_s=30.0):
    end = time.monotonic() + deadline_s
    while time.monotonic() < end:
        if not _alive(pid):
            return True
        time.sleep(0.1)
    return False


@pytest.fixture
def worker():
    w = WorkerProcess(preload=(PLANNER,))
    yield w
    w.stop()


def test_plans_and_errors_come_back_from_the_child(worker):
    grid = Costmap(np.zeros((120, 160), np.uint8), 0.05, (-4.0, -3.0))
    grid.costs[40:80, 70:75] = LETHAL_OBSTACLE
    args = (grid, (-2.0, 0.0), (3.0, 0.5, 0.7))
    there = worker.call(PLANNER, 'make_plan', *args)
    here = make_plan(*args)
    assert there.shape == here.shape and there.shape[0] > 10
    assert np.allclose(there, here, equal_nan=True)
    assert there[-1, 2] == pytest.approx(0.7)
    with pytest.raises(PlanError) as e:
        worker.call(PLANNER, 'make_plan', grid, (-2.0, 0.0), (-0.45, -0.5, 0.0), 0.0)
    assert e.value.code == 'GOAL_OCCUPIED'
    assert 'lethal' in str(e.value)
    child = worker.call('os', 'getpid')
    assert child != os.getpid()
    assert worker.call('os', 'getppid') == os.getpid()


def test_a_dead_child_is_one_error_and_the_next_call_starts_another(worker):
    first = worker.call('os', 'getpid')
    with pytest.raises(WorkerError, match='ended'):
        worker.call('os', '_exit', 3)
    assert _wait_gone(first)
    second = worker.call('os', 'getpid')
    assert second != first
    with pytest.raises(ZeroDivisionError):
        worker.call('operator', 'truediv', 1, 0)
    assert worker.call('os', 'getpid') == second  # an exception does not end the child


def test_the_child_ends_with_stop_and_ignores_ctrl_c(worker):
    pid = worker.call('os', 'getpid')
    os.kill(pid, signal.SIGINT)  # a Ctrl-C reaches the whole process group
    assert worker.call('os', 'getpid') == pid
    worker.stop()
    assert _wait_gone(pid)
    with pytest.raises(WorkerError, match='stopped'):
        worker.call('os', 'getpid')  # no new child after stop (a node cleaned up)


def test_no_child_outlives_a_killed_parent(tmp_path):
    script = textwrap.dedent("""
        import sys, time
        from amr_description.ros.worker_process import WorkerProcess
        w = WorkerProcess()
        print(w.call('os', 'getpid'), flush=True)
        time.sleep(600)
    """)
    parent = subprocess.Popen([sys.executable, '-c', script], stdout=subprocess.PIPE,
                              text=True)
    try:
        child = int(parent.stdout.readline())
        assert _alive(child)
    finally:
        parent.kill()
        parent.wait()
        parent.stdout.close()
    assert _wait_gone(child), f'worker {child} outlived its killed parent'
