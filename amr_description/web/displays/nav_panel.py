# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Navigation 2: what nav2_rviz_plugins' Nav2 panel shows, and its Cancel button.

- **Navigation** and **Localization**: ``active``, ``inactive`` or ``unknown``, asked of
  ``lifecycle_manager_navigation`` and ``lifecycle_manager_localization`` (``~/is_active``,
  std_srvs/Trigger) every :data:`PERIOD` s, as the panel does;
- **Feedback** of the newest NavigateToPose goal (``navigate_to_pose/_action/status`` and
  ``_action/feedback``, the action's own topics, as the panel subscribes them): its state
  (``active``, ``reached``, ``canceled``, ``aborted``), ETA, distance remaining, time taken
  and recoveries, in the panel's words and units (:func:`feedback_lines`);
- **Cancel**: cancels every goal of ``navigate_to_pose`` and ``navigate_through_poses``
  (action_msgs/CancelGoal with a zero goal id and stamp: all goals), whoever sent them,
  since a goal from the 2D Goal Pose tool is bt_navigator's own. Each request waits up to
  :data:`CANCEL_WAIT` s for its service to match (a request sent before is lost), on a
  thread of its own; a navigator that never offers it is one warning line.

The panel is shown once a lifecycle manager answers or a goal is seen. Source of the texts:
``nav2_rviz_plugins/src/nav2_panel.cpp`` (``getNavToPoseFeedbackLabel``).
"""

import threading
import time

from action_msgs.msg import GoalStatus
from action_msgs.msg import GoalStatusArray
from action_msgs.srv import CancelGoal
from amr_description.web.displays.base import Display
from nav2_msgs.action import NavigateToPose
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from std_srvs.srv import Trigger

PERIOD = 1.0
"""Seconds (wall) between two lifecycle questions and text refreshes."""
CANCEL_WAIT = 10.0
"""Seconds (wall) Cancel waits for a navigator's ``cancel_goal`` service not yet matched."""
STATUS_QOS = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                        durability=DurabilityPolicy.TRANSIENT_LOCAL)
"""rcl_action's status topic QoS."""
STATES = {GoalStatus.STATUS_ACCEPTED: 'active', GoalStatus.STATUS_EXECUTING: 'active',
          GoalStatus.STATUS_CANCELING: 'canceling', GoalStatus.STATUS_SUCCEEDED: 'reached',
          GoalStatus.STATUS_CANCELED: 'canceled', GoalStatus.STATUS_ABORTED: 'aborted'}
"""The panel's word for a goal status."""


def _seconds(duration):
    return duration.sec + duration.nanosec * 1e-9


def feedback_lines(status, feedback):
    """
    Return the panel's feedback lines for a goal.

    :param status: the goal's ``GoalStatus`` value, or None before any goal.
    :param feedback: its newest NavigateToPose feedback, or None.
    :returns: list of str (Markdown), e.g. ``['Feedback: **active**', 'ETA: 12 s', ...]``.
    """
    if status is None:
        return ['Feedback: **inactive**']
    lines = [f'Feedback: **{STATES.get(status, "unknown")}**']
    if feedback is not None:
        lines += [f'ETA: {_seconds(feedback.estimated_time_remaining):.0f} s',
                  f'Distance remaining: {feedback.distance_remaining:.2f} m',
                  f'Time taken: {_seconds(feedback.navigation_time):.0f} s',
                  f'Recoveries: {feedback.number_of_recoveries}']
    return lines


class NavigationPanelDisplay(Display):
    """The Nav2 panel: lifecycle states, the newest goal's feedback, Cancel."""

    order = 97
    panel_order = 6

    def __init__(self, node, server, frames):
        """Subscribe the action's topics; make the lifecycle and cancel clients."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self.goal = None  # the newest goal's id (bytes)
        self.status = None
        self.feedback = None
        self.active = {'Navigation': None, 'Localization': None}
        self._managers = {
            'Navigation': node.create_client(Trigger,
                                             '/lifecycle_manager_navigation/is_active'),
            'Localization': node.create_client(Trigger,
                                               '/lifecycle_manager_localization/is_active')}
        self._cancel = [node.create_client(CancelGoal, f'/{name}/_action/cancel_goal')
                        for name in ('navigate_to_pose', 'navigate_through_poses')]
        node.create_subscription(GoalStatusArray, '/navigate_to_pose/_action/status',
                                 self._on_status, STATUS_QOS)
        node.create_subscription(NavigateToPose.Impl.FeedbackMessage,
                                 '/navigate_to_pose/_action/feedback', self._on_feedback, 10)
        self._next = 0.0

    def build_panel(self, gui):
        """Add the panel's text and its Cancel button."""
        self._folder = gui.add_folder('Navigation 2', visible=False)
        with self._folder:
            self._text = gui.add_markdown('Navigation: **unknown**')
            self._button = gui.add_button('Cancel', disabled=True)
        self._button.on_click(lambda _: self.cancel())

    def _on_status(self, msg):
        if not msg.status_list:
            return
        newest = max(msg.status_list, key=lambda s: (s.goal_info.stamp.sec,
                                                     s.goal_info.stamp.nanosec))
        with self._lock:
            goal = bytes(newest.goal_info.goal_id.uuid)
            if goal != self.goal:
                self.feedback = None
            self.goal, self.status = goal, newest.status

    def _on_feedback(self, msg):
        with self._lock:
            if self.goal is None or bytes(msg.goal_id.uuid) == self.goal:
                self.feedback = msg.feedback

    def cancel(self):
        """Ask both navigators to cancel all their goals, on a thread (returns at once)."""
        threading.Thread(target=self._send_cancel, name='nav_panel_cancel', daemon=True).start()

    def _send_cancel(self):
        # a request sent before the service's reader matched ours is lost: a navigator
        # started just before the click (a suite's run) was asked nothing, though the log said
        # it was; each client now waits for its service first
        sent = 0
        for client in self._cancel:
            if client.wait_for_service(CANCEL_WAIT):  # at once when matched
                client.call_async(CancelGoal.Request())
                sent += 1
        log = self.node.get_logger()
        if sent:
            log.info('Navigation 2 panel: cancel requested')
        else:
            log.warning(f'Navigation 2 panel: cancel not sent: no navigator offers '
                        f'{self._cancel[0].service_name} after {CANCEL_WAIT:g} s')

    def _ask(self, label, client):
        if not client.service_is_ready():
            self.active[label] = None
            return
        future = client.call_async(Trigger.Request())
        future.add_done_callback(
            lambda f: self.active.__setitem__(label, f.result().success
                                              if f.result() is not None else None))

    def draw(self, context):
        """Ask the managers and refresh the text every :data:`PERIOD` s."""
        now = time.monotonic()
        if now < self._next:
            return
        self._next = now + PERIOD
        for label, client in self._managers.items():
            self._ask(label, client)
        words = {True: 'active', False: 'inactive', None: 'unknown'}
        with self._lock:
            lines = feedback_lines(self.status, self.feedback)
            running = self.status in (GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING)
        lines = [f'{label}: **{words[state]}**' for label, state in self.active.items()] + lines
        self._text.content = '\n\n'.join(lines)
        self._button.disabled = not running
        if not self._folder.visible and (self.status is not None
                                         or any(v is not None for v in self.active.values())):
            self._folder.visible = True  # shown once Nav2 is there
