# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Controller manager: loads controllers and runs read -> update -> write.

As ros2_control's ``controller_manager`` (jazzy): an rclpy node ``controller_manager`` whose
parameters come from the controllers YAML (same format; ``update_rate`` default 100 Hz,
``<controller>.type``, ``<controller>.params_file`` — the upstream spawner sets the last two
through the parameter services) and which serves, under ``~/``, ``list_controllers``,
``list_controller_types``, ``load_controller``, ``configure_controller``,
``cleanup_controller``, ``switch_controller``, ``unload_controller``,
``list_hardware_interfaces`` and ``list_hardware_components`` (controller_manager_msgs).

Controllers are found by their ``type`` in the entry-point group
``amr_description.controllers``; each is a lifecycle node named after it, with its parameters
from the YAML (and ``use_sim_time``). ``update(time, period)`` (seconds) is called by the
owner's control thread (the simulator, or :func:`main`'s wall-clock loop); it applies pending
switches, reads the hardware, updates active controllers in load order, then writes. A
controller whose update fails (returns False, raises, or sees NaN feedback) is deactivated
with an error log. Switches requested through the service happen at the next update; the
service waits for it up to the request's timeout (0: 1 s), as upstream.

Run standalone (ros2_control_node equivalent)::

    python -m amr_description.control.controller_manager --urdf urdf/amr.urdf \
        --params config/controllers.yaml --mock-hardware
"""

import argparse
from importlib.metadata import entry_points
import os
import sys
import threading
import time as _time

from amr_description.control.controller_interface import parameters_from_dict
from amr_description.control.resource_manager import ResourceManager
from amr_description.core import ros_param_file
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

CONTROLLER_GROUP = 'amr_description.controllers'
BASE_CLASSES = ['controller_interface::ControllerInterface',
                'controller_interface::ChainableControllerInterface']
DEFAULT_SWITCH_TIMEOUT = 1.0

_STATE_IDS = {'unknown': 0, 'unconfigured': 1, 'inactive': 2, 'active': 3, 'finalized': 4}


def controller_types():
    """Return the registered controller types, dict type string -> entry point."""
    return {ep.name: ep for ep in entry_points(group=CONTROLLER_GROUP)}


class _Switch:
    """A pending switch request, executed by the update thread."""

    def __init__(self, activate, deactivate):
        self.activate = activate
        self.deactivate = deactivate
        self.done = threading.Event()
        self.ok = False
        self.message = ''


class ControllerManager(Node):
    """
    The controller manager node (see the module docstring).

    :param urdf_xml: robot description with ``<ros2_control>`` blocks (str).
    :param executor: rclpy executor; the manager adds itself and every controller node.
    :param hardware_factory: ``(HardwareInfo) -> SystemInterface`` (default: entry points).
    :param parameters_file: path of the controllers YAML, or None.
    :param namespace: node namespace of the manager and its controllers.
    :param use_sim_time: set ``use_sim_time`` on the manager and every controller.
    :raises ValueError: one line when the URDF, its ``<ros2_control>`` blocks or the
        parameter file are invalid.
    """

    def __init__(self, urdf_xml, executor, hardware_factory=None, parameters_file=None,
                 namespace='', use_sim_time=True):
        """Create the node, the hardware and the services (see the class docstring)."""
        self._yaml_files = []
        own = {}
        if parameters_file:
            data = ros_param_file.load_yaml(parameters_file)
            self._yaml_files.append((parameters_file, data))
            own = ros_param_file.parameters_for_node(
                data, 'controller_manager', namespace, parameters_file)
        own['use_sim_time'] = bool(use_sim_time)
        overrides, skipped = parameters_from_dict(own)
        super().__init__(
            'controller_manager', namespace=namespace, context=executor.context,
            parameter_overrides=overrides, allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True)
        for name in skipped:
            self.get_logger().warn(f"Parameter '{name}' has an unsupported value: ignored")
        if not self.has_parameter('update_rate'):
            self.declare_parameter('update_rate', 100)
        rate = self.get_parameter('update_rate').value
        if not isinstance(rate, int) or rate <= 0:
            raise ValueError(f"controller_manager: parameter 'update_rate' must be a positive "
                             f'integer (Hz), got {rate!r}')
        self.update_rate = rate
        self.robot_description = urdf_xml
        self.use_sim_time = bool(use_sim_time)
        self._executor = executor
        self._lock = threading.RLock()
        self._pending = None
        self.controllers = {}  # name -> controller node, in load order
        self.resource_manager = ResourceManager(urdf_xml, hardware_factory)
        self.get_logger().info(
            f'Resource manager: {len(self.resource_manager.components)} hardware component(s) '
            f'active, {len(self.resource_manager.command_interfaces)} command and '
            f'{len(self.resource_manager.state_interfaces)} state interfaces')
        self._create_services()
        executor.add_node(self)

    # ----------------------------------------------------------------- services
    def _create_services(self):
        from controller_manager_msgs import srv
        self._srv = srv
        for name, kind, callback in (
                ('list_controllers', srv.ListControllers, self._srv_list_controllers),
                ('list_controller_types', srv.ListControllerTypes, self._srv_list_types),
                ('load_controller', srv.LoadController, self._srv_load),
                ('configure_controller', srv.ConfigureController, self._srv_configure),
                ('cleanup_controller', srv.CleanupController, self._srv_cleanup),
                ('switch_controller', srv.SwitchController, self._srv_switch),
                ('unload_controller', srv.UnloadController, self._srv_unload),
                ('list_hardware_interfaces', srv.ListHardwareInterfaces, self._srv_hw_ifaces),
                ('list_hardware_components', srv.ListHardwareComponents,
                 self._srv_hw_components)):
            self.create_service(kind, f'~/{name}', callback)

    def _srv_list_controllers(self, request, response):
        from controller_manager_msgs.msg import ControllerState
        with self._lock:
            for name, ctrl in self.controllers.items():
                state = ControllerState()
                state.name = name
                state.state = ctrl.lifecycle_state
                state.type = ctrl.controller_type
                state.is_async = False
                state.update_rate = self.update_rate
                state.claimed_interfaces = self.resource_manager.claimed_by(name)
                cmd = ctrl.command_interface_configuration() or []
                st = ctrl.state_interface_configuration()
                if st is None:
                    st = list(self.resource_manager.state_interfaces)
                state.required_command_interfaces = list(cmd)
                state.required_state_interfaces = list(st)
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

    def _srv_switch(self, request, response):
        timeout = request.timeout.sec + request.timeout.nanosec * 1e-9
        ok, message = self.switch_controller(
            list(request.activate_controllers), list(request.deactivate_controllers),
            request.strictness, timeout)
        response.ok = ok
        if hasattr(response, 'message'):
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
                msg.is_async = False
                msg.rw_rate = self.update_rate
                msg.plugin_name = getattr(component.info, 'plugin', '')
                msg.class_type = msg.plugin_name
                msg.state.id = _STATE_IDS.get(component.lifecycle_state, 0)
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

    # ----------------------------------------------------------------- controller API
    def _controller_parameters(self, name):
        """Return the flat parameters of controller ``name`` from every YAML source."""
        values = {}
        files = list(self._yaml_files)
        key = f'{name}.params_file'
        if self.has_parameter(key):
            for path in ros_param_file.parse_params_file_value(self.get_parameter(key).value):
                files.append((path, ros_param_file.load_yaml(path)))
        for path, data in files:
            values.update(ros_param_file.parameters_for_node(
                data, name, self.get_namespace(), path))
        values['use_sim_time'] = self.use_sim_time
        return values

    def load_controller(self, name):
        """
        Load controller ``name`` by its ``<name>.type`` parameter (state: unconfigured).

        :param name: controller name.
        :returns: the controller node, or None after logging a one-line error.
        """
        log = self.get_logger()
        with self._lock:
            if name in self.controllers:
                log.error(f"Controller already loaded, skipping load_controller: '{name}'")
                return None
            key = f'{name}.type'
            if not self.has_parameter(key) or not self.get_parameter(key).value:
                log.error(f"The 'type' param was not defined for '{name}'.")
                return None
            type_name = str(self.get_parameter(key).value)
            log.info(f"Loading controller : '{name}' of type '{type_name}'")
            types = controller_types()
            if type_name not in types:
                log.error(f"Loader for controller '{name}' (type '{type_name}') not found. "
                          f"Available types: {', '.join(sorted(types))}")
                return None
            try:
                cls = types[type_name].load()
                params = self._controller_parameters(name)
                params.pop('type', None)
                overrides, skipped = parameters_from_dict(params)
                ctrl = cls(name, namespace=self.get_namespace(), parameter_overrides=overrides,
                           robot_description=self.robot_description,
                           update_rate=self.update_rate, context=self.context)
            except Exception as exc:  # noqa: B902 - any plugin failure is reported, not raised
                log.error(f"Could not initialize the controller named '{name}': {exc}")
                return None
            for param in skipped:
                ctrl.get_logger().warn(f"Parameter '{param}' has an unsupported value: ignored")
            ctrl.controller_type = type_name
            self.controllers[name] = ctrl
            self._executor.add_node(ctrl)
            return ctrl

    def configure_controller(self, name):
        """
        Configure controller ``name`` (unconfigured or inactive -> inactive).

        :returns: True on success; False with a one-line error log otherwise.
        """
        log = self.get_logger()
        with self._lock:
            ctrl = self.controllers.get(name)
            if ctrl is None:
                log.error(f"Controller '{name}' is not loaded")
                return False
            state = ctrl.lifecycle_state
            if state == 'active':
                log.error(f"Controller '{name}' can not be configured from 'active' state.")
                return False
            if state == 'inactive':
                log.debug(f"Controller '{name}' is cleaned-up before configuring")
                ctrl.trigger_cleanup()
            log.info(f"Configuring controller: '{name}'")
            ctrl.trigger_configure()
            if ctrl.lifecycle_state != 'inactive':
                log.error(f"After configuring, controller '{name}' is in state "
                          f"'{ctrl.lifecycle_state}' , expected inactive.")
                return False
            return True

    def cleanup_controller(self, name):
        """Clean up an inactive controller (-> unconfigured); returns True on success."""
        with self._lock:
            ctrl = self.controllers.get(name)
            if ctrl is None or ctrl.lifecycle_state != 'inactive':
                self.get_logger().error(f"Controller '{name}' can not be cleaned-up: it is "
                                        'not loaded and inactive')
                return False
            ctrl.trigger_cleanup()
            return ctrl.lifecycle_state == 'unconfigured'

    def unload_controller(self, name):
        """Unload a non-active controller and destroy its node; returns True on success."""
        log = self.get_logger()
        with self._lock:
            ctrl = self.controllers.get(name)
            if ctrl is None:
                log.error(f"Could not unload controller with name '{name}' because no "
                          'controller with this name exists')
                return False
            if ctrl.lifecycle_state == 'active':
                log.error(f"Could not unload controller with name '{name}' because it is "
                          'still active')
                return False
            log.info(f"Unloading controller: '{name}'")
            if ctrl.lifecycle_state == 'inactive':
                ctrl.trigger_cleanup()
            del self.controllers[name]
        self._executor.remove_node(ctrl)
        ctrl.destroy_node()
        return True

    def switch_controller(self, activate, deactivate, strictness=2, timeout=0.0,
                          wait=True):
        """
        Request activation/deactivation; performed by the next :meth:`update`.

        :param activate: controller names to activate (must be inactive).
        :param deactivate: controller names to deactivate (must be active).
        :param strictness: 1 BEST_EFFORT (skip what cannot be switched), else STRICT.
        :param timeout: seconds to wait for the update thread (0: 1 s).
        :param wait: False to return right after queueing (the caller runs update()).
        :returns: (ok, message).
        """
        log = self.get_logger()
        strict = strictness != 1
        with self._lock:
            act, deact, problems = [], [], []
            for name in deactivate:
                ctrl = self.controllers.get(name)
                if ctrl is None:
                    problems.append(f"Could not deactivate controller '{name}': not loaded")
                elif ctrl.lifecycle_state != 'active':
                    if ctrl.lifecycle_state != 'inactive':
                        problems.append(f"Could not deactivate controller '{name}': it is "
                                        f"'{ctrl.lifecycle_state}'")
                elif name not in deact:
                    deact.append(name)
            claims = {}
            for name in activate:
                ctrl = self.controllers.get(name)
                if ctrl is None:
                    problems.append(f"Could not activate controller '{name}': not loaded")
                    continue
                if ctrl.lifecycle_state == 'active':
                    if name in deact:
                        act.append(name)  # restart
                    else:
                        log.warn(f"Controller '{name}' is already active, skipping")
                    continue
                if ctrl.lifecycle_state != 'inactive':
                    problems.append(f"Could not activate controller '{name}': it is "
                                    f"'{ctrl.lifecycle_state}' (configure it first)")
                    continue
                conflict = self._claim_conflict(ctrl, deact, claims)
                if conflict:
                    problems.append(conflict)
                    continue
                for iface in ctrl.command_interface_configuration() or []:
                    claims[iface] = name
                act.append(name)
            for problem in problems:
                log.error(problem) if strict else log.warn(problem)
            if problems and strict:
                return False, '; '.join(problems)
            if not act and not deact:
                return True, 'nothing to switch'
            request = _Switch(act, deact)
            self._pending = request
        if not wait:
            return True, 'queued'
        timeout = timeout if timeout > 0.0 else DEFAULT_SWITCH_TIMEOUT
        if not request.done.wait(timeout):
            with self._lock:
                if not request.done.is_set():
                    if self._pending is request:
                        self._pending = None
                    log.error(f'Switch controller timed out after {timeout} seconds!')
                    return False, 'timed out waiting for the update loop'
        return request.ok, request.message

    def _claim_conflict(self, ctrl, deactivating, claims):
        rm = self.resource_manager
        for iface in ctrl.command_interface_configuration() or []:
            if iface not in rm.command_interfaces:
                return (f"Could not activate controller '{ctrl.get_name()}': command "
                        f"interface '{iface}' does not exist")
            if not rm.command_interface_available(iface):
                return (f"Could not activate controller '{ctrl.get_name()}': command "
                        f"interface '{iface}' is not available")
            owner = rm.claimed.get(iface)
            if owner is not None and owner not in deactivating:
                return (f"Could not activate controller '{ctrl.get_name()}': command "
                        f"interface '{iface}' is already claimed by '{owner}'")
            if iface in claims:
                return (f"Could not activate controller '{ctrl.get_name()}': command "
                        f"interface '{iface}' is also requested by '{claims[iface]}'")
        state = ctrl.state_interface_configuration()
        for iface in (state or []):
            if iface not in rm.state_interfaces:
                return (f"Could not activate controller '{ctrl.get_name()}': state "
                        f"interface '{iface}' does not exist")
        return None

    # ----------------------------------------------------------------- realtime side
    def _deactivate(self, name):
        ctrl = self.controllers[name]
        if ctrl.lifecycle_state == 'active':
            try:
                ctrl.trigger_deactivate()
            except Exception:  # noqa: B902 - e.g. context already shut down
                ctrl.on_deactivate(None)
        ctrl.release_interfaces()
        self.resource_manager.release(name)

    def _activate(self, name):
        rm = self.resource_manager
        ctrl = self.controllers[name]
        try:
            command = rm.claim(name, ctrl.command_interface_configuration() or [])
        except ValueError as exc:
            return f"Could not activate controller '{name}': {exc}"
        wanted = ctrl.state_interface_configuration()
        names = list(rm.state_interfaces) if wanted is None else wanted
        state = {n: rm.state_interfaces[n] for n in names if n in rm.state_interfaces}
        ctrl.assign_interfaces(command, state)
        ctrl.last_update_time = None
        ctrl.trigger_activate()
        if ctrl.lifecycle_state != 'active':
            ctrl.release_interfaces()
            rm.release(name)
            return (f"After activating, controller '{name}' is in state "
                    f"'{ctrl.lifecycle_state}', expected 'active'")
        return None

    def _apply_switch(self, request):
        errors = []
        for name in request.deactivate:
            self._deactivate(name)
        for name in request.activate:
            error = self._activate(name)
            if error:
                errors.append(error)
                self.get_logger().error(error)
        request.ok = not errors
        request.message = '; '.join(errors) or 'switched'
        request.done.set()

    def update(self, time, period):
        """
        One control cycle: pending switch, read, update active controllers, write.

        :param time: current time in seconds (sim time when simulated).
        :param period: seconds since the previous update.
        """
        if not self.context.ok():
            return
        with self._lock:
            if self._pending is not None:
                request, self._pending = self._pending, None
                self._apply_switch(request)
            log = self.get_logger()
            for failed in self.resource_manager.read(time, period):
                log.error(f"Error in read of hardware component '{failed}'", once=True)
            for name, ctrl in list(self.controllers.items()):
                if ctrl.lifecycle_state != 'active':
                    continue
                try:
                    ok = ctrl.update(time, period)
                except Exception as exc:  # noqa: B902 - a faulty controller must not stop us
                    ok = False
                    log.error(f"Exception in update of controller '{name}': {exc}")
                if not ok:
                    log.error(f"Error in update of controller '{name}': deactivating it")
                    self._deactivate(name)
            for failed in self.resource_manager.write(time, period):
                log.error(f"Error in write of hardware component '{failed}'", once=True)

    def shutdown(self):
        """Deactivate every controller, destroy their nodes and shut the hardware down."""
        with self._lock:
            if self._pending is not None:
                self._pending.message = 'controller manager shutting down'
                self._pending.done.set()
                self._pending = None
            for name in list(self.controllers):
                ctrl = self.controllers.pop(name)
                try:
                    if ctrl.lifecycle_state == 'active':
                        try:
                            ctrl.trigger_deactivate()
                        except Exception:  # noqa: B902 - context gone: zero the wheels
                            ctrl.on_deactivate(None)
                    self._executor.remove_node(ctrl)
                    ctrl.destroy_node()
                except Exception:  # noqa: B902 - best effort at shutdown
                    pass
            self.resource_manager.shutdown()


def _mock_factory(info):
    from amr_description.control.generic_system import GenericSystem
    return GenericSystem()


def main(args=None):
    """
    Run a controller manager standalone (ros2_control_node), wall-clock loop.

    Options: ``--urdf FILE`` (required), ``--params FILE`` (controllers YAML),
    ``--mock-hardware`` (every component is ``mock_components/GenericSystem``),
    ``--use-sim-time``; ROS arguments after ``--ros-args``.

    :returns: exit code: 0 after Ctrl-C, 1 on a configuration error (one line).
    """
    argv = sys.argv[1:] if args is None else list(args)
    ros_args = argv[argv.index('--ros-args'):] if '--ros-args' in argv else []
    own = argv[:len(argv) - len(ros_args)]
    parser = argparse.ArgumentParser(prog='controller_manager')
    parser.add_argument('--urdf', required=True, help='robot description (URDF file)')
    parser.add_argument('--params', default=None, help='controllers YAML file')
    parser.add_argument('--mock-hardware', action='store_true',
                        help='replace every hardware plugin by mock_components/GenericSystem')
    parser.add_argument('--use-sim-time', action='store_true')
    parser.add_argument('-n', '--namespace', default='')
    opts = parser.parse_args(own)
    try:
        with open(opts.urdf, 'r') as f:
            urdf = f.read()
    except OSError as exc:
        print(f'controller_manager: cannot read {opts.urdf}: {exc.strerror}', file=sys.stderr)
        return 1
    rclpy.init(args=['controller_manager'] + ros_args)
    executor = rclpy.executors.MultiThreadedExecutor(num_threads=2)
    cm = None
    thread = None
    stop = threading.Event()
    try:
        try:
            cm = ControllerManager(
                urdf, executor, _mock_factory if opts.mock_hardware else None,
                opts.params, opts.namespace, use_sim_time=opts.use_sim_time)
        except ValueError as exc:
            print(f'controller_manager: {exc}', file=sys.stderr)
            return 1

        def loop():
            period = 1.0 / cm.update_rate
            start = _time.monotonic()
            previous = 0.0
            k = 0
            while not stop.is_set() and cm.context.ok():
                k += 1
                target = start + k * period
                delay = target - _time.monotonic()
                if delay > 0:
                    stop.wait(delay)
                now = _time.monotonic() - start
                t = cm.get_clock().now().nanoseconds * 1e-9 if opts.use_sim_time else \
                    _time.time()
                cm.update(t, now - previous)
                previous = now

        thread = threading.Thread(target=loop, daemon=True)
        thread.start()
        cm.get_logger().info(f'update rate is {cm.update_rate} Hz')
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        stop.set()
        if thread is not None:
            thread.join(timeout=2.0)
        if cm is not None:
            cm.shutdown()
            cm.destroy_node()
        executor.shutdown()
        if rclpy.ok():
            rclpy.try_shutdown()
    return 0


if __name__ == '__main__':
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    sys.exit(main())
