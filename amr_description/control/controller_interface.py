# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Base class of the controllers run by :class:`ControllerManager`.

As ros2_control's ``controller_interface::ControllerInterface`` (jazzy): a controller is a
lifecycle node named after the controller, created by the controller manager with its
parameters from the controllers YAML; it declares the command interfaces it claims and the
state interfaces it reads (``'<joint>/<interface>'`` names), receives the handles before
activation and is updated by the manager with ``update(time, period)`` (seconds) while active.

Subclasses override :meth:`on_init` (declare parameters with :meth:`auto_declare`),
the rclpy lifecycle callbacks ``on_configure(state)``/``on_activate``/``on_deactivate``/
``on_cleanup`` (return :class:`TransitionCallbackReturn`), :meth:`command_interface_configuration`,
:meth:`state_interface_configuration` and :meth:`update`.
"""

from amr_description.ros.node import LifecycleNode
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.lifecycle import TransitionCallbackReturn
from rclpy.parameter import Parameter

__all__ = ['ControllerInterface', 'TransitionCallbackReturn']


class ControllerInterface(LifecycleNode):
    """
    A controller: lifecycle node + interface configuration + realtime ``update``.

    :param name: controller (and node) name.
    :param namespace: node namespace ('' = root).
    :param parameter_overrides: list of :class:`rclpy.parameter.Parameter` from the YAML.
    :param robot_description: URDF XML of the robot (str), available as
        ``self.robot_description`` in :meth:`on_init` and later.
    :param update_rate: controller-manager update rate (Hz): the default of the controller's
        ``update_rate`` parameter (reported in list_controllers, as ``is_async``).
    :param node_kwargs: further keyword arguments of :class:`rclpy.node.Node` (``context``,
        ``cli_args``, ``use_global_arguments``).
    :raises RuntimeError: when :meth:`on_init` returns False (message names the controller).
    """

    def __init__(self, name, namespace='', parameter_overrides=None, robot_description='',
                 update_rate=100, **node_kwargs):
        """Create the node and call :meth:`on_init` (see the class docstring)."""
        own = list(parameter_overrides or [])
        super().__init__(
            name, namespace=namespace, parameter_overrides=own,
            allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=False,
            enable_communication_interface=False, **node_kwargs)
        # declared from the controller's own parameters (its YAML, as the manager gives
        # them), not from every override of the process: a '/**' parameter file meant for
        # the simulator hosting the manager (headless, real_time_factor, ...) must not show
        # up in the controller's parameters; a global override of a parameter the controller
        # declares still applies to it
        self.declare_parameters('', [(p.name, p.value, ParameterDescriptor()) for p in own
                                     if not self.has_parameter(p.name)])
        self.robot_description = robot_description or ''
        # the parsed robot_description (RobotDescription) when the manager has one, else None
        self.description = None
        # as upstream's ControllerInterfaceBase::init: the controller's own update rate
        # (default: the manager's), whether it runs asynchronously, and its thread priority
        self.update_rate = int(self.auto_declare(
            'update_rate', int(update_rate), 'Update rate of the controller (Hz)'))
        self.is_async = bool(self.auto_declare(
            'is_async', False, 'Whether the controller updates in its own thread'))
        self.auto_declare('thread_priority', 50,
                          'Priority of the thread of an asynchronous controller')
        self.command_interfaces = {}
        self.state_interfaces = {}
        self.last_update_time = None
        if not self.on_init():
            raise RuntimeError(f"Could not initialize the controller named '{name}'")

    # ----------------------------------------------------------------- parameters
    def auto_declare(self, name, default, description='', read_only=False):
        """
        Declare parameter ``name`` with ``default`` unless given, and return its value.

        Overrides from the YAML win; an override of another numeric type than the default is
        converted (``1`` for a double parameter gives ``1.0``). As upstream (parameters
        declared by generate_parameter_library), a parameter declared here carries
        ``description`` and ``read_only`` in its descriptor (``ros2 param describe``); one
        already declared from the YAML keeps a plain descriptor.

        :param name: parameter name, e.g. ``'linear.x.max_velocity'``.
        :param default: default value (its type decides the conversion).
        :param description: text of the parameter descriptor.
        :param read_only: whether the parameter can not be changed after declaration.
        :returns: the parameter value.
        """
        if not self.has_parameter(name):
            from rcl_interfaces.msg import ParameterDescriptor
            self.declare_parameter(name, default, ParameterDescriptor(
                description=description, read_only=read_only))
        return self.param(name, default)

    def param(self, name, default=None):
        """
        Return the current value of parameter ``name`` converted like ``default``.

        :raises ValueError: when the value cannot be converted (message names the parameter).
        """
        value = self.get_parameter(name).value if self.has_parameter(name) else None
        if value is None:
            return default
        try:
            if isinstance(default, bool):
                if isinstance(value, str):
                    return value.strip().lower() in ('true', '1', 'yes', 'on')
                return bool(value)
            if isinstance(default, float):
                return float(value)
            if isinstance(default, int):
                return int(value)
            if isinstance(default, list):
                if isinstance(value, str):
                    return [value] if value else []
                items = list(value)
                if default and isinstance(default[0], float):
                    return [float(v) for v in items]
                return items
            if isinstance(default, str):
                return str(value)
        except (TypeError, ValueError):
            raise ValueError(
                f'parameter {name!r}: expected {type(default).__name__}, got {value!r}'
            ) from None
        return value

    # ----------------------------------------------------------------- interfaces
    def on_init(self):
        """Declare parameters; returns True on success (default: nothing to declare)."""
        return True

    def command_interface_configuration(self):
        """Return the command interface names this controller claims (list of str)."""
        return []

    def state_interface_configuration(self):
        """Return the state interface names it reads (list of str), or None for all."""
        return []

    def assign_interfaces(self, command_interfaces, state_interfaces):
        """
        Receive handles before ``on_activate``.

        :param command_interfaces: dict name -> Handle, the claimed command interfaces.
        :param state_interfaces: dict name -> Handle, the available state interfaces.
        """
        self.command_interfaces = dict(command_interfaces)
        self.state_interfaces = dict(state_interfaces)

    def release_interfaces(self):
        """Forget the handles (after ``on_deactivate``)."""
        self.command_interfaces = {}
        self.state_interfaces = {}

    def update(self, time, period):
        """
        Run one control step.

        :param time: current time (s, sim time when simulated).
        :param period: time since the previous update (s).
        :returns: True when OK, False on error (the manager then deactivates the controller).
        """
        return True

    def now_seconds(self):
        """Return "now" in seconds: the last update time, else the node clock."""
        if self.last_update_time is not None:
            return self.last_update_time
        return self.get_clock().now().nanoseconds * 1e-9

    def destroy(self):
        """
        Destroy the node and every entity it created, leaving nothing in the ROS graph.

        The lifecycle state machine holds the node handle, so it is destroyed first; then
        the node (its publishers, subscriptions, timers, services and parameter services).
        """
        machine = getattr(self, '_state_machine', None)
        if machine is not None:
            try:
                machine.destroy_when_not_in_use()
            except Exception:  # noqa: B902 - already destroyed
                pass
        self.destroy_node()

    @property
    def lifecycle_state(self):
        """Return the lifecycle state label: unconfigured, inactive, active, finalized."""
        return self._state_machine.current_state[1]


def parameters_from_dict(values):
    """
    Return a list of :class:`rclpy.parameter.Parameter` from a flat dict name -> value.

    Values whose type rclpy cannot infer (mixed lists, nested) are skipped.

    :param values: dict str -> YAML value.
    :returns: (list of Parameter, list of skipped names).
    """
    params, skipped = [], []
    for name, value in values.items():
        if isinstance(value, list) and value and all(isinstance(v, (int, float)) for v in value) \
                and any(isinstance(v, float) for v in value):
            value = [float(v) for v in value]
        try:
            params.append(Parameter(name, value=value))
        except Exception:  # noqa: B902 - rclpy raises several types for unsupported values
            skipped.append(name)
    return params, skipped
