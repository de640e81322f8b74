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
    """Run README's render command in a shell that only sourced scripts/env.sh."""
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


def _bad_meshes(folder):
    """Write an ASCII STL cube, a flat quad (COLLADA), a NaN-vertex OBJ and a line OBJ."""
    import numpy as np
    import trimesh
    box = trimesh.creation.box((0.5, 0.5, 0.5))
    box.export(str(folder / 'ascii.stl'), file_type='stl_ascii')
    trimesh.Trimesh([[0, 0, 0], [2, 0, 0], [2, 0, 1], [0, 0, 1]], [[0, 1, 2], [0, 2, 3]],
                    process=False).export(str(folder / 'flat.dae'))
    vertices = box.vertices.copy()
    vertices[0] = np.nan
    (folder / 'nan.obj').write_text(''.join(f'v {x} {y} {z}\n' for x, y, z in vertices) + ''.join(
        f'f {a + 1} {b + 1} {c + 1}\n' for a, b, c in box.faces))
    (folder / 'line.obj').write_text('v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n')
    return ('ascii.stl', 'flat.dae', 'nan.obj', 'line.obj')


def test_bad_meshes_load_what_can_be_used(procs, exe, ros_env, tmp_path):
    """A world and a robot of bad meshes: one line per changed or left-out mesh, all else loads."""
    files = _bad_meshes(tmp_path)
    models = ''.join(
        f'<model name="m{i}"><static>true</static><pose>{3 * i} 4 0 0 0 0</pose>'
        f'<link name="link"><collision name="c"><geometry><mesh><uri>{tmp_path / name}</uri>'
        f'</mesh></geometry></collision></link></model>' for i, name in enumerate(files))
    world = tmp_path / 'meshes.sdf'
    world.write_text('<?xml version="1.0"?><sdf version="1.9"><world name="meshes">'
                     '<include><uri>model://ground_plane</uri></include>'
                     f'{models}</world></sdf>')
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={world}',
                       '-p', 'headless:=true'], ros_env)
    assert sim.wait_for_output('spawn with', 120.0), sim.output
    lines = sim.output
    assert 'm1::link::c: ' in lines and 'flat (all vertices in one plane): given a thickness of ' \
        '0.01 m' in lines, lines
    assert "m2::link::c: '" in lines and '4 triangle(s) with a non-finite vertex left out' in lines
    assert 'm3::link::c: ' in lines and 'every triangle has zero area: skipped' in lines
    assert "world 'meshes': 5 models" in lines and 'm0::' not in lines  # the ASCII STL: silent
    # a robot with the same meshes on a link: spawned, the meshes it can use kept
    urdf = open(URDF_PATH).read().replace('</robot>', ''.join(
        f'<link name="extra{i}"><visual><geometry><mesh filename="file://{tmp_path / name}" '
        f'scale="0.1 0.1 0.1"/></geometry></visual></link><joint name="extra{i}_joint" '
        f'type="fixed"><parent link="base_link"/><child link="extra{i}"/></joint>'
        for i, name in enumerate(files)) + '</robot>')
    robot = tmp_path / 'robot.urdf'
    robot.write_text(urdf)
    create = procs.start([exe('create'), '-file', str(robot), '-name', 'meshy'], ros_env)
    assert create.wait(120.0) == 0, create.output + sim.output
    assert sim.wait_for_output("link 'extra3' visual 0: mesh", 30.0), sim.output
    assert sim.popen.poll() is None
    _no_traceback(sim.output)
    check = procs.start([exe('check_model'), '-q', str(robot)], ros_env)
    assert check.wait(60.0) == 1
    assert "ERROR   link 'extra3' visual 0: " in check.output and 'zero area' in check.output
    assert "WARNING link 'extra1' visual 0: " in check.output
