# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Hardware-interface layer in ros2_control vocabulary: handles and the system base class.

A hardware component exports *state* interfaces (read by controllers) and *command*
interfaces (written by at most one controller), each a :class:`Handle` named
``<joint>/<interface>`` (e.g. ``joint_wheel_front_left/velocity``). The lifecycle mirrors
ros2_control's ``hardware_interface::SystemInterface``: ``on_init`` -> ``on_configure`` ->
``on_activate`` -> (``read`` / ``write`` every controller-manager update) -> ``on_deactivate``.
"""

import math

# lifecycle state labels as printed by ros2_control (list_hardware_components)
UNCONFIGURED = 'unconfigured'
INACTIVE = 'inactive'
ACTIVE = 'active'
FINALIZED = 'finalized'


class Handle:
    """
    One named double value shared between a hardware component and controllers.

    :param prefix_name: joint (or sensor/GPIO) name, e.g. ``'joint_wheel_front_left'``.
    :param interface_name: interface name, e.g. ``'position'``, ``'velocity'``, ``'effort'``.
    :param value: initial value (float); NaN means "not yet known", as in ros2_control.
    """

    __slots__ = ('prefix_name', 'interface_name', 'value')

    def __init__(self, prefix_name, interface_name, value=math.nan):
        """Create the handle (see the class docstring for the parameters)."""
        self.prefix_name = prefix_name
        self.interface_name = interface_name
        self.value = float(value)

    @property
    def name(self):
        """Return the full interface name ``'<prefix_name>/<interface_name>'``."""
        return f'{self.prefix_name}/{self.interface_name}'

    def __repr__(self):
        """Return ``Handle('joint/iface', value)``."""
        return f'Handle({self.name!r}, {self.value!r})'


def _initial(interface_info):
    """Return the float initial value of an ``InterfaceInfo`` (NaN when unset or malformed)."""
    raw = getattr(interface_info, 'initial_value', None)
    if raw in (None, ''):
        return math.nan
    try:
        return float(raw)
    except (TypeError, ValueError):
        return math.nan


class SystemInterface:
    """
    Base class of a multi-joint hardware component (ros2_control ``SystemInterface``).

    Subclasses override ``read``/``write`` (and optionally the lifecycle callbacks); the
    base ``on_init`` creates one :class:`Handle` per interface listed in the component's
    ``<ros2_control>`` block. Every callback returns True on success, False on failure.
    Times and periods are in seconds (float, sim time when simulated).
    """

    def __init__(self):
        """Create an empty, unconfigured component; ``on_init`` fills it."""
        self.info = None
        self.state_handles = {}
        self.command_handles = {}
        self.lifecycle_state = UNCONFIGURED

    @property
    def name(self):
        """Return the component name from its ``<ros2_control name=...>`` (or the class name)."""
        return getattr(self.info, 'name', None) or type(self).__name__

    def on_init(self, info):
        """
        Store ``info`` and create the state/command handles it lists.

        Initial values come from each interface's ``initial_value`` (NaN when absent;
        command interfaces too, as in ros2_control).

        :param info: a ``HardwareInfo`` from :func:`parse_ros2_control`.
        :returns: True.
        """
        self.info = info
        self.state_handles = {}
        self.command_handles = {}
        for joint in list(getattr(info, 'joints', [])) + list(getattr(info, 'sensors', [])) \
                + list(getattr(info, 'gpios', [])):
            for iface in joint.state_interfaces:
                handle = Handle(joint.name, iface.name, _initial(iface))
                self.state_handles[handle.name] = handle
            for iface in joint.command_interfaces:
                handle = Handle(joint.name, iface.name, _initial(iface))
                self.command_handles[handle.name] = handle
        return True

    def on_configure(self):
        """Configure the component (connect to hardware); returns True."""
        return True

    def on_cleanup(self):
        """Undo ``on_configure``; returns True."""
        return True

    def on_activate(self):
        """Start accepting commands; returns True."""
        return True

    def on_deactivate(self):
        """Stop accepting commands; returns True."""
        return True

    def on_shutdown(self):
        """Release the hardware; returns True."""
        return True

    def perform_command_mode_switch(self, start_interfaces, stop_interfaces):
        """
        Learn which command interfaces a controller just claimed or released.

        As ros2_control's ``perform_command_mode_switch``: called by the resource manager
        with the component's own interfaces only.

        :param start_interfaces: full names (``joint/interface``) now claimed, list of str.
        :param stop_interfaces: full names now released, list of str.
        :returns: True.
        """
        return True

    def export_state_interfaces(self):
        """Return the state handles, list of :class:`Handle`, in ``<ros2_control>`` order."""
        return list(self.state_handles.values())

    def export_command_interfaces(self):
        """Return the command handles, list of :class:`Handle`, in ``<ros2_control>`` order."""
        return list(self.command_handles.values())

    def read(self, time, period):
        """
        Update state handles from the hardware.

        :param time: current time in seconds (float).
        :param period: time since the previous read in seconds (float).
        :returns: True on success, False on a hardware error.
        """
        return True

    def write(self, time, period):
        """
        Send command handles to the hardware.

        :param time: current time in seconds (float).
        :param period: time since the previous write in seconds (float).
        :returns: True on success, False on a hardware error.
        """
        return True
