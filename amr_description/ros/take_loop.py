# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A few subscriptions taken on a thread of their own, with no executor.

An rclpy executor rebuilds its wait set in Python at every wake-up and wraps every callback
in a task: 0.3-0.4 ms of CPU per message on this project's machines, which at the hundred
``/tf`` and hundred ``/clock`` messages a second of a simulated robot was most of an idle
localization node's CPU (docs/navigation.md, "The TF listener's and the clock's thread").
A :class:`TakeLoop` waits on a wait set of its subscriptions and one guard condition, and hands
each message, taken serialized (``raw``), to its handler; this is how rclpy's own
``wait_for_message`` waits and takes, with rclpy's ``WaitSet`` and ``take_message``.
"""

import contextlib
import threading

from rclpy.callback_groups import CallbackGroup
from rclpy.exceptions import InvalidHandle
from rclpy.guard_condition import GuardCondition
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy

WAIT_TIMEOUT_NS = 500_000_000
"""The loop checks its context at least this often (ns)."""

_LOOPS = '_amr_take_loops'
"""The node attribute listing its started take loops (:class:`TakeLoop`)."""


class NotOnExecutors(CallbackGroup):
    """
    A callback group no rclpy executor runs: its entities stay out of executors' wait sets.

    rclpy's executors wait only on the entities whose group's ``can_execute`` is true
    (``Executor._wait_for_ready_callbacks``), so a :class:`TakeLoop` may take the messages
    of a subscription in this group on a node that an executor spins.
    """

    def can_execute(self, entity):
        """Return False: never run by an executor."""
        return False

    def beginning_execution(self, entity):
        """Return False: never run by an executor."""
        return False

    def ending_execution(self, entity):
        """Do nothing."""


class TakeLoop:
    """
    Subscriptions on ``node`` whose messages go to their handlers on one daemon thread.

    The subscriptions are in a :class:`NotOnExecutors` group, so the node may be spun by an
    executor too. A handler that raises has its exception logged (one warning line per topic
    every 5 s) and the loop goes on. Add every subscription with :meth:`subscribe`, then
    :meth:`start`; :meth:`stop` joins the thread and destroys the subscriptions, and
    :func:`stop_loops_of` stops every loop of a node (our nodes' ``destroy_node`` does, see
    :mod:`amr_description.ros.node`). If a node is destroyed without that, the loop ends at its
    next wake-up (rclpy defers destroying a handle in use) with one error line while the
    context is still up: it never ends unseen.

    :param node: the rclpy node owning the subscriptions.
    :param name: the thread's name.
    """

    def __init__(self, node, name):
        """Keep the node; nothing is subscribed or started yet."""
        self.node = node
        self._name = name
        self._subs = []
        self._group = NotOnExecutors()
        self._guard = GuardCondition(None, None, context=node.context)
        self._stopping = False
        self._thread = None

    def subscribe(self, msg_type, topic, qos, handler, raw=True):
        """
        Subscribe ``topic``; ``handler(data)`` gets each message (bytes when ``raw``).

        :returns: the rclpy subscription.
        """
        sub = self.node.create_subscription(msg_type, topic, lambda _: None, qos, raw=raw,
                                            callback_group=self._group)
        self._subs.append((sub, handler))
        return sub

    def start(self):
        """Start the thread."""
        self.node.__dict__.setdefault(_LOOPS, []).append(self)
        self._thread = threading.Thread(target=self._run, daemon=True, name=self._name)
        self._thread.start()

    def _run(self):
        context, guard = self.node.context, self._guard
        try:
            wait_set = _rclpy.WaitSet(len(self._subs), 1, 0, 0, 0, 0, context.handle)
            while not self._stopping and context.ok():
                with contextlib.ExitStack() as in_use:  # no handle destroyed while used
                    wait_set.clear_entities()
                    for sub, _ in self._subs:
                        in_use.enter_context(sub.handle)
                        wait_set.add_subscription(sub.handle)
                    in_use.enter_context(guard.handle)
                    wait_set.add_guard_condition(guard.handle)
                    wait_set.wait(WAIT_TIMEOUT_NS)
                    ready = wait_set.get_ready_entities('subscription')
                    for sub, handler in self._subs:
                        if sub.handle.pointer in ready:
                            self._take_all(sub, handler)
        except Exception as exc:  # noqa: B902 - one line, not a thread's traceback
            if not self._stopping and context.ok():
                self.node.get_logger().error(
                    f'{self._name} stopped: {type(exc).__name__}: {" ".join(str(exc).split())}')

    def _take_all(self, sub, handler):
        while not self._stopping:
            taken = sub.handle.take_message(sub.msg_type, sub.raw)
            if taken is None:
                return
            try:
                handler(taken[0])
            except Exception as exc:  # noqa: B902 - garbage in must not end the loop
                self.node.get_logger().warning(
                    f'{sub.topic_name}: {type(exc).__name__}: {" ".join(str(exc).split())}',
                    throttle_duration_sec=5.0)

    def stop(self, timeout=2.0):
        """Wake the thread, join it (up to ``timeout`` s), destroy the subscriptions; once."""
        if self._guard is None:
            return
        self._stopping = True
        loops = self.node.__dict__.get(_LOOPS, [])
        if self in loops:
            loops.remove(self)
        try:
            self._guard.trigger()
        except Exception:  # noqa: B902 - the context is already shut down
            pass
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=timeout)
        for sub, _ in self._subs:
            try:
                self.node.destroy_subscription(sub)
            except InvalidHandle:  # the node was destroyed first
                pass
        self._subs = []
        self._guard.destroy()
        self._guard = None


def stop_loops_of(node):
    """Stop every started :class:`TakeLoop` of ``node`` (before destroying the node)."""
    for loop in list(node.__dict__.get(_LOOPS, ())):
        loop.stop()
