# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Standalone controller manager over mock hardware + spawner + ``ros2 control`` verbs."""

import os
import shutil
import sys
import time

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
URDF = os.path.join(ROOT, 'urdf', 'amr.urdf')
PARAMS = os.path.join(ROOT, 'config', 'controllers.yaml')


@pytest.fixture
def cm_proc(ros_env, procs):
    pytest.importorskip('controller_manager_msgs.srv')
    proc = procs.start([sys.executable, '-m', 'amr_description.nodes.ros2_control_node',
                        '--urdf', URDF, '--params', PARAMS, '--mock-hardware'], ros_env)
    assert proc.wait_for_output('update rate is 100 Hz', 20.0), proc.output
    return proc


def test_spawner_and_list_controllers(cm_proc, ros_env, procs, exe):
    spawner = procs.start([exe('spawner'), 'joint_state_broadcaster', 'diff_drive_controller',
                           '--controller-manager-timeout', '20'], ros_env)
    assert spawner.wait(60.0) == 0, spawner.output
    out = spawner.output
    assert 'Loaded joint_state_broadcaster' in out
    assert 'Configured and activated joint_state_broadcaster' in out
    assert 'Configured and activated diff_drive_controller' in out

    listing = procs.start([exe('ros2'), 'control', 'list_controllers'], ros_env)
    assert listing.wait(30.0) == 0, listing.output
    lines = [line for line in listing.output.splitlines() if 'waiting for service' not in line]
    assert lines == [
        'joint_state_broadcaster joint_state_broadcaster/JointStateBroadcaster  active',
        'diff_drive_controller   diff_drive_controller/DiffDriveController      active',
    ]

    hw = procs.start([exe('ros2'), 'control', 'list_hardware_interfaces'], ros_env)
    assert hw.wait(30.0) == 0, hw.output
    assert 'command interfaces' in hw.output
    assert '\tjoint_wheel_back_left/velocity [available] [claimed]' in hw.output
    assert '\tjoint_wheel_front_right/position' in hw.output

    # spawning again: skipped with a warning, still success
    again = procs.start([exe('spawner'), 'diff_drive_controller'], ros_env)
    assert again.wait(30.0) == 0, again.output
    assert 'Controller already loaded, skipping load_controller' in again.output


def test_spawner_failures(cm_proc, ros_env, procs, exe):
    bad = procs.start([exe('spawner'), 'no_such_controller',
                       '--controller-manager-timeout', '20'], ros_env)
    assert bad.wait(30.0) == 1, bad.output
    assert 'Failed loading controller no_such_controller' in bad.output
    assert "The 'type' param was not defined for 'no_such_controller'" in cm_proc.output


def test_spawner_without_manager(ros_env, procs, exe):
    pytest.importorskip('controller_manager_msgs.srv')
    proc = procs.start([exe('spawner'), 'joint_state_broadcaster', '-c', '/nobody',
                        '--controller-manager-timeout', '1'], ros_env)
    assert proc.wait(30.0) == 1, proc.output
    assert 'Could not contact service /nobody/list_controllers' in proc.output


# ------------------------------------------------------------------ controller-manager parity
def _ros2(procs, exe, env, *argv, timeout=60.0, cwd=None):
    """Run ``ros2 ARGV`` to completion; returns (exit code, output without waiting notes)."""
    proc = procs.start([exe('ros2')] + list(argv), env, cwd=cwd)
    code = proc.wait(timeout)
    lines = [line for line in proc.output.splitlines()
             if 'waiting for service' not in line]
    return code, lines


def _node_list(procs, exe, env):
    code, lines = _ros2(procs, exe, env, 'node', 'list')
    assert code == 0, lines
    return lines


def _wait_node_list(procs, exe, env, expected, timeout=60.0):
    """Poll ``ros2 node list`` until it equals ``expected`` (discovery lags on a busy box)."""
    deadline = time.monotonic() + timeout
    lines = None
    while time.monotonic() < deadline:
        lines = _node_list(procs, exe, env)
        if lines == expected:
            return lines
    return lines


def _spawn(procs, exe, env, *argv):
    spawner = procs.start([exe('spawner')] + list(argv) +
                          ['--controller-manager-timeout', '30'], env)
    assert spawner.wait(90.0) == 0, spawner.output
    return spawner


def test_load_unload_load_leaves_one_controller_node(cm_proc, ros_env, procs, exe):
    _spawn(procs, exe, ros_env, 'joint_state_broadcaster', 'diff_drive_controller')
    with_both = ['/controller_manager', '/diff_drive_controller', '/joint_state_broadcaster']
    assert _wait_node_list(procs, exe, ros_env, with_both) == with_both
    code, lines = _ros2(procs, exe, ros_env, 'control', 'set_controller_state',
                        'diff_drive_controller', 'inactive')
    assert (code, lines) == (0, ['Successfully deactivated diff_drive_controller'])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'unload_controller',
                        'diff_drive_controller')
    assert (code, lines) == (0, ['Successfully unloaded controller diff_drive_controller'])
    without = ['/controller_manager', '/joint_state_broadcaster']
    assert _wait_node_list(procs, exe, ros_env, without) == without
    code, lines = _ros2(procs, exe, ros_env, 'control', 'load_controller',
                        'diff_drive_controller', '--set-state', 'active')
    assert code == 0, lines
    assert lines == ['Successfully loaded controller diff_drive_controller into state active']
    assert _wait_node_list(procs, exe, ros_env, with_both) == with_both
    assert 'Publisher already registered' not in cm_proc.output


def test_controller_ros_args_remap(cm_proc, ros_env, procs, exe):
    spawner = _spawn(procs, exe, ros_env, 'diff_drive_controller', '--controller-ros-args',
                     '-r ~/cmd_vel:=/cmd_vel_remapped')
    assert 'Setting controller param "node_options_args" to ' \
        '"[\'-r\', \'~/cmd_vel:=/cmd_vel_remapped\']" for diff_drive_controller' \
        in spawner.output
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline:
        code, topics = _ros2(procs, exe, ros_env, 'topic', 'list')
        if '/cmd_vel_remapped' in topics and '/diff_drive_controller/odom' in topics:
            break
    assert '/cmd_vel_remapped' in topics
    assert '/diff_drive_controller/cmd_vel' not in topics
    assert '/diff_drive_controller/odom' in topics


def test_switch_errors_and_verbose_lists(cm_proc, ros_env, procs, exe):
    _spawn(procs, exe, ros_env, 'joint_state_broadcaster')
    code, lines = _ros2(procs, exe, ros_env, 'control', 'switch_controllers', '--activate',
                        'nonexistent')
    assert code == 1, lines
    assert lines[0] == 'Error switching controllers, check controller_manager logs'
    assert "Could not activate controller with name 'nonexistent' because no controller " \
        'with this name exists' in lines[1]
    code, lines = _ros2(procs, exe, ros_env, 'control', 'list_controllers', '-v')
    assert code == 0, lines
    assert lines == [
        'joint_state_broadcaster joint_state_broadcaster/JointStateBroadcaster  active',
        '\tupdate_rate: 100 Hz',
        '\tis_async: False',
        '\tclaimed interfaces:',
        '\trequired command interfaces:',
        '\trequired state interfaces:',
    ] + [f'\t\t{w}/{i}'
         for w in ('joint_wheel_front_left', 'joint_wheel_front_right',
                   'joint_wheel_back_left', 'joint_wheel_back_right')
         for i in ('position', 'velocity')] + [
        '\tchained to interfaces:',
        '\texported state interfaces:',
        '\texported reference interfaces:',
    ]
    code, lines = _ros2(procs, exe, ros_env, 'control', 'list_hardware_components', '-v')
    assert code == 0, lines
    assert lines[:7] == [
        'Hardware Component 1', '\tname: AmrSystem', '\ttype: system',
        '\tplugin name: amr_description/MujocoSystem', '\tstate: id=3 label=active',
        '\tread/write rate: 100 Hz', '\tis_async: False']
    assert '\tcommand interfaces' in lines
    assert '\t\tjoint_wheel_front_left/velocity [double] [available] [unclaimed]' in lines
    assert '\tstate interfaces' in lines
    assert '\t\tjoint_wheel_front_left/position [double] [available]' in lines


def test_new_verbs(cm_proc, ros_env, procs, exe, tmp_path):
    _spawn(procs, exe, ros_env, 'joint_state_broadcaster', 'diff_drive_controller')
    # view_controller_chains: the DOT source always, the PDF when Graphviz's dot is there
    code, lines = _ros2(procs, exe, ros_env, 'control', 'view_controller_chains', '--save',
                        cwd=str(tmp_path))
    source = (tmp_path / 'controller_diagram.gv').read_text()
    assert source.startswith('digraph g {')
    assert 'rankdir=LR' in source
    assert ('diff_drive_controller:"command_start_joint_wheel_front_left/velocity" -> '
            'command_interfaces:"command_end_joint_wheel_front_left/velocity"') in source
    assert ('state_interfaces:"state_start_joint_wheel_back_right/position" -> '
            'joint_state_broadcaster:"state_end_joint_wheel_back_right/position"') in source
    if shutil.which('dot'):
        assert code == 0, lines
        assert lines == [f'Saved controller diagram to {tmp_path}/controller_diagram.pdf']
        assert (tmp_path / 'controller_diagram.pdf').read_bytes().startswith(b'%PDF')
    else:
        assert code == 1, lines
        assert 'install the Debian package graphviz' in lines[-1]
    # cleanup_controller: only from inactive
    code, lines = _ros2(procs, exe, ros_env, 'control', 'cleanup_controller',
                        'diff_drive_controller')
    assert (code, lines) == (1, ['Error cleanup controllers, check controller_manager logs'])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'switch_controllers', '--deactivate',
                        'diff_drive_controller')
    assert (code, lines) == (0, ['Successfully switched controllers'])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'cleanup_controller',
                        'diff_drive_controller')
    assert (code, lines) == (0, ['Successfully cleaned up controller diff_drive_controller'])
    # set_hardware_component_state: active -> inactive makes the interfaces unavailable
    code, lines = _ros2(procs, exe, ros_env, 'control', 'set_hardware_component_state',
                        'AmrSystem', 'inactive')
    assert (code, lines) == (0, [
        "Successfully set AmrSystem to state lifecycle_msgs.msg.State(id=2, label='inactive')"])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'list_hardware_interfaces')
    assert '\tjoint_wheel_front_left/velocity [unavailable] [unclaimed]' in lines
    code, lines = _ros2(procs, exe, ros_env, 'control', 'set_hardware_component_state',
                        'AmrSystem', 'active')
    assert code == 0, lines
    code, lines = _ros2(procs, exe, ros_env, 'control', 'set_hardware_component_state',
                        'Nope', 'active')
    assert (code, lines) == (1, ['component Nope does not seem to be loaded'])
    # reload_controller_libraries: refused while a controller is active, then forced
    code, lines = _ros2(procs, exe, ros_env, 'control', 'reload_controller_libraries')
    assert (code, lines) == (1, ['Error reloading libraries, check controller_manager logs'])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'reload_controller_libraries',
                        '--force-kill')
    assert (code, lines) == (0, ['Reload successful'])
    code, lines = _ros2(procs, exe, ros_env, 'control', 'list_controllers')
    assert (code, lines) == (0, ['No controllers are currently loaded!'])
    assert _wait_node_list(procs, exe, ros_env, ['/controller_manager']) == \
        ['/controller_manager']


def test_with_a_warm_daemon_ros2_control_calls_through_it(cm_proc, ros_env, procs, exe):
    """The daemon's node, long since discovered, calls the service: no discovery wait."""
    import rclpy
    from conftest import run_until
    started = procs.start([exe('ros2'), 'daemon', 'start'], ros_env)
    assert started.wait(30.0) == 0, started.output
    run_until([exe('ros2'), 'service', 'list'], ros_env,
              lambda r: '/controller_manager/list_controllers' in r.stdout)
    listing = procs.start([exe('ros2'), 'control', 'list_controllers'], ros_env)
    assert listing.wait(30.0) == 0, listing.output
    assert listing.output == 'No controllers are currently loaded!\n', listing.output
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=int(ros_env['ROS_DOMAIN_ID']))
    try:
        node = rclpy.create_node('_probe', context=context)
        deadline = time.monotonic() + 30.0
        clients = []
        while time.monotonic() < deadline and not clients:
            for name, namespace in node.get_node_names_and_namespaces():
                if name.startswith('_ros2cli_daemon_'):
                    clients = [c for c, _ in node.get_client_names_and_types_by_node(
                        name, namespace) if c == '/controller_manager/list_controllers']
            time.sleep(0.1)
        assert clients, 'the daemon has no list_controllers client: it did not make the call'
        node.destroy_node()
    finally:
        rclpy.shutdown(context=context)
