# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Start-up stress run of the sim stack under CPU load (``scripts/stress_startup``).

Starts ``ros2 launch amr_description sim`` (fast-forward, headless, no browser viewer) again
and again on one ROS domain, while ``--hogs`` busy processes load the cores. A run passes when
the spawners log both controllers active within ``--timeout`` s and, after Ctrl-C, the stack
exits 0. A run *crashed* when any output shows a traceback, ``InvalidHandle``, a FATAL log,
a stopped simulation thread, or ``mujoco_sim`` reported dead; a run that merely did not come
up in time (e.g. ``create`` timing out while robot_state_publisher starts on a saturated
machine) is counted apart. Prints one line per run (with the output of failed runs) and
``crashes: N/RUNS``; exits 1 when any run crashed.

    scripts/stress_startup --runs 50 --hogs 2
"""

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time

CRASH = ('Traceback', 'InvalidHandle', 'FATAL', 'simulation thread stopped',
         '[ERROR] [mujoco_sim-1]: process has died')
READY = 'Configured and activated diff_drive_controller'


def _hog():
    """Start one busy process (a CPU hog) in its own session."""
    return subprocess.Popen([sys.executable, '-c', 'while True:\n    pass'],
                            start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)


def _ros2():
    """Return the path of this package's ``ros2`` command (ament index)."""
    from ament_index_python.packages import get_package_prefix
    return os.path.join(get_package_prefix('amr_description'), 'lib', 'amr_description', 'ros2')


def _kill(proc):
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.wait()


def run_once(domain_id, timeout, rtf='0.0'):
    """
    Start the sim stack once, wait for both controllers, stop it.

    :param domain_id: ROS domain ID of the run.
    :param timeout: seconds allowed to reach both controllers active.
    :param rtf: the stack's ``rtf`` argument.
    :returns: ``(ok, seconds to active or None, reason, output)``.
    """
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST', PYTHONUNBUFFERED='1')
    with tempfile.TemporaryFile() as log:
        start = time.monotonic()
        proc = subprocess.Popen([_ros2(), 'launch', 'amr_description', 'sim', f'rtf:={rtf}',
                                 'headless:=true', 'viewer:=false'], env=env, stdout=log,
                                stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                start_new_session=True)

        def output():
            log.seek(0)
            return log.read().decode(errors='replace')
        ready = None
        reason = ''
        try:
            while time.monotonic() - start < timeout:
                text = output()
                if READY in text:
                    ready = time.monotonic() - start
                    break
                if proc.poll() is not None:
                    reason = f'stack exited with {proc.returncode} before the controllers'
                    break
                if any(bad in text for bad in CRASH):
                    reason = 'crash during start-up'
                    break
                time.sleep(0.1)
            else:
                reason = f'controllers not active after {timeout:g} s'
            if ready is not None:
                time.sleep(1.0)  # the simulation and the executor keep working
                os.killpg(proc.pid, signal.SIGINT)
                try:
                    code = proc.wait(30)
                except subprocess.TimeoutExpired:
                    code = None
                if code != 0:
                    reason = f'stack exit code {code} after Ctrl-C'
        finally:
            if proc.poll() is None:
                _kill(proc)
        text = output()
        crash = [b for b in CRASH if b in text]
        if crash:
            reason = f'crash: {crash[0]!r} in the output' + (f' ({reason})' if reason else '')
        return not reason, ready, reason, text


def main(argv=None):
    """Run the stress loop (see the module docstring); returns the exit code."""
    parser = argparse.ArgumentParser(prog='stress_startup', description=__doc__.split('\n')[1])
    parser.add_argument('--runs', type=int, default=50)
    parser.add_argument('--hogs', type=int, default=2, help='busy processes running meanwhile')
    parser.add_argument('--timeout', type=float, default=60.0,
                        help='seconds allowed to reach both controllers active')
    parser.add_argument('--rtf', default='0.0', help="the sim stack's rtf argument")
    parser.add_argument('--domain', type=int,
                        default=int(os.environ.get('ROS_DOMAIN_ID') or 210),
                        help='ROS domain ID of the runs (default: $ROS_DOMAIN_ID, else 210)')
    opts = parser.parse_args(argv)
    hogs = [_hog() for _ in range(opts.hogs)]
    crashes = 0
    incomplete = 0
    times = []
    try:
        for index in range(opts.runs):
            ok, ready, reason, text = run_once(opts.domain, opts.timeout, opts.rtf)
            if ready is not None:
                times.append(ready)
            shown = f'{ready:.1f} s' if ready is not None else '-'
            print(f'run {index + 1}/{opts.runs}: {"ok" if ok else "FAIL"} '
                  f'(controllers active after {shown}){"" if ok else ": " + reason}',
                  flush=True)
            if not ok:
                if reason.startswith('crash'):
                    crashes += 1
                else:
                    incomplete += 1
                print(text, flush=True)
    finally:
        for hog in hogs:
            _kill(hog)
    times.sort()
    median = f'{times[len(times) // 2]:.1f} s' if times else '-'
    load = os.getloadavg()
    print(f'crashes: {crashes}/{opts.runs} (with {opts.hogs} CPU hogs; {incomplete} more did '
          f'not come up within {opts.timeout:g} s; median start-up to both controllers active '
          f'{median}; load average {load[0]:.2f})')
    return 1 if crashes else 0


if __name__ == '__main__':
    sys.exit(main())
