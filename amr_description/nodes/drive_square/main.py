# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""``drive_square``'s command line, bring-up of the stack and ``main``."""

import argparse
import os
import re
import sys
import time

from amr_description.core.course import square_course
from amr_description.nodes.drive_square.driver import controllers_active
from amr_description.nodes.drive_square.driver import drive
from amr_description.nodes.drive_square.driver import LockStep
from amr_description.nodes.drive_square.driver import robot_namespaces
from amr_description.nodes.drive_square.driver import SquareDriver
from amr_description.nodes.drive_square.driver import wait_connected
from amr_description.nodes.drive_square.report import fail
from amr_description.nodes.drive_square.report import report
from amr_description.nodes.drive_square.scans import ScanRecorder
from amr_description.ros import shutdown
from rclpy.executors import ExternalShutdownException


START_POSES = {'arena': (1.55, -0.55, 0.0)}
"""Spawn pose ``(x, y, yaw)`` of the one robot per world: a 1 m square clear of obstacles
(worlds/arena.sdf has a pillar at (1, 0)); (0, 0, 0) in any other world."""


class StackLog:
    """
    A stack's output stream: lines go to the log file; the viewer's URL line is printed.

    The viewer takes port 8080 or the next free port (a second main job beside the first), so
    the URL to open is the one its node prints.

    :param log: the open log file.
    :param program: the prefix of the printed line.
    :param watch: texts whose occurrences in the output are counted in :attr:`counts`.
    """

    def __init__(self, log, program='drive_square', watch=()):
        self.log = log
        self.url = None
        self.program = program
        self.counts = dict.fromkeys(watch, 0)

    def write(self, text):
        self.log.write(text)
        for key in self.counts:
            self.counts[key] += text.count(key)
        found = None if self.url else re.search(r'viewer: open (http://\S+) in a browser', text)
        if found:
            self.url = found.group(1)
            print(f'[{self.program}] watch it drive: open {self.url} in a browser', flush=True)

    def flush(self):
        self.log.flush()

    def close(self):
        self.log.close()


def _bringup(rtf, robots, log_path, viewer_port=None, world='empty'):
    """
    Start the ``sim`` or ``fleet`` stack, output in ``log_path``; return (orch, log).

    The viewer runs on ``viewer_port`` when given, else on 8080 or the next free port; its
    URL is printed once its node prints it; ``viewer_port`` 0 leaves it out. ``world`` is the
    stack's ``world``.
    """
    from amr_description.launch import registry
    from amr_description.launch.orchestrator import Orchestrator

    argv = [f'rtf:={rtf}', 'headless:=true', f'world:={world}']
    if robots > 1:
        name = 'fleet'
        argv.append(f'robots:={robots}')
    else:
        name = 'sim'
        x, y, yaw = START_POSES.get(world, (0.0, 0.0, 0.0))
        argv += [f'x:={x!r}', f'y:={y!r}', f'yaw:={yaw!r}']
    declared = {d.name for d in registry.STACKS[name][1]}
    if 'viewer' in declared:
        if viewer_port == 0:
            argv.append('viewer:=false')
        elif viewer_port is not None:
            argv.append(f'viewer_port:={viewer_port}')
    log = StackLog(open(log_path, 'w'))
    orchestrator = Orchestrator(registry.describe(name, argv), stream=log)
    orchestrator.start()
    return orchestrator, log


def _parse(argv):
    parser = argparse.ArgumentParser(
        prog='drive_square', description='Bring up the simulated robot(s) and drive squares.')
    parser.add_argument('--side', type=float, default=1.0, help='side length, m (1.0)')
    parser.add_argument('--speed', type=float, default=0.25, help='linear speed, m/s (0.25)')
    parser.add_argument('--turn-rate', type=float, default=0.5,
                        help='angular speed, rad/s (0.5)')
    parser.add_argument('--rtf', type=float, default=1.0,
                        help='real-time factor of the simulation, 0 = as fast as possible '
                        '(lock-step)')
    parser.add_argument('--robots', type=int, default=1,
                        help='number of robots (1: the sim stack; N > 1: the fleet stack, '
                        'namespaces r1 ... rN)')
    parser.add_argument('--lockstep-period', type=float, default=0.02,
                        help='sim seconds per step in fast-forward lock-step (0.02)')
    # the target; measured closure (docs/simulation.md, "Closing the square"): 0.002 m and
    # 0.1 deg in ground truth, with the follower's gentle speed ramps
    parser.add_argument('--tolerance', type=float, default=0.01,
                        help='largest ground-truth closure error, m (0.01)')
    parser.add_argument('--tolerance-deg', type=float, default=1.0,
                        help='largest ground-truth heading closure error, deg (1.0)')
    parser.add_argument('--output-dir', default='out', help='where the PNGs go (out/)')
    parser.add_argument('--no-bringup', action='store_true',
                        help='use an already running sim stack')
    parser.add_argument('--timeout', type=float, default=180.0,
                        help='wall seconds for the whole course (180)')
    parser.add_argument('--startup-timeout', type=float, default=180.0,
                        help='wall seconds for the stack to come up (180; a loaded machine is '
                        'slow)')
    parser.add_argument('--viewer-port', type=int, default=None,
                        help='port of the viewer page that shows the robot live (default '
                        '8080 or the next free port; 0 = no viewer)')
    parser.add_argument('--world', default=None,
                        help='SDF world of the stack (arena for one robot: the lidar map is '
                        'drawn in out/scans.png; empty for a fleet; empty gives the run '
                        'without obstacles)')
    opts = parser.parse_args(argv)
    if opts.world is None:
        opts.world = 'arena' if opts.robots == 1 else 'empty'
    if opts.robots < 1:
        parser.error(f'argument --robots: must be >= 1, got {opts.robots}')
    if not opts.lockstep_period > 0:
        parser.error('argument --lockstep-period: must be > 0')
    if opts.rtf < 0:
        parser.error('argument --rtf: must be >= 0')
    return opts


def main(args=None):
    """
    Run the main job; see the module docstring.

    :param args: command-line arguments (default ``sys.argv[1:]``); ``--ros-args`` is
        passed to rclpy.
    :returns: 0 when every course was driven within tolerance with no command dropped and
        the outputs written, 1 otherwise.
    """
    argv = list(sys.argv[1:] if args is None else args)
    ros_args = []
    if '--ros-args' in argv:
        ros_args = argv[argv.index('--ros-args'):]
        argv = argv[:argv.index('--ros-args')]
    opts = _parse(argv)
    os.makedirs(opts.output_dir, exist_ok=True)
    orchestrator = log = None
    node = lockstep = None
    log_path = None
    try:
        shutdown.init(['drive_square', '--ros-args', '-p', 'use_sim_time:=true'] + ros_args[1:])
        if not opts.no_bringup:
            log_path = os.path.join(opts.output_dir, 'sim_stack.log')
            what = f'{opts.robots} robots' if opts.robots > 1 else 'the sim stack'
            print(f'[drive_square] starting {what} (rtf {opts.rtf:g}); its output goes '
                  f'to {log_path}', flush=True)
            orchestrator, log = _bringup(opts.rtf, opts.robots, log_path, opts.viewer_port,
                                         opts.world)
        legs = square_course(opts.side, opts.speed, opts.turn_rate)
        node = shutdown.create(SquareDriver, legs, robot_namespaces(opts.robots))
        scans = ScanRecorder(node) if opts.robots == 1 else None
        print('[drive_square] waiting for joint_state_broadcaster and diff_drive_controller '
              'to be active ...', flush=True)
        started = time.monotonic()
        startup_timeout = opts.startup_timeout + 2.0 * opts.robots
        waiting = controllers_active(node, [r.controller_manager for r in node.robots],
                                     timeout=startup_timeout)
        if waiting:
            return fail(f'the controllers of {", ".join(waiting)} did not become active '
                        f'within {startup_timeout:g} s (see the sim stack log)')
        if opts.rtf == 0:
            lockstep = LockStep(node, opts.lockstep_period)
            lockstep.set_paused(True)
        silent = wait_connected(node, 30.0, lockstep)
        if silent:
            return fail(f'nothing connected within 30 s of the controllers being active: '
                        f'{", ".join(silent)}')
        mode = 'lock-step' if opts.rtf == 0 else f'real-time factor {opts.rtf:g}'
        print(f'[drive_square] controllers active after {time.monotonic() - started:.1f} s; '
              f'driving {opts.side:g} m squares on '
              f'{", ".join(r.odom_topic for r in node.robots)} ({mode})', flush=True)
        advances, in_step, in_wait = drive(node, time.monotonic() + opts.timeout, lockstep)
        if advances:
            print(f'[drive_square] lock-step: {advances} steps of {opts.lockstep_period:g} s, '
                  f'{1000 * in_step / advances:.1f} ms per step_simulation call and '
                  f'{1000 * in_wait / advances:.1f} ms waiting for odometry (wall)', flush=True)
        if not node.done:
            finished = ', '.join(f'{r.name} {max(0, len(r.odom_marks) - 1)}'
                                 for r in node.robots)
            return fail(f'the course did not finish within {opts.timeout:g} s (legs of '
                        f'{len(legs)} finished: {finished})')
        return report(opts, node, legs, log_path, scans)
    except RuntimeError as exc:
        return fail(str(exc))
    except (KeyboardInterrupt, ExternalShutdownException):
        return 1
    finally:
        if lockstep is not None and opts.no_bringup:
            try:
                lockstep.set_paused(False)  # leave a user's simulator playing
            except (RuntimeError, Exception):  # noqa: B902 - best effort
                pass
        shutdown.shutdown(node, executor=node.spinner if node is not None else None)
        if orchestrator is not None:
            orchestrator.shutdown()
            orchestrator.wait(timeout=15.0)
            log.close()


if __name__ == '__main__':
    sys.exit(main())
