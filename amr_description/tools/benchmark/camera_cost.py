# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What cameras cost: our robot's RGB-D camera at its rate against the same robot unheard.

Side by side in one run, in this process (the engine, the camera render thread and the
messages, as the ``mujoco_sim`` node makes them when every camera topic has a subscriber: the
image, depth image, points and camera info of each due instant; no DDS), interleaved
``--repeats`` times, the best kept. Our robot (urdf/amr.urdf.xacro ``camera:=true``, lidar and
IMU off) turns in place in ``warehouse.sdf`` in fast mode:

unheard
    the camera declared, nobody subscribed (nothing is rendered): sim s per wall s, against
    the robot without a camera; their ratio is the cost of a camera nobody listens to (~1).
320x240 at 10 Hz
    every output heard: frames rendered per sim second (10 expected) and sim s per wall s
    (>= 1: the camera keeps real time).
640x480 at 20 Hz
    the same camera resized and at 20 Hz.

Memory, in a fresh process: its resident set before the first render, after it (the OpenGL
context, Mesa's rasterizer threads, the renderer's buffers) and after a second camera of the
same size renders (what one more camera costs).

Usage: ``python -m amr_description.tools.benchmark.camera_cost [--seconds 3] [--repeats 3]``.
"""

import argparse
import os
import sys
import time


def _xacro(mappings):
    from amr_description.core.description.files import read_description
    from amr_description.launch.stacks import urdf_path
    return read_description(urdf_path(), mappings)


def _resized(urdf, width, height, rate):
    urdf = urdf.replace('<width>320</width>', f'<width>{width}</width>')
    urdf = urdf.replace('<height>240</height>', f'<height>{height}</height>')
    return urdf.replace('<update_rate>10</update_rate>', f'<update_rate>{rate}</update_rate>')


def _rss_mb():
    with open('/proc/self/status') as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return 0.0


def run(urdf, seconds, heard):
    """
    Return ``(sim s per wall s, frames per sim s)`` of one robot turning in the warehouse.

    :param heard: request every camera output at its due instants (else none).
    """
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.sim.simulation import Simulation
    sim = Simulation(real_time_factor=0.0, world=load_world('warehouse'),
                     sensor_settings={'publish_ground_truth': False})
    entity = sim.spawn(urdf, name='amr', pose=[0, 0, 0.01, 0, 0, 0, 1])
    for index in range(sim.world.model.nu):
        name = sim.world.model.actuator(index).name
        sim.world.data.ctrl[index] = -5.0 if '_left' in name else 5.0
    cameras = [(s, s.period_steps(sim.physics_step)) for s in entity.sensors if s.deferred]
    renderer = sim.sensor_settings['camera_renderer']
    steps = int(round(seconds / sim.physics_step))
    start = time.perf_counter()
    while sim.step_count < steps:
        sim.run_cycle()
        t = sim.step_count * sim.physics_step
        due = [s for s, period in cameras if heard and sim.step_count % period == 0]
        for sensor in due:
            sensor.request(t, lambda msg: None)
        if due:
            renderer.flush(sim.world, t)
    renderer.idle(60.0)
    wall = time.perf_counter() - start
    frames = renderer.frames
    sim.close()
    return sim.step_count * sim.physics_step / wall, frames / seconds


def memory():
    """Return resident MB: (before a render, after one camera renders, after a second)."""
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.sim.simulation import Simulation
    urdf = _xacro({'camera': 'true', 'lidar': 'false', 'imu': 'false'})
    sim = Simulation(real_time_factor=0.0, world=load_world('warehouse'),
                     sensor_settings={'publish_ground_truth': False})
    first = sim.spawn(urdf, name='a', namespace='a', pose=[0, 0, 0.01, 0, 0, 0, 1])
    second = sim.spawn(urdf, name='b', namespace='b', pose=[2.5, 0, 0.01, 0, 0, 0, 1])
    sim.run_cycle()
    renderer = sim.sensor_settings['camera_renderer']
    before = _rss_mb()
    outputs = {s.name: s for s in first.sensors}
    outputs['camera/image'].request(0.1, lambda msg: None)
    outputs['camera/depth'].request(0.1, lambda msg: None)
    renderer.flush(sim.world, 0.1)
    renderer.idle(60.0)
    one = _rss_mb()
    for name in ('camera/image', 'camera/depth'):
        next(s for s in second.sensors if s.name == name).request(0.2, lambda msg: None)
    renderer.flush(sim.world, 0.2)
    renderer.idle(60.0)
    two = _rss_mb()
    sim.close()
    return before, one, two


def main(argv=None):
    """Print the figures and their ratios; return 0 (the targets are reported, not fatal)."""
    parser = argparse.ArgumentParser(prog='camera_cost', description=__doc__.splitlines()[1])
    parser.add_argument('--seconds', type=float, default=3.0, help='sim s per case (3)')
    parser.add_argument('--repeats', type=int, default=3, help='interleaved repeats (3)')
    parser.add_argument('--memory', action='store_true',
                        help='only print the memory figures (run in a fresh process)')
    opts = parser.parse_args(argv)
    if opts.memory:
        print(' '.join(f'{value:.1f}' for value in memory()))
        return 0
    camera = _xacro({'camera': 'true', 'lidar': 'false', 'imu': 'false'})
    plain = _xacro({'lidar': 'false', 'imu': 'false'})
    large = _resized(camera, 640, 480, 20)
    cases = {'without': (plain, False), 'unheard': (camera, False),
             '320x240@10': (camera, True), '640x480@20': (large, True)}
    best = {}
    for repeat in range(opts.repeats):
        for name, (urdf, heard) in cases.items():
            speed, frames = run(urdf, opts.seconds, heard)
            if speed > best.get(name, (0.0, 0.0))[0]:
                best[name] = (speed, frames)
        print(f'[camera_cost] repeat {repeat + 1}/{opts.repeats} done', flush=True)
    without = best['without'][0]
    unheard = best['unheard'][0]
    print(f'one robot in warehouse.sdf, fast mode: without a camera {without:.1f} x real time, '
          f'with an RGB-D camera nobody listens to {unheard:.1f} x (ratio '
          f'{unheard / without:.2f}, target ~1)')
    for name in ('320x240@10', '640x480@20'):
        speed, frames = best[name]
        print(f'RGB-D camera {name} Hz, image + depth + points + info heard: {frames:.1f} frames '
              f'per sim second, {speed:.2f} x real time (>= 1 keeps real time)')
    import subprocess
    fresh = subprocess.run([sys.executable, '-m', __spec__.name, '--memory'], check=True,
                           capture_output=True, text=True).stdout.split()
    before, one, two = (float(value) for value in fresh)
    print(f'memory: {before:.0f} MB before a render, +{one - before:.0f} MB with the first '
          f'320x240 camera (OpenGL context, buffers), +{two - one:.0f} MB for a second')
    print(f'load: {os.getloadavg()[0]:.2f} (1-minute average), {os.cpu_count()} CPUs')
    return 0


if __name__ == '__main__':
    sys.exit(main())
