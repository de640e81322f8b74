# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
How long the daily ``ros2`` verbs take against the running sim stack, with and without daemon.

Brings the ``sim`` stack up (real time, no viewer), starts ``ros2 daemon`` and lets it follow
the graph for :data:`WARM` s, then runs each verb ``--repeats`` times with the warm daemon and
``--repeats`` times with ``--no-daemon`` (interleaved, so that a change of the machine's load
hits both alike) and prints the median wall time of each, side by side, against the targets
of the issue (upstream ros2cli 0.32.2 measured on this kind of machine with its daemon:
``topic list`` 0.31 s, ``node list`` 0.30 s, ``topic echo --once`` 0.97 s,
``control list_controllers`` 0.97 s). The time is the whole process, start to exit, as a user
waits for it. ``ros2 control`` has no ``--no-daemon``: both columns run the same command.

Usage: ``python -m amr_description.tools.benchmark.cli_speed [--repeats 5] [--domain-id 96]``.
"""

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

WARM = 4.0
"""Seconds the daemon follows the graph before the first measurement."""
VERBS = (
    ('topic list', ('topic', 'list'), 0.4, True),
    ('node list', ('node', 'list'), 0.4, True),
    ('service list', ('service', 'list'), None, True),
    ('topic echo --once /odom (50 Hz)', ('topic', 'echo', '--once', '/odom'), 1.0, True),
    ('control list_controllers', ('control', 'list_controllers'), 1.0, False),
)
"""(label, ros2 arguments, target s or None, whether the verb takes --no-daemon)."""


def _time(argv, env):
    """Return (wall seconds, CompletedProcess) of one run of ``argv``."""
    start = time.perf_counter()
    result = subprocess.run(argv, env=env, capture_output=True, text=True, timeout=120)
    return time.perf_counter() - start, result


def main(argv=None):
    """Print the table; return 0 (targets are reported, not fatal), 1 when a verb failed."""
    parser = argparse.ArgumentParser(prog='cli_speed', description=__doc__.splitlines()[1])
    parser.add_argument('--repeats', type=int, default=5, help='runs per verb and mode (5)')
    parser.add_argument('--domain-id', type=int, default=96, help='ROS domain (96)')
    opts = parser.parse_args(argv)
    from amr_description.tools.benchmark.stack import Stack
    os.environ['ROS_DOMAIN_ID'] = str(opts.domain_id)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    env = dict(os.environ)
    ros2 = shutil.which('ros2', path=env.get('PATH'))
    if ros2 is None:
        print('cli_speed: no ros2 on PATH: source scripts/env.sh', file=sys.stderr)
        return 1
    stack = Stack(1, 1.0, opts.domain_id)
    try:
        stack.wait_active(timeout=120.0)
        started = subprocess.run([ros2, 'daemon', 'start'], env=env, capture_output=True,
                                 text=True, timeout=60)
        print(f'[cli_speed] {started.stdout.strip()}; warming {WARM:g} s', flush=True)
        time.sleep(WARM)
        times = {(label, mode): [] for label, *_ in VERBS for mode in ('daemon', 'direct')}
        for repeat in range(opts.repeats):
            for label, args, _, flag in VERBS:
                for mode in ('daemon', 'direct'):
                    extra = ('--no-daemon',) if mode == 'direct' and flag else ()
                    seconds, result = _time([ros2, *args, *extra], env)
                    if result.returncode != 0 or not result.stdout.strip():
                        print(f'[cli_speed] ros2 {" ".join(args + extra)} failed: '
                              f'{result.stderr.strip()[-300:]}', file=sys.stderr)
                        return 1
                    times[(label, mode)].append(seconds)
            print(f'[cli_speed] repeat {repeat + 1}/{opts.repeats} done', flush=True)
        print()
        print(f'{"verb":34} {"daemon":>8} {"--no-daemon":>12} {"target":>8}')
        for label, _, target, flag in VERBS:
            warm = statistics.median(times[(label, 'daemon')])
            direct = statistics.median(times[(label, 'direct')])
            verdict = '' if target is None else ('PASS' if warm <= target else 'MISSED')
            print(f'{label:34} {warm:7.2f}s {direct:11.2f}s '
                  f'{"" if target is None else f"<= {target:.1f}s":>8} {verdict}'
                  + ('' if flag else '  (no --no-daemon: the same command)'))
        print(f'medians of {opts.repeats} runs; load {os.getloadavg()[0]:.2f} (1-minute '
              f'average), {os.cpu_count()} CPUs')
    finally:
        subprocess.run([ros2, 'daemon', 'stop'], env=env, capture_output=True, timeout=60)
        stack.close()
    return 0


if __name__ == '__main__':
    sys.exit(main())
