# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The simulator's /clock: one clock per ROS domain, or following another simulator's.

:class:`ClockGuard` (``clock_source:=internal``) looks for another /clock publisher before
and after it starts publishing and asks the node to quit next to one; :class:`ClockFollower`
(``clock_source:=external``) hands another simulator's /clock to the engine.
"""

import threading
import time

import rclpy
import rclpy.clock
from rclpy.executors import SingleThreadedExecutor
from rosgraph_msgs.msg import Clock

CLOCK_CHECK_TIME = 1.5  # s (wall) looking for another /clock publisher before publishing
CLOCK_WATCH_TIME = 10.0  # s (wall) after which a late-found /clock publisher is not checked
CLOCK_CHECK_PERIOD = 0.1  # s (wall) between those looks

REFUSAL = ('another node already publishes /clock in this ROS domain: run one simulator per '
           'domain, or start this one with clock_source:=external to follow it')


class ClockGuard:
    """
    Publish /clock only when no other node does; refuse to run next to one.

    Runs every :data:`CLOCK_CHECK_PERIOD` s of wall time from the first spin: for
    :data:`CLOCK_CHECK_TIME` s the node publishes no /clock (the usual discovery time), then it
    publishes and keeps looking until :data:`CLOCK_WATCH_TIME` s (discovery on a loaded machine
    can take seconds).

    :param node: the simulator node (its ``create_publisher``, ``count_publishers``).
    :param on_refused: ``(one-line reason) -> None`` when another publisher is found.
    """

    def __init__(self, node, on_refused):
        """Start the wall-clock timer (the node's own clock is the maybe paused sim time)."""
        self._node = node
        self._on_refused = on_refused
        self.publisher = None  # the /clock publisher, once the check allowed it
        self._start = None
        self._timer = node.create_timer(
            CLOCK_CHECK_PERIOD, self._check,
            clock=rclpy.clock.Clock(clock_type=rclpy.clock.ClockType.STEADY_TIME))

    def _check(self):
        now = time.monotonic()
        if self._start is None:
            self._start = now
        others = self._node.count_publishers('/clock') - (1 if self.publisher is not None else 0)
        if others > 0:
            self._timer.cancel()
            self._node.get_logger().error(REFUSAL)
            self._on_refused(REFUSAL)
            return
        elapsed = now - self._start
        if self.publisher is None and elapsed >= CLOCK_CHECK_TIME:
            self.publisher = self._node.create_publisher(Clock, '/clock', 10)
        if elapsed >= CLOCK_WATCH_TIME:
            self._timer.cancel()


class ClockFollower:
    """
    Receive the external /clock in a hidden node spun by its own thread.

    Not on the simulator's executor: that one blocks in service callbacks that wait for the
    simulation (a controller switch waits for the next update), and the simulation waits for
    the external time, so one thread for both would stall until the service times out.

    :param node: the simulator node (context, name and namespace of the hidden node).
    :param on_time: ``(seconds) -> None`` for every /clock message (the follower's thread).
    """

    def __init__(self, node, on_time):
        """Create the hidden node and start its thread."""
        self._logger = node.get_logger()
        self._context = node.context
        self._node = rclpy.create_node(f'_{node.get_name()}_clock_follower',
                                       context=node.context, namespace=node.get_namespace())
        self._node.create_subscription(
            Clock, '/clock', lambda msg: on_time(msg.clock.sec + msg.clock.nanosec * 1e-9), 10)
        self._executor = SingleThreadedExecutor(context=node.context)
        self._executor.add_node(self._node)
        self._running = threading.Event()
        self._running.set()
        self._thread = threading.Thread(target=self._spin, name='clock_follower', daemon=True)
        self._thread.start()

    def _spin(self):
        try:
            while self._running.is_set() and self._context.ok():
                self._executor.spin_once(timeout_sec=0.1)
        except Exception as exc:  # noqa: B902 - e.g. the context shut down meanwhile
            if self._running.is_set():
                self._logger.error(f'external /clock follower stopped: {exc!r}')

    def stop(self):
        """Stop the thread and destroy the hidden node."""
        self._running.clear()
        self._thread.join(timeout=5.0)
        self._executor.shutdown(timeout_sec=0)
        self._node.destroy_node()
