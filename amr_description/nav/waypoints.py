# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The order in which nav2_waypoint_follower visits waypoints, and what it reports missed.

A FollowWaypoints goal lists ``count`` poses; the follower starts at ``goal_index``, sends one
NavigateToPose goal at a time and, after the last pose, starts again from pose 0 until it has
made ``number_of_loops`` extra loops. A navigation that fails (aborted or cancelled), or a task
at the waypoint that fails (TASK_EXECUTOR_FAILED), is recorded as missed; with
``stop_on_failure`` the action then ends aborted, otherwise the next waypoint follows. Source:
``nav2_waypoint_follower/src/waypoint_follower.cpp`` (``followWaypointsHandler``, Jazzy).
"""

TASK_EXECUTOR_FAILED = 601
"""``nav2_msgs/action/FollowWaypoints`` result code of a failed task at a waypoint."""


class WaypointRun:
    """
    One FollowWaypoints goal's progress.

    :param count: number of poses in the goal.
    :param goal_index: the index to start at.
    :param number_of_loops: extra loops after the first pass.
    :param stop_on_failure: end the goal at the first missed waypoint.
    :raises ValueError: no poses, or ``goal_index`` not below ``count``.
    """

    def __init__(self, count, goal_index=0, number_of_loops=0, stop_on_failure=True):
        """Start at ``goal_index``, loop 0."""
        if count < 1:
            raise ValueError('no waypoints in the goal')
        if not 0 <= goal_index < count:
            raise ValueError(f'goal_index {goal_index} is outside the {count} waypoints')
        self.count = count
        self.index = goal_index
        self.loop = 0
        self.loops = number_of_loops
        self.stop_on_failure = stop_on_failure
        self.missed = []
        """``[(index, error_code), ...]`` in the order they were missed."""

    def reached(self, task_succeeded=True):
        """
        Record that the navigation to the current waypoint succeeded.

        :param task_succeeded: what the waypoint's task (e.g. a pause) returned.
        :returns: ``'next'`` (go to :attr:`index`), ``'succeeded'`` or ``'aborted'``.
        """
        if not task_succeeded:
            return self.failed(TASK_EXECUTOR_FAILED)
        return self._advance()

    def failed(self, error_code):
        """
        Record that the current waypoint was missed with ``error_code``.

        :returns: ``'next'``, ``'succeeded'`` (the last one was missed without
            ``stop_on_failure``) or ``'aborted'``.
        """
        self.missed.append((self.index, int(error_code)))
        if self.stop_on_failure:
            return 'aborted'
        return self._advance()

    def _advance(self):
        self.index += 1
        if self.index < self.count:
            return 'next'
        if self.loop == self.loops:
            return 'succeeded'
        self.index = 0
        self.loop += 1
        return 'next'
