# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 topic echo``: print the messages of a topic as ros2topic (jazzy) does.

Each message is printed as YAML followed by ``---``; with ``--csv`` as one comma-separated
line. With ``--field``, a selected value that is itself a message is printed as YAML (or CSV);
any other value (a number, a string, a list of messages, an array) is printed with Python's
``print`` followed by ``---``, exactly as upstream's echo prints values without ``__slots__``.
"""

import sys
import time

from amr_description.cli.common import add_no_daemon_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import spin_once
from amr_description.cli.common import wait_for_graph
from amr_description.cli.extension import Verb
from amr_description.cli.topic.api import add_qos_arguments
from amr_description.cli.topic.api import daemon_topic_type
from amr_description.cli.topic.api import expand
from amr_description.cli.topic.api import message_class
from amr_description.cli.topic.api import qos_from_args
from amr_description.cli.topic.api import topic_types

DEFAULT_TRUNCATE_LENGTH = 128


def select_field(msg, fields, spec):
    """
    Follow ``fields`` (attribute names) from ``msg``.

    :param msg: a message.
    :param fields: list of field names.
    :param spec: the ``--field`` text, for the error message.
    :returns: the selected value.
    :raises CliError: ``Invalid field 'spec': ...`` (upstream's wording).
    """
    value = msg
    for name in fields:
        try:
            value = getattr(value, name)
        except AttributeError as exc:
            raise CliError(f"Invalid field '{spec}': {exc}") from None
    return value


def format_value(value, *, csv=False, truncate_length=None, no_arr=False, no_str=False,
                 flow_style=False):
    r"""
    Return the text ``ros2 topic echo`` prints for one (possibly selected) value.

    :param value: a message, or any field value selected with ``--field``.
    :param csv: one CSV line instead of YAML (messages only, as upstream).
    :param truncate_length: see :func:`amr_description.core.message_yaml.message_to_yaml`.
    :param no_arr: abbreviate arrays.
    :param no_str: abbreviate strings.
    :param flow_style: YAML flow style.
    :returns: the text, ending with ``---\n`` (YAML and plain values) or ``\n`` (CSV).
    """
    from amr_description.core.message_yaml.convert import message_to_csv
    from amr_description.core.message_yaml.convert import message_to_yaml
    if not hasattr(value, 'get_fields_and_field_types'):
        return f'{value}\n---\n'
    if csv:
        return message_to_csv(value, truncate_length=truncate_length, no_arr=no_arr,
                              no_str=no_str) + '\n'
    return message_to_yaml(value, truncate_length=truncate_length, no_arr=no_arr,
                           no_str=no_str, flow_style=flow_style) + '---\n'


KNOWN_PUBLISHERS_WAIT = 10.0
"""Seconds echo waits for its node to discover the publishers a daemon reported."""
WARN_SETTLE = 1.0
"""Seconds the discovered graph stays unchanged before "does not appear to be published"."""
WARN_LATEST = 5.0
"""Seconds after which that warning is printed anyway."""


def _echo(args):
    fields = [f for f in args.field.split('.') if f] if args.field else []
    truncate = None if args.full_length else args.truncate_length
    deadline = time.monotonic() + args.timeout if args.timeout else None
    msg_class = message_class(args.message_type) if args.message_type else None
    type_name, known = (args.message_type, 0) if args.message_type else \
        daemon_topic_type(args.topic_name, args.no_daemon)
    if type_name is not None and msg_class is None:
        msg_class = message_class(type_name)
    with cli_node(default_node_name()) as node:
        topic = expand(node, args.topic_name)
        start = changed = time.monotonic()
        warned = False
        graph = None
        while type_name is None:
            types = topic_types(node, topic)
            if len(types) > 1:
                return fail(f"Cannot echo topic '{args.topic_name}', as it contains more "
                            f"than one type: [{', '.join(types)}]")
            if types:
                type_name = types[0]
                msg_class = message_class(type_name)
                break
            # warn once discovery looks done (the graph unchanged for a while), not after a
            # fixed time: on a loaded machine a busy graph takes seconds to be discovered
            now = time.monotonic()
            signature = (len(node.get_node_names_and_namespaces()),
                         len(node.get_topic_names_and_types()))
            if signature != graph:
                graph, changed = signature, now
            # (another node seen, and nothing new since WARN_SETTLE s)
            discovered = (graph[0] > 1 and now - changed > WARN_SETTLE) or \
                now - start > WARN_LATEST
            if not warned and now - start > 1.0 and discovered:
                print(f'WARNING: topic [{topic}] does not appear to be published yet',
                      file=sys.stderr)
                warned = True
            if deadline is not None and time.monotonic() > deadline:
                return 0
            spin_once(node, timeout_sec=0.05)
        # let discovery settle so the QoS can match every publisher (ros2cli choose_qos); with
        # the type from the daemon, until this node sees the publishers the daemon knows (a
        # transient-local publisher's messages reach only a subscription that matches it)
        # (with the daemon's count, seeing them all is enough: no settling time)
        wait_for_graph(node, lambda n: len(n.get_publishers_info_by_topic(topic)),
                       settle=0.0 if known else 0.2, minimum=0.0 if known else 0.1,
                       maximum=KNOWN_PUBLISHERS_WAIT if known else 1.0,
                       ready=lambda count: count >= known)
        qos = qos_from_args(args, 'sensor_data', node, topic)
        received = []

        def callback(msg):
            value = select_field(msg, fields, args.field) if fields else msg
            sys.stdout.write(format_value(
                value, csv=args.csv, truncate_length=truncate, no_arr=args.no_arr,
                no_str=args.no_str, flow_style=args.flow_style))
            sys.stdout.flush()
            received.append(True)

        node.create_subscription(msg_class, topic, callback, qos)
        while not (args.once and received):
            if deadline is not None and time.monotonic() > deadline:
                break
            spin_once(node, timeout_sec=0.1)
    return 0


def _arguments_echo(p):
    """Add the arguments of ``ros2 topic echo``."""
    p.add_argument('topic_name', help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument('message_type', nargs='?',
                   help="Type of the ROS message (e.g. 'std_msgs/msg/String')")
    p.add_argument('--csv', action='store_true',
                   help='Output all recursive fields separated by commas (e.g. for plotting).')
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
    add_no_daemon_argument(p)
    add_qos_arguments(p, 'subscribe', 'sensor_data')


VERB_ECHO = Verb('Output messages from a topic', _echo, _arguments_echo)
"""``ros2 topic echo``."""
