# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 param set|delete|load|dump``: change and save parameters, formats of ros2param (jazzy).

* ``set NODE NAME VALUE [NAME VALUE ...]``: ``Set parameter successful`` or, on stderr,
  ``Setting parameter failed: <reason>`` (``name: `` in front with several pairs).
* ``delete NODE NAME``: ``Deleted parameter successfully`` / ``Deleting parameter failed``.
* ``load NODE FILE``: ``Set parameter <name> successful`` per parameter (failures on stderr);
  sections for the node by absolute or relative name, ``/**`` with ``--use-wildcard``.
* ``dump NODE``: ``{/node: {ros__parameters: {...}}}`` as ``yaml.dump`` writes it (keys
  sorted, dotted names nested), loadable by ``--params-file`` and ``ros2 param load``.
"""

import sys

from amr_description.cli.common import CliError
from amr_description.cli.extension import Verb
from amr_description.cli.param import api
import yaml


def _reachable(node, args):
    name = api.absolute_node_name(args.node_name)
    if not api.wait_for_node(node, name, args.timeout, args.include_hidden_nodes):
        raise CliError('Node not found')
    return name


def _report(results, names, success, failure, with_names):
    code = 0
    for name, result in zip(names, results):
        ok = result.successful
        msg = success if ok else failure
        if result.reason:
            msg += ': ' + result.reason
        if with_names:
            msg = f'{name}: {msg}'
        print(msg, file=sys.stdout if ok else sys.stderr)
        code = code or (0 if ok else 1)
    return code


def _set(args):
    pairs = args.params_and_values
    if len(pairs) % 2:
        raise CliError('Parameters must be provided as name/value pairs: name value '
                       f'[name value ...]. Got {len(pairs)} argument(s).')
    from rcl_interfaces.msg import Parameter
    params = [Parameter(name=n, value=api.parameter_value_from_string(v))
              for n, v in zip(pairs[::2], pairs[1::2])]
    with api.param_node() as node:
        name = _reachable(node, args)
        results = api.set_parameters(node, name, params,
                                     service_timeout=args.service_timeout)
    _report(results, [p.name for p in params], 'Set parameter successful',
            'Setting parameter failed', len(params) > 1)
    return 0


def _delete(args):
    from rcl_interfaces.msg import Parameter
    from rcl_interfaces.msg import ParameterValue
    param = Parameter(name=args.parameter_name, value=ParameterValue(type=0))
    with api.param_node() as node:
        name = _reachable(node, args)
        results = api.set_parameters(node, name, [param],
                                     service_timeout=args.service_timeout)
    _report(results, [param.name], 'Deleted parameter successfully',
            'Deleting parameter failed', False)
    return 0


def parameters_from_file(path, node_name, use_wildcard=False):
    """
    Return the flat parameters a parameter file holds for ``node_name``.

    :param path: the YAML file (``ros2 param dump`` format).
    :param node_name: absolute node name.
    :param use_wildcard: also take the ``/**`` section.
    :returns: dict name -> value, in file order.
    :raises CliError: one line naming the file when it is unreadable, malformed or has no
        section for the node.
    """
    from amr_description.core.ros_param_file import load_yaml
    from amr_description.core.ros_param_file import node_sections
    try:
        data = load_yaml(path)
        sections = node_sections(data, path)
    except ValueError as exc:
        raise CliError(str(exc)) from None
    relative = node_name.lstrip('/')
    params, matched = {}, False
    for pattern, values in sections:
        if pattern in (node_name, relative) or (use_wildcard and pattern == '/**'):
            params.update(values)
            matched = True
    if not matched:
        raise CliError(f'Param file does not contain parameters for {node_name}, only for '
                       f'nodes: {", ".join(p for p, _ in sections)}')
    return params


def _load(args):
    with api.param_node() as node:
        name = _reachable(node, args)
        values = parameters_from_file(args.parameter_file, name, args.use_wildcard)
        params = [api.parameter_msg(n, v) for n, v in values.items()]
        results = api.set_parameters(node, name, params)
    for param, result in zip(params, results):
        msg = f'Set parameter {param.name} ' + ('successful' if result.successful else 'failed')
        if result.reason:
            msg += ': ' + result.reason
        print(msg, file=sys.stdout if result.successful else sys.stderr)
    return 0


def dump_yaml(node_name, names, values):
    """
    Return the text ``ros2 param dump`` prints.

    :param node_name: absolute node name.
    :param names: parameter names.
    :param values: their ``ParameterValue`` messages, same order.
    :returns: the YAML text followed by an empty line, as upstream's ``print(yaml.dump())``.
    """
    params = {}
    for name, value in zip(names, values):
        target = params
        *parents, leaf = name.split('.')
        for part in parents:
            target = target.setdefault(part, {})
        target[leaf] = api.value_of(value)
    return yaml.dump({node_name: {'ros__parameters': params}}, default_flow_style=False) + '\n'


def _dump(args):
    with api.param_node() as node:
        name = _reachable(node, args)
        names = api.list_parameters(node, name, service_timeout=args.service_timeout)
        values = api.get_parameters(node, name, names, service_timeout=args.service_timeout)
    sys.stdout.write(dump_yaml(name, names, values))
    return 0


def _arguments_set(p):
    """Add the arguments of ``ros2 param set``."""
    api.add_node_arguments(p)
    p.add_argument('params_and_values', nargs='+', metavar='name value',
                   help='Parameter name and value pair(s): name value [name value ...]')
    api.add_timeout_arguments(p)


VERB_SET = Verb('Set parameter', _set, _arguments_set)
"""``ros2 param set``."""


def _arguments_delete(p):
    """Add the arguments of ``ros2 param delete``."""
    api.add_node_arguments(p)
    p.add_argument('parameter_name', help='Name of the parameter')
    api.add_timeout_arguments(p)


VERB_DELETE = Verb('Delete parameter', _delete, _arguments_delete)
"""``ros2 param delete``."""


def _arguments_load(p):
    """Add the arguments of ``ros2 param load``."""
    api.add_node_arguments(p)
    p.add_argument('parameter_file', help='Parameter file')
    p.add_argument('--use-wildcard', action='store_true',
                   help="Load parameters in the '/**' namespace into the node")
    api.add_timeout_arguments(p)


VERB_LOAD = Verb('Load parameter file for a node', _load, _arguments_load)
"""``ros2 param load``."""


def _arguments_dump(p):
    """Add the arguments of ``ros2 param dump``."""
    api.add_node_arguments(p)
    api.add_timeout_arguments(p)


VERB_DUMP = Verb(
    'Show all of the parameters of a node in a YAML file format',
    _dump, _arguments_dump)
"""``ros2 param dump``."""
