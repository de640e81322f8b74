# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The main job's scan map against closed forms: sections, distances, placing scans."""

import math
import os

from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.scan_map import compose
from amr_description.core.scan_map import interpolate
from amr_description.core.scan_map import inverse
from amr_description.core.scan_map import scan_to_world
from amr_description.core.scan_map import surface_distance
from amr_description.core.scan_map import world_sections
import numpy as np
import pytest

ROOM = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'data', 'worlds',
                    'box_room.sdf')


def test_the_box_rooms_section_is_its_four_walls_and_points_on_them_are_at_zero():
    sections = world_sections(read_world(ROOM), 0.25)
    assert len(sections) == 4 and all(s[0] == 'box' for s in sections)
    on_walls = np.array([[3.0, 0.0], [-2.0, 1.0], [0.3, 2.5], [1.0, -1.5]])
    assert np.allclose(surface_distance(on_walls, sections), 0.0, atol=1e-12)
    assert surface_distance([[0.0, 0.0]], sections)[0] == pytest.approx(1.5)  # south wall
    assert surface_distance([[4.0, 0.5]], sections)[0] == pytest.approx(0.8)  # outside east
    assert world_sections(read_world(ROOM), 1.5) == []  # above the 1 m walls


def test_a_circle_section_distance_is_the_radial_gap():
    sections = [('circle', (1.0, 2.0), 0.5)]
    assert surface_distance([[1.0, 3.0], [1.0, 2.0]], sections) == pytest.approx([0.5, 0.5])


def test_a_rotated_box_section():
    sections = [('box', (0.0, 0.0), math.pi / 4, (1.0, 0.1))]
    inside = [0.5 * math.cos(math.pi / 4), 0.5 * math.sin(math.pi / 4)]  # on the long axis
    assert surface_distance([inside], sections)[0] == pytest.approx(0.1)  # 0.1 to the side
    beyond = [1.5 * math.cos(math.pi / 4), 1.5 * math.sin(math.pi / 4)]
    assert surface_distance([beyond], sections)[0] == pytest.approx(0.5)  # past the end


def test_planar_poses_compose_invert_and_interpolate():
    a, b = (1.0, 2.0, math.pi / 2), (0.5, 0.0, 0.1)
    assert compose(a, b) == pytest.approx((1.0, 2.5, math.pi / 2 + 0.1))
    assert compose(a, inverse(a)) == pytest.approx((0.0, 0.0, 0.0))
    samples = [(0.0, (0.0, 0.0, 3.1)), (1.0, (1.0, 2.0, -3.1))]
    x, y, yaw = interpolate(samples, 0.5)
    assert (x, y) == pytest.approx((0.5, 1.0))
    assert math.cos(yaw) == pytest.approx(-1.0, abs=1e-4)  # across +-pi the short way
    assert interpolate(samples, 1.5) is None and interpolate(samples, -0.1) is None


def test_a_scan_lands_where_its_ranges_point():
    points = scan_to_world([1.0, math.inf, 2.0], -math.pi / 2, math.pi / 2,
                           (1.0, 1.0, math.pi / 2))
    assert points == pytest.approx(np.array([[2.0, 1.0], [-1.0, 1.0]]))
