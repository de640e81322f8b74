# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 bag play BAG``: publish the stored messages at their recorded times (as rosbag2).

The stored CDR bytes are published as they are (no deserialisation). Message ``i`` goes out
at ``wall_start + (t_i - t_first) / rate``; ``--start-offset S`` skips the first S seconds of
the bag; ``--topics`` plays only those; ``-l`` loops. Each topic is published with the
reliability and durability its recorded publishers offered (``/tf_static`` reliable and
transient local, so late joiners get it). ``--clock [HZ]`` publishes ``/clock`` at HZ
(default 40, as upstream) with the bag time being played, so nodes with ``use_sim_time``
follow the replay. ``--exclude-topics`` and ``-x/--exclude-regex`` leave topics out, as
rosbag2's (jazzy).

A bag recorded with ``-a`` beside a simulator holds its ``/clock``. rosbag2 plays those like any
topic, and with ``--clock`` adds its own from the bag's receive times: two interleaved clocks,
time jumping back and forth at every message, and without ``--use-sim-time`` at recording the
receive times are wall-clock times far from the messages' sim-time stamps. Here ``--clock``
with such a bag plays the recorded ``/clock`` (the time the messages were stamped with) and
publishes no second one (one info line). Without ``--clock`` the recorded ``/clock`` is played
as rosbag2 does; when another node publishes ``/clock`` too (a running simulator) one warning
says that time will jump and how to leave it out.
"""

import re
import sys
import time

from amr_description.cli.bag import api
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import spin_once
from amr_description.cli.extension import Verb

DEFAULT_CLOCK_HZ = 40.0
CLOCK_TOPIC = '/clock'


def _warn_other_clocks(node, publishers):
    """Warn once when the bag's recorded /clock will meet another node's (time jumps)."""
    if CLOCK_TOPIC not in publishers:
        return
    others = node.count_publishers(CLOCK_TOPIC) - 1
    if others > 0:
        node.get_logger().warning(
            f"The bag's recorded {CLOCK_TOPIC} is played beside {others} other "
            f'publisher(s) of it (a running simulator?): time will jump back and forth; '
            f'leave it out with --exclude-topics {CLOCK_TOPIC}')


def _play(args):
    from amr_description.core.message_yaml.utilities import get_message
    if args.rate <= 0.0:
        raise CliError('Invalid rate: must be positive')
    try:
        excluded = re.compile(args.exclude_regex) if args.exclude_regex else None
    except re.error as exc:
        raise CliError(f'--exclude-regex {args.exclude_regex!r}: {exc}') from None
    with api.open_reader(args.bag_path) as reader:
        connections = [c for c in reader.connections
                       if (not args.topics or c.topic in args.topics) and
                       c.topic not in args.exclude_topics and
                       not (excluded and excluded.search(c.topic))]
        recorded_clock = any(c.topic == CLOCK_TOPIC for c in connections)
        if not connections:
            raise CliError(f"'{args.bag_path}': no topic to play")
        start = reader.start_time + int(args.start_offset * 1e9)
        with cli_node('rosbag2_player') as node:
            if args.clock is not None and recorded_clock:
                node.get_logger().info(
                    f'The bag holds {CLOCK_TOPIC}: played as recorded (the time its messages '
                    'were stamped with) instead of a second clock from --clock')
            publishers = {}
            for connection in connections:
                if connection.topic in publishers:
                    continue
                try:
                    msg_class = get_message(connection.msgtype)
                except ValueError:
                    node.get_logger().warning(
                        f"Ignoring topic '{connection.topic}': unknown message type "
                        f"'{connection.msgtype}'")
                    continue
                offered = connection.ext.offered_qos_profiles
                qos = api.rclpy_qos(offered[0] if offered else None, connection.topic)
                publishers[connection.topic] = node.create_publisher(
                    msg_class, connection.topic, qos)
            clock = None
            if args.clock is not None and not recorded_clock:
                from rosgraph_msgs.msg import Clock
                clock = node.create_publisher(Clock, '/clock', 10)
            # let subscriptions match before the first message, as a user starting a
            # player would expect nothing lost (rosbag2 also waits for discovery)
            give_up = time.monotonic() + args.delay
            while time.monotonic() < give_up and node.context.ok():
                spin_once(node, timeout_sec=0.05)
            if args.clock is None:
                _warn_other_clocks(node, publishers)
            stop = api.StopRequest()
            while not stop:
                _play_once(node, reader, connections, publishers, start, args, clock, stop)
                if not args.loop:
                    break
            if stop:
                return 0
            # give reliable readers time to take the last samples
            give_up = time.monotonic() + 0.5
            while time.monotonic() < give_up:
                spin_once(node, timeout_sec=0.05)
    return 0


def _play_once(node, reader, connections, publishers, start, args, clock, stop):
    from builtin_interfaces.msg import Time
    from rosgraph_msgs.msg import Clock
    wall_start = time.monotonic()
    clock_period = 1.0 / args.clock if args.clock else None
    next_clock = wall_start

    def bag_time_at(wall):
        return start + int((wall - wall_start) * args.rate * 1e9)

    def publish_clock(bag_ns):
        clock.publish(Clock(clock=Time(sec=bag_ns // 10 ** 9, nanosec=bag_ns % 10 ** 9)))

    for connection, timestamp, data in reader.messages(connections=connections, start=start):
        publisher = publishers.get(connection.topic)
        if publisher is None:
            continue
        due = wall_start + (timestamp - start) / 1e9 / args.rate
        while not stop:
            now = time.monotonic()
            if clock is not None and now >= next_clock:
                publish_clock(min(bag_time_at(now), timestamp))
                next_clock += clock_period
            if now >= due:
                break
            wait = due - now
            if clock is not None:
                wait = min(wait, max(0.0, next_clock - now))
            spin_once(node, timeout_sec=min(wait, 0.05))
        if stop or not node.context.ok():
            return
        if clock is not None:
            publish_clock(timestamp)
        publisher.publish(data)
    sys.stdout.flush()


def _arguments_play(p):
    """Add the arguments of ``ros2 bag play``."""
    p.add_argument('bag_path', help='Bag to open')
    p.add_argument('-r', '--rate', type=float, default=1.0,
                   help='rate at which to play back messages. Valid range > 0.0.')
    p.add_argument('-l', '--loop', action='store_true',
                   help='enables loop playback when playing a bagfile: it starts back at the '
                        'beginning on reaching the end and plays indefinitely.')
    p.add_argument('--topics', nargs='+', default=[], metavar='topic',
                   help='topics to replay, separated by space. If none specified, all topics '
                        'will be replayed.')
    p.add_argument('--exclude-topics', nargs='+', default=[], metavar='topic',
                   help='topics not to be replayed, separated by space.')
    p.add_argument('-x', '--exclude-regex', default='', metavar='REGEX',
                   help='regular expressions to exclude topics from replay.')
    p.add_argument('--clock', type=float, nargs='?', const=DEFAULT_CLOCK_HZ, default=None,
                   metavar='HZ',
                   help='Publish to /clock at a specific frequency in Hz, to act as a ROS '
                        f'Time Source. Value must be positive. Defaults to not publishing. '
                        f'Without a value: {DEFAULT_CLOCK_HZ:g} Hz.')
    p.add_argument('--start-offset', type=float, default=0.0, metavar='SECONDS',
                   help='Start the playback player this many seconds into the bag file.')
    p.add_argument('-d', '--delay', type=float, default=1.0, metavar='SECONDS',
                   help='Sleep duration before play (each loop), in seconds (default: 1.0, '
                        'for discovery).')


VERB_PLAY = Verb('Play back ROS data from a bag', _play, _arguments_play)
"""``ros2 bag play``."""
