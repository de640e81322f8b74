# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 action list`` with the output format of ros2action (jazzy).

An action ``A`` is known to the graph by its services ``A/_action/send_goal`` (type
``pkg/action/Name_SendGoal``), ``A/_action/get_result`` and ``A/_action/cancel_goal`` and its
topics ``A/_action/feedback`` and ``A/_action/status`` (rcl_action); the list is read from the
send-goal services, so the warm daemon answers it as it answers ``service list``. Names sorted;
``-t`` adds ``[type]``, ``-c`` prints the count.
"""

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import default_node_name
from amr_description.cli.common import wait_for_graph
from amr_description.cli.daemon import graph_node
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb

SEND_GOAL = '/_action/send_goal'
SEND_GOAL_TYPE = '_SendGoal'


def action_names_and_types(services):
    """
    Return ``[(action, [types])]`` sorted by name, from ``[(service, [types])]``.

    :param services: a graph's service names and types.
    """
    actions = []
    for name, types in services:
        if name.endswith(SEND_GOAL):
            kinds = [t[:-len(SEND_GOAL_TYPE)] for t in types if t.endswith(SEND_GOAL_TYPE)]
            if kinds:
                actions.append((name[:-len(SEND_GOAL)], kinds))
    return sorted(actions)


def _list(args):
    with graph_node(args, default_node_name()) as node:
        services = wait_for_graph(node, lambda n: n.get_service_names_and_types(),
                                  settle=args.spin_time, minimum=args.spin_time,
                                  maximum=args.spin_time)
    actions = action_names_and_types(services)
    if args.count_actions:
        print(len(actions))
        return 0
    for name, types in actions:
        print(f'{name} [{", ".join(types)}]' if args.show_types else name)
    return 0


def _arguments_list(p):
    """Add the arguments of ``ros2 action list``."""
    p.add_argument('-t', '--show-types', action='store_true',
                   help='Additionally show the action type')
    p.add_argument('-c', '--count-actions', action='store_true',
                   help='Only display the number of actions discovered')
    add_spin_time_argument(p)


VERB_LIST = Verb('Output a list of action names', _list, _arguments_list)
"""``ros2 action list``."""


COMMAND = Command('Various action related sub-commands')
"""``ros2 action``: its verbs are registered in ``amr_description.action.verb``."""
