# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
``ros2 lifecycle nodes|list|get|set``, formats of ros2lifecycle (jazzy).

A node is a lifecycle node when it offers ``<node>/get_state`` of type
``lifecycle_msgs/srv/GetState``. ``nodes``: their full names (``-c`` the count, ``-a`` hidden
ones too). ``list NODE``: the transitions available from the node's state, each as
``- label [id]`` followed by ``\tStart: state`` and ``\tGoal: state`` (``-a``: the whole
transition graph). ``get [NODE]``: ``label [id]`` of its state, or ``/node: label [id]`` for
every lifecycle node when none is named. ``set NODE TRANSITION`` (label or id):
``Transitioning successful``, or ``Transitioning failed`` on stderr; an unknown transition
lists the available ones. A node that is not a lifecycle node is ``Node not found`` (exit 1).
"""

import sys

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import default_node_name
from amr_description.cli.common import wait_for_graph
from amr_description.cli.daemon import graph_node
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb
from amr_description.cli.node import fully_qualified
from amr_description.cli.param.api import call
from amr_description.cli.param.api import QUERY_RESEND

GET_STATE_TYPE = 'lifecycle_msgs/srv/GetState'

SERVICE_WAIT = 30.0
"""Seconds to wait for a lifecycle service of a node the graph has shown."""


def lifecycle_node_names(node_names, services):
    """
    Return the nodes among ``node_names`` that offer ``<node>/get_state`` (GetState).

    :param node_names: fully qualified node names.
    :param services: ``[(service name, [types])]`` of the graph.
    :returns: the lifecycle nodes, sorted.
    """
    offered = {name for name, types in services if GET_STATE_TYPE in types}
    return sorted(n for n in node_names if f'{n}/get_state' in offered)


def _lifecycle_nodes(args, include_hidden, wanted=None):
    with graph_node(args, default_node_name()) as node:
        def query(n):
            names = [fully_qualified(*pair) for pair in n.get_node_names_and_namespaces()]
            return lifecycle_node_names(names, n.get_service_names_and_types())
        if wanted is None:
            names = wait_for_graph(node, query, settle=args.spin_time,
                                   minimum=args.spin_time, maximum=args.spin_time)
        else:  # a named node: as soon as it is seen
            names = wait_for_graph(node, query, settle=0.0, minimum=0.0,
                                   maximum=args.spin_time, ready=lambda n: wanted in n)
    return [n for n in names if include_hidden or not n.rsplit('/', 1)[-1].startswith('_')]


def _absolute(name):
    return name if name.startswith('/') else '/' + name


def _nodes(args):
    names = _lifecycle_nodes(args, args.all)
    if args.count_nodes:
        print(len(names))
    elif names:
        print(*names, sep='\n')
    return 0


def _list(args):
    from lifecycle_msgs.srv import GetAvailableTransitions
    target = _absolute(args.node_name)
    if target not in _lifecycle_nodes(args, True, target):
        raise CliError('Node not found')
    service = 'get_transition_graph' if args.all else 'get_available_transitions'
    with cli_node(default_node_name()) as node:
        answer = call(node, GetAvailableTransitions, f'{target}/{service}',
                      GetAvailableTransitions.Request(), timeout=SERVICE_WAIT, resend=QUERY_RESEND)
    for t in answer.available_transitions:
        print(f'- {t.transition.label} [{t.transition.id}]\n'
              f'\tStart: {t.start_state.label}\n\tGoal: {t.goal_state.label}')
    return 0


def _get(args):
    from lifecycle_msgs.srv import GetState
    names = _lifecycle_nodes(args, args.include_hidden_nodes)
    if args.node_name:
        target = _absolute(args.node_name)
        if target not in _lifecycle_nodes(args, True, target):
            raise CliError('Node not found')
        names = [target]
    with cli_node(default_node_name()) as node:
        for name in names:
            try:
                state = call(node, GetState, f'{name}/get_state', GetState.Request(),
                             timeout=SERVICE_WAIT, service_timeout=args.timeout,
                             resend=QUERY_RESEND).current_state
            except CliError as exc:
                if args.node_name:
                    raise
                print(exc, file=sys.stderr)
                continue
            prefix = '' if args.node_name else f'{name}: '
            print(f'{prefix}{state.label} [{state.id}]')
    return 0


def _set(args):
    from lifecycle_msgs.srv import ChangeState
    from lifecycle_msgs.srv import GetAvailableTransitions
    target = _absolute(args.node_name)
    if target not in _lifecycle_nodes(args, True, target):
        raise CliError('Node not found')
    with cli_node(default_node_name()) as node:
        available = call(node, GetAvailableTransitions, f'{target}/get_available_transitions',
                         GetAvailableTransitions.Request(), timeout=SERVICE_WAIT,
                         resend=QUERY_RESEND).available_transitions
        chosen = next((t.transition for t in available
                       if t.transition.label == args.transition), None) or \
            next((t.transition for t in available
                  if str(t.transition.id) == args.transition), None)
        if chosen is None:
            raise CliError('Unknown transition requested, available ones are:' + ''.join(
                f'\n- {t.transition.label} [{t.transition.id}]' for t in available))
        request = ChangeState.Request()
        request.transition = chosen
        answer = call(node, ChangeState, f'{target}/change_state', request,
                      timeout=SERVICE_WAIT)
    if answer.success:
        print('Transitioning successful')
        return 0
    print('Transitioning failed', file=sys.stderr)
    return 0


def _arguments_nodes(p):
    """Add the arguments of ``ros2 lifecycle nodes``."""
    p.add_argument('-a', '--all', action='store_true',
                   help='Display all nodes even hidden ones')
    p.add_argument('-c', '--count-nodes', action='store_true',
                   help='Only display the number of nodes discovered')
    add_spin_time_argument(p)


def _arguments_list(p):
    """Add the arguments of ``ros2 lifecycle list``."""
    p.add_argument('node_name', help='Name of the ROS node')
    p.add_argument('-a', '--all', action='store_true', help='Display all existing transitions')
    add_spin_time_argument(p)


def _arguments_get(p):
    """Add the arguments of ``ros2 lifecycle get``."""
    p.add_argument('node_name', nargs='?', help='Name of the ROS node. If no name is provided, '
                   'then get the state for all nodes.')
    p.add_argument('--include-hidden-nodes', '-a', '--all', action='store_true',
                   help='Consider hidden nodes as well')
    p.add_argument('--timeout', metavar='N', type=float,
                   help='Maximum time to wait for response in seconds (default: waits '
                        'indefinitely)')
    add_spin_time_argument(p)


def _arguments_set(p):
    """Add the arguments of ``ros2 lifecycle set``."""
    p.add_argument('node_name', help='Name of the ROS node')
    p.add_argument('--include-hidden-nodes', action='store_true',
                   help='Consider hidden nodes as well')
    p.add_argument('transition', help='The lifecycle transition')
    add_spin_time_argument(p)


VERB_NODES = Verb('Output a list of nodes with lifecycle', _nodes, _arguments_nodes)
VERB_LIST = Verb('Output a list of available transitions', _list, _arguments_list)
VERB_GET = Verb('Get lifecycle state for one or more nodes', _get, _arguments_get)
VERB_SET = Verb('Trigger lifecycle state transition', _set, _arguments_set)
"""``ros2 lifecycle`` verbs."""

COMMAND = Command('Various lifecycle related sub-commands')
"""``ros2 lifecycle``: its verbs are registered in ``amr_description.lifecycle.verb``."""
