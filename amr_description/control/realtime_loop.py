# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The realtime half of the controller manager: ``read -> update -> write`` and the switch.

As ros2_control's ``ControllerManager::read/update/write`` (jazzy), called by the owner's
control thread (the simulation thread, or ``ros2_control_node``'s loop) and never by the
executor: ``update`` first applies a switch the services queued (checked beforehand by
:func:`~amr_description.control.switch_plan.plan_switch`), then updates the active
controllers in load order, each at its own ``update_rate``.

:class:`RealtimeLoop` is a base class of
:class:`~amr_description.control.controller_manager.ControllerManager` and works on its
state: ``controllers`` (name -> controller node, load order), ``resource_manager``,
``update_rate``, ``_lock``, ``_pending`` (the queued switch), ``_last_update``,
``_destroyed`` and ``_publish_activity()``.
"""


import threading


class PendingSwitch:
    """A switch request queued by the services, applied by the next :meth:`RealtimeLoop.update`."""

    def __init__(self, activate, deactivate):
        """Keep the plan; ``done`` is set once applied (``ok``, ``message``)."""
        self.activate = activate
        self.deactivate = deactivate
        self.done = threading.Event()
        self.ok = False
        self.message = ''


class RealtimeLoop:
    """``read``, ``update``, ``write`` and ``cycle`` of the controller manager."""

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
        self._last_update.pop(name, None)
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
        if errors:
            request.message = '; '.join(errors)
        else:
            self.get_logger().info('Successfully switched controllers!')
            request.message = 'Successfully switched controllers!'
            if request.activate:
                request.message += f" Activated: [ {' '.join(request.activate)} ]"
            if request.deactivate:
                request.message += f" Deactivated: [ {' '.join(request.deactivate)} ]"
        request.done.set()
        return True

    def read(self, time, period):
        """
        Read every active hardware component (``ResourceManager.read``).

        Errors are logged once per component.

        :param time: current time in seconds (sim time when simulated).
        :param period: seconds since the previous read.
        """
        if self._destroyed:
            return
        with self._lock:
            for failed in self.resource_manager.read(time, period):
                self.get_logger().error(f"Error in read of hardware component '{failed}'",
                                        once=True)

    def update(self, time, period):
        """
        Apply a pending switch, then update the active controllers in load order.

        A controller whose ``update_rate`` parameter is below the manager's is updated only
        when ``1/update_rate`` seconds have passed since its last update (its ``period`` is
        then that time), as upstream.

        :param time: current time in seconds (sim time when simulated).
        :param period: seconds since the previous update.
        """
        if self._destroyed or not self.context.ok():
            return
        switched = False
        with self._lock:
            if self._pending is not None:
                request, self._pending = self._pending, None
                switched = self._apply_switch(request)
            log = self.get_logger()
            for name, ctrl in list(self.controllers.items()):
                if ctrl.lifecycle_state != 'active':
                    continue
                ctrl_period = period
                rate = ctrl.update_rate
                if 0 < rate < self.update_rate:
                    last = self._last_update.get(name)
                    if last is not None:
                        ctrl_period = time - last
                        if ctrl_period < 1.0 / rate - 0.5 / self.update_rate:
                            continue
                self._last_update[name] = time
                try:
                    ok = ctrl.update(time, ctrl_period)
                except Exception as exc:  # noqa: B902 - a faulty controller must not stop us
                    ok = False
                    log.error(f"Exception in update of controller '{name}': {exc}")
                if not ok:
                    log.error(f"Error in update of controller '{name}': deactivating it")
                    self._deactivate(name)
                    switched = True
        if switched:
            self._publish_activity()

    def write(self, time, period):
        """
        Write every active hardware component (``ResourceManager.write``).

        :param time: current time in seconds (sim time when simulated).
        :param period: seconds since the previous write.
        """
        if self._destroyed:
            return
        with self._lock:
            for failed in self.resource_manager.write(time, period):
                self.get_logger().error(f"Error in write of hardware component '{failed}'",
                                        once=True)

    def cycle(self, time, period):
        """Run :meth:`read`, :meth:`update` and :meth:`write` (one control cycle)."""
        self.read(time, period)
        self.update(time, period)
        self.write(time, period)
