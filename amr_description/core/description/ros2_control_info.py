# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Parse the ``<ros2_control>`` blocks of a URDF into plain dataclasses (no rclpy).

The structure follows ros2_control's ``hardware_interface::HardwareInfo`` /
``ComponentInfo`` / ``InterfaceInfo`` (jazzy), reduced to what a Python resource manager
needs::

    <ros2_control name="AmrSystem" type="system">
      <hardware>
        <plugin>amr_description/MujocoSystem</plugin>
        <param name="key">value</param>
      </hardware>
      <joint name="joint_wheel_front_left">
        <command_interface name="velocity">
          <param name="min">-10</param>
          <param name="max">10</param>
        </command_interface>
        <state_interface name="position"/>
        <state_interface name="velocity"/>
      </joint>
    </ros2_control>

Numeric interface parameters (``min``, ``max``, ``initial_value``) are converted to float;
``None`` means "not given". Every other ``<param>`` value is kept as a string, as upstream does.
"""

from dataclasses import dataclass
from dataclasses import field

from amr_description.core.xml_document import parse_text
from amr_description.core.xml_document import XMLError

HARDWARE_TYPES = ('system', 'actuator', 'sensor')


@dataclass
class InterfaceInfo:
    """
    One command or state interface of a component.

    :param name: interface name, e.g. ``'velocity'`` (ros2_control vocabulary).
    :param min: lower limit from ``<param name="min">`` (float, joint units), or None.
    :param max: upper limit from ``<param name="max">`` (float, joint units), or None.
    :param initial_value: from ``<param name="initial_value">`` (float), or None.
    :param data_type: the ``data_type`` attribute, ``'double'`` by default.
    """

    name: str
    min: float = None  # noqa: A003 (ros2_control's name)
    max: float = None  # noqa: A003 (ros2_control's name)
    initial_value: float = None
    data_type: str = 'double'


@dataclass
class ComponentInfo:
    """
    A ``<joint>``, ``<sensor>`` or ``<gpio>`` element of a ``<ros2_control>`` block.

    :param name: the component name (for joints: the URDF joint name).
    :param command_interfaces: list of :class:`InterfaceInfo`, in document order.
    :param state_interfaces: list of :class:`InterfaceInfo`, in document order.
    :param parameters: dict str -> str of the component's own ``<param>`` elements.
    """

    name: str
    command_interfaces: list = field(default_factory=list)
    state_interfaces: list = field(default_factory=list)
    parameters: dict = field(default_factory=dict)

    def command_interface_names(self):
        """Return the command interface names, a list of str."""
        return [iface.name for iface in self.command_interfaces]

    def state_interface_names(self):
        """Return the state interface names, a list of str."""
        return [iface.name for iface in self.state_interfaces]


@dataclass
class HardwareInfo:
    """
    One ``<ros2_control>`` block.

    :param name: the ``name`` attribute, e.g. ``'AmrSystem'``.
    :param type: the ``type`` attribute: ``'system'``, ``'actuator'`` or ``'sensor'``.
    :param plugin: text of ``<hardware><plugin>``, e.g. ``'amr_description/MujocoSystem'``.
    :param parameters: dict str -> str of the ``<hardware>`` ``<param>`` elements.
    :param joints: list of :class:`ComponentInfo`, in document order.
    :param sensors: list of :class:`ComponentInfo` from ``<sensor>`` elements.
    :param gpios: list of :class:`ComponentInfo` from ``<gpio>`` elements.
    """

    name: str
    type: str  # noqa: A003 (ros2_control's name)
    plugin: str
    parameters: dict = field(default_factory=dict)
    joints: list = field(default_factory=list)
    sensors: list = field(default_factory=list)
    gpios: list = field(default_factory=list)

    def joint(self, name):
        """Return the :class:`ComponentInfo` of joint ``name``, or None when absent."""
        for joint in self.joints:
            if joint.name == name:
                return joint
        return None


def _params(element, where):
    """Return the ``<param name=...>text</param>`` children of ``element`` as a dict."""
    params = {}
    for param in element.findall('param'):
        key = param.get('name')
        if not key:
            raise ValueError(f'ros2_control: <param> without a name in {where}')
        params[key] = (param.text or '').strip()
    return params


def _float_param(params, key, where):
    """Return ``params[key]`` as float, None when absent; ValueError when not a number."""
    if key not in params:
        return None
    try:
        return float(params[key])
    except ValueError:
        raise ValueError(
            f'ros2_control: {where} param {key!r} must be a number, '
            f'found {params[key]!r}') from None


def _interface(element, where):
    """Parse a ``<command_interface>`` or ``<state_interface>`` element."""
    name = element.get('name')
    if not name:
        raise ValueError(f'ros2_control: <{element.tag}> without a name in {where}')
    where = f'{where} {element.tag} {name!r}'
    params = _params(element, where)
    return InterfaceInfo(
        name=name,
        min=_float_param(params, 'min', where),
        max=_float_param(params, 'max', where),
        initial_value=_float_param(params, 'initial_value', where),
        data_type=element.get('data_type', 'double'))


def _component(element, block):
    """Parse a ``<joint>``, ``<sensor>`` or ``<gpio>`` element of block ``block``."""
    name = element.get('name')
    if not name:
        raise ValueError(f'ros2_control {block!r}: <{element.tag}> without a name')
    where = f'{block!r} {element.tag} {name!r}'
    return ComponentInfo(
        name=name,
        command_interfaces=[_interface(e, where) for e in element.findall('command_interface')],
        state_interfaces=[_interface(e, where) for e in element.findall('state_interface')],
        parameters=_params(element, where))


def _hardware(element):
    """Parse one ``<ros2_control>`` element into a :class:`HardwareInfo`."""
    name = element.get('name')
    if not name:
        raise ValueError('ros2_control: block without a name attribute')
    hw_type = element.get('type')
    if hw_type not in HARDWARE_TYPES:
        raise ValueError(
            f'ros2_control {name!r}: type must be one of {", ".join(HARDWARE_TYPES)}, '
            f'found {hw_type!r}')
    hardware = element.find('hardware')
    if hardware is None:
        raise ValueError(f'ros2_control {name!r}: missing <hardware> element')
    plugin = (hardware.findtext('plugin') or '').strip()
    if not plugin:
        raise ValueError(f'ros2_control {name!r}: missing <hardware><plugin>')
    info = HardwareInfo(
        name=name, type=hw_type, plugin=plugin,
        parameters=_params(hardware, f'{name!r} hardware'),
        joints=[_component(e, name) for e in element.findall('joint')],
        sensors=[_component(e, name) for e in element.findall('sensor')],
        gpios=[_component(e, name) for e in element.findall('gpio')])
    seen = set()
    for joint in info.joints:
        if joint.name in seen:
            raise ValueError(f'ros2_control {name!r}: joint {joint.name!r} listed twice')
        seen.add(joint.name)
    return info


def parse_ros2_control(urdf_xml):
    """
    Parse every ``<ros2_control>`` child of the URDF ``<robot>`` element.

    :param urdf_xml: the URDF document, str or bytes, or its parsed ``<robot>`` element
        (standard library or lxml).
    :returns: list of :class:`HardwareInfo`, in document order (empty when none).
    :raises ValueError: one-line message when the XML is malformed, the root is not
        ``<robot>``, or a block lacks a name, a valid type, ``<hardware><plugin>``, an
        interface name, or has a non-numeric ``min``/``max``/``initial_value``.
    """
    if isinstance(urdf_xml, (str, bytes)):
        if isinstance(urdf_xml, str):
            urdf_xml = urdf_xml.encode('utf-8')
        try:
            root = parse_text(urdf_xml)
        except XMLError as exc:
            raise ValueError(f'ros2_control: URDF is not well-formed XML: {exc}') from None
    else:
        root = urdf_xml
    if root.tag != 'robot':
        raise ValueError(f'ros2_control: root element must be <robot>, found <{root.tag}>')
    return [_hardware(element) for element in root.findall('ros2_control')]


def driven_joints(model, infos, wheel_names=()):
    """
    Return the joints that drive the robot: the wheels that must touch the ground.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param infos: the ``<ros2_control>`` blocks
        (:func:`~amr_description.core.description.ros2_control_info.parse_ros2_control`).
    :param wheel_names: wheel joint names the controllers YAML gives
        (``left_wheel_names``/``right_wheel_names`` of a diff_drive_controller).
    :returns: dict joint name -> why it is driven (``'velocity command interface'``,
        ``'effort command interface'`` or ``'a wheel in the controllers YAML'``), URDF
        joints only, in the order found.
    """
    driven = {}
    for info in infos:
        for joint in info.joints:
            commands = joint.command_interface_names()
            for kind in ('velocity', 'effort'):
                if kind in commands and joint.name in model.joints:
                    driven.setdefault(joint.name, f'{kind} command interface')
    for name in wheel_names:
        if name in model.joints:
            driven.setdefault(name, 'a wheel in the controllers YAML')
    return driven
