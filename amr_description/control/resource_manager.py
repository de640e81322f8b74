# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Resource manager: hardware components built from a URDF and their interfaces.

As ros2_control's ``hardware_interface::ResourceManager`` (jazzy): every ``<ros2_control>``
block of the URDF becomes a component through its ``<plugin>`` string (entry-point group
``amr_description.hardware``), is initialised, configured and activated; the manager owns
the union of their state and command handles and records which controller claimed which
command interface (one controller per command interface).
"""

from importlib.metadata import entry_points

from amr_description.control import hardware_interface as hi
from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.xml_document import parse_text
from amr_description.core.xml_document import XMLError

HARDWARE_GROUP = 'amr_description.hardware'


def hardware_plugins():
    """Return the registered hardware plugins, dict plugin name -> entry point."""
    return {ep.name: ep for ep in entry_points(group=HARDWARE_GROUP)}


def default_hardware_factory(info):
    """
    Instantiate the class registered for ``info.plugin`` with no arguments.

    :param info: a ``HardwareInfo``.
    :returns: a :class:`SystemInterface` instance (not yet initialised).
    :raises ValueError: when no plugin of that name is registered.
    """
    plugins = hardware_plugins()
    if info.plugin not in plugins:
        raise ValueError(
            f'hardware component {info.name!r}: unknown plugin {info.plugin!r} '
            f'(available: {", ".join(sorted(plugins))})')
    return plugins[info.plugin].load()()


class ResourceManager:
    """
    Hardware components of one robot and their claimed interfaces.

    :param urdf_xml: the robot description with ``<ros2_control>`` blocks: URDF XML (str),
        or its :class:`~amr_description.core.description.robot_description.RobotDescription` (no
        parse).
    :param hardware_factory: callable ``(HardwareInfo) -> SystemInterface``; default
        :func:`default_hardware_factory`.
    :param activate: when True (default) every component is configured and activated.
    :raises ValueError: one line naming the problem: malformed URDF or block, a joint of a
        ``<ros2_control>`` block missing from the URDF, an unknown plugin, a component whose
        ``on_init``/``on_configure``/``on_activate`` failed, or a duplicated interface.
    """

    def __init__(self, urdf_xml, hardware_factory=None, activate=True):
        """Build, initialise and (optionally) activate every component."""
        if hasattr(urdf_xml, 'hardware'):  # a RobotDescription, parsed once by the caller
            root, self.infos = urdf_xml.root, urdf_xml.hardware
        else:
            try:
                root = parse_text(urdf_xml)
            except XMLError as exc:
                raise ValueError(f'robot description is not valid XML: {exc}') from None
            self.infos = parse_ros2_control(root)
        urdf_joints = [j.get('name') for j in root.findall('joint')]
        self.urdf_joint_names = urdf_joints
        self.rw_rates = {}  # component name -> Hz from <ros2_control rw_rate="...">, else 0
        self.is_async = {}  # component name -> bool from <ros2_control is_async="...">
        for block in root.findall('ros2_control'):
            name = block.get('name')
            try:
                self.rw_rates[name] = max(0, int(block.get('rw_rate', '0')))
            except ValueError:
                raise ValueError(f'ros2_control {name!r}: rw_rate must be an integer (Hz), '
                                 f'got {block.get("rw_rate")!r}') from None
            self.is_async[name] = block.get('is_async', 'false').strip().lower() == 'true'
        factory = hardware_factory or default_hardware_factory
        self.components = []
        self.state_interfaces = {}
        self.command_interfaces = {}
        self.claimed = {}  # command interface name -> controller name
        for info in self.infos:
            for joint in info.joints:
                if joint.name not in urdf_joints:
                    raise ValueError(
                        f'ros2_control {info.name!r}: joint {joint.name!r} is not a joint '
                        'of the URDF')
            component = factory(info)
            if not component.on_init(info):
                raise ValueError(f'hardware component {info.name!r}: on_init failed')
            component.lifecycle_state = hi.UNCONFIGURED
            for handle in component.export_state_interfaces():
                self._add(self.state_interfaces, handle, info.name)
            for handle in component.export_command_interfaces():
                self._add(self.command_interfaces, handle, info.name)
            self.components.append(component)
        if activate:
            for component in self.components:
                self.set_component_state(component, hi.ACTIVE)

    @staticmethod
    def _add(table, handle, component):
        if handle.name in table:
            raise ValueError(
                f'hardware component {component!r}: interface {handle.name!r} exported twice')
        table[handle.name] = handle

    def set_component_state(self, component, target):
        """
        Move ``component`` to lifecycle ``target``.

        As ros2_control's ``ResourceManager::set_component_state``: from unconfigured,
        ``'inactive'`` configures and ``'active'`` configures then activates; from active,
        ``'inactive'`` deactivates and ``'unconfigured'`` deactivates then cleans up;
        ``'finalized'`` shuts the component down from any state. A finalized component
        stays finalized.

        :param component: one of :attr:`components`.
        :param target: ``'unconfigured'``, ``'inactive'``, ``'active'`` or ``'finalized'``.
        :raises ValueError: when a lifecycle callback returns False.
        """
        if target in (hi.INACTIVE, hi.ACTIVE) and component.lifecycle_state == hi.UNCONFIGURED:
            if not component.on_configure():
                raise ValueError(f'hardware component {component.name!r}: on_configure failed')
            component.lifecycle_state = hi.INACTIVE
        if target == hi.ACTIVE and component.lifecycle_state == hi.INACTIVE:
            if not component.on_activate():
                raise ValueError(f'hardware component {component.name!r}: on_activate failed')
            component.lifecycle_state = hi.ACTIVE
        if target in (hi.INACTIVE, hi.UNCONFIGURED) and component.lifecycle_state == hi.ACTIVE:
            component.on_deactivate()
            component.lifecycle_state = hi.INACTIVE
        if target == hi.UNCONFIGURED and component.lifecycle_state == hi.INACTIVE:
            if not component.on_cleanup():
                raise ValueError(f'hardware component {component.name!r}: on_cleanup failed')
            component.lifecycle_state = hi.UNCONFIGURED
        if target == hi.FINALIZED and component.lifecycle_state != hi.FINALIZED:
            if component.lifecycle_state == hi.ACTIVE:
                component.on_deactivate()
            component.on_shutdown()
            component.lifecycle_state = hi.FINALIZED

    def component(self, name):
        """Return the component named ``name``, or None."""
        for component in self.components:
            if component.name == name:
                return component
        return None

    def component_of(self, interface_name):
        """Return the component exporting ``interface_name`` (state or command), or None."""
        for component in self.components:
            if interface_name in component.state_handles \
                    or interface_name in component.command_handles:
                return component
        return None

    def command_interface_available(self, name):
        """Return True when command interface ``name`` exists on an active component."""
        component = self.component_of(name)
        return (name in self.command_interfaces and component is not None
                and component.lifecycle_state == hi.ACTIVE)

    def state_interface_available(self, name):
        """Return True when state interface ``name`` exists on a configured component."""
        component = self.component_of(name)
        return (name in self.state_interfaces and component is not None
                and component.lifecycle_state in (hi.INACTIVE, hi.ACTIVE))

    def claim(self, controller, names):
        """
        Claim command interfaces ``names`` for ``controller`` (all or none).

        :param controller: claiming controller name.
        :param names: iterable of command interface names.
        :returns: dict name -> :class:`Handle`.
        :raises ValueError: naming the first missing interface, or an interface already
            claimed by another controller (and which).
        """
        names = list(names)
        for name in names:
            if name not in self.command_interfaces:
                raise ValueError(f'command interface {name!r} does not exist')
            owner = self.claimed.get(name)
            if owner is not None and owner != controller:
                raise ValueError(
                    f'command interface {name!r} is already claimed by {owner!r}')
        started = [name for name in names if name not in self.claimed]
        for name in names:
            self.claimed[name] = controller
        self._switch(started, [])
        return {name: self.command_interfaces[name] for name in names}

    def release(self, controller):
        """Release every command interface claimed by ``controller``."""
        stopped = [n for n, owner in self.claimed.items() if owner == controller]
        for name in stopped:
            del self.claimed[name]
        self._switch([], stopped)

    def _switch(self, started, stopped):
        """Tell each component which of its command interfaces were claimed or released."""
        for component in self.components:
            start = [n for n in started if n in component.command_handles]
            stop = [n for n in stopped if n in component.command_handles]
            if start or stop:
                component.perform_command_mode_switch(start, stop)

    def claimed_by(self, controller):
        """Return the command interfaces claimed by ``controller``, a sorted list of str."""
        return sorted(n for n, owner in self.claimed.items() if owner == controller)

    def read(self, time, period):
        """Call ``read`` of every active component; returns names of those that failed."""
        return [c.name for c in self.components
                if c.lifecycle_state == hi.ACTIVE and not c.read(time, period)]

    def write(self, time, period):
        """Call ``write`` of every active component; returns names of those that failed."""
        return [c.name for c in self.components
                if c.lifecycle_state == hi.ACTIVE and not c.write(time, period)]

    def shutdown(self):
        """Deactivate and shut down every component (errors ignored)."""
        for component in self.components:
            try:
                if component.lifecycle_state == hi.ACTIVE:
                    component.on_deactivate()
                component.on_shutdown()
            except Exception:  # noqa: B902 - shutdown must not raise
                pass
            component.lifecycle_state = hi.FINALIZED
