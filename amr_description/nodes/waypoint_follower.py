# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``waypoint_follower``: nav2_waypoint_follower (Jazzy), a managed (lifecycle) node.

Offers ``follow_waypoints`` (nav2_msgs/action/FollowWaypoints) and drives bt_navigator's
``navigate_to_pose`` one waypoint at a time (:class:`amr_description.nav.waypoints.WaypointRun`:
``goal_index``, ``number_of_loops``, ``stop_on_failure``), publishing ``current_waypoint`` as
feedback every ``loop_rate`` tick and when a waypoint is sent (upstream's loop does both in one
pass). The result lists the missed waypoints (index, pose and the
navigator's error code, or TASK_EXECUTOR_FAILED); the goal succeeds after the last waypoint, or
is aborted at the first miss with ``stop_on_failure``. A goal with no poses, or a
``goal_index`` past them, is aborted with one line. A cancel cancels the navigation too; a new
goal pre-empts the running one. A waypoint whose ``navigate_to_pose`` server is not found
within 5 s is missed (upstream waits for ever).

Parameters, with Nav2's code defaults: ``stop_on_failure`` (true), ``loop_rate`` (20 Hz),
``global_frame_id`` (map, used by GPS waypoints only), ``action_server_result_timeout``
(900.0 s), ``waypoint_task_executor_plugin`` (wait_at_waypoint) and, in that plugin's
namespace, ``plugin`` (``nav2_waypoint_follower::WaitAtWaypoint``), ``enabled`` (true) and
``waypoint_pause_duration`` (0 ms, wall time, as WaitAtWaypoint sleeps). Another task plugin
(PhotoAtWaypoint, InputAtWaypoint) is said in one line and WaitAtWaypoint runs instead.
``follow_gps_waypoints`` is not offered (it needs robot_localization's ``fromLL``). The other
parameters of the params file are listed once at configure. While active, ``ros2 param set``
changes ``loop_rate`` (at once; upstream's at the next goal) and ``stop_on_failure`` (also
for the goal running), as upstream's ``dynamicParametersCallback``; a ``loop_rate`` of 0 or
less is refused. Source:
``nav2_waypoint_follower/src/waypoint_follower.cpp`` and ``plugins/wait_at_waypoint.cpp``.
"""

import time

from action_msgs.msg import GoalStatus
from amr_description.nav.waypoints import WaypointRun
from amr_description.ros import shutdown
from amr_description.ros.goal_server import GoalClient
from amr_description.ros.goal_server import SingleGoalServer
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.parameters import read_parameters
from amr_description.ros.parameters import unused_parameters
from nav2_msgs.action import FollowWaypoints
from nav2_msgs.action import NavigateToPose
from nav2_msgs.msg import MissedWaypoint
from rcl_interfaces.msg import SetParametersResult

NODE_PARAMETERS = {'stop_on_failure': True, 'loop_rate': 20, 'global_frame_id': 'map',
                   'action_server_result_timeout': 900.0,
                   'waypoint_task_executor_plugin': 'wait_at_waypoint'}
WAIT_AT_WAYPOINT = 'nav2_waypoint_follower::WaitAtWaypoint'
SERVER_WAIT = 5.0
"""Seconds (wall) a waypoint waits for ``navigate_to_pose`` to be discovered, then is missed."""


class WaypointFollower(ManagedNode):
    """Node ``waypoint_follower``; see the module docstring."""

    def __init__(self, **kwargs):
        """Hold the params file's parameters; starts unconfigured (``kwargs``: rclpy's)."""
        super().__init__('waypoint_follower',
                         automatically_declare_parameters_from_overrides=True, **kwargs)
        self.p = {}
        self.pause = 0.0
        self._entities = []
        self.server = self.client = None
        self.run = None
        self.poses = []
        self.waiting_until = None  # wall time a waypoint's pause ends
        self.unsent_since = None  # wall time the navigator was first found missing

    def configure(self):
        """Read and check the parameters; say which task plugin runs."""
        self.get_logger().info('Configuring')
        self.p = read_parameters(self, NODE_PARAMETERS)
        task = self.p['waypoint_task_executor_plugin']
        task_params = read_parameters(self, {f'{task}.plugin': WAIT_AT_WAYPOINT,
                                             f'{task}.enabled': True,
                                             f'{task}.waypoint_pause_duration': 0})
        plugin = task_params[f'{task}.plugin']
        if plugin.replace('/', '::') != WAIT_AT_WAYPOINT:
            self.get_logger().warning(f"{task}: plugin '{plugin}' is not available here; "
                                      f'{WAIT_AT_WAYPOINT} runs instead')
        if self.p['loop_rate'] <= 0:
            raise ValueError(f"parameter 'loop_rate': expected a positive rate, got "
                             f"{self.p['loop_rate']}")
        enabled = task_params[f'{task}.enabled']
        self.pause = task_params[f'{task}.waypoint_pause_duration'] / 1000.0 if enabled else 0.0
        unused = unused_parameters(self, {**NODE_PARAMETERS, **task_params})
        if unused:
            self.get_logger().info('Parameters not used by this implementation: '
                                   + ', '.join(unused))

    def activate(self):
        """Offer the action and start the loop timer."""
        self.get_logger().info('Activating')
        self.client = GoalClient(self, NavigateToPose, 'navigate_to_pose')
        self.server = SingleGoalServer(self, FollowWaypoints, 'follow_waypoints',
                                       self._on_goal)
        # runs only while a goal does, as upstream's loop inside its action's execution
        self._timer = self.create_timer(1.0 / self.p['loop_rate'], self._tick)
        self._timer.cancel()
        self._entities = [self._timer]
        self.watch_parameters(self._on_set_parameters)

    def deactivate(self):
        """Abort a running goal; stop offering the action."""
        self.get_logger().info('Deactivating')
        self.unwatch_parameters()
        self.destroy_entities(self._entities)
        self._entities = []
        for part in (self.server, self.client):
            if part is not None:
                part.destroy()
        self.server = self.client = None
        self.run = None

    def _on_set_parameters(self, parameters):
        """Take ``loop_rate`` and ``stop_on_failure``; see the module docstring."""
        for parameter in parameters:
            if parameter.name == 'loop_rate' and parameter.value <= 0:
                line = f"parameter 'loop_rate': expected a positive rate, got {parameter.value}"
                return SetParametersResult(successful=False, reason=line)
        for parameter in parameters:
            if parameter.name == 'loop_rate':
                self.p['loop_rate'] = parameter.value
                self._timer.timer_period_ns = int(1e9 / parameter.value)
            elif parameter.name == 'stop_on_failure':
                self.p['stop_on_failure'] = parameter.value
                if self.run is not None:
                    self.run.stop_on_failure = parameter.value
        return SetParametersResult(successful=True)

    def _on_goal(self, handle):
        goal = handle.request
        self.get_logger().info(
            f'Received follow waypoint request with {len(goal.poses)} waypoints.')
        self.client.cancel()
        self.run = None
        self.waiting_until = self.unsent_since = None
        try:
            self.run = WaypointRun(len(goal.poses), goal.goal_index, goal.number_of_loops,
                                   self.p['stop_on_failure'])
        except ValueError as exc:
            self.get_logger().error(f'follow_waypoints: {exc}; goal aborted')
            result = FollowWaypoints.Result()
            result.error_code = FollowWaypoints.Result.UNKNOWN
            result.error_msg = str(exc)
            self.server.finish_current('abort', result)
            return
        self.poses = list(goal.poses)
        self._timer.reset()
        self._send()

    def _send(self):
        if not self.client.ready():
            if self.unsent_since is None:
                self.unsent_since = time.monotonic()
            elif time.monotonic() - self.unsent_since > SERVER_WAIT:
                self.unsent_since = None
                self.get_logger().error('navigate_to_pose action client failed to send goal '
                                        'to server (no server).')
                self._step(self.run.failed(0), f'Failed to process waypoint {self.run.index}')
            return
        self.unsent_since = None
        goal = NavigateToPose.Goal()
        goal.pose = self.poses[self.run.index]
        goal.pose.header.stamp = self.get_clock().now().to_msg()
        run = self.run
        self.client.send(goal, lambda status, result: self._on_navigated(run, status, result))
        # as upstream's loop, which sends a waypoint and publishes its index in one pass: every
        # waypoint is in the feedback, even one whose navigation ends before the next tick
        self.server.feedback(FollowWaypoints.Feedback(current_waypoint=run.index))

    def _on_navigated(self, run, status, result):
        if run is not self.run:
            return
        index = run.index
        if status == GoalStatus.STATUS_SUCCEEDED:
            self.get_logger().info(f'Succeeded processing waypoint {index}, processing '
                                   'waypoint task execution')
            self.waiting_until = time.monotonic() + self.pause
            return
        code = result.error_code if status == GoalStatus.STATUS_ABORTED and result else 0
        self._step(run.failed(code), f'Failed to process waypoint {index}')

    def _step(self, outcome, what):
        if outcome == 'next':
            self.get_logger().info(f'{what}, moving to next.')
            self._send()
            return
        result = FollowWaypoints.Result()
        result.missed_waypoints = [MissedWaypoint(index=i, goal=self.poses[i], error_code=c)
                                   for i, c in self.run.missed]
        if outcome == 'succeeded':
            self.get_logger().info(f'Completed all {len(self.poses)} waypoints requested.')
        else:
            self.get_logger().warning(f'{what} in waypoint list and stop on failure is '
                                      'enabled. Terminating action.')
        self.run = None
        self.server.finish_current('succeed' if outcome == 'succeeded' else 'abort', result)

    def _tick(self):
        if self.run is None:
            self._timer.cancel()
            return
        if self.server.cancel_requested:
            self.get_logger().info('Cancelling action.')
            self.client.cancel()
            self.run = None
            self.server.finish_current('canceled', FollowWaypoints.Result())
            return
        if not self.server.active:
            self.client.cancel()
            self.run = None
            return
        self.server.feedback(FollowWaypoints.Feedback(current_waypoint=self.run.index))
        if self.unsent_since is not None:
            self._send()
            return
        if self.waiting_until is not None and time.monotonic() >= self.waiting_until:
            self.waiting_until = None
            index = self.run.index
            self._step(self.run.reached(True), f'Handled task execution on waypoint {index}')


def main(args=None):
    """
    Run the waypoint follower until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(WaypointFollower, args)


if __name__ == '__main__':
    main()
