# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Cost of mapping and localization on this machine, with the viewer's page open.

Two stacks, one after the other, each on a private domain with the viewer's page open in
headless Debian chromium (software WebGL) while the robot drives a circle (0.2 m/s,
0.3 rad/s) for ``--seconds`` of wall time after a warm-up:

1. ``slam`` (``world:=``, warehouse by default): the real-time factor (sim seconds over wall
   seconds of ``/clock``), the ``/scan`` messages published and the scans SLAM kept
   (``/pose`` messages), and the CPU share (% of one core, from ``/proc``) of
   ``async_slam_toolbox_node``, ``mujoco_sim`` and ``viewer``; the map is then saved;
2. ``sim`` with ``rviz_config:=nav2_default_view.rviz`` and ``localization_launch.py`` on that
   map, AMCL at 2,000 particles (``min_particles`` = ``max_particles``) updating on every
   10 Hz scan (``update_min_d`` = ``update_min_a`` = 0): its CPU share, the RTF and the
   ``/amcl_pose`` messages.

Run: ``python -m amr_description.tools.benchmark.nav_cost [--world W] [--seconds S]``; the
figures are in docs/navigation.md.
"""

import argparse
import contextlib
import os
import subprocess
import tempfile
import time

from amr_description.tools.benchmark.common import cpu_seconds

DRIVE = (0.2, 0.3)
"""m/s and rad/s of the circle driven while measuring."""


class Observer:
    """An rclpy node on the stack's domain: counts topics, samples /clock, drives."""

    def __init__(self, domain_id):
        import rclpy
        from geometry_msgs.msg import PoseWithCovarianceStamped
        from geometry_msgs.msg import TwistStamped
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import qos_profile_sensor_data
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import LaserScan
        self.context = rclpy.Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('nav_cost_observer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.counts = {'/scan': 0, '/pose': 0, '/amcl_pose': 0}
        self.sim_time = None
        self.Twist = TwistStamped
        self.cmd = self.node.create_publisher(TwistStamped, '/diff_drive_controller/cmd_vel', 10)

        def counter(topic):
            def count(_):
                self.counts[topic] += 1
            return count

        self.node.create_subscription(LaserScan, '/scan', counter('/scan'),
                                      qos_profile_sensor_data)
        for topic in ('/pose', '/amcl_pose'):
            self.node.create_subscription(PoseWithCovarianceStamped, topic, counter(topic), 10)
        self.node.create_subscription(Clock, '/clock', self._on_clock, 10)

    def _on_clock(self, msg):
        self.sim_time = msg.clock.sec + msg.clock.nanosec * 1e-9

    def spin_for(self, seconds, drive=True):
        """Spin (and drive at 10 Hz when ``drive``) for ``seconds`` of wall time."""
        end = time.monotonic() + seconds
        next_cmd = 0.0
        while time.monotonic() < end:
            if drive and time.monotonic() >= next_cmd:
                msg = self.Twist()
                msg.twist.linear.x, msg.twist.angular.z = DRIVE
                self.cmd.publish(msg)
                next_cmd = time.monotonic() + 0.1
            self.executor.spin_once(timeout_sec=0.02)

    def close(self):
        """Stop the robot and the node."""
        self.cmd.publish(self.Twist())
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()


def start_stack(name, argv, env, log):
    """
    Start the stack ``name`` with launch arguments ``argv`` in an orchestrator.

    :param name: a registered stack (:data:`amr_description.launch.registry.STACKS`).
    :param argv: ``name:=value`` strings.
    :param env: the processes' environment.
    :param log: the open file the processes' output goes to.
    :returns: ``(orchestrator, lines)``, ``lines`` the output lines seen so far (grows).
    """
    from amr_description.launch import registry
    from amr_description.launch.orchestrator import Orchestrator
    lines = []
    orchestrator = Orchestrator(registry.describe(name, argv), stream=log, env=env,
                                line_callback=lambda label, line: lines.append(line))
    orchestrator.start()
    return orchestrator, lines


def wait_for_line(lines, text, observer, timeout):
    """
    Spin ``observer`` until a line of ``lines`` contains ``text``.

    :raises RuntimeError: when it is not seen within ``timeout`` seconds.
    """
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if any(text in line for line in lines):
            return
        observer.spin_for(0.2, drive=False)
    raise RuntimeError(f"'{text}' not seen in {timeout:g} s")


def process_cpu(orchestrators):
    """Return ``{action name: CPU seconds}`` of the running processes."""
    found = {}
    for orchestrator in orchestrators:
        for record in list(orchestrator.processes):
            if record.returncode is None and record.pid:
                seconds = cpu_seconds(record.pid)
                if seconds is not None:
                    found[record.action.name] = found.get(record.action.name, 0.0) + seconds
    return found


def _measure(observer, orchestrators, url, warmup, seconds):
    """Open ``url`` in chromium, drive; return the window's figures."""
    from amr_description.tools.screenshot import browser_page
    with browser_page(url, {'width': 1000, 'height': 700}, 60000):
        observer.spin_for(warmup)
        counts0, cpu0 = dict(observer.counts), process_cpu(orchestrators)
        sim0, wall0 = observer.sim_time, time.monotonic()
        observer.spin_for(seconds)
        counts1, cpu1 = dict(observer.counts), process_cpu(orchestrators)
        sim1, wall1 = observer.sim_time, time.monotonic()
    wall = wall1 - wall0
    return {'rtf': (sim1 - sim0) / wall, 'wall': wall,
            'counts': {t: counts1[t] - counts0[t] for t in counts1},
            'cpu': {name: 100.0 * (cpu1[name] - cpu0.get(name, 0.0)) / wall
                    for name in cpu1}}


def _amcl_params(folder):
    """Write config/nav2_params.yaml with AMCL at 2,000 particles, updating on every scan."""
    import yaml
    from amr_description.launch.nav_stacks import share_file
    with open(share_file('config', 'nav2_params.yaml')) as f:
        params = yaml.safe_load(f)
    amcl = params['amcl']['ros__parameters']
    amcl.update(min_particles=2000, max_particles=2000, update_min_d=0.0, update_min_a=0.0)
    path = os.path.join(folder, 'nav2_params.yaml')
    with open(path, 'w') as f:
        yaml.safe_dump(params, f)
    return path


def free_port():
    """Return a TCP port free on 127.0.0.1 now."""
    import socket
    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        return sock.getsockname()[1]


def _line(stage, figures, names):
    cpu = ', '.join(f'{n} {figures["cpu"].get(n, 0.0):.1f} %' for n in names)
    counts = ', '.join(f'{t} {c}' for t, c in figures['counts'].items() if c)
    return (f'{stage}: RTF {figures["rtf"]:.3f} over {figures["wall"]:.0f} s; {counts}; '
            f'CPU (% of one core): {cpu}')


@contextlib.contextmanager
def private_session(domain_id, prefix):
    """
    Yield ``(env, folder, stream, observer)`` for a benchmark's stacks on a private domain.

    ``env``: the processes' environment (``ROS_DOMAIN_ID``, localhost discovery); ``folder``:
    a new temporary folder; ``stream``: its open ``stacks.log`` for the processes' output;
    ``observer``: an :class:`Observer` on the domain. The observer and the log are closed after.
    """
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    folder = tempfile.mkdtemp(prefix=prefix)
    stream = open(os.path.join(folder, 'stacks.log'), 'w')
    observer = Observer(domain_id)
    try:
        yield env, folder, stream, observer
    finally:
        observer.close()
        stream.close()


def run(world='warehouse', seconds=60.0, warmup=10.0, domain_id=211, log=print):
    """
    Run both stages; return their lines (also passed to ``log``).

    :param world: the world of both stages.
    :param seconds: wall seconds measured per stage.
    :param warmup: wall seconds of driving with the page open before measuring.
    :param domain_id: the private ROS domain.
    """
    lines_out = []
    with private_session(domain_id, 'amr_nav_cost_') as (env, folder, stream, observer):
        port = free_port()
        slam, lines = start_stack('slam', [f'world:={world}', f'viewer_port:={port}'], env, stream)
        try:
            wait_for_line(lines, 'Configured and activated diff_drive_controller', observer, 240.0)
            figures = _measure(observer, [slam], f'http://127.0.0.1:{port}', warmup, seconds)
            lines_out.append(_line(f'slam in {world}', figures,
                                   ('async_slam_toolbox_node', 'mujoco_sim', 'viewer')))
            log(lines_out[-1])
            map_path = os.path.join(folder, 'map')
            subprocess.run(['ros2', 'run', 'nav2_map_server', 'map_saver_cli', '-f', map_path,
                            '--ros-args', '-p', 'save_map_timeout:=10.0'], env=env,
                           stdout=stream, stderr=stream, timeout=120, check=True)
        finally:
            slam.shutdown()
            slam.wait(timeout=60.0)
        port = free_port()
        sim, lines = start_stack('sim', [f'world:={world}', f'viewer_port:={port}',
                                         'rviz_config:=nav2_default_view.rviz'], env, stream)
        loc = None
        try:
            wait_for_line(lines, 'Configured and activated diff_drive_controller', observer, 240.0)
            loc, loc_lines = start_stack('localization', [f'map:={map_path}.yaml',
                                                          'use_sim_time:=true',
                                                          f'params_file:={_amcl_params(folder)}'],
                                         env, stream)
            wait_for_line(loc_lines, 'Please set the initial pose', observer, 120.0)
            from geometry_msgs.msg import PoseWithCovarianceStamped
            initial = observer.node.create_publisher(PoseWithCovarianceStamped, '/initialpose',
                                                     1)
            pose = PoseWithCovarianceStamped()
            pose.header.frame_id = 'map'
            pose.pose.covariance[0] = pose.pose.covariance[7] = 0.25
            pose.pose.covariance[35] = 0.0685
            while observer.counts['/amcl_pose'] == 0:
                initial.publish(pose)
                observer.spin_for(0.5)
            figures = _measure(observer, [sim, loc], f'http://127.0.0.1:{port}', warmup,
                               seconds)
            lines_out.append(_line(f'localization in {world} (2,000 particles, every scan)',
                                   figures, ('amcl', 'mujoco_sim', 'viewer')))
            log(lines_out[-1])
        finally:
            for orchestrator in (loc, sim):
                if orchestrator is not None:
                    orchestrator.shutdown()
                    orchestrator.wait(timeout=60.0)
    return lines_out


def main(argv=None):
    """Parse the arguments and print the two stages' figures."""
    parser = argparse.ArgumentParser(prog='nav_cost', description=__doc__.splitlines()[1])
    parser.add_argument('--world', default='warehouse', help='world of both stages')
    parser.add_argument('--seconds', type=float, default=60.0,
                        help='wall seconds measured per stage (60)')
    args = parser.parse_args(argv)
    run(args.world, args.seconds)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
