# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Bad input on the commands README and docs name, run as a user's shell runs them.

The environment is the one ``scripts/env.sh`` gives (``ros_env`` adds only the test's domain):
no ``MUJOCO_GL``, no test-only variable. Each case asserts the one line a user reads, the exit
code, and what still works (the rest of the world loads, the node keeps running); none may
print a traceback. docs/reliability.md lists the cases.
"""

import os

import pytest

pytest.importorskip('rclpy')

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


def _no_traceback(output):
    assert 'Traceback' not in output and 'RecursionError' not in output, output


def test_render_in_a_world_headless_without_mujoco_gl(procs, exe, ros_env, tmp_path):
    """README's render command works in a shell with only scripts/env.sh sourced."""
    env = dict(ros_env)
    env.pop('MUJOCO_GL', None)
    out = tmp_path / 'world.png'
    proc = procs.start([exe('ros2'), 'run', 'amr_description', 'render', '--urdf', URDF_PATH,
                        '--world', 'warehouse', '-o', str(out)], env)
    assert proc.wait(120.0) == 0, proc.output
    _no_traceback(proc.output)
    assert out.stat().st_size > 10000


def test_stack_stops_when_its_simulator_dies(procs, exe, ros_env):
    """The simulator is the stack's essential process: its one line ends the launch, exit 1."""
    proc = procs.start([exe('ros2'), 'launch', 'amr_description', 'sim',
                        'world:=/nonexistent.sdf', 'viewer:=false'], ros_env)
    assert proc.wait(120.0) == 1, proc.output
    _no_traceback(proc.output)
    last = proc.output.strip().splitlines()[-1]
    assert last.startswith('[mujoco_sim-1] ') and "world '/nonexistent.sdf': no such file" in last
