# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Coulomb wheel friction: the request in the URDF, the frictionless pairs, C against numpy."""

import os
import xml.etree.ElementTree as ET

from amr_description.core.description.mujoco_block import parse_mujoco_block
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.wheel_friction import CoulombWheels
from amr_description.sim.wheel_friction import library_path
from amr_description.sim.world import World
from amr_description.tools.physics_report import Bench
import numpy as np
import pytest
from sim_fixtures import AMR_URDF
from sim_fixtures import tutorial_urdf


def _amr():
    with open(AMR_URDF) as f:
        return f.read()


def test_the_request_and_its_bad_values():
    root = ET.fromstring('<robot><mujoco><link name="w" ground_friction="coulomb"/></mujoco>'
                         '</robot>')
    assert parse_mujoco_block(root).link_contact['w'] == {'ground_friction': 'coulomb'}
    root = ET.fromstring('<robot><mujoco><link name="w" ground_friction="ode"/></mujoco>'
                         '</robot>')
    with pytest.raises(ValueError, match='ground_friction must be one of mujoco, coulomb, '
                                         "found 'ode'"):
        parse_mujoco_block(root)


def test_coulomb_pairs_are_frictionless_in_mujoco_and_flagged():
    bench = Bench(_amr())
    model, wheels = bench.world.model, bench.world.wheels
    names = [model.pair(p).name for p in range(model.npair)]
    assert sorted(names) == sorted(f'amr/ground_pair/wheel_{n}/collision_0'
                                   for n in ('front_left', 'front_right', 'back_left',
                                             'back_right'))
    assert list(model.pair_dim) == [1, 1, 1, 1]  # the normal force only
    assert list(model.pair_friction[:, 0]) == [1.0] * 4  # mu kept for the friction law
    assert list(wheels.flags) == [1, 1, 1, 1] and wheels.active
    # a wheel with MuJoCo's friction (solreffriction) is not flagged
    extra = '<mujoco><link name="wheel_front_left" solreffriction="1 1"/></mujoco>'
    world = World()
    world.spawn(urdf_to_spec(tutorial_urdf(extra=extra)), 'plain')
    assert list(world.model.pair_dim) == [3] and not world.wheels.active
    world.spawn(urdf_to_spec(_amr()), 'amr')
    assert list(world.wheels.flags) == [0, 1, 1, 1, 1]
    world.remove('amr')
    assert world.model.npair == 1 and not world._coulomb_pairs and not world.wheels.active


def test_setup_built_the_c_loop():
    assert os.path.exists(library_path()), 'scripts/setup builds the wheel friction loop'
    assert Bench(_amr()).world.wheels.function is not None


def test_numpy_and_c_give_the_same_motion():
    def arc(library):
        bench = Bench(_amr())
        bench.world.wheels = CoulombWheels(library=library)
        bench.world.wheels.configure(bench.world.model, bench.world._coulomb_pairs)
        bench.command(2.0, 6.0)
        bench.run(0.3)
        return bench.world.data.qpos[:7].copy()

    c, python = arc(None), arc(False)
    assert np.linalg.norm(c[:2]) > 0.05  # it moved
    np.testing.assert_allclose(c, python, atol=1e-9)


def test_a_reset_forgets_the_normal_forces():
    bench = Bench(_amr())
    bench.command(1.0, 1.0)
    bench.run(0.1)
    wheels = bench.world.wheels
    assert (wheels.normal > 10.0).all()  # about a quarter of 7 kg each
    bench.world.reset()
    assert not wheels.normal.any()
