# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``ros2 control`` verbs that change controllers.

``load_controller``, ``set_controller_state``, ``switch_controllers``, ``unload_controller``,
``cleanup_controller``, ``reload_controller_libraries``.
"""

import sys

from amr_description.cli.control.api import error
from amr_description.cli.control.api import run
from amr_description.cli.extension import Verb
from amr_description.control import controller_manager_services as cms


def _args_load_controller(p):
    p.add_argument('controller_name', help='Name of the controller')
    p.add_argument('--set-state', choices=['inactive', 'active'],
                   help='Set the state of the loaded controller')


def _load_controller(args):
    def body(node, cm):
        name = args.controller_name
        if not cms.load_controller(node, cm, name).ok:
            return error('Error loading controller, check controller_manager logs')
        if not args.set_state:
            print(f'Successfully loaded controller {name}')
            return 0
        if not cms.configure_controller(node, cm, name).ok:
            return error('Error configuring controller')
        if args.set_state == 'active':
            if not cms.switch_controllers(node, cm, [], [name], True, True, 5.0).ok:
                return error('Error activating controller, check controller_manager logs')
        print(f'Successfully loaded controller {name} into state {args.set_state}')
        return 0
    return run(args, body)


def _args_set_controller_state(p):
    p.add_argument('controller_name', help='Name of the controller to be changed')
    p.add_argument('state', choices=['inactive', 'active'],
                   help='State in which the controller should be changed to')


def _set_controller_state(args):
    def body(node, cm):
        name = args.controller_name
        matched = [c for c in cms.list_controllers(node, cm).controller if c.name == name]
        if not matched:
            return f'controller {name} does not seem to be loaded'
        state = matched[0].state
        if args.state == 'inactive':
            if state == 'unconfigured':
                if not cms.configure_controller(node, cm, name).ok:
                    return 'Error configuring controller, check controller_manager logs'
                print(f'Successfully configured {name}')
                return 0
            if state == 'active':
                if not cms.switch_controllers(node, cm, [name], [], True, True, 5.0).ok:
                    return 'Error stopping controller, check controller_manager logs'
                print(f'Successfully deactivated {name}')
                return 0
            return f"cannot put {name} in 'inactive' state from its current state {state}"
        if state != 'inactive':
            return f'cannot activate {name} from its current state {state}'
        if not cms.switch_controllers(node, cm, [], [name], True, True, 5.0).ok:
            return 'Error activating controller, check controller_manager logs'
        print(f'Successfully activated {name}')
        return 0
    return run(args, body)


def _args_switch_controllers(p):
    p.add_argument('--deactivate', nargs='*', default=[],
                   help='Name of the controllers to be deactivated')
    p.add_argument('--activate', nargs='*', default=[],
                   help='Name of the controllers to be activated')
    p.add_argument('--strict', action='store_true', help='Strict switch')
    p.add_argument('--activate-asap', action='store_true', help='Start asap controllers')
    p.add_argument('--switch-timeout', type=float, default=5.0,
                   help='Timeout for switching controllers')


def _switch_controllers(args):
    def body(node, cm):
        c = cms.colors()
        response = cms.switch_controllers(node, cm, args.deactivate or [], args.activate or [],
                                          args.strict, args.activate_asap, args.switch_timeout)
        if not response.ok:
            error('Error switching controllers, check controller_manager logs')
            if response.message:
                print(response.message, file=sys.stderr)
            return 1
        print(f'{c.OKBLUE}Successfully switched controllers{c.ENDC}')
        return 0
    return run(args, body)


def _args_named(p):
    p.add_argument('controller_name', help='Name of the controller')


def _unload_controller(args):
    def body(node, cm):
        if not cms.unload_controller(node, cm, args.controller_name).ok:
            return error('Error unloading controller, check controller_manager logs')
        print(f'Successfully unloaded controller {args.controller_name}')
        return 0
    return run(args, body)


def _cleanup_controller(args):
    def body(node, cm):
        if not cms.cleanup_controller(node, cm, args.controller_name).ok:
            return 'Error cleanup controllers, check controller_manager logs'
        print(f'Successfully cleaned up controller {args.controller_name}')
        return 0
    return run(args, body)


def _args_reload_controller_libraries(p):
    p.add_argument('--force-kill', action='store_true', help='Force stop of loaded controllers')


def _reload_controller_libraries(args):
    def body(node, cm):
        if not cms.reload_controller_libraries(node, cm, force_kill=args.force_kill).ok:
            return 'Error reloading libraries, check controller_manager logs'
        print('Reload successful')
        return 0
    return run(args, body)


VERB_CLEANUP_CONTROLLER = Verb(
    'Cleanup a controller in a controller manager',
    _cleanup_controller, _args_named,
    description='Cleanup a controller in a controller manager')
"""``ros2 control cleanup_controller``."""

VERB_LOAD_CONTROLLER = Verb(
    'Load a controller in a controller manager',
    _load_controller, _args_load_controller,
    description='Load a controller in a controller manager')
"""``ros2 control load_controller``."""

VERB_RELOAD_CONTROLLER_LIBRARIES = Verb(
    'Reload controller libraries',
    _reload_controller_libraries, _args_reload_controller_libraries,
    description='Reload controller libraries')
"""``ros2 control reload_controller_libraries``."""

VERB_SET_CONTROLLER_STATE = Verb(
    'Adjust the state of the controller',
    _set_controller_state, _args_set_controller_state,
    description='Adjust the state of the controller')
"""``ros2 control set_controller_state``."""

VERB_SWITCH_CONTROLLERS = Verb(
    'Switch controllers in a controller manager',
    _switch_controllers, _args_switch_controllers,
    description='Switch controllers in a controller manager')
"""``ros2 control switch_controllers``."""

VERB_UNLOAD_CONTROLLER = Verb(
    'Unload a controller in a controller manager',
    _unload_controller, _args_named,
    description='Unload a controller in a controller manager')
"""``ros2 control unload_controller``."""
