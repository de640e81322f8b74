# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The MarkerArray display's logic: RViz's add / delete / delete-all, and what each type draws."""

import math

from amr_description.web.displays.markers import apply
from amr_description.web.displays.markers import geometry
from geometry_msgs.msg import Point
import numpy as np
import pytest
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker
from visualization_msgs.msg import MarkerArray


def _marker(kind, ident=0, ns='a', action=Marker.ADD, points=(), x=0.0, y=0.0, yaw=0.0,
            scale=0.1, rgb=(1.0, 0.0, 0.0)):
    m = Marker(ns=ns, id=ident, type=kind, action=action)
    m.pose.position.x, m.pose.position.y = x, y
    m.pose.orientation.z, m.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    m.scale.x = m.scale.y = m.scale.z = scale
    m.color.r, m.color.g, m.color.b, m.color.a = (*rgb, 1.0)
    m.points = [Point(x=float(p[0]), y=float(p[1])) for p in points]
    return m


def test_markers_are_kept_by_namespace_and_id_as_rviz_does():
    kept = {}
    apply(kept, MarkerArray(markers=[_marker(Marker.SPHERE, 0), _marker(Marker.SPHERE, 1),
                                     _marker(Marker.SPHERE, 0, ns='b')]))
    assert sorted(kept) == [('a', 0), ('a', 1), ('b', 0)]
    moved = _marker(Marker.SPHERE, 1, x=2.0)
    apply(kept, MarkerArray(markers=[moved, _marker(Marker.SPHERE, 0, action=Marker.DELETE)]))
    assert sorted(kept) == [('a', 1), ('b', 0)] and kept[('a', 1)] is moved
    # DELETEALL first, then the new ones: slam_toolbox's graph arrays
    apply(kept, MarkerArray(markers=[Marker(action=Marker.DELETEALL),
                                     _marker(Marker.SPHERE, 7)]))
    assert list(kept) == [('a', 7)]


def test_spheres_lists_lines_strips_and_arrows_in_the_markers_poses():
    markers = [
        _marker(Marker.SPHERE, x=1.0, y=2.0, scale=0.1),
        _marker(Marker.POINTS, points=[(1.0, 0.0)], x=1.0, yaw=math.pi / 2, scale=0.2,
                rgb=(0.0, 1.0, 0.0)),
        _marker(Marker.LINE_LIST, points=[(0, 0), (1, 0), (0, 1), (0, 2), (5, 5)],
                rgb=(0.0, 0.0, 1.0)),
        _marker(Marker.LINE_STRIP, points=[(0, 0), (1, 0), (1, 1)], y=-1.0),
        _marker(Marker.ARROW, x=3.0, yaw=math.pi, scale=0.5),
        _marker(Marker.TEXT_VIEW_FACING, x=9.0),
    ]
    points, colours, size, segments, seg_colours = geometry(markers)
    # the sphere at its position; the POINTS entry (1, 0) turned 90 deg and moved by (1, 0)
    np.testing.assert_allclose(points, [[1.0, 2.0, 0.0], [1.0, 1.0, 0.0]], atol=1e-12)
    assert colours.tolist() == [[255, 0, 0], [0, 255, 0]] and size == 0.2
    # LINE_LIST: pairs (the odd last point dropped); LINE_STRIP: consecutive points;
    # ARROW without points: scale.x along its x axis (turned 180 deg)
    np.testing.assert_allclose(segments, [
        [[0, 0, 0], [1, 0, 0]], [[0, 1, 0], [0, 2, 0]],
        [[0, -1, 0], [1, -1, 0]], [[1, -1, 0], [1, 0, 0]],
        [[3, 0, 0], [2.5, 0, 0]]], atol=1e-12)
    assert seg_colours.tolist() == [[0, 0, 255]] * 2 + [[255, 0, 0]] * 3


def test_per_point_colours_and_bad_values():
    m = _marker(Marker.SPHERE_LIST, points=[(0, 0), (1, 1)])
    m.colors = [ColorRGBA(r=0.0, g=0.0, b=1.0, a=1.0), ColorRGBA(r=1.0, g=1.0, b=1.0, a=1.0)]
    assert geometry([m])[1].tolist() == [[0, 0, 255], [255, 255, 255]]
    m.colors = m.colors[:1]  # not one per point: the marker's colour
    assert geometry([m])[1].tolist() == [[255, 0, 0]] * 2
    empty = geometry([])
    assert empty[0].shape == (0, 3) and empty[2] == 0.0 and empty[3].shape == (0, 2, 3)
    with pytest.raises(ValueError, match='not finite'):
        geometry([_marker(Marker.SPHERE, x=math.nan)])
