# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Regulated Pure Pursuit (Nav2's ``FollowPath`` controller) and the goal and progress checkers.

:class:`RegulatedPurePursuit` computes ``(v, w)`` (m/s, rad/s, REP 103, base frame) from the
path in the robot's frame: the carrot is the point at lookahead distance ``L`` along the path
(the exact circle-segment intersection), the curvature ``2 y / (x^2 + y^2)``; it rotates in
place towards the path when the carrot is more than ``rotate_to_heading_min_angle`` off, and
towards the goal's heading once the carrot is within the goal tolerance; otherwise the speed
starts at ``desired_linear_vel``, is regulated by curvature and by cost (distance to
obstacles estimated from the inflation cost), floored at ``regulated_linear_scaling_min_speed``,
slowed on approach, and ``w = v * curvature``. With ``use_fixed_curvature_lookahead`` the
curvature (for the speed, ``w`` and the rotation to the path) is taken at
``curvature_lookahead_dist`` instead, past the goal along the last segment with
``interpolate_curvature_after_goal``; with ``allow_reversing`` (only without
``use_rotate_to_heading``) a carrot behind the robot drives it backwards and neither point lies
beyond the path's first cusp; after :meth:`RegulatedPurePursuit.cancel` with
``use_cancel_deceleration`` the speed falls by ``cancel_deceleration``. The arc ahead is checked
on the local costmap; a collision raises :class:`NoValidControl`. Parameters, defaults and
formulas:
``parameter_handler.cpp``, ``regulated_pure_pursuit_controller.cpp``, ``path_handler.cpp``,
``collision_checker.cpp`` and ``regulation_functions.hpp`` of
nav2_regulated_pure_pursuit_controller (Jazzy).
The goal and progress checkers are in :mod:`amr_description.nav.checkers`.
"""

import math

from amr_description.nav.costmap import INSCRIBED_INFLATED_OBSTACLE
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.costmap import NO_INFORMATION
import numpy as np

RPP_DEFAULTS = {
    'desired_linear_vel': 0.5, 'lookahead_dist': 0.6, 'min_lookahead_dist': 0.3,
    'max_lookahead_dist': 0.9, 'lookahead_time': 1.5, 'rotate_to_heading_angular_vel': 1.8,
    'transform_tolerance': 0.1, 'use_velocity_scaled_lookahead_dist': False,
    'min_approach_linear_velocity': 0.05, 'approach_velocity_scaling_dist': 0.6,
    'use_collision_detection': True, 'max_allowed_time_to_collision_up_to_carrot': 1.0,
    'use_regulated_linear_velocity_scaling': True,
    'use_cost_regulated_linear_velocity_scaling': True,
    'regulated_linear_scaling_min_radius': 0.90, 'regulated_linear_scaling_min_speed': 0.25,
    'use_fixed_curvature_lookahead': False, 'curvature_lookahead_dist': 0.6,
    'use_rotate_to_heading': True, 'allow_reversing': False,
    'rotate_to_heading_min_angle': 0.785, 'max_angular_accel': 3.2, 'cost_scaling_dist': 0.6,
    'cost_scaling_gain': 1.0, 'inflation_cost_scaling_factor': 3.0,
    'use_cancel_deceleration': False, 'cancel_deceleration': 3.2,
    'interpolate_curvature_after_goal': False, 'max_robot_pose_search_dist': math.inf,
    'stateful': True,
}
"""
RPP's parameters (under ``<controller_id>.``) and Nav2's code defaults.

Upstream's ``max_robot_pose_search_dist`` defaults to half the local costmap's width, which
the controller server declares (amr_description/nodes/controller_server.py); here, the whole
path.
"""


class NoValidControl(Exception):
    """No safe command exists (FollowPath's NO_VALID_CONTROL, 106)."""


def carrot(path_xy, distance, interpolate_after_goal=False):
    """
    Return the point at ``distance`` (m) from the origin along a path in the robot frame.

    The first pose at least ``distance`` away and the one before it bound a segment; the
    carrot is where the circle of radius ``distance`` crosses it (the first pose itself when it
    is the path's first). No such pose: the last pose, or, with ``interpolate_after_goal`` and
    two poses or more, where the last segment carried on past the goal leaves the circle.
    ``path_xy`` is ``(n, 2)``, n >= 1. Source: ``getLookAheadPoint`` and
    ``circleSegmentIntersection``.
    """
    p = np.asarray(path_xy, float)
    d = np.hypot(p[:, 0], p[:, 1])
    far = np.nonzero(d >= distance)[0]
    if not len(far):
        if interpolate_after_goal and len(p) >= 2 and np.any(p[-1] != p[-2]):
            ahead = p[-1] - p[-2]
            return _leave_circle(p[-1], ahead / math.hypot(*ahead), distance)
        return p[-1].copy()
    k = int(far[0])
    if k == 0:
        return p[0].copy()
    a, b = p[k - 1], p[k]
    seg = b - a
    # |a + t seg| = distance, t in [0, 1]: the larger root
    qa = seg @ seg
    qb = 2.0 * (a @ seg)
    qc = a @ a - distance * distance
    disc = max(qb * qb - 4.0 * qa * qc, 0.0)
    t = (-qb + math.sqrt(disc)) / (2.0 * qa) if qa > 0 else 1.0
    return a + min(max(t, 0.0), 1.0) * seg


def _leave_circle(inside, direction, radius):
    """Return where the ray from ``inside`` along the unit ``direction`` leaves the circle."""
    b = inside @ direction
    t = -b + math.sqrt(max(b * b - (inside @ inside - radius * radius), 0.0))
    return inside + t * direction


def cusp_distance(path_xy):
    """
    Return the distance (m) from the origin to the path's first cusp, or infinity.

    A pose is a cusp where the steps before and after it point apart (a negative dot product).
    Upstream also counts two poses at one place with different orientations; the planners
    here give every pose its own place. Source: ``findVelocitySignChange``.
    """
    p = np.asarray(path_xy, float)[:, :2]
    if len(p) < 3:
        return math.inf
    step = np.diff(p, axis=0)
    back = np.nonzero(np.einsum('ij,ij->i', step[:-1], step[1:]) < 0.0)[0]
    if not len(back):
        return math.inf
    return float(math.hypot(*p[back[0] + 1]))


def checked_params(params):
    """
    Return RPP's parameters over the defaults, and the lines upstream logs while setting them.

    As ``ParameterHandler``'s constructor: ``allow_reversing`` with ``use_rotate_to_heading``
    is turned off, ``interpolate_curvature_after_goal`` without
    ``use_fixed_curvature_lookahead`` too, and cost regulation with an
    ``inflation_cost_scaling_factor`` of 0 or less (its distance divides by it). A negative
    ``max_robot_pose_search_dist`` searches the whole path.

    :param params: ``{name: value}`` (names without the controller id).
    :returns: ``(params, warnings)``: a new dict; a list of str.
    """
    p = dict(RPP_DEFAULTS)
    p.update(params or {})
    warnings = []
    if p['use_rotate_to_heading'] and p['allow_reversing']:
        warnings.append('Disabling reversing. Both use_rotate_to_heading and allow_reversing '
                        'parameter cannot be set to true. By default setting '
                        'use_rotate_to_heading true')
        p['allow_reversing'] = False
    if p['interpolate_curvature_after_goal'] and not p['use_fixed_curvature_lookahead']:
        warnings.append('For interpolate_curvature_after_goal to be set to true, '
                        'use_fixed_curvature_lookahead should be true, it is currently set '
                        'to false. Disabling.')
        p['interpolate_curvature_after_goal'] = False
    if p['max_robot_pose_search_dist'] < 0.0:
        warnings.append('Max robot search distance is negative, setting to max to search '
                        'every point on path for the closest value.')
        p['max_robot_pose_search_dist'] = math.inf
    if p['inflation_cost_scaling_factor'] <= 0.0:
        warnings.append('The value inflation_cost_scaling_factor is incorrectly set, it '
                        'should be >0. Disabling cost regulated linear velocity scaling.')
        p['use_cost_regulated_linear_velocity_scaling'] = False
    return p, warnings


def curvature(x, y):
    """Return pure pursuit's curvature ``2 y / (x^2 + y^2)`` (1/m; 0 near the origin)."""
    d2 = x * x + y * y
    return 2.0 * y / d2 if d2 > 0.001 else 0.0


def cost_distance(cost, inscribed_radius, scaling_factor):
    """
    Return the obstacle distance (m) an inflation cost stands for, inverting Nav2's formula.

    ``d = (k * r_inscribed - ln(cost) + ln(253)) / k`` (``costConstraint`` in
    ``regulation_functions.hpp``).
    """
    return (scaling_factor * inscribed_radius - math.log(cost) + math.log(253.0)) / \
        scaling_factor


class RegulatedPurePursuit:
    """
    Nav2's Regulated Pure Pursuit on plain arrays.

    :param params: ``{name: value}`` overriding :data:`RPP_DEFAULTS`.
    :param goal_xy_tolerance: the goal checker's ``xy_goal_tolerance`` (m).
    :param inscribed_radius: the footprint's inscribed radius (m), for cost regulation.
    :param circumscribed_radius: the footprint's circumscribed radius (m), for the time step
        of the collision check while rotating in place (0: ``inscribed_radius``, or 0.1 m).
    :param resolution: the local costmap's resolution (m), the collision check's step.
    """

    def __init__(self, params=None, goal_xy_tolerance=0.25, inscribed_radius=0.0,
                 circumscribed_radius=0.0, resolution=0.05):
        """Merge the parameters over the defaults (:func:`checked_params`)."""
        self.p, _ = checked_params(params)
        self.goal_xy_tolerance = float(goal_xy_tolerance)
        self.inscribed_radius = float(inscribed_radius)
        self.circumscribed_radius = float(circumscribed_radius) or self.inscribed_radius or 0.1
        self.resolution = float(resolution)
        self.cancelling = self.cancel_finished = False
        self.reset()

    def reset(self):
        """Forget the latched goal-heading rotation (a new path)."""
        self.rotating_to_goal = False

    def cancel(self):
        """
        Return True once a cancelled goal may end (``RegulatedPurePursuitController::cancel``).

        Without ``use_cancel_deceleration`` at once; with it, :meth:`compute` from now on
        slows the robot by ``cancel_deceleration`` (m/s^2) and this returns True once it has
        commanded 0 m/s.
        """
        if not self.p['use_cancel_deceleration']:
            return True
        self.cancelling = True
        return self.cancel_finished

    def lookahead(self, speed):
        """Return the lookahead distance (m) for the current speed (m/s)."""
        p = self.p
        if p['use_velocity_scaled_lookahead_dist']:
            return min(max(abs(speed) * p['lookahead_time'], p['min_lookahead_dist']),
                       p['max_lookahead_dist'])
        return p['lookahead_dist']

    def _rotate(self, angle, w_now, dt, lateness=0.0):
        # RegulatedPurePursuitController::rotateToHeading: the turn rate within the
        # acceleration limit of the odometry's, then, if faster than stops within the angle,
        # that stopping rate towards the heading: a turn that overshot (the odometry still
        # turning the other way) is reversed at once, not carried on at the stopping rate.
        # The stopping rate holds the command for ``lateness`` before braking at ``a``:
        # w lateness + w^2 / (2 a) = |angle|, upstream's sqrt(2 a |angle|) at 0
        p = self.p
        sign = 1.0 if angle > 0.0 else -1.0
        w = sign * p['rotate_to_heading_angular_vel']
        a = p['max_angular_accel']
        w = min(max(w, w_now - a * dt), w_now + a * dt)
        limit = a * (math.sqrt(lateness * lateness + 2.0 * abs(angle) / a) - lateness)
        if abs(w) > limit:
            w = sign * limit
        return 0.0, w

    def compute(self, path, speed=(0.0, 0.0), dt=0.05, cost=0, remaining=None,
                collision=None, lateness=0.0):
        """
        Return ``(v, w)`` for a path in the robot frame.

        :param path: ``(n, 3)`` poses ``x, y, yaw`` in the robot's base frame (m, rad); the
            last is the goal.
        :param speed: the robot's ``(v, w)`` now (m/s, rad/s).
        :param dt: the control period (s): the time one step of the in-place turn's
            ``max_angular_accel`` limit spans (upstream: ``1 / controller_frequency``).
        :param cost: the local costmap's cost under the robot (0..255).
        :param remaining: the path's length from the robot (m; default: from ``path``).
        :param collision: ``f(x, y, yaw) -> bool`` in the robot frame, or None (no check).
        :param lateness: s the next command may come later than ``dt``
            (:class:`amr_description.nav.cycle_clock.CycleClock`): the in-place turn's
            stopping rate leaves that much time at the command's rate before braking,
            ``w lateness + w^2 / (2 max_angular_accel) <= |angle|``; 0 is upstream's
            ``sqrt(2 max_angular_accel |angle|)``.
        :raises NoValidControl: when the robot's footprint is in collision now or on the
            command's arc (a rotation in place included) within the carrot's distance and
            ``max_allowed_time_to_collision_up_to_carrot``.
        """
        p = self.p
        path = np.asarray(path, float)
        L = self.lookahead(speed[0])
        curvature_L = p['curvature_lookahead_dist']
        if p['allow_reversing']:  # a cusp ahead: look no further than it
            cusp = cusp_distance(path)
            L, curvature_L = min(L, cusp), min(curvature_L, cusp)
        goal = path[-1]
        c = carrot(path[:, :2], L)
        c_dist = math.hypot(c[0], c[1])
        toward = c  # the point the rotation to the path turns to
        kappa = curvature(c[0], c[1])
        if p['use_fixed_curvature_lookahead']:
            toward = carrot(path[:, :2], curvature_L, p['interpolate_curvature_after_goal'])
            kappa = curvature(toward[0], toward[1])
        sign = -1.0 if p['allow_reversing'] and c[0] < 0.0 else 1.0
        heading = math.atan2(toward[1], toward[0])
        if sign < 0.0:
            heading = math.atan2(-math.sin(heading), -math.cos(heading))
        if p['use_rotate_to_heading'] and (c_dist < self.goal_xy_tolerance or
                                           (p['stateful'] and self.rotating_to_goal)):
            self.rotating_to_goal = p['stateful']
            yaw = goal[2] if math.isfinite(goal[2]) else 0.0
            v, w = self._rotate(math.atan2(math.sin(yaw), math.cos(yaw)), speed[1], dt,
                                lateness)
        elif p['use_rotate_to_heading'] and abs(heading) > p['rotate_to_heading_min_angle']:
            v, w = self._rotate(heading, speed[1], dt, lateness)
        else:
            v = sign * self._regulate(kappa, cost, path, remaining)
            if self.cancelling:  # slow down from the odometry's speed, then stop
                v = speed[0] - sign * dt * p['cancel_deceleration']
                if sign * v <= 0.0:
                    v, self.cancel_finished = 0.0, True
            w = v * kappa
        # every command is checked, a rotation in place too, as computeVelocityCommands does
        if collision is not None and p['use_collision_detection'] and \
                self.collision_imminent(v, w, c_dist, collision):
            raise NoValidControl('RegulatedPurePursuitController detected collision ahead!')
        return v, w

    def _regulate(self, kappa, cost, path, remaining):
        p = self.p
        v = p['desired_linear_vel']
        limits = [v]
        if p['use_regulated_linear_velocity_scaling'] and kappa != 0.0:
            radius = abs(1.0 / kappa)
            r_min = p['regulated_linear_scaling_min_radius']
            if radius < r_min:
                limits.append(v * (1.0 - abs(radius - r_min) / r_min))
        if p['use_cost_regulated_linear_velocity_scaling'] and \
                cost not in (0, NO_INFORMATION) and cost < LETHAL_OBSTACLE:
            d = cost_distance(cost, self.inscribed_radius, p['inflation_cost_scaling_factor'])
            if d < p['cost_scaling_dist']:
                limits.append(v * p['cost_scaling_gain'] * d / p['cost_scaling_dist'])
        v = max(min(limits), p['regulated_linear_scaling_min_speed'])
        if remaining is None:
            xy = path[:, :2]
            remaining = math.hypot(*xy[0]) + float(np.hypot(*np.diff(xy, axis=0).T).sum())
        if remaining < p['approach_velocity_scaling_dist']:
            end = math.hypot(path[-1, 0], path[-1, 1])
            v = max(v * end / p['approach_velocity_scaling_dist'],
                    p['min_approach_linear_velocity'])
        return min(max(v, 0.0), p['desired_linear_vel'])

    def collision_imminent(self, v, w, c_dist, collision):
        """
        Return True when the robot collides now or while ``(v, w)`` is applied.

        The robot's pose is checked, then poses along the arc, one step apart, until
        ``max_allowed_time_to_collision_up_to_carrot`` or past the carrot's distance. The step
        is the time to move one costmap cell: ``resolution / |v|``, or while rotating in place
        (``|v| < 0.01`` and ``|w| > 0.01``) ``2 sin(resolution / 2 / r_max) / |w|``, r_max
        the circumscribed radius. Source: ``CollisionChecker::isCollisionImminent``
        (``collision_checker.cpp`` of nav2_regulated_pure_pursuit_controller).

        :param v: linear velocity (m/s).
        :param w: angular velocity (rad/s).
        :param c_dist: the carrot's distance (m).
        :param collision: ``f(x, y, yaw) -> bool``, in the robot frame (m, rad).
        """
        if collision(0.0, 0.0, 0.0):
            return True
        if abs(v) < 0.01 and abs(w) > 0.01:
            step = 2.0 * math.sin(self.resolution / 2.0 / self.circumscribed_radius) / abs(w)
        elif abs(v) > 0.0:
            step = self.resolution / abs(v)
        else:
            return False  # standing still: only the pose now
        horizon = self.p['max_allowed_time_to_collision_up_to_carrot']
        x = y = yaw = 0.0
        i = 1
        while i * step < horizon:
            i += 1
            x += step * v * math.cos(yaw)
            y += step * v * math.sin(yaw)
            yaw += step * w
            if math.hypot(x, y) > c_dist:
                break
            if collision(x, y, yaw):
                return True
        return False


def circle_collides(costmap, x, y):
    """Return True when a round robot's centre cell at ``(x, y)`` is inscribed or lethal."""
    cost = costmap.cost_at(x, y)
    return cost is not None and INSCRIBED_INFLATED_OBSTACLE <= cost <= LETHAL_OBSTACLE


def to_robot_frame(path, pose):
    """
    Return ``(n, 3)`` poses ``x, y, yaw`` expressed in the robot's frame.

    :param path: ``(n, 3)`` poses in the frame of ``pose`` (m, rad; NaN yaws stay NaN).
    :param pose: the robot's ``(x, y, yaw)``.
    """
    p = np.asarray(path, float).reshape(-1, 3)
    c, s = math.cos(pose[2]), math.sin(pose[2])
    dx, dy = p[:, 0] - pose[0], p[:, 1] - pose[1]
    yaw = np.arctan2(np.sin(p[:, 2] - pose[2]), np.cos(p[:, 2] - pose[2]))
    return np.column_stack((c * dx + s * dy, -s * dx + c * dy, yaw))


def closest_pose(path, pose, search_dist):
    """
    Return the index of the path pose closest to the robot, searching ``search_dist`` (m).

    The search runs from the first pose along the path until the integrated distance exceeds
    ``search_dist`` (upstream's ``max_robot_pose_search_dist``; the local costmap's half
    width by default; negative: the whole path). Source: RPP's
    ``PathHandler::transformGlobalPlan``.
    """
    p = np.asarray(path, float).reshape(-1, 3)
    along = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(p[:, :2], axis=0).T))))
    if search_dist < 0.0:  # upstream's "search every point on path"
        search_dist = math.inf
    n = max(int(np.searchsorted(along, search_dist, side='right')), 1)
    d = np.hypot(p[:n, 0] - pose[0], p[:n, 1] - pose[1])
    return int(np.argmin(d))
