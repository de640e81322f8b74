# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``ros2 control`` verbs that list.

``list_controllers``, ``list_hardware_interfaces``, ``list_controller_types``,
``list_hardware_components``.
"""

from amr_description.cli.control.api import run
from amr_description.cli.extension import Verb
from amr_description.control import controller_manager_services as cms


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
    return run(args, body)


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
    return run(args, body)


def _list_controller_types(args):
    def body(node, cm):
        response = cms.list_controller_types(node, cm)
        for type_name, base in zip(response.types, response.base_classes):
            print(f'{type_name:70s} {base}')
        return 0
    return run(args, body)


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
    return run(args, body)


VERB_LIST_CONTROLLER_TYPES = Verb(
    'Output the available controller types and their base classes',
    _list_controller_types,
    description='Output the available controller types and their base classes')
"""``ros2 control list_controller_types``."""

VERB_LIST_CONTROLLERS = Verb(
    'Output the list of loaded controllers, their type and status',
    _list_controllers, _args_list_controllers,
    description='Output the list of loaded controllers, their type and status')
"""``ros2 control list_controllers``."""

VERB_LIST_HARDWARE_COMPONENTS = Verb(
    'Output the list of available hardware components',
    _list_hardware_components, _args_list_hardware_components,
    description='Output the list of available hardware components')
"""``ros2 control list_hardware_components``."""

VERB_LIST_HARDWARE_INTERFACES = Verb(
    'Output the list of available command and state interfaces',
    _list_hardware_interfaces, _args_list_hardware_interfaces,
    description='Output the list of available command and state interfaces')
"""``ros2 control list_hardware_interfaces``."""
