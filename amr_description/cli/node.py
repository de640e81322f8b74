# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
``ros2 node list|info``, formats of ros2node (jazzy).

``list``: fully qualified node names, sorted. ``info NODE``: the node name, then the sections
``  Subscribers:``, ``  Publishers:``, ``  Service Servers:``, ``  Service Clients:``,
``  Action Servers:``, ``  Action Clients:``, each followed by ``    /name: type[, type]``
lines (an empty line when the section is empty, as upstream's ``print(*[], sep='\n')``);
hidden topics and services are left out unless ``--include-hidden``; a missing node gives
``Unable to find node '/x'`` and exit 1.
"""

import sys

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import CliError
from amr_description.cli.common import default_node_name
from amr_description.cli.common import is_hidden_name
from amr_description.cli.common import wait_for_graph
from amr_description.cli.daemon import graph_node
from amr_description.cli.daemon import node_endpoints
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb


def fully_qualified(name, namespace):
    """
    Join a node name and namespace into ``/ns/name``.

    :param name: node name.
    :param namespace: its namespace (``/`` for the root).
    :returns: the fully qualified name.
    """
    return namespace.rstrip('/') + '/' + name


def _list(args):
    with graph_node(args, default_node_name()) as node:
        # our own node is left out; the daemon's is listed with --all, as upstream's
        own = None if getattr(node, 'settled', False) else \
            fully_qualified(node.get_name(), node.get_namespace())
        names = wait_for_graph(
            node, lambda n: sorted(fully_qualified(*pair)
                                   for pair in n.get_node_names_and_namespaces()),
            settle=args.spin_time, minimum=args.spin_time, maximum=args.spin_time)
    names = [n for n in names if n != own
             and (args.all or not n.rsplit('/', 1)[-1].startswith('_'))]
    if args.count_nodes:
        print(len(names))
        return 0
    for name in names:
        print(name)
    return 0


def format_section(title, names_and_types):
    r"""
    Return one section of ``ros2 node info``.

    :param title: e.g. ``'Publishers'``.
    :param names_and_types: ``[(name, [type, ...]), ...]``.
    :returns: ``'  Title:\n'`` followed by ``'    name: types'`` lines, or by one empty line.
    """
    lines = [f'    {name}: {", ".join(types)}' for name, types in names_and_types]
    return f'  {title}:\n' + '\n'.join(lines) + '\n'


def _split_ns(full_name):
    namespace, _, name = full_name.rpartition('/')
    return name, namespace or '/'


def _info(args):
    target = args.node_name if args.node_name.startswith('/') else '/' + args.node_name
    with graph_node(args, default_node_name()) as node:
        def matches(n):
            return [fully_qualified(*pair)
                    for pair in n.get_node_names_and_namespaces()].count(target)
        settled = getattr(node, 'settled', False)  # a warm daemon: the graph is known
        count = matches(node) if settled else wait_for_graph(
            node, matches, settle=0.5, minimum=0.0, maximum=args.spin_time, ready=bool)
        if not count:
            raise CliError(f"Unable to find node '{args.node_name}'")
        if count > 1:
            print(f'There are {count} nodes in the graph with the exact name "{target}". '
                  'You are seeing information about only one of them.', file=sys.stderr)
        name, namespace = _split_ns(target)
        if settled:
            sections = node.node_endpoints(name, namespace)
        else:
            # the node's own endpoints are announced a little after the node itself
            wait_for_graph(node, lambda n: (
                n.get_publisher_names_and_types_by_node(name, namespace),
                n.get_service_names_and_types_by_node(name, namespace)), settle=0.5,
                minimum=0.0, maximum=args.spin_time)
            sections = node_endpoints(node, name, namespace)

    def visible(items):
        return [(n, t) for n, t in items if args.include_hidden or not is_hidden_name(n)]
    print(target)
    for title, items in sections:
        sys.stdout.write(format_section(title, visible(items)))
    return 0


def _arguments_list(p):
    """Add the arguments of ``ros2 node list``."""
    p.add_argument('-a', '--all', action='store_true',
                   help='Display all nodes even hidden ones')
    p.add_argument('-c', '--count-nodes', action='store_true',
                   help='Only display the number of nodes discovered')
    add_spin_time_argument(p)


VERB_LIST = Verb('Output a list of available nodes', _list, _arguments_list)
"""``ros2 node list``."""


def _arguments_info(p):
    """Add the arguments of ``ros2 node info``."""
    p.add_argument('node_name', help='Node name to request information')
    p.add_argument('--include-hidden', action='store_true', help='Display hidden topics, '
                   'services, and actions as well')
    add_spin_time_argument(p, default=10.0)  # the longest wait: it ends when the node is seen


VERB_INFO = Verb('Output information about a node', _info, _arguments_info)
"""``ros2 node info``."""


COMMAND = Command('Various node related sub-commands')
"""``ros2 node``: its verbs are registered in ``amr_description.node.verb``."""
