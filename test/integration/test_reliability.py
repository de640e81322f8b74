# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Bad robots, bad arguments and stops: one line and exit code 1, or a clean stop; no traceback.

- robot_state_publisher, create and render refuse what the one URDF loader refuses (a NaN
  origin, a duplicate link) with one error line naming the element;
- rcl argument-parsing errors (a ``-p`` value that is not YAML, an empty one) are one line and
  exit code 1 in every node that parses ROS arguments;
- a whole number for a floating-point parameter is accepted (``real_time_factor:=0``), another
  wrong type is one line naming the parameter and the expected type;
- the fast-forward sim stack stops cleanly, twice in a row (``scripts/stress_shutdown`` runs
  it 50 times).
"""

import os
import subprocess
import sys

import pytest

pytest.importorskip('rclpy')

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


def _urdf():
    with open(URDF_PATH) as f:
        return f.read()


def nan_origin():
    text = _urdf()
    old = '<origin xyz="0 0 0.1" rpy="0 0 0"/>'
    assert old in text
    return text.replace(old, '<origin xyz="0 0 nan" rpy="0 0 0"/>', 1)


def duplicate_link():
    text = _urdf()
    start = text.index('<link name="wheel_back_left">')
    end = text.index('</link>', start) + len('</link>')
    return text[:end] + text[start:end] + text[end:]


BAD_ROBOTS = [
    (nan_origin, "joint 'base_joint'", 'is not finite'),
    (duplicate_link, "link 'wheel_back_left'", 'duplicate link name'),
]


def _one_error_line(output, *words):
    """Assert ``output`` holds exactly one error line, holding ``words``, and no traceback."""
    assert 'Traceback' not in output, output
    errors = [line for line in output.splitlines() if 'ERROR' in line or 'error' in line]
    assert len(errors) == 1, output
    for word in words:
        assert word in errors[0], output
    return errors[0]


@pytest.mark.parametrize('make, element, words', BAD_ROBOTS)
def test_robot_state_publisher_refuses(procs, exe, ros_env, make, element, words):
    proc = procs.start([exe('robot_state_publisher'), '--ros-args', '-p',
                        f'robot_description:={make()}'], ros_env)
    assert proc.wait(30.0) == 1, proc.output
    _one_error_line(proc.output, element, words)


@pytest.mark.parametrize('make, element, words', BAD_ROBOTS)
def test_create_refuses(procs, exe, ros_env, tmp_path, make, element, words):
    # no simulator running: the description is refused before the spawn service is looked for
    path = tmp_path / 'bad.urdf'
    path.write_text(make())
    proc = procs.start([exe('create'), '-file', str(path), '-timeout', '5'], ros_env)
    assert proc.wait(30.0) == 1, proc.output
    line = _one_error_line(proc.output, element, words, str(path))
    assert 'Waiting for service' not in proc.output, line


@pytest.mark.parametrize('make, element, words', BAD_ROBOTS)
def test_render_refuses(procs, exe, ros_env, tmp_path, make, element, words):
    path = tmp_path / 'bad.urdf'
    path.write_text(make())
    png = tmp_path / 'out.png'
    proc = procs.start([exe('render'), '--urdf', str(path), '-o', str(png)],
                       ros_env)
    assert proc.wait(60.0) == 1, proc.output
    lines = proc.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f'render: {path}: '), proc.output
    assert element in lines[0] and words in lines[0]
    assert not png.exists()


def test_check_model_names_base_joint(exe, ros_env, tmp_path):
    path = tmp_path / 'bad.urdf'
    path.write_text(nan_origin())
    result = subprocess.run([exe('check_model'), str(path)], env=ros_env, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 1, result.stdout + result.stderr
    assert result.stderr == ''  # no numpy RuntimeWarning
    line = _one_error_line(result.stdout.splitlines()[0], "joint 'base_joint'")
    assert 'wheel' not in line


NODES = [
    ('talker', []),
    ('listener', []),
    ('robot_state_publisher', []),
    ('joint_state_publisher', []),
    ('joint_state_publisher_gui', []),
    ('viewer', []),
    ('mujoco_sim', []),
    ('create', ['-file', URDF_PATH]),
    ('spawner', ['joint_state_broadcaster']),
    ('render', []),
]


@pytest.mark.parametrize('value, rcl_words', [
    ('<not xml: [>', 'Unknown YAML event'),
    ('', "rule: '-p robot_description:='"),
])
@pytest.mark.parametrize('name, extra', NODES, ids=[n for n, _ in NODES])
def test_rcl_argument_error_is_one_line(exe, ros_env, name, extra, value, rcl_words):
    result = subprocess.run(
        [exe(name)] + extra + ['--ros-args', '-p', f'robot_description:={value}'],
        env=ros_env, capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    assert result.returncode == 1, result.stdout + result.stderr
    output = result.stdout + result.stderr
    line = _one_error_line(output, "Couldn't parse parameter override rule", rcl_words)
    assert line.startswith('[ERROR] ') and f'[{name}]' in line, line


def test_whole_number_for_a_float_parameter(procs, exe, ros_env):
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0'], ros_env)
    echo = procs.start([exe('ros2'), 'topic', 'echo', '--once', '/clock'], ros_env)
    assert echo.wait(60.0) == 0, sim.output + echo.output
    assert 'clock:' in echo.output
    assert sim.popen.poll() is None, sim.output
    assert sim.interrupt(15.0) == 0, sim.output
    assert 'Traceback' not in sim.output


@pytest.mark.parametrize('name, parameter, value, expected', [
    ('mujoco_sim', 'real_time_factor', 'fast', "expecting type 'DOUBLE'"),
    ('mujoco_sim', 'headless', '3', "expecting type 'BOOL'"),
    ('robot_state_publisher', 'publish_frequency', 'high', "expecting type 'DOUBLE'"),
    ('talker', 'use_sim_time', '2.5', "expecting type 'BOOL'"),
])
def test_wrong_parameter_type_is_one_line(exe, ros_env, name, parameter, value, expected):
    argv = [exe(name), '--ros-args', '-p', f'{parameter}:={value}']
    if name == 'robot_state_publisher':
        argv += ['-p', f'robot_description:={_urdf()}']
    result = subprocess.run(argv, env=ros_env, capture_output=True, text=True, timeout=60,
                            stdin=subprocess.DEVNULL)
    assert result.returncode == 1, result.stdout + result.stderr
    _one_error_line(result.stdout + result.stderr, f"'{parameter}'", expected)


def test_fast_stack_stops_cleanly(ros_env):
    # the short version of scripts/stress_shutdown (50 rounds, run by hand: docs/reliability.md)
    script = os.path.join(ROOT, 'scripts', 'stress_shutdown')
    result = subprocess.run(
        [sys.executable, script, '-n', '2', '--domain', ros_env['ROS_DOMAIN_ID']],
        env=ros_env, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    assert '2/2 clean stops' in result.stdout
