# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The replay tool's pure parts: pose interpolation, errors, clock runs, parameters."""

import math

from amr_description.tools.benchmark.amcl_replay import interpolate_pose
from amr_description.tools.benchmark.amcl_replay import last_clock_run
from amr_description.tools.benchmark.amcl_replay import params_from_file
from amr_description.tools.benchmark.amcl_replay import pose_error
from amr_description.tools.benchmark.amcl_replay import replay
from amr_description.tools.benchmark.amcl_replay import settled_after
import numpy as np
import pytest


def test_interpolation_is_linear_and_takes_the_short_way_round():
    track = np.array([[0.0, 0.0, 0.0, math.radians(170.0)],
                      [1.0, 2.0, -1.0, math.radians(-170.0)]])
    x, y, yaw = interpolate_pose(track, 0.25)
    assert (x, y) == pytest.approx((0.5, -0.25))
    # 170 deg to -170 deg is 20 deg through 180, so a quarter of the way is 175 deg
    assert math.degrees(yaw) == pytest.approx(175.0)
    assert interpolate_pose(track, 1.0) == pytest.approx([2.0, -1.0, math.radians(-170.0)])
    assert interpolate_pose(track, -0.1) is None and interpolate_pose(track, 1.1) is None


def test_pose_error_wraps_the_heading():
    d, a = pose_error((3.0, 4.0, math.radians(179.0)), (0.0, 0.0, math.radians(-179.0)))
    assert d == pytest.approx(5.0) and math.degrees(a) == pytest.approx(2.0)


def test_the_last_run_of_a_clock_starts_after_its_last_step_back():
    assert last_clock_run([1.0, 2.0, 3.0]) == 0
    assert last_clock_run([1.0, 90.0, 0.5, 1.0, 80.0, 0.2, 0.3]) == 5
    assert last_clock_run([5.0, 4.0]) == 0  # a 1 s step back is reordering, not a restart


def test_params_come_from_the_amcl_section_then_the_overrides(tmp_path):
    path = tmp_path / 'p.yaml'
    path.write_text('amcl:\n  ros__parameters:\n    sigma_hit: 0.3\n    max_beams: 90\n'
                    '    base_frame_id: base_footprint\n')
    p = params_from_file(str(path), ['alpha1=0.4', 'max_beams=120'])
    assert (p.sigma_hit, p.alpha1, p.max_beams, p.alpha2) == (0.3, 0.4, 120, 0.2)
    assert isinstance(p.max_beams, int)
    with pytest.raises(ValueError, match='expected name=value'):
        params_from_file(str(path), ['sigma=0.1'])
    with pytest.raises(ValueError, match='not a number'):
        params_from_file(str(path), ['alpha1=high'])


def test_a_text_parameter_is_kept_as_text(tmp_path):
    path = tmp_path / 'p.yaml'
    path.write_text('amcl:\n  ros__parameters:\n    alpha5: 0.3\n')
    p = params_from_file(str(path), ['robot_model_type=nav2_amcl::OmniMotionModel'])
    assert (p.robot_model_type, p.alpha5) == ('nav2_amcl::OmniMotionModel', 0.3)


def test_settled_after_is_where_the_last_excursion_ends():
    driven = np.array([0.0, 0.5, 1.0, 1.5, 2.0])
    three = math.radians(3.0)
    errors = np.array([[0.3, 0.1], [0.04, 0.0], [0.06, 0.0], [0.01, three], [0.02, 0.01]])
    assert settled_after(errors, driven) == 1.5  # 6 cm at 1.0 m; exactly 3 deg is within
    assert settled_after(np.zeros((5, 2)), driven) == 0.0
    errors[-1, 1] = math.radians(3.1)
    assert settled_after(errors, driven) is None  # outside at the end
    assert settled_after(np.zeros((0, 2)), np.zeros(0)) is None


def test_replay_refuses_an_unknown_start():
    with pytest.raises(ValueError, match='expected truth, offset or global'):
        replay([], np.zeros((0, 4)), np.zeros((0, 4)), None, None, start='rviz')
