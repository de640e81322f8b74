# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""URDF documents shared by the simulation unit tests (the tutorial robot, self-contained)."""

import os

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
AMR_URDF = os.path.join(REPO, 'urdf', 'amr.urdf')

WHEELS = {
    'front_left': (0.2, 0.15), 'front_right': (0.2, -0.15),
    'rear_left': (-0.2, 0.15), 'rear_right': (-0.2, -0.15),
}


def _wheel(name, x, y):
    return f"""
  <link name="wheel_{name}">
    <visual><geometry><cylinder radius="0.1" length="0.04"/></geometry>
      <material name="black"/></visual>
    <collision>
      <geometry><cylinder radius="0.1" length="0.04"/></geometry></collision>
    <inertial><mass value="0.5"/>
      <inertia ixx="0.0013167" ixy="0" ixz="0" iyy="0.0013167" iyz="0" izz="0.0025"/>
    </inertial>
  </link>
  <joint name="joint_wheel_{name}" type="continuous">
    <parent link="base_link"/><child link="wheel_{name}"/>
    <origin xyz="{x} {y} -0.05" rpy="1.5708 0 0"/><axis xyz="0 0 1"/>
  </joint>"""


def _rc_joint(name):
    return f"""
    <joint name="joint_wheel_{name}">
      <command_interface name="velocity"><param name="min">-10</param>
        <param name="max">10</param></command_interface>
      <state_interface name="position"/><state_interface name="velocity"/>
    </joint>"""


def tutorial_urdf(plugin='amr_description/MujocoSystem', extra=''):
    """
    Return the tutorial skid-steer robot (7 kg) as a URDF string.

    ``base_footprint`` sits on the ground: wheel centres at z 0.1 (the wheel radius).

    :param plugin: the ``<hardware><plugin>`` string.
    :param extra: XML appended inside ``<robot>``.
    """
    wheels = ''.join(_wheel(n, x, y) for n, (x, y) in WHEELS.items())
    rc = ''.join(_rc_joint(n) for n in WHEELS)
    return f"""<?xml version="1.0"?>
<robot name="amr">
  <material name="black"><color rgba="0.1 0.1 0.1 1"/></material>
  <link name="base_footprint"/>
  <link name="base_link">
    <visual><geometry><box size="0.5 0.3 0.1"/></geometry>
      <material name="blue"><color rgba="0 0 0.8 1"/></material></visual>
    <collision><geometry><box size="0.5 0.3 0.1"/></geometry></collision>
    <inertial><mass value="5.0"/>
      <inertia ixx="0.041667" ixy="0" ixz="0" iyy="0.108333" iyz="0" izz="0.141667"/>
    </inertial>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.15"/>
  </joint>{wheels}
  <ros2_control name="AmrSystem" type="system">
    <hardware><plugin>{plugin}</plugin></hardware>{rc}
  </ros2_control>
  <mujoco>
    <ros2_control parameters="package://amr_description/config/controllers.yaml"/>
    <contact friction="1.0 0.005 0.0001"/>
    <actuator kv="5.0" forcerange="-20 20"/>
  </mujoco>{extra}
</robot>
"""


class ListLog:
    """A logger-like object (``info``, ``warning``, ``error``, ``debug``) keeping its lines."""

    def __init__(self):
        """Start with no line."""
        self.lines = []

    def warning(self, text):
        """Keep one line (every level does)."""
        self.lines.append(text)

    info = error = debug = warning


PROBE_BASE = """<link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <inertial><mass value="1.0"/>
      <inertia ixx="0.00667" iyy="0.00667" izz="0.00667" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>"""
"""The sensor tests' probe: a 1 kg, 0.2 m box link (its centre 0.1 m up when spawned at 0.1)."""
