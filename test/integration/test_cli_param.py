# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 param`` against a live robot_state_publisher, compared with ros2param's (jazzy) formats.

Expected texts come from ros2param's verbs: ``  name`` list lines (``  name (type: double)``
with ``-t``), ``Double value is: 20.0``, ``Set parameter successful``, ``Parameter name:`` /
``  Type:`` / ``  Description:`` / ``  Constraints:`` / ``    Min value:`` describe blocks,
``Node not found`` with exit 1, and the ``/node: ros__parameters:`` dump YAML.
"""

import os
import subprocess

import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


def _ros2(exe, env, *argv, timeout=60):
    return subprocess.run([exe('ros2'), *argv], env=env, capture_output=True, text=True,
                          timeout=timeout)


def _start_rsp(procs, exe, env, *ros_args):
    rsp = procs.start([exe('robot_state_publisher'), '--ros-args', *ros_args], env)
    assert rsp.wait_for_output('got segment', timeout=30.0), rsp.output
    return rsp


def test_param_verbs_on_robot_state_publisher(ros_env, procs, exe, tmp_path):
    with open(URDF_PATH) as f:
        urdf = f.read()
    start_file = tmp_path / 'start.yaml'
    start_file.write_text(yaml.safe_dump(
        {'robot_state_publisher': {'ros__parameters': {'robot_description': urdf}}}))
    rsp = _start_rsp(procs, exe, ros_env, '--params-file', str(start_file))

    result = _ros2(exe, ros_env, 'param', 'list', '/robot_state_publisher')
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert '  publish_frequency' in lines and '  use_sim_time' in lines, result.stdout
    assert lines == sorted(lines)

    # prefixes are parameter namespaces (rclpy matches 'p' and 'p.*'), as upstream
    result = _ros2(exe, ros_env, 'param', 'list', '/robot_state_publisher', '-t',
                   '--param-prefixes', 'publish_frequency', 'frame')
    assert result.stdout == '  publish_frequency (type: double)\n', result.stdout

    from conftest import run_until  # every node: a discovery snapshot, asked until complete
    result = run_until([exe('ros2'), 'param', 'list'], ros_env,
                       lambda r: '/robot_state_publisher:\n' in r.stdout)
    assert '/robot_state_publisher:\n' in result.stdout, result.stdout

    result = _ros2(exe, ros_env, 'param', 'get', '/robot_state_publisher', 'publish_frequency')
    assert (result.returncode, result.stdout) == (0, 'Double value is: 20.0\n'), result.stderr
    result = _ros2(exe, ros_env, 'param', 'get', 'robot_state_publisher', 'ignore_timestamp',
                   '--hide-type')
    assert result.stdout == 'False\n'

    result = _ros2(exe, ros_env, 'param', 'set', '/robot_state_publisher', 'publish_frequency',
                   '35.0')
    assert (result.returncode, result.stdout) == (0, 'Set parameter successful\n'), result.stderr
    result = _ros2(exe, ros_env, 'param', 'set', '/robot_state_publisher',
                   'robot_description', '')
    assert result.stderr == ('Setting parameter failed: robot_description must not be '
                             'empty\n'), result.stderr

    result = _ros2(exe, ros_env, 'param', 'describe', '/robot_state_publisher',
                   'publish_frequency')
    assert result.stdout == ('Parameter name: publish_frequency\n'
                             '  Type: double\n'
                             '  Description: Maximum frequency (Hz) of /tf per joint\n'
                             '  Constraints:\n'
                             '    Min value: 0.0\n'
                             '    Max value: 1000.0\n'), result.stdout

    result = _ros2(exe, ros_env, 'param', 'dump', '/robot_state_publisher')
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith('/robot_state_publisher:\n  ros__parameters:\n')
    dumped = yaml.safe_load(result.stdout)
    params = dumped['/robot_state_publisher']['ros__parameters']
    assert params['publish_frequency'] == 35.0 and params['robot_description'] == urdf
    dump_file = tmp_path / 'rsp.yaml'
    dump_file.write_text(result.stdout)

    result = _ros2(exe, ros_env, 'param', 'get', '/nobody', 'x')
    assert (result.returncode, result.stderr) == (1, 'Node not found\n')
    result = _ros2(exe, ros_env, 'param', 'get', '/robot_state_publisher', 'nope')
    assert (result.returncode, result.stderr) == (1, 'Parameter not set\n')

    # the dump is a parameter file: a fresh node started from it alone gets the same values
    assert rsp.interrupt() == 0, rsp.output
    _start_rsp(procs, exe, ros_env, '--params-file', str(dump_file))
    result = _ros2(exe, ros_env, 'param', 'get', '/robot_state_publisher', 'publish_frequency')
    assert result.stdout == 'Double value is: 35.0\n', result.stderr

    # and `param load` applies it to a running node
    dump_file.write_text('/robot_state_publisher:\n  ros__parameters:\n'
                         '    publish_frequency: 12.5\n    frame_prefix: robot1/\n')
    result = _ros2(exe, ros_env, 'param', 'load', '/robot_state_publisher', str(dump_file))
    assert result.stdout == ('Set parameter publish_frequency successful\n'
                             'Set parameter frame_prefix successful\n'), result.stderr
    result = _ros2(exe, ros_env, 'param', 'get', '/robot_state_publisher', 'frame_prefix')
    assert result.stdout == 'String value is: robot1/\n'

    result = _ros2(exe, ros_env, 'param', 'delete', '/robot_state_publisher', 'frame_prefix')
    assert result.returncode == 0
    assert result.stderr.startswith('Deleting parameter failed'), result.stderr
    assert 'Traceback' not in result.stderr


def test_param_load_bad_file_is_one_line(ros_env, procs, exe, tmp_path):
    procs.start([exe('talker')], ros_env)
    bad = tmp_path / 'bad.yaml'
    bad.write_text('/minimal_publisher: [1, 2\n')
    result = _ros2(exe, ros_env, 'param', 'load', '/minimal_publisher', str(bad))
    assert result.returncode == 1
    assert str(bad) in result.stderr and result.stderr.count('\n') == 1, result.stderr
