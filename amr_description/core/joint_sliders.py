# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The slider logic of ``joint_state_publisher_gui`` (pure, no rclpy, no GUI).

Reproduces upstream ``joint_state_publisher`` / ``joint_state_publisher_gui`` (ROS 2 Jazzy):

- one slider per revolute, continuous and prismatic joint that is not a mimic joint, in URDF
  order (mimic joints follow their parent: ``multiplier * parent + offset``);
- range: continuous joints -pi..pi rad; revolute and prismatic joints their ``<limit>``
  ``lower..upper``, narrowed by ``<safety_controller>`` ``soft_lower_limit`` /
  ``soft_upper_limit`` when present;
- centre value (the **Center** button and the start value): the ``zeros`` parameter's value
  for that joint when given, else 0 when 0 is inside the range, else the middle of the range;
- **Randomize**: every slider to a uniform random value in its range;
- a typed value is clamped into the slider's range.
"""

from dataclasses import dataclass
import math
import random

from amr_description.core.kinematics import MOVING_JOINT_TYPES


@dataclass(frozen=True)
class Slider:
    """
    One GUI slider.

    :param joint: joint name.
    :param lower: lowest value (rad, or m for prismatic joints).
    :param upper: highest value (same unit).
    :param center: the value of the Center button (same unit).
    :param continuous: True for a continuous joint.
    """

    joint: str
    lower: float
    upper: float
    center: float
    continuous: bool = False

    def clamp(self, value):
        """Return ``value`` clamped into ``lower..upper`` (NaN gives the centre value)."""
        value = float(value)
        if math.isnan(value):
            return self.center
        return min(max(value, self.lower), self.upper)


def _range(joint):
    """Return ``(lower, upper)`` of a yourdfpy joint (see the module docstring)."""
    if joint.type == 'continuous':
        return -math.pi, math.pi
    limit = joint.limit
    if limit is None or limit.lower is None or limit.upper is None:
        raise ValueError(f"joint '{joint.name}': a {joint.type} joint needs <limit lower= "
                         'upper=>')
    lower, upper = float(limit.lower), float(limit.upper)
    safety = getattr(joint, 'safety_controller', None)
    if safety is not None:
        if getattr(safety, 'soft_lower_limit', None) is not None:
            lower = max(lower, float(safety.soft_lower_limit))
        if getattr(safety, 'soft_upper_limit', None) is not None:
            upper = min(upper, float(safety.soft_upper_limit))
    if lower > upper:
        raise ValueError(f"joint '{joint.name}': limit lower {lower} is above upper {upper}")
    return lower, upper


def center_value(lower, upper, zero=None):
    """
    Return a slider's centre value.

    :param lower: range start.
    :param upper: range end.
    :param zero: the ``zeros`` parameter's value for the joint, or None.
    :returns: ``zero`` when given, else 0 when ``lower <= 0 <= upper``, else
        ``(lower + upper) / 2`` (upstream joint_state_publisher).
    """
    if zero is not None:
        return float(zero)
    if lower > 0.0 or upper < 0.0:
        return (lower + upper) / 2.0
    return 0.0


def sliders(joints, zeros=None):
    """
    Return the sliders of a robot's joints.

    :param joints: iterable of yourdfpy joints (``name``, ``type``, ``limit``, ``mimic``,
        ``safety_controller``), URDF order, e.g. ``RobotModel.joints.values()``.
    :param zeros: dict joint name -> centre value (the ``zeros`` parameter), optional.
    :returns: list of :class:`Slider`, URDF order.
    :raises ValueError: one line naming the joint when a revolute or prismatic joint has no
        usable limits.
    """
    zeros = zeros or {}
    result = []
    for joint in joints:
        if joint.type not in MOVING_JOINT_TYPES or joint.mimic is not None:
            continue
        lower, upper = _range(joint)
        result.append(Slider(joint.name, lower, upper,
                             center_value(lower, upper, zeros.get(joint.name)),
                             joint.type == 'continuous'))
    return result


def centered(slider_list):
    """Return ``{joint: centre value}`` of every slider (the Center button)."""
    return {s.joint: s.center for s in slider_list}


def randomized(slider_list, rng=random):
    """
    Return ``{joint: value}`` with each value uniform in its slider's range (Randomize).

    :param slider_list: list of :class:`Slider`.
    :param rng: object with ``uniform(a, b)`` (default: the ``random`` module).
    """
    return {s.joint: rng.uniform(s.lower, s.upper) for s in slider_list}
