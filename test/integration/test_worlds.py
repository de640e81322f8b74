# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
SDF worlds in the simulator: ``mujoco_sim -p world:=...`` as a user starts it.

The caster robot of test/data/gz_diff_drive (gz-sim's DiffDrive on ``/cmd_vel``) is spawned
with ``create -world warehouse -file`` in the shipped warehouse (``-world arena`` is
refused), facing a shelf, and driven into it at 1 m/s:
its ground truth stops at the shelf's face. A world file that cannot be read stops the
simulator at start with exit code 1 and one line.
"""

import math
import os

from conftest import run_until
from test_gz_systems import gz_peer  # noqa: F401 - the gz-sim systems' DDS peer fixture
from test_gz_systems import XACRO

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')


def _stamp(msg):
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def _ground_truth_y(peer):
    """Return y (m) of the ground truth stamped at the paused simulator's time (50 Hz)."""
    now = peer.now
    assert peer.spin_until(lambda: peer.odom and _stamp(peer.odom[-1]) > now - 0.021, 10)
    return peer.odom[-1].pose.pose.position.y


def test_a_robot_driven_into_a_shelf_of_the_warehouse_stops_at_it(
        procs, exe, ros_env, gz_peer):  # noqa: F811 - the imported fixture
    peer = gz_peer
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'world:=warehouse',
                       '-p', 'real_time_factor:=0.0'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    assert "world 'warehouse': 17 models from " in sim.output
    assert "world 'warehouse' (" in sim.output and 'not simulated: light' in sim.output
    # the loose boxes' poses, as gz-sim's SceneBroadcaster (the viewer draws them there)
    poses = run_until([exe('ros2'), 'topic', 'echo', '--once', '--timeout', '30',
                       '/world/warehouse/dynamic_pose/info'], ros_env,
                      lambda r: 'child_frame_id: box_0/link' in r.stdout)
    assert 'frame_id: world\n' in poses.stdout, poses.stdout + poses.stderr
    assert poses.stdout.count('child_frame_id: box_') == 3, poses.stdout
    # -world names the loaded world, or nothing is spawned (one line, exit 1)
    wrong = procs.start([exe('create'), '-file', XACRO, '-world', 'arena'], ros_env)
    assert wrong.wait(60) == 1, wrong.output
    assert 'world [arena] is not loaded: /mujoco_sim runs world [warehouse]' in wrong.output
    # facing +y at the origin; shelf_0_0 (x -2.5 .. 0.5, y 0.75 .. 1.25) is in front
    create = procs.start([exe('create'), '-world', 'warehouse', '-file', XACRO,
                          '-Y', repr(math.pi / 2), '-z', '0.02'], ros_env)
    assert create.wait(60) == 0, create.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    peer.step(300)
    peer.command_until(1.0, 0.0, lambda twist: twist.linear.x > 0.5)
    peer.step(3000)  # 3 s at 1 m/s would take it 2.5 m past the shelf's face
    y = _ground_truth_y(peer)
    peer.step(1000)
    later = _ground_truth_y(peer)
    print(f'warehouse: the base front at y = {y + 0.2:.4f} m against the shelf face at '
          f'0.75 m; {later - y:+.4f} m in the next second at 1 m/s commanded')
    assert 0.5 < y + 0.2 < 0.78, sim.output[-2000:]
    assert abs(later - y) < 0.01
    assert sim.popen.poll() is None


def test_a_world_that_cannot_be_read_stops_the_simulator_in_one_line(procs, exe, ros_env,
                                                                     tmp_path):
    world = tmp_path / 'broken.sdf'
    world.write_text('<sdf version="1.9">\n<world name="w">\n<model name="x">\n</world>\n</sdf>\n')
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={world}'], ros_env)
    assert sim.wait(60) == 1, sim.output
    errors = [line for line in sim.output.splitlines() if 'malformed XML' in line]
    assert len(errors) == 1 and f'{world}:4: malformed XML (Opening and ending tag mismatch: ' \
        'model line 3 and world' in errors[0], sim.output
    assert 'Traceback' not in sim.output
    missing = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'world:=nowhere'], ros_env)
    assert missing.wait(60) == 1, missing.output
    assert "world 'nowhere': no such file and not a shipped world (arena, empty, warehouse)" \
        in missing.output and 'Traceback' not in missing.output


SHELF_RGB = (230, 140, 38)  # worlds/warehouse.sdf shelves: diffuse 0.9 0.55 0.15


def test_the_sim_stack_shows_the_robot_among_the_shelves(procs, exe, ros_env, tmp_path):
    import shutil
    import time
    from browser import colour_mask
    from browser import ensure_chromium
    from browser import free_port
    from browser import open_page
    assert ensure_chromium(), 'Debian chromium is missing: run scripts/setup'
    port = free_port()
    stack = procs.start([exe('bringup'), 'sim', 'world:=warehouse', f'viewer_port:={port}'],
                        ros_env)
    assert stack.wait_for_output(f'viewer: open http://127.0.0.1:{port}/ in a browser', 180.0), \
        stack.output[-3000:]
    assert stack.wait_for_output("world 'warehouse': 17 models,", 60.0), stack.output[-3000:]
    with open_page(f'http://127.0.0.1:{port}/') as page:
        assert page.wait_for_text('Fixed Frame', 120.0), page.page.inner_text('body')
        page.close_notifications()
        shelf = 0
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and shelf < 500:
            image = page.pixels(str(tmp_path / 'warehouse.png'))
            mask = colour_mask(image, SHELF_RGB, 60)
            mask[:, int(mask.shape[1] * 0.6):] = False  # the panel
            shelf = int(mask.sum())
            if shelf < 500:
                page.page.wait_for_timeout(500)
        assert shelf >= 500, f'{shelf} shelf-coloured pixels'
        if os.environ.get('AMR_UPDATE_SCREENSHOTS'):
            shutil.copy(tmp_path / 'warehouse.png',
                        os.path.join(ROOT, 'docs', 'img', 'warehouse.png'))
    assert stack.interrupt(timeout=30.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]


def test_a_world_with_gazebos_ground_plane_and_sun_holds_the_robot_up(
        procs, exe, ros_env, gz_peer, tmp_path):  # noqa: F811 - the imported fixture
    """Issue 33: ``model://ground_plane`` / Fuel's "Ground Plane" loaded no ground."""
    peer = gz_peer
    world = tmp_path / 'everyday.sdf'
    world.write_text(
        '<?xml version="1.0"?>\n<sdf version="1.9"><world name="everyday">\n'
        '<include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri>'
        '</include>\n'
        '<include><uri>model://ground_plane</uri></include>\n</world></sdf>\n')
    env = dict(ros_env, GZ_SIM_RESOURCE_PATH='')
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={world}',
                       '-p', 'real_time_factor:=0.0'], env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    assert "world 'everyday': 1 models from " in sim.output, sim.output
    assert 'not found' not in sim.output and 'Fuel' not in sim.output, sim.output
    create = procs.start([exe('create'), '-world', 'everyday', '-file', XACRO, '-z', '0.05'],
                         env)
    assert create.wait(60) == 0, create.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    peer.step(2000)  # 2 s: a robot with no ground falls 19.6 m
    now = peer.now
    assert peer.spin_until(lambda: peer.odom and _stamp(peer.odom[-1]) > now - 0.021, 10)
    z = peer.odom[-1].pose.pose.position.z
    print(f'everyday world: base_footprint at z = {z:.4f} m after 2 s')
    assert abs(z) < 0.05, sim.output[-2000:]
