# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The controller manager's ROS face: parameters, services and ``~/activity``, as upstream.

:class:`ManagerServices` is a mix-in of
:class:`~amr_description.control.controller_manager.ControllerManager`: it creates, under
``~/``, the controller_manager_msgs services (``list_controllers``,
``list_controller_types``, ``load_controller``, ``configure_controller``,
``cleanup_controller``, ``switch_controller``, ``unload_controller``,
``reload_controller_libraries``, ``list_hardware_interfaces``, ``list_hardware_components``,
``set_hardware_component_state``) and the ``~/activity`` publisher (reliable, transient local,
depth 1), and answers each service from the manager's state under its lock; the work itself
(load, configure, switch, ...) is the manager's.
"""

from importlib.metadata import entry_points

CONTROLLER_GROUP = 'amr_description.controllers'
"""Entry-point group of the controller types (``diff_drive_controller/DiffDriveController``)."""

BASE_CLASSES = ['controller_interface::ControllerInterface',
                'controller_interface::ChainableControllerInterface']
"""What ``list_controller_types`` gives as base classes (upstream's names)."""

UPDATE_RATE_DESCRIPTION = (
    "The frequency of controller manager's real-time update loop. This loop reads states "
    'from hardware, updates controllers and writes commands to hardware.')
"""Upstream's description of ``update_rate``."""
CONTROLLER_KEYS = {
    'type': 'The type of the controller, e.g. diff_drive_controller/DiffDriveController.',
    'params_file': 'The parameter files of the controller (string or string array).',
    'node_options_args': 'The node arguments of the controller node, e.g. '
                         "['-r', '~/cmd_vel:=/cmd_vel_remapped'].",
    'fallback_controllers': 'The controllers activated when this one fails.',
}
"""Descriptions of the ``<controller>.<key>`` parameters (upstream's)."""

STATE_IDS = {'unknown': 0, 'unconfigured': 1, 'inactive': 2, 'active': 3, 'finalized': 4}
"""lifecycle_msgs/State ids of the lifecycle labels."""


def list_value(value):
    """Return a str or string-array parameter value as a list of str ([] when unset)."""
    if value is None:
        return []
    if isinstance(value, str):
        return value.split()
    return [str(v) for v in value]


def controller_types():
    """Return the registered controller types, dict type string -> entry point."""
    return {ep.name: ep for ep in entry_points(group=CONTROLLER_GROUP)}


class ManagerServices:
    """
    The services and ``~/activity`` of a controller manager (a mix-in of the rclpy Node).

    Uses the manager's ``controllers``, ``resource_manager``, ``update_rate``, ``_lock``,
    ``_destroyed`` and its controller API (``load_controller``, ``switch_controller``, ...).
    """

    def _declare_parameters(self, overrides, skipped):
        """
        Declare ``update_rate`` (read-only, default 100) and every ``<controller>.<key>``.

        :param overrides: the YAML's parameters (rclpy ``Parameter`` list).
        :param skipped: names of values rclpy cannot hold (warned and ignored).
        :returns: the update rate, Hz (int).
        :raises ValueError: one line when ``update_rate`` is not a positive integer.
        """
        from rcl_interfaces.msg import ParameterDescriptor
        for name in skipped:
            self.get_logger().warn(f"Parameter '{name}' has an unsupported value: ignored")
        # update_rate is read-only, as upstream (generate_parameter_library read_only: true)
        self.declare_parameter('update_rate', 100, ParameterDescriptor(
            description=UPDATE_RATE_DESCRIPTION, read_only=True))
        for param in overrides:
            if param.name in ('update_rate', 'use_sim_time') or self.has_parameter(param.name):
                continue
            key = param.name.rpartition('.')[2]
            self.declare_parameter(param.name, param.value, ParameterDescriptor(
                description=CONTROLLER_KEYS.get(key, ''), dynamic_typing=True))
        rate = self.get_parameter('update_rate').value
        if not isinstance(rate, int) or isinstance(rate, bool) or rate <= 0:
            raise ValueError(f"controller_manager: parameter 'update_rate' must be a positive "
                             f'integer (Hz), got {rate!r}')
        return rate

    def _create_services(self):
        from controller_manager_msgs import msg
        from controller_manager_msgs import srv
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        from rclpy.qos import ReliabilityPolicy
        self._srv = srv
        self._cm_services = []
        for name, kind, callback in (
                ('list_controllers', srv.ListControllers, self._srv_list_controllers),
                ('list_controller_types', srv.ListControllerTypes, self._srv_list_types),
                ('load_controller', srv.LoadController, self._srv_load),
                ('configure_controller', srv.ConfigureController, self._srv_configure),
                ('cleanup_controller', srv.CleanupController, self._srv_cleanup),
                ('switch_controller', srv.SwitchController, self._srv_switch),
                ('unload_controller', srv.UnloadController, self._srv_unload),
                ('reload_controller_libraries', srv.ReloadControllerLibraries,
                 self._srv_reload_libraries),
                ('list_hardware_interfaces', srv.ListHardwareInterfaces, self._srv_hw_ifaces),
                ('list_hardware_components', srv.ListHardwareComponents,
                 self._srv_hw_components),
                ('set_hardware_component_state', srv.SetHardwareComponentState,
                 self._srv_set_hw_state)):
            self._cm_services.append(self.create_service(kind, f'~/{name}', callback))
        self._activity_pub = self.create_publisher(
            msg.ControllerManagerActivity, '~/activity',
            QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                       durability=DurabilityPolicy.TRANSIENT_LOCAL))

    def _publish_activity(self):
        """Publish ``~/activity``: the lifecycle state of every controller and component."""
        from controller_manager_msgs.msg import ControllerManagerActivity
        from controller_manager_msgs.msg import NamedLifecycleState
        if self._destroyed or not self.context.ok():
            return
        msg = ControllerManagerActivity()
        msg.header.stamp = self.get_clock().now().to_msg()
        with self._lock:
            for name, ctrl in self.controllers.items():
                item = NamedLifecycleState(name=name)
                item.state.label = ctrl.lifecycle_state
                item.state.id = STATE_IDS.get(item.state.label, 0)
                msg.controllers.append(item)
            for component in self.resource_manager.components:
                item = NamedLifecycleState(name=component.name)
                item.state.label = component.lifecycle_state
                item.state.id = STATE_IDS.get(item.state.label, 0)
                msg.hardware_components.append(item)
        try:
            self._activity_pub.publish(msg)
        except Exception:  # noqa: B902 - context shutting down: nothing to tell
            pass

    def _srv_list_controllers(self, request, response):
        from controller_manager_msgs.msg import ControllerState
        with self._lock:
            for name, ctrl in self.controllers.items():
                state = ControllerState()
                state.name = name
                state.state = ctrl.lifecycle_state
                state.type = ctrl.controller_type
                state.is_async = ctrl.is_async
                state.update_rate = ctrl.update_rate
                state.claimed_interfaces = self.resource_manager.claimed_by(name)
                cmd = ctrl.command_interface_configuration() or []
                st = ctrl.state_interface_configuration()
                if st is None:
                    st = list(self.resource_manager.state_interfaces)
                state.required_command_interfaces = list(cmd)
                state.required_state_interfaces = list(st)
                state.is_chainable = False
                state.is_chained = False
                response.controller.append(state)
        return response

    def _srv_list_types(self, request, response):
        for name in sorted(controller_types()):
            response.types.append(name)
            response.base_classes.append(BASE_CLASSES[0])
        return response

    def _srv_load(self, request, response):
        response.ok = self.load_controller(request.name) is not None
        return response

    def _srv_configure(self, request, response):
        response.ok = self.configure_controller(request.name)
        return response

    def _srv_cleanup(self, request, response):
        response.ok = self.cleanup_controller(request.name)
        return response

    def _srv_unload(self, request, response):
        response.ok = self.unload_controller(request.name)
        return response

    def _srv_reload_libraries(self, request, response):
        response.ok = self.reload_controller_libraries(request.force_kill)
        return response

    def _srv_switch(self, request, response):
        timeout = request.timeout.sec + request.timeout.nanosec * 1e-9
        ok, message = self.switch_controller(
            list(request.activate_controllers), list(request.deactivate_controllers),
            request.strictness, timeout)
        response.ok = ok
        response.message = message
        return response

    def _hw_iface(self, name, claimed, available):
        from controller_manager_msgs.msg import HardwareInterface
        return HardwareInterface(name=name, data_type='double', is_available=available,
                                 is_claimed=claimed)

    def _srv_hw_ifaces(self, request, response):
        rm = self.resource_manager
        with self._lock:
            for name in rm.command_interfaces:
                response.command_interfaces.append(self._hw_iface(
                    name, name in rm.claimed, rm.command_interface_available(name)))
            for name in rm.state_interfaces:
                response.state_interfaces.append(self._hw_iface(
                    name, False, rm.state_interface_available(name)))
        return response

    def _srv_hw_components(self, request, response):
        from controller_manager_msgs.msg import HardwareComponentState
        rm = self.resource_manager
        with self._lock:
            for component in rm.components:
                msg = HardwareComponentState()
                msg.name = component.name
                msg.type = getattr(component.info, 'type', 'system')
                msg.is_async = rm.is_async.get(component.name, False)
                msg.rw_rate = rm.rw_rates.get(component.name) or self.update_rate
                msg.plugin_name = getattr(component.info, 'plugin', '')
                msg.class_type = msg.plugin_name
                msg.state.id = STATE_IDS.get(component.lifecycle_state, 0)
                msg.state.label = component.lifecycle_state
                msg.command_interfaces = [
                    self._hw_iface(h.name, h.name in rm.claimed,
                                   rm.command_interface_available(h.name))
                    for h in component.export_command_interfaces()]
                msg.state_interfaces = [
                    self._hw_iface(h.name, False, rm.state_interface_available(h.name))
                    for h in component.export_state_interfaces()]
                response.component.append(msg)
        return response

    def _srv_set_hw_state(self, request, response):
        ok, label = self.set_hardware_component_state(
            request.name, request.target_state.id, request.target_state.label)
        response.ok = ok
        response.state.id = STATE_IDS.get(label, 0)
        response.state.label = label
        return response
