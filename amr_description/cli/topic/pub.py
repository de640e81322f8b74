# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 topic pub``: publish a message built from YAML values, as ros2topic (jazzy) does.

Prints ``Waiting for at least N matching subscription(s)...``, ``publisher: beginning loop``
and ``publishing #N: <repr>``; ``header: auto`` and ``stamp: now`` are stamped at each
publication (simulation time with ``-s/--use-sim-time``); after the last message the node
stays alive for ``--keep-alive`` seconds (default 0.1 s, as upstream) so that a subscription
matching late still receives it.
"""

import time

from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import fail
from amr_description.cli.common import spin_once
from amr_description.cli.extension import Verb
from amr_description.cli.topic.api import add_qos_arguments
from amr_description.cli.topic.api import expand
from amr_description.cli.topic.api import message_class
from amr_description.cli.topic.api import qos_from_args


def _pub(args):
    from amr_description.core.message_yaml.set_message import message_from_values
    from rclpy.qos import QoSDurabilityPolicy
    from rclpy.qos import QoSProfile
    from rclpy.qos import QoSReliabilityPolicy
    if args.rate <= 0.0:
        return fail('The rate must be positive')
    msg_class = message_class(args.message_type)
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
        qos = qos_from_args(args, 'default')
    ros_args = ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None
    with cli_node(args.node_name or default_node_name(), args=ros_args) as node:
        publisher = node.create_publisher(msg_class, expand(node, args.topic_name), qos)
        if args.use_sim_time and stamp_setters:
            # stamp with simulation time: wait (at most --spin-time) for the first /clock
            give_up = time.monotonic() + args.spin_time
            while node.get_clock().now().nanoseconds == 0 and time.monotonic() < give_up:
                spin_once(node, timeout_sec=0.05)
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
        # keep the node alive so late-matching subscriptions still get the (transient
        # local) message, as upstream's --keep-alive
        give_up = time.monotonic() + args.keep_alive
        while time.monotonic() < give_up:
            spin_once(node, timeout_sec=max(0.0, min(0.05, give_up - time.monotonic())))
    return 0


def _arguments_pub(p):
    """Add the arguments of ``ros2 topic pub``."""
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
    p.add_argument('-s', '--use-sim-time', action='store_true',
                   help='Enable ROS simulation time')
    p.add_argument('--spin-time', type=float, default=2.0, metavar='SPIN_TIME',
                   help='Spin time in seconds to wait for discovery (and, with -s, for the '
                        'first /clock; default: 2.0)')
    add_qos_arguments(p, 'publish', 'reliable, transient_local, depth 1')


VERB_PUB = Verb('Publish a message to a topic', _pub, _arguments_pub)
"""``ros2 topic pub``."""
