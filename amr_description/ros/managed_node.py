# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Managed (lifecycle) nodes as Nav2's are: the lifecycle services, and a bond while active.

The lifecycle itself is rclpy's (``rclpy.lifecycle``): the node starts *unconfigured* and
offers ``~/change_state``, ``~/get_state``, ``~/get_available_states``,
``~/get_available_transitions``, ``~/get_transition_graph`` and ``~/transition_event``, so
``ros2 lifecycle`` and Nav2's lifecycle manager drive it. As ``nav2_util::LifecycleNode``
(``nav2_util/src/lifecycle_node.cpp``) it declares ``bond_heartbeat_period`` (0.1 s) and, when
that is above 0, creates a bond on topic ``bond`` with its own name as id on activate (heartbeat
timeout 4 s) and destroys it on deactivate, cleanup and shutdown.

On the first activation the params file's entries the node never declared are listed in one
line (:func:`amr_description.ros.parameters.unused_overrides`), so that a Nav2 params file's
parameters that do nothing here are said once.

Subclasses implement :meth:`ManagedNode.configure`, :meth:`ManagedNode.activate`,
:meth:`ManagedNode.deactivate` and :meth:`ManagedNode.cleanup`; an exception they raise
(``ValueError``, ``OSError``, ``RuntimeError``) is logged as one error line and the transition
fails, the node staying where it was, as a Nav2 node whose callback returns FAILURE.
"""

from amr_description.ros.bond import Bond
from amr_description.ros.bond import prepare_bonds
from amr_description.ros.node import LifecycleNode
from amr_description.ros.parameters import unused_overrides
from rclpy.lifecycle import TransitionCallbackReturn

BOND_TOPIC = 'bond'
BOND_HEARTBEAT_TIMEOUT = 4.0
"""Nav2's bond topic and the heartbeat timeout its managed nodes use (s)."""

_FAILURES = (ValueError, OSError, RuntimeError, KeyError, TypeError)


class ManagedNode(LifecycleNode):
    """
    A lifecycle node with Nav2's bond.

    :param node_name: the node's name.
    :param kwargs: passed to ``rclpy.lifecycle.LifecycleNode``.
    """

    def __init__(self, node_name, **kwargs):
        """Declare ``bond_heartbeat_period``; the node starts unconfigured."""
        super().__init__(node_name, **kwargs)
        if self.has_parameter('bond_heartbeat_period'):  # declared from a params file's
            period = self.get_parameter('bond_heartbeat_period').value
        else:
            period = self.declare_parameter('bond_heartbeat_period', 0.1).value
        self.bond = None
        if period > 0.0 and type(self).wants_bond is ManagedNode.wants_bond:
            prepare_bonds(self, BOND_TOPIC)  # matched with the manager's while it configures

    # what subclasses implement
    def configure(self):
        """Read parameters and create what the node needs (subclasses)."""

    def activate(self):
        """Start working (subclasses)."""

    def deactivate(self):
        """Stop working (subclasses)."""

    def cleanup(self):
        """Release what :meth:`configure` created (subclasses)."""

    def _run(self, step, what):
        try:
            step()
        except _FAILURES as exc:
            self.get_logger().error(f'{what} failed: {exc}')
            return TransitionCallbackReturn.FAILURE
        return TransitionCallbackReturn.SUCCESS

    def on_configure(self, state):
        """Run :meth:`configure`; then make the bond topic's endpoints if not made yet."""
        result = self._run(self.configure, 'Configuring')
        if result == TransitionCallbackReturn.SUCCESS and self.wants_bond() and \
                float(self.get_parameter('bond_heartbeat_period').value) > 0.0:
            prepare_bonds(self, BOND_TOPIC)
        return result

    def on_activate(self, state):
        """Run :meth:`activate`, then create the bond."""
        result = self._run(self.activate, 'Activating')
        if result == TransitionCallbackReturn.SUCCESS:
            super().on_activate(state)  # activates the lifecycle publishers
            self._create_bond()
            self._say_unused()
        return result

    def _say_unused(self):
        if getattr(self, '_said_unused', False):
            return
        self._said_unused = True
        unused = unused_overrides(self)
        if unused:
            self.get_logger().info('Parameters not used by this implementation: '
                                   + ', '.join(unused))

    def on_deactivate(self, state):
        """Run :meth:`deactivate` and destroy the bond."""
        super().on_deactivate(state)
        self._destroy_bond()
        return self._run(self.deactivate, 'Deactivating')

    def on_cleanup(self, state):
        """Run :meth:`cleanup`."""
        self._destroy_bond()
        return self._run(self.cleanup, 'Cleaning up')

    def on_shutdown(self, state):
        """Deactivate and clean up from whatever state the node is in."""
        self._destroy_bond()
        for step in (self.deactivate, self.cleanup):
            self._run(step, 'Shutting down')
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state):
        """Log as Nav2 does; the node goes back to unconfigured."""
        self.get_logger().fatal(f'Lifecycle node {self.get_name()} entered error state')
        return TransitionCallbackReturn.SUCCESS

    def wants_bond(self):
        """Return True when the node bonds with a lifecycle manager on activate (default)."""
        return True

    def _create_bond(self):
        period = float(self.get_parameter('bond_heartbeat_period').value)
        if period > 0.0 and self.bond is None and self.wants_bond():
            self.get_logger().info('Creating bond (%s) to lifecycle manager.' % self.get_name())
            self.bond = Bond(self, BOND_TOPIC, self.get_name(), heartbeat_period=period,
                             heartbeat_timeout=BOND_HEARTBEAT_TIMEOUT)

    def _destroy_bond(self):
        if self.bond is not None:
            self.get_logger().info('Destroying bond (%s) to lifecycle manager.' % self.get_name())
            self.bond.destroy()
            self.bond = None

    def destroy_entities(self, entities):
        """Destroy publishers, subscriptions, timers and services (what activate created)."""
        for entity in entities:
            for destroy in (self.destroy_publisher, self.destroy_subscription,
                            self.destroy_timer, self.destroy_service):
                if destroy(entity):
                    break

    def is_active(self):
        """Return True when the node's lifecycle state is ``active``."""
        return self._state_machine.current_state[1] == 'active'
