# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The pose graph as slam_toolbox draws it: ``slam_toolbox/graph_visualization`` markers.

Messages only (visualization_msgs), no rclpy. Source: slam_toolbox 2.8.3
``src/loop_closure_assistant.cpp`` (``publishGraph``) and ``include/slam_toolbox/
visualization_utils.hpp`` (``toMarker``).
"""

from geometry_msgs.msg import Point
from visualization_msgs.msg import Marker
from visualization_msgs.msg import MarkerArray

NODE_SCALE = 0.1
"""Diameter of a node's sphere (m)."""

EDGE_WIDTH = 0.05
"""Width of an edge's line (m)."""


def graph_markers(poses, edges, frame_id, stamp, first_localization=None):
    """
    Return the MarkerArray of a pose graph, as slam_toolbox publishes it.

    The array holds a ``DELETEALL`` marker (nodes removed since the last array go), one red
    ``SPHERE`` (namespace ``slam_toolbox``, id = node index, 0.1 m) per node at its ``(x, y)``
    (yellow from ``first_localization`` on), and two ``LINE_LIST`` markers in namespace
    ``slam_toolbox_edges``, 0.05 m wide: id 0 (blue) with the edges between mapping nodes,
    id 1 (cyan) with those touching a localization node.

    :param poses: (N, 3) array-like of node poses ``(x, y, yaw)`` in ``frame_id`` (m, rad).
    :param edges: iterable of ``(i, j, ...)`` tuples: node indices first
        (:attr:`~amr_description.nav.pose_graph.PoseGraph.edges`).
    :param frame_id: the map frame.
    :param stamp: builtin_interfaces/Time of every marker.
    :param first_localization: index of the first localization node, or None.
    :returns: visualization_msgs/MarkerArray.
    """
    first = len(poses) if first_localization is None else int(first_localization)
    clear = Marker(action=Marker.DELETEALL)
    clear.header.stamp = stamp
    markers = [clear]
    for index, pose in enumerate(poses):
        node = _marker(frame_id, stamp, 'slam_toolbox', index, Marker.SPHERE)
        node.scale.x = node.scale.y = node.scale.z = NODE_SCALE
        node.color.r = 1.0
        node.color.g = 0.0 if index < first else 1.0
        node.pose.position.x, node.pose.position.y = float(pose[0]), float(pose[1])
        markers.append(node)
    lines = []
    for ident, (r, g, b) in enumerate(((0.0, 0.0, 1.0), (0.0, 1.0, 1.0))):
        line = _marker(frame_id, stamp, 'slam_toolbox_edges', ident, Marker.LINE_LIST)
        line.scale.x = EDGE_WIDTH
        line.color.r, line.color.g, line.color.b = r, g, b
        lines.append(line)
    for edge in edges:
        i, j = int(edge[0]), int(edge[1])
        line = lines[1] if i >= first or j >= first else lines[0]
        for k in (i, j):
            line.points.append(Point(x=float(poses[k][0]), y=float(poses[k][1])))
    return MarkerArray(markers=markers + lines)


def _marker(frame_id, stamp, ns, ident, kind):
    marker = Marker(ns=ns, id=ident, type=kind, action=Marker.ADD)
    marker.header.frame_id = frame_id
    marker.header.stamp = stamp
    marker.pose.orientation.w = 1.0
    marker.color.a = 1.0
    return marker
