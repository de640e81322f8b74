# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 param list|get|describe``: read parameters, formats of ros2param (jazzy).

* ``list [NODE]``: without a node, ``/node:`` then ``  name`` lines for every node offering
  parameter services, sorted by node; with a node, only the ``  name`` lines; ``-t``
  (``--param-type``) appends `` (type: double)``.
* ``get NODE NAME``: ``Double value is: 0.4`` (``Boolean``, ``Integer``, ``String``; arrays
  ``... values are: <value>``); ``--hide-type`` prints only the value; exit 1 with
  ``Parameter not set`` / ``Node not found``.
* ``describe NODE NAME...``: ``Parameter name:``, ``  Type:``, ``  Description:`` (when set),
  ``  Constraints:`` with ``    Read only: true``, ``    Min value:``, ``    Max value:``,
  ``    Step:``, ``    Additional constraints:`` where they apply.
"""

import sys

from amr_description.cli.common import CliError
from amr_description.cli.extension import Verb
from amr_description.cli.param import api

_GET_LABELS = (None, 'Boolean value is:', 'Integer value is:', 'Double value is:',
               'String value is:', 'Byte values are:', 'Boolean values are:',
               'Integer values are:', 'Double values are:', 'String values are:')
_GET_FIELDS = (None, 'bool_value', 'integer_value', 'double_value', 'string_value',
               'byte_array_value', 'bool_array_value', 'integer_array_value',
               'double_array_value', 'string_array_value')


def _list(args):
    wanted = api.absolute_node_name(args.node_name)
    with api.param_node() as node:
        if wanted:
            if not api.wait_for_node(node, wanted, args.timeout, args.include_hidden_nodes):
                raise CliError('Node not found')
            names = [wanted]
        else:
            names = api.node_names(node, args.spin_time, args.include_hidden_nodes)
        services = {name for name, _ in api.graph(node).get_service_names_and_types()}
        code = 0
        for name in sorted(names):
            if f'{name}/list_parameters' not in services and not wanted:
                continue
            try:
                params = api.list_parameters(node, name, args.param_prefixes)
                types = {}
                if args.param_type and params:
                    types = {d.name: api.type_name(d.type)
                             for d in api.describe_parameters(node, name, params)}
            except CliError as exc:
                print(f"Exception while calling service of node '{name}': {exc}",
                      file=sys.stderr)
                code = 1
                continue
            if not wanted:
                print(f'{name}:')
            for param in params:
                print(f'  {param} (type: {types.get(param, "not set")})' if args.param_type
                      else f'  {param}')
    return code


def _get(args):
    name = api.absolute_node_name(args.node_name)
    with api.param_node() as node:
        if not api.wait_for_node(node, name, args.timeout, args.include_hidden_nodes):
            raise CliError('Node not found')
        values = api.get_parameters(node, name, [args.parameter_name])
    if not values:
        raise CliError('Parameter not set')
    value = values[0]
    if value.type == 0:
        print('Parameter not set.')
        return 0
    if not 0 < value.type < len(_GET_FIELDS):
        raise CliError(f"Unknown parameter type '{value.type}'")
    data = getattr(value, _GET_FIELDS[value.type])
    if args.hide_type:
        print(data)
    else:
        print(_GET_LABELS[value.type], data)
    return 0


def format_descriptor(descriptor):
    """
    Return the lines ``ros2 param describe`` prints for one descriptor.

    :param descriptor: an ``rcl_interfaces/msg/ParameterDescriptor``.
    :returns: the text, ending with a newline.
    """
    lines = [f'Parameter name: {descriptor.name}',
             f'  Type: {api.type_name(descriptor.type)}']
    if descriptor.description:
        lines.append(f'  Description: {descriptor.description}')
    lines.append('  Constraints:')
    if descriptor.read_only:
        lines.append('    Read only: true')
    ranges = list(descriptor.floating_point_range) + list(descriptor.integer_range)
    if ranges:
        lines.append(f'    Min value: {ranges[0].from_value}')
        lines.append(f'    Max value: {ranges[0].to_value}')
        if ranges[0].step:
            lines.append(f'    Step: {ranges[0].step}')
    if descriptor.additional_constraints:
        lines.append(f'    Additional constraints: {descriptor.additional_constraints}')
    return '\n'.join(lines) + '\n'


def _describe(args):
    name = api.absolute_node_name(args.node_name)
    with api.param_node() as node:
        if not api.wait_for_node(node, name, args.timeout, args.include_hidden_nodes):
            raise CliError('Node not found')
        descriptors = api.describe_parameters(node, name, args.parameter_names)
    for descriptor in descriptors:
        sys.stdout.write(format_descriptor(descriptor))
    return 0


def _arguments_list(p):
    """Add the arguments of ``ros2 param list``."""
    api.add_node_arguments(p, optional=True)
    p.add_argument('--param-prefixes', nargs='+', default=[],
                   help='Only list parameters with the provided prefixes')
    p.add_argument('-t', '--param-type', action='store_true',
                   help='Print parameter types with parameter names')
    p.add_argument('--spin-time', type=float, default=3.0, metavar='SECONDS',
                   help='Spin time in seconds to wait for discovery of all nodes (default: '
                        '3.0)')
    p.add_argument('--timeout', metavar='N', type=float, default=10.0,
                   help='Wait for N seconds until the named node becomes available (default '
                        '10.0 sec; there is no daemon)')


VERB_LIST = Verb('Output a list of available parameters', _list, _arguments_list)
"""``ros2 param list``."""


def _arguments_get(p):
    """Add the arguments of ``ros2 param get``."""
    api.add_node_arguments(p)
    p.add_argument('parameter_name', help='Name of the parameter')
    p.add_argument('--hide-type', action='store_true', help='Hide the type information')
    api.add_timeout_arguments(p)


VERB_GET = Verb('Get parameter', _get, _arguments_get)
"""``ros2 param get``."""


def _arguments_describe(p):
    """Add the arguments of ``ros2 param describe``."""
    api.add_node_arguments(p)
    p.add_argument('parameter_names', nargs='+', help='Names of the parameters')
    api.add_timeout_arguments(p)


VERB_DESCRIBE = Verb(
    'Show descriptive information about declared parameters',
    _describe, _arguments_describe)
"""``ros2 param describe``."""
