# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 node list``: fully qualified node names, sorted (as ros2node)."""

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import wait_for_graph


def fully_qualified(name, namespace):
    """
    Join a node name and namespace into ``/ns/name``.

    :param name: node name.
    :param namespace: its namespace (``/`` for the root).
    :returns: the fully qualified name.
    """
    return namespace.rstrip('/') + '/' + name


def _list(args):
    with cli_node(default_node_name()) as node:
        own = fully_qualified(node.get_name(), node.get_namespace())
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


def add_command(subparsers):
    """
    Add the ``node`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('node', help='Various node related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    p = verbs.add_parser('list', help='Output a list of available nodes')
    p.add_argument('-a', '--all', action='store_true',
                   help='Display all nodes even hidden ones')
    p.add_argument('-c', '--count-nodes', action='store_true',
                   help='Only display the number of nodes discovered')
    add_spin_time_argument(p)
    p.set_defaults(main=_list)
