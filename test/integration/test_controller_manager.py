# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Standalone controller manager over mock hardware + spawner + ``ros2 control`` verbs."""

import os
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
URDF = os.path.join(ROOT, 'urdf', 'amr.urdf')
PARAMS = os.path.join(ROOT, 'config', 'controllers.yaml')


@pytest.fixture
def cm_proc(ros_env, procs):
    pytest.importorskip('controller_manager_msgs.srv')
    proc = procs.start([sys.executable, '-m', 'amr_description.control.controller_manager',
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
    lines = [line for line in listing.output.splitlines() if not line.startswith('waiting')]
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
