# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 service list|find|type|call`` with the output formats of ros2service (jazzy).

``call`` prints ``requester: making request: <repr>`` then ``response:`` and the response
repr, each followed by a blank line, as upstream.
"""

import time

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import is_hidden_name
from amr_description.cli.common import spin_once
from amr_description.cli.common import wait_for_graph
from amr_description.cli.daemon import graph_node
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb


def _service_types(node, name):
    for service, types in node.get_service_names_and_types():
        if service == name:
            return types
    return []


def _full_name(name):
    return name if name.startswith('/') else '/' + name


def _list(args):
    with graph_node(args, default_node_name()) as node:
        services = wait_for_graph(node, lambda n: n.get_service_names_and_types(),
                                  settle=args.spin_time, minimum=args.spin_time,
                                  maximum=args.spin_time)
        own = node.get_fully_qualified_name() + '/'
    services = [(n, t) for n, t in services if not n.startswith(own)
                and (args.include_hidden_services or not is_hidden_name(n))]
    if args.count_services:
        print(len(services))
        return 0
    for name, types in services:
        print(f'{name} [{", ".join(types)}]' if args.show_types else name)
    return 0


def _find(args):
    with graph_node(args, default_node_name()) as node:
        services = wait_for_graph(node, lambda n: n.get_service_names_and_types(),
                                  settle=args.spin_time, minimum=args.spin_time,
                                  maximum=args.spin_time)
    found = [name for name, types in services if args.service_type in types
             and (args.include_hidden_services or not is_hidden_name(name))]
    if args.count_services:
        print(len(found))
        return 0
    for name in found:
        print(name)
    return 0


def _type(args):
    name = _full_name(args.service_name)
    with graph_node(args, default_node_name()) as node:
        types = wait_for_graph(node, lambda n: _service_types(n, name), settle=0.0,
                               minimum=0.0, maximum=args.spin_time, ready=bool)
    if not types:
        return fail(f"Unknown service '{args.service_name}'")
    for type_name in types:
        print(type_name)
    return 0


def _call(args):
    from amr_description.core.message_yaml.utilities import get_service
    from amr_description.core.message_yaml.set_message import message_from_values
    try:
        srv_class = get_service(args.service_type)
    except ValueError:
        return fail('The passed service type is invalid')
    try:
        request, setters = message_from_values(
            srv_class.Request, args.values, expand_header_auto=True, expand_time_now=True)
    except ValueError as exc:
        if str(exc).startswith('The passed value'):
            return fail(str(exc))
        return fail(f'Failed to populate field: {exc}')
    except (AttributeError, TypeError) as exc:
        return fail(f'Failed to populate field: {exc}')
    period = 1.0 / args.rate if args.rate else None
    with cli_node(default_node_name()) as node:
        client = node.create_client(srv_class, args.service_name)
        if not client.wait_for_service(timeout_sec=1.0):
            print('waiting for service to become available...')
            deadline = time.monotonic() + args.timeout if args.timeout else None
            while not client.wait_for_service(timeout_sec=1.0):
                if deadline is not None and time.monotonic() > deadline:
                    return fail(f"Service '{args.service_name}' is not available")
        while True:
            if setters:
                now = node.get_clock().now().to_msg()
                for setter in setters:
                    setter(now)
            started = time.monotonic()
            print('requester: making request: %r\n' % request)
            future = client.call_async(request)
            while not future.done():
                spin_once(node, timeout_sec=0.1)
            if future.exception() is not None:
                return fail(f'Service call failed: {future.exception()}')
            print('response:\n%r\n' % future.result())
            if period is None:
                return 0
            time.sleep(max(0.0, period - (time.monotonic() - started)))


def _arguments_list(p):
    """Add the arguments of ``ros2 service list``."""
    p.add_argument('-t', '--show-types', action='store_true',
                   help='Additionally show the service type')
    p.add_argument('-c', '--count-services', action='store_true',
                   help='Only display the number of services discovered')
    p.add_argument('--include-hidden-services', action='store_true',
                   help='Consider hidden services as well')
    add_spin_time_argument(p)


VERB_LIST = Verb('Output a list of available services', _list, _arguments_list)
"""``ros2 service list``."""


def _arguments_find(p):
    """Add the arguments of ``ros2 service find``."""
    p.add_argument('service_type',
                   help="Name of the ROS service type to filter for (e.g. 'rcl_interfaces/srv/"
                        "ListParameters')")
    p.add_argument('-c', '--count-services', action='store_true',
                   help='Only display the number of services discovered')
    p.add_argument('--include-hidden-services', action='store_true',
                   help='Consider hidden services as well')
    add_spin_time_argument(p)


VERB_FIND = Verb('Output a list of available services of a given type', _find, _arguments_find)
"""``ros2 service find``."""


def _arguments_type(p):
    """Add the arguments of ``ros2 service type``."""
    p.add_argument('service_name', help="Name of the ROS service (e.g. '/add_two_ints')")
    add_spin_time_argument(p)


VERB_TYPE = Verb("Output a service's type", _type, _arguments_type)
"""``ros2 service type``."""


def _arguments_call(p):
    """Add the arguments of ``ros2 service call``."""
    p.add_argument('service_name', help="Name of the ROS service to call (e.g. '/add_two_ints')")
    p.add_argument('service_type', help="Type of the ROS service (e.g. 'std_srvs/srv/Empty')")
    p.add_argument('values', nargs='?', default='{}',
                   help='Values to fill the service request with in YAML format '
                        "(e.g. '{a: 1, b: 2}'), otherwise the request uses default values")
    p.add_argument('-r', '--rate', metavar='N', type=float,
                   help='Repeat the call at a specific rate in Hz')
    p.add_argument('--timeout', type=float, default=None,
                   help='Give up when the service is not available after this many seconds '
                        '(default: wait forever)')


VERB_CALL = Verb('Call a service', _call, _arguments_call)
"""``ros2 service call``."""


COMMAND = Command('Various service related sub-commands')
"""``ros2 service``: its verbs are registered in ``amr_description.service.verb``."""
