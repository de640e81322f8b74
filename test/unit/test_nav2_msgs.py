# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
nav2_msgs as built at set-up: Jazzy's interface list, and the route server's field lists.

Upstream: navigation2's jazzy branch (1.3.12), ``nav2_msgs/CMakeLists.txt`` and the files it
names; docs/architecture.md ("Interface packages").
"""

import os

from nav2_msgs.action import ComputeAndTrackRoute
from nav2_msgs.action import ComputeRoute
from nav2_msgs.action import FollowObject
from nav2_msgs.msg import CriticsStats
from nav2_msgs.msg import EdgeCost
from nav2_msgs.msg import Route
from nav2_msgs.msg import RouteEdge
from nav2_msgs.msg import RouteNode
from nav2_msgs.srv import DynamicEdges
from nav2_msgs.srv import SetRouteGraph
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.join(HERE, '..', '..', 'interfaces', 'nav2_msgs')

JAZZY = {
    'msg': {
        'BehaviorTreeLog', 'BehaviorTreeStatusChange', 'CollisionDetectorState',
        'CollisionMonitorState', 'Costmap', 'CostmapFilterInfo', 'CostmapMetaData',
        'CostmapUpdate', 'CriticsStats', 'EdgeCost', 'MissedWaypoint', 'Particle',
        'ParticleCloud', 'Route', 'RouteEdge', 'RouteNode', 'SpeedLimit', 'VoxelGrid'},
    'srv': {
        'ClearCostmapAroundPose', 'ClearCostmapAroundRobot', 'ClearCostmapExceptRegion',
        'ClearEntireCostmap', 'DynamicEdges', 'GetCost', 'GetCostmap', 'IsPathValid',
        'LoadMap', 'ManageLifecycleNodes', 'ReloadDockDatabase', 'SaveMap', 'SetInitialPose',
        'SetRouteGraph', 'Toggle'},
    'action': {
        'AssistedTeleop', 'BackUp', 'ComputeAndTrackRoute', 'ComputePathThroughPoses',
        'ComputePathToPose', 'ComputeRoute', 'DockRobot', 'DriveOnHeading', 'DummyBehavior',
        'FollowGPSWaypoints', 'FollowObject', 'FollowPath', 'FollowWaypoints',
        'NavigateThroughPoses', 'NavigateToPose', 'SmoothPath', 'Spin', 'UndockRobot', 'Wait'},
}


@pytest.mark.parametrize('kind', sorted(JAZZY))
def test_the_package_has_jazzys_interfaces(kind):
    names = {os.path.splitext(name)[0] for name in os.listdir(os.path.join(PACKAGE, kind))}
    assert names == JAZZY[kind]
    with open(os.path.join(PACKAGE, 'CMakeLists.txt')) as cmake:
        text = cmake.read()
    assert all(f'"{kind}/{name}.{kind}"' in text for name in JAZZY[kind])


def fields(message):
    return list(message.get_fields_and_field_types().items())


def test_the_route_messages_field_for_field():
    assert fields(Route) == [
        ('header', 'std_msgs/Header'), ('route_cost', 'float'),
        ('nodes', 'sequence<nav2_msgs/RouteNode>'), ('edge_ids', 'sequence<uint16>')]
    assert fields(RouteNode) == [('nodeid', 'uint64'), ('position', 'geometry_msgs/Point')]
    assert fields(RouteEdge) == [
        ('edgeid', 'uint16'), ('start', 'geometry_msgs/Point'), ('end', 'geometry_msgs/Point')]
    assert fields(EdgeCost) == [('edgeid', 'uint64'), ('cost', 'float')]
    assert fields(CriticsStats) == [
        ('header', 'std_msgs/Header'), ('critics', 'sequence<string>'),
        ('changed', 'sequence<boolean>'), ('costs_sum', 'sequence<float>')]
    assert fields(SetRouteGraph.Request) == [('graph_filepath', 'string')]
    assert fields(DynamicEdges.Request) == [
        ('closed_edges', 'sequence<uint16>'), ('opened_edges', 'sequence<uint16>'),
        ('adjust_edges', 'sequence<nav2_msgs/EdgeCost>')]
    assert fields(DynamicEdges.Response) == [('success', 'boolean')]


def test_the_route_actions_field_for_field():
    goal = [('start_id', 'uint16'), ('start', 'geometry_msgs/PoseStamped'),
            ('goal_id', 'uint16'), ('goal', 'geometry_msgs/PoseStamped'),
            ('use_start', 'boolean'), ('use_poses', 'boolean')]
    assert fields(ComputeRoute.Goal) == goal == fields(ComputeAndTrackRoute.Goal)
    # Jazzy's route results have no error_msg (later distributions added it).
    assert fields(ComputeRoute.Result) == [
        ('planning_time', 'builtin_interfaces/Duration'), ('path', 'nav_msgs/Path'),
        ('route', 'nav2_msgs/Route'), ('error_code', 'uint16')]
    assert fields(ComputeAndTrackRoute.Result) == [
        ('execution_duration', 'builtin_interfaces/Duration'), ('error_code', 'uint16')]
    assert fields(ComputeAndTrackRoute.Feedback) == [
        ('last_node_id', 'uint16'), ('next_node_id', 'uint16'), ('current_edge_id', 'uint16'),
        ('route', 'nav2_msgs/Route'), ('path', 'nav_msgs/Path'),
        ('operations_triggered', 'sequence<string>'), ('rerouted', 'boolean')]
    codes = {name: getattr(ComputeAndTrackRoute.Result, name) for name in (
        'NONE', 'UNKNOWN', 'TF_ERROR', 'NO_VALID_GRAPH', 'INDETERMINANT_NODES_ON_GRAPH',
        'TIMEOUT', 'NO_VALID_ROUTE', 'OPERATION_FAILED', 'INVALID_EDGE_SCORER_USE')}
    assert list(codes.values()) == [0, 400, 401, 402, 403, 404, 405, 406, 407]
    assert not hasattr(ComputeRoute.Result, 'OPERATION_FAILED')


def test_follow_object_field_for_field():
    assert fields(FollowObject.Goal) == [
        ('pose_topic', 'string'), ('tracked_frame', 'string'),
        ('max_duration', 'builtin_interfaces/Duration')]
    assert fields(FollowObject.Result) == [
        ('total_elapsed_time', 'builtin_interfaces/Duration'), ('error_code', 'uint16'),
        ('num_retries', 'uint16'), ('error_msg', 'string')]
    assert fields(FollowObject.Feedback) == [
        ('state', 'uint16'), ('following_time', 'builtin_interfaces/Duration'),
        ('num_retries', 'uint16')]
    assert (FollowObject.Result.TF_ERROR, FollowObject.Result.TIMEOUT,
            FollowObject.Result.UNKNOWN) == (901, 904, 999)
    assert (FollowObject.Feedback.INITIAL_PERCEPTION, FollowObject.Feedback.RETRY) == (1, 4)
