# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The Gazebo dialect of a URDF that the simulator reads: gz_ros2_control's names and plugin.

As gz_ros2_control (jazzy): the ``<ros2_control>`` hardware plugins
``gz_ros2_control/GazeboSimSystem`` and ``ign_ros2_control/IgnitionSystem`` are the
simulator's own hardware component (:data:`SIMULATOR_SYSTEMS`), and a ``<gazebo><plugin>``
whose ``filename`` is one of :data:`CONTROL_PLUGIN_FILES` (or whose ``name`` is one of
:data:`CONTROL_PLUGIN_NAMES`) starts the robot's controller manager with its children
(``GazeboSimROS2ControlPlugin::Configure``): every ``<parameters>`` file in document order
(a later file overrides an earlier one), ``<controller_manager_name>`` (default
``controller_manager``), ``<ros><namespace>`` and every ``<ros><remapping>``,
``<hold_joints>`` (default true) and ``<position_proportional_gain>`` (default 0.1). Both the
text form and a ``value="..."`` attribute are read.
"""

from dataclasses import dataclass
from dataclasses import field

SIMULATOR_SYSTEMS = ('amr_description/MujocoSystem', 'gz_ros2_control/GazeboSimSystem',
                     'ign_ros2_control/IgnitionSystem')
"""``<hardware><plugin>`` names that select the simulator's hardware component."""

CONTROL_PLUGIN_FILES = ('gz_ros2_control-system', 'libgz_ros2_control-system.so',
                        'libign_ros2_control-system.so', 'ign_ros2_control-system')
"""``<gazebo><plugin filename>`` values of gz_ros2_control's system plugin."""

CONTROL_PLUGIN_NAMES = ('gz_ros2_control::GazeboSimROS2ControlPlugin',
                        'ign_ros2_control::IgnitionROS2ControlPlugin')
"""``<gazebo><plugin name>`` values of gz_ros2_control's system plugin."""


@dataclass
class ControlPlugin:
    """
    The gz_ros2_control ``<gazebo><plugin>`` of a robot description.

    :param parameters: the ``<parameters>`` files, document order (URIs as written).
    :param controller_manager_name: the controller manager's node name.
    :param namespace: ``<ros><namespace>``, '' for none (a leading ``/`` is added).
    :param remappings: ``<ros><remapping>`` rules, e.g. ``['/tf:=tf']``.
    :param hold_joints: hold joints no controller commands (velocity 0).
    :param position_proportional_gain: the gain of position commands.
    """

    parameters: list = field(default_factory=list)
    controller_manager_name: str = 'controller_manager'
    namespace: str = ''
    remappings: list = field(default_factory=list)
    hold_joints: bool = True
    position_proportional_gain: float = 0.1


def _text(element):
    """Return the value of a Gazebo tag: its ``value`` attribute or its text, stripped."""
    value = element.get('value')
    return (value if value is not None else element.text or '').strip()


def _bool(element, where):
    text = _text(element).lower()
    if text in ('true', '1'):
        return True
    if text in ('false', '0'):
        return False
    raise ValueError(f'{where}: expected true or false, found {_text(element)!r}')


def is_control_plugin(plugin):
    """Return True when a ``<plugin>`` element is gz_ros2_control's system plugin."""
    return (plugin.get('filename') or '').strip() in CONTROL_PLUGIN_FILES or \
        (plugin.get('name') or '').strip() in CONTROL_PLUGIN_NAMES


def parse_control_plugin(root):
    """
    Return the :class:`ControlPlugin` of a URDF ``<robot>`` element, or None without one.

    :param root: the ``<robot>`` element (standard library or lxml).
    :raises ValueError: one line naming the element: no (or an empty) ``<parameters>``, a
        ``<hold_joints>`` that is not a boolean, a gain that is not a number.
    """
    for gazebo in root.findall('gazebo'):
        for plugin in gazebo.findall('plugin'):
            if is_control_plugin(plugin):
                return _read_plugin(plugin)
    return None


def _read_plugin(plugin):
    where = f"<gazebo><plugin name=\"{plugin.get('name', '')}\">"
    result = ControlPlugin()
    result.parameters = [_text(p) for p in plugin.findall('parameters')]
    if not result.parameters or not all(result.parameters):
        raise ValueError(f'{where}: <parameters> (the controllers YAML) is required and must '
                         'not be empty, as gz_ros2_control needs it')
    element = plugin.find('controller_manager_name')
    if element is not None and _text(element):
        result.controller_manager_name = _text(element)
    ros = plugin.find('ros')
    if ros is not None:
        namespace = ros.find('namespace')
        if namespace is not None and _text(namespace).strip('/'):
            result.namespace = '/' + _text(namespace).strip('/')
        result.remappings = [_text(r) for r in ros.findall('remapping') if _text(r)]
    element = plugin.find('hold_joints')
    if element is not None:
        result.hold_joints = _bool(element, f'{where}<hold_joints>')
    element = plugin.find('position_proportional_gain')
    if element is not None:
        try:
            result.position_proportional_gain = float(_text(element))
        except ValueError:
            raise ValueError(f'{where}<position_proportional_gain>: expected a number, found '
                             f'{_text(element)!r}') from None
    return result
