# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Helpers shared by the ``ros2 topic`` verbs: names, types, QoS arguments (as ros2topic)."""

from amr_description.cli.common import CliError

QOS_PROFILES = ('default', 'sensor_data', 'services_default', 'parameters',
                'parameter_events', 'system_default', 'action_status_default')


def expand(node, topic):
    """
    Fully qualify a topic name relative to the CLI node (``/`` namespace).

    :param node: the CLI node.
    :param topic: a topic name as typed.
    :returns: the absolute name.
    :raises CliError: ``Invalid topic name 'x': ...`` on an invalid name.
    """
    from rclpy.expand_topic_name import expand_topic_name
    try:
        return expand_topic_name(topic, node.get_name(), node.get_namespace())
    except Exception as exc:  # rclpy raises several kinds for an invalid name
        raise CliError(f"Invalid topic name '{topic}': {exc}") from None


def topic_types(node, topic):
    """
    Return the types the graph knows for ``topic``.

    :param node: a node.
    :param topic: an absolute topic name.
    :returns: list of ``pkg/msg/Type`` strings (empty when unknown).
    """
    for name, types in node.get_topic_names_and_types():
        if name == topic:
            return types
    return []


DAEMON_AGE = 3.0
"""Seconds a daemon must have followed the graph before a verb takes a topic's type from it."""


def daemon_topic_type(topic_name, no_daemon=False):
    """
    Return ``(type, publishers)`` of a topic as a warm daemon knows it, else ``(None, 0)``.

    Only when the daemon (:mod:`amr_description.cli.daemon`) has followed the graph for
    :data:`DAEMON_AGE` seconds and knows exactly one type; no wait for discovery, no daemon
    started (the verb's own node looks the type up then).

    :param topic_name: the topic name as typed (relative names get a leading ``/``).
    :param no_daemon: ``--no-daemon``: never ask.
    :returns: ``('pkg/msg/Type', publisher count)`` or ``(None, 0)``.
    """
    if no_daemon:
        return None, 0
    import xmlrpc.client

    from amr_description.cli.daemon import DaemonNode
    from amr_description.cli.daemon import usable_daemon
    proxy = usable_daemon(DAEMON_AGE)
    if proxy is None:
        return None, 0
    try:
        daemon = DaemonNode(proxy)
        topic = expand(daemon, topic_name)
        types = topic_types(daemon, topic)
        publishers = daemon.count_publishers(topic)
    except (OSError, xmlrpc.client.Error):
        return None, 0
    return (types[0], publishers) if len(types) == 1 else (None, 0)


def message_class(type_name):
    """
    Import a message class by name.

    :param type_name: ``pkg/msg/Type`` or ``pkg/Type``.
    :returns: the class.
    :raises CliError: ``The passed message type is invalid`` (upstream's wording) and the
        reason, naming the type (a package not installed, no such type).
    """
    from amr_description.core.message_yaml.utilities import get_message
    try:
        return get_message(type_name)
    except ValueError as exc:  # upstream's words, then which type and why
        raise CliError(f'The passed message type is invalid: {exc}') from None


def qos_from_args(args, default_key, node=None, topic=None):
    """
    Return the QoS profile of a verb: preset, adapted to the publishers as ros2cli's choose_qos.

    :param args: parsed arguments holding the ``--qos-*`` options.
    :param default_key: preset used when ``--qos-profile`` is absent.
    :param node: a node to look at the publishers with (None: no adaptation).
    :param topic: the absolute topic name.
    :returns: an :class:`rclpy.qos.QoSProfile`.
    """
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


def add_qos_arguments(parser, verb, default_key):
    """
    Add the ``--qos-*`` options of ros2topic to a verb parser.

    :param parser: the verb's parser.
    :param verb: ``subscribe`` or ``publish`` (help text).
    :param default_key: default profile named in the help.
    """
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
