# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The benchmark's table, targets, report in docs/benchmark.md and command line."""

import argparse
import datetime
import os
import sys

from amr_description.tools import benchmark
from amr_description.tools.benchmark import world_cost
from amr_description.tools.benchmark.common import BenchmarkError
from amr_description.tools.benchmark.common import DEFAULT_ROBOTS
from amr_description.tools.benchmark.common import repo_root
from amr_description.tools.benchmark.common import TARGETS
from amr_description.tools.benchmark.measure import run


def format_table(rows):
    """Return the printed/Markdown table of :func:`run` rows (str)."""
    lines = [
        '| N | start-up s | real time: rtf held | mujoco_sim CPU / robot | stack CPU / robot '
        '| fast: x real time | cost / robot-s vs N=1 | raw mj_step x real time '
        '| fast / raw | load avg |',
        '|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        rel = f'{r["cost_rel"]:.2f}' if r['cost_rel'] is not None else '-'
        lines.append(
            f'| {r["robots"]} | {r["startup"]:.2f} | {r["rtf"]:.3f} | '
            f'{100 * r["cpu_sim"] / r["robots"]:.1f} % | '
            f'{100 * r["cpu_stack"] / r["robots"]:.1f} % | {r["fast"]:.1f}x | {rel} | '
            f'{r["raw"]:.1f}x | {100 * r["fast"] / r["raw"]:.0f} % | '
            f'{r["load"][0]:.1f} -> {r["load"][1]:.1f} |')
    return '\n'.join(lines)


def targets(rows):
    """Return ``(description, measured text, passed)`` for every target whose N was run."""
    by_n = {r['robots']: r for r in rows}
    out = []
    if 16 in by_n:
        r = by_n[16]
        out.append(('16 robots, real time: rtf >= 1.0 (paced to 1.0, 1 % tolerance)',
                    f'{r["rtf"]:.3f}',
                    r['rtf'] >= 0.99 * TARGETS['rtf16']))
        if r['cost_rel'] is not None:
            out.append(('16 robots, fast: cost per robot-second <= 1.3x linear',
                        f'{r["cost_rel"]:.2f}x', r['cost_rel'] <= TARGETS['linear16']))
        out.append(('16 robots: all controllers active < 10 s', f'{r["startup"]:.2f} s',
                    r['startup'] < TARGETS['startup16']))
    viewer = next((r['viewer'] for r in rows if r.get('viewer')), None)
    if viewer is not None:
        out.append(('1 robot + viewer + browser: rtf >= 0.99, viewer < 20 % of a core',
                    f'{viewer["rtf"]:.4f}, {100 * viewer["viewer_cpu"]:.1f} %',
                    viewer['rtf'] >= TARGETS['viewer_rtf'] and
                    viewer['viewer_cpu'] < TARGETS['viewer_cpu']))
    if 1 in by_n:
        r = by_n[1]
        out.append(('1 robot, fast: >= 60 % of raw mj_step', f'{100 * r["fast"] / r["raw"]:.0f} %',
                    r['fast'] / r['raw'] >= TARGETS['raw1']))
        out.append(('1 robot: both controllers active < 2 s', f'{r["startup"]:.2f} s',
                    r['startup'] < TARGETS['startup1']))
    return out


def report(rows, duration, argv, worlds=''):
    """Return the Markdown page of the :func:`format_table` rows and the targets (str)."""
    load = ', '.join(f'N={r["robots"]}: {r["load"][0]:.1f} -> {r["load"][1]:.1f}' for r in rows)
    lines = [
        '# Simulation benchmark: scaling with the number of robots', '',
        f'Measured {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC with '
        f'`scripts/benchmark_sim {" ".join(argv)}` (window {duration:g} s per mode) on '
        f'{os.cpu_count()} CPU cores. 1-minute load average before -> after each N: {load}.',
        '',
        'Each N runs two fresh stacks (real time, then as fast as possible) under the '
        'orchestrator: the `sim` stack for N = 1, the `fleet` stack (`robots:=N`, 2 m grid) '
        'for N > 1; every robot drives a 0.6 m circle (0.3 m/s, 0.5 rad/s) on its own '
        '`cmd_vel`. Start-up: stack start until every spawner exited 0 (the smaller of the '
        'two runs). CPU: user + system time from /proc of mujoco_sim and of every process '
        'of the stack over the window, per robot, in % of one core. Cost per robot-second = '
        '1 / (x real time * N), relative to N = 1 (1.00 = linear). Raw mj_step: the same '
        'N-robot world stepped in the benchmark process with the same wheel speeds.', '',
        format_table(rows), '',
        '| target | measured | |', '|---|---|---|',
    ]
    lines += [f'| {d} | {m} | {"PASS" if ok else "FAIL"} |' for d, m, ok in targets(rows)]
    if worlds:
        lines += ['', '## World cost', '', 'Loading each shipped world and the physics rate of '
                  'one robot turning in it, side by side in the benchmark process '
                  '(`amr_description/tools/benchmark/world_cost.py`):', '', worlds]
    lines += ['', 'A loaded machine (other work running) lowers every figure; re-run '
              '`scripts/benchmark_sim` on a quiet machine for reference values. A stage '
              'that fails stops the benchmark with the captured error and leaves this page '
              'unchanged.', '']
    return '\n'.join(lines)


BEGIN = '<!-- benchmark_sim: generated from here -->'
END = '<!-- benchmark_sim: generated up to here -->'


def write_report(path, text):
    """
    Write ``text`` between the :data:`BEGIN` and :data:`END` markers of ``path``.

    What the file holds outside the markers (method notes, profiles, history) is kept; a
    file without markers gets the block at its top.

    :param path: the Markdown file.
    :param text: the generated report.
    """
    try:
        with open(path) as f:
            old = f.read()
    except FileNotFoundError:
        old = ''
    block = f'{BEGIN}\n{text.rstrip()}\n{END}\n'
    if BEGIN in old and END in old:
        head, rest = old.split(BEGIN, 1)
        new = head + block + rest.split(END, 1)[1].lstrip('\n')
    else:
        new = block + ('\n' + old if old else '')
    with open(path, 'w') as f:
        f.write(new)


def _robot_list(text):
    try:
        values = [int(v) for v in text.split(',') if v.strip()]
    except ValueError:
        values = []
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError(f'expected a comma-separated list of robot counts '
                                         f'>= 1, got {text!r}')
    return values


def main(args=None):
    """Run the benchmark, print the ratios, write the report; 0, or 1 on a failed stage."""
    argv = list(sys.argv[1:] if args is None else args)
    parser = argparse.ArgumentParser(prog='benchmark_sim',
                                     description=benchmark.__doc__.split('\n')[1])
    parser.add_argument('--robots', type=_robot_list, default=list(DEFAULT_ROBOTS),
                        help='robot counts to run, e.g. 1,2,4 (default 1,2,4,8,16,32)')
    parser.add_argument('--duration', type=float, default=10.0,
                        help='measuring window of each mode in wall seconds (10)')
    parser.add_argument('--domain', type=int,
                        default=int(os.environ.get('ROS_DOMAIN_ID', '0') or 0),
                        help='ROS domain of the stacks (default $ROS_DOMAIN_ID or 0)')
    parser.add_argument('--no-viewer', action='store_true',
                        help='leave out part (d), the viewer with a headless browser')
    parser.add_argument('--no-worlds', action='store_true',
                        help='leave out the world cost (shipped worlds, one robot, no ROS)')
    parser.add_argument('--output', default=os.path.join(repo_root(), 'docs', 'benchmark.md'),
                        help='Markdown report to write ("" = none)')
    opts = parser.parse_args(argv)
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    log = lambda m: print(m, flush=True)  # noqa: E731
    try:
        rows = run(opts.robots, opts.duration, opts.domain, log=log, viewer=not opts.no_viewer)
    except BenchmarkError as exc:
        print(f'benchmark_sim: FAILED at {exc}', file=sys.stderr, flush=True)
        if exc.output:
            print(exc.output, file=sys.stderr, flush=True)
        print('benchmark_sim: no figures reported, ' +
              (f'{opts.output} left unchanged' if opts.output else 'no report written'),
              file=sys.stderr, flush=True)
        return 1
    worlds = ''
    if not opts.no_worlds:
        log('world cost: empty, arena, warehouse, one robot, 5 interleaved repeats')
        worlds, _ = world_cost.format_rows(world_cost.run(['empty', 'arena', 'warehouse']))
    print()
    print(format_table(rows))
    for description, measured, ok in targets(rows):
        print(f'{description}: {measured} {"PASS" if ok else "FAIL"}')
    if worlds:
        print(worlds)
    if opts.output:
        write_report(opts.output, report(rows, opts.duration, argv, worlds))
        print(f'written {opts.output}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
