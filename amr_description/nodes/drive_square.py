# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The main job: bring up the simulated robot, drive a square on ``/odom``, report and draw it.

``ros2 run amr_description drive_square [--side 1.0] [--rtf 1.0] [--output-dir out]``
starts the ``sim`` stack (unless ``--no-bringup``), waits until ``joint_state_broadcaster``
and ``diff_drive_controller`` are active, then drives the course closed-loop on
``/odom`` by publishing ``geometry_msgs/TwistStamped`` on ``/diff_drive_controller/cmd_vel``,
exactly as a user's node would. It records ``/odom`` and the simulator's
``/ground_truth/odom``, prints a table per leg (commanded, odometry, ground truth), writes
``path.png`` (odometry vs ground truth) and ``scene.png`` (a render of the final scene), stops
the stack and exits 0 (1 on a time-out or failure).
"""

import argparse
import math
import os
import sys
import time

from amr_description.core.course import closure_error
from amr_description.core.course import CourseFollower
from amr_description.core.course import format_leg_table
from amr_description.core.course import leg_progress
from amr_description.core.course import square_course
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

CMD_TOPIC = '/diff_drive_controller/cmd_vel'
ODOM_TOPIC = '/odom'
TRUTH_TOPIC = '/ground_truth/odom'
CONTROLLERS = ('joint_state_broadcaster', 'diff_drive_controller')


def planar_pose(msg):
    """
    Return ``(x, y, yaw)`` of a nav_msgs/Odometry pose.

    :param msg: nav_msgs/Odometry.
    :returns: position in m and yaw in rad (rotation about z from the quaternion).
    """
    q = msg.pose.pose.orientation
    yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    return (msg.pose.pose.position.x, msg.pose.pose.position.y, yaw)


def stamp_seconds(stamp):
    """Return a builtin_interfaces/Time as float seconds."""
    return stamp.sec + stamp.nanosec * 1e-9


class SquareDriver(Node):
    """
    Drive a list of legs closed-loop on ``/odom``; record odometry and ground truth.

    Each ``/odom`` message advances the :class:`~amr_description.core.course.CourseFollower`
    and publishes the resulting command, stamped with the odometry stamp (sim time). After
    each leg the robot is held still for ``settle`` seconds of sim time, then both poses are
    recorded and the next leg starts from the settled pose. Nothing is driven or recorded
    before :attr:`enabled` is set.
    """

    def __init__(self, legs, settle=0.4):
        """
        Create the node, its publisher and subscriptions.

        :param legs: list of :class:`~amr_description.core.course.Leg`.
        :param settle: seconds of sim time to stand still between legs.
        """
        super().__init__('drive_square')
        self.legs = legs
        self.follower = CourseFollower(legs)
        self.settle = settle
        self.odom_marks = []
        self.truth_marks = []
        self.odom_path = []
        self.truth_path = []
        self.truth = None
        self.odom = None
        self._settle_until = None
        self._next_progress = None
        self.enabled = False
        self._cmd = self.create_publisher(TwistStamped, CMD_TOPIC, 10)
        self.create_subscription(Odometry, ODOM_TOPIC, self._on_odom, 50)
        self.create_subscription(Odometry, TRUTH_TOPIC, self._on_truth, 50)

    @property
    def done(self):
        """Return True once every leg is driven and the final poses are recorded."""
        return self.follower.done and self._settle_until is None

    def _publish(self, stamp, linear, angular):
        msg = TwistStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = 'base_link'
        msg.twist.linear.x = float(linear)
        msg.twist.angular.z = float(angular)
        self._cmd.publish(msg)

    def _on_truth(self, msg):
        self.truth = planar_pose(msg)
        self.truth_path.append(self.truth[:2])

    def _on_odom(self, msg):
        pose = planar_pose(msg)
        self.odom = pose
        self.odom_path.append(pose[:2])
        now = stamp_seconds(msg.header.stamp)
        if self.truth is None or not self.enabled:
            return
        if not self.odom_marks:
            self.odom_marks.append(pose)
            self.truth_marks.append(self.truth)
        if self._settle_until is not None:
            self._publish(msg.header.stamp, 0.0, 0.0)
            if now >= self._settle_until:
                self._settle_until = None
                self.odom_marks.append(pose)
                self.truth_marks.append(self.truth)
                self.follower.start = None
                self._report_leg(len(self.odom_marks) - 2)
            return
        if self.follower.done:
            return
        linear, angular, finished = self.follower.step(pose)
        self._publish(msg.header.stamp, linear, angular)
        self._progress(now, pose)
        if finished is not None:
            self._settle_until = now + self.settle

    def _progress(self, now, pose):
        """Print where the current leg stands, once per second of sim time."""
        if self._next_progress is not None and now < self._next_progress:
            return
        self._next_progress = now + 1.0
        if self.follower.done or self.follower.start is None:
            return
        index = self.follower.index
        leg = self.legs[index]
        done = leg_progress(leg, self.follower.start, pose)
        if leg.kind == 'straight':
            text = f'{done:.2f} of {leg.target:.2f} m'
        else:
            text = f'{math.degrees(done):.0f} of {math.degrees(leg.target):.0f} deg'
        print(f'[drive_square] t={now:6.1f} s  leg {index + 1}/{len(self.legs)} {leg.kind}: '
              f'{text}', flush=True)

    def _report_leg(self, index):
        leg = self.legs[index]
        start, end = self.odom_marks[index], self.odom_marks[index + 1]
        if leg.kind == 'straight':
            value = f'{math.hypot(end[0] - start[0], end[1] - start[1]):.3f} m'
        else:
            turn = math.atan2(math.sin(end[2] - start[2]), math.cos(end[2] - start[2]))
            value = f'{math.degrees(turn):.1f} deg'
        print(f'[drive_square] leg {index + 1}/{len(self.legs)} done: {leg.kind}, '
              f'odometry says {value}', flush=True)


def _controllers_active(node, timeout):
    """
    Wait until every controller in :data:`CONTROLLERS` is active.

    :param node: an rclpy node (its executor is spun here).
    :param timeout: wall seconds.
    :returns: True when all are active before the time-out.
    """
    from controller_manager_msgs.srv import ListControllers

    client = node.create_client(ListControllers, '/controller_manager/list_controllers')
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            if not client.wait_for_service(timeout_sec=0.5):
                continue
            future = client.call_async(ListControllers.Request())
            rclpy.spin_until_future_complete(node, future, timeout_sec=2.0)
            result = future.result()
            if result is not None:
                states = {c.name: c.state for c in result.controller}
                if all(states.get(name) == 'active' for name in CONTROLLERS):
                    return True
            time.sleep(0.2)
        return False
    finally:
        node.destroy_client(client)


def _relative_path(points, origin):
    """Express planar points in the frame of ``origin`` = ``(x, y, yaw)``."""
    c, s = math.cos(origin[2]), math.sin(origin[2])
    return [((x - origin[0]) * c + (y - origin[1]) * s,
             -(x - origin[0]) * s + (y - origin[1]) * c) for x, y in points]


def write_path_plot(path, odom_path, truth_path, odom_origin, truth_origin, side):
    """
    Plot the odometry and ground-truth paths, each relative to its own start pose, to a PNG.

    :param path: output PNG path.
    :param odom_path: list of ``(x, y)`` from ``/odom``, m.
    :param truth_path: list of ``(x, y)`` from the ground truth, m.
    :param odom_origin: ``(x, y, yaw)`` where the course began, in odom.
    :param truth_origin: the same instant in the ground truth.
    :param side: commanded side length in m (drawn as the reference square).
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 6), dpi=100)
    ax.plot([0, side, side, 0, 0], [0, 0, side, side, 0], color='0.7', linestyle='--',
            label='commanded square')
    for points, origin, colour, label in ((odom_path, odom_origin, 'tab:red', '/odom'),
                                          (truth_path, truth_origin, 'tab:blue',
                                           'ground truth')):
        rel = _relative_path(points, origin)
        if rel:
            ax.plot([p[0] for p in rel], [p[1] for p in rel], color=colour, label=label)
    ax.set_aspect('equal')
    ax.set_xlabel('x [m] (start frame)')
    ax.set_ylabel('y [m] (start frame)')
    ax.set_title('amr: 1 m square, odometry vs ground truth')
    ax.grid(True, alpha=0.3)
    ax.legend(loc='center')
    fig.savefig(path)
    plt.close(fig)


def _bringup(rtf, log_path):
    """Start the ``sim`` stack with its output in ``log_path``; return the orchestrator."""
    from amr_description.launch import stacks
    from amr_description.launch.orchestrator import Orchestrator

    log = open(log_path, 'w')
    orchestrator = Orchestrator(stacks.describe('sim', [f'rtf:={rtf}', 'headless:=true']),
                                stream=log)
    orchestrator.start()
    return orchestrator, log


def _parse(argv):
    parser = argparse.ArgumentParser(
        prog='drive_square', description='Bring up the simulated robot and drive a square.')
    parser.add_argument('--side', type=float, default=1.0, help='side length, m (1.0)')
    parser.add_argument('--speed', type=float, default=0.25, help='linear speed, m/s (0.25)')
    parser.add_argument('--turn-rate', type=float, default=0.5,
                        help='angular speed, rad/s (0.5)')
    parser.add_argument('--rtf', type=float, default=1.0,
                        help='real-time factor of the simulation, 0 = as fast as possible')
    parser.add_argument('--output-dir', default='out', help='where the PNGs go (out/)')
    parser.add_argument('--no-bringup', action='store_true',
                        help='use an already running sim stack')
    parser.add_argument('--timeout', type=float, default=180.0,
                        help='wall seconds for the whole course (180)')
    return parser.parse_args(argv)


def main(args=None):
    """
    Run the main job; see the module docstring.

    :param args: command-line arguments (default ``sys.argv[1:]``); ``--ros-args`` is
        passed to rclpy.
    :returns: 0 when the course was driven and the outputs written, 1 otherwise.
    """
    argv = list(sys.argv[1:] if args is None else args)
    ros_args = []
    if '--ros-args' in argv:
        ros_args = argv[argv.index('--ros-args'):]
        argv = argv[:argv.index('--ros-args')]
    opts = _parse(argv)
    os.makedirs(opts.output_dir, exist_ok=True)
    orchestrator = log = None
    node = None
    rclpy.init(args=['drive_square', '--ros-args', '-p', 'use_sim_time:=true'] + ros_args[1:])
    try:
        if not opts.no_bringup:
            log_path = os.path.join(opts.output_dir, 'sim_stack.log')
            print(f'[drive_square] starting the sim stack (rtf {opts.rtf:g}); its output goes '
                  f'to {log_path}', flush=True)
            orchestrator, log = _bringup(opts.rtf, log_path)
        legs = square_course(opts.side, opts.speed, opts.turn_rate)
        node = SquareDriver(legs)
        print('[drive_square] waiting for joint_state_broadcaster and diff_drive_controller '
              'to be active ...', flush=True)
        started = time.monotonic()
        if not _controllers_active(node, timeout=60.0):
            print('[drive_square] error: the controllers did not become active within 60 s '
                  '(see the sim stack log)', file=sys.stderr)
            return 1
        print(f'[drive_square] controllers active after {time.monotonic() - started:.1f} s; '
              f'driving a {opts.side:g} m square on {ODOM_TOPIC}', flush=True)
        node.enabled = True
        deadline = time.monotonic() + opts.timeout
        while not node.done and time.monotonic() < deadline:
            rclpy.spin_once(node, timeout_sec=0.1)
        if not node.done:
            print(f'[drive_square] error: the course did not finish within {opts.timeout:g} s '
                  f'(finished {len(node.odom_marks) - 1 if node.odom_marks else 0} of '
                  f'{len(legs)} legs)', file=sys.stderr)
            return 1
        print()
        print(format_leg_table(legs, node.odom_marks, node.truth_marks))
        odom_err = closure_error(node.odom_marks)
        truth_err = closure_error(node.truth_marks)
        print()
        print(f'closure (end vs start): /odom {odom_err[0]:.3f} m, '
              f'{math.degrees(odom_err[1]):.1f} deg; ground truth {truth_err[0]:.3f} m, '
              f'{math.degrees(truth_err[1]):.1f} deg')
        plot = os.path.join(opts.output_dir, 'path.png')
        write_path_plot(plot, node.odom_path, node.truth_path, node.odom_marks[0],
                        node.truth_marks[0], opts.side)
        scene = os.path.join(opts.output_dir, 'scene.png')
        from amr_description.launch.stacks import read_urdf
        from amr_description.sim.render import render_scene
        from amr_description.sim.render import save_png
        save_png(render_scene(read_urdf(), node.truth_marks[-1], node.truth_path), scene)
        print(f'wrote {plot} and {scene}')
        return 0
    except (KeyboardInterrupt, ExternalShutdownException):
        return 1
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
        if orchestrator is not None:
            orchestrator.shutdown()
            orchestrator.wait(timeout=15.0)
            log.close()


if __name__ == '__main__':
    sys.exit(main())
