# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""One measurement per robot count: start-up, real time, fast-forward, raw mj_step."""

import math
import os
import time

from amr_description.tools.benchmark.common import BenchmarkError
from amr_description.tools.benchmark.common import cpu_seconds
from amr_description.tools.benchmark.common import DEFAULT_ROBOTS
from amr_description.tools.benchmark.common import namespaces
from amr_description.tools.benchmark.common import raw_step_rate
from amr_description.tools.benchmark.common import repo_root
from amr_description.tools.benchmark.common import TURN_TWIST
from amr_description.tools.benchmark.common import wheel_speeds
from amr_description.tools.benchmark.observer import Observer
from amr_description.tools.benchmark.stack import Stack


def measure(count, rtf, duration, domain_id, log, startup_timeout=120.0, extra=(),
            listen=()):
    """
    Bring a stack up, drive every robot, measure, stop it.

    ``extra``: more launch arguments of the stack (``name:=value``); ``listen``: topics the
    observer subscribes to (:class:`~amr_description.tools.benchmark.observer.Observer`).

    :returns: dict ``startup`` (s), ``speed`` (sim s per wall s), ``cpu_sim`` and
        ``cpu_stack`` (cores, over the window).
    :raises BenchmarkError: on a failed stage (see the module docstring).
    """
    stack = Stack(count, rtf, domain_id, extra)
    observer = None
    try:
        startup = stack.wait_active(timeout=startup_timeout + 3.0 * count)
        log(f'  {stack.stage}: controllers active after {startup:.2f} s')
        observer = Observer(domain_id, namespaces(count), listen)
        first = observer.clock_sample()
        if first is None:
            stack.check('measuring')
            raise BenchmarkError(f'measuring, {stack.stage}', 'no /clock within 10 s',
                                 stack.output('mujoco_sim-1'))
        observer.wait(1.0, first[1])  # every robot under way before the window opens
        pids_sim, pids_all = stack.pids('mujoco_sim'), stack.pids()
        cpu0 = {p: cpu_seconds(p) for p in pids_all}
        start = observer.clock_sample()
        wall0 = time.monotonic()
        observer.wait(duration, first[1])
        end = observer.clock_sample()
        cpu1 = {p: cpu_seconds(p) for p in pids_all}
        wall = time.monotonic() - wall0
        stack.check('measuring')
        if start is None or end is None or end[0] <= start[0]:
            raise BenchmarkError(f'measuring, {stack.stage}', 'no /clock during the window',
                                 stack.output('mujoco_sim-1'))

        def cores(pids):
            used = [cpu1[p] - cpu0[p] for p in pids
                    if cpu0.get(p) is not None and cpu1.get(p) is not None]
            return sum(used) / wall

        return {'startup': startup, 'speed': (end[1] - start[1]) / (end[0] - start[0]),
                'cpu_sim': cores(pids_sim), 'cpu_stack': cores(pids_all)}
    finally:
        if observer is not None:
            observer.close()
        stack.close()


def run(robots=DEFAULT_ROBOTS, duration=10.0, domain_id=0, log=print, viewer=True):
    """
    Measure every N of ``robots``; return a list of row dicts (see :func:`report`).

    :raises BenchmarkError: on the first failed stage; nothing is retried.
    """
    root = repo_root()
    with open(os.path.join(root, 'urdf', 'amr.urdf')) as f:
        urdf = f.read()
    wheels = wheel_speeds(TURN_TWIST, os.path.join(root, 'config', 'controllers.yaml'))
    rows = []
    for count in robots:
        log(f'N = {count}: load average {os.getloadavg()[0]:.2f}')
        row = {'robots': count, 'load': [os.getloadavg()[0]]}
        real = measure(count, 1.0, duration, domain_id, log)
        log(f'  real time: rtf {real["speed"]:.3f}, mujoco_sim {100 * real["cpu_sim"]:.0f} % '
            f'of a core')
        fast = measure(count, 0.0, duration, domain_id, log)
        log(f'  fast-forward: {fast["speed"]:.1f}x real time')
        try:
            raw = raw_step_rate(urdf, count, wheels, seconds=min(5.0, duration)) * 0.001
        except Exception as exc:  # noqa: B902 - reported as the stage that failed
            raise BenchmarkError(f'raw mj_step, {count} robots', repr(exc)) from None
        log(f'  raw mj_step: {raw:.1f}x real time')
        row['load'].append(os.getloadavg()[0])
        row.update(rtf=real['speed'], cpu_sim=real['cpu_sim'], cpu_stack=real['cpu_stack'],
                   fast=fast['speed'], raw=raw,
                   startup=min(real['startup'], fast['startup']),
                   startups=(real['startup'], fast['startup']))
        rows.append(row)
    base = next((r for r in rows if r['robots'] == 1), None)
    for row in rows:
        row['cost'] = 1.0 / (row['fast'] * row['robots']) if row['fast'] > 0 else math.inf
        row['cost_rel'] = row['cost'] / base['cost'] if base else None
    if viewer and rows:
        log('viewer: 1 robot in real time with the viewer and a headless browser ...')
        rows[0]['viewer'] = measure_viewer(duration, domain_id, log)
        log(f'  rtf {rows[0]["viewer"]["rtf"]:.4f}, viewer '
            f'{100 * rows[0]["viewer"]["viewer_cpu"]:.1f} % of a core')
    return rows


def measure_viewer(duration, domain_id, log):
    """
    Run part (d); return ``{'rtf': float, 'viewer_cpu': fraction of a core}``.

    :raises BenchmarkError: when the viewer page could not be opened or no /clock came.
    """
    from amr_description.tools.benchmark.viewer_cost import viewer_cost
    lines = []
    try:
        result = viewer_cost(domain_id, os.path.join(repo_root(), 'urdf', 'amr.urdf'),
                             duration, log=lines.append)
    except Exception as exc:  # noqa: B902 - reported as the stage that failed
        raise BenchmarkError('viewer, 1 robot, rtf 1', repr(exc), '\n'.join(lines)) from None
    if result['viewer_cpu'] is None or not result['rtf'] > 0:
        raise BenchmarkError('viewer, 1 robot, rtf 1', 'the viewer page was not measured',
                             '\n'.join(lines))
    return result
