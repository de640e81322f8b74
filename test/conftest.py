# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Shared pytest fixtures: an isolated ROS environment per test and a process runner.

Every test that starts ROS processes takes ``ros_env`` (a fresh ``ROS_DOMAIN_ID``, discovery
limited to localhost) and ``procs`` (starts processes in their own process group, reads their
output, and kills the whole group when the test ends, so no test leaves a ROS process behind).
"""

import fcntl
import itertools
import os
import signal
import subprocess
import tempfile
import time

import pytest

TIERS = ('unit', 'integration')
"""The suite's tiers, in the order they run (docs/testing.md): ``unit`` (test/unit/ and the
lint checks: no process, no DDS) first, so a broken piece of logic shows in seconds, then
``integration`` (test/integration/: real processes, real DDS, browsers)."""


def pytest_collection_modifyitems(config, items):
    """
    Mark every test with its tier and run the unit tier first.

    ``unit`` or ``integration`` by folder, ``browser`` too for a page test; the order inside
    a tier, and so every module-scoped stack, is kept.
    """
    def tier(item):
        parts = item.path.parts
        return 'integration' if 'integration' in parts else 'unit'

    for item in items:
        item.add_marker(tier(item))
        names = vars(item.module).values() if item.module is not None else ()
        if any(getattr(value, '__module__', None) == 'browser' for value in names):
            item.add_marker('browser')  # uses the page helpers of test/integration/browser.py
    items.sort(key=lambda item: TIERS.index(tier(item)))


# Domain IDs 1..199 are handed out to tests; 200..232 stay free for hand-started stacks.
_FIRST_DOMAIN, _LAST_DOMAIN = 1, 199
_SHELL_MUJOCO_GL = os.environ.get('MUJOCO_GL')
"""``MUJOCO_GL`` as the shell that started pytest had it (the package sets ``egl`` in this
process when imported; child processes get the shell's, as a user's commands do)."""
_DOMAIN_IDS = itertools.count((os.getpid() * 7) % _LAST_DOMAIN)
_DOMAIN_LOCKS = []
_LOCK_DIR = os.path.join(tempfile.gettempdir(), 'amr_description_domains')


def next_domain_id():
    """
    Return a ROS domain ID that no other test process on this machine holds (1..199).

    Each ID is claimed with an exclusive ``flock`` on a file under the temporary directory and
    held until this test process exits, so concurrent test runs (two checkouts, a CI job next
    to a developer's run) never share a domain.

    :returns: the domain ID, an int.
    :raises RuntimeError: when every ID in the range is held by other processes.
    """
    os.makedirs(_LOCK_DIR, exist_ok=True)
    span = _LAST_DOMAIN - _FIRST_DOMAIN + 1
    for _ in range(span):
        domain = next(_DOMAIN_IDS) % span + _FIRST_DOMAIN
        fd = os.open(os.path.join(_LOCK_DIR, f'{domain}.lock'), os.O_CREAT | os.O_RDWR, 0o666)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            continue
        _DOMAIN_LOCKS.append((domain, fd))
        return domain
    raise RuntimeError(f'every ROS domain ID {_FIRST_DOMAIN}..{_LAST_DOMAIN} is in use')


def release_domain_id(domain):
    """
    Give back a domain ID claimed by :func:`next_domain_id` (no-op when not held).

    A ``ros2`` daemon a graph verb started in the domain is stopped first.

    :param domain: the domain ID, an int.
    """
    stop_daemon(domain)
    for entry in list(_DOMAIN_LOCKS):
        if entry[0] == domain:
            _DOMAIN_LOCKS.remove(entry)
            os.close(entry[1])


def package_exe(name):
    """
    Return the absolute path of an installed ``amr_description`` executable.

    :param name: executable name, as in ``ros2 run amr_description NAME``.
    :returns: ``<prefix>/lib/amr_description/NAME`` found through the ament index.
    :raises FileNotFoundError: when the package is not installed (source ``scripts/env.sh``).
    """
    from ament_index_python.packages import get_package_prefix
    path = os.path.join(get_package_prefix('amr_description'), 'lib', 'amr_description', name)
    if not os.path.isfile(path):
        raise FileNotFoundError(f'no executable {path}: run scripts/setup first')
    return path


@pytest.fixture
def exe():
    """Return :func:`package_exe`, resolving installed executables by name."""
    return package_exe


@pytest.fixture
def ros_env():
    """
    Environment for child processes: a fresh ``ROS_DOMAIN_ID`` and localhost-only DDS.

    The domain is held (see :func:`next_domain_id`) until the test's processes are gone.

    :returns: a dict to pass as ``env=`` to subprocesses; the test process itself is not changed.
    """
    domain = next_domain_id()
    env = dict(os.environ)
    env['ROS_DOMAIN_ID'] = str(domain)
    env['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    env['PYTHONUNBUFFERED'] = '1'
    env.pop('ROS_LOCALHOST_ONLY', None)
    if _SHELL_MUJOCO_GL is None:
        env.pop('MUJOCO_GL', None)
    yield env
    release_domain_id(domain)


def stop_daemon(domain):
    """
    Stop the ``ros2`` daemon of ``domain`` if one runs (a graph verb started it).

    The daemon outlives the command that started it, as ros2cli's; a test's must not outlive
    the test: asked to end (``amr_description.cli.daemon.stop_daemon``), killed if it does not.
    """
    from amr_description.cli.daemon import running_daemon
    from amr_description.cli.daemon import stop_daemon as ask_to_stop
    proxy = running_daemon(domain)
    if proxy is None:
        return
    stopped, pid = ask_to_stop(proxy, domain)
    if not stopped and pid is not None:
        os.kill(pid, signal.SIGKILL)


def run_until(argv, env, check, timeout=90.0, **kwargs):
    """
    Run a command again and again until its result passes ``check`` (for graph queries).

    A fresh ``ros2`` process answers from what its own discovery found in its spin time; on a
    loaded machine that can miss a node or an endpoint that exists. This waits for the
    observed answer instead of trusting one snapshot.

    :param argv: command line, a list of str.
    :param env: environment dict.
    :param check: callable ``check(completed_process) -> bool``.
    :param timeout: seconds to keep trying.
    :param kwargs: extra :func:`subprocess.run` arguments.
    :returns: the last :class:`subprocess.CompletedProcess` (``check`` may be false on it).
    """
    deadline = time.monotonic() + timeout
    while True:
        result = subprocess.run(argv, env=env, capture_output=True, text=True,
                                timeout=max(60.0, timeout), **kwargs)
        if check(result) or time.monotonic() >= deadline:
            return result


def launched_pids(log_text):
    """Return the pids a launch log names (``process started with pid [N]``), as ints."""
    import re
    return [int(p) for p in re.findall(r'process started with pid \[(\d+)\]', log_text)]


def left_running(pids, timeout=30.0):
    """Wait up to ``timeout`` s for ``pids`` to end; return those still running."""
    def alive(pid):
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True

    deadline = time.monotonic() + timeout
    while any(alive(p) for p in pids) and time.monotonic() < deadline:
        time.sleep(0.1)
    return [p for p in pids if alive(p)]


def _default_sigint():
    """
    Give the child SIGINT's default action (run in the child before exec).

    A suite started with SIGINT ignored (``nohup ... &`` in a script) would pass that on to
    every child; Python then installs no ``KeyboardInterrupt`` handler, and the tests'
    Ctrl-C would be ignored by every program that relies on it (as upstream ros2cli does).
    """
    signal.signal(signal.SIGINT, signal.SIG_DFL)


class Proc:
    """A started child process whose combined stdout/stderr goes to a temporary file."""

    def __init__(self, argv, env, cwd=None, stdin=subprocess.DEVNULL):
        """
        Start ``argv`` in a new session (its own process group).

        :param argv: command line, a list of str.
        :param env: environment dict.
        :param cwd: working directory or None.
        :param stdin: stdin for the child (default: /dev/null).
        """
        self.argv = list(argv)
        self._log = tempfile.NamedTemporaryFile(prefix='amr_test_', suffix='.log', delete=False)
        self.popen = subprocess.Popen(
            self.argv, env=env, cwd=cwd, stdin=stdin, stdout=self._log,
            stderr=subprocess.STDOUT, start_new_session=True, preexec_fn=_default_sigint)

    @property
    def output(self):
        """Return everything the process printed so far, as str."""
        with open(self._log.name, 'r', errors='replace') as f:
            return f.read()

    def wait_for_output(self, text, timeout=60.0):
        """
        Wait until ``text`` appears in the output.

        :param text: substring to wait for.
        :param timeout: seconds to wait.
        :returns: True when seen, False on timeout or when the process exited without it.
        """
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if text in self.output:
                return True
            if self.popen.poll() is not None:
                return text in self.output
            time.sleep(0.05)
        return False

    def wait(self, timeout=30.0):
        """Wait for exit and return the exit code (None if still running after ``timeout``)."""
        try:
            return self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def interrupt(self, timeout=30.0):
        """Send SIGINT (Ctrl-C) to the process group and return the exit code (None on timeout)."""
        if self.popen.poll() is None:
            os.killpg(self.popen.pid, signal.SIGINT)
        return self.wait(timeout)

    def kill(self):
        """SIGKILL the whole process group (no-op when already gone) and remove the log."""
        try:
            os.killpg(self.popen.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.popen.wait()
        try:
            os.unlink(self._log.name)
        except OSError:
            pass


@pytest.fixture
def procs(ros_env):
    """
    Start processes with ``procs.start(argv, env)``; all are killed when the test ends.

    :returns: an object with ``start(argv, env, **kwargs) -> Proc``.
    """
    started = []

    class _Runner:

        def start(self, argv, env, **kwargs):
            proc = Proc(argv, env, **kwargs)
            started.append(proc)
            return proc

    yield _Runner()
    for proc in started:
        if proc.popen.poll() is None:
            proc.interrupt(timeout=5.0)
        proc.kill()


@pytest.fixture
def ros():
    """In-process rclpy on a fresh domain: ``(make(name) -> Node, spin_until(cond, timeout))``."""
    import rclpy
    import rclpy.executors
    import rclpy.node
    os.environ['ROS_DOMAIN_ID'] = str(next_domain_id())
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    context = rclpy.context.Context()
    rclpy.init(context=context)
    executor = rclpy.executors.SingleThreadedExecutor(context=context)
    nodes = []

    def make(name):
        node = rclpy.node.Node(name, context=context)
        executor.add_node(node)
        nodes.append(node)
        return node

    def spin_until(condition, timeout=30.0):
        deadline = time.monotonic() + timeout
        while not condition() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
        return condition()

    yield make, spin_until
    for node in nodes:
        node.destroy_node()
    executor.shutdown()
    rclpy.shutdown(context=context)
