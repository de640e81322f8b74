# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 param set`` on the Nav2 servers while active, as upstream's dynamicParametersCallback.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes: velocity_smoother,
waypoint_follower and planner_server are configured and activated by their lifecycle
transitions, then given values through ``set_parameters`` (what ``ros2 param set`` calls).
"""

import pytest

pytest.importorskip('nav2_msgs.msg')

NO_BOND = 'bond_heartbeat_period'


def _managed(cls, context, **overrides):
    from rclpy.parameter import Parameter
    node = cls(context=context, parameter_overrides=[Parameter(NO_BOND, value=0.0)] + [
        Parameter(k, value=v) for k, v in overrides.items()])
    return node


def _set(node, name, value):
    from rclpy.parameter import Parameter
    return node.set_parameters([Parameter(name, value=value)])[0]


def test_velocity_smoother_takes_its_limits_and_refuses_upstreams_bad_values(ros):
    from amr_description.nodes.velocity_smoother import VelocitySmoother
    make, _ = ros
    node = _managed(VelocitySmoother, make('unused1').context)
    node.trigger_configure()
    node.trigger_activate()
    assert _set(node, 'max_velocity', [0.3, 0.0, 1.0]).successful
    assert _set(node, 'smoothing_frequency', 10.0).successful
    assert node._timer.timer_period_ns == 100_000_000
    # one tick from rest towards 1 m/s: clamped to 0.3 m/s, then by max_accel 2.5 m/s^2 over
    # 0.1 s, i.e. 0.25 m/s
    node._on_command(1.0, 0.0, 0.0)
    node._tick()
    assert node.current[0] == pytest.approx(0.25)
    for name, value, line in [
            ('max_accel', [-1.0, 0.0, 3.2], 'Negative values set of acceleration! These should '
             'be positive to speed up!'),
            ('max_decel', [2.5, 0.0, -3.2], 'Positive values set of deceleration! These should '
             'be negative to slow down!'),
            ('deadband_velocity', [0.0, 0.0], 'Invalid size of parameter deadband_velocity. '
             'Must be size 3'),
            ('feedback', 'SOMETIMES', 'Invalid feedback_type, options are OPEN_LOOP and '
             'CLOSED_LOOP.')]:
        result = _set(node, name, value)
        assert not result.successful and result.reason == line
    assert node.p['max_accel'] == [2.5, 0.0, 3.2] and node.p['feedback'] == 'OPEN_LOOP'
    assert list(node.get_parameter('max_accel').value) == [2.5, 0.0, 3.2]
    node.trigger_deactivate()
    assert _set(node, 'max_velocity', [0.1, 0.0, 1.0]).successful  # inactive: not taken
    assert node.p['max_velocity'] == [0.3, 0.0, 1.0]
    node.destroy_node()


def test_velocity_smoother_configure_refuses_with_upstreams_lines(ros):
    from amr_description.nodes.velocity_smoother import VelocitySmoother
    from rclpy.lifecycle import TransitionCallbackReturn
    make, _ = ros
    for overrides, line in [
            ({'max_decel': [2.5, 0.0, -3.2]}, 'Positive values set of deceleration!'),
            ({'min_velocity': [0.6, 0.0, -2.5]}, 'Min velocities are higher than max'),
            ({'max_velocity': [0.5, 0.0]}, 'All limits must be size of 3'),
            ({'feedback': 'OFTEN'}, 'Invalid feedback_type')]:
        node = _managed(VelocitySmoother, make('unused2').context, **overrides)
        lines = []
        node.get_logger().error = lines.append
        assert node.on_configure(None) == TransitionCallbackReturn.FAILURE
        assert len(lines) == 1 and line in lines[0], (overrides, lines)
        node.destroy_node()


def test_waypoint_follower_takes_loop_rate_and_stop_on_failure(ros):
    from amr_description.nav.waypoints import WaypointRun
    from amr_description.nodes.waypoint_follower import WaypointFollower
    make, _ = ros
    node = _managed(WaypointFollower, make('unused3').context)
    node.trigger_configure()
    node.trigger_activate()
    node.run = WaypointRun(3, stop_on_failure=True)
    assert _set(node, 'stop_on_failure', False).successful
    assert node.p['stop_on_failure'] is False and node.run.stop_on_failure is False
    assert _set(node, 'loop_rate', 10).successful
    assert node._timer.timer_period_ns == 100_000_000
    result = _set(node, 'loop_rate', 0)
    assert not result.successful and 'loop_rate' in result.reason
    assert node.p['loop_rate'] == 10
    node.trigger_deactivate()
    node.destroy_node()


def test_planner_server_takes_navfns_parameters_and_its_frequency(ros):
    from amr_description.nodes.planner_server import PlannerServer
    make, _ = ros
    node = _managed(PlannerServer, make('unused4').context)
    node.tf_buffer.set_transform('map', 'base_link', 0.0, (0.0, 0.0, 0.0),
                                 (0.0, 0.0, 0.0, 1.0), static=True)
    node.trigger_configure()
    node.trigger_activate()
    for name, value in [('GridBased.tolerance', 0.0), ('GridBased.allow_unknown', False),
                        ('GridBased.use_final_approach_orientation', True)]:
        assert _set(node, name, value).successful
    assert node.planners['GridBased'] == {
        'plugin': 'nav2_navfn_planner::NavfnPlanner', 'tolerance': 0.0, 'allow_unknown': False,
        'use_astar': False, 'use_final_approach_orientation': True}
    lines = []
    node.get_logger().warning = lines.append
    assert _set(node, 'expected_planner_frequency', 0.0).successful
    assert node.frequency == 0.0 and lines == [
        'The expected planner frequency parameter is 0.0000 Hz. The value should to be greater '
        'than 0.0 to turn on duration overrrun warning messages']
    node.trigger_deactivate()
    node.trigger_cleanup()  # stops the TF listener's thread
    node.costmap.destroy_node()
    node.destroy_node()
