# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Cost of the ``navigation`` stack composed in one process and as one process per node.

The ``navigation`` stack (simulator, map_server, AMCL, costmaps, the Nav2 servers, both
lifecycle managers, the viewer with its page open in headless Debian chromium) runs twice on
a private domain, with ``use_composition:=True`` (nav2_bringup's default: every Nav2 node in
one ``component_container_isolated``) and ``use_composition:=False``, one after the other in
the same run. For each: the CPU share (% of one core, from ``/proc``) of every process and of
the Nav2 processes together, and the real-time factor (sim seconds over wall seconds of
``/clock``), first with the robot standing (``--seconds`` of wall time after the managers
said "Managed nodes are active" and ``--warmup`` seconds), then while it drives to a
NavigateToPose goal (``--seconds`` after the goal was accepted). The last line is the ratio
of the Nav2 processes' CPU, composed over separate.

Run: ``python -m amr_description.tools.benchmark.nav_composition [--world W] [--seconds S]``;
the figures are in docs/navigation.md.
"""

import argparse
import time

from amr_description.tools.benchmark.nav_cost import free_port
from amr_description.tools.benchmark.nav_cost import private_session
from amr_description.tools.benchmark.nav_cost import process_cpu
from amr_description.tools.benchmark.nav_cost import start_stack
from amr_description.tools.benchmark.nav_cost import wait_for_line

GOALS = {'warehouse': (4.9, 2.0), 'arena': (2.5, 0.5)}
"""A goal per world (map frame, m) whose path takes longer than the measured window."""

NOT_NAV2 = ('mujoco_sim', 'viewer', 'robot_state_publisher', 'spawner', 'create')
"""Processes of the stacks that are not Nav2's (the rest are summed as "Nav2")."""


def _window(observer, orchestrators, seconds, spin=None):
    """
    Spin ``seconds`` of wall time; return RTF and ``{process: % of one core}``.

    ``spin(seconds)``, when given, spins instead of ``observer.spin_for`` (to act meanwhile).
    """
    cpu0, sim0, wall0 = process_cpu(orchestrators), observer.sim_time, time.monotonic()
    if spin is None:
        observer.spin_for(seconds, drive=False)
    else:
        spin(seconds)
    cpu1, sim1, wall1 = process_cpu(orchestrators), observer.sim_time, time.monotonic()
    wall = wall1 - wall0
    cpu = {name: 100.0 * (cpu1[name] - cpu0.get(name, 0.0)) / wall for name in cpu1}
    return (sim1 - sim0) / wall, cpu


def _nav2_share(cpu):
    return sum(v for k, v in cpu.items() if k not in NOT_NAV2)


def _line(label, rtf, cpu):
    parts = ', '.join(f'{k} {v:.1f}' for k, v in sorted(cpu.items(), key=lambda kv: -kv[1]))
    return (f'{label}: RTF {rtf:.3f}; Nav2 processes {_nav2_share(cpu):.1f} % of one core '
            f'({parts})')


def _stage(composed, world, seconds, warmup, env, observer, stream):
    """Run the stack once; return ``(idle figures, driving figures, goal status)``."""
    from amr_description.tools.screenshot import browser_page
    from nav2_msgs.action import NavigateToPose
    from rclpy.action import ActionClient
    port = free_port()
    stack, lines = start_stack('navigation', [f'world:={world}', f'viewer_port:={port}',
                                              f'use_composition:={composed}'], env, stream)
    client = ActionClient(observer.node, NavigateToPose, 'navigate_to_pose')
    try:
        wait_for_line(lines, '[lifecycle_manager_navigation]: Managed nodes are active',
                      observer, 240.0)
        with browser_page(f'http://127.0.0.1:{port}', {'width': 1000, 'height': 700}, 60000):
            observer.spin_for(warmup, drive=False)
            idle = _window(observer, [stack], seconds)
            goal = NavigateToPose.Goal()
            goal.pose.header.frame_id = 'map'
            goal.pose.pose.position.x, goal.pose.pose.position.y = GOALS.get(world, (1.0, 0.0))
            goal.pose.pose.orientation.w = 1.0
            if not client.wait_for_server(timeout_sec=60.0):
                raise RuntimeError('navigate_to_pose: no action server in 60 s')
            future = client.send_goal_async(goal)
            end = time.monotonic() + 60.0
            while not future.done() and time.monotonic() < end:
                observer.spin_for(0.1, drive=False)
            if not future.done() or not future.result().accepted:
                raise RuntimeError('navigate_to_pose: goal not accepted')
            driving = _window(observer, [stack], seconds)
            handle = future.result()
            status = handle.get_result_async()
            observer.spin_for(0.5, drive=False)
            handle.cancel_goal_async()
            observer.spin_for(1.0, drive=False)
        return idle, driving, status.done()
    finally:
        client.destroy()
        stack.shutdown()
        stack.wait(timeout=60.0)


def run(world='warehouse', seconds=30.0, warmup=10.0, domain_id=212, log=print):
    """
    Run both stages; return their lines (also passed to ``log``).

    :param world: the world (a shipped name).
    :param seconds: wall seconds of each measured window (idle, driving).
    :param warmup: wall seconds with the page open before the idle window.
    :param domain_id: the private ROS domain.
    :returns: list of str.
    """
    out = []
    shares = {}
    with private_session(domain_id, 'amr_nav_composition_') as (env, _, stream, observer):
        for composed in (True, False):
            idle, driving, _ = _stage(composed, world, seconds, warmup, env, observer, stream)
            label = f'navigation in {world}, use_composition:={composed}'
            for name, (rtf, cpu) in (('standing', idle), ('driving to a goal', driving)):
                out.append(_line(f'{label}, {name}', rtf, cpu))
                log(out[-1])
                shares[composed, name] = _nav2_share(cpu)
        for name in ('standing', 'driving to a goal'):
            ratio = shares[True, name] / max(shares[False, name], 1e-9)
            out.append(f'Nav2 processes composed / separate, {name}: {ratio:.2f}')
            log(out[-1])
    return out


def main(argv=None):
    """Parse the arguments and print the figures."""
    parser = argparse.ArgumentParser(prog='nav_composition',
                                     description=__doc__.splitlines()[1])
    parser.add_argument('--world', default='warehouse', help='world (warehouse)')
    parser.add_argument('--seconds', type=float, default=30.0,
                        help='wall seconds of each measured window (30)')
    args = parser.parse_args(argv)
    run(args.world, args.seconds)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
