# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The MuJoCo world: dropped robot settles without bounce or creep; spawn/reset/ground truth."""

import math

from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.world import free_joint_ground_truth
from amr_description.sim.world import World
import mujoco
import numpy as np
import pytest
from sim_fixtures import tutorial_urdf

WHEEL_RADIUS = 0.1


def _spawn(world, name='amr', pose=(0.0, 0.0, 0.2, 0.0, 0.0, 0.0), extra=''):
    return world.spawn(urdf_to_spec(tutorial_urdf(extra=extra), name=name, pose=pose), name)


def test_world_options():
    world = World(physics_step=0.002)
    assert world.model.opt.timestep == 0.002
    assert world.model.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    np.testing.assert_allclose(world.model.opt.gravity, [0, 0, -9.81])
    with pytest.raises(ValueError):
        World(physics_step=0.0)


def test_drop_settles_without_bounce_or_creep():
    world = World()
    _spawn(world)
    z = []
    for _ in range(1000):  # 1 s
        world.step(1)
        z.append(world.ground_truth('amr')[0][2])
    touchdown = next(i for i, v in enumerate(z) if v < 0.01)
    rest = z[-1]
    # base_footprint lies on the ground (wheel centres at the wheel radius) within 2 mm
    assert abs(rest) < 0.002
    # no rebound of more than 1 cm above the rest height after touching down
    assert max(z[touchdown:]) - rest < 0.01
    start, _, _, _ = world.ground_truth('amr')
    world.step(10000)  # 10 s more at rest, no command
    end, quat, linear, angular = world.ground_truth('amr')
    assert np.linalg.norm(end[:2] - start[:2]) < 1e-3  # no creep
    assert abs(end[2] - rest) < 1e-3
    assert np.linalg.norm(linear) < 1e-3 and np.linalg.norm(angular) < 1e-3
    wheel_z = world.data.xpos[world.model.body('amr/wheel_front_left').id][2]
    assert wheel_z == pytest.approx(WHEEL_RADIUS, abs=0.002)


def test_spawn_keeps_state_and_prefixes_names():
    world = World()
    _spawn(world, 'a')
    world.step(500)
    qpos = world.data.qpos.copy()
    time = world.time
    _spawn(world, 'b', pose=(3.0, 0.0, 0.2, 0.0, 0.0, 0.0),
           extra="""<link name="arm"><inertial><mass value="1"/>
             <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>
           </link><joint name="arm_joint" type="revolute"><parent link="base_link"/>
           <child link="arm"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>""")
    assert world.time == time
    np.testing.assert_array_equal(world.data.qpos[:len(qpos)], qpos)
    assert world.model.nu == 8
    assert world.model.actuator('b/joint_wheel_front_left/velocity') is not None
    np.testing.assert_allclose(world.model.joint('b/arm_joint').range, [-1, 1])  # radians
    assert set(world.robots) == {'a', 'b'}
    with pytest.raises(ValueError, match='already exists'):
        _spawn(world, 'a')
    world.remove('b')
    assert world.model.nu == 4 and world.model.nbody == 8  # world, ground_plane, 6 links
    np.testing.assert_array_equal(world.data.qpos, qpos)


def test_reset_returns_to_spawn_pose():
    world = World()
    _spawn(world, pose=(1.0, -1.0, 0.2, 0.0, 0.0, 0.5))
    world.step(700)
    world.reset()
    assert world.time == 0.0
    position, quat, _, _ = world.ground_truth('amr')
    np.testing.assert_allclose(position, [1.0, -1.0, 0.2])
    np.testing.assert_allclose(quat, [0, 0, math.sin(0.25), math.cos(0.25)], atol=1e-12)


def test_ground_truth_twist_in_body_frame():
    yaw = math.pi / 2
    qpos = [1, 2, 3, math.cos(yaw / 2), 0, 0, math.sin(yaw / 2)]
    qvel = [0.0, 1.5, 0.0, 0.0, 0.0, 0.3]  # world +y while facing +y: forward in body
    position, quat, linear, angular = free_joint_ground_truth(qpos, qvel)
    np.testing.assert_allclose(position, [1, 2, 3])
    np.testing.assert_allclose(quat, [0, 0, math.sin(yaw / 2), math.cos(yaw / 2)])
    np.testing.assert_allclose(linear, [1.5, 0, 0], atol=1e-12)
    np.testing.assert_allclose(angular, [0, 0, 0.3])
