# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""joint_state_publisher_gui's slider logic: which joints, ranges, centre values (pure)."""

import math
import random

from amr_description.core import joint_sliders as js
from amr_description.core.description.urdf_model import parse_urdf
import pytest

URDF = """<robot name="r">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <link name="e"/><link name="f"/>
  <joint name="wheel" type="continuous"><parent link="base"/><child link="a"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="arm" type="revolute"><parent link="base"/><child link="b"/>
    <limit lower="-1.0" upper="2.0" effort="1" velocity="1"/></joint>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="c"/>
    <limit lower="0.2" upper="0.6" effort="1" velocity="1"/></joint>
  <joint name="soft" type="revolute"><parent link="base"/><child link="d"/>
    <limit lower="-2.0" upper="2.0" effort="1" velocity="1"/>
    <safety_controller soft_lower_limit="-1.5" soft_upper_limit="1.0" k_velocity="1"/></joint>
  <joint name="follower" type="revolute"><parent link="base"/><child link="e"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="arm"/></joint>
  <joint name="fixed" type="fixed"><parent link="base"/><child link="f"/></joint>
</robot>"""


def model_sliders(zeros=None):
    return js.sliders(parse_urdf(URDF).joints.values(), zeros)


def test_one_slider_per_moving_non_mimic_joint_in_urdf_order():
    assert [s.joint for s in model_sliders()] == ['wheel', 'arm', 'lift', 'soft']


def test_ranges_and_centres():
    by_name = {s.joint: s for s in model_sliders()}
    assert (by_name['wheel'].lower, by_name['wheel'].upper) == (-math.pi, math.pi)
    assert by_name['wheel'].continuous and not by_name['arm'].continuous
    assert (by_name['arm'].lower, by_name['arm'].upper, by_name['arm'].center) == (-1, 2, 0)
    # 0 outside 0.2..0.6: the middle of the range
    assert by_name['lift'].center == pytest.approx(0.4)
    # safety_controller soft limits narrow the range
    assert (by_name['soft'].lower, by_name['soft'].upper) == (-1.5, 1.0)


def test_zeros_parameter_sets_the_centre():
    by_name = {s.joint: s for s in model_sliders({'arm': 0.5})}
    assert by_name['arm'].center == 0.5
    assert js.centered(model_sliders({'arm': 0.5})) == {
        'wheel': 0.0, 'arm': 0.5, 'lift': pytest.approx(0.4), 'soft': 0.0}


def test_center_value_closed_form():
    assert js.center_value(-1.0, 1.0) == 0.0
    assert js.center_value(1.0, 3.0) == 2.0
    assert js.center_value(-3.0, -1.0) == -2.0
    assert js.center_value(-3.0, -1.0, zero=-1.5) == -1.5


def test_clamp():
    arm = {s.joint: s for s in model_sliders()}['arm']
    assert arm.clamp(5.0) == 2.0
    assert arm.clamp(-5.0) == -1.0
    assert arm.clamp(1.57) == 1.57
    assert arm.clamp(math.nan) == 0.0


def test_randomize_stays_in_range():
    rng = random.Random(4)
    for _ in range(50):
        values = js.randomized(model_sliders(), rng)
        for s in model_sliders():
            assert s.lower <= values[s.joint] <= s.upper


def test_revolute_without_limits_is_one_line_error():
    bad = URDF.replace('<limit lower="-1.0" upper="2.0" effort="1" velocity="1"/>', '')
    with pytest.raises(ValueError, match="joint 'arm': a revolute joint needs <limit"):
        js.sliders(parse_urdf(bad).joints.values())
