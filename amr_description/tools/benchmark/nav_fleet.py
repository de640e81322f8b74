# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Real-time factor of fleets navigating at once: one namespaced Nav2 per robot.

The ``fleet`` stack with ``navigation:=true`` in arena.sdf (simulator, the robots'
robot_state_publishers, and per robot ``rI`` map_server, AMCL, costmaps and the Nav2 servers
composed in ``/rI/nav2_container``; the viewer with its page open in headless Debian
chromium) runs once per robot count of ``--robots`` (default 1 and 4), one after the other in
the same run on a private domain. For each: the real-time factor (sim seconds over wall
seconds of ``/clock``) and the CPU share (% of one core, from ``/proc``) of every process,
first with the robots standing (``--seconds`` of wall time after every lifecycle manager said
"Managed nodes are active" and ``--warmup`` seconds), then while every robot shuttles between
its spawn and its goal of :data:`GOALS` (a NavigateToPose goal to ``/rI/navigate_to_pose``,
the next one as soon as the last ended), with the legs that succeeded and failed counted,
and the whole machine's busy share (all cores, ``/proc/stat``: the browser's CPU is not the
stack's). ``--no-viewer`` runs the stacks with ``viewer:=false`` and no browser.

Run: ``python -m amr_description.tools.benchmark.nav_fleet [--robots 1 4] [--seconds S]``;
the figures are in docs/navigation.md.
"""

import argparse
import math
import time

from amr_description.launch.stacks import fleet_grid
from amr_description.tools.benchmark.nav_composition import _window
from amr_description.tools.benchmark.nav_cost import free_port
from amr_description.tools.benchmark.nav_cost import private_session
from amr_description.tools.benchmark.nav_cost import start_stack

GOALS = [(0.5, 0.55), (2.7, -0.3), (0.5, 2.0), (2.7, 1.9)]
"""Goal of robot rI at index I - 1 in arena.sdf (map frame, m): about 0.7 m from its spawn on
the fleet's 2 m grid, in free space beside it (walls and pillars 0.5 m or more away)."""

NAV2 = 'component_container_isolated'
"""The process name of every robot's ``nav2_container`` (summed as "Nav2 processes")."""


class _Shuttle:
    """Send robot ``ns`` to its goal and back to its spawn, again and again; count the legs."""

    def __init__(self, node, ns, spawn, goal):
        from nav2_msgs.action import NavigateToPose
        from rclpy.action import ActionClient
        self.Goal = NavigateToPose.Goal
        self.client = ActionClient(node, NavigateToPose, f'/{ns}/navigate_to_pose')
        self.ns, self.ends = ns, (goal, spawn)
        self.legs = 0
        self.sent = self.handle = self.result = None
        self.succeeded = self.failed = 0

    def step(self):
        """Send the next leg when none runs; count the last one's result."""
        from action_msgs.msg import GoalStatus
        if self.result is not None and self.result.done():
            if self.result.result().status == GoalStatus.STATUS_SUCCEEDED:
                self.succeeded += 1
            else:
                self.failed += 1
            self.result = None
        if self.sent is not None and self.sent.done():
            self.handle, self.sent = self.sent.result(), None
            if self.handle.accepted:
                self.result = self.handle.get_result_async()
            else:
                self.failed += 1
        if self.sent is None and self.result is None:
            (x, y), (fx, fy) = self.ends[self.legs % 2], self.ends[(self.legs + 1) % 2]
            goal = self.Goal()
            goal.pose.header.frame_id = 'map'
            goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
            yaw = math.atan2(y - fy, x - fx)  # facing the way it drives
            goal.pose.pose.orientation.z = math.sin(yaw / 2.0)
            goal.pose.pose.orientation.w = math.cos(yaw / 2.0)
            self.sent = self.client.send_goal_async(goal)
            self.legs += 1

    def stop(self):
        """Cancel the running leg; drop the client."""
        if self.result is not None and not self.result.done():
            self.handle.cancel_goal_async()
        self.client.destroy()


def _machine_busy():
    """Return ``(busy, total)`` CPU jiffies of the whole machine (``/proc/stat``)."""
    with open('/proc/stat') as f:
        values = [int(v) for v in f.readline().split()[1:]]
    idle = values[3] + values[4]  # idle, iowait
    return sum(values) - idle, sum(values)


def _measured(window):
    """Run ``window()``; return its figures and the machine's busy share, % of all cores."""
    busy0, total0 = _machine_busy()
    figures = window()
    busy1, total1 = _machine_busy()
    return figures, 100.0 * (busy1 - busy0) / max(total1 - total0, 1)


def _shuttling(observer, shuttles):
    """Return a ``spin(seconds)`` that keeps every robot of ``shuttles`` on its legs."""
    def spin(seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            for shuttle in shuttles:
                shuttle.step()
            observer.executor.spin_once(timeout_sec=0.05)
    return spin


def _stage(count, seconds, warmup, env, observer, stream, log, viewer=True):
    """Run the fleet of ``count`` robots once; return its lines."""
    import contextlib
    from amr_description.tools.screenshot import browser_page
    port = free_port()
    stack, lines = start_stack('fleet', [f'robots:={count}', 'world:=arena', 'navigation:=true',
                                         f'viewer_port:={port}', f'viewer:={viewer}'],
                               env, stream)
    names = [f'r{i}' for i in range(1, count + 1)]
    shuttles = []
    out = []
    try:
        end = time.monotonic() + 300.0
        while sum('Managed nodes are active' in line for line in lines) < 2 * count:
            if time.monotonic() > end:
                raise RuntimeError(f'fleet of {count}: Nav2 not active in 300 s')
            observer.spin_for(0.2, drive=False)
        shuttles = [_Shuttle(observer.node, ns, spawn, goal) for ns, spawn, goal in
                    zip(names, fleet_grid(count, 2.0), GOALS)]
        for shuttle in shuttles:
            if not shuttle.client.wait_for_server(timeout_sec=60.0):
                raise RuntimeError(f'/{shuttle.ns}/navigate_to_pose: no action server in 60 s')
        page = browser_page(f'http://127.0.0.1:{port}', {'width': 1000, 'height': 700},
                            60000) if viewer else contextlib.nullcontext()
        with page:
            observer.spin_for(warmup, drive=False)
            standing = _measured(lambda: _window(observer, [stack], seconds))
            driving = _measured(lambda: _window(observer, [stack], seconds,
                                                _shuttling(observer, shuttles)))
        for label, ((rtf, cpu), busy) in (('standing', standing), ('navigating', driving)):
            parts = ', '.join(f'{k} {v:.1f}' for k, v in
                              sorted(cpu.items(), key=lambda kv: -kv[1]))
            where = 'arena' if viewer else 'arena (no viewer)'
            out.append(f'fleet of {count} in {where}, {label}: RTF {rtf:.3f}; Nav2 processes '
                       f'{cpu.get(NAV2, 0.0):.1f} % of one core ({parts}); machine '
                       f'{busy:.0f} % busy (all cores, the browser too)')
            log(out[-1])
        legs = ', '.join(f'{s.ns} {s.succeeded}/{s.succeeded + s.failed}' for s in shuttles)
        out.append(f'fleet of {count}: legs succeeded {legs}')
        log(out[-1])
        return out
    finally:
        for shuttle in shuttles:
            shuttle.stop()
        observer.spin_for(1.0, drive=False)
        stack.shutdown()
        stack.wait(timeout=60.0)


def run(robots=(1, 4), seconds=30.0, warmup=10.0, domain_id=213, log=print, viewer=True):
    """
    Run one stage per robot count; return their lines (also passed to ``log``).

    :param robots: robot counts, each at most ``len(GOALS)``.
    :param seconds: wall seconds of each measured window (standing, navigating).
    :param warmup: wall seconds with the page open before the standing window.
    :param domain_id: the private ROS domain.
    :param viewer: run the viewer with its page open in chromium.
    :returns: list of str.
    :raises ValueError: a count out of 1 ... ``len(GOALS)``.
    """
    if any(not 1 <= n <= len(GOALS) for n in robots):
        raise ValueError(f'--robots: expected counts from 1 to {len(GOALS)}, got {robots}')
    out = []
    with private_session(domain_id, 'amr_nav_fleet_') as (env, _, stream, observer):
        for count in robots:
            out += _stage(count, seconds, warmup, env, observer, stream, log, viewer)
    log(f"(the stacks' output: {stream.name})")
    return out


def main(argv=None):
    """Parse the arguments and print the figures."""
    parser = argparse.ArgumentParser(prog='nav_fleet', description=__doc__.splitlines()[1])
    parser.add_argument('--robots', type=int, nargs='+', default=[1, 4],
                        help='robot counts, one stage each (1 4)')
    parser.add_argument('--seconds', type=float, default=30.0,
                        help='wall seconds of each measured window (30)')
    parser.add_argument('--no-viewer', action='store_true',
                        help='run the stacks with viewer:=false')
    args = parser.parse_args(argv)
    run(tuple(args.robots), args.seconds, viewer=not args.no_viewer)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
