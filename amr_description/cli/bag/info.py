# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 bag info BAG``: what upstream rosbag2 (jazzy, ``format_bag_meta_data``) prints.

Labels are padded to 19 columns (``Files:``, ``Bag size:``, ``Storage id:``, ``ROS Distro:``,
``Duration:``, ``Start:``, ``End:``, ``Messages:``, ``Topic information:``), then
``Service:`` and ``Service information:``; continuation lines are indented 19 spaces. Sizes
are 1024-based with one decimal (``B`` without); times are local, ``%b %e %Y %H:%M:%S`` plus
the milliseconds written as upstream writes them (``std::to_string(ms % 1000)``, so 5 ms is
``.5``), then ``(seconds.ms)``. A missing or unreadable bag is one line naming it, exit 1.
"""

import os
import sys
import time

from amr_description.cli.bag.api import open_reader
from amr_description.cli.extension import Verb

_INDENT = ' ' * 19


def format_size(num_bytes):
    """
    Format a size as upstream: 1024-based units, one decimal except for bytes.

    :param num_bytes: size in bytes (int).
    :returns: e.g. ``'512 B'``, ``'2.2 MiB'``.
    """
    size, index = float(num_bytes), 0
    units = ('B', 'KiB', 'MiB', 'GiB', 'TiB')
    while size >= 1024 and index < 4:
        size /= 1024
        index += 1
    return f'{size:.0f} B' if index == 0 else f'{size:.1f} {units[index]}'


def _split_ms(nanoseconds):
    ms = nanoseconds // 1_000_000
    return ms // 1000, str(ms % 1000)


def format_duration(nanoseconds):
    """
    Format a duration as upstream's ``time_in_sec``: ``<s>.<ms % 1000 unpadded>``.

    :param nanoseconds: int.
    :returns: str.
    """
    seconds, fraction = _split_ms(nanoseconds)
    return f'{seconds}.{fraction}'


def format_time_point(nanoseconds):
    """
    Format a time point (ns since the epoch) as upstream, in local time.

    :param nanoseconds: int.
    :returns: e.g. ``'Nov 21 2026 18:55:16.123 (1763751316.123)'``.
    """
    seconds, fraction = _split_ms(nanoseconds)
    local = time.localtime(seconds)
    date = time.strftime('%b %e %Y', local)
    return f'{date} {time.strftime("%H:%M:%S", local)}.{fraction} ({seconds}.{fraction})'


def format_info(files, bag_size, storage_id, ros_distro, start_ns, duration_ns, topics):
    """
    Return the text of ``ros2 bag info``.

    :param files: relative file names.
    :param bag_size: total size in bytes.
    :param storage_id: ``mcap`` or ``sqlite3``.
    :param ros_distro: distro name or None.
    :param start_ns: start time (ns since the epoch).
    :param duration_ns: duration (ns).
    :param topics: ``[(name, type, count, serialization_format)]``.
    :returns: the text, starting with an empty line.
    """
    def listed(lines):
        if not lines:
            return '\n'
        return lines[0] + '\n' + ''.join(_INDENT + line + '\n' for line in lines[1:])
    topic_lines = [f'Topic: {name} | Type: {type_} | Count: {count} | '
                   f'Serialization Format: {fmt}' for name, type_, count, fmt in topics]
    return ('\n'
            f'Files:             {listed(files)}'
            f'Bag size:          {format_size(bag_size)}\n'
            f'Storage id:        {storage_id}\n'
            f'ROS Distro:        {ros_distro or "unknown"}\n'
            f'Duration:          {format_duration(duration_ns)}s\n'
            f'Start:             {format_time_point(start_ns)}\n'
            f'End:               {format_time_point(start_ns + duration_ns)}\n'
            f'Messages:          {sum(t[2] for t in topics)}\n'
            f'Topic information: {listed(topic_lines)}'
            'Service:           0\n'
            'Service information: \n')


def _main(args):
    import yaml
    with open_reader(args.bag_path) as reader:
        topics = [(c.topic, c.msgtype, c.msgcount,
                   getattr(c.ext, 'serialization_format', 'cdr'))
                  for c in reader.connections]
        start, duration = reader.start_time, reader.duration
        distro = reader.ros_distro
        if reader.message_count == 0:
            start, duration = 0, 0
    folder = args.bag_path if os.path.isdir(args.bag_path) else os.path.dirname(args.bag_path)
    files, storage = [os.path.basename(args.bag_path)], 'mcap'
    if os.path.isdir(args.bag_path):
        with open(os.path.join(folder, 'metadata.yaml')) as f:
            meta = yaml.safe_load(f)['rosbag2_bagfile_information']
        files, storage = meta['relative_file_paths'], meta['storage_identifier']
    elif args.bag_path.endswith('.db3'):
        storage = 'sqlite3'
    size = sum(os.path.getsize(os.path.join(folder, f)) for f in files
               if os.path.exists(os.path.join(folder, f)))
    sys.stdout.write(format_info(files, size, storage, distro, start, duration, topics))
    return 0


def _arguments_info(p):
    """Add the arguments of ``ros2 bag info``."""
    p.add_argument('bag_path', help='Bag to open')
    p.add_argument('-s', '--storage', default='', help='Storage implementation of bag (read '
                   'from the bag by default)')


VERB_INFO = Verb('Print information about a bag to the screen', _main, _arguments_info)
"""``ros2 bag info``."""
