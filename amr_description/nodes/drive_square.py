# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The main job: bring up the simulated robot(s), drive a square on odometry, report and draw it.

``ros2 run amr_description drive_square [--side 1.0] [--rtf 1.0] [--robots N]
[--output-dir out]`` starts the ``sim`` stack (``--robots 1``, today's names: ``/odom``,
``/diff_drive_controller/cmd_vel``, ``/ground_truth/odom``) or the ``fleet`` stack
(``--robots N`` > 1: robots ``r1`` ... ``rN`` with ``/rI/odom``,
``/rI/diff_drive_controller/cmd_vel``, ``/rI/ground_truth/odom``), unless ``--no-bringup``.
It waits until every robot's ``joint_state_broadcaster`` and ``diff_drive_controller`` are
active, then every robot drives its own square at once, closed-loop on its odometry, by
publishing ``geometry_msgs/TwistStamped`` exactly as a user's node would: one command per
odometry message, stamped with that message's stamp (sim time).

Fast-forward (``--rtf 0``) runs in lock-step: the job pauses the simulator
(``/mujoco_sim/set_simulation_state``) and advances it ``--lockstep-period`` (0.02 s, one
odometry period) at a time with ``/mujoco_sim/step_simulation``, answering every odometry
message before the next step. The course starts from odometry stamped at or after the time
at which the paused simulator stands (two equal values in a row on ``/clock``): messages it
published while it still ran ahead, maybe queued in this process, are not answered. The
simulation can therefore never run ahead of the driver, a command is at most one period old
in sim time when the controller takes it (far below ``cmd_vel_timeout``), and the result does
not depend on how loaded the machine is. In real-time mode (``--rtf`` > 0) the simulator
runs free.

The job fails (exit 1, one line on stderr) when a command was dropped as stale (a command
published when the sim time it observes on ``/clock`` is already ``cmd_vel_timeout`` past its
stamp, or an "Ignoring the received message" line of diff_drive_controller in the stack's own
log), when a course does not finish within ``--timeout``, or when a robot's ground-truth
closure misses ``--tolerance`` (m) or ``--tolerance-deg``. Otherwise it prints a table per
leg (one robot) or one row per robot and a per-leg summary (several robots), writes
``path.png`` (odometry vs ground truth of every robot) and, for one robot, ``scene.png`` (a
render of the final scene), stops the stack and exits 0.
"""

import argparse
import collections
import math
import os
import sys
import time

from amr_description.core.course import closure_error
from amr_description.core.course import CourseFollower
from amr_description.core.course import format_leg_table
from amr_description.core.course import leg_delta
from amr_description.core.course import leg_progress
from amr_description.core.course import square_course
from amr_description.launch.stacks import CONTROLLERS
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry
from rclpy.executors import ExternalShutdownException
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rosgraph_msgs.msg import Clock

CMD_TOPIC = '/diff_drive_controller/cmd_vel'
ODOM_TOPIC = '/odom'
TRUTH_TOPIC = '/ground_truth/odom'
SIM_NODE = '/mujoco_sim'
CMD_VEL_TIMEOUT = 0.5  # s, diff_drive_controller's cmd_vel_timeout in config/controllers.yaml
STALE_LOG_LINE = 'Ignoring the received message'  # diff_drive_controller's warning


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


def robot_namespaces(count):
    """
    Return the namespaces of ``count`` robots: ``['']`` for one, ``r1`` ... ``rN`` otherwise.

    :param count: number of robots, >= 1.
    :returns: list of str (no leading slash).
    :raises ValueError: when ``count`` < 1.
    """
    if count < 1:
        raise ValueError(f'--robots must be >= 1, got {count}')
    return [''] if count == 1 else [f'r{i}' for i in range(1, count + 1)]


class RobotDriver:
    """
    Drive one robot's legs closed-loop on its odometry; record odometry and ground truth.

    Each odometry message advances the :class:`~amr_description.core.course.CourseFollower`
    and publishes the resulting command, stamped with the odometry stamp (sim time). After
    each leg the robot is held still for ``settle`` seconds of sim time, then both poses are
    recorded and the next leg starts from the settled pose. Nothing is driven or recorded
    before :attr:`enabled` is set.
    """

    def __init__(self, node, namespace, legs, settle=0.4):
        """
        Create the robot's publisher and subscriptions on ``node``.

        :param node: the rclpy node that owns them (its clock gives the sim time).
        :param namespace: robot namespace without slashes, '' for the robot without one.
        :param legs: list of :class:`~amr_description.core.course.Leg`.
        :param settle: seconds of sim time to stand still between legs.
        """
        self.node = node
        self.namespace = namespace
        self.name = namespace or 'amr'
        prefix = f'/{namespace}' if namespace else ''
        self.controller_manager = f'{prefix}/controller_manager'
        self.odom_topic = prefix + ODOM_TOPIC
        self.legs = legs
        self.follower = CourseFollower(legs)
        self.settle = settle
        self.odom_marks = []
        self.truth_marks = []
        self.odom_path = []
        self.truth_path = []
        self.truth = None
        self.odom = None
        self.odom_count = 0
        self.stale = 0
        self._settle_until = None
        self._next_progress = None
        self.enabled = False
        self.start_after = None  # sim s: odometry older than this predates the course
        self._cmd = node.create_publisher(TwistStamped, prefix + CMD_TOPIC, 10)
        node.create_subscription(Odometry, self.odom_topic, self._on_odom, 50)
        node.create_subscription(Odometry, prefix + TRUTH_TOPIC, self._on_truth, 50)

    @property
    def done(self):
        """Return True once every leg is driven and the final poses are recorded."""
        return self.follower.done and self._settle_until is None

    def cmd_subscribers(self):
        """Return how many subscriptions the robot's cmd_vel publisher is matched with."""
        return self._cmd.get_subscription_count()

    def _publish(self, stamp, linear, angular):
        # sim time as this process last saw it on /clock: if it is already cmd_vel_timeout
        # past the stamp, the controller (whose clock is at least as far) drops the command
        now = self.node.get_clock().now().nanoseconds * 1e-9
        if now - stamp_seconds(stamp) >= CMD_VEL_TIMEOUT:
            self.stale += 1
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
        self.odom_count += 1
        self.odom_path.append(pose[:2])
        now = stamp_seconds(msg.header.stamp)
        if self.truth is None or not self.enabled:
            return
        if self.start_after is not None and now < self.start_after:
            return  # queued before the course began (e.g. while the stack came up)
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

    def _tag(self):
        return f'[drive_square] {self.name}: ' if self.namespace else '[drive_square] '

    def _progress(self, now, pose):
        """Print where the current leg stands, once per second of sim time."""
        if self._next_progress is not None and now < self._next_progress:
            return
        self._next_progress = now + 1.0
        if self.follower.done or self.follower.start is None or self.namespace:
            return  # several robots: leg reports only, or the output is unreadable
        index = self.follower.index
        leg = self.legs[index]
        done = leg_progress(leg, self.follower.start, pose)
        if leg.kind == 'straight':
            text = f'{done:.2f} of {leg.target:.2f} m'
        else:
            text = f'{math.degrees(done):.0f} of {math.degrees(leg.target):.0f} deg'
        print(f'{self._tag()}t={now:6.1f} s  leg {index + 1}/{len(self.legs)} {leg.kind}: '
              f'{text}', flush=True)

    def _report_leg(self, index):
        leg = self.legs[index]
        start, end = self.odom_marks[index], self.odom_marks[index + 1]
        if leg.kind == 'straight':
            value = f'{math.hypot(end[0] - start[0], end[1] - start[1]):.3f} m'
        else:
            turn = math.atan2(math.sin(end[2] - start[2]), math.cos(end[2] - start[2]))
            value = f'{math.degrees(turn):.1f} deg'
        print(f'{self._tag()}leg {index + 1}/{len(self.legs)} done: {leg.kind}, '
              f'odometry says {value}', flush=True)


class SquareDriver(Node):
    """Node ``drive_square``: one :class:`RobotDriver` per robot namespace."""

    def __init__(self, legs, namespaces=('',), settle=0.4):
        """
        Create the node and a driver per robot.

        :param legs: list of :class:`~amr_description.core.course.Leg` (every robot).
        :param namespaces: robot namespaces ('' = the robot without a namespace).
        :param settle: seconds of sim time to stand still between legs.
        """
        super().__init__('drive_square')
        self.legs = legs
        self.robots = [RobotDriver(self, ns, legs, settle) for ns in namespaces]
        self.spinner = SingleThreadedExecutor()
        self.spinner.add_node(self)

    def spin_once(self, timeout):
        """Run at most one callback, waiting up to ``timeout`` s."""
        self.spinner.spin_once(timeout_sec=timeout)

    def call(self, client, request, timeout):
        """
        Call a service, spinning this node's executor until the answer.

        :returns: the response, or None when the service is absent or silent for ``timeout``
            wall seconds.
        """
        if not client.wait_for_service(timeout_sec=timeout):
            return None
        future = client.call_async(request)
        # spin_once, not spin_until_future_complete: with a time-out the latter (rclpy jazzy)
        # turns its wait into a busy loop that takes the CPU the simulator needs
        deadline = time.monotonic() + timeout
        while not future.done() and time.monotonic() < deadline:
            self.spinner.spin_once(timeout_sec=min(0.1, max(0.0, deadline - time.monotonic())))
        if not future.done():
            client.remove_pending_request(future)
            return None
        return future.result()

    @property
    def done(self):
        """Return True once every robot finished its course."""
        return all(robot.done for robot in self.robots)

    def enable(self, start=None):
        """
        Start driving every robot, from odometry stamped at or after ``start``.

        :param start: sim time in s; None for this node's clock (the last /clock it took).
            In lock-step give the paused simulator's own time (:meth:`LockStep.sim_time`):
            odometry the simulator published while it ran ahead may still be queued here, and
            this node's clock may lag it by more than ``cmd_vel_timeout``.
        """
        if start is None:
            start = self.get_clock().now().nanoseconds * 1e-9
        for robot in self.robots:
            robot.start_after = start - 1e-6
            robot.enabled = True


def _controllers_active(node, controller_managers, timeout):
    """
    Wait until every controller in :data:`CONTROLLERS` is active in every controller manager.

    :param node: :class:`SquareDriver` (its executor is spun here).
    :param controller_managers: fully qualified controller manager names.
    :param timeout: wall seconds.
    :returns: the list of controller managers that are not ready (empty when all are).
    """
    from controller_manager_msgs.srv import ListControllers

    waiting = list(controller_managers)
    clients = {cm: node.create_client(ListControllers, f'{cm}/list_controllers')
               for cm in waiting}
    deadline = time.monotonic() + timeout
    try:
        while waiting and time.monotonic() < deadline:
            for cm in list(waiting):
                result = node.call(clients[cm], ListControllers.Request(), 0.5)
                if result is not None:
                    states = {c.name: c.state for c in result.controller}
                    if all(states.get(name) == 'active' for name in CONTROLLERS):
                        waiting.remove(cm)
            if waiting:
                time.sleep(0.2)
        return waiting
    finally:
        for client in clients.values():
            node.destroy_client(client)


def _wait_connected(node, timeout, lockstep=None):
    """
    Wait until every robot's cmd_vel has a subscriber and its odometry and ground truth arrive.

    Commands published before DDS matched the publisher with diff_drive_controller's
    subscription would be lost.

    :param node: :class:`SquareDriver`.
    :param timeout: wall seconds.
    :param lockstep: :class:`LockStep` of the paused simulator (advanced while waiting), or
        None.
    :returns: the list of robots (names) not connected in time (empty when all are).
    """
    deadline = time.monotonic() + timeout

    def pending():
        missing = []
        for r in node.robots:
            what = [w for w, ok in (('cmd_vel subscriber', r.cmd_subscribers() > 0),
                                    ('odometry', r.odom_count > 0),
                                    ('ground truth', r.truth is not None)) if not ok]
            if what:
                missing.append(f'{r.name} ({", ".join(what)})')
        return missing
    while pending() and time.monotonic() < deadline:
        if lockstep is not None:
            lockstep.advance()
        node.spin_once(0.1)
    return pending()


class LockStep:
    """
    Pause ``mujoco_sim`` and advance it one period at a time (simulation_interfaces services).

    :ivar steps: physics steps per advance (``period / physics_step``, at least 1).
    """

    def __init__(self, node, period, sim_node=SIM_NODE, timeout=30.0):
        """
        Create the service clients and read the simulator's ``physics_step``.

        :param node: :class:`SquareDriver` (its executor is spun while waiting).
        :param period: sim seconds per advance (> 0).
        :param sim_node: fully qualified name of the simulator node.
        :param timeout: wall seconds to wait for a service answer.
        :raises RuntimeError: one line when the simulator cannot be paused.
        """
        from rcl_interfaces.srv import GetParameters
        from simulation_interfaces.msg import Result
        from simulation_interfaces.msg import SimulationState
        from simulation_interfaces.srv import SetSimulationState
        from simulation_interfaces.srv import StepSimulation
        self.node = node
        self.timeout = timeout
        self._ok = Result.RESULT_OK
        self._state_type = SimulationState
        self._state_request = SetSimulationState.Request
        self._already = SetSimulationState.Response.ALREADY_IN_TARGET_STATE
        self._state = node.create_client(SetSimulationState, f'{sim_node}/set_simulation_state')
        self._step = node.create_client(StepSimulation, f'{sim_node}/step_simulation')
        self._step_request = StepSimulation.Request()
        params = node.create_client(GetParameters, f'{sim_node}/get_parameters')
        physics_step = 0.001
        answer = node.call(params, GetParameters.Request(names=['physics_step']), timeout)
        node.destroy_client(params)
        if answer is not None and answer.values and answer.values[0].type == 3:
            physics_step = answer.values[0].double_value
        self.steps = max(1, int(round(period / physics_step)))
        self._step_request.steps = self.steps

    def set_paused(self, paused):
        """
        Pause or resume the simulator.

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        request = self._state_request()
        S = self._state_type
        request.state.state = S.STATE_PAUSED if paused else S.STATE_PLAYING
        answer = self.node.call(self._state, request, self.timeout)
        if answer is None:
            raise RuntimeError(f'{SIM_NODE}/set_simulation_state did not answer')
        if answer.result.result not in (self._ok, self._already):
            raise RuntimeError(f'{SIM_NODE}/set_simulation_state: '
                               f'{answer.result.error_message}')

    def sim_time(self):
        """
        Return the time (s) at which the paused simulator stands, read from ``/clock``.

        When the pause is answered, /clock messages of the running simulator may still be in
        flight; a paused ``mujoco_sim`` repeats its time on /clock every 0.1 s of wall time,
        so two equal values in a row are that time.

        :raises RuntimeError: one line when /clock does not repeat a value within the
            time-out (the simulator is not paused or publishes no /clock).
        """
        values = collections.deque(maxlen=2)  # nanoseconds of the last two messages
        # best effort matches any /clock publisher; a lost message only delays the answer
        subscription = self.node.create_subscription(
            Clock, '/clock', lambda msg: values.append(msg.clock.sec * 1_000_000_000 +
                                                       msg.clock.nanosec),
            QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
        try:
            deadline = time.monotonic() + self.timeout
            while time.monotonic() < deadline:
                if len(values) == 2 and values[0] == values[1]:
                    return values[1] * 1e-9
                self.node.spin_once(0.1)
        finally:
            self.node.destroy_subscription(subscription)
        raise RuntimeError(f'/clock did not hold still within {self.timeout:g} s of pausing '
                           f'{SIM_NODE}')

    def advance(self):
        """
        Advance the paused simulator by :attr:`steps` physics steps; answers when done.

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        answer = self.node.call(self._step, self._step_request, self.timeout)
        if answer is None:
            raise RuntimeError(f'{SIM_NODE}/step_simulation did not answer within '
                               f'{self.timeout:g} s')
        if answer.result.result != self._ok:
            raise RuntimeError(f'{SIM_NODE}/step_simulation: {answer.result.error_message}')


def drive(node, deadline, lockstep=None, odom_timeout=10.0):
    """
    Spin ``node`` until every robot finished its course or the wall-clock ``deadline``.

    With ``lockstep``, the simulator is advanced one period at a time and every robot's
    next odometry message is answered before the next advance.

    :param node: :class:`SquareDriver`.
    :param deadline: ``time.monotonic()`` value to give up at.
    :param lockstep: :class:`LockStep` or None (free-running simulator).
    :param odom_timeout: wall seconds to wait for odometry after an advance.
    :returns: ``(advances, wall seconds spent in them, wall seconds waiting for odometry)``
        (zeros without ``lockstep``).
    :raises RuntimeError: one line when odometry stops arriving in lock-step.
    """
    node.enable(lockstep.sim_time() if lockstep is not None else None)
    advances, in_step, in_wait = 0, 0.0, 0.0
    while not node.done and time.monotonic() < deadline:
        if lockstep is None:
            node.spin_once(0.1)
            continue
        counts = [robot.odom_count for robot in node.robots]
        started = time.monotonic()
        lockstep.advance()
        advances += 1
        stepped = time.monotonic()
        in_step += stepped - started
        end = min(deadline, time.monotonic() + odom_timeout)
        while any(r.odom_count == c for r, c in zip(node.robots, counts)) and \
                time.monotonic() < end:
            node.spin_once(0.1)
        silent = [r.odom_topic for r, c in zip(node.robots, counts) if r.odom_count == c]
        if silent and time.monotonic() < deadline:
            raise RuntimeError(f'no message on {", ".join(silent)} within {odom_timeout:g} s '
                               f'after a step of {lockstep.steps} physics steps')
        in_wait += time.monotonic() - stepped
    # take what already arrived (the last settled poses) without waiting
    node.spin_once(0.0)
    return advances, in_step, in_wait


def _relative_path(points, origin):
    """Express planar points in the frame of ``origin`` = ``(x, y, yaw)``."""
    c, s = math.cos(origin[2]), math.sin(origin[2])
    return [((x - origin[0]) * c + (y - origin[1]) * s,
             -(x - origin[0]) * s + (y - origin[1]) * c) for x, y in points]


def _to_world(points, origin):
    """Map planar points given in the frame of ``origin`` = ``(x, y, yaw)`` to its parent."""
    c, s = math.cos(origin[2]), math.sin(origin[2])
    return [(origin[0] + x * c - y * s, origin[1] + x * s + y * c) for x, y in points]


def write_fleet_plot(path, robots, side):
    """
    Plot every robot's odometry and ground-truth paths to a PNG.

    One robot is drawn in its start frame (the commanded square from the origin); several
    are drawn in the simulator's ``world`` frame, each odometry path placed at its robot's
    ground-truth start pose, with each robot's commanded square.

    :param path: output PNG path.
    :param robots: list of dicts with ``name``, ``odom_path``, ``truth_path`` (lists of
        ``(x, y)`` in m, odom and world frames), ``odom_origin`` and ``truth_origin``
        (``(x, y, yaw)`` of the course start in each frame).
    :param side: commanded side length in m.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    single = len(robots) == 1
    fig, ax = plt.subplots(figsize=(7, 7), dpi=100)
    square = [(0, 0), (side, 0), (side, side), (0, side), (0, 0)]
    for i, robot in enumerate(robots):
        first = i == 0
        start = (0.0, 0.0, 0.0) if single else robot['truth_origin']
        corners = _to_world(square, start)
        ax.plot([p[0] for p in corners], [p[1] for p in corners], color='0.7',
                linestyle='--', label='commanded square' if first else None)
        odom = _to_world(_relative_path(robot['odom_path'], robot['odom_origin']), start)
        truth = _to_world(_relative_path(robot['truth_path'], robot['truth_origin']), start)
        if truth:
            ax.plot([p[0] for p in truth], [p[1] for p in truth], color='tab:blue',
                    label='ground truth' if first else None)
        if odom:
            ax.plot([p[0] for p in odom], [p[1] for p in odom], color='tab:red',
                    linewidth=0.8, label='odometry' if first else None)
        if not single:
            ax.annotate(robot['name'], (start[0], start[1]), textcoords='offset points',
                        xytext=(-14, -14), fontsize=9)
    ax.set_aspect('equal')
    if single:
        ax.set_xlabel('x [m] (start frame)')
        ax.set_ylabel('y [m] (start frame)')
        ax.set_title(f'amr: {side:g} m square, odometry vs ground truth')
        ax.legend(loc='center')
    else:
        ax.set_xlabel('x [m] (world)')
        ax.set_ylabel('y [m] (world)')
        ax.set_title(f'{len(robots)} robots: {side:g} m squares, odometry vs ground truth')
        ax.legend(loc='upper left', bbox_to_anchor=(1.0, 1.0))
        fig.tight_layout()
    ax.grid(True, alpha=0.3)
    fig.savefig(path)
    plt.close(fig)


def format_robot_table(legs, robots):
    """
    Format one row per robot (closures) and a per-leg summary over the robots.

    :param legs: the :class:`~amr_description.core.course.Leg` list every robot drove.
    :param robots: list of ``(name, odom_marks, truth_marks, stale)``: the poses at the start
        and at the end of each leg (``len(legs) + 1`` each) and the dropped command count.
    :returns: the two tables as one str (m and deg).
    """
    header = (f"{'robot':<6}  {'odom closure':>12}  {'odom hdg':>8}  {'true closure':>12}  "
              f"{'true hdg':>8}  {'dropped':>7}")
    lines = [header, '-' * len(header)]
    for name, odom, truth, stale in robots:
        od, oh = closure_error(odom)
        td, th = closure_error(truth)
        lines.append(f'{name:<6}  {od:>10.3f} m  {math.degrees(oh):>6.2f} d  '
                     f'{td:>10.3f} m  {math.degrees(th):>6.2f} d  {stale:>7}')
    lines.append('')
    header = (f"{'leg':>3}  {'kind':<8}  {'cmd':>7}  {'true min':>8}  {'true mean':>9}  "
              f"{'true max':>8}  {'|odom - true| max':>17}")
    lines += [header, '-' * len(header)]
    for i, leg in enumerate(legs):
        straight = leg.kind == 'straight'
        values, gaps = [], []
        for _, odom, truth, _ in robots:
            o = leg_delta(odom[i], odom[i + 1])[0 if straight else 1]
            t = leg_delta(truth[i], truth[i + 1])[0 if straight else 1]
            values.append(t if straight else math.degrees(t))
            gaps.append(abs(o - t) if straight else abs(math.degrees(o - t)))
        unit = 'm' if straight else 'd'
        cmd = leg.target if straight else math.degrees(leg.target)
        fmt = '.3f' if straight else '.1f'
        lines.append(f'{i + 1:>3}  {leg.kind:<8}  {cmd:>5{fmt}} {unit}  '
                     f'{min(values):>6{fmt}} {unit}  {sum(values) / len(values):>7{fmt}} {unit}'
                     f'  {max(values):>6{fmt}} {unit}  {max(gaps):>15{fmt}} {unit}')
    return '\n'.join(lines)


def _bringup(rtf, robots, log_path, viewer_port=8080):
    """
    Start the ``sim`` or ``fleet`` stack, output in ``log_path``; return (orch, log, url).

    The viewer runs on ``viewer_port`` when the stack has one (``url`` is then its page,
    otherwise None); ``viewer_port`` 0 leaves it out.
    """
    from amr_description.launch import stacks
    from amr_description.launch.orchestrator import Orchestrator

    argv = [f'rtf:={rtf}', 'headless:=true']
    if robots > 1:
        name = 'fleet'
        argv.append(f'robots:={robots}')
    else:
        name = 'sim'
    declared = {d.name for d in stacks.STACKS[name][1]}
    url = None
    if 'viewer' in declared:
        if viewer_port and 'viewer_port' in declared:
            argv.append(f'viewer_port:={viewer_port}')
            url = f'http://127.0.0.1:{viewer_port}/'
        else:
            argv.append('viewer:=false')
    log = open(log_path, 'w')
    orchestrator = Orchestrator(stacks.describe(name, argv), stream=log)
    orchestrator.start()
    return orchestrator, log, url


def count_stale_lines(log_path):
    """Return how many commands diff_drive_controller logged as dropped in ``log_path``."""
    try:
        with open(log_path, 'r', errors='replace') as f:
            return sum(1 for line in f if STALE_LOG_LINE in line)
    except OSError:
        return 0


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
    parser.add_argument('--viewer-port', type=int, default=8080,
                        help='port of the viewer page that shows the robot live (8080; 0 = '
                        'no viewer)')
    opts = parser.parse_args(argv)
    if opts.robots < 1:
        parser.error(f'argument --robots: must be >= 1, got {opts.robots}')
    if not opts.lockstep_period > 0:
        parser.error('argument --lockstep-period: must be > 0')
    if opts.rtf < 0:
        parser.error('argument --rtf: must be >= 0')
    return opts


def _fail(message):
    print(f'[drive_square] error: {message}', file=sys.stderr, flush=True)
    return 1


def _report(opts, node, legs, log_path):
    """Print the tables, check drops and closures, write the PNGs; return the exit code."""
    robots = node.robots
    print()
    if len(robots) == 1:
        robot = robots[0]
        print(format_leg_table(legs, robot.odom_marks, robot.truth_marks))
        odom_err = closure_error(robot.odom_marks)
        truth_err = closure_error(robot.truth_marks)
        print()
        print(f'closure (end vs start): /odom {odom_err[0]:.3f} m, '
              f'{math.degrees(odom_err[1]):.1f} deg; ground truth {truth_err[0]:.3f} m, '
              f'{math.degrees(truth_err[1]):.1f} deg')
    else:
        print(format_robot_table(legs, [(r.name, r.odom_marks, r.truth_marks, r.stale)
                                        for r in robots]))
    print()
    plot = os.path.join(opts.output_dir, 'path.png')
    write_fleet_plot(plot, [{'name': r.name, 'odom_path': r.odom_path,
                             'truth_path': r.truth_path, 'odom_origin': r.odom_marks[0],
                             'truth_origin': r.truth_marks[0]} for r in robots], opts.side)
    written = [plot]
    if len(robots) == 1:
        scene = os.path.join(opts.output_dir, 'scene.png')
        from amr_description.launch.stacks import read_urdf
        from amr_description.sim.render import render_scene
        from amr_description.sim.render import save_png
        save_png(render_scene(read_urdf(), robots[0].truth_marks[-1], robots[0].truth_path),
                 scene)
        written.append(scene)
    print(f'wrote {" and ".join(written)}')
    dropped = sum(r.stale for r in robots)
    logged = count_stale_lines(log_path) if log_path else 0
    if dropped or logged:
        return _fail(f'{max(dropped, logged)} command(s) dropped as older than cmd_vel_timeout '
                     f'({CMD_VEL_TIMEOUT:g} s of sim time): the driver fell behind the '
                     'simulation (try --rtf 0, the lock-step mode)')
    missed = []
    for r in robots:
        distance, heading = closure_error(r.truth_marks)
        if distance > opts.tolerance or math.degrees(heading) > opts.tolerance_deg:
            missed.append(f'{r.name} {distance:.3f} m {math.degrees(heading):.2f} deg')
    if missed:
        return _fail(f'ground-truth closure beyond {opts.tolerance:g} m / '
                     f'{opts.tolerance_deg:g} deg: {", ".join(missed)}')
    return 0


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
    shutdown.init(['drive_square', '--ros-args', '-p', 'use_sim_time:=true'] + ros_args[1:])
    try:
        if not opts.no_bringup:
            log_path = os.path.join(opts.output_dir, 'sim_stack.log')
            what = f'{opts.robots} robots' if opts.robots > 1 else 'the sim stack'
            print(f'[drive_square] starting {what} (rtf {opts.rtf:g}); its output goes '
                  f'to {log_path}', flush=True)
            orchestrator, log, url = _bringup(opts.rtf, opts.robots, log_path,
                                              opts.viewer_port)
            if url:
                print(f'[drive_square] watch it drive: open {url} in a browser', flush=True)
        legs = square_course(opts.side, opts.speed, opts.turn_rate)
        node = shutdown.create(SquareDriver, legs, robot_namespaces(opts.robots))
        print('[drive_square] waiting for joint_state_broadcaster and diff_drive_controller '
              'to be active ...', flush=True)
        started = time.monotonic()
        startup_timeout = opts.startup_timeout + 2.0 * opts.robots
        waiting = _controllers_active(node, [r.controller_manager for r in node.robots],
                                      timeout=startup_timeout)
        if waiting:
            return _fail(f'the controllers of {", ".join(waiting)} did not become active '
                         f'within {startup_timeout:g} s (see the sim stack log)')
        if opts.rtf == 0:
            lockstep = LockStep(node, opts.lockstep_period)
            lockstep.set_paused(True)
        silent = _wait_connected(node, 30.0, lockstep)
        if silent:
            return _fail(f'nothing connected within 30 s of the controllers being active: '
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
            return _fail(f'the course did not finish within {opts.timeout:g} s (legs of '
                         f'{len(legs)} finished: {finished})')
        return _report(opts, node, legs, log_path)
    except RuntimeError as exc:
        return _fail(str(exc))
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
