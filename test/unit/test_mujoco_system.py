# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""MujocoSystem: state from qpos/qvel, velocity commands to actuators, NaN and clamping."""

import math

from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.sim.mujoco_system import MujocoSystem
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.world import World
import pytest
from sim_fixtures import tutorial_urdf


def _system(urdf=None):
    urdf = urdf or tutorial_urdf()
    world = World()
    world.spawn(urdf_to_spec(urdf, pose=(0, 0, 0.0, 0, 0, 0)), 'amr')
    system = MujocoSystem(world.model, world.data, prefix='amr/')
    assert system.on_init(parse_ros2_control(urdf)[0])
    return world, system


def test_handles_and_initial_state():
    _, system = _system()
    names = [h.name for h in system.export_state_interfaces()]
    assert names[:2] == ['joint_wheel_front_left/position', 'joint_wheel_front_left/velocity']
    assert len(names) == 8
    assert all(h.value == 0.0 for h in system.export_state_interfaces())
    assert all(math.isnan(h.value) for h in system.export_command_interfaces())


def test_velocity_command_tracks_and_nan_holds_zero():
    world, system = _system()
    system.command_handles['joint_wheel_front_left/velocity'].value = 3.0
    system.command_handles['joint_wheel_front_right/velocity'].value = 50.0  # clamped to 10
    for _ in range(200):  # 2 s, 100 Hz control, 1 kHz physics
        system.write(world.time, 0.01)
        world.step(10)
        system.read(world.time, 0.01)
    state = system.state_handles
    assert state['joint_wheel_front_left/velocity'].value == pytest.approx(3.0, abs=0.2)
    assert state['joint_wheel_front_left/position'].value > 4.0
    assert world.data.ctrl[world.model.actuator('amr/joint_wheel_front_right/velocity').id] \
        == 10.0
    for handle in system.export_command_interfaces():
        handle.value = math.nan
    for _ in range(200):
        system.write(world.time, 0.01)
        world.step(10)
        system.read(world.time, 0.01)
    assert all(c == 0.0 for c in world.data.ctrl)
    assert state['joint_wheel_front_left/velocity'].value == pytest.approx(0.0, abs=0.05)


def test_rebind_after_second_spawn():
    world, system = _system()
    world.spawn(urdf_to_spec(tutorial_urdf(), pose=(2, 0, 0.0, 0, 0, 0)), 'other')
    system.rebind(world.model, world.data)
    system.command_handles['joint_wheel_rear_left/velocity'].value = 1.0
    system.write(0.0, 0.0)
    assert world.data.ctrl[world.model.actuator('amr/joint_wheel_rear_left/velocity').id] == 1.0
    assert world.data.ctrl[world.model.actuator('other/joint_wheel_rear_left/velocity').id] \
        == 0.0


def test_missing_model_or_joint_is_one_line_error():
    info = parse_ros2_control(tutorial_urdf())[0]
    with pytest.raises(ValueError, match='needs the simulator'):
        MujocoSystem().on_init(info)
    world, _ = _system()
    with pytest.raises(ValueError, match="joint 'joint_wheel_front_left' is not in"):
        MujocoSystem(world.model, world.data, prefix='nope/').on_init(info)
