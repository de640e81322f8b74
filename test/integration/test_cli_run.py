# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 run`` resolves executables through the ament index; ``ros2 pkg`` lists them."""

import os
import signal
import subprocess
import time

import pytest


def test_run_talker_through_ament_index(ros_env, procs, exe):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker'], ros_env)
    assert run.wait_for_output('Publishing: "Hello World: 0"', timeout=60.0), run.output
    assert run.interrupt() == 0
    assert 'Traceback' not in run.output


def test_run_passes_arguments_and_ros_args(ros_env, procs, exe):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker', '--ros-args',
                       '-r', '__node:=renamed'], ros_env)
    assert run.wait_for_output('[renamed]: Publishing', timeout=60.0), run.output
    assert run.interrupt() == 0


def test_run_errors_in_upstream_wording(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'run', 'no_such_pkg', 'x'], env=ros_env,
                            capture_output=True, text=True, timeout=60)
    assert (result.returncode, result.stderr) == (1, "Package 'no_such_pkg' not found\n")
    result = subprocess.run([exe('ros2'), 'run', 'amr_description', 'nope'], env=ros_env,
                            capture_output=True, text=True, timeout=60)
    assert (result.returncode, result.stderr) == (1, 'No executable found\n')


def test_pkg_executables_lists_talker(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'pkg', 'executables', 'amr_description'],
                            env=ros_env, capture_output=True, text=True, timeout=60)
    lines = result.stdout.splitlines()
    assert 'amr_description talker' in lines and lines == sorted(lines)


def _children(pid):
    """Return the pids of the direct children of ``pid`` (from /proc)."""
    found = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open(f'/proc/{entry}/stat') as f:
                fields = f.read().rsplit(')', 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            found.append(int(entry))
    return found


def _gone(pid, timeout=15.0):
    """Wait until ``pid`` no longer runs (or is a zombie); True when it is gone."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            with open(f'/proc/{pid}/stat') as f:
                state = f.read().rsplit(')', 1)[1].split()[0]
        except OSError:
            return True
        if state == 'Z':
            return True
        time.sleep(0.05)
    return False


@pytest.mark.parametrize('signum', [signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
def test_run_leaves_no_orphan_whatever_signal_reaches_it_alone(ros_env, procs, exe, signum):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker'], ros_env)
    assert run.wait_for_output('Publishing: "Hello World: 0"', timeout=60.0), run.output
    children = _children(run.popen.pid)
    assert len(children) == 1, children
    os.kill(run.popen.pid, signum)  # to ros2 run alone, not to its process group
    assert _gone(children[0]), f'talker {children[0]} outlived ros2 run after {signum!r}'
    code = run.wait(60.0)
    if signum == signal.SIGKILL:
        assert code == -signal.SIGKILL
    else:
        # the child stopped cleanly on the forwarded signal and ros2 run exits with its code
        assert code == 0, run.output
        assert 'Traceback' not in run.output


def test_run_terminal_ctrl_c_reaches_child_once(ros_env, procs, exe):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker'], ros_env)
    assert run.wait_for_output('Publishing: "Hello World: 0"', timeout=60.0), run.output
    assert run.interrupt() == 0  # SIGINT to the whole process group, as a terminal does
    assert 'Traceback' not in run.output
