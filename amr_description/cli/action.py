# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 action list|info|send_goal`` with the output formats of ros2action (jazzy).

An action ``A`` is known to the graph by its services ``A/_action/send_goal`` (type
``pkg/action/Name_SendGoal``), ``A/_action/get_result`` and ``A/_action/cancel_goal`` and its
topics ``A/_action/feedback`` and ``A/_action/status`` (rcl_action); the list is read from the
send-goal services, so the warm daemon answers it as it answers ``service list``. Names sorted;
``-t`` adds ``[type]``, ``-c`` prints the count.

``info`` lists the nodes with a client or a server of the action (rclpy's graph queries per
node). ``send_goal NAME TYPE GOAL [-f]`` waits for the server, prints ``Sending goal:`` with the
goal as YAML, ``Goal accepted with ID: <hex>``, with ``-f`` each ``Feedback:``, then
``Result:`` and ``Goal finished with status: SUCCEEDED|ABORTED|CANCELED``; Ctrl-C cancels the
goal (``Canceling goal...``, ``Goal canceled.``). A bad type or goal is one line on stderr
and exit code 1. Source: ``ros2action/verb/{info,send_goal}.py``.
"""

import time

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import spin_once
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


def _clients_and_servers(node, action):
    from rclpy.action import get_action_client_names_and_types_by_node
    from rclpy.action import get_action_server_names_and_types_by_node
    clients, servers = [], []
    for name, ns in node.get_node_names_and_namespaces():
        full = f"{ns.rstrip('/')}/{name}"
        for found, table in ((get_action_client_names_and_types_by_node(node, name, ns), clients),
                             (get_action_server_names_and_types_by_node(node, name, ns), servers)):
            table += [(full, types) for a, types in found if a == action]
    return sorted(clients), sorted(servers)


def _info(args):
    action = args.action_name if args.action_name.startswith('/') else '/' + args.action_name
    # a node of its own: rclpy's per-node action queries need an rcl node, not the daemon's
    with cli_node(default_node_name()) as node:
        clients, servers = wait_for_graph(node, lambda n: _clients_and_servers(n, action),
                                          settle=0.4, minimum=max(args.spin_time, 0.3),
                                          maximum=max(args.spin_time, 3.0))
    print(f'Action: {action}')
    for label, table in (('Action clients', clients), ('Action servers', servers)):
        print(f'{label}: {len(table)}')
        if not args.count:
            for name, types in table:
                print(f'    {name} [{", ".join(types)}]' if args.show_types else f'    {name}')
    return 0


def _arguments_info(p):
    """Add the arguments of ``ros2 action info``."""
    p.add_argument('action_name', help="Name of the ROS action to get info (e.g. '/fibonacci')")
    p.add_argument('-t', '--show-types', action='store_true',
                   help='Additionally show the action type')
    p.add_argument('-c', '--count', action='store_true',
                   help='Only display the number of action clients and action servers')
    add_spin_time_argument(p)


VERB_INFO = Verb('Print information about an action', _info, _arguments_info)
"""``ros2 action info``."""

STATUS_NAMES = {1: 'ACCEPTED', 2: 'EXECUTING', 3: 'CANCELING', 4: 'SUCCEEDED', 5: 'CANCELED',
                6: 'ABORTED'}
"""action_msgs/GoalStatus values as ros2action prints them (else UNKNOWN)."""


def _wait(node, future):
    while not future.done():
        spin_once(node, timeout_sec=0.1)
    return future.result()


def _send_goal(args):
    from amr_description.core.message_yaml.convert import message_to_yaml
    from amr_description.core.message_yaml.set_message import message_from_values
    from amr_description.core.message_yaml.utilities import get_action
    from rclpy.action import ActionClient
    try:
        action = get_action(args.action_type)
    except ValueError:
        return fail('The passed action type is invalid')
    try:
        goal, _ = message_from_values(action.Goal, args.goal)
    except (ValueError, AttributeError, TypeError) as exc:
        return fail(f'Failed to populate message fields: {exc}')
    name = f"_ros2cli_send_goal_{args.action_type.replace('/', '_')}"
    handle = None
    with cli_node(name) as node:
        client = ActionClient(node, action, args.action_name)
        try:
            print('Waiting for an action server to become available...')
            while not client.server_is_ready():
                spin_once(node, timeout_sec=0.1)
            print('Sending goal:\n     ' + message_to_yaml(goal))
            on_feedback = (lambda m: print('Feedback:\n    ' + message_to_yaml(m.feedback))) \
                if args.feedback else None
            handle = _wait(node, client.send_goal_async(goal, feedback_callback=on_feedback))
            if not handle.accepted:
                print('Goal was rejected.')
                handle = None
                return 0
            print(f'Goal accepted with ID: {bytes(handle.goal_id.uuid).hex()}\n')
            result = _wait(node, handle.get_result_async())
            handle = None
            print('Result:\n    ' + message_to_yaml(result.result))
            print(f'Goal finished with status: {STATUS_NAMES.get(result.status, "UNKNOWN")}')
            return 0
        except KeyboardInterrupt:
            if handle is None:
                raise
            print('Canceling goal...')
            deadline = time.monotonic() + 10.0
            cancel = handle.cancel_goal_async()
            while not cancel.done() and time.monotonic() < deadline:
                spin_once(node, timeout_sec=0.1)
            if cancel.done() and cancel.result().goals_canceling:
                print('Goal canceled.')
                return 0
            return fail('Failed to cancel goal')
        finally:
            client.destroy()


def _arguments_send_goal(p):
    """Add the arguments of ``ros2 action send_goal``."""
    p.add_argument('action_name', help="Name of the ROS action (e.g. '/fibonacci')")
    p.add_argument('action_type',
                   help="Type of the ROS action (e.g. 'example_interfaces/action/Fibonacci')")
    p.add_argument('goal', nargs='?', default='{}',
                   help="Goal request values in YAML format (e.g. '{order: 10}')")
    p.add_argument('-f', '--feedback', action='store_true',
                   help='Echo feedback messages for the goal')


VERB_SEND_GOAL = Verb('Send an action goal', _send_goal, _arguments_send_goal)
"""``ros2 action send_goal``."""


COMMAND = Command('Various action related sub-commands')
"""``ros2 action``: its verbs are registered in ``amr_description.action.verb``."""
