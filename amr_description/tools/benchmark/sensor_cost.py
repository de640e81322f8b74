# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What sensors cost: the lidar's ray path against raw ``mj_multiRay``, and robots in fast mode.

Side by side in one run, in this process (no ROS, no DDS: the engine and the sensors'
messages, as the ``mujoco_sim`` node measures them when every topic has a subscriber),
interleaved ``--repeats`` times so that a change of the machine's load hits every case alike;
the best of the repeats is kept:

rays
    rays per wall second of our robot's 2-D lidar (360 rays) in ``warehouse.sdf``: through the
    sensor path (:class:`~amr_description.sim.sensors.lidar.LidarScan`: pose update, the cast,
    REP 117, noise, the LaserScan message) against bare ``mujoco.mj_multiRay`` with the same
    rays from the same pose. Target >= 0.8.
fast mode
    sim seconds per wall second of one robot (urdf/amr.urdf.xacro) turning in place in the
    empty world, with its lidar (10 Hz) and IMU (100 Hz) measured at their rates, against the
    same robot without sensors (``lidar:=false imu:=false``). Target >= 0.9.
3-D lidar
    the same robot whose lidar is 16 x 1024 rays at 10 Hz, PointCloud2 included: its sim
    seconds per wall second (>= 1 keeps real time).
fleet
    16 such robots (2-D lidar, IMU) in ``warehouse.sdf``: sim seconds per wall second
    (>= 1 keeps real time).
sim stack (``--stack``)
    the ``sim`` stack in fast mode (``rtf:=0``: mujoco_sim with its controller manager,
    robot_state_publisher, the robot driven in a circle, every topic on DDS; the main
    benchmark's measurement, :func:`~amr_description.tools.benchmark.measure.measure`) with
    the default robot against ``xacro_args:="lidar:=false imu:=false"``: x real time and their
    ratio (target >= 0.9), once with nobody listening to the sensors (an unheard instant only
    draws its noise), once with /scan and /imu subscribed to by the benchmark's observer
    (reliable, depth 10) and once with the sensor-data QoS (best effort), as slam_toolbox and
    Nav2's AMCL and costmaps subscribe to a scan.
    Then, once, the ``fleet`` stack of ``--fleet`` such robots in ``world:=warehouse`` (its
    2 m grid puts them in the aisles) in real time through DDS: the real-time factor held.

Usage: ``python -m amr_description.tools.benchmark.sensor_cost [--seconds 3] [--repeats 3]
[--stack] [--duration 10]``.
"""

import argparse
import os
import sys
import time

RAY_TARGET = 0.8
FAST_TARGET = 0.9
VLP = ('<vertical><samples>16</samples><min_angle>-0.2618</min_angle>'
       '<max_angle>0.2618</max_angle></vertical>')


def _xacro(mappings=None):
    from amr_description.core.description.files import read_description
    from amr_description.launch.stacks import urdf_path
    return read_description(urdf_path(), mappings or {})


def _3d(urdf):
    """Return the description with its lidar turned into 16 x 1024 rays."""
    urdf = urdf.replace('<samples>360</samples>', '<samples>1024</samples>')
    return urdf.replace('</horizontal>', '</horizontal>' + VLP, 1)


def _turn(world):
    for index in range(world.model.nu):
        name = world.model.actuator(index).name
        world.data.ctrl[index] = -5.0 if '_left' in name else 5.0


def ray_rates(scans):
    """Return (sensor-path rays/s, raw mj_multiRay rays/s) in the warehouse."""
    import mujoco
    import numpy as np
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.sim.simulation import Simulation
    sim = Simulation(real_time_factor=0.0, world=load_world('warehouse'),
                     sensor_settings={'publish_ground_truth': False})
    entity = sim.spawn(_xacro(), name='amr', pose=[0, 0, 0.01, 0, 0, 0, 1])
    lidar = next(s for s in entity.sensors if s.name == 'lidar')
    world = sim.world
    for _ in range(50):
        sim.run_cycle()
    cast = lidar.cast
    n = len(cast.directions)
    start = time.perf_counter()
    for k in range(scans):
        lidar.measure(world, 1000.0 + k)  # a new instant each time: no cached scan
    sensor = n * scans / (time.perf_counter() - start)
    model, data = world.model, world.data
    site = model.site(cast.site).id
    body = int(model.site_bodyid[site])
    rotation = data.site_xmat[site].reshape(3, 3)
    vec = (cast.directions @ rotation.T).ravel()
    geomid, dist = np.zeros(n, np.int32), np.zeros(n)
    start = time.perf_counter()
    for _ in range(scans):
        mujoco.mj_multiRay(model, data, data.site_xpos[site], vec, None, 1, body, geomid, dist,
                           None, n, cast.spec.range_max)
    raw = n * scans / (time.perf_counter() - start)
    sim.close()
    return sensor, raw


def sim_rate(urdfs, world_name, seconds):
    """Return sim seconds per wall second of robots measuring every due sensor."""
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.sim.simulation import Simulation
    world = None if world_name == 'empty' else load_world(world_name)
    sim = Simulation(real_time_factor=0.0, world=world,
                     sensor_settings={'publish_ground_truth': False})
    entities = []
    for i, urdf in enumerate(urdfs):
        x, y = (i % 4) * 2.5 - 1.5, (i // 4) * 2.0  # warehouse.sdf's aisles, 4 per aisle
        entities.append(sim.spawn(urdf, name=f'r{i}', namespace=f'r{i}' if len(urdfs) > 1
                                  else '', pose=[x, y, 0.01, 0, 0, 0, 1]))
    _turn(sim.world)
    due = [(s, s.period_steps(sim.physics_step)) for e in entities for s in e.sensors]
    steps = int(round(seconds / sim.physics_step))
    start = time.perf_counter()
    while sim.step_count < steps:
        sim.run_cycle()
        t = sim.step_count * sim.physics_step
        for sensor, period in due:
            if sim.step_count % period == 0:
                sensor.measure(sim.world, t)
    rate = sim.step_count * sim.physics_step / (time.perf_counter() - start)
    sim.close()
    return rate


def stack_rate(extra, opts, listen=False, qos=10):
    """
    Return the sim stack's x real time in fast mode with launch arguments ``extra``.

    :param listen: when True, /scan and /imu have a subscriber (as a SLAM node and a state
        estimator would); otherwise nobody listens to the sensors.
    :param qos: the subscribers' QoS: depth 10 reliable, or a profile (the sensor-data
        profile, best effort, is how slam_toolbox, Nav2's AMCL and costmaps subscribe).
    """
    from amr_description.tools.benchmark.measure import measure
    from sensor_msgs.msg import Imu
    from sensor_msgs.msg import LaserScan
    os.environ['ROS_DOMAIN_ID'] = str(opts.domain_id)
    topics = (('/scan', LaserScan, qos), ('/imu', Imu, qos)) if listen else ()
    result = measure(1, 0.0, opts.duration, opts.domain_id, lambda line: None, extra=extra,
                     listen=topics)
    return result['speed']


def fleet_stack_rtf(opts):
    """Return (rtf held, mujoco_sim cores) of the fleet stack in the warehouse in real time."""
    from amr_description.tools.benchmark.measure import measure
    os.environ['ROS_DOMAIN_ID'] = str(opts.domain_id)
    result = measure(opts.fleet, 1.0, opts.duration, opts.domain_id, lambda line: None,
                     extra=('world:=warehouse',))
    return result['speed'], result['cpu_sim']


def main(argv=None):
    """Print the figures and their ratios; return 0 (the targets are reported, not fatal)."""
    parser = argparse.ArgumentParser(prog='sensor_cost', description=__doc__.splitlines()[1])
    parser.add_argument('--seconds', type=float, default=3.0, help='sim s per case (3)')
    parser.add_argument('--repeats', type=int, default=3, help='interleaved repeats (3)')
    parser.add_argument('--fleet', type=int, default=16, help='robots of the fleet case (16)')
    parser.add_argument('--stack', action='store_true',
                        help='also measure the sim stack in fast mode with and without sensors')
    parser.add_argument('--duration', type=float, default=10.0,
                        help='wall s of each sim stack measurement (10)')
    parser.add_argument('--domain-id', type=int, default=97, help='ROS domain of --stack (97)')
    opts = parser.parse_args(argv)
    from rclpy.qos import qos_profile_sensor_data
    with_sensors = _xacro()
    without = _xacro({'lidar': 'false', 'imu': 'false'})
    best = {}
    for repeat in range(opts.repeats):
        cases = {
            'rays': lambda: ray_rates(500),
            'with': lambda: sim_rate([with_sensors], 'empty', opts.seconds),
            'without': lambda: sim_rate([without], 'empty', opts.seconds),
            '3d': lambda: sim_rate([_3d(with_sensors)], 'empty', opts.seconds),
            'fleet': lambda: sim_rate([with_sensors] * opts.fleet, 'warehouse',
                                      opts.seconds / 3),
        }
        if opts.stack:
            cases['stack with'] = lambda: stack_rate((), opts)
            cases['stack heard'] = lambda: stack_rate((), opts, listen=True)
            cases['stack heard best effort'] = lambda: stack_rate(
                (), opts, listen=True, qos=qos_profile_sensor_data)
            cases['stack without'] = lambda: stack_rate(
                ('xacro_args:=lidar:=false imu:=false',), opts)
        for name, case in cases.items():
            value = case()
            if name == 'rays':
                old = best.get(name, (0.0, 0.0))
                best[name] = (max(old[0], value[0]), max(old[1], value[1]))
            else:
                best[name] = max(best.get(name, 0.0), value)
        print(f'[sensor_cost] repeat {repeat + 1}/{opts.repeats} done', flush=True)
    sensor, raw = best['rays']
    print(f'lidar rays/s: sensor path {sensor / 1e6:.2f} M, raw mj_multiRay {raw / 1e6:.2f} M, '
          f'ratio {sensor / raw:.2f} (target >= {RAY_TARGET})')
    print(f'one robot, fast mode: with lidar + IMU {best["with"]:.1f} x real time, without '
          f'{best["without"]:.1f} x, ratio {best["with"] / best["without"]:.2f} '
          f'(target >= {FAST_TARGET})')
    print(f'one robot with a 16 x 1024 lidar at 10 Hz: {best["3d"]:.1f} x real time '
          '(target >= 1)')
    print(f'{opts.fleet} robots with 2-D lidar and IMU in warehouse.sdf: {best["fleet"]:.2f} x '
          'real time (target >= 1)')
    if opts.stack:
        rtf, cores = fleet_stack_rtf(opts)
        print(f'fleet stack, {opts.fleet} robots with 2-D lidar and IMU in warehouse.sdf, real '
              f'time through DDS: rtf {rtf:.3f} held, mujoco_sim {cores:.2f} cores (target >= 1)')
        without = best['stack without']
        print(f'sim stack, fast mode: without sensors {without:.2f} x real time; with lidar + '
              f'IMU, nobody listening {best["stack with"]:.2f} x (ratio '
              f'{best["stack with"] / without:.2f}), /scan and /imu heard '
              f'{best["stack heard"]:.2f} x (ratio {best["stack heard"] / without:.2f}), heard '
              f'with the sensor-data QoS (best effort) {best["stack heard best effort"]:.2f} x '
              f'(ratio {best["stack heard best effort"] / without:.2f}); target >= '
              f'{FAST_TARGET}')
    print(f'load: {os.getloadavg()[0]:.2f} (1-minute average), {os.cpu_count()} CPUs')
    return 0


if __name__ == '__main__':
    sys.exit(main())
