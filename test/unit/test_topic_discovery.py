# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The viewer's topics found by type in a graph (web/displays/discovery.py)."""

from amr_description.core.message_yaml.utilities import type_name_of
from amr_description.web.displays.discovery import split_topics
from amr_description.web.displays.discovery import TopicFinder
import pytest
from sensor_msgs.msg import Imu
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

pytestmark = pytest.mark.unit

GRAPH = [('/r1/scan', ['sensor_msgs/msg/LaserScan']),
         ('/r2/scan', ['sensor_msgs/msg/LaserScan']),
         ('/scan', ['sensor_msgs/msg/LaserScan']),  # only a subscriber: not taken
         ('/r1/imu', ['sensor_msgs/msg/Imu']),
         ('/r1/robot_description', ['std_msgs/msg/String']),
         ('/chatter', ['std_msgs/msg/String'])]
PUBLISHERS = {'/r1/scan': 1, '/r2/scan': 2, '/r1/imu': 1, '/r1/robot_description': 1,
              '/chatter': 1}


def test_type_names_are_the_graphs():
    assert type_name_of(LaserScan) == 'sensor_msgs/msg/LaserScan'
    assert type_name_of(String) == 'std_msgs/msg/String'


def test_split_topics_keeps_named_ones_and_reads_the_star():
    assert split_topics(['*']) == ([], True)
    assert split_topics(['/odom', '', '*']) == (['/odom'], True)
    assert split_topics(['/odom']) == (['/odom'], False)
    assert split_topics([]) == ([], False)


def test_a_finder_returns_each_published_topic_of_its_types_once():
    finder = TopicFinder([LaserScan], known=['/r2/scan'])
    count = PUBLISHERS.get
    assert finder.new_topics(GRAPH, lambda t: count(t, 0)) == ['/r1/scan']
    assert finder.new_topics(GRAPH, lambda t: count(t, 0)) == []
    later = GRAPH + [('/r3/scan', ['sensor_msgs/msg/LaserScan'])]
    assert finder.new_topics(later, lambda t: {'/r3/scan': 1}.get(t, 0)) == ['/r3/scan']
    both = TopicFinder([LaserScan, Imu])
    assert both.new_topics(GRAPH, lambda t: count(t, 0)) == ['/r1/imu', '/r1/scan', '/r2/scan']


def test_a_suffix_keeps_only_description_topics():
    finder = TopicFinder([String], suffix='robot_description')
    assert finder.new_topics(GRAPH, lambda t: PUBLISHERS.get(t, 0)) == ['/r1/robot_description']


def test_the_pad_drives_a_controllers_cmd_vel_before_a_bare_one():
    from amr_description.web.displays.discovery import choose_cmd_vel
    stamped, plain = ['geometry_msgs/msg/TwistStamped'], ['geometry_msgs/msg/Twist']
    demos = [('/cmd_vel', plain), ('/diff_drive_base_controller/cmd_vel', stamped),
             ('/diff_drive_base_controller/odom', ['nav_msgs/msg/Odometry'])]
    assert choose_cmd_vel(demos, lambda t: 1) == ('/diff_drive_base_controller/cmd_vel',
                                                  stamped[0])
    # gz-sim's DiffDrive alone: a bare /cmd_vel of Twist
    assert choose_cmd_vel(demos, lambda t: int(t == '/cmd_vel')) == ('/cmd_vel', plain[0])
    fleet = [('/r2/diff_drive_controller/cmd_vel', stamped),
             ('/r1/diff_drive_controller/cmd_vel', stamped)]
    assert choose_cmd_vel(fleet, lambda t: 1)[0] == '/r1/diff_drive_controller/cmd_vel'
    # nothing subscribed (the display stack): no pad topic
    assert choose_cmd_vel(demos, lambda t: 0) is None
    assert choose_cmd_vel([('/cmd_vel_mux', plain)], lambda t: 1) is None
