# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
``ros2 topic hz|bw|delay``: rates, bandwidth and header delays, formats of ros2topic (jazzy).

* ``hz`` prints ``average rate: %.3f`` and
  ``\tmin: %.3fs max: %.3fs std dev: %.5fs window: N`` once a second;
* ``bw`` prints ``Subscribed to [/topic]`` then, once a second,
  ``<bw>/s from N messages`` and ``\tMessage size mean: A min: B max: C`` with sizes in
  ``B`` (under 1000 B/s), ``KB`` or ``MB`` (1000-based, two decimals), over a window of the
  last 100 messages (``-w``) of serialized (CDR) size;
* ``delay`` prints ``average delay: %.3f`` and
  ``\tmin: %.3fs max: %.3fs std dev: %.5fs window: N`` once a second: the age of each
  message's ``header.stamp`` on arrival, by the node's clock (``-s`` for sim time).
"""

import math
import time

from amr_description.cli.common import add_no_daemon_argument
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import default_node_name
from amr_description.cli.common import spin_once
from amr_description.cli.extension import Verb
from amr_description.cli.topic.api import daemon_topic_type
from amr_description.cli.topic.api import expand
from amr_description.cli.topic.api import message_class
from amr_description.cli.topic.api import topic_types

DEFAULT_BW_WINDOW = 100
DEFAULT_DELAY_WINDOW = 10000


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


def _hz(args):
    with cli_node(default_node_name()) as node:
        topic = expand(node, args.topic_name)
        msg_class = _wait_for_type(node, topic, args)
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


def format_size(num_bytes, unit):
    """
    Format a byte count in the unit ``ros2 topic bw`` chose from the bandwidth.

    :param num_bytes: bytes (float).
    :param unit: ``'B'``, ``'KB'`` or ``'MB'`` (1000-based).
    :returns: ``'12 B'``, ``'1.23 KB'`` or ``'1.23 MB'``.
    """
    if unit == 'B':
        return f'{num_bytes:.0f} B'
    if unit == 'KB':
        return f'{num_bytes / 1000:.2f} KB'
    return f'{num_bytes / 1000 / 1000:.2f} MB'


def format_bandwidth(sizes, seconds):
    r"""
    Return the two lines ``ros2 topic bw`` prints for a window of message sizes.

    :param sizes: serialized sizes in bytes of the messages in the window (at least one).
    :param seconds: time from the first message of the window to now (> 0).
    :returns: ``'<bw>/s from N messages\n\tMessage size mean: A min: B max: C'``.
    """
    total = sum(sizes)
    rate = total / seconds
    unit = 'B' if rate < 1000 else 'KB' if rate < 1000000 else 'MB'
    mean = total / len(sizes)
    bw, mean_s, low, high = (format_size(v, unit) for v in (rate, mean, min(sizes), max(sizes)))
    return (f'{bw}/s from {len(sizes)} messages\n'
            f'\tMessage size mean: {mean_s} min: {low} max: {high}')


def format_delay(delays):
    r"""
    Return the two lines ``ros2 topic delay`` prints for a window of delays.

    :param delays: seconds between each message's header stamp and its arrival (>= 1 item).
    :returns: ``'average delay: D\n\tmin: As max: Bs std dev: Cs window: N'``.
    """
    n = len(delays)
    mean = sum(delays) / n
    std_dev = math.sqrt(sum((d - mean) ** 2 for d in delays) / n)
    return (f'average delay: {mean:.3f}\n'
            f'\tmin: {min(delays):.3f}s max: {max(delays):.3f}s std dev: {std_dev:.5f}s '
            f'window: {n}')


def _wait_for_type(node, topic, args):
    """Return the topic's message class: from a warm daemon, else once the node sees it."""
    type_name, _ = daemon_topic_type(topic, args.no_daemon)
    if type_name is not None:
        return message_class(type_name)
    types = topic_types(node, topic)
    while not types:
        spin_once(node, timeout_sec=0.1)
        types = topic_types(node, topic)
    return message_class(types[0])


def _node_args(args):
    return ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None


def _bw(args):
    from rclpy.qos import qos_profile_sensor_data
    with cli_node(default_node_name(), args=_node_args(args)) as node:
        topic = expand(node, args.topic_name)
        msg_class = _wait_for_type(node, topic, args)
        window = []  # (time s, size bytes)

        def now():
            if args.use_sim_time:
                return node.get_clock().now().nanoseconds * 1e-9
            return time.monotonic()

        def callback(data):
            window.append((now(), len(data)))
            del window[:-args.window]

        node.create_subscription(msg_class, topic, callback, qos_profile_sensor_data,
                                 raw=True)
        print(f'Subscribed to [{topic}]')
        last_print = time.monotonic()
        while True:
            spin_once(node, timeout_sec=0.05)
            if time.monotonic() - last_print < 1.0:
                continue
            last_print = time.monotonic()
            if len(window) < 2:
                continue
            seconds = now() - window[0][0]
            if seconds <= 0.0:
                window.clear()
                continue
            print(format_bandwidth([size for _, size in window], seconds))


def _delay(args):
    from rclpy.qos import qos_profile_sensor_data
    from rclpy.time import Time
    with cli_node(default_node_name(), args=_node_args(args)) as node:
        topic = expand(node, args.topic_name)
        msg_class = _wait_for_type(node, topic, args)
        if 'header' not in msg_class.get_fields_and_field_types():
            raise CliError(f"The type of '{topic}' has no header: no delay to compute")
        delays = []
        fresh = [False]

        def callback(msg):
            now = node.get_clock().now()
            if now.nanoseconds == 0:
                return
            delays.append((now - Time.from_msg(msg.header.stamp)).nanoseconds * 1e-9)
            del delays[:-args.window]
            fresh[0] = True

        node.create_subscription(msg_class, topic, callback, qos_profile_sensor_data)
        last_print = time.monotonic()
        while True:
            spin_once(node, timeout_sec=0.05)
            if time.monotonic() - last_print < 1.0:
                continue
            last_print = time.monotonic()
            if not delays:
                continue
            if not fresh[0]:
                print('no new messages')
                continue
            fresh[0] = False
            print(format_delay(delays))


def _arguments_hz(p):
    """Add the arguments of ``ros2 topic hz``."""
    p.add_argument('topic_name', help="Name of the ROS topic to listen to (e.g. '/chatter')")
    p.add_argument('--window', '-w', type=int, default=10000,
                   help='window size, in # of messages, for calculating rate (default: 10000)')
    add_no_daemon_argument(p)


VERB_HZ = Verb('Print the average publishing rate to screen', _hz, _arguments_hz)
"""``ros2 topic hz``."""


def _arguments_bw(p):
    """Add the arguments of ``ros2 topic bw``."""
    p.add_argument('topic_name', metavar='topic',
                   help='Topic name to monitor for bandwidth utilization')
    p.add_argument('--window', '-w', type=_positive_int, default=DEFAULT_BW_WINDOW,
                   help='maximum window size, in # of messages, for calculating rate '
                        f'(default: {DEFAULT_BW_WINDOW})')
    p.add_argument('-s', '--use-sim-time', action='store_true',
                   help='Enable ROS simulation time')
    add_no_daemon_argument(p)


VERB_BW = Verb('Display bandwidth used by topic', _bw, _arguments_bw)
"""``ros2 topic bw``."""


def _arguments_delay(p):
    """Add the arguments of ``ros2 topic delay``."""
    p.add_argument('topic_name', metavar='topic',
                   help='Topic name to be calculated the delay')
    p.add_argument('--window', '-w', type=_positive_int, default=DEFAULT_DELAY_WINDOW,
                   help='window size, in # of messages, for calculating rate '
                        f'(default: {DEFAULT_DELAY_WINDOW})')
    p.add_argument('-s', '--use-sim-time', action='store_true',
                   help='Enable ROS simulation time')
    add_no_daemon_argument(p)


VERB_DELAY = Verb('Display delay of topic from timestamp in header', _delay, _arguments_delay)
"""``ros2 topic delay``."""


def _positive_int(text):
    import argparse
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value <= 0:
        raise argparse.ArgumentTypeError('value must be a positive integer')
    return value
