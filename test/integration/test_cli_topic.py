# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 topic pub/echo`` round trips over DDS, and one-line errors on bad input."""

import re
import subprocess

import pytest


def test_pub_once_echo_once_twist_stamped(ros_env, procs, exe):
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/cmd',
                        'geometry_msgs/msg/TwistStamped'], ros_env)
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '--once', '/cmd', 'geometry_msgs/msg/TwistStamped',
         '{header: {frame_id: base_link}, twist: {linear: {x: 0.5}, angular: {z: -1.5}}}'],
        env=ros_env, capture_output=True, text=True, timeout=15)
    assert pub.returncode == 0, pub.stderr
    assert pub.stdout.startswith('Waiting for at least 1 matching subscription(s)...\n'
                                 'publisher: beginning loop\n'
                                 'publishing #1: geometry_msgs.msg.TwistStamped(')
    assert echo.wait(10.0) == 0, echo.output
    assert ('  frame_id: base_link\ntwist:\n  linear:\n    x: 0.5\n    y: 0.0\n    z: 0.0\n'
            '  angular:\n    x: 0.0\n    y: 0.0\n    z: -1.5\n---\n') in echo.output


def test_echo_of_talker(ros_env, procs, exe):
    procs.start([exe('talker')], ros_env)
    echo = procs.start([exe('ros2'), 'topic', 'echo', '/topic'], ros_env)
    assert echo.wait_for_output('---\n', timeout=12.0), echo.output
    assert re.match(r"data: 'Hello World: \d+'\n---\n", echo.output), echo.output
    assert echo.interrupt() == 0
    assert 'Traceback' not in echo.output


def test_header_auto_is_stamped(ros_env, procs, exe):
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/cmd',
                        'geometry_msgs/msg/TwistStamped', '--field', 'header.stamp.sec'],
                       ros_env)
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '-1', '/cmd', 'geometry_msgs/msg/TwistStamped',
         '{header: auto}'], env=ros_env, capture_output=True, text=True, timeout=15)
    assert pub.returncode == 0, pub.stderr
    assert echo.wait(10.0) == 0, echo.output
    assert int(echo.output.split('\n')[0]) > 1_000_000_000


@pytest.mark.parametrize('msg_type, values, error', [
    ('geometry_msgs/msg/TwistStamped', '{twist: [1', 'Failed to populate field: Invalid YAML'),
    ('geometry_msgs/msg/TwistStamped', '{twist: {linear: {q: 1}}}',
     "Failed to populate field: 'Vector3' object has no attribute 'q'"),
    ('geometry_msgs/msg/TwistStamped', '{twist: {linear: {x: fast}}}',
     "Failed to populate field: The 'twist.linear.x' field must be of type 'float'"),
    ('geometry_msgs/msg/Nope', '{}', 'The passed message type is invalid'),
    ('std_msgs/msg/String', 'hello', 'The passed value needs to be a dictionary in YAML format'),
])
def test_pub_bad_input_is_one_line_error(ros_env, exe, msg_type, values, error):
    result = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '--once', '/x', msg_type, values],
        env=ros_env, capture_output=True, text=True, timeout=15)
    assert result.returncode == 1
    assert result.stderr.startswith(error), result.stderr
    assert result.stderr.count('\n') == 1
    assert 'Traceback' not in result.stderr
