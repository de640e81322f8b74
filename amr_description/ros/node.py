# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The one Node base of every node of the package (nodes, controller manager, controllers).

rcl parses ``-p real_time_factor:=0`` as an integer and rclpy (like rclcpp) then refuses it
for a parameter whose default is a float, which users do not expect. :class:`Node` and
:class:`LifecycleNode` accept such a whole number as that float, and stop the node's
:class:`~amr_description.ros.take_loop.TakeLoop` threads before destroying it; everything else
is rclpy's.
"""

from amr_description.ros.take_loop import stop_loops_of
import rclpy.lifecycle
import rclpy.node
from rclpy.parameter import Parameter


class Node(rclpy.node.Node):
    """
    ``rclpy.node.Node`` that accepts a whole number for a floating-point parameter.

    When a parameter is declared with a float default (or type ``Parameter.Type.DOUBLE``) and
    its override (``--ros-args -p`` or a parameters file) is an integer, the override is
    converted to that float before rclpy checks its type. Everything else is rclpy's.
    """

    def declare_parameters(self, namespace, parameters, ignore_override=False):
        """Declare as rclpy does, after converting whole-number overrides of float parameters."""
        for parameter in parameters:
            name, value = parameter[0], parameter[1] if len(parameter) > 1 else None
            full = f'{namespace}.{name}' if namespace else name
            override = self._parameter_overrides.get(full)
            wants_float = isinstance(value, float) or value == Parameter.Type.DOUBLE
            if override is not None and wants_float and \
                    override.type_ == Parameter.Type.INTEGER:
                self._parameter_overrides[full] = Parameter(
                    full, Parameter.Type.DOUBLE, float(override.value))
        return super().declare_parameters(namespace, parameters, ignore_override)

    def watch_parameters(self, callback):
        """
        Take ``ros2 param set`` through ``callback`` until :meth:`unwatch_parameters`.

        Nav2's servers add their ``dynamicParametersCallback`` on activate and remove it on
        deactivate; so do this package's (managed nodes from ``activate`` and ``deactivate``,
        the costmaps from ``start`` and ``stop``).

        :param callback: ``callback(parameters) -> rcl_interfaces/SetParametersResult``.
        """
        self.unwatch_parameters()
        self.add_on_set_parameters_callback(callback)  # rclpy returns None: keep the callback
        self._parameters_handler = callback

    def unwatch_parameters(self):
        """Remove the callback :meth:`watch_parameters` added, if any."""
        handler = getattr(self, '_parameters_handler', None)
        if handler is not None:
            self.remove_on_set_parameters_callback(handler)
        self._parameters_handler = None

    def destroy_node(self):
        """Stop the node's take loops, then destroy it as rclpy does."""
        stop_loops_of(self)
        return super().destroy_node()


class LifecycleNode(rclpy.lifecycle.LifecycleNode, Node):
    """``rclpy.lifecycle.LifecycleNode`` on the :class:`Node` base (same parameter rule)."""
