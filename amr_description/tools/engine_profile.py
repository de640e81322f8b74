# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Engine cost per robot, in one process: the Simulation cycle against raw ``mj_step``.

``python -m amr_description.tools.engine_profile --robots N [--profile]`` spawns N tutorial
robots (namespaces ``r0``... when N > 1) into a :class:`~amr_description.sim.simulation.
Simulation` with real controller managers (joint_state_broadcaster and diff_drive_controller
active, publishing over DDS on ``ROS_DOMAIN_ID``), runs the cycle as fast as possible for
``--seconds`` of wall time, then ``mj_step`` alone on the same world in the same batches, and
prints both rates and their ratio (the engine's share of the raw physics throughput) with the
load average. ``--profile`` adds cProfile's top functions of the engine run, i.e. where the
time goes per cycle. No /clock or ground truth is published (that is mujoco_sim's part).
"""

import argparse
import cProfile
import os
import pstats
import sys
import time


def build(robots, urdf_path):
    """Return ``(simulation, executor)`` with ``robots`` robots and active controllers."""
    from amr_description.control.controller_manager import ControllerManager
    from amr_description.launch.stacks import CONTROLLERS
    from amr_description.ros.sim_time import SimTime
    from amr_description.ros.sim_time import SimTimeExecutor
    from amr_description.sim.simulation import Simulation
    sim_time = SimTime()
    executor = SimTimeExecutor(sim_time)

    def factory(entity, hardware_factory, parameters_file):
        return ControllerManager(entity.description, executor, hardware_factory, parameters_file,
                                 entity.namespace, use_sim_time=True)
    sim = Simulation(real_time_factor=0.0, controller_manager_factory=factory,
                     controller_manager_release=lambda cm: cm.destroy())
    sim.before_update.append(sim_time.set_time)
    with open(urdf_path) as f:
        urdf = f.read()
    for i in range(robots):
        entity = sim.spawn(urdf, f'r{i}', [1.0 * (i % 6), 1.0 * (i // 6), 0.0, 0, 0, 0, 1],
                           namespace=f'r{i}' if robots > 1 else '')
        cm = entity.controller_manager
        for name in CONTROLLERS:
            cm.load_controller(name)
            cm.configure_controller(name)
        cm.switch_controller(list(CONTROLLERS), [], 2, 0.0, wait=False)
    for _ in range(50):  # switches applied, robots settled
        sim.run_cycle()
    return sim, executor


def engine_rate(sim, seconds):
    """
    Return physics steps per wall second of :meth:`Simulation.run_cycle`.

    The CPU seconds of this thread per step (a figure a loaded machine disturbs less than
    the wall rate) are kept in ``engine_rate.cpu_per_step``.
    """
    start, steps, cpu = time.perf_counter(), sim.step_count, time.thread_time()
    while time.perf_counter() - start < seconds:
        sim.run_cycle()
    engine_rate.cpu_per_step = (time.thread_time() - cpu) / max(1, sim.step_count - steps)
    return (sim.step_count - steps) / (time.perf_counter() - start)


def raw_rate(sim, seconds, batch):
    """
    Return steps per wall second of ``mj_step`` alone, ``batch`` steps per call.

    CPU seconds per step in ``raw_rate.cpu_per_step`` (see :func:`engine_rate`).
    """
    import mujoco
    model, data = sim.world.model, sim.world.data
    start, steps, cpu = time.perf_counter(), 0, time.thread_time()
    while time.perf_counter() - start < seconds:
        mujoco.mj_step(model, data, nstep=batch)
        steps += batch
    raw_rate.cpu_per_step = (time.thread_time() - cpu) / max(1, steps)
    return steps / (time.perf_counter() - start)


def main(argv=None):
    """Measure and print (see the module docstring); returns 0."""
    import rclpy
    parser = argparse.ArgumentParser(prog='engine_profile')
    parser.add_argument('--robots', type=int, default=1)
    parser.add_argument('--seconds', type=float, default=5.0)
    parser.add_argument('--profile', action='store_true')
    parser.add_argument('--urdf', default=os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
        'urdf', 'amr.urdf'))
    opts = parser.parse_args(argv)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    rclpy.init()
    sim = None
    try:
        sim, _ = build(opts.robots, opts.urdf)
        engine = engine_rate(sim, opts.seconds)
        batch = min((e.steps_per_update for e in sim.active if e.steps_per_update), default=10)
        raw = raw_rate(sim, opts.seconds, batch)
        print(f'robots {opts.robots}: engine {engine:.0f} steps/s ({engine / 1000:.1f}x real '
              f'time at 1 ms), raw mj_step {raw:.0f} steps/s, engine/raw '
              f'{100 * engine / raw:.1f} %, engine cost per robot-step '
              f'{1e6 / engine / opts.robots:.1f} us (load average {os.getloadavg()[0]:.2f})')
        engine_cpu, raw_cpu = engine_rate.cpu_per_step, raw_rate.cpu_per_step
        print(f'CPU per robot-step: engine {1e6 * engine_cpu / opts.robots:.1f} us, raw '
              f'mj_step {1e6 * raw_cpu / opts.robots:.1f} us, raw/engine '
              f'{100 * raw_cpu / engine_cpu:.1f} %')
        if opts.profile:
            profile = cProfile.Profile()
            profile.enable()
            engine_rate(sim, opts.seconds)
            profile.disable()
            pstats.Stats(profile, stream=sys.stdout).sort_stats('tottime').print_stats(20)
    finally:
        if sim is not None:
            sim.close()
        rclpy.try_shutdown()
    return 0


if __name__ == '__main__':
    sys.exit(main())
