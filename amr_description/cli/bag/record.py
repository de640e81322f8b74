# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 bag record``: write a rosbag2 directory (metadata.yaml version 9) with ``rosbags``.

What is recorded: the listed topics, or every topic (``-a``), or those matching ``-e REGEX``,
minus those matching ``-x REGEX`` (``re.search``, as rosbag2's regex search); hidden topics
only with ``--include-hidden-topics``. The graph is polled every ``--polling-interval`` ms, so
topics appearing later are recorded too. Each topic is subscribed raw (the CDR bytes the
publisher sent, never re-serialised) with reliability and durability adapted to what every
publisher offers (as rosbag2's recorder), and stored with the publishers' offered QoS
profiles and their RIHS01 type hash. Messages are stamped with their reception time by the
recorder's clock (ROS time with ``--use-sim-time``).

Storage: MCAP (default) or ``-s sqlite3``. Every second the pending MCAP chunk is written out
and a provisional metadata.yaml is written, so a recorder killed without warning leaves a bag
readable up to that point; Ctrl-C (SIGINT) or SIGTERM closes the bag cleanly. A write error
(full disk, file size limit) stops recording with one line on stderr naming the bag, keeps
what was written and exits 1. ``--max-duration S`` stops after S seconds of recording time.
"""

import datetime
import errno
import os
import re
import sys
import time

from amr_description.cli.bag import api
from amr_description.cli.common import cli_node
from amr_description.cli.common import CliError
from amr_description.cli.common import is_hidden_name
from amr_description.cli.common import spin_once
from amr_description.cli.extension import Verb

FLUSH_PERIOD = 1.0
"""Seconds between writes of the pending data and of a provisional metadata.yaml."""


class Recorder:
    """
    Subscribes to the selected topics and writes what arrives into a rosbags ``Writer``.

    :param node: the recorder's rclpy node.
    :param writer: an open :class:`rosbags.rosbag2.Writer`.
    :param args: the parsed ``record`` arguments.
    """

    def __init__(self, node, writer, args):
        """Prepare the topic filters; nothing is subscribed yet."""
        self.node = node
        self.writer = writer
        self.args = args
        self.include = re.compile(args.regex) if args.regex else None
        self.exclude = re.compile(args.exclude_regex) if args.exclude_regex else None
        self.topics = set()
        for topic in args.topics:
            self.topics.add(topic if topic.startswith('/') else '/' + topic)
        self.subscribed = {}
        self.skipped = set()
        self.count = 0
        self.error = None

    def wanted(self, name):
        """
        Tell whether topic ``name`` is to be recorded.

        :param name: absolute topic name.
        :returns: bool.
        """
        if self.exclude is not None and self.exclude.search(name):
            return False
        if name in self.topics:
            return True
        if is_hidden_name(name) and not self.args.include_hidden_topics:
            return False
        return self.args.all or (self.include is not None and bool(self.include.search(name)))

    def discover(self):
        """Subscribe to every wanted topic that has a publisher and is not recorded yet."""
        for name, types in self.node.get_topic_names_and_types():
            if name in self.subscribed or name in self.skipped or not self.wanted(name):
                continue
            infos = self.node.get_publishers_info_by_topic(name)
            if not infos:
                continue
            if len(types) != 1:
                self._skip(name, f'it has more than one type: {", ".join(types)}')
                continue
            self._subscribe(name, types[0], infos)

    def _skip(self, name, why):
        self.skipped.add(name)
        self.node.get_logger().warning(f"Cannot record topic '{name}': {why}")

    def _subscribe(self, name, msgtype, infos):
        from rclpy.qos import QoSDurabilityPolicy
        from rclpy.qos import QoSProfile
        from rclpy.qos import QoSReliabilityPolicy
        from amr_description.core.message_yaml.utilities import get_message
        try:
            msg_class = get_message(msgtype)
            store = api.typestore_for([msgtype])
            msgdef, _ = store.generate_msgdef(msgtype, ros_version=2)
            digest = _type_hash(infos) or store.hash_rihs01(msgtype)
        except (ValueError, CliError, KeyError) as exc:
            self._skip(name, str(exc) or type(exc).__name__)
            return
        offered = [i.qos_profile for i in infos]
        qos = QoSProfile(depth=1000)
        if all(p.reliability == QoSReliabilityPolicy.RELIABLE for p in offered):
            qos.reliability = QoSReliabilityPolicy.RELIABLE
        else:
            qos.reliability = QoSReliabilityPolicy.BEST_EFFORT
        if all(p.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL for p in offered):
            qos.durability = QoSDurabilityPolicy.TRANSIENT_LOCAL
        connection = self.writer.add_connection(
            name, msgtype, msgdef=msgdef, rihs01=digest,
            offered_qos_profiles=[api.rosbags_qos(p) for p in offered])
        self.subscribed[name] = self.node.create_subscription(
            msg_class, name, lambda data, c=connection: self._write(c, data), qos, raw=True)
        self.node.get_logger().info(f"Subscribed to topic '{name}'")

    def now_ns(self):
        """Return the recording clock: ROS time with ``--use-sim-time``, else system time."""
        if self.args.use_sim_time:
            return self.node.get_clock().now().nanoseconds
        return time.time_ns()

    def _write(self, connection, data):
        stamp = self.now_ns()
        if self.error is not None or stamp <= 0:
            return
        try:
            self.writer.write(connection, stamp, data)
            self.count += 1
        except Exception as exc:  # noqa: B902 - OSError, or the database's own error kinds
            self.error = exc

    def flush(self):
        """Write out the pending chunk (MCAP) and a provisional metadata.yaml."""
        if self.error is not None:
            return
        storage = self.writer.storage
        try:
            if getattr(storage, 'chunk', None) is not None and storage.chunk.msgs:
                storage.close_chunk()
            for attribute in ('bio',):
                stream = getattr(storage, attribute, None)
                if stream is not None:
                    stream.flush()
            db = getattr(storage, 'conn', None) or getattr(storage, 'db', None)
            if db is not None and hasattr(db, 'commit'):
                db.commit()
            write_provisional_metadata(self.writer)
        except Exception as exc:  # noqa: B902 - OSError, or the database's own error kinds
            self.error = exc


def _type_hash(infos):
    """Return the RIHS01 type hash the publishers offer (``RIHS01_<hex>``), or None."""
    for info in infos:
        value = getattr(info, 'topic_type_hash', None)
        text = str(value) if value is not None else ''
        if text.startswith('RIHS01_') and len(text) > 7:
            return text
    return None


def write_provisional_metadata(writer):
    """
    Write a metadata.yaml describing what ``writer`` has written so far.

    It is replaced by the final one when the writer closes; it lets a killed recording be
    read. Format: rosbag2 metadata version 9 (as rosbags writes it on close).

    :param writer: an open :class:`rosbags.rosbag2.Writer`.
    :raises OSError: when the file cannot be written.
    """
    import yaml
    from rosbags.rosbag2.metadata import dump_qos_v9
    count = sum(writer.counts.values())
    start = writer.min_timestamp if count else 0
    duration = max(0, writer.max_timestamp - writer.min_timestamp) if count else 0
    name = writer.storage.path.name
    info = {
        'version': writer.version,
        'storage_identifier': writer.storage_plugin.name.lower(),
        'relative_file_paths': [name],
        'duration': {'nanoseconds': duration},
        'starting_time': {'nanoseconds_since_epoch': start},
        'message_count': count,
        'topics_with_message_count': [{
            'topic_metadata': {
                'name': c.topic, 'type': c.msgtype,
                'serialization_format': c.ext.serialization_format,
                'offered_qos_profiles': dump_qos_v9(c.ext.offered_qos_profiles),
                'type_description_hash': c.digest},
            'message_count': writer.counts[c.id]} for c in writer.connections],
        'compression_format': '', 'compression_mode': '',
        'files': [{'path': name, 'starting_time': {'nanoseconds_since_epoch': start},
                   'duration': {'nanoseconds': duration}, 'message_count': count}],
        'custom_data': None,
        'ros_distro': os.environ.get('ROS_DISTRO') or 'jazzy',
    }
    tmp = writer.metapath.with_suffix('.yaml.tmp')
    tmp.write_text(yaml.safe_dump({'rosbag2_bagfile_information': info},
                                  default_flow_style=False))
    tmp.replace(writer.metapath)


def _set_distro(metapath):
    """Name the ROS distro in the final metadata.yaml (rosbags writes ``rosbags``)."""
    text = metapath.read_text()
    distro = os.environ.get('ROS_DISTRO') or 'jazzy'
    metapath.write_text(text.replace('ros_distro: rosbags', f'ros_distro: {distro}'))


def _record(args):
    from rosbags.rosbag2 import StoragePlugin
    from rosbags.rosbag2 import Writer
    from rosbags.rosbag2 import WriterError
    if not (args.all or args.topics or args.regex):
        raise CliError('Need to specify at least one option out of --all, --regex or topics')
    output = args.output or datetime.datetime.now().strftime('rosbag2_%Y_%m_%d-%H_%M_%S')
    if os.path.exists(output):
        raise CliError(f"Output folder '{output}' already exists.")
    plugin = StoragePlugin.SQLITE3 if args.storage == 'sqlite3' else StoragePlugin.MCAP
    ros_args = ['--ros-args', '-p', 'use_sim_time:=true'] if args.use_sim_time else None
    try:
        writer = Writer(output, version=9, storage_plugin=plugin)
        writer.open()
    except (WriterError, OSError) as exc:
        raise CliError(f"'{output}': cannot create bag: {exc}") from None
    error = None
    stop = api.StopRequest()
    with cli_node('rosbag2_recorder', args=ros_args) as node:
        recorder = Recorder(node, writer, args)
        node.get_logger().info('Listening for topics...')
        started = None
        next_poll = next_flush = time.monotonic()
        try:
            while node.context.ok() and recorder.error is None and not stop:
                now = time.monotonic()
                if started is None and recorder.now_ns() > 0:
                    started = recorder.now_ns()
                    node.get_logger().info('Recording...')
                # with --use-sim-time nothing is subscribed before the first /clock, as
                # rosbag2 (ros2/rosbag2#1378): a message stamped 0 would make the bag span
                # from 1970 to the simulation's time
                if now >= next_poll and started is not None:
                    recorder.discover()
                    next_poll = now + args.polling_interval / 1000.0
                if args.max_duration and started is not None and \
                        recorder.now_ns() - started >= args.max_duration * 1e9:
                    break
                if now >= next_flush:
                    recorder.flush()
                    next_flush = now + FLUSH_PERIOD
                spin_once(node, timeout_sec=0.05)
        except KeyboardInterrupt:
            pass
        except Exception as exc:  # noqa: B902 - rclpy's shutdown raises several kinds
            if node.context.ok():
                raise
            del exc
        error = recorder.error
        count = recorder.count
        for subscription in list(recorder.subscribed.values()):
            node.destroy_subscription(subscription)
    try:
        writer.close()
        _set_distro(writer.metapath)
    except Exception as exc:  # noqa: B902 - OSError, or the database's own error kinds
        error = error or exc
        try:
            write_provisional_metadata(writer)
        except Exception:  # noqa: B902 - the disk is full: keep what is there
            pass
    if error is not None:
        reason = getattr(error, 'errno', None)
        reason = os.strerror(reason) if reason in errno.errorcode else ' '.join(
            str(error).split()) or type(error).__name__
        print(f"ros2 bag record: '{output}': {reason}: recording stopped, the bag keeps the "
              f'{count} message(s) written before', file=sys.stderr)
        return 1
    print(f'[INFO] [{time.time():.9f}] [rosbag2_recorder]: Recording stopped', file=sys.stderr)
    return 0


def _arguments_record(p):
    """Add the arguments of ``ros2 bag record``."""
    p.add_argument('topics', nargs='*', default=[], metavar='topics',
                   help='List of topics to record.')
    p.add_argument('-a', '--all', '--all-topics', action='store_true',
                   help='Record all topics.')
    p.add_argument('-e', '--regex', default='',
                   help='Record only topics containing provided regular expression. '
                        'Overrides --all, applies on top of topics list.')
    p.add_argument('-x', '--exclude-regex', default='',
                   help='Exclude topics containing provided regular expression. Works on top '
                        'of --all, --regex, or topics list.')
    p.add_argument('--include-hidden-topics', action='store_true',
                   help='Record also hidden topics.')
    p.add_argument('-o', '--output',
                   help='Destination of the bagfile to create, defaults to a timestamped '
                        'folder in the current directory.')
    p.add_argument('-s', '--storage', default='mcap', choices=('mcap', 'sqlite3'),
                   help="Storage identifier to be used, defaults to 'mcap'.")
    p.add_argument('--max-duration', type=float, default=0.0, metavar='SECONDS',
                   help='Stop recording after this many seconds of recording time '
                        '(default: 0, record until Ctrl-C).')
    p.add_argument('--use-sim-time', action='store_true',
                   help='Use simulation time for message timestamps by subscribing to the '
                        '/clock topic. Until first /clock message is received, no messages '
                        'will be written to bag.')
    p.add_argument('-p', '--polling-interval', type=int, default=100, metavar='MS',
                   help='Time in ms to wait between querying available topics for recording.')


VERB_RECORD = Verb('Record ROS data to a bag', _record, _arguments_record)
"""``ros2 bag record``."""
