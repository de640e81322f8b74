# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 topic pub/echo`` round trips over DDS, and one-line errors on bad input."""

import re
import subprocess
import time

import pytest


def test_pub_once_echo_once_twist_stamped(ros_env, procs, exe):
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/cmd',
                        'geometry_msgs/msg/TwistStamped'], ros_env)
    # the publisher may see the echo's subscription before the echo has matched the
    # publisher; --keep-alive keeps the writer up until reliable delivery repairs that (the
    # default 0.1 s is upstream's, too short on a loaded machine)
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '--once', '--keep-alive', '5', '/cmd',
         'geometry_msgs/msg/TwistStamped',
         '{header: {frame_id: base_link}, twist: {linear: {x: 0.5}, angular: {z: -1.5}}}'],
        env=ros_env, capture_output=True, text=True, timeout=60)
    assert pub.returncode == 0, pub.stderr
    # upstream prints the waiting line once a second while it waits (none when the echo was
    # already matched)
    assert re.match(r'(Waiting for at least 1 matching subscription\(s\)\.\.\.\n)*'
                    r'publisher: beginning loop\n'
                    r'publishing #1: geometry_msgs\.msg\.TwistStamped\(', pub.stdout), pub.stdout
    assert echo.wait(60.0) == 0, echo.output
    assert ('  frame_id: base_link\ntwist:\n  linear:\n    x: 0.5\n    y: 0.0\n    z: 0.0\n'
            '  angular:\n    x: 0.0\n    y: 0.0\n    z: -1.5\n---\n') in echo.output


def test_echo_of_talker(ros_env, procs, exe):
    procs.start([exe('talker')], ros_env)
    echo = procs.start([exe('ros2'), 'topic', 'echo', '/topic'], ros_env)
    assert echo.wait_for_output('---\n', timeout=60.0), echo.output
    # under load upstream's 'does not appear to be published yet' warning (stderr) may come
    # first
    assert re.search(r"^data: 'Hello World: \d+'\n---\n", echo.output, re.M), echo.output
    assert echo.interrupt() == 0
    assert 'Traceback' not in echo.output


def test_echo_of_a_published_topic_does_not_warn_it_is_unpublished(ros_env, procs, exe):
    # with a warm daemon that knows the topic (as upstream, whose warning comes from the
    # daemon's graph) echo takes the type from it: no false warning (seen beside the sim
    # stack while /tf was being published)
    import xmlrpc.client
    talker = procs.start([exe('talker')], ros_env)
    assert talker.wait_for_output('Publishing', 60.0), talker.output
    assert subprocess.run([exe('ros2'), 'daemon', 'start'], env=ros_env,
                          timeout=60).returncode == 0
    daemon = xmlrpc.client.ServerProxy(
        f'http://127.0.0.1:{11511 + int(ros_env["ROS_DOMAIN_ID"])}/')
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline and not (
            daemon.uptime() > 3.5 and daemon.count_publishers('/topic') > 0):
        time.sleep(0.1)
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/topic'], ros_env)
    assert echo.wait(90.0) == 0, echo.output
    assert 'does not appear to be published yet' not in echo.output, echo.output
    # nobody publishes: the warning comes, once
    absent = procs.start([exe('ros2'), 'topic', 'echo', '/nobody_publishes'], ros_env)
    assert absent.wait_for_output('WARNING: topic [/nobody_publishes] does not appear to be '
                                  'published yet', 60.0), absent.output
    assert absent.interrupt() == 0
    assert absent.output.count('does not appear') == 1, absent.output


def test_header_auto_is_stamped(ros_env, procs, exe):
    # The publisher sees the subscription matched before the subscription has matched the
    # publisher; a message sent in between is lost for a volatile reader. With a reliable,
    # transient-local reader and `--keep-alive`, the publisher stays until the reader has
    # matched and received the message, however loaded the machine.
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/cmd',
                        'geometry_msgs/msg/TwistStamped', '--field', 'header.stamp.sec',
                        '--qos-reliability', 'reliable', '--qos-durability', 'transient_local'],
                       ros_env)
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '-1', '--keep-alive', '5', '/cmd',
         'geometry_msgs/msg/TwistStamped', '{header: auto}'],
        env=ros_env, capture_output=True, text=True, timeout=60)
    assert pub.returncode == 0, pub.stderr
    assert echo.wait(30.0) == 0, echo.output
    assert int(echo.output.split('\n')[0]) > 1_000_000_000


def test_pub_once_keeps_its_node_alive_for_keep_alive(ros_env, exe):
    started = time.monotonic()
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '-1', '-w', '0', '--keep-alive', '2.0', '/x',
         'std_msgs/msg/String', '{data: a}'], env=ros_env, capture_output=True, text=True,
        timeout=60)
    assert pub.returncode == 0, pub.stderr
    assert time.monotonic() - started >= 2.0


def test_pub_use_sim_time_stamps_with_clock(ros_env, procs, exe):
    procs.start([exe('ros2'), 'topic', 'pub', '-r', '20', '/clock', 'rosgraph_msgs/msg/Clock',
                 '{clock: {sec: 4242, nanosec: 5}}'], ros_env)
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/cmd',
                        'geometry_msgs/msg/TwistStamped', '--field', 'header.stamp',
                        '--qos-reliability', 'reliable', '--qos-durability', 'transient_local'],
                       ros_env)
    # --spin-time: how long pub waits for the first /clock (a loaded machine may take seconds
    # to discover the clock's publisher; stamped before it, the header would be 0)
    pub = subprocess.run(
        [exe('ros2'), 'topic', 'pub', '-1', '-s', '--spin-time', '60', '--keep-alive', '5',
         '/cmd', 'geometry_msgs/msg/TwistStamped', '{header: auto}'],
        env=ros_env, capture_output=True, text=True, timeout=60)
    assert pub.returncode == 0, pub.stderr
    assert echo.wait(30.0) == 0, echo.output
    assert echo.output.startswith('sec: 4242\nnanosec: 5\n---\n'), echo.output


def test_echo_csv_and_field_of_a_message_list(ros_env, procs, exe):
    # upstream echo prints a selected non-message value (here a list of messages) with
    # print(value), and a message as one CSV line with --csv
    values = ('{transforms: [{header: {stamp: {sec: 1, nanosec: 2}, frame_id: odom}, '
              'child_frame_id: base_link, transform: {translation: {x: 0.5}, '
              'rotation: {w: 1.0}}}]}')
    pub = procs.start([exe('ros2'), 'topic', 'pub', '-r', '5', '/tf', 'tf2_msgs/msg/TFMessage',
                       values], ros_env)
    field = subprocess.run([exe('ros2'), 'topic', 'echo', '--once', '/tf', '--field',
                            'transforms'], env=ros_env, capture_output=True, text=True,
                           timeout=60)
    assert field.returncode == 0, field.stderr
    assert field.stdout == (
        '[geometry_msgs.msg.TransformStamped(header=std_msgs.msg.Header(stamp='
        "builtin_interfaces.msg.Time(sec=1, nanosec=2), frame_id='odom'), "
        "child_frame_id='base_link', transform=geometry_msgs.msg.Transform(translation="
        'geometry_msgs.msg.Vector3(x=0.5, y=0.0, z=0.0), rotation=geometry_msgs.msg.'
        'Quaternion(x=0.0, y=0.0, z=0.0, w=1.0)))]\n---\n'), field.stdout
    csv = subprocess.run([exe('ros2'), 'topic', 'echo', '--once', '--csv', '/tf'],
                         env=ros_env, capture_output=True, text=True, timeout=60)
    assert csv.stdout == '1,2,odom,base_link,0.5,0.0,0.0,0.0,0.0,0.0,1.0\n', csv.stdout
    pub.interrupt()


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
        env=ros_env, capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert result.stderr.startswith(error), result.stderr
    assert result.stderr.count('\n') == 1
    assert 'Traceback' not in result.stderr
