# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Benchmark part (d): real time with the viewer and one headless browser on its page.

The single-robot stack of the earlier benchmark (mujoco_sim, ``create``, the two spawners on
a private domain) plus robot_state_publisher and the ``viewer`` node, measured by
:func:`viewer_cost`; run by ``scripts/benchmark_sim`` (``--no-viewer`` leaves it out).
"""

import os
import signal
import subprocess
import tempfile
import time

from amr_description.launch.stacks import CONTROLLERS
from amr_description.tools.benchmark.common import cpu_seconds
from amr_description.tools.benchmark.common import TURN_TWIST


def _exe(name):
    from ament_index_python.packages import get_package_prefix
    return os.path.join(get_package_prefix('amr_description'), 'lib', 'amr_description', name)


class _Stack:
    """mujoco_sim + create + spawners on a private domain; killed on exit."""

    def __init__(self, domain_id, real_time_factor, urdf_path):
        self.env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
                        ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST', PYTHONUNBUFFERED='1')
        self.procs = []
        self.start_wall = time.monotonic()
        self.start_epoch = time.time()
        self.sim = self._start([_exe('mujoco_sim'), '--ros-args', '-p',
                                f'real_time_factor:={real_time_factor}', '-r',
                                '/diff_drive_controller/odom:=/odom'])
        self.create = self._start([_exe('create'), '-file', urdf_path, '-name', 'amr'])
        self.spawners = [self._start([_exe('spawner'), name, '--controller-manager-timeout',
                                      '30']) for name in CONTROLLERS]

    def _start(self, argv):
        log = tempfile.TemporaryFile()
        proc = subprocess.Popen(argv, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, start_new_session=True)
        proc.log = log
        self.procs.append(proc)
        return proc

    def output(self, proc):
        proc.log.seek(0)
        return proc.log.read().decode(errors='replace')

    def close(self):
        for proc in self.procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
        for proc in self.procs:
            try:
                proc.wait(5)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()


class _Observer:
    """Observer node: receives /clock, /joint_states, /odom, /tf; publishes cmd_vel."""

    def __init__(self, domain_id):
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import qos_profile_sensor_data
        from controller_manager_msgs.srv import ListControllers
        from geometry_msgs.msg import TwistStamped
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import JointState
        from tf2_msgs.msg import TFMessage

        os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
        self.rclpy = rclpy
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('benchmark_observer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.counts = {'/clock': 0, '/joint_states': 0, '/odom': 0, '/tf': 0}
        self.clock = None  # (wall, sim) of the latest /clock

        def counter(topic):
            def callback(msg):
                self.counts[topic] += 1
            return callback

        def on_clock(msg):
            self.counts['/clock'] += 1
            self.clock = (time.monotonic(), msg.clock.sec + msg.clock.nanosec * 1e-9)

        self._clock_sub = self.node.create_subscription(Clock, '/clock', on_clock, 10)
        self._other_subs = [
            self.node.create_subscription(JointState, '/joint_states', counter('/joint_states'),
                                          qos_profile_sensor_data),
            self.node.create_subscription(Odometry, '/odom', counter('/odom'), 10),
            self.node.create_subscription(TFMessage, '/tf', counter('/tf'), 100)]
        self.cmd_pub = self.node.create_publisher(
            TwistStamped, '/diff_drive_controller/cmd_vel', 10)
        self.twist = TwistStamped()
        self.twist.twist.linear.x, self.twist.twist.angular.z = TURN_TWIST
        self.list_client = self.node.create_client(
            ListControllers, '/controller_manager/list_controllers')
        self.list_request = ListControllers.Request()

    def spin_for(self, seconds, cmd_rate=20.0):
        """Spin ``seconds`` wall seconds, publishing cmd_vel (zero stamp = now) at cmd_rate."""
        end = time.monotonic() + seconds
        next_cmd = 0.0
        while True:
            now = time.monotonic()
            if now >= end:
                break
            if now >= next_cmd:
                self.cmd_pub.publish(self.twist)
                next_cmd = now + 1.0 / cmd_rate
            # sleep in the wait until the next command (callbacks wake it up)
            self.executor.spin_once(timeout_sec=max(0.0, min(next_cmd, end) - now))

    def active_controllers(self):
        """Return the names of active controllers (empty while the manager is absent)."""
        if not self.list_client.service_is_ready():
            self.executor.spin_once(timeout_sec=0.02)
            return set()
        future = self.list_client.call_async(self.list_request)
        end = time.monotonic() + 2.0
        while not future.done() and time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.01)
        if not future.done():
            return set()
        return {c.name for c in future.result().controller if c.state == 'active'}

    def measure(self, seconds):
        """Return (rtf, rates dict Hz of wall time) over ``seconds`` wall seconds."""
        self.spin_for(0.5)
        self.counts = dict.fromkeys(self.counts, 0)
        first = self.clock
        self.spin_for(seconds)
        last = self.clock
        if first is None or last is None or last[0] <= first[0]:
            return 0.0, self.counts
        wall = last[0] - first[0]
        return (last[1] - first[1]) / wall, {k: v / seconds for k, v in self.counts.items()}

    def close(self):
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


def viewer_cost(domain_id, urdf_path, duration, log=print):
    """
    (d) Real time with the viewer and one browser connected: RTF held and the viewer's CPU.

    Starts the (a) stack plus robot_state_publisher and the ``viewer`` node (30 Hz scene
    updates, use_sim_time) on a free port, opens its page in headless Debian chromium (driven
    by playwright, software WebGL) and, while the robot drives in a circle, measures the
    real-time factor as (a) does and the viewer's CPU time (user + system of its process
    group, from /proc) per wall second. Targets: RTF >= 0.99, viewer < 20 % of one core.

    :param domain_id: private ROS domain.
    :param urdf_path: robot URDF file.
    :param duration: measuring time, wall s.
    :param log: callable for progress lines.
    :returns: dict ``rtf`` (float), ``viewer_cpu`` (fraction of one core, None when the page
        could not be opened), ``rates`` (Hz).
    """
    import shutil
    import socket

    def group_cpu_seconds(pgid):
        total = 0.0
        for entry in os.listdir('/proc'):
            if entry.isdigit():
                try:
                    in_group = os.getpgid(int(entry)) == pgid
                except OSError:  # gone meanwhile
                    continue
                total += (cpu_seconds(entry) or 0.0) if in_group else 0.0
        return total

    result = {'rtf': 0.0, 'viewer_cpu': None, 'rates': {}}
    observer = _Observer(domain_id)
    stack = _Stack(domain_id, 1.0, urdf_path)
    profile = tempfile.mkdtemp(prefix='amr_bench_chromium_')
    try:
        with open(urdf_path) as f:
            description = f.read()
        params = os.path.join(profile, 'rsp.yaml')
        import yaml
        with open(params, 'w') as f:
            yaml.safe_dump({'robot_state_publisher': {'ros__parameters': {
                'robot_description': description, 'use_sim_time': True}}}, f)
        stack._start([_exe('robot_state_publisher'), '--ros-args', '--params-file', params])
        with socket.socket() as sock:
            sock.bind(('127.0.0.1', 0))
            port = sock.getsockname()[1]
        viewer = stack._start([_exe('viewer'), '--ros-args', '-p', f'port:={port}', '-p',
                               'use_sim_time:=true'])
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline and not (
                set(CONTROLLERS) <= observer.active_controllers() and
                'open http' in stack.output(viewer)):
            time.sleep(0.2)
        if 'open http' not in stack.output(viewer):
            log(f'viewer did not start:\n{stack.output(viewer)}')
            return result
        from playwright.sync_api import sync_playwright
        with sync_playwright() as playwright:
            context = playwright.chromium.launch_persistent_context(
                os.path.join(profile, 'chromium'), headless=True,
                executable_path=shutil.which('chromium') or '/usr/bin/chromium',
                viewport={'width': 960, 'height': 640},
                args=['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
                      '--disable-background-networking', '--disable-component-update',
                      '--disable-sync', '--use-gl=angle', '--use-angle=swiftshader',
                      '--enable-unsafe-swiftshader'])
            try:
                page = context.pages[0] if context.pages else context.new_page()
                page.goto(f'http://127.0.0.1:{port}/', timeout=120000)
                page.get_by_text('Fixed Frame').first.wait_for(timeout=120000)
                observer.spin_for(2.0)
                cpu0, wall0 = group_cpu_seconds(viewer.pid), time.monotonic()
                result['rtf'], result['rates'] = observer.measure(duration)
                result['viewer_cpu'] = (group_cpu_seconds(viewer.pid) - cpu0) / \
                    (time.monotonic() - wall0)
            finally:
                context.close()
    finally:
        stack.close()
        observer.close()
        shutil.rmtree(profile, ignore_errors=True)
    return result
