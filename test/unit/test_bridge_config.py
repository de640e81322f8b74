# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""ros_gz_bridge YAML: parsing as ros_gz_bridge does, and the ROS side of system topics."""

from amr_description.core.gazebo.bridge_config import parse_bridge_config
from amr_description.core.gazebo.bridge_config import read_bridge_config
from amr_description.nodes.mujoco_sim.bridge import bridged_inputs
from amr_description.nodes.mujoco_sim.bridge import bridged_outputs
from amr_description.sim.systems.base import Input
from amr_description.sim.systems.base import Output
import pytest

TYPES = 'ros_type_name: nav_msgs/msg/Odometry\n  gz_type_name: gz.msgs.Odometry\n'


def test_names_default_to_the_other_side_and_are_absolute():
    entries = parse_bridge_config(
        f'- topic_name: odom\n  {TYPES}'
        f'- ros_topic_name: wheel_odom\n  {TYPES}  direction: GZ_TO_ROS\n'
        f'- gz_topic_name: /model/x/odometry\n  {TYPES}  lazy: true\n', 'b.yaml')
    assert [(e.ros_topic, e.gz_topic, e.direction) for e in entries] == [
        ('/odom', '/odom', 'BIDIRECTIONAL'), ('/wheel_odom', '/wheel_odom', 'GZ_TO_ROS'),
        ('/model/x/odometry', '/model/x/odometry', 'BIDIRECTIONAL')]
    assert entries[1].carries(to_ros=True) and not entries[1].carries(to_ros=False)
    assert parse_bridge_config('', 'b.yaml') == []


@pytest.mark.parametrize('text, message', [
    ('topic_name: x', 'expected a list of bridge entries'),
    ('- 3', 'entry 1: expected a map'),
    (f'- topic_name: a\n  ros_topic_name: b\n  {TYPES}', 'topic_name cannot be combined'),
    (f'- {TYPES}', 'topic_name, ros_topic_name or gz_topic_name is required'),
    ('- topic_name: a\n  ros_type_name: std_msgs/msg/Bool\n', 'gz_type_name is required'),
    (f'- topic_name: a\n  {TYPES}  direction: UP\n', "direction 'UP' is not one of"),
    (f'- topic_name: a\n  {TYPES}  qos: 1\n', "unknown key 'qos'"),
    ('- [a', 'not YAML'),
])
def test_bad_bridge_config_is_one_line_naming_file_and_entry(text, message):
    with pytest.raises(ValueError, match=message) as error:
        parse_bridge_config(text, 'b.yaml')
    assert str(error.value).startswith('b.yaml') and '\n' not in str(error.value)


def test_missing_file_is_one_line(tmp_path):
    with pytest.raises(ValueError, match=r"^bridge_config '.*nope.yaml': No such file"):
        read_bridge_config(str(tmp_path / 'nope.yaml'))


def test_system_topics_reach_ros_as_bridged():
    from geometry_msgs.msg import Twist
    from geometry_msgs.msg import TwistStamped
    from nav_msgs.msg import Odometry
    odom = Output('o', '/odom', Odometry, 50, None)
    other = Output('t', '/model/x/tf', Odometry, 50, None)
    received = []
    command = Input('/cmd_vel', Twist, received.append)
    assert bridged_outputs([odom], None) == [(odom, '/odom')]
    entries = parse_bridge_config(
        f'- ros_topic_name: wheel_odom\n  gz_topic_name: odom\n  {TYPES}'
        '- ros_topic_name: /r/cmd_vel\n  gz_topic_name: cmd_vel\n'
        '  ros_type_name: geometry_msgs/msg/TwistStamped\n  gz_type_name: gz.msgs.Twist\n',
        'b.yaml')
    assert bridged_outputs([odom, other], entries) == [(odom, '/wheel_odom')]
    [(topic, message_type, callback)] = bridged_inputs([command], entries)
    assert (topic, message_type) == ('/r/cmd_vel', TwistStamped)
    stamped = TwistStamped()
    stamped.twist.linear.x = 0.7
    callback(stamped)
    assert received[0].linear.x == 0.7
    wrong = parse_bridge_config('- topic_name: odom\n  ros_type_name: std_msgs/msg/Bool\n'
                                '  gz_type_name: gz.msgs.Boolean\n', 'b.yaml')
    with pytest.raises(ValueError, match="gz topic '/odom' carries nav_msgs/msg/Odometry, "
                                         'not std_msgs/msg/Bool'):
        bridged_outputs([odom], wrong)
