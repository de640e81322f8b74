# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Sim time of in-process nodes, set directly by a simulation thread instead of over /clock.

A node on sim time normally subscribes to /clock and sets its clocks in the callback. In the
simulator (and in a container of composed nodes) one thread knows the time first, so the nodes'
own /clock subscriptions are removed (:func:`take_over_time_source`) and the owner sets their
clocks at every instant, as rclpy's ``TimeSource.clock_callback`` would. A node spun on its
own hears /clock on a thread of its own instead of its executor (:func:`take_clock_on_thread`).
"""

import threading
import weakref

from amr_description.ros.cdr import clock_nanoseconds
from amr_description.ros.take_loop import TakeLoop
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rclpy.time import Time
from rosgraph_msgs.msg import Clock


def take_over_time_source(node):
    """
    Stop a node's /clock subscription so the caller can drive its sim time directly.

    Only for nodes in this process with ``use_sim_time`` true; the caller then sets the time
    of the source's clocks at every /clock instant, as rclpy ``TimeSource.clock_callback``
    does. Call it before the node is added to an executor (or on the executor's thread).

    :param node: an rclpy node.
    :returns: the node's ``TimeSource``, or None when the node does not use sim time (then it
        is left alone).
    """
    source = getattr(node, '_time_source', None)
    if source is None or not source.ros_time_is_active:
        return None
    subscription = getattr(source, '_clock_sub', None)
    if subscription is not None:
        node.destroy_subscription(subscription)
        source._clock_sub = None
    return source


def set_source_time(source, nanoseconds):
    """
    Set the clocks of an rclpy ``TimeSource`` to sim time, as its ``clock_callback`` does.

    :param source: the ``TimeSource`` (its own /clock subscription removed).
    :param nanoseconds: the sim time (int, ns).
    """
    _set_clocks(source, Time(nanoseconds=nanoseconds), guarded=True)


def _set_clocks(source, now, guarded):
    """
    Set the clocks of ``source`` to ``now`` (an rclpy ``Time``), as ``clock_callback`` does.

    :param guarded: False skips ``Clock.set_ros_time_override``'s type check and handle guard,
        for a caller whose lock keeps the clocks' nodes alive (:meth:`SimTime.set_time`).
    """
    source._last_time_set = now
    for clock in source._associated_clocks:
        if guarded:
            clock.set_ros_time_override(now)
        else:
            clock.handle.set_ros_time_override(now._time_handle)


_CLOCK_LOOPS = weakref.WeakKeyDictionary()  # node -> TakeLoop taking its /clock
_CLOCK_LOOPS_LOCK = threading.Lock()


def take_clock_on_thread(node):
    """
    Take ``node``'s ``/clock`` on a thread of its own instead of the node's executor.

    rclpy's ``TimeSource`` subscribes ``/clock`` on the node (depth 1, best effort) and its
    executor wakes for every message: 100 times a second of sim time, 0.3-0.4 ms of CPU each
    (docs/navigation.md, "The TF listener's and the clock's thread"). Here the same
    subscription, on the same node (so with the same remaps), is taken serialized by a
    :class:`amr_description.ros.take_loop.TakeLoop` that sets the source's clocks as
    ``TimeSource.clock_callback`` does. Only when the node subscribes ``/clock`` itself
    (``use_sim_time`` true, the subscription not taken over already); once per node. The
    thread lasts until :func:`stop_clock_threads` or the node's destruction.

    :param node: an rclpy node (not yet spun, or on the executor's thread).
    :returns: True when the clock was taken now.
    """
    source = getattr(node, '_time_source', None)
    if getattr(source, '_clock_sub', None) is None:
        return False
    with _CLOCK_LOOPS_LOCK:
        if node in _CLOCK_LOOPS:
            return False
        take_over_time_source(node)
        loop = TakeLoop(node, f'{node.get_name()}_clock')
        loop.subscribe(Clock, '/clock', QoSProfile(depth=1,
                                                   reliability=ReliabilityPolicy.BEST_EFFORT),
                       lambda data: set_source_time(source, clock_nanoseconds(data)))
        _CLOCK_LOOPS[node] = loop
    loop.start()
    return True


def stop_clock_threads():
    """Stop every thread of :func:`take_clock_on_thread` (before the nodes are destroyed)."""
    with _CLOCK_LOOPS_LOCK:
        loops = list(_CLOCK_LOOPS.values())
        _CLOCK_LOOPS.clear()
    for loop in loops:
        loop.stop()


class SimTime:
    """
    The sim time of in-process nodes, set by the simulation thread without DDS.

    Nodes are adopted when they are added to the executor (their /clock subscription is
    destroyed then, on the adding thread, before any executor waits on it) and dropped when
    they are removed; :meth:`set_time` (simulation thread) sets every adopted clock. A lock keeps
    :meth:`set` off a node that is being removed (and destroyed right after).
    """

    def __init__(self):
        """Start with no node."""
        self._lock = threading.Lock()
        self._sources = {}   # node -> TimeSource
        self._snapshot = ()

    def adopt(self, node):
        """Take over ``node``'s time source when it uses sim time (see take_over_time_source)."""
        source = take_over_time_source(node)
        if source is not None:
            with self._lock:
                self._sources[node] = source
                self._snapshot = tuple(self._sources.values())

    def drop(self, node):
        """Stop setting ``node``'s clocks (before it is destroyed)."""
        with self._lock:
            if self._sources.pop(node, None) is not None:
                self._snapshot = tuple(self._sources.values())

    def set_time(self, t):
        """Set every adopted clock to sim time ``t`` (s), as ``TimeSource.clock_callback``."""
        now = Time(nanoseconds=int(round(t * 1e9)))
        with self._lock:  # a node is dropped (under this lock) before it is destroyed
            for source in self._snapshot:
                _set_clocks(source, now, guarded=False)


class SimTimeExecutor(SingleThreadedExecutor):
    """A single-threaded executor whose added nodes get their sim time from :class:`SimTime`."""

    def __init__(self, sim_time, context=None):
        """:param sim_time: the :class:`SimTime` adopting every added node."""
        super().__init__(context=context)
        self.sim_time = sim_time
        self.exempt = set()

    def add_node(self, node):
        """Adopt ``node``'s time source (unless exempt), then add it."""
        if node not in self.exempt:
            self.sim_time.adopt(node)
        return super().add_node(node)

    def remove_node(self, node):
        """Drop ``node`` from the sim time, then remove it."""
        self.sim_time.drop(node)
        super().remove_node(node)
