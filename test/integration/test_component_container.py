# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``component_container``: robot_state_publishers composed in one process.

Two namespaced robot_state_publishers and one with a NaN in its description are loaded into
one container: the two good ones are ordinary nodes in the graph (names, parameters,
``robot_description`` and static TF with their frame prefix), the bad one is one error line
naming the plugin and the loader's reason, and the container keeps serving and stops
cleanly on Ctrl-C.
"""

import os
import time

from amr_description.launch.actions import ComposableNode
from amr_description.launch.actions import ComposableNodeContainer
from conftest import run_until
import pytest

pytest.importorskip('rclpy')

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')
PLUGIN = 'amr_description::RobotStatePublisher'


def _container(tmp_path, exe, descriptions):
    nodes = [ComposableNode('amr_description', PLUGIN, namespace=ns,
                            parameters=[{'robot_description': text, 'frame_prefix': f'{ns}/'}])
             for ns, text in descriptions]
    action = ComposableNodeContainer('rsp_container', composable_node_descriptions=nodes,
                                     exe_path=exe('component_container'))
    return action.build_cmd(str(tmp_path))


def test_composed_robot_state_publishers(procs, exe, ros_env, tmp_path):
    with open(URDF_PATH) as f:
        good = f.read()
    bad = good.replace('<origin xyz="0 0 0.1" rpy="0 0 0"/>',
                       '<origin xyz="0 0 nan" rpy="0 0 0"/>', 1)
    assert bad != good
    cmd = _container(tmp_path, exe, [('r1', good), ('r2', bad), ('r3', good)])
    proc = procs.start(cmd, ros_env)
    assert proc.wait_for_output("as '/r3/robot_state_publisher'", 90), proc.output

    nodes = run_until([exe('ros2'), 'node', 'list'], ros_env,
                      lambda r: '/r3/robot_state_publisher' in r.stdout.split())
    names = set(nodes.stdout.split())
    assert {'/rsp_container', '/r1/robot_state_publisher',
            '/r3/robot_state_publisher'} <= names, nodes.stdout
    assert '/r2/robot_state_publisher' not in names, nodes.stdout

    errors = [line for line in proc.output.splitlines() if '[ERROR]' in line]
    assert len(errors) == 1, proc.output
    assert f"Failed to load component '{PLUGIN}'" in errors[0] and '__ns:=/r2' in errors[0]
    assert 'nan' in errors[0].lower() or 'non-finite' in errors[0], errors[0]

    prefix = run_until([exe('ros2'), 'param', 'get', '/r3/robot_state_publisher',
                        'frame_prefix'], ros_env, lambda r: r.returncode == 0)
    assert prefix.stdout.strip() == 'String value is: r3/', prefix.stdout + prefix.stderr
    # /tf_static is transient local per publisher: both composed nodes' transforms are heard
    echo = procs.start([exe('ros2'), 'topic', 'echo', '/tf_static'], ros_env)
    for ns in ('r1', 'r3'):
        assert echo.wait_for_output(f'child_frame_id: {ns}/base_link', 90), echo.output
    assert 'frame_id: r1/base_footprint' in echo.output, echo.output
    assert echo.interrupt(30) == 0
    description = run_until([exe('ros2'), 'topic', 'echo', '--once', '/r1/robot_description',
                             '--field', 'data'], ros_env, lambda r: '<robot' in r.stdout)
    assert '<robot name=' in description.stdout

    assert proc.interrupt(30) == 0, proc.output[-2000:]
    assert 'Traceback' not in proc.output


def test_unreadable_component_list(procs, exe, ros_env, tmp_path):
    missing = procs.start([exe('component_container'), '--nodes', str(tmp_path / 'none.yaml')],
                          ros_env)
    assert missing.wait(60) == 1
    lines = missing.output.strip().splitlines()
    assert len(lines) == 1 and 'cannot read --nodes' in lines[0], missing.output
    listed = tmp_path / 'bad.yaml'
    listed.write_text('plugin: amr_description::RobotStatePublisher\n')
    bad = procs.start([exe('component_container'), '--nodes', str(listed)], ros_env)
    assert bad.wait(60) == 1
    assert 'expected a list of components' in bad.output and 'Traceback' not in bad.output


def test_composed_nodes_share_the_container_clock(ros_env):
    # in this process: the container and a composed robot_state_publisher on sim time; the
    # node's own /clock subscription is gone and its clock follows the container's
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.parameter import Parameter
    from rosgraph_msgs.msg import Clock

    from amr_description.nodes.component_container import ComponentContainer
    from amr_description.nodes.component_container import registry

    with open(URDF_PATH) as f:
        urdf = f.read()
    rclpy.init(domain_id=int(ros_env['ROS_DOMAIN_ID']))
    try:
        container = ComponentContainer(
            parameter_overrides=[Parameter('use_sim_time', value=True)])
        node = container.load(PLUGIN, ['--ros-args', '-r', '__ns:=/r7', '-p',
                                       'use_sim_time:=true', '-p',
                                       f'robot_description:={urdf}'], registry())
        assert node.get_fully_qualified_name() == '/r7/robot_state_publisher'
        assert node._time_source._clock_sub is None
        subscribed = [name for name, _ in node.get_subscriber_names_and_types_by_node(
            'robot_state_publisher', '/r7')]
        assert '/clock' not in subscribed and '/r7/joint_states' in subscribed
        feeder = rclpy.create_node('clock_feeder')
        publisher = feeder.create_publisher(Clock, '/clock', 10)
        executor = SingleThreadedExecutor()
        for each in (container, node, feeder):
            executor.add_node(each)
        message = Clock()
        message.clock.sec = 42
        end = time.monotonic() + 60
        while node.get_clock().now().nanoseconds != 42_000_000_000 and time.monotonic() < end:
            publisher.publish(message)
            executor.spin_once(timeout_sec=0.1)
        assert node.get_clock().now().nanoseconds == 42_000_000_000
        executor.shutdown()
    finally:
        rclpy.try_shutdown()
