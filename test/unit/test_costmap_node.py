# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The costmap node's activation wait for TF and its scans waiting for their transforms.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes.
"""

import math
import threading
import time

import numpy as np
import pytest

pytest.importorskip('nav2_msgs.msg')


def test_a_costmap_activates_once_tf_joins_its_frames_and_fails_after_the_timeout(ros, caplog):
    from amr_description.core.tf_buffer import TransformBuffer
    from amr_description.nodes.costmap_2d import CostmapNode
    from rclpy.parameter import Parameter
    make, _ = ros
    tf = TransformBuffer()
    costmap = CostmapNode('global_costmap', tf, context=make('unused2').context,
                          parameter_overrides=[Parameter('initial_transform_timeout',
                                                         value=0.3)])
    started = time.monotonic()
    with pytest.raises(RuntimeError, match='Failed to activate global_costmap because '
                       'transform from base_link to map did not become available'):
        costmap.wait_for_transform(period=0.05)
    assert 0.3 <= time.monotonic() - started < 5.0
    tf.set_transform('map', 'base_link', 0.0, (1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0),
                     static=True)
    costmap.wait_for_transform(period=0.05)  # returns at once
    costmap.tf = tf = TransformBuffer()
    threading.Timer(0.2, lambda: tf.set_transform(
        'map', 'base_link', 0.0, (1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0), static=True)).start()
    costmap.p['initial_transform_timeout'] = 30.0
    started = time.monotonic()
    costmap.wait_for_transform(period=0.05)  # waits until the transform comes
    assert 0.15 <= time.monotonic() - started < 5.0
    costmap.destroy_node()


def test_the_timeout_starts_with_the_first_clock_message(ros):
    # use_sim_time before /clock: the node's time is 0; the timeout must count from the first
    # time the clock gives (a clean-clone run failed planner_server's activation at once:
    # 0 + 60 s was over when the next check read sim time 73 s)
    from amr_description.core.tf_buffer import TransformBuffer
    from amr_description.nodes.costmap_2d import CostmapNode
    from rclpy.time import Time
    make, _ = ros
    tf = TransformBuffer()
    costmap = CostmapNode('global_costmap', tf, context=make('unused3').context)
    readings = iter([0.0, 0.0, 73.0, 73.5])

    class Clock:

        def now(self):
            seconds = next(readings, 74.0)
            if seconds == 74.0:  # the transform comes after four checks
                tf.set_transform('map', 'base_link', 0.0, (1.0, 2.0, 0.0),
                                 (0.0, 0.0, 0.0, 1.0), static=True)
            return Time(nanoseconds=int(seconds * 1e9))

    costmap.get_clock = Clock
    costmap.wait_for_transform(period=0.01)  # no RuntimeError
    assert tf.lookup('map', 'base_link')[0] is not None
    costmap.destroy_node()


def _scan(stamp, ranges, frame='lidar_link'):
    from sensor_msgs.msg import LaserScan
    scan = LaserScan()
    scan.header.frame_id = frame
    scan.header.stamp.sec, scan.header.stamp.nanosec = int(stamp), int(round(stamp % 1 * 1e9))
    scan.angle_min, scan.angle_increment = 0.0, 0.0
    scan.range_min, scan.range_max = 0.1, 10.0
    scan.ranges = ranges
    return scan


def test_a_scan_waits_for_the_transform_at_its_stamp(ros):
    # one ray straight ahead hitting 1.5 m away, the robot turning: the scan must be placed
    # with the heading at its stamp (tf2 MessageFilter), not the latest one known earlier
    from amr_description.core.tf_buffer import TransformBuffer
    from amr_description.nav import costmap as cm
    from amr_description.nodes.costmap_2d import CostmapNode
    from rclpy.parameter import Parameter
    make, _ = ros
    tf = TransformBuffer()
    costmap = CostmapNode('local_costmap', tf, context=make('unused3').context,
                          parameter_overrides=[
                              Parameter('global_frame', value='odom'),
                              Parameter('plugins', value=['obstacle_layer']),
                              Parameter('obstacle_layer.plugin',
                                        value='nav2_costmap_2d::ObstacleLayer'),
                              Parameter('obstacle_layer.observation_sources', value='scan'),
                              Parameter('obstacle_layer.scan.topic', value='/scan'),
                              Parameter('obstacle_layer.scan.marking', value=True),
                              Parameter('obstacle_layer.footprint_clearing_enabled',
                                        value=False)])
    params = costmap.layers[0][2]

    def heading(t, yaw):
        tf.set_transform('odom', 'lidar_link', t, (0.0, 0.0, 0.0),
                         (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)))

    heading(10.0, 0.0)
    heading(10.1, 0.18)  # 1.8 rad/s
    costmap._queue('scan').append(_scan(10.1, [1.5]))
    costmap._queue('scan').append(_scan(10.2, [1.5]))  # its transform has not come yet
    costmap._observe(params)
    marked = np.argwhere(costmap.obstacles == cm.LETHAL_OBSTACLE)
    assert len(marked) == 1
    x, y = costmap.grid.origin[0] + (marked[0][1] + 0.5) * 0.1, \
        costmap.grid.origin[1] + (marked[0][0] + 0.5) * 0.1
    assert math.atan2(y, x) == pytest.approx(0.18, abs=0.07)  # the 10.1 s heading
    assert [s.header.stamp.nanosec for s in costmap._queue('scan')] == [200000000]
    costmap._observe(params)  # still waiting: nothing marked with the 10.1 s heading
    assert np.count_nonzero(costmap.obstacles == cm.LETHAL_OBSTACLE) == 1
    heading(10.2, 0.36)
    costmap._observe(params)
    marked = np.argwhere(costmap.obstacles == cm.LETHAL_OBSTACLE)
    angles = sorted(math.atan2(costmap.grid.origin[1] + (i + 0.5) * 0.1,
                               costmap.grid.origin[0] + (j + 0.5) * 0.1) for i, j in marked)
    assert len(angles) == 2 and angles[1] == pytest.approx(0.36, abs=0.07)
    assert not costmap._queue('scan')
    # a scan older than TF's cache can reach is dropped with one warning, not kept
    costmap._queue('scan').append(_scan(1.0, [1.5]))
    costmap._observe(params)
    assert not costmap._queue('scan')
    costmap.destroy_node()


@pytest.mark.parametrize('server', ['controller_server', 'planner_server'])
def test_a_servers_costmap_takes_its_use_sim_time_and_updates_on_wall_time(
        ros, tmp_path, server):
    # nav2_bringup hands use_sim_time to the server alone (a launch file's dict is keyed to
    # the server's name); the server passes it to its costmap, as Nav2's do to Costmap2DROS.
    # The layers then update on wall time (mapUpdateLoop's WallRate) and the costmap is
    # published on the node's clock, here sim time
    import importlib

    from amr_description.launch.actions import params_key
    from rclpy.clock import ClockType
    import yaml
    make, _ = ros
    params = tmp_path / 'server.yaml'
    params.write_text(yaml.safe_dump({params_key(server, '/r1'): {
        'ros__parameters': {'use_sim_time': True}}}))
    module = importlib.import_module(f'amr_description.nodes.{server}')
    cls = {'controller_server': 'ControllerServer', 'planner_server': 'PlannerServer'}[server]
    node = getattr(module, cls)(
        context=make('unused4').context, use_global_arguments=False,
        cli_args=['--ros-args', '-r', f'__node:={server}', '-r', '__ns:=/r1',
                  '--params-file', str(params)])
    costmap = node.costmap
    assert node.get_parameter('use_sim_time').value is True
    assert costmap.get_fully_qualified_name().startswith('/r1/')
    assert costmap.get_parameter('use_sim_time').value is True
    costmap.tf.set_transform(costmap.p['global_frame'], costmap.p['robot_base_frame'], 0.0,
                             (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), static=True)
    costmap.start()
    timers = {t.callback.__name__: t.clock.clock_type for t in costmap.timers}
    assert timers == {'update': ClockType.STEADY_TIME, 'publish': ClockType.ROS_TIME}
    costmap.destroy_node()
    node.destroy_node()


def _wall_map(width=60, height=60, column=10, resolution=0.05):
    from nav_msgs.msg import OccupancyGrid
    msg = OccupancyGrid()
    msg.header.frame_id = 'map'
    msg.info.resolution = resolution
    msg.info.width, msg.info.height = width, height
    msg.info.origin.orientation.w = 1.0
    data = np.zeros((height, width), np.int8)
    data[:, column] = 100
    msg.data = data.ravel().tolist()
    return msg


def _active_costmap(ros, name, frame, overrides):
    """Return a started CostmapNode, the robot at ``frame``'s origin, an inflation layer."""
    from amr_description.core.tf_buffer import TransformBuffer
    from amr_description.nodes.costmap_2d import CostmapNode
    from rclpy.parameter import Parameter
    make, _ = ros
    tf = TransformBuffer()
    tf.set_transform(frame, 'base_link', 0.0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0),
                     static=True)
    overrides = {'inflation_layer.plugin': 'nav2_costmap_2d::InflationLayer', **overrides}
    costmap = CostmapNode(name, tf, context=make(f'unused_{name}').context,
                          parameter_overrides=[Parameter(k, value=v)
                                               for k, v in overrides.items()])
    costmap.start()
    return costmap


def test_ros2_param_set_reaches_the_costmaps_footprint_layers_and_geometry(ros):
    # Costmap2DROS's and the layers' dynamicParametersCallback: a wall along column 10 of a
    # 5 cm map, a 0.4 m square footprint (inscribed radius 0.2 m, no padding); a cell k cells
    # from the wall is d = 0.05 k m from it and costs floor(252 exp(-f (d - r))) up to the
    # inflation radius (InflationLayer::computeCost)
    from rclpy.parameter import Parameter
    costmap = _active_costmap(ros, 'global_costmap', 'map', {
        'plugins': ['static_layer', 'inflation_layer'],
        'static_layer.plugin': 'nav2_costmap_2d::StaticLayer',
        'footprint': '[[0.2, 0.2], [0.2, -0.2], [-0.2, -0.2], [-0.2, 0.2]]',
        'footprint_padding': 0.0})
    costmap._on_map(_wall_map())

    def cost(k):
        costmap.update()
        return int(costmap.grid.costs[30, 10 + k])

    def set_(name, value):
        return costmap.set_parameters([Parameter(name, value=value)])[0]

    assert (cost(6), cost(7), cost(11), cost(12)) == (92, 56, 7, 0)  # e^-1, e^-1.5, e^-3.5
    assert set_('footprint_padding', 0.1).successful  # inscribed 0.3 m
    assert cost(7) == 152  # floor(252 e^-0.5)
    assert set_('robot_radius', 0.5).successful  # the footprint came from `footprint`: kept
    assert cost(7) == 152
    assert set_('footprint', '[[1.0, 2.0]]').successful  # does not parse: kept, one line
    assert cost(7) == 152
    assert set_('footprint', '[[0.1, 0.1], [0.1, -0.1], [-0.1, -0.1], [-0.1, 0.1]]').successful
    assert cost(7) == 56  # padded 0.1: inscribed 0.2 m again
    assert set_('inflation_layer.cost_scaling_factor', 2.0).successful
    assert cost(7) == 186  # floor(252 e^-0.3)
    assert set_('inflation_layer.inflation_radius', 0.3).successful
    assert (cost(6), cost(7)) == (206, 0)  # floor(252 e^-0.2); 7 cells are past 0.3 m
    assert set_('inflation_layer.enabled', False).successful
    assert cost(1) == 0 and cost(0) == 254
    assert set_('static_layer.enabled', False).successful
    assert cost(0) == 0

    refused = set_('width', 0)
    assert not refused.successful and 'negative or zero' in refused.reason
    assert not set_('resolution', 0.0).successful and costmap.p['resolution'] == 0.1
    assert costmap.p['width'] == 5
    started = time.monotonic()
    assert not set_('robot_base_frame', 'nowhere').successful  # TF cannot join it in 1 s
    assert 1.0 <= time.monotonic() - started < 10.0
    assert costmap.get_parameter('robot_base_frame').value == 'base_link'
    assert set_('publish_frequency', 4.0).successful
    assert costmap._publish_timer.timer_period_ns == 250_000_000
    assert set_('width', 2).successful  # the static layer's map fixed the size
    assert costmap.grid.shape == (60, 60)
    costmap.stop()
    assert set_('inflation_layer.enabled', True).successful  # inactive: stored, not applied
    assert costmap.layers[1][2]['enabled'] is False
    costmap.destroy_node()


def test_a_costmap_without_a_static_map_takes_a_new_size(ros):
    from rclpy.parameter import Parameter
    costmap = _active_costmap(ros, 'local_costmap', 'odom', {
        'global_frame': 'odom', 'rolling_window': True, 'plugins': ['inflation_layer']})
    costmap.update()
    assert costmap.grid.shape == (50, 50)  # Nav2's 5 m at 0.1 m
    results = costmap.set_parameters([Parameter('width', value=3),
                                      Parameter('resolution', value=0.05)])
    assert all(r.successful for r in results)
    assert costmap.grid.shape == (100, 60)
    assert costmap.grid.origin == pytest.approx((-1.5, -2.5))  # centred on the robot
    costmap.stop()
    costmap.destroy_node()


def test_the_clear_and_cost_services_and_the_footprint_topic(ros):
    # ClearCostmapService: the obstacle layer's cells strictly between the corner cells of a
    # square of side d around the robot (at the odom origin of a 5 m x 5 m, 0.1 m window:
    # cells 20..30 on each axis for d = 1.0, so 9 x 9 cleared) reset to its default (unknown
    # with track_unknown_space); clear_except the other 2500 - 81; GetCost the cell's cost
    from amr_description.nav import costmap as cm
    from geometry_msgs.msg import Point32
    from geometry_msgs.msg import Polygon
    from nav2_msgs.srv import ClearCostmapAroundPose
    from nav2_msgs.srv import ClearCostmapAroundRobot
    from nav2_msgs.srv import ClearCostmapExceptRegion
    from nav2_msgs.srv import GetCost
    costmap = _active_costmap(ros, 'local_costmap', 'odom', {
        'global_frame': 'odom', 'rolling_window': True, 'track_unknown_space': True,
        'plugins': ['obstacle_layer'],
        'obstacle_layer.plugin': 'nav2_costmap_2d::ObstacleLayer',
        'obstacle_layer.footprint_clearing_enabled': False})
    costmap.update()
    assert costmap.grid.origin == pytest.approx((-2.5, -2.5))

    def fill():
        costmap.obstacles[:] = cm.LETHAL_OBSTACLE

    def unknown():
        return int(np.count_nonzero(costmap.grid.costs == cm.NO_INFORMATION))

    fill()
    request = ClearCostmapAroundRobot.Request(reset_distance=1.0)
    costmap._on_clear_around(request, ClearCostmapAroundRobot.Response())
    assert unknown() == 81
    fill()
    request = ClearCostmapExceptRegion.Request(reset_distance=1.0)
    costmap._on_clear_except(request, ClearCostmapExceptRegion.Response())
    assert unknown() == 2500 - 81
    fill()
    request = ClearCostmapAroundPose.Request(reset_distance=0.6)
    request.pose.header.frame_id = 'odom'
    request.pose.pose.position.x, request.pose.pose.position.y = 1.05, -1.05
    request.pose.pose.orientation.w = 1.0
    costmap._on_clear_around_pose(request, ClearCostmapAroundPose.Response())
    assert unknown() == 25  # corners in cells 32 and 38 (x), 11 and 17 (y): 5 x 5
    request.reset_distance = float('nan')  # garbage: one line, nothing cleared, no exception
    costmap._on_clear_around_pose(request, ClearCostmapAroundPose.Response())
    assert unknown() == 25
    assert costmap.grid.cost_at(1.05, -1.05) == cm.NO_INFORMATION
    assert costmap.grid.cost_at(0.0, 0.0) == cm.LETHAL_OBSTACLE

    def cost(x, y, theta=0.0, use_footprint=False):
        request = GetCost.Request(x=x, y=y, theta=theta, use_footprint=use_footprint)
        return costmap._on_get_cost(request, GetCost.Response()).cost

    assert cost(1.05, -1.05) == 255.0 and cost(0.0, 0.0) == 254.0
    assert cost(10.0, 0.0) == -1.0  # outside the window: -1 and one warning
    costmap.obstacles[:] = cm.FREE_SPACE
    costmap.obstacles[25, 32] = cm.LETHAL_OBSTACLE  # the cell of (0.75, 0.05)
    costmap.update()
    assert cost(0.75, 0.05) == 254.0
    # the footprint topic: a 0.5 m square (padding 0.01), its outline on that cell when
    # centred 0.26 m short of it, not when centred on it
    square = Polygon(points=[Point32(x=x, y=y) for x, y in
                             ((0.25, 0.25), (0.25, -0.25), (-0.25, -0.25), (-0.25, 0.25))])
    costmap._on_footprint(square)
    assert costmap.footprint[:, 0].max() == pytest.approx(0.26)
    assert cost(0.49, 0.05, use_footprint=True) == 254.0
    assert cost(0.75, 0.05, use_footprint=True) == 0.0
    costmap._on_footprint(Polygon(points=[Point32(x=1.0)]))  # garbage: one line, kept
    assert costmap.footprint[:, 0].max() == pytest.approx(0.26)
    costmap.stop()
    costmap.destroy_node()
