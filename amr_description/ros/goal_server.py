# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Action servers and clients for goals that run for seconds, driven by the node's timers.

rclpy runs an action's execute callback as an executor task; a callback that waits (or a
coroutine that awaits) would block a single-threaded executor or, in Jazzy, make it spin on
the pending task. Nav2's servers (``nav2_util::SimpleActionServer``) run one goal at a time
on a worker thread and a new goal pre-empts the running one. :class:`SingleGoalServer` gives
the same behaviour on one thread: an accepted goal is marked EXECUTING at once, the node's
timer does the work (:attr:`SingleGoalServer.current`, :meth:`SingleGoalServer.feedback`)
and :meth:`SingleGoalServer.finish` sets the terminal state and hands the result to rclpy,
whose result service answers the clients. A new goal pre-empts the current one, which is
aborted with an empty result, as SimpleActionServer's ``accept_pending_goal`` terminates it.
Cancel requests are accepted; the timer sees :attr:`SingleGoalServer.cancel_requested`.

:class:`GoalClient` sends goals with callbacks only (no waiting), for a node that drives
other servers from a timer (the navigator).
"""

from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient
from rclpy.action import ActionServer
from rclpy.action import CancelResponse
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy


class SingleGoalServer:
    """
    One goal at a time; see the module docstring.

    :param node: the rclpy node.
    :param action_type: e.g. ``nav2_msgs.action.FollowPath``.
    :param name: the action name (relative to the node's namespace).
    :param on_goal: ``f(handle)`` called when a goal becomes the current one.
    """

    def __init__(self, node, action_type, name, on_goal):
        """Create the rclpy action server."""
        self.node = node
        self.type = action_type
        self.name = name
        self.on_goal = on_goal
        self.current = None
        self.server = ActionServer(node, action_type, name, execute_callback=self._late,
                                   handle_accepted_callback=self._on_accepted,
                                   cancel_callback=lambda handle: CancelResponse.ACCEPT)

    def _on_accepted(self, handle):
        previous = self.current
        self.current = handle
        handle._update_state(_rclpy.GoalEvent.EXECUTE)  # as ServerGoalHandle.execute does
        if previous is not None and previous.is_active:
            self.node.get_logger().info(f'{self.name}: a new goal pre-empts the current one')
            self.finish(previous, 'abort', self.type.Result())
        self.on_goal(handle)

    @staticmethod
    def _late(handle):
        return handle.request  # never called: goals are finished by finish()

    @property
    def active(self):
        """Return True while a current goal runs."""
        return self.current is not None and self.current.is_active

    @property
    def cancel_requested(self):
        """Return True when the current goal's client asked to cancel it."""
        return self.active and self.current.is_cancel_requested

    @property
    def goal(self):
        """Return the current goal's request message, or None."""
        return self.current.request if self.active else None

    def feedback(self, message):
        """Publish feedback for the current goal."""
        if self.active:
            self.current.publish_feedback(message)

    def finish(self, handle, outcome, result):
        """
        End a goal.

        :param handle: the goal (usually :attr:`current`).
        :param outcome: 'succeed', 'abort' or 'canceled'.
        :param result: the action's Result message.
        """
        if handle is None or not handle.is_active:
            return
        if outcome == 'canceled' and not handle.is_cancel_requested:
            outcome = 'abort'
        getattr(handle, outcome)()
        self.server.notify_execute(handle, lambda h: result)
        if handle is self.current:
            self.current = None

    def finish_current(self, outcome, result):
        """End the current goal (see :meth:`finish`)."""
        self.finish(self.current, outcome, result)

    def destroy(self):
        """Abort a running goal and destroy the server."""
        self.finish_current('abort', self.type.Result())
        self.server.destroy()


class GoalClient:
    """
    An action client used from timers: send a goal, hear how it ended, cancel it.

    :param node: the rclpy node.
    :param action_type: the action type.
    :param name: the action name.
    """

    def __init__(self, node, action_type, name):
        """Create the rclpy action client."""
        self.node = node
        self.type = action_type
        self.name = name
        self.client = ActionClient(node, action_type, name)
        self.handle = None
        self.busy = False  # from send() until the goal ends (or is rejected)
        self._serial = 0
        self._cancelled = 0  # goals sent up to this serial were cancelled

    def ready(self):
        """Return True when the server is discovered."""
        return self.client.server_is_ready()

    def send(self, goal, on_done=None):
        """
        Send ``goal``; a goal sent before is forgotten (the server pre-empts it).

        :param on_done: ``f(status, result)`` when the goal ends; status is a GoalStatus value
            (STATUS_ABORTED with result None for a rejected goal).
        """
        self._serial += 1
        serial = self._serial
        self.busy = True
        future = self.client.send_goal_async(goal)
        future.add_done_callback(lambda f: self._on_response(serial, f, on_done))

    def _on_response(self, serial, future, on_done):
        handle = future.result()
        if serial != self._serial:
            if serial <= self._cancelled and handle is not None and handle.accepted:
                handle.cancel_goal_async()  # cancelled before its answer came
            return
        if handle is None or not handle.accepted:
            self._end(serial, GoalStatus.STATUS_ABORTED, None, on_done)
            return
        self.handle = handle
        handle.get_result_async().add_done_callback(
            lambda f: self._end(serial, f.result().status, f.result().result, on_done))

    def _end(self, serial, status, result, on_done):
        if serial != self._serial:
            return
        self.busy = False
        self.handle = None
        if on_done is not None:
            on_done(status, result)

    def cancel(self):
        """Cancel the goal in flight (its end is not reported) and forget it."""
        self._serial += 1
        self._cancelled = self._serial - 1
        self.busy = False
        if self.handle is not None:
            self.handle.cancel_goal_async()
        self.handle = None

    def destroy(self):
        """Cancel and destroy the client."""
        self.cancel()
        self.client.destroy()
