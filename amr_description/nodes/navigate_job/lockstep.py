# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``navigate_job --rtf 0``: the simulator advanced as fast as the navigation stack keeps up.

A free-running simulator outruns Nav2's servers (their timers run on ``/clock``, their work on
the CPU): at 5.7x the route missed 5 of 7 waypoints (docs/navigation.md). Here the job pauses
the simulator once the stack is active and advances it :data:`TICK` s at a time through its
simulation_interfaces ``~/step_simulation`` service (as ``drive_square``'s lock-step). Before
the next advance it waits, up to :data:`WAIT_LIMIT` wall s, for each velocity command the
stack owes for the tick just simulated: the path follower's (``cmd_vel_nav``: controller_server
at 20 Hz, behavior_server at 10 Hz) and the velocity smoother's (the robot's
``diff_drive_controller/cmd_vel``), each expected on its own cadence (:class:`Cadence`). So
the control loop closes in every tick as it does in real time, and the simulation runs at the
stack's pace rather than the machine's. The localizer is waited for too (up to
:data:`LOCALIZER_WAIT` wall s): the newest ``map -> odom`` on ``/tf`` (SLAM's or AMCL's, stamped
with their last scan's stamp plus their transform timeout or tolerance) must be at most
:data:`MAP_LAG` s older than the simulation; a localizer that does not catch up within the wait
is not waited for again until it publishes. While nothing is owed (planning, the robot at
rest) a tick lasts at least ``TICK / IDLE_FACTOR`` wall s, so that a plan's wall latency costs
no more sim time than at :data:`IDLE_FACTOR` x real time. The costmaps are not waited for:
they place each scan with TF at its stamp.

:class:`Cadence` is plain logic; :class:`LockStepGovernor` is the rclpy thread.
"""

import threading
import time

TICK = 0.05
"""Sim seconds per advance: one period of controller_server and velocity_smoother (20 Hz)."""

WAIT_LIMIT = 0.5
"""Wall seconds to wait for an owed command before advancing anyway (a source that stopped)."""

MAP_LAG = 0.7
"""Sim seconds ``map -> odom`` may trail the simulation before the lock-step waits for the
localizer. slam_toolbox stamps it with its newest scan + ``transform_timeout`` (0.2 s), so on
time it leads the simulation; 0.7 s leaves room for a scan period and for the node's Python
TF listener, measured up to 0.28 s behind the scans (:mod:`amr_description.nodes.slam_toolbox`)."""

LOCALIZER_WAIT = 2.0
"""Wall seconds to wait for the localizer to catch up before advancing anyway."""

IDLE_FACTOR = 4.0
"""Most sim seconds per wall second while no command is owed."""

SOURCES = ('cmd_vel_nav', 'diff_drive_controller/cmd_vel')
"""The TwistStamped topics waited for (relative; ``enable_stamped_cmd_vel`` true, as
config/nav2_params.yaml)."""


class Cadence:
    """
    When a periodic source owes its next message, from the stamps of its last two.

    A source whose messages came ``period`` s apart is expected again at ``last + period``;
    it owes that message to the tick ``(t0, t1]`` holding that instant, and to no later tick
    (a source that stopped is owed nothing until it sends again).
    """

    def __init__(self):
        """Start with no message heard."""
        self.stamps = []

    def heard(self, t):
        """Record a message stamped ``t`` (sim s); older stamps than the last are ignored."""
        if not self.stamps or t > self.stamps[-1]:
            self.stamps = (self.stamps + [t])[-2:]

    def owed(self, t0, t1):
        """
        Return True when a message stamped in ``(t0, t1]`` is expected and not yet heard.

        :param t0: sim s before the tick.
        :param t1: sim s after it.
        """
        if len(self.stamps) < 2:
            return False
        before, last = self.stamps
        if last > t0:
            return False  # heard in this tick already
        expected = last + (last - before)
        return t0 < expected <= t1 + 1e-9


class LockStepGovernor:
    """
    Pause the simulator and advance it in lock-step with the stack (module docstring).

    Runs its own rclpy node and executor on a daemon thread, beside the job's navigator.

    :param namespace: the robot's namespace ('' for a single robot).
    :ivar ticks: advances made.
    :ivar waited: wall seconds spent waiting for owed commands.
    :ivar late: owed commands not heard within :data:`WAIT_LIMIT`, and waits for the localizer
        given up after :data:`LOCALIZER_WAIT`.
    :ivar error: the one-line error that stopped the thread, or None.
    """

    def __init__(self, namespace=''):
        """Create the node (name ``navigate_job_lockstep``) and its subscriptions."""
        import rclpy
        from geometry_msgs.msg import TwistStamped
        from tf2_msgs.msg import TFMessage
        from rclpy.executors import SingleThreadedExecutor
        from amr_description.ros.simulation_services import SimulationServices
        from amr_description.ros.transforms import stamp_seconds
        self._stamp_seconds = stamp_seconds
        self.node = rclpy.create_node('navigate_job_lockstep')
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.services = SimulationServices(self.node, self._spin_until)
        self.cadences = {}
        prefix = f'/{namespace.strip("/")}/' if namespace.strip('/') else '/'
        for topic in SOURCES:
            cadence = self.cadences[topic] = Cadence()
            self.node.create_subscription(
                TwistStamped, prefix + topic,
                lambda msg, c=cadence: c.heard(stamp_seconds(msg.header.stamp)), 10)
        self.map_stamp = None
        self.node.create_subscription(TFMessage, '/tf', self._on_tf, 100)
        self.ticks = 0
        self.waited = 0.0
        self.late = 0
        self.error = None
        self._stop = threading.Event()
        self._thread = None

    def _on_tf(self, msg):
        for transform in msg.transforms:
            if transform.header.frame_id.lstrip('/') == 'map':
                t = self._stamp_seconds(transform.header.stamp)
                self.map_stamp = t if self.map_stamp is None else max(self.map_stamp, t)

    def _spin_until(self, predicate):
        while not predicate() and not self._stop.is_set():
            self.executor.spin_once(timeout_sec=0.005)

    def start(self, timeout=30.0):
        """
        Pause the simulator and start advancing it on the thread.

        :param timeout: wall seconds for each simulator service to answer.
        :raises RuntimeError: one line when the simulator does not pause or answer.
        """
        physics_step = self.services.physics_step(timeout)
        steps = max(1, int(round(TICK / physics_step)))
        self.services.set_paused(True, timeout)
        t = self.services.paused_time(timeout)
        self._thread = threading.Thread(target=self._run,
                                        args=(steps, steps * physics_step, t, timeout),
                                        name='lockstep', daemon=True)
        self._thread.start()

    def _localizer_behind(self, t, given_up):
        """Return True when ``map -> odom`` trails sim time ``t`` by more than MAP_LAG."""
        if self.map_stamp is None or self.map_stamp == given_up:
            return False
        return self.map_stamp < t - MAP_LAG

    def _wait(self, behind, limit):
        """Spin while ``behind()`` for up to ``limit`` wall s; return ``behind()``."""
        waiting = time.monotonic()
        self._spin_until(lambda: not behind() or time.monotonic() > waiting + limit)
        self.waited += time.monotonic() - waiting
        return behind()

    def _run(self, steps, tick, t, timeout):
        given_up = None  # the map -> odom stamp the last wait for the localizer gave up on
        try:
            while not self._stop.is_set():
                began = time.monotonic()
                self.services.step(steps, timeout)
                self.ticks += 1
                t0, t = t, t + tick
                owed = [c for c in self.cadences.values() if c.owed(t0, t)]
                if owed:
                    self._wait(lambda: any(c.owed(t0, t) for c in owed), WAIT_LIMIT)
                    self.late += sum(c.owed(t0, t) for c in owed)
                if self._localizer_behind(t, given_up):
                    owed = True
                    if self._wait(lambda: self._localizer_behind(t, None), LOCALIZER_WAIT):
                        self.late += 1
                        given_up = self.map_stamp
                if not owed:
                    pause = began + tick / IDLE_FACTOR
                    self._spin_until(lambda: time.monotonic() >= pause)
        except RuntimeError as exc:
            if not self._stop.is_set():
                self.error = str(exc)

    def stop(self):
        """Stop advancing (the simulator stays paused) and destroy the node."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=10.0 + WAIT_LIMIT)
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
