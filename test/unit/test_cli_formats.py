# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Output formatters of the ``ros2`` verbs against texts worked out from ros2cli/rosbag2."""

import time

from amr_description.cli.bag.info import format_duration
from amr_description.cli.bag.info import format_info
from amr_description.cli.bag.info import format_size
from amr_description.cli.doctor import format_report
from amr_description.cli.param.api import parameter_value_from_string
from amr_description.cli.param.change import dump_yaml
from amr_description.cli.topic.rates import format_bandwidth
from amr_description.cli.topic.rates import format_delay
from amr_description.core.message_yaml.convert import message_to_csv
import pytest


def test_message_to_csv_flattens_in_field_order():
    from geometry_msgs.msg import PoseStamped
    msg = PoseStamped()
    msg.header.stamp.sec, msg.header.frame_id = 3, 'map'
    msg.pose.position.x, msg.pose.orientation.w = 1.5, 1.0
    assert message_to_csv(msg) == '3,0,map,1.5,0.0,0.0,0.0,0.0,0.0,1.0'


def test_message_to_csv_truncates_and_abbreviates():
    from sensor_msgs.msg import JointState
    msg = JointState(name=['a', 'b', 'c'], position=[1.0, 2.0, 3.0])
    assert message_to_csv(msg, truncate_length=2) == '0,0,,a,b,...,1.0,2.0,...,,'
    assert message_to_csv(msg, no_arr=True, no_str=True) == (
        '0,0,<string length: <0>>,<sequence type: string, length: 3>,'
        '<sequence type: double, length: 3>,<sequence type: double, length: 0>,'
        '<sequence type: double, length: 0>')


@pytest.mark.parametrize('size, text', [
    (0, '0 B'), (1023, '1023 B'), (1024, '1.0 KiB'), (2_306_867, '2.2 MiB')])
def test_bag_size_is_1024_based(size, text):
    assert format_size(size) == text


def test_bag_duration_keeps_upstreams_unpadded_milliseconds():
    # rosbag2 writes std::to_string(ms % 1000): 5.005 s is printed "5.5"
    assert format_duration(5_005_000_000) == '5.5'
    assert format_duration(12_345_678_901) == '12.345'


def test_bag_info_layout():
    start = int(time.mktime((2026, 11, 21, 18, 55, 16, 0, 0, -1))) * 10 ** 9 + 123_000_000
    text = format_info(['b_0.mcap'], 2048, 'mcap', 'jazzy', start, 2_500_000_000,
                       [('/a', 'std_msgs/msg/String', 3, 'cdr'),
                        ('/b', 'std_msgs/msg/Int32', 4, 'cdr')])
    seconds = start // 10 ** 9
    assert text == (
        '\nFiles:             b_0.mcap\n'
        'Bag size:          2.0 KiB\n'
        'Storage id:        mcap\n'
        'ROS Distro:        jazzy\n'
        'Duration:          2.500s\n'
        f'Start:             Nov 21 2026 18:55:16.123 ({seconds}.123)\n'
        f'End:               Nov 21 2026 18:55:18.623 ({seconds + 2}.623)\n'
        'Messages:          7\n'
        'Topic information: Topic: /a | Type: std_msgs/msg/String | Count: 3 | '
        'Serialization Format: cdr\n'
        '                   Topic: /b | Type: std_msgs/msg/Int32 | Count: 4 | '
        'Serialization Format: cdr\n'
        'Service:           0\n'
        'Service information: \n')


def test_bandwidth_units_follow_the_rate():
    assert format_bandwidth([68] * 10, 1.0) == (
        '680 B/s from 10 messages\n\tMessage size mean: 68 B min: 68 B max: 68 B')
    assert format_bandwidth([1500, 2500], 2.0) == (
        '2.00 KB/s from 2 messages\n\tMessage size mean: 2.00 KB min: 1.50 KB max: 2.50 KB')


def test_delay_statistics():
    assert format_delay([0.1, 0.3]) == (
        'average delay: 0.200\n\tmin: 0.100s max: 0.300s std dev: 0.10000s window: 2')


def test_doctor_report_pads_to_longest_item_plus_four():
    assert format_report('RMW MIDDLEWARE', [('middleware name', 'rmw_fastrtps_cpp')]) == (
        '\n   RMW MIDDLEWARE\nmiddleware name    : rmw_fastrtps_cpp\n')


@pytest.mark.parametrize('text, field, value', [
    ('true', 'bool_value', True), ('3', 'integer_value', 3), ('2.5', 'double_value', 2.5),
    ('hello', 'string_value', 'hello'), ('[1, 2]', 'integer_array_value', [1, 2]),
    ('[a, b]', 'string_array_value', ['a', 'b']), ('[1, a]', 'string_value', '[1, a]'),
    ('{x: [', 'string_value', '{x: ['),
])
def test_set_guesses_the_type_as_ros2param(text, field, value):
    parameter = parameter_value_from_string(text)
    assert list(getattr(parameter, field)) == value if isinstance(value, list) \
        else getattr(parameter, field) == value


def test_dump_nests_dotted_names_and_sorts():
    from rcl_interfaces.msg import ParameterValue
    names = ['linear.x.max_velocity', 'use_sim_time', 'wheel_names']
    values = [ParameterValue(type=3, double_value=1.0), ParameterValue(type=1),
              ParameterValue(type=9, string_array_value=['l', 'r'])]
    assert dump_yaml('/ddc', names, values) == (
        '/ddc:\n  ros__parameters:\n    linear:\n      x:\n        max_velocity: 1.0\n'
        '    use_sim_time: false\n    wheel_names:\n    - l\n    - r\n\n')


def test_actions_are_read_from_their_send_goal_services():
    from amr_description.cli.action import action_names_and_types
    services = [
        ('/fibonacci/_action/send_goal', ['example_interfaces/action/Fibonacci_SendGoal']),
        ('/fibonacci/_action/get_result', ['example_interfaces/action/Fibonacci_GetResult']),
        ('/a/navigate/_action/send_goal', ['nav2_msgs/action/NavigateToPose_SendGoal']),
        ('/talker/list_parameters', ['rcl_interfaces/srv/ListParameters'])]
    assert action_names_and_types(services) == [
        ('/a/navigate', ['nav2_msgs/action/NavigateToPose']),
        ('/fibonacci', ['example_interfaces/action/Fibonacci'])]


def test_rates_take_the_type_from_a_warm_daemon_without_asking_their_node(monkeypatch):
    import argparse

    from amr_description.cli.topic import rates

    class GraphlessNode:

        def get_topic_names_and_types(self):
            raise AssertionError('the verb asked its own node although the daemon knew')

    monkeypatch.setattr(rates, 'daemon_topic_type',
                        lambda topic, no_daemon: (None, 0) if no_daemon else
                        ('std_msgs/msg/String', 1))
    from std_msgs.msg import String
    args = argparse.Namespace(no_daemon=False)
    assert rates._wait_for_type(GraphlessNode(), '/chatter', args) is String
    with pytest.raises(AssertionError):
        rates._wait_for_type(GraphlessNode(), '/chatter', argparse.Namespace(no_daemon=True))


class _LostFirstAnswer:
    """A client, node and executor whose first request's answer never comes."""

    class _Future:

        def __init__(self, result):
            self._result = result

        def done(self):
            return self._result is not None

        def exception(self):
            return None

        def result(self):
            return self._result

    def __init__(self, clock, answer='answer'):
        self.clock = clock
        self.answer = answer
        self.sent = []
        self._cli_executor = self

    def create_client(self, srv_type, service):
        return self

    def destroy_client(self, client):
        pass

    def service_is_ready(self):
        return True

    def call_async(self, request):
        self.sent.append(self.clock[0])
        return self._Future(None if len(self.sent) == 1 else self.answer)

    def spin_once(self, timeout_sec=None):
        self.clock[0] += timeout_sec


def test_a_query_resent_after_its_answer_was_lost(monkeypatch):
    from amr_description.cli.param import api
    clock = [0.0]
    monkeypatch.setattr(api.time, 'monotonic', lambda: clock[0])
    node = _LostFirstAnswer(clock)
    assert api.call(node, None, '/n/get_state', 'request', resend=5.0) == 'answer'
    assert len(node.sent) == 2 and 5.0 < node.sent[1] < 5.2
    # without resend the call waits on (until the service timeout here)
    node = _LostFirstAnswer(clock)
    with pytest.raises(api.CliError, match='Timed out waiting'):
        api.call(node, None, '/n/get_state', 'request', service_timeout=30.0)
    assert len(node.sent) == 1


def test_parameter_queries_are_resent_and_a_set_is_not(monkeypatch):
    from amr_description.cli.param import api
    from rcl_interfaces.msg import Parameter
    from rcl_interfaces.srv import GetParameters
    clock = [0.0]
    monkeypatch.setattr(api.time, 'monotonic', lambda: clock[0])
    node = _LostFirstAnswer(clock, GetParameters.Response())
    assert api.get_parameters(node, '/slam_toolbox', ['paused_processing'],
                              service_timeout=30.0) == []
    assert len(node.sent) == 2 and api.QUERY_RESEND < node.sent[1] < api.QUERY_RESEND + 0.2
    node = _LostFirstAnswer(clock)
    start = clock[0]
    with pytest.raises(api.CliError, match='Timed out waiting'):
        api.set_parameters(node, '/slam_toolbox', [Parameter(name='paused_processing')],
                           service_timeout=30.0)
    assert node.sent == [start]
