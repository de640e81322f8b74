# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A ros_gz_bridge YAML configuration: which gz topic reaches ROS under which name and type.

Read as ros_gz_bridge (jazzy) reads it (``ros_gz_bridge/src/bridge_config.cpp``): a list of
maps with ``topic_name`` (one name for both sides) or ``ros_topic_name`` and/or
``gz_topic_name`` (one alone is used for both sides), ``ros_type_name`` and ``gz_type_name``
(both required), ``direction`` (``BIDIRECTIONAL``, the default, ``GZ_TO_ROS`` or
``ROS_TO_GZ``), and ``publisher_queue``, ``subscriber_queue``, ``lazy`` (accepted; the
queue depth stays 10 here). There is no bridge process here: the simulator publishes and
subscribes the ROS side of each entry itself (:func:`ros_side`).
"""

from dataclasses import dataclass

from amr_description.core.ros_names import topic_name_problem
from amr_description.core.yaml_text import safe_load
import yaml

DIRECTIONS = ('BIDIRECTIONAL', 'GZ_TO_ROS', 'ROS_TO_GZ')
KEYS = ('topic_name', 'ros_topic_name', 'gz_topic_name', 'ros_type_name', 'gz_type_name',
        'direction', 'publisher_queue', 'subscriber_queue', 'lazy')


@dataclass
class BridgeEntry:
    """
    One bridged topic.

    :param ros_topic: the ROS topic name (absolute: a relative one is resolved in the root
        namespace, where the bridge node runs).
    :param gz_topic: the gz topic name (absolute, as gz-transport resolves it).
    :param ros_type: e.g. ``'geometry_msgs/msg/Twist'``.
    :param gz_type: e.g. ``'gz.msgs.Twist'``.
    :param direction: one of :data:`DIRECTIONS`.
    """

    ros_topic: str
    gz_topic: str
    ros_type: str
    gz_type: str
    direction: str = 'BIDIRECTIONAL'

    def carries(self, to_ros):
        """Return True when the entry bridges gz -> ROS (``to_ros``) or ROS -> gz."""
        wanted = 'GZ_TO_ROS' if to_ros else 'ROS_TO_GZ'
        return self.direction in ('BIDIRECTIONAL', wanted)


def _absolute(name):
    name = str(name).strip()
    return name if name.startswith('/') else '/' + name


def parse_bridge_config(text, source):
    """
    Return the :class:`BridgeEntry` list of a ros_gz_bridge YAML document.

    :param text: the YAML text.
    :param source: the file name, for error messages.
    :raises ValueError: one line naming ``source``, the entry (1-based) and the field:
        not a list of maps, ``topic_name`` with another name key, no name, a missing type,
        an unknown direction or key.
    """
    try:
        data = safe_load(text)
    except yaml.YAMLError as exc:
        raise ValueError(f'{source}: not YAML: {str(exc).splitlines()[0]}') from None
    if data is None:
        return []
    if not isinstance(data, list):
        raise ValueError(f'{source}: expected a list of bridge entries, found '
                         f'{type(data).__name__}')
    entries = []
    for index, item in enumerate(data, 1):
        where = f'{source} entry {index}'
        if not isinstance(item, dict):
            raise ValueError(f'{where}: expected a map, found {type(item).__name__}')
        unknown = sorted(set(item) - set(KEYS))
        if unknown:
            raise ValueError(f'{where}: unknown key {unknown[0]!r} (expected one of '
                             f'{", ".join(KEYS)})')
        if 'topic_name' in item and ('ros_topic_name' in item or 'gz_topic_name' in item):
            raise ValueError(f'{where}: topic_name cannot be combined with ros_topic_name or '
                             'gz_topic_name')
        ros = item.get('topic_name', item.get('ros_topic_name', item.get('gz_topic_name')))
        gz = item.get('topic_name', item.get('gz_topic_name', item.get('ros_topic_name')))
        if not ros or not gz:
            raise ValueError(f'{where}: topic_name, ros_topic_name or gz_topic_name is '
                             'required')
        problem = topic_name_problem(str(ros))
        if problem:
            raise ValueError(f'{where}: ROS topic {ros!r} is not a valid ROS topic name: '
                             f'{problem}')
        for key in ('ros_type_name', 'gz_type_name'):
            if not item.get(key):
                raise ValueError(f'{where}: {key} is required')
        direction = str(item.get('direction', 'BIDIRECTIONAL')).strip()
        if direction not in DIRECTIONS:
            raise ValueError(f'{where}: direction {direction!r} is not one of '
                             f'{", ".join(DIRECTIONS)}')
        entries.append(BridgeEntry(_absolute(ros), _absolute(gz), str(item['ros_type_name']),
                                   str(item['gz_type_name']), direction))
    return entries


def read_bridge_config(path):
    """
    Return the entries of a ros_gz_bridge YAML file (:func:`parse_bridge_config`).

    :raises ValueError: one line naming the file when it cannot be read or is malformed.
    """
    try:
        with open(path, encoding='utf-8') as stream:
            text = stream.read()
    except OSError as exc:
        raise ValueError(f'bridge_config {path!r}: {exc.strerror}') from None
    except UnicodeDecodeError as exc:
        raise ValueError(f'bridge_config {path!r}: not UTF-8 text (byte '
                         f'{exc.object[exc.start]:#04x} at offset {exc.start})') from None
    return parse_bridge_config(text, path)


def ros_side(entries, gz_topic, to_ros):
    """
    Return the entry that bridges ``gz_topic`` in that direction, or None.

    :param entries: :class:`BridgeEntry` list.
    :param gz_topic: absolute gz topic.
    :param to_ros: True for a gz -> ROS topic (a publisher here), False for ROS -> gz.
    """
    for entry in entries:
        if entry.gz_topic == gz_topic and entry.carries(to_ros):
            return entry
    return None
