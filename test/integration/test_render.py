# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""render writes a PNG of the robot: blue chassis, black wheels; from a file or the topic."""

import os

import numpy as np
import pytest
import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
URDF_PATH = os.path.join(ROOT, 'urdf', 'amr.urdf')


def colour_fractions(path):
    """Return the fractions of (blue, black) pixels of a PNG."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.image

    image = matplotlib.image.imread(str(path))[..., :3]
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    blue = (b > 0.35) & (r < 0.2) & (g < 0.2)
    black = (r < 0.08) & (g < 0.08) & (b < 0.08)
    return blue.mean(), black.mean()


def check_png(path, shape):
    import matplotlib.image
    assert path.stat().st_size > 1000
    assert matplotlib.image.imread(str(path)).shape[:2] == shape
    blue, black = colour_fractions(path)
    assert blue > 0.02, blue
    assert black > 0.01, black


def test_render_from_file(procs, exe, ros_env, tmp_path):
    out = tmp_path / 'amr.png'
    env = ros_env
    proc = procs.start([exe('render'), '--urdf', URDF_PATH, '-o', str(out), '--width', '320',
                        '--height', '240', '--frames'], env)
    assert proc.wait(60.0) == 0, proc.output
    check_png(out, (240, 320))


def test_render_from_robot_description_topic(procs, exe, ros_env, tmp_path):
    with open(URDF_PATH) as f:
        params = {'robot_state_publisher': {'ros__parameters': {'robot_description': f.read()}}}
    params_file = tmp_path / 'rsp.yaml'
    params_file.write_text(yaml.safe_dump(params))
    procs.start([exe('robot_state_publisher'), '--ros-args', '--params-file', str(params_file)],
                ros_env)
    out = tmp_path / 'topic.png'
    proc = procs.start([exe('render'), '-o', str(out), '--width', '200', '--height', '150'],
                       ros_env)
    assert proc.wait(60.0) == 0, proc.output
    check_png(out, (150, 200))


def test_bad_urdf_is_one_line_error(procs, exe, ros_env, tmp_path):
    bad = tmp_path / 'bad.urdf'
    bad.write_text('<robot name="x"><link name="a">')
    proc = procs.start([exe('render'), '--urdf', str(bad), '-o', str(tmp_path / 'x.png')],
                       ros_env)
    assert proc.wait(60.0) == 1
    assert 'Traceback' not in proc.output and proc.output.startswith('render: ')
    assert not (tmp_path / 'x.png').exists()


def test_render_in_a_world_draws_the_world_and_the_robot(procs, exe, ros_env, tmp_path):
    import matplotlib.image
    out = tmp_path / 'warehouse.png'
    env = ros_env
    proc = procs.start([exe('render'), '--urdf', URDF_PATH, '--world', 'warehouse', '-o',
                        str(out)], env)
    assert proc.wait(60.0) == 0, proc.output
    image = matplotlib.image.imread(str(out))[..., :3]
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    shelves = (r > 0.8) & (g > 0.4) & (g < 0.75) & (b < 0.3)  # the shelves' orange
    chassis = (b > 0.6) & (r < 0.2) & (g < 0.2)
    assert shelves.mean() > 0.05 and chassis.sum() > 20, (shelves.mean(), chassis.sum())
    # an unknown world: one line, exit 1, no file
    bad = procs.start([exe('render'), '--urdf', URDF_PATH, '--world', 'nowhere', '-o',
                       str(tmp_path / 'x.png')], env)
    assert bad.wait(60.0) == 1
    assert "render: world 'nowhere': no such file" in bad.output, bad.output
    assert 'Traceback' not in bad.output and not (tmp_path / 'x.png').exists()


@pytest.mark.parametrize('frames', [False, True])
def test_render_pure(frames):
    from amr_description.sim.render import render_urdf
    with open(URDF_PATH) as f:
        image = render_urdf(f.read(), 160, 120, frames)
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    r, g, b = (image[..., i].astype(int) for i in range(3))
    assert ((b > 90) & (r < 50) & (g < 50)).mean() > 0.02  # the blue chassis is in view
    red = ((r > 128) & (g < 50) & (b < 50)).sum()  # x axes of the body frames
    assert (red > 5) if frames else (red == 0), red


def test_a_fleet_scene_draws_every_robot_where_it_stands():
    # the main job's out/scene.png of a fleet run: one chassis per robot, side by side
    import math
    from amr_description.launch.stacks import read_urdf
    from amr_description.sim.render import render_scene
    urdf = read_urdf(os.path.join(ROOT, 'urdf', 'amr.urdf'))
    poses = [(2.0 * i, 0.0, math.pi / 2) for i in range(3)]
    image = render_scene(urdf, poses[0], [(0.0, -0.5)],
                         others=[(pose, [(pose[0], -0.5)]) for pose in poses[1:]])
    r, g, b = (image[..., k].astype(int) for k in range(3))
    columns = np.flatnonzero(((b > 90) & (r < 50) & (g < 50)).any(axis=0))
    groups = np.split(columns, np.flatnonzero(np.diff(columns) > 5) + 1)
    assert len(groups) == 3, [(int(c[0]), int(c[-1])) for c in groups]


def test_the_main_jobs_scene_draws_the_world_it_drove_in():
    # out/scene.png of the main job in arena.sdf: the pillars (diffuse 0.25 0.45 0.8) and the
    # walls stand around the robot; on the plain ground there are none
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.launch.stacks import read_urdf
    from amr_description.sim.render import render_scene
    urdf = read_urdf(os.path.join(ROOT, 'urdf', 'amr.urdf'))

    def pillar_share(world):
        image = render_scene(urdf, (1.0, 0.0, 1.57), [(1.0, -0.5)], 400, 300, world=world)
        r, g, b = (image[..., k].astype(int) for k in range(3))
        # light blue: green well above red (the chassis' pure blue has g == r)
        return ((b > 150) & (b - r > 60) & (g - r > 30)).mean()

    in_arena, alone = pillar_share(load_world('arena')), pillar_share(None)
    assert in_arena > 0.002 and alone == 0.0, (in_arena, alone)
