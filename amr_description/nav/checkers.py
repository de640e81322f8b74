# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The controller server's goal and progress checkers (``nav2_controller/plugins``, Jazzy).

:class:`SimpleGoalChecker` and :class:`StoppedGoalChecker` say when the robot is at the path's
end; :class:`SimpleProgressChecker` and :class:`PoseProgressChecker` when it has stopped
making progress. Poses are ``(x, y, yaw)`` (m, rad) in one frame, speeds ``(v, w)`` (m/s,
rad/s), times in s.
"""

import math


class SimpleGoalChecker:
    """
    ``nav2_controller::SimpleGoalChecker``: xy within tolerance, then yaw (xy latched).

    :param xy_goal_tolerance: m. :param yaw_goal_tolerance: rad.
    :param stateful: once xy is reached it stays reached until :meth:`reset`.
    """

    def __init__(self, xy_goal_tolerance=0.25, yaw_goal_tolerance=0.25, stateful=True):
        """Keep the tolerances."""
        self.xy = float(xy_goal_tolerance)
        self.yaw = float(yaw_goal_tolerance)
        self.stateful = bool(stateful)
        self.reset()

    def reset(self):
        """Forget the latched position."""
        self.xy_reached = False

    def is_goal_reached(self, pose, goal, speed=(0.0, 0.0)):
        """
        Return True for ``pose`` and ``goal`` as ``(x, y, yaw)`` in one frame.

        :param speed: the robot's ``(v, w)`` (m/s, rad/s); not used here (see
            :class:`StoppedGoalChecker`).
        """
        if not self.xy_reached:
            if (pose[0] - goal[0]) ** 2 + (pose[1] - goal[1]) ** 2 > self.xy * self.xy:
                return False
            self.xy_reached = self.stateful
        d = math.atan2(math.sin(goal[2] - pose[2]), math.cos(goal[2] - pose[2]))
        return abs(d) <= self.yaw


class StoppedGoalChecker(SimpleGoalChecker):
    """
    ``nav2_controller::StoppedGoalChecker``: as :class:`SimpleGoalChecker`, and stopped.

    The goal counts as reached only while the odometry's speed is at most
    ``trans_stopped_velocity`` (m/s, 0.25) and its turn rate at most ``rot_stopped_velocity``
    (rad/s, 0.25). Source: ``nav2_controller/plugins/stopped_goal_checker.cpp``.
    """

    def __init__(self, xy_goal_tolerance=0.25, yaw_goal_tolerance=0.25, stateful=True,
                 rot_stopped_velocity=0.25, trans_stopped_velocity=0.25):
        """Keep the tolerances (m, rad, rad/s, m/s)."""
        super().__init__(xy_goal_tolerance, yaw_goal_tolerance, stateful)
        self.rot_stopped = float(rot_stopped_velocity)
        self.trans_stopped = float(trans_stopped_velocity)

    def is_goal_reached(self, pose, goal, speed=(0.0, 0.0)):
        """Return True at the goal (:class:`SimpleGoalChecker`) with ``speed`` (v, w) stopped."""
        return super().is_goal_reached(pose, goal) and abs(speed[1]) <= self.rot_stopped and \
            abs(speed[0]) <= self.trans_stopped


class SimpleProgressChecker:
    """
    ``nav2_controller::SimpleProgressChecker``: move far enough in time, or fail.

    The robot must move ``required_movement_radius`` (m) from a baseline pose within
    ``movement_time_allowance`` (s); the baseline resets each time it does.
    Source: ``nav2_controller/plugins/simple_progress_checker.cpp``.
    """

    def __init__(self, required_movement_radius=0.5, movement_time_allowance=10.0):
        """Keep the limits (m, s)."""
        self.radius = float(required_movement_radius)
        self.allowance = float(movement_time_allowance)
        self.reset()

    def reset(self):
        """Start over at the next pose."""
        self.baseline = None  # the pose the robot must move (or turn) away from
        self.since = None  # when it was there (s)

    def moved_enough(self, pose):
        """Return True when ``pose`` (x, y[, yaw]) is farther than the radius from the baseline."""
        b = self.baseline
        return math.hypot(pose[0] - b[0], pose[1] - b[1]) > self.radius

    def check(self, pose, now):
        """
        Return False when the robot made no progress.

        :param pose: the robot's ``(x, y, yaw)`` (m, rad; ``(x, y)`` is enough here).
        :param now: the time (s).
        """
        if self.baseline is None or self.moved_enough(pose):
            self.baseline = tuple(pose)
            self.since = now
            return True
        return now - self.since <= self.allowance


class PoseProgressChecker(SimpleProgressChecker):
    """
    ``nav2_controller::PoseProgressChecker`` (Jazzy): a turn in place is progress too.

    As :class:`SimpleProgressChecker`, and the baseline also resets when the heading has turned
    more than ``required_movement_angle`` (rad, default 0.5) from the baseline's.
    Source: ``nav2_controller/plugins/pose_progress_checker.cpp``.
    """

    def __init__(self, required_movement_radius=0.5, movement_time_allowance=10.0,
                 required_movement_angle=0.5):
        """Keep the limits (m, s, rad)."""
        super().__init__(required_movement_radius, movement_time_allowance)
        self.angle = float(required_movement_angle)

    def moved_enough(self, pose):
        """Return True when ``pose`` (x, y, yaw) moved or turned enough from the baseline."""
        turned = pose[2] - self.baseline[2]
        return super().moved_enough(pose) or \
            abs(math.atan2(math.sin(turned), math.cos(turned))) > self.angle
