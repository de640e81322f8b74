# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
gz_ros2_control's command semantics and the link tags of sdformat, against closed forms.

A base resting on the ground carries an arm on a horizontal hinge (``shoulder``, axis y, 1 kg
at 0.2 m: gravity torque 1.962 N m when horizontal) and a light ``finger`` that mimics it.
As ``gz_system.cpp``: a claimed position command is a velocity target ``gain * (command - q)
* update_rate``, so the error decays by ``(1 - gain)`` per update; nothing claimed holds the
joint at velocity 0 (``hold_joints``) or leaves it free.
"""

from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.tags import ControlPlugin
from amr_description.core.gazebo.tags import gazebo_material
from amr_description.core.gazebo.tags import link_gravity
from amr_description.sim.mujoco_system import IDLE_GROUP
from amr_description.sim.mujoco_system import MujocoSystem
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.world import World
import pytest

UPDATE = 0.01  # s: 100 Hz controller manager, 1 kHz physics


def _inertial(mass, x=0.0):
    i = mass * 0.001
    return (f'<inertial><origin xyz="{x} 0 0"/><mass value="{mass}"/>'
            f'<inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial>')


def arm_urdf(arm_tags='', initial='', plugin='gz_ros2_control/GazeboSimSystem', finger_tags=''):
    """Return the test robot (see the module docstring)."""
    return f"""<robot name="arm_bot">
  <link name="base">{_inertial(20.0)}
    <collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision></link>
  <link name="arm">{_inertial(1.0, 0.2)}
    <visual><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.02 0.02"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material></visual></link>
  <link name="finger">{_inertial(0.01)}</link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/></joint>
  <joint name="knuckle" type="revolute"><parent link="arm"/><child link="finger"/>
    <origin xyz="0.4 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="5"/>
    <mimic joint="shoulder" multiplier="-1" offset="0.2"/></joint>
  <gazebo reference="arm">{arm_tags}</gazebo>
  <gazebo reference="finger">{finger_tags}</gazebo>
  <ros2_control name="GazeboSimSystem" type="system">
    <hardware><plugin>{plugin}</plugin></hardware>
    <joint name="shoulder">
      <command_interface name="position"/>
      <command_interface name="velocity"/>
      <command_interface name="effort"/>
      <state_interface name="position">{initial}</state_interface>
      <state_interface name="velocity"/>
      <state_interface name="effort"/>
    </joint>
  </ros2_control>
</robot>"""


def _robot(urdf=None, plugin=None):
    urdf = urdf or arm_urdf()
    description = RobotDescription(urdf, source='URDF')
    world = World()
    world.spawn(urdf_to_spec(description, name='arm_bot', pose=(0, 0, 0.05, 0, 0, 0)),
                'arm_bot', self_collide=description.self_collide_links())
    system = MujocoSystem(world.model, world.data, prefix='arm_bot/',
                          gazebo=ControlPlugin() if plugin is None else plugin)
    assert system.on_init(description.hardware[0])
    return world, system


def _run(world, system, seconds):
    for _ in range(int(round(seconds / UPDATE))):
        system.read(world.time, UPDATE)
        system.write(world.time, UPDATE)
        world.step(10)
    system.read(world.time, UPDATE)


def _q(system, name='shoulder'):
    return system.state_handles[f'{name}/position'].value


def _angle(world, joint):
    return float(world.data.qpos[world.model.joint(f'arm_bot/{joint}').qposadr[0]])


def test_nothing_claimed_holds_the_joint_against_gravity_and_hold_joints_false_frees_it():
    world, system = _robot()
    _run(world, system, 1.0)
    held = _q(system)
    assert abs(held) < 0.05  # the PI velocity servo's sag while it takes up 1.96 N m
    _run(world, system, 1.0)
    assert _q(system) == pytest.approx(held, abs=1e-3)  # then held at velocity 0
    world, system = _robot(plugin=ControlPlugin(hold_joints=False))
    _run(world, system, 1.0)
    assert _q(system) > 0.5  # swings down (+y rotation takes +x towards -z)
    forces = world.data.actuator_force
    assert all(forces[a] == 0.0 for a in range(world.model.nu))  # every actuator switched off


def test_a_claimed_position_is_a_proportional_velocity_target():
    world, system = _robot()
    system.perform_command_mode_switch(['shoulder/position'], [])
    system.command_handles['shoulder/position'].value = 0.5
    _run(world, system, 0.1)
    # gz: target velocity 0.1 * error * 100 Hz: the error decays as 0.9 per update
    # (0.9^10 = 0.349 after 0.1 s), slowed a little by the servo's own lag
    assert 0.30 < (0.5 - _q(system)) / 0.5 < 0.48
    _run(world, system, 1.4)
    assert _q(system) == pytest.approx(0.5, abs=0.005)
    # the mimic joint: offset + multiplier * leader
    assert _angle(world, 'knuckle') == pytest.approx(0.2 - _q(system), abs=1e-3)
    # only the position servo acts; the velocity and effort actuators are switched off
    groups = world.model.actuator_group
    used = world.model.actuator('arm_bot/shoulder/position').id
    assert groups[used] == 0
    assert groups[world.model.actuator('arm_bot/shoulder/effort').id] == IDLE_GROUP
    assert world.model.opt.disableactuator & (1 << IDLE_GROUP)


def test_claimed_velocity_and_effort_and_release():
    world, system = _robot()
    system.perform_command_mode_switch(['shoulder/velocity'], [])
    system.command_handles['shoulder/velocity'].value = -1.0
    _run(world, system, 0.5)
    assert system.state_handles['shoulder/velocity'].value == pytest.approx(-1.0, abs=0.05)
    system.perform_command_mode_switch(['shoulder/effort'], ['shoulder/velocity'])
    system.command_handles['shoulder/effort'].value = 3.0
    _run(world, system, 0.02)
    motor = world.model.actuator('arm_bot/shoulder/effort').id
    assert world.data.actuator_force[motor] == pytest.approx(3.0)
    servo = world.model.actuator('arm_bot/shoulder/velocity').id
    assert world.data.actuator_force[servo] == 0.0
    # released: held at velocity 0 again
    system.perform_command_mode_switch([], ['shoulder/effort'])
    _run(world, system, 0.5)
    before = _q(system)
    _run(world, system, 0.5)
    assert abs(_q(system) - before) < 0.01


def test_initial_value_starts_the_joint_there_and_reset_returns_to_it():
    description = RobotDescription(
        arm_urdf(initial='<param name="initial_value">0.7</param>'), source='URDF')
    assert description.initial_joint_states() == [('shoulder', 0.7, None)]
    world, _ = _robot()
    world.set_initial_joint_state('arm_bot/shoulder', 0.7, -0.2)
    assert _angle(world, 'shoulder') == 0.7
    world.step(5)
    world.reset()
    assert _angle(world, 'shoulder') == 0.7
    assert world.data.qvel[world.model.joint('arm_bot/shoulder').dofadr[0]] == -0.2
    with pytest.raises(ValueError, match="'arm_bot/nope' is not in the simulated world"):
        world.set_initial_joint_state('arm_bot/nope', 0.1)


def test_gravity_off_on_a_link_cancels_its_weight():
    for tags in ('<turnGravityOff>true</turnGravityOff>', '<gravity value="false"/>'):
        world, system = _robot(arm_urdf(arm_tags=tags, finger_tags=tags),
                               plugin=ControlPlugin(hold_joints=False))
        _run(world, system, 1.0)
        assert abs(_q(system)) < 1e-3, tags  # no torque on the free arm
    world, system = _robot(arm_urdf(arm_tags=tags), plugin=ControlPlugin(hold_joints=False))
    _run(world, system, 1.0)
    assert _q(system) > 0.1  # the finger alone (10 g at 0.4 m) still pulls it down
    assert link_gravity({'gravity': 'true'}, '') and link_gravity({}, '')
    with pytest.raises(ValueError, match=r'<gazebo reference="arm"><turnGravityOff>: '
                                         r"expected true or false, found 'maybe'"):
        RobotDescription(arm_urdf(arm_tags='<turnGravityOff>maybe</turnGravityOff>'))


def test_gazebo_material_colours_the_links_visuals_in_the_simulator():
    description = RobotDescription(arm_urdf(arm_tags='<material>Gazebo/Orange</material>'))
    spec = urdf_to_spec(description, name='arm_bot')
    model = spec.compile()
    rgba = model.geom('arm/visual_0').rgba
    assert list(rgba) == pytest.approx([1.0, 0.5088, 0.0468, 1.0])
    rgba, line = gazebo_material({'material': 'Gazebo/WoodFloor'}, '<gazebo reference="a">')
    assert rgba is None and line == ("<gazebo reference=\"a\"><material>: 'Gazebo/WoodFloor' "
                                     'is not a solid Gazebo material: the URDF colour is used')
    description = RobotDescription(arm_urdf(arm_tags='<material>Gazebo/WoodFloor</material>'))
    assert description.messages and 'Gazebo/WoodFloor' in description.messages[0]
    model = urdf_to_spec(description, name='arm_bot').compile()
    assert list(model.geom('arm/visual_0').rgba) == [0.0, 0.0, 1.0, 1.0]  # the URDF's blue
