# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The pose graph's markers are slam_toolbox's: namespaces, ids, types, colours, points."""

from amr_description.nav.graph_markers import graph_markers
from builtin_interfaces.msg import Time
from visualization_msgs.msg import Marker

POSES = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.5), (1.0, 2.0, 1.0), (0.5, 2.5, 2.0)]
EDGES = [(0, 1, None), (1, 2, None), (2, 3, None), (0, 2, None)]


def test_one_sphere_per_node_and_the_edges_as_line_lists():
    stamp = Time(sec=12, nanosec=5)
    markers = graph_markers(POSES, EDGES, 'map', stamp).markers
    assert markers[0].action == Marker.DELETEALL and markers[0].header.stamp == stamp
    nodes, edges = markers[1:5], markers[5:]
    assert [m.id for m in nodes] == [0, 1, 2, 3]
    for m, pose in zip(nodes, POSES):
        assert (m.ns, m.type, m.action) == ('slam_toolbox', Marker.SPHERE, Marker.ADD)
        assert m.header.frame_id == 'map'
        assert (m.pose.position.x, m.pose.position.y, m.pose.orientation.w) == (*pose[:2], 1.0)
        assert (m.scale.x, m.scale.y, m.scale.z) == (0.1, 0.1, 0.1)
        assert (m.color.r, m.color.g, m.color.b, m.color.a) == (1.0, 0.0, 0.0, 1.0)
    assert [(m.ns, m.id, m.type) for m in edges] == [
        ('slam_toolbox_edges', 0, Marker.LINE_LIST), ('slam_toolbox_edges', 1, Marker.LINE_LIST)]
    assert edges[0].scale.x == 0.05 and (edges[0].color.b, edges[0].color.a) == (1.0, 1.0)
    # each edge is a pair of points: its two nodes' positions, in the edges' order
    points = [(p.x, p.y) for p in edges[0].points]
    assert points == [(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (1.0, 2.0), (1.0, 2.0), (0.5, 2.5),
                      (0.0, 0.0), (1.0, 2.0)]
    assert edges[1].points == []


def test_localization_nodes_are_yellow_and_their_edges_cyan():
    markers = graph_markers(POSES, EDGES, 'map', Time(), first_localization=3).markers
    assert [m.color.g for m in markers[1:5]] == [0.0, 0.0, 0.0, 1.0]
    mapping, localization = markers[5:]
    assert len(mapping.points) == 6 and len(localization.points) == 2
    assert (localization.points[1].x, localization.points[1].y) == (0.5, 2.5)
    assert (localization.color.g, localization.color.b) == (1.0, 1.0)
