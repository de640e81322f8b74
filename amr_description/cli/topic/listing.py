# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 topic list|type|info|find``: graph queries with the output formats of ros2topic (jazzy).

``list -v`` prints ``Published topics:`` and ``Subscribed topics:`` sections of
`` * /name [type] N publisher(s)`` lines, each section followed by a blank line, as upstream.
"""

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import is_hidden_name
from amr_description.cli.common import wait_for_graph
from amr_description.cli.daemon import graph_node
from amr_description.cli.extension import Verb
from amr_description.cli.topic.api import expand
from amr_description.cli.topic.api import topic_types


def _graph_topics(args):
    """Return ``[(name, types, publishers, subscribers)]`` after discovery settled."""
    with graph_node(args, default_node_name()) as node:
        topics = wait_for_graph(node, lambda n: n.get_topic_names_and_types(),
                                settle=args.spin_time, minimum=args.spin_time,
                                maximum=args.spin_time)
        result = [(name, types, node.count_publishers(name), node.count_subscribers(name))
                  for name, types in topics
                  if args.include_hidden_topics or not is_hidden_name(name)]
    return result


def format_verbose(topics, publishers):
    """
    Return one section of ``ros2 topic list -v``.

    :param topics: ``[(name, types, publisher_count, subscriber_count)]``.
    :param publishers: True for ``Published topics:``, False for ``Subscribed topics:``.
    :returns: the section text, ending with a newline (upstream prints it with ``print``).
    """
    text = ('Published' if publishers else 'Subscribed') + ' topics:\n'
    for name, types, pubs, subs in topics:
        count = pubs if publishers else subs
        if count:
            word = 'publisher' if publishers else 'subscriber'
            text += f' * {name} [{", ".join(types)}] {count} {word}{"s" if count > 1 else ""}\n'
    return text


def _list(args):
    topics = _graph_topics(args)
    if args.count_topics:
        print(len(topics))
    elif topics and args.verbose:
        print(format_verbose(topics, True))
        print(format_verbose(topics, False))
    else:
        for name, types, _, _ in topics:
            print(f'{name} [{", ".join(types)}]' if args.show_types else name)
    return 0


def _find(args):
    topics = _graph_topics(args)
    found = [name for name, types, _, _ in topics if args.topic_type in types]
    if args.count_topics:
        print(len(found))
    else:
        for name in found:
            print(name)
    return 0


def _type(args):
    with graph_node(args, default_node_name()) as node:
        topic = expand(node, args.topic_name)
        types = wait_for_graph(node, lambda n: topic_types(n, topic), settle=0.0,
                               minimum=0.0, maximum=args.spin_time, ready=bool)
    if not types:
        return fail(f"Unknown topic '{args.topic_name}'")
    for type_name in types:
        print(type_name)
    return 0


def _info(args):
    # The counts are the graph's: the warm daemon's, or this node's after the whole spin time
    # (a snapshot taken as soon as the type is known can miss a publisher not yet discovered).
    with graph_node(args, default_node_name()) as node:
        topic = expand(node, args.topic_name)
        types = wait_for_graph(node, lambda n: topic_types(n, topic), settle=args.spin_time,
                               minimum=args.spin_time, maximum=args.spin_time)
        if not types:
            return fail(f"Unknown topic '{args.topic_name}'")
        publishers = node.get_publishers_info_by_topic(topic)
        subscriptions = node.get_subscriptions_info_by_topic(topic)
    line_end = '\n\n' if args.verbose else '\n'
    print(f'Type: {", ".join(types)}', end=line_end)
    print(f'Publisher count: {len(publishers)}', end=line_end)
    if args.verbose:
        for info in publishers:
            print(info, end='\n\n')
    print(f'Subscription count: {len(subscriptions)}', end=line_end)
    if args.verbose:
        for info in subscriptions:
            print(info, end='\n\n')
    return 0


def _arguments_list(p):
    """Add the arguments of ``ros2 topic list``."""
    p.add_argument('-t', '--show-types', action='store_true',
                   help='Additionally show the topic type')
    p.add_argument('-c', '--count-topics', '--count', action='store_true',
                   help='Only display the number of topics discovered')
    p.add_argument('--include-hidden-topics', '-a', '--all', action='store_true',
                   help='Consider hidden topics as well')
    p.add_argument('-v', '--verbose', action='store_true',
                   help='List full details about each topic')
    add_spin_time_argument(p)


VERB_LIST = Verb('Output a list of available topics', _list, _arguments_list)
"""``ros2 topic list``."""


def _arguments_find(p):
    """Add the arguments of ``ros2 topic find``."""
    p.add_argument('topic_type',
                   help="Name of the ROS topic type to filter for (e.g. 'std_msg/msg/String')")
    p.add_argument('-c', '--count-topics', action='store_true',
                   help='Only display the number of topics discovered')
    p.add_argument('--include-hidden-topics', action='store_true',
                   help='Consider hidden topics as well')
    add_spin_time_argument(p)


VERB_FIND = Verb('Output a list of available topics of a given type', _find, _arguments_find)
"""``ros2 topic find``."""


def _arguments_type(p):
    """Add the arguments of ``ros2 topic type``."""
    p.add_argument('topic_name', help="Name of the ROS topic to get type (e.g. '/chatter')")
    add_spin_time_argument(p)


VERB_TYPE = Verb("Print a topic's type", _type, _arguments_type)
"""``ros2 topic type``."""


def _arguments_info(p):
    """Add the arguments of ``ros2 topic info``."""
    p.add_argument('topic_name', help="Name of the ROS topic to get info (e.g. '/chatter')")
    p.add_argument('-v', '--verbose', action='store_true',
                   help='Prints detailed information like the node name, node namespace, '
                        'topic type, GUID and QoS Profile of the publishers and subscribers')
    add_spin_time_argument(p)


VERB_INFO = Verb('Print information about a topic', _info, _arguments_info)
"""``ros2 topic info``."""
