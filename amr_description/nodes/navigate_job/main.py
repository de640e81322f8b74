# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""``navigate_job``'s command line, its two stacks and ``main`` (see the package docstring)."""

import argparse
import bisect
import math
import os
import sys
import time

from amr_description.core.course import wrap_angle
from amr_description.launch.actions import LaunchError
from amr_description.nodes.drive_square.main import StackLog
from amr_description.nodes.navigate_job.report import fail
from amr_description.nodes.navigate_job.report import format_table
from amr_description.nodes.navigate_job.report import robot_params
from amr_description.nodes.navigate_job.report import write_map_png
from amr_description.nodes.navigate_job.report import write_navigation_png
from amr_description.ros import shutdown
from amr_description.ros.map_saver_cli import map_saver_command
from amr_description.ros.map_saver_cli import run_map_saver
from amr_description.ros.transforms import set_yaw
from amr_description.ros.transforms import stamp_seconds
from amr_description.ros.transforms import yaw_of
from rclpy.executors import ExternalShutdownException

PROGRAM = 'navigate_job'
ACTIVE = 'Managed nodes are active'
"""The line each lifecycle manager prints once its nodes are active (nav2_lifecycle_manager)."""

ROUTES = {
    'warehouse': ((4.85, 0.0, 0.0), (4.85, 2.0, math.pi), (0.95, 2.0, math.pi / 2),
                  (0.95, 4.0, 0.0), (4.85, 4.0, math.pi / 2), (4.85, 6.0, math.pi),
                  (0.95, 6.0, math.pi)),
}
"""Mapping routes ``(x, y, yaw)`` per world, from the spawn pose (0, 0, 0): in warehouse.sdf
along the south aisle, through the gaps between the shelves (x 0.5 .. 1.4 and 4.4 .. 5.3) and
along each aisle (y 2, 4, 6), so that the lidar sees both faces of every shelf."""


class Recorder:
    """
    The ground truth of the robot (``/ground_truth/odom``), recorded on the navigator's node.

    The ground truth's 50 messages a second are taken on a thread of their own
    (:class:`~amr_description.ros.take_loop.TakeLoop`): on the navigator's executor each woke
    it with every entity of its action and service clients. ``stop_loops_of(node)`` ends
    the thread.

    :param node: the rclpy node (the job's ``BasicNavigator``).
    """

    def __init__(self, node):
        from amr_description.ros.take_loop import TakeLoop
        from geometry_msgs.msg import PoseWithCovarianceStamped
        from nav_msgs.msg import Odometry
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        self.samples = []  # (t, x, y, yaw): sim s, world-frame m and rad
        self.amcl = None  # the last /amcl_pose as (t, x, y, yaw), map frame
        loop = TakeLoop(node, f'{PROGRAM}_ground_truth')
        loop.subscribe(Odometry, '/ground_truth/odom', 50, self._on_truth, raw=False)
        loop.start()
        node.create_subscription(PoseWithCovarianceStamped, '/amcl_pose', self._on_amcl,
                                 QoSProfile(depth=1,
                                            durability=DurabilityPolicy.TRANSIENT_LOCAL))

    def _on_amcl(self, msg):
        p = msg.pose.pose
        self.amcl = (stamp_seconds(msg.header.stamp), p.position.x, p.position.y,
                     yaw_of(p.orientation))

    def amcl_error(self):
        """
        Return AMCL's last pose against the ground truth at its stamp: (m, rad), or None.

        The SLAM map's frame is the world's (the robot starts mapping at the world origin).
        """
        if self.amcl is None or not self.samples:
            return None
        t, x, y, yaw = self.amcl
        k = bisect.bisect_left(self.samples, t, key=lambda s: s[0])
        truth = min(self.samples[max(0, k - 1):k + 1], key=lambda s: abs(s[0] - t))
        return math.hypot(x - truth[1], y - truth[2]), abs(wrap_angle(yaw - truth[3]))

    def _on_truth(self, msg):
        p = msg.pose.pose.position
        t = stamp_seconds(msg.header.stamp)
        if self.samples and t < self.samples[-1][0]:
            self.samples.clear()  # a new simulator: its time starts again
        self.samples.append((t, p.x, p.y, yaw_of(msg.pose.pose.orientation)))

    def now(self):
        """Return the latest sample's sim time, s (None before the first)."""
        return self.samples[-1][0] if self.samples else None

    def between(self, t0, t1):
        """Return the samples with ``t0 <= t <= t1`` as a list of ``(t, x, y, yaw)``."""
        return [s for s in self.samples if t0 <= s[0] <= t1]


def _parse(argv):
    parser = argparse.ArgumentParser(
        prog=PROGRAM, description='Map a world with SLAM, save the map, localize in it with '
        'AMCL and navigate to seeded random goals (Nav2 and slam_toolbox as a user runs them).')
    parser.add_argument('--world', default='warehouse', choices=sorted(ROUTES),
                        help='the world to map and navigate (warehouse)')
    parser.add_argument('--goals', type=int, default=10, help='number of goals (10)')
    parser.add_argument('--seed', type=int, default=0, help='seed of the goals (0)')
    parser.add_argument('--passage', type=float, default=0.3,
                        help='m of clearance on the way to a goal (0.3: through the 0.9 m gaps '
                        'between the shelves; 0.45 keeps the goals in the aisle of the start)')
    parser.add_argument('--rtf', type=float, default=1.0,
                        help='real-time factor of the simulation (1.0; 0 = as fast as the '
                        'navigation stack keeps up, in lock-step; the factor reached is '
                        'printed per phase)')
    parser.add_argument('--output-dir', default='out', help='where the map and PNGs go (out/)')
    parser.add_argument('--goal-timeout', type=float, default=300.0,
                        help='wall seconds per goal before it is canceled (300)')
    parser.add_argument('--route-timeout', type=float, default=900.0,
                        help='wall seconds for the mapping route (900)')
    parser.add_argument('--startup-timeout', type=float, default=300.0,
                        help='wall seconds for a stack to come up (300)')
    parser.add_argument('--viewer-port', type=int, default=None,
                        help='port of the viewer page (default 8080 or the next free port; '
                        '0 = no viewer)')
    opts = parser.parse_args(argv)
    if opts.goals < 1:
        parser.error(f'argument --goals: must be >= 1, got {opts.goals}')
    if not opts.rtf >= 0:
        parser.error(f'argument --rtf: must be >= 0 (0: lock-step), got {opts.rtf:g}')
    return opts


def _start(opts, name, extra):
    """Start the ``navigation`` stack with ``extra`` arguments; return (orchestrator, log)."""
    from amr_description.launch import registry
    from amr_description.launch.orchestrator import Orchestrator
    # with --rtf 0 the stack comes up in real time; the lock-step starts once it is active
    argv = [f'world:={opts.world}', f'rtf:={opts.rtf or 1.0}', 'headless:=true'] + extra
    if opts.viewer_port == 0:
        argv.append('viewer:=false')
    elif opts.viewer_port is not None:
        argv.append(f'viewer_port:={opts.viewer_port}')
    path = os.path.join(opts.output_dir, f'{name}_stack.log')
    print(f'[{PROGRAM}] starting the {name} stack: navigation {" ".join(argv)}; its output '
          f'goes to {path}', flush=True)
    log = StackLog(open(path, 'w'), PROGRAM, watch=(ACTIVE,))
    orchestrator = Orchestrator(registry.describe('navigation', argv), stream=log)
    orchestrator.start()
    return orchestrator, log


def _govern(opts):
    """With ``--rtf 0``, pause the simulator and start the lock-step; return it (or None)."""
    if opts.rtf:
        return None
    from amr_description.nodes.navigate_job.lockstep import LockStepGovernor
    governor = LockStepGovernor()
    try:
        governor.start()
    except RuntimeError:
        governor.stop()
        raise
    print(f'[{PROGRAM}] lock-step: the simulator advances as the navigation stack keeps up',
          flush=True)
    return governor


def _speed(what, sim, wall, governor):
    """Print a phase's sim and wall seconds, its real-time factor and the lock-step's waits."""
    text = (f'[{PROGRAM}] {what} in {sim:.1f} s of sim time ({wall:.1f} s wall, real-time '
            f'factor {sim / max(wall, 1e-9):.2f})')
    if governor is not None:
        if governor.error:
            raise RuntimeError(f'lock-step: {governor.error}')
        text += (f'; lock-step: {governor.ticks} ticks, {governor.waited:.1f} s waiting for '
                 f'the stack, {governor.late} waits given up')
    print(text, flush=True)


def _stop(orchestrator, log, governor=None):
    if governor is not None:
        governor.stop()
    if orchestrator is not None:
        orchestrator.shutdown()
        orchestrator.wait(timeout=30.0)
        log.close()


def _spin_until(node, done, timeout):
    """Spin ``node`` until ``done()`` or ``timeout`` wall seconds; return ``done()``."""
    import rclpy
    deadline = time.monotonic() + timeout
    while not done() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    return done()


def _wait_for_global_costmap(node, timeout):
    """
    Spin until ``global_costmap/costmap`` has the size and origin of the latest ``/map``.

    Both are latched (reliable, transient local, depth 1). Returns True when they match
    within ``timeout`` wall seconds.
    """
    from nav_msgs.msg import OccupancyGrid
    from rclpy.qos import DurabilityPolicy
    from rclpy.qos import QoSProfile
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    last = {}

    def keep(key):
        def store(msg):
            last[key] = (msg.info.width, msg.info.height, round(msg.info.origin.position.x, 6),
                         round(msg.info.origin.position.y, 6))
        return store
    subs = [node.create_subscription(OccupancyGrid, topic, keep(topic), latched)
            for topic in ('map', 'global_costmap/costmap')]
    try:
        return _spin_until(node, lambda: 'map' in last and
                           last.get('global_costmap/costmap') == last['map'], timeout)
    finally:
        for sub in subs:
            node.destroy_subscription(sub)


def _pose(node, x, y, yaw):
    from geometry_msgs.msg import PoseStamped
    pose = PoseStamped()
    pose.header.frame_id = 'map'
    pose.header.stamp = node.get_clock().now().to_msg()
    pose.pose.position.x, pose.pose.position.y = float(x), float(y)
    set_yaw(pose.pose.orientation, yaw)
    return pose


def _wait_task(navigator, timeout):
    """Wait for the navigator's task; cancel it at ``timeout`` wall s. Return TaskResult."""
    deadline = time.monotonic() + timeout
    while not navigator.isTaskComplete():
        if time.monotonic() > deadline:
            navigator.cancelTask()
            _spin_until(navigator, navigator.isTaskComplete, 30.0)
            break
    return navigator.getResult()


def _up(navigator, recorder, log, managers, timeout):
    """Wait until ``managers`` lifecycle managers are active and ground truth arrives."""
    return _spin_until(navigator, lambda: log.counts[ACTIVE] >= managers
                       and recorder.now() is not None, timeout)


def _map_phase(opts, navigator, recorder):
    """Drive the route with SLAM and save the map; return (map yaml, route samples) or fail."""
    orchestrator, log = _start(opts, 'slam', ['slam:=True'])
    governor = None
    try:
        if not _up(navigator, recorder, log, 1, opts.startup_timeout):
            raise RuntimeError(f'the slam stack was not active within {opts.startup_timeout:g} '
                               's (see its log)')
        # the route's poses are in map, which exists once SLAM publishes map -> odom on /tf
        from tf2_msgs.msg import TFMessage
        seen = []
        sub = navigator.create_subscription(
            TFMessage, '/tf', lambda m: seen.extend(
                t for t in m.transforms if t.header.frame_id.lstrip('/') == 'map'), 10)
        if not _spin_until(navigator, lambda: seen, 120.0):
            raise RuntimeError('SLAM published no map -> odom transform within 120 s of the '
                               'stack being active')
        navigator.destroy_subscription(sub)
        # and the planner's costmap must hold SLAM's map: before it arrives the global
        # costmap has its parameters' default size, and a plan from the robot's cell fails
        # with "Start Coordinates ... was outside bounds" (203), as upstream's would
        if not _wait_for_global_costmap(navigator, 120.0):
            raise RuntimeError("the global costmap did not take SLAM's /map within 120 s")
        governor = _govern(opts)
        route = [_pose(navigator, *p) for p in ROUTES[opts.world]]
        t0 = recorder.now()
        started = time.monotonic()
        print(f'[{PROGRAM}] mapping: following {len(route)} waypoints of the {opts.world} route '
              '(follow_waypoints)', flush=True)
        if not navigator.followWaypoints(route):
            raise RuntimeError('follow_waypoints refused the route')
        result = _wait_task(navigator, opts.route_timeout)
        missed = list(getattr(navigator.result_future.result().result, 'missed_waypoints', []))
        t1 = recorder.now()
        wall = time.monotonic() - started
        _speed(f'route {result.name}: {len(route) - len(missed)} of {len(route)} waypoints',
               t1 - t0, wall, governor)
        if result.name != 'SUCCEEDED' or missed:
            raise RuntimeError(f'the mapping route ended {result.name} with waypoints '
                               f'{[m.index for m in missed]} missed')
        stem = os.path.join(os.path.abspath(opts.output_dir), 'map')
        # no ros2 on PATH: FileNotFoundError, an OSError, main's one line
        cmd = map_saver_command(stem, ros_args=('-p', 'use_sim_time:=true'))
        saved = run_map_saver(cmd, capture=True, timeout=120)
        if saved.returncode != 0 or not os.path.isfile(stem + '.yaml'):
            raise RuntimeError(f'map_saver_cli failed ({saved.returncode}): '
                               f'{(saved.stdout + saved.stderr).strip()[-300:]}')
        print(f'[{PROGRAM}] saved the map: {stem}.yaml', flush=True)
        return stem + '.yaml', recorder.between(t0, t1)
    finally:
        _stop(orchestrator, log, governor)


def _goal_phase(opts, navigator, recorder, map_yaml, true_map, saved_map):
    """Restart on the saved map with AMCL and go to the goals; return the rows."""
    from amr_description.nav.trials import path_length
    from amr_description.nav.trials import sample_goals
    navigator.initial_pose_received = False
    recorder.samples.clear()
    orchestrator, log = _start(opts, 'navigation', [f'map:={map_yaml}'])
    rows = []
    governor = None
    try:
        if not _up(navigator, recorder, log, 2, opts.startup_timeout):
            raise RuntimeError(f'the navigation stack was not active within '
                               f'{opts.startup_timeout:g} s (see its log)')
        if not _spin_until(navigator, lambda: navigator.initial_pose_received, 60.0):
            raise RuntimeError('no amcl_pose within 60 s of the stack being active')
        governor = _govern(opts)
        start = recorder.samples[-1]
        began = time.monotonic()
        goals = sample_goals([true_map, saved_map], start[1:3], opts.goals, opts.seed,
                             passage=opts.passage)
        for i, (x, y, yaw) in enumerate(goals, 1):
            here = recorder.samples[-1]
            goal = _pose(navigator, x, y, yaw)
            plan = navigator.getPath(goal, goal)
            planned = [] if plan is None else [(p.pose.position.x, p.pose.position.y)
                                               for p in plan.poses]
            print(f'[{PROGRAM}] goal {i}/{len(goals)}: ({x:.2f}, {y:.2f}, {yaw:.2f}), '
                  f'{path_length(planned):.2f} m planned', flush=True)
            t0 = recorder.now()
            result = (_wait_task(navigator, opts.goal_timeout)
                      if navigator.goToPose(goal) else None)
            t1 = recorder.now()  # the result's time; the robot then settles
            error = recorder.amcl_error()
            print(f'[{PROGRAM}] goal {i}/{len(goals)}: '
                  f'{"REJECTED" if result is None else result.name} after {t1 - t0:.1f} s'
                  + ('' if error is None else f'; AMCL {error[0]:.3f} m and '
                     f'{math.degrees(error[1]):.1f} deg from the ground truth'), flush=True)
            _spin_until(navigator, lambda: False, 0.5)  # the last ground truth
            rows.append({'goal': (x, y, yaw), 'start': here[1:], 'result':
                         'REJECTED' if result is None else result.name, 'planned': planned,
                         'truth': recorder.between(t0, recorder.now()), 'span': (t0, t1)})
        _speed(f'goals: {len(goals)}', recorder.now() - start[0], time.monotonic() - began,
               governor)
    finally:
        _stop(orchestrator, log, governor)
    return rows


def main(args=None):
    """
    Run the navigation job; see the package docstring.

    :param args: command-line arguments (default ``sys.argv[1:]``).
    :returns: 0 when every goal succeeded without a collision, 1 otherwise.
    """
    argv = list(sys.argv[1:] if args is None else args)
    opts = _parse(argv)
    os.makedirs(opts.output_dir, exist_ok=True)
    navigator = None
    try:
        shutdown.init([PROGRAM, '--ros-args', '-p', 'use_sim_time:=true'])
        from amr_description.core.gazebo.sdf_world import load_world
        from amr_description.core.scan_map import world_sections
        from amr_description.launch.nav_stacks import share_file
        from amr_description.nav.map_io import load_map
        from amr_description.nav.world_map import HEIGHTS
        from amr_description.nav.world_map import world_map
        from nav2_simple_commander.robot_navigator import BasicNavigator
        world = load_world(opts.world)
        true_map = world_map(world)
        sections = [s for h in HEIGHTS for s in world_sections(world, h)]
        robot = robot_params(share_file('config', 'nav2_params.yaml'))
        navigator = shutdown.create(BasicNavigator, PROGRAM)
        recorder = Recorder(navigator)
        map_yaml, route = _map_phase(opts, navigator, recorder)
        saved_map, _ = load_map(map_yaml)
        rows = _goal_phase(opts, navigator, recorder, map_yaml, true_map, saved_map)
        text, ok = format_table(rows, route, sections, robot)
        print(text, flush=True)
        write_map_png(os.path.join(opts.output_dir, 'map.png'), saved_map, true_map, route,
                      ROUTES[opts.world])
        write_navigation_png(os.path.join(opts.output_dir, 'navigation.png'), saved_map, rows)
        print(f'[{PROGRAM}] wrote {opts.output_dir}/map.png and '
              f'{opts.output_dir}/navigation.png', flush=True)
        return 0 if ok else fail('a goal was not reached or the robot touched the world')
    except (RuntimeError, ValueError, OSError, LaunchError) as exc:
        return fail(str(exc))
    except (KeyboardInterrupt, ExternalShutdownException):
        return 1
    finally:
        if navigator is not None:
            from amr_description.ros.take_loop import stop_loops_of
            stop_loops_of(navigator)  # the recorder's thread, before the node goes
        shutdown.shutdown(navigator)


if __name__ == '__main__':
    sys.exit(main())
