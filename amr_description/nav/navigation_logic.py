# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The rules of Nav2's default navigation behaviour tree, as plain functions and tables.

``navigate_to_pose_w_replanning_and_recovery.xml`` (nav2_bt_navigator, Jazzy): replan at
1 Hz; a failed plan clears the global costmap and is retried once when a planner recovery
could help (``WouldAPlannerRecoveryHelp``); a failed FollowPath clears the local costmap and is
retried once when a controller recovery could help; otherwise, up to 6 times, the round robin
of recoveries runs (clear both costmaps, Spin 1.57 rad, Wait 5 s, BackUp 0.30 m at 0.15 m/s)
and the navigation starts over. The result's ``error_code`` is the smallest non-zero of the
error codes named in ``error_code_names`` (``bt_action_server_impl.hpp``,
``populateErrorCode``).
"""

import math

import numpy as np

NUMBER_OF_RETRIES = 6
"""The outer RecoveryNode's ``number_of_retries``."""

REPLAN_PERIOD = 1.0
"""The RateController's period (s)."""

PLANNER_HELPS = {200, 207, 208, 300, 307, 308}
"""ComputePathToPose / ThroughPoses codes a planner recovery can help: UNKNOWN, TIMEOUT,
NO_VALID_PATH (``would_a_planner_recovery_help_condition.cpp``)."""

CONTROLLER_HELPS = {100, 104, 105, 106}
"""FollowPath codes a controller recovery can help: UNKNOWN, PATIENCE_EXCEEDED,
FAILED_TO_MAKE_PROGRESS, NO_VALID_CONTROL (``would_a_controller_recovery_help_condition``)."""

RECOVERIES = (('clear', None), ('spin', 1.57), ('wait', 5.0), ('backup', (0.30, 0.15)))
"""The RoundRobin's children, in order."""

PASSED_GOAL_RADIUS = 0.5
"""RemovePassedGoals' ``radius`` in the through-poses tree (m)."""


def error_code(codes):
    """Return the smallest non-zero code of ``codes`` (0 when all are 0)."""
    nonzero = [int(c) for c in codes if c]
    return min(nonzero) if nonzero else 0


def recovery_could_help(compute_code, follow_code):
    """Return True when the recovery subtree would run for these last error codes."""
    return compute_code in PLANNER_HELPS or follow_code in CONTROLLER_HELPS


def remaining_distance(path_xy, robot_xy):
    """
    Return the path's length (m) from the pose closest to the robot to its end.

    NavigateToPose's feedback ``distance_remaining``: ``(n, 2)`` path in the robot's frame
    of reference (the global frame); 0 for an empty path.
    """
    p = np.asarray(path_xy, float).reshape(-1, 2)
    if not len(p):
        return 0.0
    k = int(np.argmin(np.hypot(p[:, 0] - robot_xy[0], p[:, 1] - robot_xy[1])))
    return float(np.hypot(*np.diff(p[k:], axis=0).T).sum()) if len(p) - k > 1 else 0.0


def time_remaining(distance, speed):
    """
    Return ``estimated_time_remaining`` (s): distance / |speed| when the robot moves.

    0 unless ``|speed| > 0.01`` m/s and ``distance > 0.1`` m (``navigate_to_pose.cpp``).
    """
    if abs(speed) > 0.01 and distance > 0.1:
        return distance / abs(speed)
    return 0.0


def passed_goals(goals_xy, robot_xy, radius=PASSED_GOAL_RADIUS):
    """
    Return how many leading goals the robot has passed (RemovePassedGoals).

    A goal is passed when the robot is within ``radius`` of it; the last goal is never removed.
    """
    n = 0
    for gx, gy in list(goals_xy)[:-1]:
        if math.hypot(gx - robot_xy[0], gy - robot_xy[1]) > radius:
            break
        n += 1
    return n
