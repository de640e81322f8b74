# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``ros2 control`` verb ``set_hardware_component_state``."""

from amr_description.cli.control.api import run
from amr_description.cli.extension import Verb
from amr_description.control import controller_manager_services as cms


def _args_set_hardware_component_state(p):
    p.add_argument('hardware_component_name',
                   help='Name of the hardware_component to be changed')
    p.add_argument('state', choices=['unconfigured', 'inactive', 'active'],
                   help='State in which the hardware component should be changed to')


def _set_hardware_component_state(args):
    from lifecycle_msgs.msg import State

    def body(node, cm):
        name = args.hardware_component_name
        found = [c for c in cms.list_hardware_components(node, cm).component if c.name == name]
        if not found:
            return f'component {name} does not seem to be loaded'
        current = found[0].state
        target = State()
        if args.state == 'unconfigured':
            if current.label != 'inactive':
                return f'cannot cleanup {name} from its current state {current}'
            target.id, target.label = State.PRIMARY_STATE_UNCONFIGURED, 'unconfigured'
            error = 'Error cleaning up hardware component, check controller_manager logs'
        elif args.state == 'inactive':
            target.id, target.label = State.PRIMARY_STATE_INACTIVE, 'inactive'
            if current.label == 'unconfigured':
                error = 'Error configuring hardware component, check controller_manager logs'
            elif current.label == 'active':
                error = 'Error stopping hardware component, check controller_manager logs'
            else:
                return (f'cannot put {name} in "inactive" state from its current state '
                        f'{current}')
        else:
            if current.label != 'inactive':
                return f'cannot activate {name} from its current state {current}'
            target.id, target.label = State.PRIMARY_STATE_ACTIVE, 'active'
            error = 'Error activating hardware component, check controller_manager logs'
        response = cms.set_hardware_component_state(node, cm, name, target)
        if not response.ok:
            return error
        print(f'Successfully set {name} to state {response.state}')
        return 0
    return run(args, body)


VERB_SET_HARDWARE_COMPONENT_STATE = Verb(
    'Adjust the state of the hardware component',
    _set_hardware_component_state, _args_set_hardware_component_state,
    description='Adjust the state of the hardware component')
"""``ros2 control set_hardware_component_state``."""
