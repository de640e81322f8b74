# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Controller manager: loads controllers and runs read -> update -> write.

As ros2_control's ``controller_manager`` (jazzy): an rclpy node ``controller_manager`` whose
parameters come from the controllers YAML (same format; ``update_rate`` default 100 Hz and
read-only, ``<controller>.type``, ``<controller>.params_file`` and
``<controller>.node_options_args`` — the upstream spawner sets the last three through the
parameter services) and which serves, under ``~/``, ``list_controllers``,
``list_controller_types``, ``load_controller``, ``configure_controller``,
``cleanup_controller``, ``switch_controller``, ``unload_controller``,
``reload_controller_libraries``, ``list_hardware_interfaces``, ``list_hardware_components``
and ``set_hardware_component_state`` (controller_manager_msgs), and publishes
``~/activity`` (``ControllerManagerActivity``, reliable, transient local, depth 1) whenever a
controller or hardware component changes lifecycle state.

Controllers are found by their ``type`` in the entry-point group
``amr_description.controllers``; each is a lifecycle node named after it, with its parameters
from the YAML (and ``use_sim_time``), the node arguments of ``<name>.node_options_args`` (e.g.
``['-r', '~/cmd_vel:=/x']``), which win over the process' global arguments. The owner's
control thread calls ``read``, ``update`` and ``write`` each cycle
(:mod:`amr_description.control.realtime_loop`). Switches requested through the service happen
at the next update; the service waits for it up to the request's timeout (0: 1 s), as
upstream. :meth:`ControllerManager.destroy` leaves nothing of the manager in the ROS graph.
Run standalone with :mod:`amr_description.nodes.ros2_control_node`.
"""

import threading

from amr_description.control import hardware_interface as hi
from amr_description.control.controller_interface import parameters_from_dict
from amr_description.control.manager_services import controller_types
from amr_description.control.manager_services import list_value
from amr_description.control.manager_services import ManagerServices
from amr_description.control.manager_services import STATE_IDS
from amr_description.control.realtime_loop import PendingSwitch
from amr_description.control.realtime_loop import RealtimeLoop
from amr_description.control.resource_manager import ResourceManager
from amr_description.control.switch_plan import ControllerSpec
from amr_description.control.switch_plan import plan_switch
from amr_description.control.switch_plan import Resources
from amr_description.core import ros_param_file
from amr_description.ros.node import Node

DEFAULT_SWITCH_TIMEOUT = 1.0
BEST_EFFORT, STRICT = 1, 2

_STATE_LABELS = {v: k for k, v in STATE_IDS.items()}


class ControllerManager(RealtimeLoop, ManagerServices, Node):
    """
    The controller manager node (see the module docstring).

    :param urdf_xml: robot description with ``<ros2_control>`` blocks: URDF XML (str), or
        its :class:`~amr_description.core.description.robot_description.RobotDescription` (the
        simulator parses a spawned robot once and hands it on).
    :param executor: rclpy executor; the manager adds itself and every controller node.
    :param hardware_factory: ``(HardwareInfo) -> SystemInterface`` (default: entry points).
    :param parameters_file: path of the controllers YAML, a list of paths (a later file
        overrides an earlier one, as rcl's ``--params-file``), or None.
    :param namespace: node namespace of the manager and its controllers.
    :param use_sim_time: set ``use_sim_time`` on the manager and every controller.
    :param name: node name (gz_ros2_control's ``<controller_manager_name>``).
    :param remappings: remapping rules (``from:=to``) of the manager and its controllers
        (gz_ros2_control's ``<ros><remapping>``).
    :raises ValueError: one line when the URDF, its ``<ros2_control>`` blocks or the
        parameter file are invalid.
    """

    def __init__(self, urdf_xml, executor, hardware_factory=None, parameters_file=None,
                 namespace='', use_sim_time=True, name='controller_manager', remappings=()):
        """Create the node, the hardware and the services (see the class docstring)."""
        self._remap_args = ['--ros-args'] + [a for rule in remappings for a in ('-r', rule)] \
            if remappings else []
        self._yaml_files = []
        own = {}
        files = [parameters_file] if isinstance(parameters_file, str) else parameters_file
        for path in files or ():  # a later file overrides an earlier one, as --params-file
            data = ros_param_file.load_yaml(path)
            self._yaml_files.append((path, data))
            own.update(ros_param_file.parameters_for_node(
                data, name, namespace, path))
        own['use_sim_time'] = bool(use_sim_time)
        overrides, skipped = parameters_from_dict(own)
        super().__init__(
            name, namespace=namespace, context=executor.context,
            parameter_overrides=overrides, allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=False,
            cli_args=self._remap_args or None)
        self._executor = executor
        self._destroyed = False
        try:
            self._setup(urdf_xml, hardware_factory, overrides, skipped, use_sim_time)
        except BaseException:
            # a rejected robot leaves nothing in the ROS graph
            self._destroyed = True
            for cleanup in (lambda: executor.remove_node(self), self.destroy_node):
                try:
                    cleanup()
                except Exception:  # noqa: B902 - the node may not be added yet
                    pass
            raise

    def _setup(self, urdf_xml, hardware_factory, overrides, skipped, use_sim_time):
        """Declare parameters, build the hardware and services, join the executor."""
        self.update_rate = self._declare_parameters(overrides, skipped)
        self.description = urdf_xml if hasattr(urdf_xml, 'hardware') else None
        self.robot_description = urdf_xml.xml if self.description is not None else urdf_xml
        self.use_sim_time = bool(use_sim_time)
        self._lock = threading.RLock()
        self._pending = None
        self.controllers = {}  # name -> controller node, in load order
        self._last_update = {}  # controller name -> time of its last update (s)
        self.resource_manager = ResourceManager(urdf_xml, hardware_factory)
        self.get_logger().info(
            f'Resource manager: {len(self.resource_manager.components)} hardware component(s) '
            f'active, {len(self.resource_manager.command_interfaces)} command and '
            f'{len(self.resource_manager.state_interfaces)} state interfaces')
        self._create_services()
        self._executor.add_node(self)
        self._publish_activity()

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

    def _node_options_args(self, name):
        """Return the rcl arguments of controller ``name`` ('--ros-args' first) or []."""
        key = f'{name}.node_options_args'
        args = list_value(self.get_parameter(key).value) if self.has_parameter(key) else []
        if args and args[0] != '--ros-args':
            args = ['--ros-args'] + args
        if self._remap_args:  # the manager's remappings reach its controllers too
            args = self._remap_args + args[1:] if args else list(self._remap_args)
        return args

    def load_controller(self, name):
        """
        Load controller ``name`` by its ``<name>.type`` parameter (state: unconfigured).

        The node gets the arguments of ``<name>.node_options_args`` (which win over the
        process' global arguments, e.g. a remapping given to the simulator; upstream still
        honours those too, deprecated).

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
            ctrl = None
            try:
                cls = types[type_name].load()
                params = self._controller_parameters(name)
                params.pop('type', None)
                overrides, skipped = parameters_from_dict(params)
                cli_args = self._node_options_args(name)
                if cli_args:
                    log.info(f"Controller '{name}' node arguments: {' '.join(cli_args)}")
                ctrl = cls(name, namespace=self.get_namespace(), parameter_overrides=overrides,
                           robot_description=self.robot_description,
                           update_rate=self.update_rate, context=self.context,
                           cli_args=cli_args or None)
            except Exception as exc:  # noqa: B902 - any plugin failure is reported, not raised
                log.error(f"Could not initialize the controller named '{name}': {exc}")
                return None
            for param in skipped:
                ctrl.get_logger().warn(f"Parameter '{param}' has an unsupported value: ignored")
            ctrl.controller_type = type_name
            ctrl.description = self.description
            self.controllers[name] = ctrl
            self._executor.add_node(ctrl)
        self._publish_activity()
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
            ok = ctrl.lifecycle_state == 'inactive'
            if not ok:
                log.error(f"After configuring, controller '{name}' is in state "
                          f"'{ctrl.lifecycle_state}' , expected inactive.")
        self._publish_activity()
        return ok

    def cleanup_controller(self, name):
        """
        Clean up an inactive (or unconfigured) controller -> unconfigured.

        :returns: True on success; False with a one-line error log otherwise.
        """
        log = self.get_logger()
        with self._lock:
            ctrl = self.controllers.get(name)
            if ctrl is None:
                log.error(f"Could not cleanup controller with name '{name}' because no "
                          'controller with this name exists')
                return False
            state = ctrl.lifecycle_state
            if state == 'unconfigured':
                log.debug(f"Controller '{name}' is already unconfigured")
                return True
            if state != 'inactive':
                log.error(f"Controller '{name}' can not be cleaned-up from '{state}' state")
                return False
            log.info(f"Cleaning-up controller: '{name}'")
            ctrl.trigger_cleanup()
            ok = ctrl.lifecycle_state == 'unconfigured'
            if not ok:
                log.error(f"After cleaning-up, controller '{name}' is in state "
                          f"'{ctrl.lifecycle_state}' , expected unconfigured.")
        self._publish_activity()
        return ok

    def _destroy_controller(self, ctrl):
        """Remove ``ctrl`` from the executor and destroy its node and every entity of it."""
        try:
            self._executor.remove_node(ctrl)
        except Exception:  # noqa: B902 - executor already shut down
            pass
        destroy = getattr(ctrl, 'destroy', None)
        if destroy is not None:
            destroy()
        else:
            ctrl.destroy_node()

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
            self._last_update.pop(name, None)
        self._destroy_controller(ctrl)
        log.info(f"Successfully unloaded controller '{name}'")
        self._publish_activity()
        return True

    def reload_controller_libraries(self, force_kill=False):
        """
        Forget and re-read the controller plugins (entry points), as upstream.

        Refused (one error line, False) while a controller is active unless ``force_kill``,
        which first deactivates and unloads every controller.

        :returns: True on success.
        """
        log = self.get_logger()
        with self._lock:
            active = [n for n, c in self.controllers.items() if c.lifecycle_state == 'active']
            loaded = list(self.controllers)
        if active and not force_kill:
            log.error('Controller manager: Cannot reload controller libraries because there '
                      f'are still {len(active)} active controllers')
            return False
        if loaded:
            if active:
                log.info('Controller manager: Stopping all active controllers')
                ok, _ = self.switch_controller([], active, BEST_EFFORT, wait=True)
                if not ok:
                    log.error('Controller manager: Cannot reload controller libraries because '
                              'failed to stop active controllers')
                    return False
            for name in loaded:
                if not self.unload_controller(name):
                    log.error('Controller manager: Cannot reload controller libraries because '
                              f"failed to unload controller '{name}'")
                    return False
        import importlib
        importlib.invalidate_caches()
        log.info("Controller manager: reloaded controller libraries for 'controller_interface'")
        return True

    def set_hardware_component_state(self, name, target_id, target_label=''):
        """
        Move hardware component ``name`` to the lifecycle state ``target_id``.

        Controllers that claimed a command interface of a component leaving ``active`` are
        deactivated first (their interfaces become unavailable).

        :param name: component name (``<ros2_control name=...>``).
        :param target_id: ``lifecycle_msgs/State`` id (1 unconfigured, 2 inactive, 3 active,
            4 finalized); 0 takes the state from ``target_label``.
        :param target_label: the state label, used when ``target_id`` is 0.
        :returns: (ok, label of the state the component is in afterwards).
        """
        log = self.get_logger()
        rm = self.resource_manager
        with self._lock:
            component = rm.component(name)
            if component is None:
                log.error(f"hardware component with name '{name}' does not exist")
                return False, 'unknown'
            target = _STATE_LABELS.get(int(target_id)) if target_id else target_label
            if target not in (hi.UNCONFIGURED, hi.INACTIVE, hi.ACTIVE, hi.FINALIZED):
                log.error(f"hardware component '{name}': unknown target state "
                          f'{target_id} {target_label!r}')
                return False, component.lifecycle_state
            if component.lifecycle_state == hi.FINALIZED and target != hi.FINALIZED:
                log.error(f"hardware component '{name}' is finalized: it can not be moved "
                          f"to '{target}'")
                return False, component.lifecycle_state
            if target != hi.ACTIVE:
                own = {h.name for h in component.export_command_interfaces()}
                for ctrl_name, ctrl in self.controllers.items():
                    if ctrl.lifecycle_state == 'active' and own & set(
                            rm.claimed_by(ctrl_name)):
                        log.warn(f"Deactivating controller '{ctrl_name}': hardware component "
                                 f"'{name}' goes to '{target}'")
                        self._deactivate(ctrl_name)
            log.info(f"Setting hardware component '{name}' to state '{target}'")
            try:
                rm.set_component_state(component, target)
                ok = component.lifecycle_state == target
            except ValueError as exc:
                log.error(str(exc))
                ok = False
            label = component.lifecycle_state
        self._publish_activity()
        return ok, label

    def switch_controller(self, activate, deactivate, strictness=STRICT, timeout=0.0,
                          wait=True):
        """
        Request activation/deactivation; performed by the next :meth:`update`.

        As upstream: strictness 1 BEST_EFFORT (skip what cannot be switched, with a
        warning), 2 STRICT (switch nothing when anything is wrong); 0 (unset) is treated as
        BEST_EFFORT with a warning; AUTO (3) and FORCE_AUTO (4) as STRICT (we have no chained
        controllers to add). A request naming only controllers that cannot be switched fails
        under either strictness.

        :param activate: controller names to activate (must be inactive).
        :param deactivate: controller names to deactivate (must be active).
        :param strictness: see above.
        :param timeout: seconds to wait for the update thread (0: 1 s).
        :param wait: False to return right after queueing (the caller runs update()).
        :returns: (ok, message), the message as upstream ("Successfully switched
            controllers!", or what failed).
        """
        log = self.get_logger()
        if strictness == 0:
            log.warn('Controller Manager: to switch controllers you need to specify a '
                     f'strictness level of STRICT ({STRICT}) or BEST_EFFORT ({BEST_EFFORT}). '
                     'Defaulting to BEST_EFFORT')
            strictness = BEST_EFFORT
        strict = strictness != BEST_EFFORT
        with self._lock:
            plan = plan_switch(activate, deactivate, self.specs(), self.resources())
            act, deact, problems = plan.activate, plan.deactivate, plan.problems
            for problem in problems:
                log.error(problem) if strict else log.warn(problem)
            if problems and strict:
                message = '; '.join(problems) + \
                    " Aborting, no controller is switched! ('STRICT' switch)"
                log.error("Aborting, no controller is switched! ('STRICT' switch)")
                return False, message
            if not act and not deact:
                if problems:
                    return False, '; '.join(problems)
                message = ('After checking the controllers, no controllers need to be '
                           'activated or deactivated.')
                log.info(message)
                return True, message
            if deact:
                log.info(f"Deactivating controllers: [ {' '.join(deact)} ]")
            if act:
                log.info(f"Activating controllers: [ {' '.join(act)} ]")
            request = PendingSwitch(act, deact)
            request.problems = problems
            self._pending = request
        if not wait:
            return True, 'queued'
        timeout = timeout if timeout > 0.0 else DEFAULT_SWITCH_TIMEOUT
        if not request.done.wait(timeout):
            with self._lock:
                if not request.done.is_set():
                    if self._pending is request:
                        self._pending = None
                    message = f'Switch controller timed out after {timeout} seconds!'
                    log.error(message)
                    return False, message
        return request.ok, request.message

    def specs(self):
        """Return dict name -> :class:`ControllerSpec` of every loaded controller."""
        specs = {}
        for name, ctrl in self.controllers.items():
            state = ctrl.state_interface_configuration()
            specs[name] = ControllerSpec(
                name, getattr(ctrl, 'controller_type', ''), ctrl.lifecycle_state,
                tuple(ctrl.command_interface_configuration() or ()),
                None if state is None else tuple(state))
        return specs

    def resources(self):
        """Return the resource manager's interfaces as a :class:`Resources`."""
        rm = self.resource_manager
        return Resources(
            frozenset(rm.command_interfaces),
            frozenset(n for n in rm.command_interfaces if rm.command_interface_available(n)),
            dict(rm.claimed), frozenset(rm.state_interfaces))

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
                    self._destroy_controller(ctrl)
                except Exception:  # noqa: B902 - best effort at shutdown
                    pass
            self.resource_manager.shutdown()

    def destroy(self):
        """
        Leave nothing in the ROS graph: :meth:`shutdown`, then destroy this node.

        Removes the manager from its executor first; safe to call twice.
        """
        if self._destroyed:
            return
        self.shutdown()
        self._destroyed = True
        try:
            self._executor.remove_node(self)
        except Exception:  # noqa: B902 - executor already shut down
            pass
        self.destroy_node()
