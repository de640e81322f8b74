# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Controller manager + joint_state_broadcaster + diff_drive_controller on mock hardware.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery); ``update()`` is driven with
synthetic time, so results are deterministic and compared with closed-form answers.
"""

import math
import os
import textwrap
import time

from conftest import next_domain_id
import pytest

rclpy = pytest.importorskip('rclpy')
pytest.importorskip('controller_manager_msgs.srv')

from geometry_msgs.msg import TwistStamped  # noqa: E402, I100, I202

from amr_description.control.controller_manager import ControllerManager  # noqa: E402, I100
from amr_description.control.generic_system import GenericSystem  # noqa: E402
from amr_description.ros.stamps import time_to_msg  # noqa: E402

WHEELS = ('joint_wheel_front_left', 'joint_wheel_front_right', 'joint_wheel_back_left',
          'joint_wheel_back_right')
S, R = 0.3, 0.1


def _urdf(wheels=WHEELS, extra_ros2_control_joint=None):
    joints = ''.join(
        f'<joint name="{w}" type="continuous"><parent link="base_link"/>'
        f'<child link="{w}_link"/></joint><link name="{w}_link"/>' for w in wheels)
    rc_joints = list(wheels) + ([extra_ros2_control_joint] if extra_ros2_control_joint else [])
    rc = ''.join(
        f'<joint name="{w}"><command_interface name="velocity"/>'
        f'<state_interface name="position"/><state_interface name="velocity"/></joint>'
        for w in rc_joints)
    return (f'<robot name="t"><link name="base_link"/>{joints}'
            f'<ros2_control name="Mock" type="system"><hardware>'
            f'<plugin>mock_components/GenericSystem</plugin></hardware>{rc}</ros2_control>'
            f'</robot>')


PARAMS = textwrap.dedent("""
    controller_manager:
      ros__parameters:
        update_rate: 100
        joint_state_broadcaster:
          type: joint_state_broadcaster/JointStateBroadcaster
        diff_drive_controller:
          type: diff_drive_controller/DiffDriveController
        other:
          type: diff_drive_controller/DiffDriveController
    /**/diff_drive_controller:
      ros__parameters:
        left_wheel_names: [joint_wheel_front_left, joint_wheel_back_left]
        right_wheel_names: [joint_wheel_front_right, joint_wheel_back_right]
        wheel_separation: 0.3
        wheel_radius: 0.1
        cmd_vel_timeout: 0.5
        publish_rate: 50.0
    other:
      ros__parameters:
        left_wheel_names: [joint_wheel_front_left]
        right_wheel_names: [joint_wheel_front_right]
        wheel_separation: 0.3
        wheel_radius: 0.1
    """)


@pytest.fixture
def cm(tmp_path):
    os.environ['ROS_DOMAIN_ID'] = str(next_domain_id())
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    params = tmp_path / 'controllers.yaml'
    params.write_text(PARAMS)
    context = rclpy.context.Context()
    rclpy.init(context=context)
    executor = rclpy.executors.SingleThreadedExecutor(context=context)
    manager = ControllerManager(_urdf(), executor, lambda info: GenericSystem(),
                                str(params), use_sim_time=False)
    yield manager
    manager.destroy()
    executor.shutdown()
    rclpy.shutdown(context=context)


def _activate(cm, *names):
    for name in names:
        assert cm.load_controller(name) is not None
        assert cm.configure_controller(name)
    ok, message = cm.switch_controller(list(names), [], wait=False)
    assert ok, message
    cm.cycle(0.0, 0.01)
    for name in names:
        assert cm.controllers[name].lifecycle_state == 'active'


def _command(ddc, linear, angular, stamp):
    msg = TwistStamped()
    msg.header.stamp = time_to_msg(stamp)
    msg.twist.linear.x = linear
    msg.twist.angular.z = angular
    ddc._on_cmd_vel(msg)


def _wheel_cmds(cm):
    return [cm.resource_manager.command_interfaces[f'{w}/velocity'].value for w in WHEELS]


def test_wheel_commands_odometry_and_timeout(cm):
    _activate(cm, 'joint_state_broadcaster', 'diff_drive_controller')
    ddc = cm.controllers['diff_drive_controller']
    # before the first command nothing is written
    cm.cycle(0.01, 0.01)
    assert all(math.isnan(v) for v in _wheel_cmds(cm))
    t = 0.01
    v, w = 0.5, 0.4
    for _ in range(100):  # 1 s, commands refreshed every step
        t += 0.01
        _command(ddc, v, w, t)
        cm.cycle(t, 0.01)
    left = (v - w * S / 2) / R
    right = (v + w * S / 2) / R
    fl, fr, bl, br = _wheel_cmds(cm)
    assert (fl, bl) == pytest.approx((left, left))
    assert (fr, br) == pytest.approx((right, right))
    odom = ddc.odometry
    # one step of delay (mock mirrors the command at the next read): ~0.99 s of motion
    assert odom.heading == pytest.approx(w * 0.99, abs=1e-6)
    assert odom.x == pytest.approx(v / w * math.sin(odom.heading), abs=1e-6)
    assert odom.linear == pytest.approx(v)
    # timeout: the last command ages beyond 0.5 s -> zero wheel commands
    for _ in range(60):
        t += 0.01
        cm.cycle(t, 0.01)
    assert _wheel_cmds(cm) == pytest.approx([0.0] * 4)


def test_nan_command_ignored_and_stale_dropped(cm):
    _activate(cm, 'diff_drive_controller')
    ddc = cm.controllers['diff_drive_controller']
    cm.cycle(1.0, 0.01)
    _command(ddc, 0.2, 0.0, 1.0)
    _command(ddc, math.nan, 0.0, 1.0)
    _command(ddc, 1.0, 0.0, 0.2)  # 0.8 s old: dropped
    cm.cycle(1.01, 0.01)
    assert _wheel_cmds(cm) == pytest.approx([2.0] * 4)


def test_nan_state_deactivates(cm):
    _activate(cm, 'diff_drive_controller')
    cm.resource_manager.state_interfaces['joint_wheel_back_left/position'].value = math.nan
    cm.resource_manager.components[0].command_handles.clear()  # keep the NaN state
    cm.cycle(0.02, 0.01)
    assert cm.controllers['diff_drive_controller'].lifecycle_state == 'inactive'
    assert cm.resource_manager.claimed_by('diff_drive_controller') == []
    assert _wheel_cmds(cm) == pytest.approx([0.0] * 4)  # deactivation writes zero


def test_claim_conflict_rejected(cm):
    _activate(cm, 'diff_drive_controller')
    assert cm.load_controller('other') is not None
    assert cm.configure_controller('other')
    ok, message = cm.switch_controller(['other'], [], wait=False)
    assert not ok
    assert "already claimed by 'diff_drive_controller'" in message


def test_joint_state_broadcaster_order_and_values(cm):
    _activate(cm, 'joint_state_broadcaster')
    jsb = cm.controllers['joint_state_broadcaster']
    assert [row[0] for row in jsb._rows] == list(WHEELS)
    received = []
    jsb._publisher.publish = received.append
    jsb._publisher.get_subscription_count = lambda: 1  # as if subscribed (see heard)
    cm.cycle(0.5, 0.01)
    msg = received[-1]
    assert list(msg.name) == list(WHEELS)
    assert msg.header.stamp.sec == 0 and msg.header.stamp.nanosec == 500_000_000
    assert all(math.isnan(e) for e in msg.effort)
    assert list(msg.position) == [0.0] * 4


def test_controllers_skip_unheard_publications(cm):
    _activate(cm, 'joint_state_broadcaster', 'diff_drive_controller')
    jsb = cm.controllers['joint_state_broadcaster']
    ddc = cm.controllers['diff_drive_controller']
    sent = []
    for publisher in (jsb._publisher, ddc._odom_pub, ddc._tf_pub):
        publisher.publish = sent.append
        publisher.get_subscription_count = lambda: 0
    for i in range(1, 11):
        cm.cycle(0.01 * i, 0.01)
    assert sent == []  # volatile topics nobody subscribes to: nothing converted or sent
    ddc._odom_pub.get_subscription_count = lambda: 1
    for i in range(11, 21):
        cm.cycle(0.01 * i, 0.01)
    assert sent and all(type(m).__name__ == 'Odometry' for m in sent)  # odom only


def test_configure_fails_without_wheels(cm, tmp_path):
    cm.set_parameters([rclpy.parameter.Parameter('bad.type', value='diff_drive_controller/'
                                                 'DiffDriveController')])
    assert cm.load_controller('bad') is not None
    assert not cm.configure_controller('bad')
    assert cm.controllers['bad'].lifecycle_state == 'unconfigured'


def test_unknown_type_and_ros2_control_joint_missing(cm):
    cm.set_parameters([rclpy.parameter.Parameter('x.type', value='nope/Nope')])
    assert cm.load_controller('x') is None
    from amr_description.control.resource_manager import ResourceManager
    with pytest.raises(ValueError, match="joint 'ghost'"):
        ResourceManager(_urdf(extra_ros2_control_joint='ghost'), lambda i: GenericSystem())


# ------------------------------------------------------------------ controller-manager parity
def _graph_node_names(cm):
    return sorted(name for name, ns in cm.get_node_names_and_namespaces())


def test_unload_removes_the_controller_node_from_the_graph(cm):
    """Load-unload-load leaves exactly one controller node (issue: a node stayed behind)."""
    before = _graph_node_names(cm)
    _activate(cm, 'diff_drive_controller')
    assert _graph_node_names(cm).count('diff_drive_controller') == 1
    ok, _ = cm.switch_controller([], ['diff_drive_controller'], wait=False)
    assert ok
    cm.cycle(0.02, 0.01)
    assert cm.unload_controller('diff_drive_controller')
    assert _graph_node_names(cm) == before
    assert cm.load_controller('diff_drive_controller') is not None
    names = _graph_node_names(cm)
    assert names.count('diff_drive_controller') == 1
    assert cm.unload_controller('diff_drive_controller')
    assert _graph_node_names(cm) == before


def test_node_options_args_remap_the_controller_topics(cm):
    from rclpy.parameter import Parameter
    result = cm.set_parameters([Parameter(
        'diff_drive_controller.node_options_args',
        value=['-r', '~/cmd_vel:=/cmd_vel_remapped'])])
    assert result[0].successful
    ctrl = cm.load_controller('diff_drive_controller')
    assert cm.configure_controller('diff_drive_controller')
    topics = [sub.topic_name for sub in ctrl.subscriptions]
    assert '/cmd_vel_remapped' in topics
    assert '/diff_drive_controller/cmd_vel' not in topics


def test_update_rate_is_read_only_and_described(cm):
    from rclpy.parameter import Parameter
    result = cm.set_parameters([Parameter('update_rate', value=50)])
    assert not result[0].successful
    assert cm.get_parameter('update_rate').value == 100
    descriptor = cm.describe_parameter('update_rate')
    assert descriptor.read_only
    assert 'update loop' in descriptor.description


def test_controller_nodes_have_update_rate_and_is_async(cm):
    ctrl = cm.load_controller('joint_state_broadcaster')
    assert ctrl.get_parameter('update_rate').value == 100
    assert ctrl.get_parameter('is_async').value is False
    assert ctrl.get_parameter('thread_priority').value == 50


def test_controller_update_rate_decimates_its_updates(cm):
    from rclpy.parameter import Parameter
    cm.set_parameters([Parameter('joint_state_broadcaster.node_options_args',
                                 value=['-p', 'update_rate:=25'])])
    _activate(cm, 'joint_state_broadcaster')
    jsb = cm.controllers['joint_state_broadcaster']
    assert jsb.update_rate == 25
    received = []
    jsb._publisher.publish = received.append
    jsb._publisher.get_subscription_count = lambda: 1  # as if subscribed (see heard)
    for k in range(1, 101):  # 1 s at 100 Hz
        cm.cycle(k * 0.01, 0.01)
    assert len(received) == 25


def test_switch_strictness_and_messages(cm):
    assert cm.load_controller('joint_state_broadcaster') is not None
    assert cm.configure_controller('joint_state_broadcaster')
    # strictness 0 (unset) is BEST_EFFORT, as upstream: the valid part is switched
    ok, message = cm.switch_controller(['joint_state_broadcaster', 'nonexistent'], [], 0,
                                       wait=False)
    assert ok, message
    cm.cycle(0.01, 0.01)
    assert cm.controllers['joint_state_broadcaster'].lifecycle_state == 'active'
    # STRICT with an unknown name: nothing switched, upstream's message
    ok, message = cm.switch_controller([], ['joint_state_broadcaster', 'nonexistent'], 2,
                                       wait=False)
    assert not ok
    assert "Could not deactivate controller with name 'nonexistent' because no controller " \
        'with this name exists' in message
    assert cm.controllers['joint_state_broadcaster'].lifecycle_state == 'active'
    # BEST_EFFORT naming only what cannot be switched fails too
    ok, message = cm.switch_controller(['nonexistent'], [], 1, wait=False)
    assert not ok
    # a real switch answers upstream's success message
    done = []
    import threading
    thread = threading.Thread(target=lambda: done.append(cm.switch_controller(
        [], ['joint_state_broadcaster'], 1, timeout=30.0)))
    thread.start()
    while thread.is_alive():
        cm.cycle(0.02, 0.01)
        thread.join(0.01)
    ok, message = done[0]
    assert ok
    assert message.startswith('Successfully switched controllers!')


def test_cleanup_reload_and_hardware_state(cm):
    _activate(cm, 'diff_drive_controller')
    assert not cm.cleanup_controller('diff_drive_controller')  # active
    assert not cm.reload_controller_libraries(False)  # a controller is active
    # the hardware leaving 'active' deactivates the controller claiming its interfaces
    ok, label = cm.set_hardware_component_state('Mock', 2, 'inactive')
    assert (ok, label) == (True, 'inactive')
    assert cm.controllers['diff_drive_controller'].lifecycle_state == 'inactive'
    assert not cm.resource_manager.command_interface_available(
        'joint_wheel_front_left/velocity')
    assert cm.set_hardware_component_state('Mock', 1, '') == (True, 'unconfigured')
    assert cm.set_hardware_component_state('Mock', 3, '') == (True, 'active')
    assert cm.set_hardware_component_state('nope', 3, '') == (False, 'unknown')
    assert cm.cleanup_controller('diff_drive_controller')
    assert cm.controllers['diff_drive_controller'].lifecycle_state == 'unconfigured'
    before = _graph_node_names(cm)
    assert 'diff_drive_controller' in before
    assert cm.reload_controller_libraries(True)
    assert cm.controllers == {}
    assert 'diff_drive_controller' not in _graph_node_names(cm)


def test_activity_topic(cm):
    from controller_manager_msgs.msg import ControllerManagerActivity
    from rclpy.qos import DurabilityPolicy
    from rclpy.qos import QoSProfile
    received = []
    listener = rclpy.create_node('activity_listener', context=cm.context)
    try:
        listener.create_subscription(
            ControllerManagerActivity, '/controller_manager/activity', received.append,
            QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        executor = rclpy.executors.SingleThreadedExecutor(context=cm.context)
        executor.add_node(listener)
        assert cm.load_controller('joint_state_broadcaster') is not None
        deadline = time.monotonic() + 30.0
        while time.monotonic() < deadline and not any(
                [c.name for c in m.controllers] == ['joint_state_broadcaster']
                for m in received):
            executor.spin_once(timeout_sec=0.1)
        last = received[-1]
        assert [(c.name, c.state.id, c.state.label) for c in last.controllers] == [
            ('joint_state_broadcaster', 1, 'unconfigured')]
        assert [(c.name, c.state.label) for c in last.hardware_components] == [
            ('Mock', 'active')]
        executor.shutdown()
    finally:
        listener.destroy_node()


def test_controller_parameters_have_descriptions(cm):
    ddc = cm.load_controller('diff_drive_controller')
    assert 'odometry' in ddc.describe_parameter('open_loop').description
    assert ddc.describe_parameter('update_rate').description


def test_destroy_leaves_nothing_in_the_graph(tmp_path):
    os.environ['ROS_DOMAIN_ID'] = str(next_domain_id())
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    params = tmp_path / 'controllers.yaml'
    params.write_text(PARAMS)
    context = rclpy.context.Context()
    rclpy.init(context=context)
    try:
        observer = rclpy.create_node('observer', context=context)
        executor = rclpy.executors.SingleThreadedExecutor(context=context)
        manager = ControllerManager(_urdf(), executor, lambda info: GenericSystem(),
                                    str(params), use_sim_time=False)
        _activate(manager, 'joint_state_broadcaster', 'diff_drive_controller')
        assert _graph_node_names(observer) == [
            'controller_manager', 'diff_drive_controller', 'joint_state_broadcaster',
            'observer']
        manager.destroy()
        manager.destroy()  # twice is harmless
        assert _graph_node_names(observer) == ['observer']
        assert executor.get_nodes() == []
        executor.shutdown()
        observer.destroy_node()
    finally:
        rclpy.shutdown(context=context)
