# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Constants and helpers shared by the benchmark's parts (processes, /clock, wheels)."""

import dataclasses
import os
import time


DEFAULT_ROBOTS = (1, 2, 4, 8, 16, 32)
TURN_TWIST = (0.3, 0.5)  # m/s, rad/s: every robot drives a circle of about 0.6 m radius
SPACING = 2.0  # m between robots on the fleet grid
CMD_LEAD = 3600.0  # s of sim time a command stays valid (stamped ahead)
TARGETS = {
    'rtf16': 1.0,  # real-time factor held with 16 robots
    'linear16': 1.3,  # fast-mode cost per robot-second at 16 robots relative to N = 1
    'startup16': 10.0,  # s until all 16 robots' controllers are active
    'raw1': 0.60,  # fast mode / raw mj_step with one robot
    'startup1': 2.0,  # s until both controllers of one robot are active
    'viewer_rtf': 0.99,  # real-time factor held with the viewer and a browser
    'viewer_cpu': 0.20,  # viewer CPU, fraction of one core
}


class BenchmarkError(Exception):
    """A stage of the benchmark failed; ``str()`` is the one-line reason."""

    def __init__(self, stage, message, output=''):
        """
        Record the failure.

        :param stage: what was being done, e.g. ``'start-up, 4 robots, rtf 0'``.
        :param message: one line: what went wrong.
        :param output: captured output of the failing process(es), printed after the line.
        """
        super().__init__(f'{stage}: {message}')
        self.output = output


def repo_root():
    """Return the repository (or install prefix) root above the package."""
    here = os.path.abspath(__file__)
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(here))))


def namespaces(count):
    """Return the robot namespaces of the stack for ``count`` robots ('' for one robot)."""
    return [''] if count == 1 else [f'r{i}' for i in range(1, count + 1)]


def wheel_speeds(twist, config_path):
    """
    Return the (left, right) wheel speeds diff_drive_controller commands for ``twist``.

    :param twist: ``(linear m/s, angular rad/s)``.
    :param config_path: the controllers.yaml (``wheel_separation``, ``wheel_radius`` and their
        multipliers of ``diff_drive_controller``).
    :returns: rad/s of the left and right wheels (unicycle kinematics with the effective
        track ``wheel_separation * wheel_separation_multiplier``, as the controller).
    """
    import yaml

    from amr_description.core.model_check.controllers_yaml import node_parameters
    with open(config_path) as f:
        params = node_parameters(yaml.safe_load(f), 'diff_drive_controller')
    track = params['wheel_separation'] * params.get('wheel_separation_multiplier', 1.0)
    radius = params['wheel_radius']
    left = radius * params.get('left_wheel_radius_multiplier', 1.0)
    right = radius * params.get('right_wheel_radius_multiplier', 1.0)
    v, w = twist
    return (v - w * track / 2.0) / left, (v + w * track / 2.0) / right


def raw_step_rate(urdf_xml, count, wheels, seconds=3.0, physics_step=0.001):
    """
    Measure raw ``mj_step`` throughput of ``count`` robots on the fleet grid, each driven.

    :param urdf_xml: the robot URDF (str).
    :param count: number of robots.
    :param wheels: ``(left, right)`` wheel velocity commands, rad/s (every robot).
    :param seconds: measuring time (wall s).
    :param physics_step: physics step (s).
    :returns: physics steps per wall second (float); x real time is that times
        ``physics_step``.
    """
    import mujoco
    from amr_description.launch.stacks import fleet_grid
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import World

    world = World(physics_step)
    for i, (x, y) in enumerate(fleet_grid(count, SPACING)):
        name = f'r{i + 1}'
        world.spawn(urdf_to_spec(urdf_xml, name=name, pose=(x, y, 0.0, 0, 0, 0)), name)
    model, data = world.model, world.data
    for i in range(model.nu):
        data.ctrl[i] = wheels[0] if 'left' in model.actuator(i).name else wheels[1]
    mujoco.mj_step(model, data, nstep=500)  # settle on the ground, start turning
    steps, batch = 0, 200
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        mujoco.mj_step(model, data, nstep=batch)
        steps += batch
    return steps / (time.perf_counter() - start)


def cpu_seconds(pid):
    """Return user + system CPU seconds of a process (``/proc/PID/stat``), or None."""
    try:
        with open(f'/proc/{pid}/stat') as f:
            fields = f.read().rsplit(')', 1)[1].split()
    except (OSError, IndexError):
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def sample_clock(node, executor, timeout):
    """
    Return ``(wall, sim)`` of one /clock message from a short-lived subscription.

    Receiving every /clock message would load the 2-core machine with the observer's own
    callbacks in fast-forward mode.

    :param node: the observer's rclpy node.
    :param executor: the executor spinning ``node``.
    :param timeout: seconds to wait.
    :returns: monotonic wall s and sim s, or None when no /clock came within ``timeout``.
    """
    from rosgraph_msgs.msg import Clock
    sample = []
    sub = node.create_subscription(
        Clock, '/clock', lambda m: sample.append(
            (time.monotonic(), m.clock.sec + m.clock.nanosec * 1e-9)), 1)
    end = time.monotonic() + timeout
    while not sample and time.monotonic() < end:
        executor.spin_once(timeout_sec=0.005)
    node.destroy_subscription(sub)
    return sample[0] if sample else None


def parameter_overrides(cls, texts):
    """
    Return ``{name: value}`` from ``--set name=value`` texts, each name a field of ``cls``.

    A value takes its field's type: text as given, ``true``/``false`` for a bool, else a
    number converted to the field's type.

    :param cls: a dataclass of parameters with defaults (``AmclParameters``, ``SlamParameters``).
    :param texts: list of ``name=value`` strings.
    :raises ValueError: one line, for text that is not ``name=value`` with a known name, or a
        value that is not a number where one is needed.
    """
    kinds = {f.name: type(f.default) for f in dataclasses.fields(cls)}
    values = {}
    for text in texts:
        name, sep, value = text.partition('=')
        if not sep or name not in kinds:
            raise ValueError(f'--set {text}: expected name=value with a name of '
                             f'{sorted(kinds)}')
        if kinds[name] is str:
            values[name] = value
        elif kinds[name] is bool and value.lower() in ('true', 'false'):
            values[name] = value.lower() == 'true'
        else:
            try:
                values[name] = kinds[name](float(value))
            except (ValueError, OverflowError):
                raise ValueError(f'--set {text}: {value!r} is not a number') from None
    return values
