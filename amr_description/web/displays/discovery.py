# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Topics found by type in the ROS graph, as RViz's "Add by topic" offers them.

A display's topic-list parameter may hold :data:`AUTO` (``'*'``, the default of the sensor,
odometry and robot model displays): the display then takes every topic of its message type
that has a publisher, in any namespace, as such topics appear (the viewer looks at the graph
every :data:`DISCOVERY_PERIOD` s). Nothing is subscribed before a publisher exists, so the
viewer adds no topic of its own to ``ros2 topic list``. Named topics in the same list are
subscribed from the start, as before.
"""

from amr_description.core.message_yaml.utilities import type_name_of

AUTO = '*'
"""The topic-list entry meaning "every topic of the display's type that has a publisher"."""
DISCOVERY_PERIOD = 2.0
"""Seconds (wall) between two looks at the graph."""


def split_topics(topics):
    """
    Return ``(named topics, auto)`` of a topic-list parameter value.

    :param topics: list of str; '' entries are ignored, :data:`AUTO` sets ``auto``.
    """
    named = [t for t in topics if t and t != AUTO]
    return named, AUTO in topics


class TopicFinder:
    """
    The topics of some message types that gained a publisher since the last look.

    :param types: message classes (a topic of any of them is taken).
    :param suffix: only names ending with it (e.g. ``'robot_description'``); '' for any.
    :param known: topics already taken (never returned).
    :param key: sort key of the topics found in one look (default: the name).
    """

    def __init__(self, types, suffix='', known=(), key=None):
        """Keep the types; nothing is looked at yet."""
        self.types = {type_name_of(t) for t in types}
        self.suffix = suffix
        self.known = set(known)
        self.key = key

    def new_topics(self, graph, count_publishers):
        """
        Return the topics of the types with a publisher not returned before, sorted by ``key``.

        :param graph: ``[(topic, [type names])]`` (``Node.get_topic_names_and_types()``).
        :param count_publishers: callable ``topic -> int`` (``Node.count_publishers``).
        """
        found = []
        for topic, types in graph:
            if topic in self.known or not self.types.intersection(types) or \
                    not topic.endswith(self.suffix):
                continue
            if count_publishers(topic) > 0:
                self.known.add(topic)
                found.append(topic)
        return sorted(found, key=self.key)


CMD_VEL_TYPES = ('geometry_msgs/msg/TwistStamped', 'geometry_msgs/msg/Twist')
"""The types a velocity command topic may have, preferred first."""


def choose_cmd_vel(graph, count_subscribers):
    """
    Return the velocity command topic a teleop pad should drive, or None.

    Among topics named ``.../cmd_vel`` of a type of :data:`CMD_VEL_TYPES` that something
    subscribes to: a controller's (``/diff_drive_controller/cmd_vel``,
    ``/diff_drive_base_controller/cmd_vel``, ``/r1/...``) before a bare ``/cmd_vel``, stamped
    before unstamped, then the first by name.

    :param graph: ``[(topic, [type names])]``.
    :param count_subscribers: callable ``topic -> int``.
    :returns: ``(topic, type name)`` or None.
    """
    found = []
    for topic, types in graph:
        kind = next((t for t in CMD_VEL_TYPES if t in types), None)
        if kind is None or topic.rpartition('/')[2] != 'cmd_vel' or \
                count_subscribers(topic) == 0:
            continue
        bare = topic.strip('/').count('/') == 0
        found.append(((bare, CMD_VEL_TYPES.index(kind), topic), topic, kind))
    return min(found)[1:] if found else None
