# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Scaling benchmark of the simulator: N robots, each driven, real time and fast-forward.

For every N in ``--robots`` (default 1, 2, 4, 8, 16, 32), each against a fresh stack brought
up by the orchestrator on one ROS domain (localhost only): the ``sim`` stack for N = 1 (the
robot without a namespace, as the tutorial runs it) and the ``fleet`` stack (``robots:=N``,
namespaces ``r1`` ... ``rN`` on a 2 m grid) for N > 1:

start-up
    wall time from starting the stack (mujoco_sim, robot_state_publishers, ``create`` and
    spawners, as a launch file does) until every spawner has exited 0, i.e. every robot's
    ``joint_state_broadcaster`` and ``diff_drive_controller`` are active. Measured in both
    runs below; the smaller is reported.
real time (``rtf:=1``)
    every robot driven in a circle (``TURN_TWIST`` on its ``diff_drive_controller/cmd_vel``);
    real-time factor held (sim seconds from /clock per wall second) over ``--duration``, CPU
    of the ``mujoco_sim`` process and of the whole stack (``/proc/PID/stat``) per robot, in %
    of one core.
fast-forward (``rtf:=0``)
    the same drive; x real time over ``--duration``, and the cost per robot-second (wall
    seconds per simulated robot-second, ``1 / (x real time * N)``) relative to N = 1 (1.00 =
    linear scaling).
raw ``mj_step``
    the same N-robot world (:func:`~amr_description.launch.stacks.fleet_grid` positions)
    stepped by ``mujoco.mj_step`` in this process with the wheel speeds diff_drive_controller
    commands for ``TURN_TWIST``; the simulator's fast-forward speed as a fraction of it.

Commands are stamped an hour of sim time ahead of the /clock time seen when driving starts,
so ``cmd_vel_timeout`` never stops a robot whatever the speed of the simulation (a load
generator, not a user's behaviour); robots 2 m apart driving 0.6 m circles never touch.

viewer (part d, unless ``--no-viewer``)
    one robot in real time with robot_state_publisher, the ``viewer`` node and one headless
    browser on its page: real-time factor held and the viewer's CPU
    (:func:`amr_description.sim.benchmark_viewer.viewer_cost`).

A run whose stack does not come up (a process exits with an error, or the controllers are
not active in time) or whose measurement gets no /clock stops the benchmark: it prints the
stage that failed and the captured output of the failing process, exits 1 and writes no
report; nothing is retried. Usage: ``scripts/benchmark_sim [--robots 1,2,4] [--duration S]
[--output docs/benchmark.md]`` (``--output ''`` prints only).
"""

import argparse
import datetime
import math
import os
import sys
import tempfile
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


def _repo_root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


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

    from amr_description.core.model_check import node_parameters
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


def _cpu_seconds(pid):
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


class Observer:
    """A node in its own context: samples /clock and publishes every robot's cmd_vel."""

    def __init__(self, domain_id, robot_namespaces):
        """
        Create the node and one cmd_vel publisher per robot.

        :param domain_id: ROS domain of the stack.
        :param robot_namespaces: list of namespaces ('' for the robot without one).
        """
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from geometry_msgs.msg import TwistStamped

        self.rclpy = rclpy
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('benchmark_observer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.publishers = [self.node.create_publisher(
            TwistStamped, (f'/{ns}' if ns else '') + '/diff_drive_controller/cmd_vel', 10)
            for ns in robot_namespaces]
        self.twist = TwistStamped()
        self.twist.header.frame_id = 'base_link'
        self.twist.twist.linear.x, self.twist.twist.angular.z = TURN_TWIST

    def clock_sample(self, timeout=10.0):
        """Return ``(wall, sim)`` of one /clock message, or None (:func:`sample_clock`)."""
        return sample_clock(self.node, self.executor, timeout)

    def drive(self, sim_now):
        """Publish every robot's command, stamped :data:`CMD_LEAD` after ``sim_now`` (s)."""
        stamp = sim_now + CMD_LEAD
        self.twist.header.stamp.sec = int(stamp)
        self.twist.header.stamp.nanosec = int((stamp - int(stamp)) * 1e9)
        for publisher in self.publishers:
            publisher.publish(self.twist)

    def wait(self, seconds, sim_now):
        """Wait ``seconds`` wall seconds, re-publishing the commands every 0.5 s."""
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.drive(sim_now)
            time.sleep(max(0.0, min(0.5, end - time.monotonic())))

    def close(self):
        """Destroy the node and shut the context down."""
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


class Stack:
    """The ``sim`` (one robot) or ``fleet`` stack under the orchestrator, output captured."""

    def __init__(self, count, rtf, domain_id):
        """
        Start the stack.

        :param count: number of robots.
        :param rtf: real-time factor (0 = as fast as possible).
        :param domain_id: ROS domain.
        """
        from amr_description.launch import stacks
        from amr_description.launch.orchestrator import Orchestrator

        self.count = count
        self.stage = f'{count} robot{"s" if count > 1 else ""}, rtf {rtf:g}'
        name = 'sim' if count == 1 else 'fleet'
        argv = [f'rtf:={rtf:g}', 'headless:=true']
        if count > 1:
            argv += [f'robots:={count}', f'spacing:={SPACING:g}']
        if 'viewer' in {d.name for d in stacks.STACKS[name][1]}:
            argv.append('viewer:=false')
        self.lines = {}
        env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
                   ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
        self._log = tempfile.TemporaryFile(mode='w+')
        self.orchestrator = Orchestrator(stacks.describe(name, argv), stream=self._log,
                                         env=env, line_callback=self._line)
        self.started = time.monotonic()
        self.orchestrator.start()
        self.spawners = count  # one spawner per robot, for both controllers

    def _line(self, label, line):
        self.lines.setdefault(label, []).append(line)

    def output(self, label, tail=40):
        """Return the last ``tail`` output lines of process ``label``."""
        return '\n'.join(f'[{label}] {line}' for line in self.lines.get(label, [])[-tail:])

    def _failed(self):
        """Return the record of a process that exited with an error (or the sim), or None."""
        for record in list(self.orchestrator.processes):
            code = record.returncode
            if code is None:
                continue
            if code != 0 or record.action.name == 'mujoco_sim':
                return record
        return None

    def check(self, what):
        """
        Raise :class:`BenchmarkError` when a process of the stack failed.

        :param what: the stage, e.g. ``'start-up'``.
        """
        record = self._failed()
        if record is not None:
            raise BenchmarkError(f'{what}, {self.stage}',
                                 f'{record.label} exited with code {record.returncode}',
                                 self.output(record.label))

    def wait_active(self, timeout):
        """
        Wait until every spawner exited 0; return the wall seconds since the stack started.

        :raises BenchmarkError: a process failed, or not every controller was active in time.
        """
        deadline = self.started + timeout
        while time.monotonic() < deadline:
            self.check('start-up')
            done = [r for r in self.orchestrator.find('spawner') if r.returncode == 0]
            if len(done) >= self.spawners:
                return time.monotonic() - self.started
            time.sleep(0.02)
        records = list(self.orchestrator.processes)
        states = ', '.join(
            f'{r.label} ' + ('running' if r.returncode is None else f'exit {r.returncode}')
            for r in records)
        raise BenchmarkError(
            f'start-up, {self.stage}',
            f'controllers not active after {timeout:g} s ({self.spawners} spawner(s) '
            f'expected to exit 0; processes: {states})',
            '\n'.join(self.output(r.label, 8) for r in records if r.returncode is None))

    def pids(self, name=None):
        """Return the pids of the running processes (of action ``name`` only, if given)."""
        return [r.pid for r in list(self.orchestrator.processes)
                if r.returncode is None and r.pid and (name is None or r.action.name == name)]

    def close(self):
        """Stop every process of the stack and wait for them."""
        self.orchestrator.shutdown()
        self.orchestrator.wait(timeout=30.0)
        self._log.close()


def measure(count, rtf, duration, domain_id, log, startup_timeout=120.0):
    """
    Bring a stack up, drive every robot, measure, stop it.

    :returns: dict ``startup`` (s), ``speed`` (sim s per wall s), ``cpu_sim`` and
        ``cpu_stack`` (cores, over the window).
    :raises BenchmarkError: on a failed stage (see the module docstring).
    """
    stack = Stack(count, rtf, domain_id)
    observer = None
    try:
        startup = stack.wait_active(timeout=startup_timeout + 3.0 * count)
        log(f'  {stack.stage}: controllers active after {startup:.2f} s')
        observer = Observer(domain_id, namespaces(count))
        first = observer.clock_sample()
        if first is None:
            stack.check('measuring')
            raise BenchmarkError(f'measuring, {stack.stage}', 'no /clock within 10 s',
                                 stack.output('mujoco_sim-1'))
        observer.wait(1.0, first[1])  # every robot under way before the window opens
        pids_sim, pids_all = stack.pids('mujoco_sim'), stack.pids()
        cpu0 = {p: _cpu_seconds(p) for p in pids_all}
        start = observer.clock_sample()
        wall0 = time.monotonic()
        observer.wait(duration, first[1])
        end = observer.clock_sample()
        cpu1 = {p: _cpu_seconds(p) for p in pids_all}
        wall = time.monotonic() - wall0
        stack.check('measuring')
        if start is None or end is None or end[0] <= start[0]:
            raise BenchmarkError(f'measuring, {stack.stage}', 'no /clock during the window',
                                 stack.output('mujoco_sim-1'))

        def cores(pids):
            used = [cpu1[p] - cpu0[p] for p in pids
                    if cpu0.get(p) is not None and cpu1.get(p) is not None]
            return sum(used) / wall

        return {'startup': startup, 'speed': (end[1] - start[1]) / (end[0] - start[0]),
                'cpu_sim': cores(pids_sim), 'cpu_stack': cores(pids_all)}
    finally:
        if observer is not None:
            observer.close()
        stack.close()


def run(robots=DEFAULT_ROBOTS, duration=10.0, domain_id=0, log=print, viewer=True):
    """
    Measure every N of ``robots``; return a list of row dicts (see :func:`report`).

    :raises BenchmarkError: on the first failed stage; nothing is retried.
    """
    root = _repo_root()
    with open(os.path.join(root, 'urdf', 'amr.urdf')) as f:
        urdf = f.read()
    wheels = wheel_speeds(TURN_TWIST, os.path.join(root, 'config', 'controllers.yaml'))
    rows = []
    for count in robots:
        log(f'N = {count}: load average {os.getloadavg()[0]:.2f}')
        row = {'robots': count, 'load': [os.getloadavg()[0]]}
        real = measure(count, 1.0, duration, domain_id, log)
        log(f'  real time: rtf {real["speed"]:.3f}, mujoco_sim {100 * real["cpu_sim"]:.0f} % '
            f'of a core')
        fast = measure(count, 0.0, duration, domain_id, log)
        log(f'  fast-forward: {fast["speed"]:.1f}x real time')
        try:
            raw = raw_step_rate(urdf, count, wheels, seconds=min(5.0, duration)) * 0.001
        except Exception as exc:  # noqa: B902 - reported as the stage that failed
            raise BenchmarkError(f'raw mj_step, {count} robots', repr(exc)) from None
        log(f'  raw mj_step: {raw:.1f}x real time')
        row['load'].append(os.getloadavg()[0])
        row.update(rtf=real['speed'], cpu_sim=real['cpu_sim'], cpu_stack=real['cpu_stack'],
                   fast=fast['speed'], raw=raw,
                   startup=min(real['startup'], fast['startup']),
                   startups=(real['startup'], fast['startup']))
        rows.append(row)
    base = next((r for r in rows if r['robots'] == 1), None)
    for row in rows:
        row['cost'] = 1.0 / (row['fast'] * row['robots']) if row['fast'] > 0 else math.inf
        row['cost_rel'] = row['cost'] / base['cost'] if base else None
    if viewer and rows:
        log('viewer: 1 robot in real time with the viewer and a headless browser ...')
        rows[0]['viewer'] = measure_viewer(duration, domain_id, log)
        log(f'  rtf {rows[0]["viewer"]["rtf"]:.4f}, viewer '
            f'{100 * rows[0]["viewer"]["viewer_cpu"]:.1f} % of a core')
    return rows


def measure_viewer(duration, domain_id, log):
    """
    Run part (d); return ``{'rtf': float, 'viewer_cpu': fraction of a core}``.

    :raises BenchmarkError: when the viewer page could not be opened or no /clock came.
    """
    from amr_description.sim.benchmark_viewer import viewer_cost
    lines = []
    try:
        result = viewer_cost(domain_id, os.path.join(_repo_root(), 'urdf', 'amr.urdf'),
                             duration, log=lines.append)
    except Exception as exc:  # noqa: B902 - reported as the stage that failed
        raise BenchmarkError('viewer, 1 robot, rtf 1', repr(exc), '\n'.join(lines)) from None
    if result['viewer_cpu'] is None or not result['rtf'] > 0:
        raise BenchmarkError('viewer, 1 robot, rtf 1', 'the viewer page was not measured',
                             '\n'.join(lines))
    return result


def format_table(rows):
    """Return the printed/Markdown table of :func:`run` rows (str)."""
    lines = [
        '| N | start-up s | real time: rtf held | mujoco_sim CPU / robot | stack CPU / robot '
        '| fast: x real time | cost / robot-s vs N=1 | raw mj_step x real time '
        '| fast / raw | load avg |',
        '|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        rel = f'{r["cost_rel"]:.2f}' if r['cost_rel'] is not None else '-'
        lines.append(
            f'| {r["robots"]} | {r["startup"]:.2f} | {r["rtf"]:.3f} | '
            f'{100 * r["cpu_sim"] / r["robots"]:.1f} % | '
            f'{100 * r["cpu_stack"] / r["robots"]:.1f} % | {r["fast"]:.1f}x | {rel} | '
            f'{r["raw"]:.1f}x | {100 * r["fast"] / r["raw"]:.0f} % | '
            f'{r["load"][0]:.1f} -> {r["load"][1]:.1f} |')
    return '\n'.join(lines)


def targets(rows):
    """Return ``(description, measured text, passed)`` for every target whose N was run."""
    by_n = {r['robots']: r for r in rows}
    out = []
    if 16 in by_n:
        r = by_n[16]
        out.append(('16 robots, real time: rtf >= 1.0 (paced to 1.0, 1 % tolerance)',
                    f'{r["rtf"]:.3f}',
                    r['rtf'] >= 0.99 * TARGETS['rtf16']))
        if r['cost_rel'] is not None:
            out.append(('16 robots, fast: cost per robot-second <= 1.3x linear',
                        f'{r["cost_rel"]:.2f}x', r['cost_rel'] <= TARGETS['linear16']))
        out.append(('16 robots: all controllers active < 10 s', f'{r["startup"]:.2f} s',
                    r['startup'] < TARGETS['startup16']))
    viewer = next((r['viewer'] for r in rows if r.get('viewer')), None)
    if viewer is not None:
        out.append(('1 robot + viewer + browser: rtf >= 0.99, viewer < 20 % of a core',
                    f'{viewer["rtf"]:.4f}, {100 * viewer["viewer_cpu"]:.1f} %',
                    viewer['rtf'] >= TARGETS['viewer_rtf'] and
                    viewer['viewer_cpu'] < TARGETS['viewer_cpu']))
    if 1 in by_n:
        r = by_n[1]
        out.append(('1 robot, fast: >= 60 % of raw mj_step', f'{100 * r["fast"] / r["raw"]:.0f} %',
                    r['fast'] / r['raw'] >= TARGETS['raw1']))
        out.append(('1 robot: both controllers active < 2 s', f'{r["startup"]:.2f} s',
                    r['startup'] < TARGETS['startup1']))
    return out


def report(rows, duration, argv):
    """Return the Markdown page of the :func:`format_table` rows and the targets (str)."""
    load = ', '.join(f'N={r["robots"]}: {r["load"][0]:.1f} -> {r["load"][1]:.1f}' for r in rows)
    lines = [
        '# Simulation benchmark: scaling with the number of robots', '',
        f'Measured {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC with '
        f'`scripts/benchmark_sim {" ".join(argv)}` (window {duration:g} s per mode) on '
        f'{os.cpu_count()} CPU cores. 1-minute load average before -> after each N: {load}.',
        '',
        'Each N runs two fresh stacks (real time, then as fast as possible) under the '
        'orchestrator: the `sim` stack for N = 1, the `fleet` stack (`robots:=N`, 2 m grid) '
        'for N > 1; every robot drives a 0.6 m circle (0.3 m/s, 0.5 rad/s) on its own '
        '`cmd_vel`. Start-up: stack start until every spawner exited 0 (the smaller of the '
        'two runs). CPU: user + system time from /proc of mujoco_sim and of every process '
        'of the stack over the window, per robot, in % of one core. Cost per robot-second = '
        '1 / (x real time * N), relative to N = 1 (1.00 = linear). Raw mj_step: the same '
        'N-robot world stepped in the benchmark process with the same wheel speeds.', '',
        format_table(rows), '',
        '| target | measured | |', '|---|---|---|',
    ]
    lines += [f'| {d} | {m} | {"PASS" if ok else "FAIL"} |' for d, m, ok in targets(rows)]
    lines += ['', 'A loaded machine (other work running) lowers every figure; re-run '
              '`scripts/benchmark_sim` on a quiet machine for reference values. A stage '
              'that fails stops the benchmark with the captured error and leaves this page '
              'unchanged.', '']
    return '\n'.join(lines)


BEGIN = '<!-- benchmark_sim: generated from here -->'
END = '<!-- benchmark_sim: generated up to here -->'


def write_report(path, text):
    """
    Write ``text`` between the :data:`BEGIN` and :data:`END` markers of ``path``.

    What the file holds outside the markers (method notes, profiles, history) is kept; a
    file without markers gets the block at its top.

    :param path: the Markdown file.
    :param text: the generated report.
    """
    try:
        with open(path) as f:
            old = f.read()
    except FileNotFoundError:
        old = ''
    block = f'{BEGIN}\n{text.rstrip()}\n{END}\n'
    if BEGIN in old and END in old:
        head, rest = old.split(BEGIN, 1)
        new = head + block + rest.split(END, 1)[1].lstrip('\n')
    else:
        new = block + ('\n' + old if old else '')
    with open(path, 'w') as f:
        f.write(new)


def _robot_list(text):
    try:
        values = [int(v) for v in text.split(',') if v.strip()]
    except ValueError:
        values = []
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError(f'expected a comma-separated list of robot counts '
                                         f'>= 1, got {text!r}')
    return values


def main(args=None):
    """Run the benchmark, print the ratios, write the report; 0, or 1 on a failed stage."""
    argv = list(sys.argv[1:] if args is None else args)
    parser = argparse.ArgumentParser(prog='benchmark_sim', description=__doc__.split('\n')[1])
    parser.add_argument('--robots', type=_robot_list, default=list(DEFAULT_ROBOTS),
                        help='robot counts to run, e.g. 1,2,4 (default 1,2,4,8,16,32)')
    parser.add_argument('--duration', type=float, default=10.0,
                        help='measuring window of each mode in wall seconds (10)')
    parser.add_argument('--domain', type=int,
                        default=int(os.environ.get('ROS_DOMAIN_ID', '0') or 0),
                        help='ROS domain of the stacks (default $ROS_DOMAIN_ID or 0)')
    parser.add_argument('--no-viewer', action='store_true',
                        help='leave out part (d), the viewer with a headless browser')
    parser.add_argument('--output', default=os.path.join(_repo_root(), 'docs', 'benchmark.md'),
                        help='Markdown report to write ("" = none)')
    opts = parser.parse_args(argv)
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    log = lambda m: print(m, flush=True)  # noqa: E731
    try:
        rows = run(opts.robots, opts.duration, opts.domain, log=log, viewer=not opts.no_viewer)
    except BenchmarkError as exc:
        print(f'benchmark_sim: FAILED at {exc}', file=sys.stderr, flush=True)
        if exc.output:
            print(exc.output, file=sys.stderr, flush=True)
        print('benchmark_sim: no figures reported, ' +
              (f'{opts.output} left unchanged' if opts.output else 'no report written'),
              file=sys.stderr, flush=True)
        return 1
    print()
    print(format_table(rows))
    for description, measured, ok in targets(rows):
        print(f'{description}: {measured} {"PASS" if ok else "FAIL"}')
    if opts.output:
        write_report(opts.output, report(rows, opts.duration, argv))
        print(f'written {opts.output}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
