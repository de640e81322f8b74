# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``drive_square`` node: one course follower per robot, lock-step with the simulator."""

import math
import time

from amr_description.core.course import CourseFollower
from amr_description.core.course import leg_progress
from amr_description.launch.stacks import CONTROLLERS
from amr_description.ros.node import Node
from amr_description.ros.simulation_services import SimulationServices
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor

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
        self.odom_stamp = -math.inf  # sim s of the newest odometry message taken
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
        self.odom_stamp = max(self.odom_stamp, now)
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
        self.simulation = SimulationServices(self, self._spin_until, SIM_NODE)

    def spin_once(self, timeout):
        """Run at most one callback, waiting up to ``timeout`` s."""
        self.spinner.spin_once(timeout_sec=timeout)

    def _spin_until(self, predicate):
        while not predicate():
            self.spinner.spin_once(timeout_sec=0.1)

    def call(self, client, request, timeout):
        """
        Call a service, spinning this node's executor until the answer.

        :returns: the response, or None when the service is absent or silent for ``timeout``
            wall seconds.
        """
        return self.simulation.call(client, request, timeout)

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


def controllers_active(node, controller_managers, timeout):
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


def wait_connected(node, timeout, lockstep=None):
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
    :ivar period: sim seconds per advance (``steps * physics_step``).
    """

    def __init__(self, node, period, timeout=30.0):
        """
        Read the simulator's ``physics_step`` through ``node.simulation``.

        :param node: :class:`SquareDriver` (its executor is spun while waiting).
        :param period: sim seconds per advance (> 0).
        :param timeout: wall seconds to wait for a service answer.
        """
        self.simulation = node.simulation
        self.timeout = timeout
        physics_step = self.simulation.physics_step(timeout)
        self.steps = max(1, int(round(period / physics_step)))
        self.period = self.steps * physics_step

    def set_paused(self, paused):
        """
        Pause or resume the simulator.

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        self.simulation.set_paused(paused, self.timeout)

    def sim_time(self):
        """
        Return the time (s) at which the paused simulator stands, read from ``/clock``.

        :raises RuntimeError: one line when /clock does not hold still (see
            :meth:`~amr_description.ros.simulation_services.SimulationServices.paused_time`).
        """
        return self.simulation.paused_time(self.timeout)

    def advance(self):
        """
        Advance the paused simulator by :attr:`steps` physics steps; answers when done.

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        self.simulation.step(self.steps, self.timeout)


def drive(node, deadline, lockstep=None, odom_timeout=10.0):
    """
    Spin ``node`` until every robot finished its course or the wall-clock ``deadline``.

    With ``lockstep``, the simulator is advanced one period at a time and every robot's
    odometry of that period (stamped after the time the advance started from) is answered
    before the next advance. A message stamped earlier (the simulator's run-ahead before it
    paused, delivered late on a loaded machine) does not count: counting every message let
    the advances run ahead of the answered odometry by as many messages as were late, and the
    robot overshot its first leg by that many periods (a clean-clone run: 1.049 m for 1 m).

    :param node: :class:`SquareDriver`.
    :param deadline: ``time.monotonic()`` value to give up at.
    :param lockstep: :class:`LockStep` or None (free-running simulator).
    :param odom_timeout: wall seconds to wait for odometry after an advance.
    :returns: ``(advances, wall seconds spent in them, wall seconds waiting for odometry)``
        (zeros without ``lockstep``).
    :raises RuntimeError: one line when odometry stops arriving in lock-step.
    """
    start = lockstep.sim_time() if lockstep is not None else None
    node.enable(start)
    advances, in_step, in_wait = 0, 0.0, 0.0
    while not node.done and time.monotonic() < deadline:
        if lockstep is None:
            node.spin_once(0.1)
            continue
        before = start + advances * lockstep.period + 1e-6  # sim s the advance starts from
        started = time.monotonic()
        lockstep.advance()
        advances += 1
        stepped = time.monotonic()
        in_step += stepped - started
        end = min(deadline, time.monotonic() + odom_timeout)
        while any(r.odom_stamp <= before for r in node.robots) and time.monotonic() < end:
            node.spin_once(0.1)
        silent = [r.odom_topic for r in node.robots if r.odom_stamp <= before]
        if silent and time.monotonic() < deadline:
            raise RuntimeError(f'no message on {", ".join(silent)} within {odom_timeout:g} s '
                               f'after a step of {lockstep.steps} physics steps')
        in_wait += time.monotonic() - stepped
    # take what already arrived (the last settled poses) without waiting
    node.spin_once(0.0)
    return advances, in_step, in_wait
