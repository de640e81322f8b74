# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Unit tests of amr_description.core.message_yaml: exact echo YAML and checked YAML->message."""

import math

from amr_description.core.message_yaml.convert import message_to_ordereddict
from amr_description.core.message_yaml.convert import message_to_yaml
from amr_description.core.message_yaml.set_message import message_from_values
from amr_description.core.message_yaml.set_message import set_message_fields
from amr_description.core.message_yaml.utilities import get_message
from amr_description.core.message_yaml.utilities import get_service
from amr_description.core.message_yaml.utilities import type_name_of
from builtin_interfaces.msg import Duration
from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseWithCovariance
from geometry_msgs.msg import TwistStamped
import pytest
from rmw_dds_common.msg import NodeEntitiesInfo
from shape_msgs.msg import SolidPrimitive
from std_msgs.msg import Bool
from std_msgs.msg import Byte
from std_msgs.msg import ByteMultiArray
from std_msgs.msg import Float32
from std_msgs.msg import Float64
from std_msgs.msg import Float64MultiArray
from std_msgs.msg import String
from std_msgs.msg import UInt8MultiArray
from std_srvs.srv import SetBool


def test_type_lookup_accepts_three_and_two_part_names():
    assert get_message('std_msgs/msg/String') is String
    assert get_message('std_msgs/String') is String
    assert get_service('std_srvs/srv/SetBool') is SetBool
    assert get_service('std_srvs/SetBool') is SetBool
    assert type_name_of(String()) == 'std_msgs/msg/String'


@pytest.mark.parametrize('name', ['String', 'a/b/c/d', 'std_msgs/msg/Nope', 'nope_msgs/msg/X',
                                  'std_msgs/foo/String', 'std_msgs/srv/String'])
def test_type_lookup_rejects_bad_names(name):
    with pytest.raises(ValueError):
        get_message(name)


def test_nested_message_yaml_is_exact():
    msg = TwistStamped()
    msg.header.stamp = Time(sec=1, nanosec=2)
    msg.header.frame_id = 'base_link'
    msg.twist.linear.x = 0.5
    msg.twist.angular.z = -1.0
    assert message_to_yaml(msg) == (
        'header:\n  stamp:\n    sec: 1\n    nanosec: 2\n  frame_id: base_link\n'
        'twist:\n  linear:\n    x: 0.5\n    y: 0.0\n    z: 0.0\n'
        '  angular:\n    x: 0.0\n    y: 0.0\n    z: -1.0\n')


def test_strings_are_quoted_like_yaml_dump_and_no_str_abbreviates():
    assert message_to_yaml(String(data='Hello World: 3')) == "data: 'Hello World: 3'\n"
    assert message_to_yaml(String(data='')) == "data: ''\n"
    assert message_to_yaml(String(data='abc'), no_str=True) == "data: '<string length: <3>>'\n"
    assert message_to_yaml(String(data='abcdef'), truncate_length=2) == 'data: ab...\n'


def test_float_specials_and_bool():
    assert message_to_yaml(Float64(data=math.nan)) == 'data: .nan\n'
    assert message_to_yaml(Float64(data=math.inf)) == 'data: .inf\n'
    assert message_to_yaml(Float64(data=-math.inf)) == 'data: -.inf\n'
    assert message_to_yaml(Bool(data=True)) == 'data: true\n'


def test_fixed_array_numpy_truncation_and_no_arr():
    msg = PoseWithCovariance()
    msg.covariance[0] = 1.5
    text = message_to_yaml(msg, truncate_length=2)
    assert text.endswith("covariance:\n- 1.5\n- 0.0\n- '...'\n")
    assert message_to_ordereddict(msg)['covariance'] == [1.5] + [0.0] * 35
    assert message_to_yaml(msg, no_arr=True).endswith(
        "covariance: '<array type: double[36]>'\n")


def test_bounded_and_unbounded_sequences_no_arr():
    msg = SolidPrimitive(dimensions=[1.0, 2.0])
    assert message_to_yaml(msg, no_arr=True) == (
        'type: 0\n'
        "dimensions: '<sequence type: double[3], length: 2>'\n"
        "polygon:\n  points: '<sequence type: geometry_msgs/msg/Point32, length: 0>'\n")
    assert message_to_yaml(Float64MultiArray(data=[1.0]), no_arr=True) == (
        "layout:\n  dim: '<sequence type: std_msgs/msg/MultiArrayDimension, length: 0>'\n"
        "  data_offset: 0\ndata: '<sequence type: double, length: 1>'\n")


def test_bytes_and_uint8():
    assert message_to_yaml(Byte(data=b'A')) == 'data: A\n'
    assert message_to_yaml(ByteMultiArray(data=[b'a', b'\x00'])).endswith(
        'data:\n- a\n- "\\0"\n')
    assert message_to_yaml(UInt8MultiArray(data=[1, 255])).endswith('data:\n- 1\n- 255\n')


def test_flow_style():
    assert message_to_yaml(String(data='x'), flow_style=True) == '{data: x}\n'


def test_yaml_to_nested_message_round_trip():
    text = ('{header: {stamp: {sec: 3, nanosec: 4}, frame_id: odom}, '
            'twist: {linear: {x: 1}, angular: {z: -0.25}}}')
    msg, setters = message_from_values(TwistStamped, text)
    assert setters == []
    assert msg.header.stamp == Time(sec=3, nanosec=4)
    assert msg.header.frame_id == 'odom'
    assert msg.twist.linear.x == 1.0 and isinstance(msg.twist.linear.x, float)
    assert msg.twist.angular.z == -0.25
    assert message_from_values(TwistStamped, message_to_yaml(msg))[0] == msg


def test_sequences_arrays_bytes_bool_specials_from_yaml():
    assert list(message_from_values(UInt8MultiArray, '{data: [1, 2, 255]}')[0].data) == [
        1, 2, 255]
    assert message_from_values(ByteMultiArray, '{data: [97, 0]}')[0].data == [b'a', b'\x00']
    assert message_from_values(Byte, '{data: 65}')[0].data == b'A'
    assert message_from_values(Bool, '{data: true}')[0].data is True
    assert math.isnan(message_from_values(Float64, '{data: .nan}')[0].data)
    assert message_from_values(Float64, '{data: -.inf}')[0].data == -math.inf
    assert message_from_values(Float64, '{data: 1e-3}')[0].data == 0.001
    assert message_from_values(Float64, '{data: nan}')[0].data != 0.0
    cov = message_from_values(PoseWithCovariance, {'covariance': list(range(36))})[0]
    assert cov.covariance[35] == 35.0
    prim = message_from_values(
        SolidPrimitive, '{dimensions: [1, 2, 3], polygon: {points: [{x: 1}, {y: 2}]}}')[0]
    assert list(prim.dimensions) == [1.0, 2.0, 3.0]
    assert prim.polygon.points[1].y == 2.0


def test_time_and_duration_as_fields_or_seconds():
    assert message_from_values(Time, {'sec': 5, 'nanosec': 6})[0] == Time(sec=5, nanosec=6)
    stamped = message_from_values(TwistStamped, '{header: {stamp: 1.25}}')[0]
    assert stamped.header.stamp == Time(sec=1, nanosec=250000000)
    msg = Duration()
    set_message_fields(msg, {'sec': -1, 'nanosec': 0})
    assert msg.sec == -1


def test_header_auto_and_stamp_now_hooks():
    msg, setters = message_from_values(TwistStamped, '{header: auto}', True, True)
    assert len(setters) == 1
    setters[0](Time(sec=7, nanosec=8))
    assert msg.header.stamp == Time(sec=7, nanosec=8)
    msg, setters = message_from_values(TwistStamped, '{header: {stamp: now}}', True, True)
    setters[0](Time(sec=9))
    assert msg.header.stamp.sec == 9
    with pytest.raises(TypeError):   # not expanded unless asked
        message_from_values(TwistStamped, '{header: auto}')


@pytest.mark.parametrize('cls, text, error, message', [
    (TwistStamped, '{twist: {linear: {q: 1}}}', AttributeError,
     "'Vector3' object has no attribute 'q'"),
    (String, '{text: a}', AttributeError, "'String' object has no attribute 'text'"),
    (TwistStamped, '{twist: {linear: {x: abc}}}', TypeError,
     "The 'twist.linear.x' field must be of type 'float', got str 'abc'"),
    (TwistStamped, '{header: {stamp: {sec: 1.5}}}', TypeError,
     "The 'header.stamp.sec' field must be of type 'int', got float 1.5"),
    (Time, '{nanosec: -1}', ValueError,
     "The 'nanosec' field must be an integer in [0, 4294967295], got -1"),
    (Bool, '{data: 1}', TypeError, "The 'data' field must be of type 'bool', got int 1"),
    (TwistStamped, '{twist: 3}', TypeError,
     "The 'twist' field must be a dictionary of geometry_msgs/msg/Twist fields, got int 3"),
    (PoseWithCovariance, '{covariance: [1, 2]}', ValueError,
     "The 'covariance' field must be a sequence of exactly 36 elements, got 2"),
    (SolidPrimitive, '{dimensions: [1, 2, 3, 4]}', ValueError,
     "The 'dimensions' field must be a sequence of at most 3 elements, got 4"),
    (Float64MultiArray, '{data: 1.0}', TypeError,
     "The 'data' field must be a sequence (a YAML list), got float 1.0"),
    (Float32, '{data: 1e39}', ValueError, "The 'data' field must be a float in"),
    (NodeEntitiesInfo, {'node_name': 'x' * 257}, ValueError,
     "The 'node_name' field must be a string of at most 256 characters, got 257"),
    (String, 'a', ValueError, 'The passed value needs to be a dictionary in YAML format'),
    (String, '[1', ValueError,
     "Invalid YAML in the passed value: expected ',' or ']', but got '<stream end>' "
     '(line 1, column 3)'),
])
def test_bad_values_raise_one_line_errors(cls, text, error, message):
    with pytest.raises(error) as info:
        message_from_values(cls, text)
    text = info.value.args[0]
    assert text.startswith(message)
    assert '\n' not in text


def test_empty_values_give_default_message():
    assert message_from_values(String, '')[0] == String()
    assert message_from_values(String, '{}')[0] == String()
