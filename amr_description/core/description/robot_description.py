# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A robot description parsed once: what every consumer of one spawn reads.

The simulator parses the URDF of a spawned robot once into a :class:`RobotDescription` and
hands it to the URDF -> MJCF converter, the resource manager and joint_state_broadcaster, so
one spawn is one XML parse (test/unit/test_robot_description.py counts them).
"""

from amr_description.core.description.mujoco_block import add_drive_defaults
from amr_description.core.description.mujoco_block import parse_mujoco_block
from amr_description.core.description.ros2_control_info import driven_joints
from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.description.urdf_model import model_from_element
from amr_description.core.description.urdf_model import parse_xml
from amr_description.core.gazebo.sensors import parse_sensors
from amr_description.core.gazebo.systems import parse_gazebo_systems
from amr_description.core.gazebo.tags import apply_surface_tags
from amr_description.core.gazebo.tags import gazebo_material
from amr_description.core.gazebo.tags import GAZEBO_SYSTEMS
from amr_description.core.gazebo.tags import link_gravity
from amr_description.core.gazebo.tags import parse_control_plugin
from amr_description.core.gazebo.tags import parse_reference_tags
from amr_description.core.gazebo.tags import SIMULATOR_SYSTEMS
from amr_description.core.gazebo.tags import text_bool


class RobotDescription:
    """
    A URDF document with its parsed parts.

    :param xml: the URDF text (str or bytes).
    :param source: what error messages name (a file path or parameter name).
    :ivar xml: the URDF text (str), as given to controllers (``robot_description``).
    :ivar root: the lxml ``<robot>`` element (comments removed).
    :ivar name: the ``<robot name>``.
    :ivar model: the kinematic :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :ivar hardware: the ``<ros2_control>`` blocks, list of
        :class:`~amr_description.core.description.ros2_control_info.HardwareInfo`.
    :ivar mujoco: the simulator settings, :class:`~amr_description.core.description.mujoco_block.
        MujocoConfig`.
    :ivar control_plugin: gz_ros2_control's ``<gazebo><plugin>``, a
        :class:`~amr_description.core.gazebo.tags.ControlPlugin`, or None.
    :ivar gz_systems: the gz-sim system plugins, a
        :class:`~amr_description.core.gazebo.systems.GazeboSystems`.
    :ivar gazebo_tags: the ``<gazebo reference>`` tags, dict reference -> dict tag -> value.
    :ivar sensors: the ``<gazebo reference><sensor>`` blocks, a
        :class:`~amr_description.core.gazebo.sensors.SensorBlocks` (its ``messages`` name the
        sensors left out).
    :ivar link_colours: dict link -> rgba (4 floats) of its ``<gazebo reference><material>``
        (``Gazebo/*``, :data:`~amr_description.core.gazebo.tags.GAZEBO_MATERIALS`): the
        colour of all its visuals in the simulator, as gz-sim.
    :ivar weightless_links: links whose ``<gazebo reference>`` turns gravity off (a set).
    :ivar messages: lines about Gazebo tags read but not applied (an unknown material) and
        driven wheels without ``<collision>`` (spawned anyway, as Gazebo does).
    :ivar system_hardware: the joints those systems command, as ``HardwareInfo`` blocks of
        the simulator's system (their actuators are made as for ``<ros2_control>``).
    :raises ValueError: one line naming ``source`` (URDF), ``ros2_control`` or ``<mujoco>``
        and the element at fault.
    """

    def __init__(self, xml, source='robot_description'):
        """Parse ``xml`` once and read every part (see the class docstring)."""
        self.xml = xml.decode('utf-8', errors='replace') if isinstance(xml, bytes) else xml
        self.root = parse_xml(xml, source)
        self.name = self.root.get('name')
        self.model = model_from_element(self.root, source)
        self.hardware = parse_ros2_control(self.root)
        self.mujoco = parse_mujoco_block(self.root)
        self.control_plugin = parse_control_plugin(self.root)
        self.gz_systems = parse_gazebo_systems(self.root, self.joint_names(moving_only=True))
        self.system_hardware = self.gz_systems.hardware()
        _check_one_command_source(self.hardware, self.system_hardware)
        add_drive_defaults(self.mujoco, self.model, self.hardware + self.system_hardware,
                           SIMULATOR_SYSTEMS, GAZEBO_SYSTEMS)
        self.gazebo_tags = parse_reference_tags(self.root)
        apply_surface_tags(self.mujoco, self.gazebo_tags, self.model)
        self.sensors = parse_sensors(self.root, self.model.links)
        self.link_colours, self.weightless_links, self.messages = {}, set(), []
        for reference, tags in self.gazebo_tags.items():
            if reference not in self.model.links:
                continue
            where = f'<gazebo reference="{reference}">'
            rgba, line = gazebo_material(tags, where)
            if rgba is not None:
                self.link_colours[reference] = rgba
            elif line:
                self.messages.append(line)
            if not link_gravity(tags, where):
                self.weightless_links.add(reference)
        for joint, why in driven_joints(self.model, self.hardware + self.system_hardware).items():
            link = self.model.joints[joint].child
            if not self.model.links[link].collisions:  # spawned anyway, as Gazebo does
                self.messages.append(f'link {link!r}: no <collision> on the link driven by '
                                     f'joint {joint!r} ({why}): it cannot touch the ground')

    def parameters_files(self):
        """
        Return the controllers YAML files this description names, in order (URIs as written).

        ``<mujoco><ros2_control parameters>`` when given, else gz_ros2_control's
        ``<parameters>`` (every one, a later file overriding an earlier one); [] for none.
        """
        if self.mujoco.parameters:
            return [self.mujoco.parameters]
        return list(self.control_plugin.parameters) if self.control_plugin else []

    def self_collide_links(self):
        """
        Return the links that collide with the robot's other links (a set of names).

        Gazebo's rule (SDF ``self_collide``, false by default): the links whose
        ``<gazebo reference>`` sets ``<selfCollide>`` true.

        :raises ValueError: one line when a ``selfCollide`` is not a boolean.
        """
        links = set()
        for reference, tags in self.gazebo_tags.items():
            if 'selfCollide' in tags and text_bool(
                    tags['selfCollide'], f'<gazebo reference="{reference}"><selfCollide>'):
                links.add(reference)
        return links

    def initial_joint_states(self):
        """
        Return the joints the simulator starts away from 0, as gz_ros2_control does.

        ``<param name="initial_value">`` of a ``position`` or ``velocity`` state interface of
        a ``<ros2_control>`` block of the simulator's hardware component.

        :returns: list of ``(joint, position or None, velocity or None)``.
        """
        states = []
        for info in self.hardware:
            if info.plugin not in SIMULATOR_SYSTEMS:
                continue
            for joint in info.joints:
                urdf_joint = self.model.joints.get(joint.name)
                if urdf_joint is None or urdf_joint.type not in MOVING_TYPES:
                    continue  # gz_ros2_control skips fixed joints
                values = {iface.name: iface.initial_value for iface in joint.state_interfaces}
                position, velocity = values.get('position'), values.get('velocity')
                if position is not None or velocity is not None:
                    states.append((joint.name, position, velocity))
        return states

    def joint_names(self, moving_only=False):
        """
        Return the URDF joint names in document order.

        :param moving_only: True to leave out fixed joints (and joints without a type).
        """
        return [joint.get('name') for joint in self.root.findall('joint')
                if not moving_only or joint.get('type') not in ('fixed', None)]


MOVING_TYPES = ('revolute', 'continuous', 'prismatic')


def _check_one_command_source(hardware, system_hardware):
    """Refuse a joint commanded both by ``<ros2_control>`` and by a gz-sim system."""
    claimed = {joint.name: info.name for info in hardware for joint in info.joints
               if joint.command_interfaces}
    for info in system_hardware:
        for joint in info.joints:
            if joint.name in claimed:
                raise ValueError(
                    f'joint {joint.name!r} is commanded by ros2_control {claimed[joint.name]!r}'
                    ' and by the gz-sim DiffDrive plugin: keep one of them')
