# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""plan_switch: the checks of a switch_controller request, without rclpy."""

from amr_description.control.switch_plan import ControllerSpec
from amr_description.control.switch_plan import plan_switch
from amr_description.control.switch_plan import Resources

WHEELS = ('left/velocity', 'right/velocity')
RESOURCES = Resources(command_interfaces=frozenset(WHEELS + ('arm/position',)),
                      available=frozenset(WHEELS),
                      claimed={'left/velocity': 'old'},
                      state_interfaces=frozenset({'left/position', 'right/position'}))


def _specs(**states):
    claims = {'ddc': WHEELS, 'old': ('left/velocity',), 'jsb': (), 'arm': ('arm/position',),
              'twin': WHEELS}
    reads = {'jsb': None, 'ddc': ('left/position',), 'old': (), 'arm': (),
             'twin': ('left/effort',)}
    return {name: ControllerSpec(name, 'x/X', state, claims[name], reads[name])
            for name, state in states.items()}


def test_activate_with_the_holder_deactivated():
    plan = plan_switch(['ddc'], ['old'], _specs(ddc='inactive', old='active'), RESOURCES)
    assert (plan.activate, plan.deactivate, plan.problems) == (['ddc'], ['old'], [])


def test_interface_claimed_by_a_controller_that_stays():
    plan = plan_switch(['ddc'], [], _specs(ddc='inactive', old='active'), RESOURCES)
    assert plan.activate == [] and plan.problems == [
        "Could not activate controller 'ddc': command interface 'left/velocity' is already "
        "claimed by 'old'"]


def test_one_request_asks_for_an_interface_twice_and_for_a_missing_state_interface():
    resources = Resources(RESOURCES.command_interfaces, RESOURCES.available, {},
                          RESOURCES.state_interfaces)
    plan = plan_switch(['ddc', 'old', 'twin'], [],
                       _specs(ddc='inactive', old='inactive', twin='inactive'), resources)
    assert plan.activate == ['ddc']
    assert plan.problems == [
        "Could not activate controller 'old': command interface 'left/velocity' is also "
        "requested by 'ddc'",
        "Could not activate controller 'twin': command interface 'left/velocity' is also "
        "requested by 'ddc'"]
    alone = plan_switch(['twin'], [], _specs(twin='inactive'), resources)
    assert alone.problems == ["Could not activate controller 'twin': state interface "
                              "'left/effort' does not exist"]


def test_unavailable_and_unknown_interfaces():
    plan = plan_switch(['arm'], [], _specs(arm='inactive'), RESOURCES)
    assert plan.problems == ["Could not activate controller 'arm': command interface "
                             "'arm/position' is not available"]


def test_states_and_names():
    specs = _specs(jsb='active', ddc='unconfigured')
    plan = plan_switch(['jsb', 'ddc', 'nope'], ['nope', 'ddc'], specs, RESOURCES)
    assert plan.activate == [] and plan.deactivate == []
    assert plan.problems == [
        "Could not deactivate controller with name 'nope' because no controller with this "
        'name exists',
        "Controller with name 'ddc' can not be deactivated since it is not active (state: "
        'unconfigured)',
        "Controller with name 'jsb' is already active.",
        "Controller with name 'ddc' is not inactive so its state can not be changed to active "
        '(state: unconfigured); configure it first',
        "Could not activate controller with name 'nope' because no controller with this name "
        'exists']


def test_restart_is_deactivate_then_activate():
    plan = plan_switch(['jsb'], ['jsb', 'jsb'], _specs(jsb='active'), RESOURCES)
    assert (plan.activate, plan.deactivate, plan.problems) == (['jsb'], ['jsb'], [])
