# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""URDF -> MuJoCo conversion keeps masses, inertias, axes, joint types and actuators."""

import math
import os

from amr_description.core.description.mujoco_block import parse_mujoco_block
from amr_description.sim.urdf_to_mjcf import rpy_to_quat
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
import mujoco
import numpy as np
import pytest
from sim_fixtures import AMR_URDF
from sim_fixtures import tutorial_urdf
from sim_fixtures import WHEELS


def _compile(urdf, **kwargs):
    model = urdf_to_spec(urdf, **kwargs).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


def _body_inertia_in_body_frame(model, name):
    """Return the 3x3 inertia tensor of a body about its COM, in the body frame."""
    body = model.body(name)
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, body.iquat)
    rot = rot.reshape(3, 3)
    return rot @ np.diag(body.inertia) @ rot.T


def test_tutorial_masses_and_total():
    model, _ = _compile(tutorial_urdf())
    assert model.body('base_footprint').mass[0] == 0.0
    assert model.body('base_link').mass[0] == pytest.approx(5.0)
    for wheel in WHEELS:
        assert model.body(f'wheel_{wheel}').mass[0] == pytest.approx(0.5)
    assert model.body('base_footprint').subtreemass[0] == pytest.approx(7.0)


def test_tutorial_inertia_diagonal_preserved():
    model, _ = _compile(tutorial_urdf())
    np.testing.assert_allclose(_body_inertia_in_body_frame(model, 'base_link'),
                               np.diag([0.041667, 0.108333, 0.141667]), atol=1e-9)
    np.testing.assert_allclose(_body_inertia_in_body_frame(model, 'wheel_rear_left'),
                               np.diag([0.0013167, 0.0013167, 0.0025]), atol=1e-9)


def test_joint_types_axes_and_root_free_joint():
    model, data = _compile(tutorial_urdf(), pose=(1.0, 2.0, 0.2, 0.0, 0.0, math.pi / 2))
    assert model.njnt == 5
    assert model.jnt_type[model.joint('base_footprint').id] == mujoco.mjtJoint.mjJNT_FREE
    np.testing.assert_allclose(data.qpos[:3], [1.0, 2.0, 0.2])
    np.testing.assert_allclose(data.qpos[3:7], rpy_to_quat(0, 0, math.pi / 2), atol=1e-12)
    for wheel, (x, y) in WHEELS.items():
        joint = model.joint(f'joint_wheel_{wheel}')
        assert joint.type[0] == mujoco.mjtJoint.mjJNT_HINGE
        assert joint.limited[0] == 0
        np.testing.assert_allclose(joint.axis, [0, 0, 1])
        # axle along -y of base_link (rpy 1.5708 about x), world frame rotated by yaw 90 deg
        world_axis = data.xaxis[joint.id]
        np.testing.assert_allclose(world_axis, [1, 0, 0], atol=1e-4)
        # wheel centre at (x, y, 0.1) in base_footprint: world = (1 - y, 2 + x, 0.3)
        np.testing.assert_allclose(data.xpos[model.body(f'wheel_{wheel}').id],
                                   [1.0 - y, 2.0 + x, 0.3], atol=1e-9)
    assert model.opt.timestep > 0


def test_off_diagonal_inertia_origin_and_other_joint_types():
    extra = """
  <link name="arm">
    <inertial><origin xyz="0.1 0.02 -0.03" rpy="0.3 -0.2 0.5"/><mass value="1.25"/>
      <inertia ixx="0.02" ixy="0.001" ixz="-0.002" iyy="0.03" iyz="0.0015" izz="0.04"/>
    </inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/><limit lower="-1.0" upper="2.0" effort="5" velocity="1"/>
    <dynamics damping="0.3" friction="0.1"/>
  </joint>
  <link name="slider"><inertial><mass value="0.25"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="slider_joint" type="prismatic">
    <parent link="arm"/><child link="slider"/><axis xyz="0 0 2"/>
    <limit lower="0" upper="0.3" effort="5" velocity="1"/>
  </joint>"""
    model, _ = _compile(tutorial_urdf(extra=extra))
    assert model.body('base_footprint').subtreemass[0] == pytest.approx(8.5)
    arm = model.body('arm')
    assert arm.mass[0] == pytest.approx(1.25)
    np.testing.assert_allclose(arm.ipos, [0.1, 0.02, -0.03], atol=1e-12)
    tensor = np.array([[0.02, 0.001, -0.002], [0.001, 0.03, 0.0015], [-0.002, 0.0015, 0.04]])
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, rpy_to_quat(0.3, -0.2, 0.5))
    rot = rot.reshape(3, 3)
    np.testing.assert_allclose(_body_inertia_in_body_frame(model, 'arm'),
                               rot @ tensor @ rot.T, atol=1e-10)
    hinge = model.joint('arm_joint')
    assert hinge.type[0] == mujoco.mjtJoint.mjJNT_HINGE
    assert hinge.limited[0] == 1
    np.testing.assert_allclose(hinge.range, [-1.0, 2.0])
    np.testing.assert_allclose(hinge.axis, [0, 1, 0])
    assert hinge.damping[0] == pytest.approx(0.3)
    assert hinge.frictionloss[0] == pytest.approx(0.1)
    slide = model.joint('slider_joint')
    assert slide.type[0] == mujoco.mjtJoint.mjJNT_SLIDE
    np.testing.assert_allclose(slide.axis, [0, 0, 1])
    np.testing.assert_allclose(slide.range, [0.0, 0.3])


def test_geoms_visual_and_collision():
    model, _ = _compile(tutorial_urdf())
    box = model.geom('base_link/collision_0')
    assert box.type[0] == mujoco.mjtGeom.mjGEOM_BOX
    np.testing.assert_allclose(box.size, [0.25, 0.15, 0.05])
    assert box.contype[0] == 1 and box.conaffinity[0] == 1
    np.testing.assert_allclose(box.friction, [1.0, 0.005, 0.0001])
    wheel = model.geom('wheel_front_left/collision_0')
    assert wheel.type[0] == mujoco.mjtGeom.mjGEOM_CYLINDER
    np.testing.assert_allclose(wheel.size[:2], [0.1, 0.02])
    visual = model.geom('wheel_front_left/visual_0')
    assert visual.contype[0] == 0 and visual.conaffinity[0] == 0 and visual.group[0] == 2
    np.testing.assert_allclose(visual.rgba, [0.1, 0.1, 0.1, 1.0])  # robot-level material
    np.testing.assert_allclose(model.geom('base_link/visual_0').rgba, [0, 0, 0.8, 1])


def test_velocity_actuators_from_ros2_control_and_mujoco_block():
    extra = """
  <mujoco><actuator joint="joint_wheel_rear_right" kv="7.5" forcerange="-3 4"/>
    <link name="wheel_rear_right" friction="0.4"/></mujoco>"""
    model, _ = _compile(tutorial_urdf(extra=extra))
    assert model.nu == 4
    for wheel in WHEELS:
        actuator = model.actuator(f'joint_wheel_{wheel}/velocity')
        assert actuator.trnid[0] == model.joint(f'joint_wheel_{wheel}').id
        np.testing.assert_allclose(actuator.ctrlrange, [-10, 10])
    front = model.actuator('joint_wheel_front_left/velocity')
    assert front.gainprm[0] == pytest.approx(5.0) and front.biasprm[2] == pytest.approx(-5.0)
    np.testing.assert_allclose(front.forcerange, [-20, 20])
    rear = model.actuator('joint_wheel_rear_right/velocity')
    assert rear.gainprm[0] == pytest.approx(7.5)
    np.testing.assert_allclose(rear.forcerange, [-3, 4])
    np.testing.assert_allclose(model.geom('wheel_rear_right/collision_0').friction,
                               [0.4, 0.005, 0.0001])


@pytest.mark.parametrize('urdf, message', [
    ('<robot name="x"><link name="a"/>', 'not well-formed'),
    ('<robt name="x"/>', 'root element must be <robot>'),
    (tutorial_urdf().replace('<child link="wheel_rear_left"/>', '<child link="nope"/>'),
     "'nope' does not exist"),
    (tutorial_urdf().replace('<joint name="joint_wheel_rear_left">',
                             '<joint name="joint_missing">'), "'joint_missing' is not in"),
    (tutorial_urdf(extra='<mujoco><contact friction="a b"/></mujoco>'), 'must be numbers'),
])
def test_bad_input_one_line_value_error(urdf, message):
    with pytest.raises(ValueError) as info:
        urdf_to_spec(urdf)
    assert message in str(info.value)
    assert '\n' not in str(info.value)


def test_mujoco_block_defaults():
    import xml.etree.ElementTree as ET
    config = parse_mujoco_block(ET.fromstring('<robot name="r"/>'))
    assert config.parameters is None
    assert config.actuator['kv'] == 5.0
    config = parse_mujoco_block(ET.fromstring(tutorial_urdf()))
    assert config.parameters == 'package://amr_description/config/controllers.yaml'


@pytest.mark.skipif(not os.path.isfile(AMR_URDF), reason='urdf/amr.urdf not written yet')
def test_package_urdf_total_mass_7kg():
    with open(AMR_URDF) as f:
        model, _ = _compile(f.read())
    assert model.body(1).subtreemass[0] == pytest.approx(7.0)
    assert model.nu == 8  # PI wheel drives: <joint>/velocity and <joint>/velocity/integral


def test_wheel_contact_shape_friction_reference_and_pi_drive():
    extra = """<mujoco><link name="wheel_front_left" shape="ellipsoid" solreffriction="1 1"/>
      <actuator joint="joint_wheel_front_left" kv="5" ki="100" armature="0.05"
                forcerange="-3 4"/></mujoco>"""
    spec = urdf_to_spec(tutorial_urdf(extra=extra))
    assert [t.name for t in spec.texts] == ['ground_contact/wheel_front_left/collision_0']
    assert spec.texts[0].data == 'solreffriction 1.0 1.0'
    model = spec.compile()
    left = model.geom('wheel_front_left/collision_0')
    assert left.type[0] == mujoco.mjtGeom.mjGEOM_ELLIPSOID
    np.testing.assert_allclose(left.size, [0.1, 0.1, 0.02])  # radius, radius, half width
    assert model.geom('wheel_front_left/visual_0').type[0] == mujoco.mjtGeom.mjGEOM_CYLINDER
    assert model.geom('wheel_front_right/collision_0').type[0] == \
        mujoco.mjtGeom.mjGEOM_CYLINDER
    joint = model.joint('joint_wheel_front_left')
    assert joint.armature[0] == 0.05 and model.joint('joint_wheel_front_right').armature[0] == 0
    np.testing.assert_allclose(model.jnt_actfrcrange[joint.id], [-3, 4])
    assert model.jnt_actfrclimited[joint.id]
    p = model.actuator('joint_wheel_front_left/velocity')
    i = model.actuator('joint_wheel_front_left/velocity/integral')
    assert p.gainprm[0] == 5.0 and p.biasprm[2] == -5.0 and not p.forcelimited[0]
    assert i.dyntype[0] == mujoco.mjtDyn.mjDYN_INTEGRATOR and i.gainprm[0] == 100.0
    assert i.biasprm[1] == -100.0 and i.biasprm[2] == 0.0 and not i.actlimited[0]
    assert model.nu == 5
    with pytest.raises(ValueError, match='shape must be one of urdf, sphere, ellipsoid'):
        urdf_to_spec(tutorial_urdf(extra='<mujoco><link name="base_link" shape="box"/>'
                                         '</mujoco>'))


@pytest.mark.parametrize('shape, gap, touches', [
    # the wheel's outer face is at y 0.15 + 0.02 (urdf/amr.urdf: axle at y 0.15, 0.04 wide)
    ('ellipsoid', 0.005, False), ('ellipsoid', -0.005, True),
    ('urdf', 0.005, False), ('urdf', -0.005, True),
    # a sphere of the wheel's radius reaches 0.1 - 0.02 m beyond that face
    ('sphere', 0.07, True), ('sphere', 0.085, False)])
def test_a_round_wheel_is_as_wide_as_its_cylinder(shape, gap, touches):
    extra = f'<mujoco><link name="wheel_front_left" shape="{shape}"/></mujoco>'
    spec = urdf_to_spec(tutorial_urdf(extra=extra), pose=(0, 0, 0.5, 0, 0, 0))
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    wheel = data.xpos[model.body('wheel_front_left').id]
    wall = spec.worldbody.add_geom(name='wall', type=mujoco.mjtGeom.mjGEOM_BOX,
                                   size=[0.5, 0.05, 0.5])
    wall.pos = [wheel[0], wheel[1] + 0.02 + gap + 0.05, wheel[2]]
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    wall_id = model.geom('wall').id
    touching = {int(model.geom_bodyid[g]) for c in data.contact[:data.ncon]
                for g in (c.geom1, c.geom2) if wall_id in (c.geom1, c.geom2) and g != wall_id}
    assert (model.body('wheel_front_left').id in touching) == touches


def test_pose_as_quaternion_matches_rpy():
    half = math.pi / 8
    _, by_quat = _compile(tutorial_urdf(), pose=(1, 2, 3, 0, 0, 2 * math.sin(half),
                                                 2 * math.cos(half)))  # normalised here
    _, by_rpy = _compile(tutorial_urdf(), pose=(1, 2, 3, 0, 0, math.pi / 4))
    np.testing.assert_allclose(by_quat.qpos[:7], by_rpy.qpos[:7], atol=1e-12)
    with pytest.raises(ValueError, match='finite numbers'):
        urdf_to_spec(tutorial_urdf(), pose=(0, 0, 0, 0, 0))
    with pytest.raises(ValueError, match='non-zero'):
        urdf_to_spec(tutorial_urdf(), pose=(0, 0, 0, 0, 0, 0, 0))
