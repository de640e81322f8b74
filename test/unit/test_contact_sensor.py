# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The contact sensor (a bumper) against closed forms.

A 1 kg box probe resting on the ground presses on it with its weight: the forces on the probe
at its contact points add up to m g = 9.81 N up, the normals point down (from the probe to the
ground). Pushed into the loose box of test/data/worlds/contact_box.sdf, the sensor names that
box's collision (``loose_box::link::collision``).
"""

import os

from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.gazebo.sensors import collision_names
from amr_description.sim.simulation import Simulation
import numpy as np
import pytest
from sim_fixtures import ListLog as _Log  # noqa: I100 - the unit tests' helpers

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD = os.path.join(os.path.dirname(HERE), 'data', 'worlds', 'contact_box.sdf')


def _robot(collision='base_link_collision'):
    return f"""<robot name="probe">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <collision name="top"><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.05"/>
      </geometry></collision>
    <inertial><mass value="1.0"/>
      <inertia ixx="0.00667" iyy="0.00667" izz="0.00667" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="bumper_link">
    <collision><geometry><box size="0.01 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="bumper_joint" type="fixed"><parent link="base_link"/>
    <child link="bumper_link"/><origin xyz="0.2 0 0"/></joint>
  <gazebo reference="base_link">
    <sensor name="bumper" type="contact"><update_rate>50</update_rate>
      <contact><collision>{collision}</collision></contact><topic>bumper</topic></sensor>
    <sensor name="imu" type="imu"><update_rate>100</update_rate></sensor>
  </gazebo>
</robot>"""


def _spawn(collision='base_link_collision'):
    sim = Simulation(physics_step=0.001, real_time_factor=0.0, logger=_Log(),
                     sensor_settings={'publish_ground_truth': False}, world=read_world(WORLD))
    entity = sim.spawn(_robot(collision), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    return sim, {s.name: s for s in entity.sensors}


def test_sdf_collision_names_of_a_urdf_as_sdformat_converts_them():
    names = collision_names(RobotDescription(_robot()).model, {})
    assert names['base_link_collision'] == ('base_link', 0)
    assert names['base_link_collision_1'] == ('base_link', 1)
    assert names['top'] == ('base_link', 1)
    assert names['bumper_link_collision'] == ('bumper_link', 0)
    assert names['base_link_fixed_joint_lump__bumper_link_collision'] == ('bumper_link', 0)


def test_resting_on_the_ground_the_forces_add_up_to_the_weight_and_the_normals_point_down():
    sim, sensors = _spawn()
    while sim.step_count < 500:
        sim.run_cycle()
    msg = sensors['bumper'].measure(sim.world, 0.5)
    assert (msg.header.frame_id, sensors['bumper'].topic) == ('', '/bumper')  # world frame
    (contact,) = msg.contacts
    assert contact.collision1.name == 'probe::base_link::base_link_collision'
    assert contact.collision2.name == 'ground_plane::link::collision'
    assert contact.collision1.type == contact.collision2.type == 5  # COLLISION
    assert len(contact.positions) == len(contact.normals) == len(contact.depths) == \
        len(contact.wrenches) >= 3
    force = sum(np.array([w.body_1_wrench.force.x, w.body_1_wrench.force.y,
                          w.body_1_wrench.force.z]) for w in contact.wrenches)
    assert force == pytest.approx([0.0, 0.0, 9.81], abs=0.02)
    assert all(n.z == pytest.approx(-1.0, abs=1e-6) for n in contact.normals)
    assert all(abs(p.z) < 2e-3 for p in contact.positions)  # on the ground plane
    assert all(0.0 <= d < 2e-3 for d in contact.depths)
    sim.close()


def test_pushed_into_the_loose_box_the_bumper_names_its_collision():
    sim, sensors = _spawn('base_link_fixed_joint_lump__bumper_link_collision')
    model, data = sim.world.model, sim.world.data
    dof = model.jnt_dofadr[model.body('probe/base_link').jntadr[0]]  # the probe's free joint
    touched = set()
    while sim.step_count < 3000:
        data.qvel[dof] = 0.2  # driven along +x into the box
        sim.run_cycle()
        msg = sensors['bumper'].measure(sim.world, sim.step_count * 0.001)
        touched |= {c.collision2.name for c in msg.contacts}
    assert 'loose_box::link::collision' in touched, touched
    assert data.body('loose_box::link').xpos[0] > 0.65  # pushed along from x = 0.6
    sim.close()


def test_a_collision_the_link_does_not_have_is_one_line_and_the_sensor_is_skipped():
    sim, sensors = _spawn('wheel_collision')
    assert sorted(sensors) == ['imu']
    (line,) = [text for text in sim.logger.lines if "sensor 'bumper'" in text]
    assert line == ("entity 'probe': sensor 'bumper': <contact><collision> 'wheel_collision' "
                    "is not a collision of link 'base_link' (its collisions: "
                    'base_link_collision, base_link_collision_1, '
                    'base_link_fixed_joint_lump__bumper_link_collision, bumper_link_collision, '
                    'top); the sensor is skipped')
    sim.close()
