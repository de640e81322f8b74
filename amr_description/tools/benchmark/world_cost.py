# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What a world costs: loading it, and the physics rate of one robot driving in it.

Side by side in one run, in this process (no ROS): for the shipped ``empty`` and
``warehouse`` worlds (and any others named), interleaved ``--repeats`` times so that a
change of the machine's load hits both alike:

load
    wall time of :func:`~amr_description.core.gazebo.sdf_world.load_world` plus building and
    compiling the MuJoCo world (:class:`~amr_description.sim.world.World`); the smallest of
    the repeats.
step rate
    ``mujoco.mj_step`` calls per wall second for one robot (urdf/amr.urdf) spawned at the
    origin (clear of every shipped world's obstacles) turning in place (left wheels -5,
    right wheels 5 rad/s) for ``--steps`` steps; the largest of the repeats, and its ratio to
    the empty world's.

Usage: ``python -m amr_description.tools.benchmark.world_cost [--worlds empty,warehouse]
[--steps 5000] [--repeats 5]``. Targets (docs/worlds.md): warehouse load < 1 s; step rate
>= 90 % of the empty world's.
"""

import argparse
import os
import sys
import time

LOAD_TARGET = 1.0
"""Seconds: a shipped world loads in less."""

RATE_TARGET = 0.9
"""One robot in a shipped world keeps at least this share of its empty-world step rate."""


def measure(world_name, urdf, steps):
    """
    Return (load seconds, mj_step calls per second) of one world with one driving robot.

    :param world_name: a shipped world's name or a file (``world`` parameter).
    :param urdf: the robot's URDF text.
    :param steps: physics steps timed.
    """
    import mujoco
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import World
    start = time.perf_counter()
    description = load_world(world_name)
    world = World(description.physics_step, description)
    loaded = time.perf_counter() - start
    world.spawn(urdf_to_spec(urdf, name='amr', pose=(0, 0, 0.2, 0, 0, 0)), 'amr')
    for index in range(world.model.nu):  # turn in place: the left wheels back, the right on
        name = world.model.actuator(index).name
        world.data.ctrl[index] = -5.0 if '_left' in name else 5.0
    model, data = world.model, world.data
    start = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    return loaded, steps / (time.perf_counter() - start)


def run(names, steps=5000, repeats=5):
    """
    Measure every world side by side, interleaved ``repeats`` times (module docstring).

    :param names: world names or files; the first is the reference (``empty``).
    :returns: list of ``(name, load s, mj_step/s, ratio to the first)``.
    """
    from amr_description.core.description.files import read_description
    from amr_description.tools.benchmark.common import repo_root
    urdf = read_description(os.path.join(repo_root(), 'urdf', 'amr.urdf'))
    loads = {n: [] for n in names}
    rates = {n: [] for n in names}
    for _ in range(repeats):
        for name in names:
            loaded, rate = measure(name, urdf, steps)
            loads[name].append(loaded)
            rates[name].append(rate)
    base = max(rates[names[0]])
    return [(n, min(loads[n]), max(rates[n]), max(rates[n]) / base) for n in names]


def format_rows(rows):
    """Return the Markdown table of :func:`run` rows and its targets line, and whether met."""
    lines = [f'| world | load (s) | mj_step/s, one robot | vs {rows[0][0]} |',
             '| --- | --- | --- | --- |']
    ok = True
    for name, load, rate, ratio in rows:
        ok = ok and load < LOAD_TARGET and ratio >= RATE_TARGET
        lines.append(f'| {name} | {load:.4f} | {rate:,.0f} | {ratio:.3f} |')
    lines.append(f'targets: load < {LOAD_TARGET:g} s, step rate >= {RATE_TARGET:.0%} of '
                 f'{rows[0][0]}: {"PASS" if ok else "FAIL"}')
    return '\n'.join(lines), ok


def main(args=None):
    """Measure and print the table; return 0 when every target holds, else 1."""
    parser = argparse.ArgumentParser(prog='world_cost', description=__doc__.split('\n')[1])
    parser.add_argument('--worlds', default='empty,arena,warehouse')
    parser.add_argument('--steps', type=int, default=5000)
    parser.add_argument('--repeats', type=int, default=5)
    opts = parser.parse_args(args)
    text, ok = format_rows(run([n for n in opts.worlds.split(',') if n], opts.steps,
                               opts.repeats))
    print(text)
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
