# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Validation of a ``switch_controller`` request, without rclpy.

As ros2_control's ``ControllerManager::switch_controller`` (jazzy) checks a request before the
realtime loop applies it: controllers to deactivate must exist and be active, controllers to
activate must exist and be inactive (an active one named in both lists is restarted), every
command interface a controller claims must exist, be available and be free (or held by a
controller being deactivated) and not be asked for twice, every state interface it reads must
exist. The messages are upstream's.
"""

from dataclasses import dataclass
from dataclasses import field


@dataclass(frozen=True)
class ControllerSpec:
    """
    What the controller manager knows of one loaded controller.

    :param name: controller name.
    :param type: its type string, e.g. ``diff_drive_controller/DiffDriveController``.
    :param state: lifecycle state label: ``unconfigured``, ``inactive``, ``active``, ...
    :param command_interfaces: command interfaces it claims, ``'<joint>/<interface>'``.
    :param state_interfaces: state interfaces it reads; None for every one.
    """

    name: str
    type: str = ''  # noqa: A003 - ros2_control's field name (ControllerState.type)
    state: str = 'unconfigured'
    command_interfaces: tuple = ()
    state_interfaces: tuple = None


@dataclass(frozen=True)
class Resources:
    """
    The hardware interfaces of the resource manager, as a switch sees them.

    :param command_interfaces: names of every command interface.
    :param available: names of the command interfaces of active hardware components.
    :param claimed: command interface name -> the controller that holds it.
    :param state_interfaces: names of every state interface.
    """

    command_interfaces: frozenset = frozenset()
    available: frozenset = frozenset()
    claimed: dict = field(default_factory=dict)
    state_interfaces: frozenset = frozenset()


@dataclass
class SwitchPlan:
    """
    The outcome of :func:`plan_switch`.

    :param activate: controllers to activate, in request order.
    :param deactivate: controllers to deactivate, in request order.
    :param problems: one line per refused part of the request (upstream's wording).
    """

    activate: list = field(default_factory=list)
    deactivate: list = field(default_factory=list)
    problems: list = field(default_factory=list)


def claim_conflict(spec, deactivating, claims, resources):
    """
    Return why ``spec`` cannot be activated next to ``claims``, or None.

    :param spec: the :class:`ControllerSpec` to activate.
    :param deactivating: names of the controllers deactivated by the same request.
    :param claims: command interface -> controller, of those activated before it.
    :param resources: the :class:`Resources`.
    """
    name = spec.name
    for iface in spec.command_interfaces:
        if iface not in resources.command_interfaces:
            return (f"Could not activate controller '{name}': command interface "
                    f"'{iface}' does not exist")
        if iface not in resources.available:
            return (f"Could not activate controller '{name}': command interface "
                    f"'{iface}' is not available")
        owner = resources.claimed.get(iface)
        if owner is not None and owner not in deactivating:
            return (f"Could not activate controller '{name}': command interface "
                    f"'{iface}' is already claimed by '{owner}'")
        if iface in claims:
            return (f"Could not activate controller '{name}': command interface "
                    f"'{iface}' is also requested by '{claims[iface]}'")
    for iface in spec.state_interfaces or ():
        if iface not in resources.state_interfaces:
            return (f"Could not activate controller '{name}': state interface "
                    f"'{iface}' does not exist")
    return None


def plan_switch(activate, deactivate, specs, resources):
    """
    Check a switch request; return what to switch and what was refused.

    :param activate: names to activate (list of str).
    :param deactivate: names to deactivate (list of str).
    :param specs: dict name -> :class:`ControllerSpec` of every loaded controller.
    :param resources: the :class:`Resources` of the robot.
    :returns: a :class:`SwitchPlan`; the caller decides by strictness whether problems abort.
    """
    plan = SwitchPlan()
    for name in deactivate:
        spec = specs.get(name)
        if spec is None:
            plan.problems.append(f"Could not deactivate controller with name '{name}' "
                                 'because no controller with this name exists')
        elif spec.state != 'active':
            plan.problems.append(f"Controller with name '{name}' can not be deactivated "
                                 f'since it is not active (state: {spec.state})')
        elif name not in plan.deactivate:
            plan.deactivate.append(name)
    claims = {}
    for name in activate:
        spec = specs.get(name)
        if spec is None:
            plan.problems.append(f"Could not activate controller with name '{name}' "
                                 'because no controller with this name exists')
            continue
        if spec.state == 'active':
            if name in plan.deactivate:
                plan.activate.append(name)  # restart
            else:
                plan.problems.append(f"Controller with name '{name}' is already active.")
            continue
        if spec.state != 'inactive':
            plan.problems.append(f"Controller with name '{name}' is not inactive so its "
                                 f'state can not be changed to active (state: '
                                 f'{spec.state}); configure it first')
            continue
        conflict = claim_conflict(spec, plan.deactivate, claims, resources)
        if conflict:
            plan.problems.append(conflict)
            continue
        for iface in spec.command_interfaces:
            claims[iface] = name
        plan.activate.append(name)
    return plan
