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
