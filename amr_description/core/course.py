# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
A scripted course (straight legs and turns in place) and the per-leg comparison table.

Pure logic for the main job: no rclpy. Poses are planar ``(x, y, yaw)`` tuples in metres and
radians (REP 103), in whichever fixed frame the caller uses (``odom`` or the simulator's
world); only differences between poses of the same source are compared.
"""

from dataclasses import dataclass
import math


def wrap_angle(angle):
    """
    Wrap an angle to ``(-pi, pi]``.

    :param angle: angle in rad.
    :returns: the equivalent angle in ``(-pi, pi]``, rad.
    """
    wrapped = math.atan2(math.sin(angle), math.cos(angle))
    return math.pi if wrapped == -math.pi else wrapped


@dataclass(frozen=True)
class Leg:
    """
    One leg of a course.

    :ivar kind: ``'straight'`` (drive ``target`` metres forward) or ``'turn'`` (rotate in place
        by ``target`` rad, positive counter-clockwise).
    :ivar target: distance in m (straight) or heading change in rad (turn).
    :ivar speed: cruise linear speed in m/s (straight) or angular speed in rad/s (turn), > 0.
    """

    kind: str
    target: float
    speed: float

    def __post_init__(self):
        """
        Validate the leg.

        :raises ValueError: on an unknown kind, a non-finite target or a speed <= 0.
        """
        if self.kind not in ('straight', 'turn'):
            raise ValueError(f"leg kind must be 'straight' or 'turn', got {self.kind!r}")
        if not math.isfinite(self.target):
            raise ValueError(f'leg target must be finite, got {self.target}')
        if not (math.isfinite(self.speed) and self.speed > 0.0):
            raise ValueError(f'leg speed must be > 0, got {self.speed}')


def square_course(side=1.0, speed=0.25, turn_rate=0.5, counter_clockwise=True):
    """
    Return the legs of a closed square: four times (side, quarter turn).

    :param side: side length in m, > 0.
    :param speed: linear cruise speed in m/s.
    :param turn_rate: angular cruise speed in rad/s.
    :param counter_clockwise: turn left (positive yaw) at each corner when True.
    :returns: list of 8 :class:`Leg`, ending with the robot back at its start pose.
    :raises ValueError: when ``side`` is not > 0.
    """
    if not side > 0.0:
        raise ValueError(f'side must be > 0, got {side}')
    quarter = math.pi / 2.0 if counter_clockwise else -math.pi / 2.0
    legs = []
    for _ in range(4):
        legs.append(Leg('straight', side, speed))
        legs.append(Leg('turn', quarter, turn_rate))
    return legs


def leg_progress(leg, start, pose):
    """
    Return how far a leg has come from its start pose.

    :param leg: the :class:`Leg`.
    :param start: ``(x, y, yaw)`` when the leg began.
    :param pose: current ``(x, y, yaw)``.
    :returns: distance travelled along the start heading (m, signed) for a straight leg, or
        the signed heading change (rad) for a turn.
    """
    if leg.kind == 'straight':
        dx, dy = pose[0] - start[0], pose[1] - start[1]
        return dx * math.cos(start[2]) + dy * math.sin(start[2])
    return wrap_angle(pose[2] - start[2])


class CourseFollower:
    """
    Closed-loop follower of a list of legs, fed with odometry poses.

    Each leg follows a trapezoidal speed profile in its own progress (distance along the start
    heading, or heading change): the speed is
    ``min(cruise, sqrt(v0^2 + 2 a done), sqrt(v0^2 + 2 a remaining))``, never below
    ``v0 = min_fraction * cruise``, so it ramps up and down at the constant ``acceleration``
    ``a`` (m/s^2 or rad/s^2) without a clock. Each leg ends when its progress reaches the
    target within ``tolerance``. A turn's target is the course's heading, not the leg's: the
    heading at the course's start plus every turn so far, so that what one turn overshoots
    after its stop (a wheel's velocity servo catching up with its integral, about 0.25 deg per
    corner with Coulomb wheel friction, docs/simulation.md) the next turn takes back instead
    of adding it up.

    Gentle ramps are part of the accuracy: in the MuJoCo world the yaw a skid-steer turn gains
    or loses against the Coulomb model grows with how fast the wheel speeds change
    (docs/simulation.md, "Closing the square").
    """

    def __init__(self, legs, acceleration=(0.5, 0.5), min_fraction=0.1,
                 tolerance=(0.001, 0.001)):
        """
        Create the follower.

        :param legs: list of :class:`Leg`.
        :param acceleration: ``(m/s^2, rad/s^2)`` of the speed ramps, both > 0.
        :param min_fraction: lowest speed as a fraction of the cruise speed, in (0, 1].
        :param tolerance: ``(metres, radians)`` within which a leg counts as done.
        :raises ValueError: when an acceleration is not > 0 or ``min_fraction`` not in (0, 1].
        """
        if not all(a > 0.0 for a in acceleration):
            raise ValueError(f'acceleration must be > 0, got {acceleration}')
        if not 0.0 < min_fraction <= 1.0:
            raise ValueError(f'min_fraction must be in (0, 1], got {min_fraction}')
        self.legs = list(legs)
        self.acceleration = acceleration
        self.min_fraction = min_fraction
        self.tolerance = tolerance
        self.index = 0
        self.start = None
        self.heading = None  # the course's nominal heading before the current leg, rad

    @property
    def done(self):
        """Return True once every leg is finished."""
        return self.index >= len(self.legs)

    def speed(self, leg, done, remaining):
        """
        Return the profile speed of a leg (unsigned, the leg's units per second).

        :param leg: the :class:`Leg`.
        :param done: progress so far, >= 0 counts (m or rad, towards the target).
        :param remaining: what is left to the target (m or rad).
        :returns: float in ``[min_fraction * leg.speed, leg.speed]``.
        """
        a = self.acceleration[0 if leg.kind == 'straight' else 1]
        floor = self.min_fraction * leg.speed
        ramp = math.sqrt(floor * floor + 2.0 * a * max(0.0, min(done, remaining)))
        return max(floor, min(leg.speed, ramp))

    def step(self, pose):
        """
        Advance with a new pose and return the command to send.

        :param pose: current ``(x, y, yaw)`` in m, m, rad.
        :returns: ``(linear_x, angular_z, leg_index_finished)``: velocities in m/s and rad/s
            (both 0.0 once done), and the index of the leg that just finished or None.
        """
        if self.done:
            return 0.0, 0.0, None
        leg = self.legs[self.index]
        if self.start is None:
            self.start = pose
        if self.heading is None:
            self.heading = pose[2]
        straight = leg.kind == 'straight'
        done = math.copysign(1.0, leg.target) * leg_progress(leg, self.start, pose)
        remaining = abs(leg.target) - done
        if not straight:  # less what the turns before overshot the course's heading
            overshot = wrap_angle(self.start[2] - self.heading)
            remaining -= math.copysign(1.0, leg.target) * overshot
        if remaining <= self.tolerance[0 if straight else 1]:
            finished = self.index
            self.index += 1
            self.start = pose
            if not straight:
                self.heading = wrap_angle(self.heading + leg.target)
            return 0.0, 0.0, finished
        value = math.copysign(self.speed(leg, done, remaining), leg.target)
        return (value, 0.0, None) if straight else (0.0, value, None)


def leg_delta(start, end):
    """
    Return what a leg did between two poses of one source.

    :param start: ``(x, y, yaw)`` at the leg's start.
    :param end: ``(x, y, yaw)`` at its end.
    :returns: ``(distance, heading_change)``: straight-line distance in m and wrapped yaw
        change in rad.
    """
    return (math.hypot(end[0] - start[0], end[1] - start[1]),
            wrap_angle(end[2] - start[2]))


def format_leg_table(legs, odom_poses, truth_poses):
    """
    Format the per-leg table: commanded, ``/odom`` and ground truth, distance and heading.

    :param legs: the :class:`Leg` list driven.
    :param odom_poses: ``len(legs) + 1`` odometry poses: the start, then the end of each leg.
    :param truth_poses: the same instants from the simulator's ground truth.
    :returns: the table as a str (fixed-width columns, distances in m, headings in deg).
    :raises ValueError: when the pose lists do not have ``len(legs) + 1`` entries.
    """
    if len(odom_poses) != len(legs) + 1 or len(truth_poses) != len(legs) + 1:
        raise ValueError(f'need {len(legs) + 1} poses per source, got {len(odom_poses)} '
                         f'(odom) and {len(truth_poses)} (ground truth)')
    header = (f"{'leg':>3}  {'kind':<8}  {'cmd dist':>8}  {'odom dist':>9}  {'true dist':>9}  "
              f"{'cmd hdg':>8}  {'odom hdg':>8}  {'true hdg':>8}")
    lines = [header, '-' * len(header)]
    for i, leg in enumerate(legs):
        odom_d, odom_h = leg_delta(odom_poses[i], odom_poses[i + 1])
        true_d, true_h = leg_delta(truth_poses[i], truth_poses[i + 1])
        cmd_d = leg.target if leg.kind == 'straight' else 0.0
        cmd_h = leg.target if leg.kind == 'turn' else 0.0
        lines.append(
            f'{i + 1:>3}  {leg.kind:<8}  {cmd_d:>8.3f}  {odom_d:>9.3f}  {true_d:>9.3f}  '
            f'{math.degrees(cmd_h):>8.1f}  {math.degrees(odom_h):>8.1f}  '
            f'{math.degrees(true_h):>8.1f}')
    return '\n'.join(lines)


def closure_error(poses):
    """
    Return how far a closed course ends from where it began.

    :param poses: the course's poses, first = start, last = end, ``(x, y, yaw)``.
    :returns: ``(position_error, heading_error)`` in m and rad (absolute, wrapped).
    """
    distance, heading = leg_delta(poses[0], poses[-1])
    return distance, abs(heading)
