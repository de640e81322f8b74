# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Parameter-service calls and value conversions shared by the ``ros2 param`` verbs.

Behaviour reproduced from ros2param (jazzy): a value typed on the command line is read as
YAML and becomes a bool, integer, double, string or a homogeneous array of those (anything
else is a string); type names are ``boolean``, ``integer``, ``double``, ``string``,
``byte array``, ``boolean array``, ``integer array``, ``double array``, ``string array``,
``not set``; a node that is not in the graph gives ``Node not found``.
"""

import contextlib
import time

from amr_description.cli.common import CliError
from amr_description.cli.common import spin_once
from amr_description.cli.common import wait_for_graph
from amr_description.core.yaml_text import safe_load
import yaml

TYPE_NAMES = ('not set', 'boolean', 'integer', 'double', 'string', 'byte array',
              'boolean array', 'integer array', 'double array', 'string array')
"""``rcl_interfaces/msg/ParameterType`` value -> upstream type name."""

_VALUE_FIELDS = (None, 'bool_value', 'integer_value', 'double_value', 'string_value',
                 'byte_array_value', 'bool_array_value', 'integer_array_value',
                 'double_array_value', 'string_array_value')


def absolute_node_name(name):
    """
    Return ``name`` with a leading ``/`` (ros2node's get_absolute_node_name).

    :param name: a node name as typed, or None.
    :returns: the absolute name, or None.
    """
    if not name:
        return None
    return name if name.startswith('/') else '/' + name


def type_name(parameter_type):
    """
    Return the upstream name of a ``ParameterType`` value.

    :param parameter_type: int (0..9).
    :returns: e.g. ``'double array'``.
    """
    if 0 <= parameter_type < len(TYPE_NAMES):
        return TYPE_NAMES[parameter_type]
    return f'unknown ({parameter_type})'


def value_of(parameter_value):
    """
    Return the Python value of an ``rcl_interfaces/msg/ParameterValue`` (lists for arrays).

    :param parameter_value: the message.
    :returns: bool, int, float, str, list, or None when not set.
    """
    if 0 < parameter_value.type < len(_VALUE_FIELDS):
        value = getattr(parameter_value, _VALUE_FIELDS[parameter_value.type])
        if parameter_value.type >= 5:
            value = [v.item() if hasattr(v, 'item') else v for v in value]
            if parameter_value.type == 5:
                value = [v if isinstance(v, bytes) else bytes([v]) for v in value]
        return value
    return None


def parameter_value_from_string(text):
    """
    Build a ``ParameterValue`` from a command-line string, as ``ros2 param set`` guesses it.

    :param text: the value as typed (YAML).
    :returns: an ``rcl_interfaces/msg/ParameterValue``.
    """
    from rcl_interfaces.msg import ParameterType
    from rcl_interfaces.msg import ParameterValue
    value = ParameterValue()
    try:
        data = safe_load(text)
    except yaml.YAMLError:
        data = text
    if isinstance(data, bool):
        value.type, value.bool_value = ParameterType.PARAMETER_BOOL, data
    elif isinstance(data, int):
        value.type, value.integer_value = ParameterType.PARAMETER_INTEGER, data
    elif isinstance(data, float):
        value.type, value.double_value = ParameterType.PARAMETER_DOUBLE, data
    elif isinstance(data, list) and data and all(isinstance(v, bool) for v in data):
        value.type, value.bool_array_value = ParameterType.PARAMETER_BOOL_ARRAY, data
    elif isinstance(data, list) and data and all(
            isinstance(v, int) and not isinstance(v, bool) for v in data):
        value.type, value.integer_array_value = ParameterType.PARAMETER_INTEGER_ARRAY, data
    elif isinstance(data, list) and data and all(isinstance(v, float) for v in data):
        value.type, value.double_array_value = ParameterType.PARAMETER_DOUBLE_ARRAY, data
    elif isinstance(data, list) and data and all(isinstance(v, str) for v in data):
        value.type, value.string_array_value = ParameterType.PARAMETER_STRING_ARRAY, data
    else:
        value.type, value.string_value = ParameterType.PARAMETER_STRING, text
    return value


def parameter_msg(name, value):
    """
    Build an ``rcl_interfaces/msg/Parameter`` from a Python value (as a parameter file gives).

    :param name: parameter name.
    :param value: bool, int, float, str or a homogeneous list.
    :returns: the message.
    :raises CliError: one line naming the parameter when the value has no parameter type.
    """
    from rclpy.parameter import Parameter
    try:
        return Parameter(name, value=value).to_parameter_msg()
    except (TypeError, ValueError) as exc:
        raise CliError(f"Invalid value of parameter '{name}': {exc}") from None


@contextlib.contextmanager
def param_node():
    """
    Yield the CLI node of a param verb, with the warm daemon's relay when one runs.

    The daemon (``amr_description.cli.daemon``) then answers the graph questions and makes
    the parameter service calls, which a new node would make only after its discovery.
    """
    from amr_description.cli.common import cli_node
    from amr_description.cli.common import default_node_name
    from amr_description.cli.daemon import service_relay
    with cli_node(default_node_name()) as node:
        node.service_relay = service_relay()
        yield node


def graph(node):
    """Return what answers graph questions for ``node``: the daemon's graph, or the node."""
    relay = getattr(node, 'service_relay', None)
    return relay.graph if relay is not None else node


def wait_for_node(node, name, timeout, include_hidden=False):
    """
    Spin until ``name`` is in the graph, at most ``timeout`` seconds.

    :param node: the CLI node.
    :param name: absolute node name.
    :param timeout: seconds.
    :param include_hidden: accept hidden nodes.
    :returns: True when found.
    """
    def names(n):
        return {f'{ns.rstrip("/")}/{nm}' for nm, ns in n.get_node_names_and_namespaces()}
    if name in names(graph(node)):
        return True  # the daemon knows it already
    found = wait_for_graph(node, names, settle=0.0, minimum=0.0, maximum=timeout,
                           ready=lambda value: name in value)
    return name in found


def node_names(node, spin_time, include_hidden=False):
    """
    Return the absolute names of the nodes in the graph after discovery settled.

    :param node: the CLI node.
    :param spin_time: seconds to listen to discovery.
    :param include_hidden: keep nodes whose name starts with ``_``.
    :returns: sorted list of names, without the CLI node itself.
    """
    own = node.get_fully_qualified_name()

    def names_of(n):
        return sorted({f'{ns.rstrip("/")}/{nm}' for nm, ns in n.get_node_names_and_namespaces()})
    names = wait_for_graph(graph(node), names_of, settle=min(1.0, spin_time),
                           minimum=spin_time, maximum=spin_time)
    return [n for n in names if n != own
            and (include_hidden or not n.rsplit('/', 1)[-1].startswith('_'))]


def call(node, srv_type, service, request, timeout=5.0, service_timeout=None, resend=None):
    """
    Call ``service`` and return its response.

    :param node: the CLI node.
    :param srv_type: the service class.
    :param service: absolute service name.
    :param request: the request.
    :param timeout: seconds to wait for the service to appear.
    :param service_timeout: seconds to wait for the response (None: forever).
    :param resend: for a query that changes nothing (``get_state``): seconds after which an
        unanswered request is sent again, and again, the first answer taken (None: never).
        A server can match the client's request writer before its own response writer has
        matched the client's reader; its answer is then lost, and a CLI waiting forever for
        it hung in a 2026-11-26 test run (``ros2 lifecycle get``, 90 s).
    :returns: the response.
    :raises CliError: ``Wait for service timed out`` or the call's exception, on one line.
    """
    relay = getattr(node, 'service_relay', None)
    if relay is not None:
        response = relay(service, srv_type, request, service_timeout or 10.0)
        if response is not None:
            return response
    client = node.create_client(srv_type, service)
    try:
        give_up = time.monotonic() + timeout
        while not client.service_is_ready():
            if time.monotonic() > give_up:
                raise CliError('Wait for service timed out')
            spin_once(node, timeout_sec=0.05)
        futures = [client.call_async(request)]
        give_up = None if service_timeout is None else time.monotonic() + service_timeout
        again = None if resend is None else time.monotonic() + resend
        while not any(f.done() for f in futures):
            if give_up is not None and time.monotonic() > give_up:
                raise CliError(f"Timed out waiting for the response of '{service}'")
            if again is not None and time.monotonic() > again:
                futures.append(client.call_async(request))
                again = time.monotonic() + resend
            spin_once(node, timeout_sec=0.05)
        future = next(f for f in futures if f.done())
        if future.exception() is not None:
            raise CliError('Exception while calling service of node '
                           f"'{service.rsplit('/', 1)[0]}': {future.exception()}")
        return future.result()
    finally:
        node.destroy_client(client)


QUERY_RESEND = 5.0
"""
Seconds after which an unanswered query is sent again (``resend`` of :func:`call`).

The parameter queries (list, get, describe) and the lifecycle ones (``get_state``, the
available transitions). A lost answer (see :func:`call`) hung ``ros2 param get`` for 180 s
in a 2026-11-29 CI run; the queries change nothing, so sending them again is safe.
``set``, ``delete`` and lifecycle transitions are not resent.
"""


def _query(kwargs):
    """Return ``kwargs`` with ``resend`` set to :data:`QUERY_RESEND` unless given."""
    return {'resend': QUERY_RESEND, **kwargs}


def list_parameters(node, node_name, prefixes=(), **kwargs):
    """
    Return the sorted parameter names of ``node_name``.

    :param node: the CLI node.
    :param node_name: absolute node name.
    :param prefixes: only names under these prefixes.
    :returns: list of str.
    """
    from rcl_interfaces.srv import ListParameters
    request = ListParameters.Request(prefixes=list(prefixes))
    return sorted(call(node, ListParameters, f'{node_name}/list_parameters', request,
                       **_query(kwargs)).result.names)


def get_parameters(node, node_name, names, **kwargs):
    """
    Return the ``ParameterValue`` messages of ``names`` (empty when not set, as upstream).

    :param node: the CLI node.
    :param node_name: absolute node name.
    :param names: list of parameter names.
    :returns: list of ``ParameterValue``.
    """
    from rcl_interfaces.srv import GetParameters
    return list(call(node, GetParameters, f'{node_name}/get_parameters',
                     GetParameters.Request(names=list(names)), **_query(kwargs)).values)


def describe_parameters(node, node_name, names, **kwargs):
    """
    Return the ``ParameterDescriptor`` messages of ``names``.

    :param node: the CLI node.
    :param node_name: absolute node name.
    :param names: list of parameter names.
    :returns: list of ``ParameterDescriptor``.
    """
    from rcl_interfaces.srv import DescribeParameters
    return list(call(node, DescribeParameters, f'{node_name}/describe_parameters',
                     DescribeParameters.Request(names=list(names)),
                     **_query(kwargs)).descriptors)


def set_parameters(node, node_name, parameters, **kwargs):
    """
    Set parameters one by one (``set_parameters``) and return their results.

    :param node: the CLI node.
    :param node_name: absolute node name.
    :param parameters: list of ``rcl_interfaces/msg/Parameter``.
    :returns: list of ``SetParametersResult``.
    """
    from rcl_interfaces.srv import SetParameters
    return list(call(node, SetParameters, f'{node_name}/set_parameters',
                     SetParameters.Request(parameters=list(parameters)), **kwargs).results)


def add_node_arguments(parser, node_help='Name of the ROS node', optional=False):
    """
    Add ``node_name`` and ``--include-hidden-nodes`` to a verb parser.

    :param parser: the verb's parser.
    :param node_help: help of the node argument.
    :param optional: the node name may be omitted (``list``).
    """
    parser.add_argument('node_name', nargs='?' if optional else None, help=node_help)
    parser.add_argument('--include-hidden-nodes', action='store_true',
                        help='Consider hidden nodes as well')


def add_timeout_arguments(parser):
    """
    Add ``--timeout`` (node discovery) and ``--service-timeout`` to a verb parser.

    Without ros2cli's daemon a fresh CLI process needs up to a few seconds of discovery
    (measured here 0.3-2.7 s, more on a loaded machine), so the node wait defaults to 10 s
    where upstream's is 1 s; it ends as soon as the node is seen.

    :param parser: the verb's parser.
    """
    parser.add_argument('--timeout', metavar='N', type=float, default=10.0,
                        help='Wait for N seconds until node becomes available (default 10.0 '
                             'sec; there is no daemon)')
    parser.add_argument('--service-timeout', metavar='N', type=float,
                        help='Maximum time to wait for service response in seconds '
                             '(default: waits indefinitely)')
