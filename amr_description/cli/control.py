# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 control`` verbs: talk to a controller manager through its services.

Output formats follow ros2controlcli (jazzy): ``list_controllers`` prints
``name type  state`` with columns padded to the longest entry, ``list_hardware_interfaces``
prints ``command interfaces``, one tab-indented ``<name> [available] [claimed]`` line
each, then ``state interfaces``.
ANSI colours (as upstream) are used only when stdout is a terminal.
"""

import sys
import time

from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import spin_once


class _Colors:
    MAGENTA = '\033[95m'
    OKBLUE = '\033[94m'
    OKCYAN = '\033[96m'
    OKGREEN = '\033[92m'
    WARNING = '\033[93m'
    FAIL = '\033[91m'
    ENDC = '\033[0m'


class _NoColors:
    MAGENTA = OKBLUE = OKCYAN = OKGREEN = WARNING = FAIL = ENDC = ''


def _colors():
    return _Colors if sys.stdout.isatty() else _NoColors


def _cm_name(node, name):
    if name.startswith('/'):
        return name
    ns = node.get_namespace()
    return f'{ns.rstrip("/")}/{name}' if ns and ns != '/' else f'/{name}'


def call_service(node, service_name, service_type, request, service_timeout=0.0,
                 call_timeout=10.0):
    """
    Call ``service_name`` and return the response (waits for it like upstream).

    :param node: the CLI node.
    :param service_name: absolute service name.
    :param service_type: service class.
    :param request: request message.
    :param service_timeout: seconds to wait for the service, 0 = forever (logging every 10 s).
    :param call_timeout: seconds to wait for the response.
    :returns: the response message.
    :raises RuntimeError: one line naming the service when it is missing or does not answer.
    """
    client = node.create_client(service_type, service_name)
    try:
        start = time.monotonic()
        last_note = None
        while not client.service_is_ready():
            now = time.monotonic()
            if (last_note is None and now - start >= 1.0) or \
                    (last_note is not None and now - last_note >= 10.0):
                print(f'waiting for service {service_name} to become available...',
                      file=sys.stderr)
                last_note = now
            if service_timeout and now - start > service_timeout:
                raise RuntimeError(f'Could not contact service {service_name}')
            spin_once(node, timeout_sec=0.1)
        future = client.call_async(request)
        deadline = time.monotonic() + call_timeout
        while not future.done():
            if time.monotonic() > deadline:
                raise RuntimeError(f'Could not successfully call service {service_name}')
            spin_once(node, timeout_sec=0.1)
        return future.result()
    finally:
        node.destroy_client(client)


def _call(args, node, verb, request_kwargs=None):
    from controller_manager_msgs import srv
    kinds = {
        'list_controllers': srv.ListControllers,
        'list_controller_types': srv.ListControllerTypes,
        'list_hardware_interfaces': srv.ListHardwareInterfaces,
        'list_hardware_components': srv.ListHardwareComponents,
        'load_controller': srv.LoadController,
        'configure_controller': srv.ConfigureController,
        'switch_controller': srv.SwitchController,
        'unload_controller': srv.UnloadController,
    }
    kind = kinds[verb]
    request = kind.Request(**(request_kwargs or {}))
    return call_service(node, f'{_cm_name(node, args.controller_manager)}/{verb}', kind,
                        request)


def _switch(args, node, activate, deactivate, strict=True, asap=True, timeout=5.0):
    from builtin_interfaces.msg import Duration
    return _call(args, node, 'switch_controller', {
        'activate_controllers': list(activate), 'deactivate_controllers': list(deactivate),
        'strictness': 2 if strict else 1, 'activate_asap': asap,
        'timeout': Duration(sec=int(timeout), nanosec=int((timeout % 1.0) * 1e9))})


def _node_args(args):
    return ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None


def _run(args, body):
    try:
        with cli_node(default_node_name(), _node_args(args)) as node:
            return body(node)
    except RuntimeError as exc:
        return fail(str(exc))


# ------------------------------------------------------------------------------- verbs
def _list_controllers(args):
    def body(node):
        c = _colors()
        response = _call(args, node, 'list_controllers')
        if not response.controller:
            print('No controllers are currently loaded!')
            return 0
        w_name = max(len(x.name) for x in response.controller)
        w_type = max(len(x.type) for x in response.controller)
        w_state = max(len(x.state) for x in response.controller)
        for ctrl in response.controller:
            color = {'active': c.OKGREEN, 'inactive': c.OKCYAN,
                     'unconfigured': c.WARNING}.get(ctrl.state, '')
            end = c.ENDC
            print(f'{color}{ctrl.name:<{w_name}}{end} {ctrl.type:<{w_type}}  '
                  f'{color}{ctrl.state:<{w_state}}{end}')
            if args.claimed_interfaces or args.verbose:
                print('\tclaimed interfaces:')
                for name in ctrl.claimed_interfaces:
                    print(f'\t\t{name}')
            if args.required_command_interfaces or args.verbose:
                print('\trequired command interfaces:')
                for name in ctrl.required_command_interfaces:
                    print(f'\t\t{name}')
            if args.required_state_interfaces or args.verbose:
                print('\trequired state interfaces:')
                for name in ctrl.required_state_interfaces:
                    print(f'\t\t{name}')
            if args.chained_interfaces or args.verbose:
                print('\tchained to interfaces:')
                for connection in ctrl.chain_connections:
                    for ref in connection.reference_interfaces:
                        print(f'\t\t{ref:20s}')
            if args.reference_interfaces or args.verbose:
                print('\texported reference interfaces:')
                for ref in ctrl.reference_interfaces:
                    print(f'\t\t{ref}')
        return 0
    return _run(args, body)


def _list_hardware_interfaces(args):
    def body(node):
        c = _colors()
        response = _call(args, node, 'list_hardware_interfaces')
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


def _list_controller_types(args):
    def body(node):
        response = _call(args, node, 'list_controller_types')
        for type_name, base in zip(response.types, response.base_classes):
            print(f'{type_name:70s} {base}')
        return 0
    return _run(args, body)


def _list_hardware_components(args):
    def body(node):
        c = _colors()
        response = _call(args, node, 'list_hardware_components')
        for idx, comp in enumerate(response.component):
            color = {1: c.WARNING, 2: c.MAGENTA, 3: c.OKGREEN}.get(comp.state.id, c.FAIL)
            print(f'Hardware Component {idx + 1}\n\tname: {color}{comp.name}{c.ENDC}\n'
                  f'\ttype: {comp.type}')
            print(f'\tplugin name: {comp.plugin_name}\n'
                  f'\tstate: id={comp.state.id} label={color}{comp.state.label}{c.ENDC}\n'
                  '\tcommand interfaces')
            for iface in comp.command_interfaces:
                available = (f'{c.OKBLUE}[available]{c.ENDC}' if iface.is_available
                             else f'{c.WARNING}[unavailable]{c.ENDC}')
                claimed = f'{c.OKBLUE}[claimed]{c.ENDC}' if iface.is_claimed else '[unclaimed]'
                print(f'\t\t{iface.name} {available} {claimed}')
            if args.verbose:
                print('\tstate interfaces')
                for iface in comp.state_interfaces:
                    available = (f'{c.OKBLUE}[available]{c.ENDC}' if iface.is_available
                                 else f'{c.WARNING}[unavailable]{c.ENDC}')
                    print(f'\t\t{iface.name} {available}')
        return 0
    return _run(args, body)


def _load_controller(args):
    def body(node):
        response = _call(args, node, 'load_controller', {'name': args.controller_name})
        if not response.ok:
            return fail('Error loading controller, check controller_manager logs')
        if not args.set_state:
            print(f'Successfully loaded controller {args.controller_name}')
            return 0
        response = _call(args, node, 'configure_controller', {'name': args.controller_name})
        if not response.ok:
            return fail('Error configuring controller')
        if args.set_state == 'active':
            response = _switch(args, node, [args.controller_name], [])
            if not response.ok:
                return fail('Error activating controller, check controller_manager logs')
        print(f'Successfully loaded controller {args.controller_name} into state '
              f'{args.set_state}')
        return 0
    return _run(args, body)


def _set_controller_state(args):
    def body(node):
        name = args.controller_name
        controllers = _call(args, node, 'list_controllers').controller
        matched = [c for c in controllers if c.name == name]
        if not matched:
            return fail(f'controller {name} does not seem to be loaded')
        state = matched[0].state
        if args.state == 'inactive':
            if state == 'unconfigured':
                if not _call(args, node, 'configure_controller', {'name': name}).ok:
                    return fail('Error configuring controller, check controller_manager logs')
                print(f'Successfully configured {name}')
                return 0
            if state == 'active':
                if not _switch(args, node, [], [name]).ok:
                    return fail('Error stopping controller, check controller_manager logs')
                print(f'Successfully deactivated {name}')
                return 0
            return fail(f"cannot put {name} in 'inactive' state from its current state {state}")
        if state != 'inactive':
            return fail(f'cannot activate {name} from its current state {state}')
        if not _switch(args, node, [name], []).ok:
            return fail('Error activating controller, check controller_manager logs')
        print(f'Successfully activated {name}')
        return 0
    return _run(args, body)


def _switch_controllers(args):
    def body(node):
        response = _switch(args, node, args.activate or [], args.deactivate or [],
                           args.strict, args.activate_asap, args.switch_timeout)
        if not response.ok:
            return fail('Error switching controllers, check controller_manager logs')
        print('Successfully switched controllers')
        return 0
    return _run(args, body)


def _unload_controller(args):
    def body(node):
        response = _call(args, node, 'unload_controller', {'name': args.controller_name})
        if not response.ok:
            return fail('Error unloading controller, check controller_manager logs')
        print(f'Successfully unloaded controller {args.controller_name}')
        return 0
    return _run(args, body)


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


def add_command(subparsers):
    """
    Add the ``control`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('control', help='Various control related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')

    p = verbs.add_parser('list_controllers',
                         help='Output the list of loaded controllers, their type and status')
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
    _common(p)
    p.set_defaults(main=_list_controllers)

    p = verbs.add_parser('list_hardware_interfaces',
                         help='Output the list of available command and state interfaces')
    p.add_argument('-v', '--verbose', action='store_true',
                   help='List hardware interfaces and their data types')
    _common(p)
    p.set_defaults(main=_list_hardware_interfaces)

    p = verbs.add_parser('list_hardware_components',
                         help='Output the list of available hardware components')
    p.add_argument('-v', '--verbose', action='store_true',
                   help='List hardware components with command and state interfaces')
    _common(p)
    p.set_defaults(main=_list_hardware_components)

    p = verbs.add_parser('list_controller_types',
                         help='Output the available controller types and their base classes')
    _common(p)
    p.set_defaults(main=_list_controller_types)

    p = verbs.add_parser('load_controller', help='Load a controller in a controller manager')
    p.add_argument('controller_name', help='Name of the controller')
    p.add_argument('--set-state', choices=['inactive', 'active'],
                   help='Set the state of the loaded controller')
    _common(p)
    p.set_defaults(main=_load_controller)

    p = verbs.add_parser('set_controller_state', help='Adjust the state of the controller')
    p.add_argument('controller_name', help='Name of the controller to be changed')
    p.add_argument('state', choices=['inactive', 'active'],
                   help='State in which the controller should be changed to')
    _common(p)
    p.set_defaults(main=_set_controller_state)

    p = verbs.add_parser('switch_controllers', help='Switch controllers in a controller manager')
    p.add_argument('--deactivate', nargs='*', default=[], help='Name of the controllers to be '
                   'deactivated')
    p.add_argument('--activate', nargs='*', default=[], help='Name of the controllers to be '
                   'activated')
    p.add_argument('--strict', action='store_true', help='Strict switch')
    p.add_argument('--activate-asap', action='store_true', help='Start asap controllers')
    p.add_argument('--switch-timeout', type=float, default=5.0,
                   help='Timeout for switching controllers')
    _common(p)
    p.set_defaults(main=_switch_controllers)

    p = verbs.add_parser('unload_controller', help='Unload a controller in a controller manager')
    p.add_argument('controller_name', help='Name of the controller')
    _common(p)
    p.set_defaults(main=_unload_controller)
