# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Sim time of in-process nodes, set directly by a simulation thread instead of over /clock.

A node on sim time normally subscribes to /clock and sets its clocks in the callback. In the
simulator (and in a container of composed nodes) one thread knows the time first, so the nodes'
own /clock subscriptions are removed (:func:`take_over_time_source`) and the owner sets their
clocks at every instant, as rclpy's ``TimeSource.clock_callback`` would.
"""

import threading

from rclpy.executors import SingleThreadedExecutor
from rclpy.time import Time


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
    now = Time(nanoseconds=nanoseconds)
    source._last_time_set = now
    for clock in source._associated_clocks:
        clock.set_ros_time_override(now)


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
        handle = now._time_handle
        with self._lock:  # a node is dropped (under this lock) before it is destroyed
            for source in self._snapshot:
                source._last_time_set = now
                for clock in source._associated_clocks:
                    # Clock.set_ros_time_override without its type check and handle guard
                    clock.handle.set_ros_time_override(handle)


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
