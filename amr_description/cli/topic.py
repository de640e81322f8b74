# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
``ros2 topic list|echo|pub|hz|info|type``, with the output formats of ros2cli (jazzy).

Formats reproduced from ros2topic: ``echo`` prints the message YAML then ``---``; ``pub``
prints ``Waiting for at least N matching subscription(s)...``, ``publisher: beginning loop``
and ``publishing #N: <repr>``; ``hz`` prints ``average rate: %.3f`` and
``\tmin: %.3fs max: %.3fs std dev: %.5fs window: N`` once a second.
"""

import math
import sys
import time

from amr_description.cli.common import add_spin_time_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import is_hidden_name
from amr_description.cli.common import spin_once
from amr_description.cli.common import wait_for_graph

DEFAULT_TRUNCATE_LENGTH = 128
QOS_PROFILES = ('default', 'sensor_data', 'services_default', 'parameters',
                'parameter_events', 'system_default', 'action_status_default')


def rate_statistics(deltas):
    """
    Statistics of inter-arrival times as ``ros2 topic hz`` reports them.

    :param deltas: seconds between consecutive messages (at least one).
    :returns: ``(rate_hz, min_s, max_s, std_dev_s)``; the rate is 1/mean (0 when mean is 0),
        the standard deviation is the population one.
    """
    n = len(deltas)
    mean = sum(deltas) / n
    rate = 1.0 / mean if mean > 0.0 else 0.0
    std_dev = math.sqrt(sum((d - mean) ** 2 for d in deltas) / n)
    return rate, min(deltas), max(deltas), std_dev


def format_rate(deltas):
    r"""
    Return the two lines ``ros2 topic hz`` prints for a window of inter-arrival times.

    :param deltas: seconds between consecutive messages (at least one).
    :returns: ``'average rate: R\n\tmin: As max: Bs std dev: Cs window: N'`` with
        N = number of messages = ``len(deltas) + 1``.
    """
    rate, low, high, std_dev = rate_statistics(deltas)
    return (f'average rate: {rate:.3f}\n'
            f'\tmin: {low:.3f}s max: {high:.3f}s std dev: {std_dev:.5f}s '
            f'window: {len(deltas) + 1}')


def _expand(node, topic):
    """Fully qualify a topic name relative to the CLI node (``/`` namespace)."""
    from rclpy.expand_topic_name import expand_topic_name
    try:
        return expand_topic_name(topic, node.get_name(), node.get_namespace())
    except Exception as exc:  # rclpy raises several kinds for an invalid name
        raise CliError(f"Invalid topic name '{topic}': {exc}") from None


def _topic_types(node, topic):
    for name, types in node.get_topic_names_and_types():
        if name == topic:
            return types
    return []


def _message_class(type_name):
    from amr_description.core.message_yaml import get_message
    try:
        return get_message(type_name)
    except ValueError:
        raise CliError('The passed message type is invalid') from None


def _qos_from_args(args, default_key, node=None, topic=None):
    """Return the QoS profile: preset, adapted to the publishers as ros2cli's choose_qos does."""
    from rclpy.qos import QoSDurabilityPolicy
    from rclpy.qos import QoSHistoryPolicy
    from rclpy.qos import QoSPresetProfiles
    from rclpy.qos import QoSReliabilityPolicy
    profile = QoSPresetProfiles.get_from_short_key(args.qos_profile or default_key)
    explicit = any(v is not None for v in (
        args.qos_reliability, args.qos_durability, args.qos_history)) or args.qos_depth >= 0
    if node is not None and not explicit:
        infos = node.get_publishers_info_by_topic(topic)
        if infos:
            reliable = sum(i.qos_profile.reliability == QoSReliabilityPolicy.RELIABLE
                           for i in infos)
            latched = sum(i.qos_profile.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL
                          for i in infos)
            if reliable == len(infos):
                profile.reliability = QoSReliabilityPolicy.RELIABLE
            else:
                if reliable:
                    print('Some, but not all, publishers are offering '
                          'QoSReliabilityPolicy.RELIABLE. Falling back to '
                          'QoSReliabilityPolicy.BEST_EFFORT as it will connect to all '
                          'publishers')
                profile.reliability = QoSReliabilityPolicy.BEST_EFFORT
            if latched == len(infos):
                profile.durability = QoSDurabilityPolicy.TRANSIENT_LOCAL
            else:
                if latched:
                    print('Some, but not all, publishers are offering '
                          'QoSDurabilityPolicy.TRANSIENT_LOCAL. Falling back to '
                          'QoSDurabilityPolicy.VOLATILE as it will connect to all '
                          'publishers')
                profile.durability = QoSDurabilityPolicy.VOLATILE
        return profile
    if args.qos_reliability is not None:
        profile.reliability = QoSReliabilityPolicy.get_from_short_key(args.qos_reliability)
    if args.qos_durability is not None:
        profile.durability = QoSDurabilityPolicy.get_from_short_key(args.qos_durability)
    if args.qos_history is not None:
        profile.history = QoSHistoryPolicy.get_from_short_key(args.qos_history)
    if args.qos_depth >= 0:
        profile.depth = args.qos_depth
    return profile


def _add_qos_arguments(parser, verb, default_key):
    parser.add_argument(
        '--qos-profile', choices=QOS_PROFILES,
        help=f'Quality of service preset profile to {verb} with (default: {default_key})')
    parser.add_argument(
        '--qos-depth', metavar='N', type=int, default=-1,
        help=f'Queue size setting to {verb} with (overrides depth of --qos-profile)')
    parser.add_argument('--qos-history', choices=('system_default', 'keep_last', 'keep_all'),
                        help=f'History setting to {verb} with')
    parser.add_argument('--qos-reliability',
                        choices=('system_default', 'reliable', 'best_effort'),
                        help=f'Reliability setting to {verb} with (default: match publishers)')
    parser.add_argument('--qos-durability',
                        choices=('system_default', 'transient_local', 'volatile'),
                        help=f'Durability setting to {verb} with (default: match publishers)')


# --------------------------------------------------------------------------- list / type / info


def _list(args):
    with cli_node(default_node_name()) as node:
        topics = wait_for_graph(node, lambda n: n.get_topic_names_and_types(),
                                settle=args.spin_time, minimum=args.spin_time,
                                maximum=args.spin_time)
    topics = [(name, types) for name, types in topics
              if args.include_hidden_topics or not is_hidden_name(name)]
    if args.count_topics:
        print(len(topics))
        return 0
    for name, types in topics:
        print(f'{name} [{", ".join(types)}]' if args.show_types else name)
    return 0


def _type(args):
    with cli_node(default_node_name()) as node:
        topic = _expand(node, args.topic_name)
        types = wait_for_graph(node, lambda n: _topic_types(n, topic), settle=0.0,
                               minimum=0.0, maximum=args.spin_time, ready=bool)
    if not types:
        return fail(f"Unknown topic '{args.topic_name}'")
    for type_name in types:
        print(type_name)
    return 0


def _info(args):
    with cli_node(default_node_name()) as node:
        topic = _expand(node, args.topic_name)

        def snapshot(n):
            return (_topic_types(n, topic), n.count_publishers(topic),
                    n.count_subscribers(topic))
        types, _, _ = wait_for_graph(node, snapshot, settle=0.3, minimum=0.0,
                                     maximum=args.spin_time, ready=lambda v: bool(v[0]))
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


# --------------------------------------------------------------------------- echo


def _select_field(msg, fields, spec):
    value = msg
    for name in fields:
        try:
            value = getattr(value, name)
        except AttributeError as exc:
            raise CliError(f"Invalid field '{spec}': {exc}") from None
    return value


def _echo(args):
    from amr_description.core.message_yaml import message_to_yaml
    from amr_description.core.message_yaml import to_yaml
    fields = [f for f in args.field.split('.') if f] if args.field else []
    truncate = None if args.full_length else args.truncate_length
    deadline = time.monotonic() + args.timeout if args.timeout else None
    msg_class = _message_class(args.message_type) if args.message_type else None
    with cli_node(default_node_name()) as node:
        topic = _expand(node, args.topic_name)
        type_name = args.message_type
        start = time.monotonic()
        warned = False
        while type_name is None:
            types = _topic_types(node, topic)
            if len(types) > 1:
                return fail(f"Cannot echo topic '{args.topic_name}', as it contains more "
                            f"than one type: [{', '.join(types)}]")
            if types:
                type_name = types[0]
                msg_class = _message_class(type_name)
                break
            if not warned and time.monotonic() - start > 1.0:
                print(f'WARNING: topic [{topic}] does not appear to be published yet',
                      file=sys.stderr)
                warned = True
            if deadline is not None and time.monotonic() > deadline:
                return 0
            spin_once(node, timeout_sec=0.05)
        # let discovery settle so the QoS can match every publisher (ros2cli choose_qos)
        wait_for_graph(node, lambda n: len(n.get_publishers_info_by_topic(topic)),
                       settle=0.2, minimum=0.1, maximum=1.0)
        qos = _qos_from_args(args, 'sensor_data', node, topic)
        received = []

        def callback(msg):
            value = _select_field(msg, fields, args.field) if fields else msg
            if hasattr(value, 'get_fields_and_field_types'):
                text = message_to_yaml(value, truncate_length=truncate, no_arr=args.no_arr,
                                       no_str=args.no_str, flow_style=args.flow_style)
            elif isinstance(value, (list, tuple)) or hasattr(value, 'tolist'):
                text = to_yaml(list(value.tolist() if hasattr(value, 'tolist') else value),
                               flow_style=args.flow_style)
            else:
                text = f'{value}\n'
            sys.stdout.write(text + '---\n')
            sys.stdout.flush()
            received.append(True)

        node.create_subscription(msg_class, topic, callback, qos)
        while not (args.once and received):
            if deadline is not None and time.monotonic() > deadline:
                break
            spin_once(node, timeout_sec=0.1)
    return 0


# --------------------------------------------------------------------------- pub


def _pub(args):
    from amr_description.core.message_yaml import message_from_values
    from rclpy.qos import QoSDurabilityPolicy
    from rclpy.qos import QoSProfile
    from rclpy.qos import QoSReliabilityPolicy
    if args.rate <= 0.0:
        return fail('The rate must be positive')
    msg_class = _message_class(args.message_type)
    try:
        msg, stamp_setters = message_from_values(
            msg_class, args.values, expand_header_auto=True, expand_time_now=True)
    except ValueError as exc:
        if str(exc).startswith('The passed value'):
            return fail(str(exc))
        return fail(f'Failed to populate field: {exc}')
    except (AttributeError, TypeError) as exc:
        return fail(f'Failed to populate field: {exc}')
    times = 1 if args.once else args.times
    wait = args.wait_matching_subscriptions
    if wait is None:
        wait = 1 if times != 0 else 0
    if args.qos_profile is None and not any(v is not None for v in (
            args.qos_reliability, args.qos_durability, args.qos_history)) \
            and args.qos_depth < 0:
        qos = QoSProfile(reliability=QoSReliabilityPolicy.RELIABLE,
                         durability=QoSDurabilityPolicy.TRANSIENT_LOCAL, depth=1)
    else:
        qos = _qos_from_args(args, 'default')
    with cli_node(args.node_name or default_node_name()) as node:
        publisher = node.create_publisher(msg_class, _expand(node, args.topic_name), qos)
        ticks = 0
        while publisher.get_subscription_count() < wait:
            if ticks % 10 == 0:
                print(f'Waiting for at least {wait} matching subscription(s)...')
            ticks += 1
            spin_once(node, timeout_sec=0.1)
        print('publisher: beginning loop')
        count = 0

        def publish_once():
            nonlocal count
            if stamp_setters:
                now = node.get_clock().now().to_msg()
                for setter in stamp_setters:
                    setter(now)
            count += 1
            if args.print and count % args.print == 0:
                print('publishing #%d: %r\n' % (count, msg))
            publisher.publish(msg)

        publish_once()
        if times != 1:
            node.create_timer(1.0 / args.rate, publish_once)
            while times == 0 or count < times:
                spin_once(node, timeout_sec=0.1)
        time.sleep(args.keep_alive)
    return 0


# --------------------------------------------------------------------------- hz


def _hz(args):
    with cli_node(default_node_name()) as node:
        topic = _expand(node, args.topic_name)
        types = _topic_types(node, topic)
        while not types:
            spin_once(node, timeout_sec=0.1)
            types = _topic_types(node, topic)
        msg_class = _message_class(types[0])
        from rclpy.qos import qos_profile_sensor_data
        arrivals = []
        received = [0]

        def callback(_msg):
            received[0] += 1
            arrivals.append(time.monotonic())
            del arrivals[:-(args.window + 1)]

        node.create_subscription(msg_class, topic, callback, qos_profile_sensor_data,
                                 raw=True)
        last_print = time.monotonic()
        printed_at = 0
        while True:
            spin_once(node, timeout_sec=0.05)
            now = time.monotonic()
            if now - last_print < 1.0:
                continue
            last_print = now
            if received[0] == printed_at or len(arrivals) < 2:
                continue
            printed_at = received[0]
            print(format_rate([b - a for a, b in zip(arrivals, arrivals[1:])]))


# --------------------------------------------------------------------------- parser


def add_command(subparsers):
    """
    Add the ``topic`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('topic', help='Various topic related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')

    p = verbs.add_parser('list', help='Output a list of available topics')
    p.add_argument('-t', '--show-types', action='store_true',
                   help='Additionally show the topic type')
    p.add_argument('-c', '--count-topics', action='store_true',
                   help='Only display the number of topics discovered')
    p.add_argument('--include-hidden-topics', action='store_true',
                   help='Consider hidden topics as well')
    add_spin_time_argument(p)
    p.set_defaults(main=_list)

    p = verbs.add_parser('type', help="Print a topic's type")
    p.add_argument('topic_name', help="Name of the ROS topic to get type (e.g. '/chatter')")
    add_spin_time_argument(p)
    p.set_defaults(main=_type)

    p = verbs.add_parser('info', help='Print information about a topic')
    p.add_argument('topic_name', help="Name of the ROS topic to get info (e.g. '/chatter')")
    p.add_argument('-v', '--verbose', action='store_true',
                   help='Prints detailed information like the node name, node namespace, '
                        'topic type, GUID and QoS Profile of the publishers and subscribers')
    add_spin_time_argument(p)
    p.set_defaults(main=_info)

    p = verbs.add_parser('echo', help='Output messages from a topic')
    p.add_argument('topic_name', help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument('message_type', nargs='?',
                   help="Type of the ROS message (e.g. 'std_msgs/msg/String')")
    p.add_argument('--once', action='store_true', help='Print the first message received and '
                   'then exit')
    p.add_argument('--field', type=str, default=None,
                   help="Echo a selected field of a message, e.g. 'twist.linear'")
    p.add_argument('--no-arr', action='store_true', help="Don't print array fields of messages")
    p.add_argument('--no-str', action='store_true',
                   help="Don't print string fields of messages")
    p.add_argument('--flow-style', action='store_true',
                   help='Print collections in the block style (not available with csv format)')
    p.add_argument('--full-length', '-f', action='store_true',
                   help='Output all elements for arrays, bytes, and string with a length > '
                        "'--truncate-length'")
    p.add_argument('--truncate-length', '-l', type=int, default=DEFAULT_TRUNCATE_LENGTH,
                   help='The length to truncate arrays, bytes, and string to (default: '
                        f'{DEFAULT_TRUNCATE_LENGTH})')
    p.add_argument('--timeout', type=float, default=None,
                   help='Stop after this many seconds (default: wait forever)')
    _add_qos_arguments(p, 'subscribe', 'sensor_data')
    p.set_defaults(main=_echo)

    p = verbs.add_parser('pub', help='Publish a message to a topic')
    p.add_argument('topic_name', help="Name of the ROS topic to publish to (e.g. '/chatter')")
    p.add_argument('message_type', help="Type of the ROS message (e.g. 'std_msgs/String')")
    p.add_argument('values', nargs='?', default='{}',
                   help="Values to fill the message with in YAML format (e.g. 'data: Hello "
                        "World'), otherwise the message will be published with default values")
    p.add_argument('-r', '--rate', metavar='N', type=float, default=1.0,
                   help='Publishing rate in Hz (default: 1)')
    p.add_argument('-p', '--print', metavar='N', type=int, default=1,
                   help='Only print every N-th published message (default: 1)')
    group = p.add_mutually_exclusive_group()
    group.add_argument('-1', '--once', action='store_true', help='Publish one message and exit')
    group.add_argument('-t', '--times', type=int, default=0,
                       help='Publish this number of times and then exit')
    p.add_argument('-w', '--wait-matching-subscriptions', type=int, default=None,
                   help='Wait until finding the specified number of matching subscriptions. '
                        'Defaults to 1 when using "-1"/"--once"/"--times", otherwise 0.')
    p.add_argument('--keep-alive', metavar='N', type=float, default=0.1,
                   help='Keep publishing node alive for N seconds after the last msg '
                        '(default: 0.1)')
    p.add_argument('-n', '--node-name', help='Name of the created publishing node')
    _add_qos_arguments(p, 'publish', 'reliable, transient_local, depth 1')
    p.set_defaults(main=_pub)

    p = verbs.add_parser('hz', help='Print the average publishing rate to screen')
    p.add_argument('topic_name', help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument('--window', '-w', type=int, default=10000,
                   help='window size, in # of messages, for calculating rate (default: 10000)')
    p.set_defaults(main=_hz)
