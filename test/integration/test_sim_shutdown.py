# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Ctrl-C of ``mujoco_sim`` with active controllers, and of the nodes that receive its /clock.

SIGINT is sent twice to each process group, as a terminal Ctrl-C followed by the
orchestrator's own SIGINT (what launch does): every process must exit 0 without an ERROR
line or a traceback.
"""

import os
import signal
import time

import pytest

pytest.importorskip('rclpy')

URDF_PATH = os.path.join(os.path.dirname(__file__), '..', '..', 'urdf', 'amr.urdf')


def _ctrl_c(proc):
    os.killpg(proc.popen.pid, signal.SIGINT)
    time.sleep(0.05)
    return proc.interrupt(timeout=15.0)


def _assert_clean(proc, code):
    output = proc.output
    assert code == 0, output
    for bad in ('ERROR', 'FATAL', 'Traceback', 'Error'):
        assert bad not in output, output


@pytest.mark.parametrize('rtf', ['0.0', '1.0'])
def test_sigint_with_active_controllers(procs, exe, ros_env, rtf):
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'real_time_factor:={rtf}'],
                      ros_env)
    with open(URDF_PATH) as f:
        urdf = f.read()
    rsp = procs.start([exe('robot_state_publisher'), '--ros-args', '-p', 'use_sim_time:=true',
                       '-p', f'robot_description:={urdf}'], ros_env)
    create = procs.start([exe('create'), '-file', URDF_PATH, '-name', 'amr'], ros_env)
    assert create.wait(60) == 0, create.output
    spawner = procs.start([exe('spawner'), 'joint_state_broadcaster', 'diff_drive_controller'],
                          ros_env)
    assert spawner.wait(60) == 0, spawner.output
    assert 'Configured and activated diff_drive_controller' in spawner.output
    assert rsp.wait_for_output('got segment base_link'), rsp.output
    time.sleep(2.0)  # controllers publishing, /clock reaching robot_state_publisher
    _assert_clean(sim, _ctrl_c(sim))
    _assert_clean(rsp, _ctrl_c(rsp))


def test_sigint_during_startup(procs, exe, ros_env):
    # early: while the interpreter imports rclpy or rcl starts up; any exit code, but it exits
    for delay in (0.0, 0.3):
        node = procs.start([exe('joint_state_publisher')], ros_env)
        time.sleep(delay)  # not a wait for an event: the moment the signal lands
        assert _ctrl_c(node) is not None, node.output
    # from main() on (observed: the node parsed its robot_description and logged it), clean
    with open(URDF_PATH) as f:
        urdf = f.read()
    node = procs.start([exe('joint_state_publisher'), '--ros-args', '-p',
                        f'robot_description:={urdf}'], ros_env)
    assert node.wait_for_output('publishing 4 joints', timeout=90.0), node.output
    _assert_clean(node, _ctrl_c(node))
