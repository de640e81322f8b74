# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 control`` verbs: talk to a controller manager through its services.

Output formats, messages and exit codes follow ros2controlcli (jazzy): ``list_controllers``
prints ``name type  state`` with columns padded to the longest entry, ``-v`` adds the update
rate, ``is_async`` and the interfaces; ``list_hardware_interfaces`` prints ``command
interfaces``, one tab-indented ``<name> [available] [claimed]`` line each, then ``state
interfaces``; a failing verb prints upstream's "Error ..., check controller_manager logs" and
exits 1. Every service call goes through
:mod:`amr_description.control.controller_manager_services`, shared with the spawner.
ANSI colours (as upstream) are used only when stdout is a terminal. Each verb's arguments
are added by the ``_args_<verb>`` function right above the verb.
"""

import sys

from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.control import controller_manager_services as cms


def _node_args(args):
    return ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None


def _run(args, body):
    """Run ``body(node, cm)`` with a CLI node; errors of the service layer: one line, 1."""
    try:
        with cli_node(default_node_name(), _node_args(args)) as node:
            cm = cms.resolve_controller_manager(node, args.controller_manager)
            code = body(node, cm)
            return code if isinstance(code, int) else fail(code)
    except (RuntimeError, cms.ServiceNotFoundError) as exc:
        return fail(str(exc))


def _error(message):
    """Print an upstream error line (red on a terminal) to stdout; returns 1."""
    c = cms.colors()
    print(f'{c.FAIL}{message}{c.ENDC}')
    return 1


def _common(parser):
    parser.add_argument('-c', '--controller-manager', default='controller_manager',
                        help='Name of the controller manager ROS node (default: '
                        'controller_manager)')
    parser.add_argument('--include-hidden-nodes', action='store_true',
                        help='Consider hidden nodes as well')
    parser.add_argument('-s', '--use-sim-time', action='store_true',
                        help='Enable ROS simulation time')
    parser.add_argument('--spin-time', type=float, default=0.5,
                        help='Spin time in seconds to wait for discovery')


# ------------------------------------------------------------------- list_controllers
def _args_list_controllers(p):
    for flag, text in (('--claimed-interfaces', "List controller's claimed interfaces"),
                       ('--required-state-interfaces',
                        "List controller's required state interfaces"),
                       ('--required-command-interfaces',
                        "List controller's required command interfaces"),
                       ('--chained-interfaces',
                        'List interfaces that the controllers are chained to'),
                       ('--reference-interfaces', "List controller's exported references")):
        p.add_argument(flag, action='store_true', help=text)
    p.add_argument('-v', '--verbose', action='store_true',
                   help="List controller's claimed interfaces, required state interfaces and "
                   'required command interfaces')


def _print_controller(ctrl, args, w_name, w_type, w_state):
    c = cms.colors()
    color = {'active': c.OKGREEN, 'inactive': c.OKCYAN,
             'unconfigured': c.WARNING}.get(ctrl.state, '')
    print(f'{color}{ctrl.name:<{w_name}}{c.ENDC} {ctrl.type:<{w_type}}  '
          f'{color}{ctrl.state:<{w_state}}{c.ENDC}')
    if args.verbose:
        print(f'\tupdate_rate: {ctrl.update_rate} Hz')
        print(f'\tis_async: {ctrl.is_async}')
    sections = (
        (args.claimed_interfaces, 'claimed interfaces', ctrl.claimed_interfaces),
        (args.required_command_interfaces, 'required command interfaces',
         ctrl.required_command_interfaces),
        (args.required_state_interfaces, 'required state interfaces',
         ctrl.required_state_interfaces))
    for wanted, title, names in sections:
        if wanted or args.verbose:
            print(f'\t{title}:')
            for name in names:
                print(f'\t\t{name}')
    if args.chained_interfaces or args.verbose:
        print('\tchained to interfaces:')
        for connection in ctrl.chain_connections:
            for ref in connection.reference_interfaces:
                print(f'\t\t{ref:20s}')
    if args.verbose:
        print('\texported state interfaces:')
        for name in ctrl.exported_state_interfaces:
            print(f'\t\t{name}')
    if args.reference_interfaces or args.verbose:
        print('\texported reference interfaces:')
        for ref in ctrl.reference_interfaces:
            print(f'\t\t{ref}')


def _list_controllers(args):
    def body(node, cm):
        response = cms.list_controllers(node, cm)
        if not response.controller:
            print('No controllers are currently loaded!')
            return 0
        w_name = max(len(x.name) for x in response.controller)
        w_type = max(len(x.type) for x in response.controller)
        w_state = max(len(x.state) for x in response.controller)
        for ctrl in response.controller:
            _print_controller(ctrl, args, w_name, w_type, w_state)
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- list_hardware_interfaces
def _args_list_hardware_interfaces(p):
    p.add_argument('-v', '--verbose', action='store_true',
                   help='List hardware interfaces and their data types')


def _list_hardware_interfaces(args):
    def body(node, cm):
        c = cms.colors()
        response = cms.list_hardware_interfaces(node, cm)
        print('command interfaces')
        for iface in sorted(response.command_interfaces, key=lambda i: i.name):
            dtype = f' [{iface.data_type}]' if args.verbose else ''
            if iface.is_available and iface.is_claimed:
                print(f'\t{c.OKBLUE}{iface.name}{dtype} [available] [claimed]{c.ENDC}')
            elif iface.is_available:
                print(f'\t{c.OKCYAN}{iface.name}{dtype} [available] [unclaimed]{c.ENDC}')
            else:
                print(f'\t{c.WARNING}{iface.name}{dtype} [unavailable] [unclaimed]{c.ENDC}')
        print('state interfaces')
        for iface in sorted(response.state_interfaces, key=lambda i: i.name):
            dtype = f' [{iface.data_type}]' if args.verbose else ''
            print(f'\t{iface.name}{dtype}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- list_controller_types
def _list_controller_types(args):
    def body(node, cm):
        response = cms.list_controller_types(node, cm)
        for type_name, base in zip(response.types, response.base_classes):
            print(f'{type_name:70s} {base}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- list_hardware_components
def _args_list_hardware_components(p):
    p.add_argument('-v', '--verbose', action='store_true',
                   help='List hardware components with command and state interfaces')


def _list_hardware_components(args):
    def body(node, cm):
        c = cms.colors()
        response = cms.list_hardware_components(node, cm)
        for idx, comp in enumerate(response.component):
            color = {1: c.WARNING, 2: c.MAGENTA, 3: c.OKGREEN}.get(comp.state.id, c.FAIL)
            print(f'Hardware Component {idx + 1}\n\tname: {color}{comp.name}{c.ENDC}\n'
                  f'\ttype: {comp.type}')
            print(f'\tplugin name: {comp.plugin_name}\n'
                  f'\tstate: id={comp.state.id} label={color}{comp.state.label}{c.ENDC}')
            if args.verbose:
                print(f'\tread/write rate: {comp.rw_rate} Hz\n\tis_async: {comp.is_async}')
            print('\tcommand interfaces')
            for iface in comp.command_interfaces:
                dtype = f'[{iface.data_type}] ' if args.verbose else ''
                available = (f'{c.OKBLUE}[available]{c.ENDC}' if iface.is_available
                             else f'{c.WARNING}[unavailable]{c.ENDC}')
                claimed = f'{c.OKBLUE}[claimed]{c.ENDC}' if iface.is_claimed else '[unclaimed]'
                print(f'\t\t{iface.name} {dtype}{available} {claimed}')
            if args.verbose:
                print('\tstate interfaces')
                for iface in comp.state_interfaces:
                    available = (f'{c.OKBLUE}[available]{c.ENDC}' if iface.is_available
                                 else f'{c.WARNING}[unavailable]{c.ENDC}')
                    print(f'\t\t{iface.name} [{iface.data_type}] {available}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- load_controller
def _args_load_controller(p):
    p.add_argument('controller_name', help='Name of the controller')
    p.add_argument('--set-state', choices=['inactive', 'active'],
                   help='Set the state of the loaded controller')


def _load_controller(args):
    def body(node, cm):
        name = args.controller_name
        if not cms.load_controller(node, cm, name).ok:
            return _error('Error loading controller, check controller_manager logs')
        if not args.set_state:
            print(f'Successfully loaded controller {name}')
            return 0
        if not cms.configure_controller(node, cm, name).ok:
            return _error('Error configuring controller')
        if args.set_state == 'active':
            if not cms.switch_controllers(node, cm, [], [name], True, True, 5.0).ok:
                return _error('Error activating controller, check controller_manager logs')
        print(f'Successfully loaded controller {name} into state {args.set_state}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- set_controller_state
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
    return _run(args, body)


# ------------------------------------------------------------------- switch_controllers
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
            _error('Error switching controllers, check controller_manager logs')
            if response.message:
                print(response.message, file=sys.stderr)
            return 1
        print(f'{c.OKBLUE}Successfully switched controllers{c.ENDC}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- unload_controller
def _args_named(p):
    p.add_argument('controller_name', help='Name of the controller')


def _unload_controller(args):
    def body(node, cm):
        if not cms.unload_controller(node, cm, args.controller_name).ok:
            return _error('Error unloading controller, check controller_manager logs')
        print(f'Successfully unloaded controller {args.controller_name}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- cleanup_controller
def _cleanup_controller(args):
    def body(node, cm):
        if not cms.cleanup_controller(node, cm, args.controller_name).ok:
            return 'Error cleanup controllers, check controller_manager logs'
        print(f'Successfully cleaned up controller {args.controller_name}')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- reload_controller_libraries
def _args_reload_controller_libraries(p):
    p.add_argument('--force-kill', action='store_true', help='Force stop of loaded controllers')


def _reload_controller_libraries(args):
    def body(node, cm):
        if not cms.reload_controller_libraries(node, cm, force_kill=args.force_kill).ok:
            return 'Error reloading libraries, check controller_manager logs'
        print('Reload successful')
        return 0
    return _run(args, body)


# ------------------------------------------------------------------- set_hardware_component_state
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
    return _run(args, body)


# ------------------------------------------------------------------- view_controller_chains
def _args_view_controller_chains(p):
    p.add_argument('--save', action='store_true',
                   help='Save the diagram as controller_diagram.pdf in the current directory '
                   'instead of opening it in a viewer')


def _view_controller_chains(args):
    from amr_description.cli import control_chains

    def body(node, cm):
        controllers = cms.list_controllers(node, cm)
        hardware = cms.list_hardware_components(node, cm)
        return control_chains.write_diagram(controllers, hardware, view=not args.save)
    return _run(args, body)


# ------------------------------------------------------------------- the command
_VERBS = (
    ('cleanup_controller', 'Cleanup a controller in a controller manager', _args_named,
     _cleanup_controller),
    ('list_controller_types', 'Output the available controller types and their base classes',
     None, _list_controller_types),
    ('list_controllers', 'Output the list of loaded controllers, their type and status',
     _args_list_controllers, _list_controllers),
    ('list_hardware_components', 'Output the list of available hardware components',
     _args_list_hardware_components, _list_hardware_components),
    ('list_hardware_interfaces', 'Output the list of available command and state interfaces',
     _args_list_hardware_interfaces, _list_hardware_interfaces),
    ('load_controller', 'Load a controller in a controller manager', _args_load_controller,
     _load_controller),
    ('reload_controller_libraries', 'Reload controller libraries',
     _args_reload_controller_libraries, _reload_controller_libraries),
    ('set_controller_state', 'Adjust the state of the controller', _args_set_controller_state,
     _set_controller_state),
    ('set_hardware_component_state', 'Adjust the state of the hardware component',
     _args_set_hardware_component_state, _set_hardware_component_state),
    ('switch_controllers', 'Switch controllers in a controller manager',
     _args_switch_controllers, _switch_controllers),
    ('unload_controller', 'Unload a controller in a controller manager', _args_named,
     _unload_controller),
    ('view_controller_chains', 'Generates a diagram of the loaded chained controllers',
     _args_view_controller_chains, _view_controller_chains),
)


def add_command(subparsers):
    """
    Add the ``control`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('control', help='Various control related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    for name, text, add_arguments, main in _VERBS:
        p = verbs.add_parser(name, help=text, description=text)
        if add_arguments is not None:
            add_arguments(p)
        _common(p)
        p.set_defaults(main=main)
