# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A robot written for Gazebo runs unchanged: xacro, gz_ros2_control's names and plugin.

test/data/gz_tutorial/robot.urdf.xacro is the tutorial robot as Jazzy + Harmonic users write
it (``gz_ros2_control/GazeboSimSystem``, the ``libgz_ros2_control-system.so`` plugin with
its ``<parameters>``, no ``<mujoco>`` block) with the tutorial's literal controllers.yaml
(``base_frame_id: base_link``, no multiplier). It goes through the tutorial's own command
sequence: robot_state_publisher with the xacro output, ``create -topic robot_description``,
one spawner for both controllers; then it drives forward and turns.
"""

import math
import os

import pytest
import yaml
from test_drive import DrivePeer  # noqa: I100 - the drive tests' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
DATA = os.path.join(ROOT, 'test', 'data', 'gz_tutorial')


@pytest.fixture
def drive_peer(ros_env):
    pytest.importorskip('controller_manager_msgs.srv')
    p = DrivePeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def _description(**xacro_args):
    from amr_description.core.description.files import read_description
    args = {'controllers': os.path.join(DATA, 'controllers.yaml')}
    args.update(xacro_args)
    return read_description(os.path.join(DATA, 'robot.urdf.xacro'), args)


def test_tutorial_gazebo_robot_drives_forward_and_turns(procs, exe, ros_env, drive_peer,
                                                        tmp_path):
    peer = drive_peer
    params = tmp_path / 'rsp.yaml'
    params.write_text(yaml.safe_dump({'robot_state_publisher': {'ros__parameters': {
        'robot_description': _description(), 'use_sim_time': True}}}))
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0.0',
                       '-r', '/diff_drive_controller/odom:=/odom'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 30), sim.output
    procs.start([exe('robot_state_publisher'), '--ros-args', '--params-file', str(params)],
                ros_env)
    create = procs.start([exe('create'), '-topic', 'robot_description', '-z', '0.05'],
                         ros_env)
    assert create.wait(60) == 0, create.output + sim.output
    assert 'tutorial_bot' in create.output
    spawner = procs.start([exe('spawner'), 'joint_state_broadcaster', 'diff_drive_controller',
                           '--controller-manager-timeout', '30'], ros_env)
    assert spawner.wait(90) == 0, spawner.output + sim.output
    assert 'Configured and activated diff_drive_controller' in spawner.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    peer.step(500)  # settle
    assert peer.odom and peer.ctrl_odom, sim.output
    assert peer.ctrl_odom[-1].child_frame_id == 'base_link'  # the tutorial's base_frame_id
    gx0, gy0, gyaw0, ox0, oy0, oyaw0 = peer.pose()

    peer.drive(0.5, 0.0, 2.0)
    peer.command(0.0, 0.0)
    peer.step(500)
    gx, gy, gyaw, ox, oy, oyaw = peer.pose()
    ground = math.hypot(gx - gx0, gy - gy0)
    odometry = math.hypot(ox - ox0, oy - oy0)
    print(f'gazebo dialect straight: ground truth {ground:.4f} m, odometry {odometry:.4f} m')
    assert ground == pytest.approx(1.0, rel=0.05), sim.output[-2000:]
    assert odometry == pytest.approx(ground, rel=0.01)

    peer.drive(0.0, 1.0, 1.5)
    peer.command(0.0, 0.0)
    peer.step(500)
    gx1, gy1, gyaw1, ox1, oy1, oyaw1 = peer.pose()
    turned = math.atan2(math.sin(gyaw1 - gyaw), math.cos(gyaw1 - gyaw))
    print(f'gazebo dialect turn: ground truth {math.degrees(turned):.1f} deg')
    # counter-clockwise, as commanded; 1.5 rad commanded, a skid-steer without the
    # wheel_separation_multiplier turns less (0.46 rad measured, docs/gazebo.md)
    assert turned > 0.3


def test_bad_gazebo_descriptions_are_one_line_and_the_simulator_runs_on(procs, exe, ros_env,
                                                                        drive_peer, tmp_path):
    peer = drive_peer
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0.0'],
                      ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 30), sim.output
    # the xacro's default <parameters> (controllers.yaml, relative) names no file here
    missing = procs.start([exe('create'), '-file', os.path.join(DATA, 'robot.urdf.xacro')],
                          ros_env)
    assert missing.wait(60) == 1, missing.output
    assert "controller parameters file 'controllers.yaml' not found" in missing.output
    broken = tmp_path / 'broken.urdf.xacro'
    broken.write_text('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                      '<xacro:include filename="$(find nosuchpkg)/x.urdf"/></robot>')
    refused = procs.start([exe('create'), '-file', str(broken)], ros_env)
    assert refused.wait(60) == 1, refused.output
    errors = [line for line in refused.output.splitlines() if '[ERROR]' in line]
    assert len(errors) == 1 and 'nosuchpkg' in errors[0] and str(broken) in errors[0], \
        refused.output
    # a gz-sim DiffDrive naming a joint the URDF does not have
    caster = os.path.join(ROOT, 'test', 'data', 'gz_diff_drive', 'robot.urdf.xacro')
    from amr_description.core.description.files import read_description
    wrong = tmp_path / 'wrong_joint.urdf'
    wrong.write_text(read_description(caster).replace(
        '<left_joint>left_wheel_joint</left_joint>', '<left_joint>left_wheel</left_joint>'))
    refused = procs.start([exe('create'), '-file', str(wrong)], ros_env)
    assert refused.wait(60) == 1, refused.output
    errors = [line for line in refused.output.splitlines() if '[ERROR]' in line]
    assert len(errors) == 1 and "<left_joint>: joint 'left_wheel' is not a moving joint" \
        in errors[0], refused.output
    # the simulator is still there and spawns the next robot
    good = procs.start([exe('create'), '-file', os.path.join(ROOT, 'urdf', 'amr.urdf')],
                       ros_env)
    assert good.wait(60) == 0, good.output + sim.output
    assert sim.popen.poll() is None
