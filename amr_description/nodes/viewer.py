# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
viewer: the RViz stand-in, a live 3D view of the robot in the browser (viser).

What RViz's displays of the tutorial show, on a web page served by this node:

- **Grid** in the fixed frame;
- **RobotModel**: every ``robot_description_topics`` entry (std_msgs/String, transient local;
  default ``['/robot_description']``) builds a robot, rebuilt when a new description arrives;
  its links are posed from ``/tf`` + ``/tf_static`` in the **Fixed Frame** (parameter
  ``fixed_frame``, ``odom``) with a tf2-like buffer
  (:mod:`amr_description.core.tf_buffer`, latest common time per link). A description
  published under a namespace (``/r1/robot_description``) uses frames ``r1/<link>``, as
  robot_state_publisher's ``frame_prefix``. When the fixed frame does not exist (yet), the
  view falls back to the first robot's root link and says so, as RViz's status does;
- **TF** axes of every frame (checkbox);
- **Odometry** trails of ``odometry_topics`` (``/odom``, ``/ground_truth/odom``), one colour
  each with a legend and a Clear button. A trail whose ``header.frame_id`` is not in TF (the
  simulator's ``world``) is drawn as if that frame were the fixed frame, and the legend says
  so;
- a **status** panel: sim time and real-time factor (from ``/clock``), rates of ``/clock``,
  ``/joint_states`` (as remapped), the first of ``odometry_topics`` and ``/tf``;
- a **teleop pad** (no RViz peer): hold a button, or a key while the page has focus (arrows or
  ``I J L`` and ``K`` to stop; ``,`` is not available to page hotkeys), to publish
  ``geometry_msgs/TwistStamped`` on ``cmd_vel_topic`` (``/diff_drive_controller/cmd_vel``)
  at 20 Hz, stamped with the node clock (``use_sim_time`` aware), ``header.frame_id`` =
  ``frame_id`` (``base_link``); one zero twist on release. Dead-man
  (:mod:`amr_description.core.teleop_pad`): a control that the page stops refreshing (released,
  page closed, focus lost, connection dropped) is released within 0.25 s (buttons) or
  0.6 s (keys, which repeat only after the keyboard's auto-repeat delay). Speed (m/s) and
  turn rate (rad/s) are set on the page (``speed`` 0.5, ``turn`` 1.0 to start, as
  teleop_twist_keyboard).

Parameters ``host`` (127.0.0.1: only this machine can open the page; use ``ssh -L`` from
another one) and ``port`` (8080); ``update_rate`` (Hz of scene updates, 30). A port in use:
one line naming it and the parameter, exit code 1. A description that does not parse: the
error on the page and in the log, the node keeps running. Prints
``viewer: open http://HOST:PORT/ in a browser`` once serving.
"""

import collections
import math
import sys
import threading
import time

from amr_description.core import teleop_pad
from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.ros.node import Node
from amr_description.web.robot_scene import wxyzs_positions
from amr_description.web.server import page_url
from amr_description.web.server import run_web_node
from amr_description.web.server import start_server
from amr_description.web.server import stop_server
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import Odometry
import numpy as np
from rcl_interfaces.msg import ParameterDescriptor
from rcl_interfaces.msg import ParameterType
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock as ClockMsg
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from tf2_msgs.msg import TFMessage

NODE_NAME = 'viewer'
TRAIL_COLOURS = [((255, 140, 0), 'orange'), ((0, 170, 0), 'green'), ((200, 0, 200), 'magenta'),
                 ((0, 160, 200), 'cyan')]
PAD_RATE = 20.0
BUTTON_HOLD = 0.25
KEY_HOLD = 0.6
RATE_WINDOW = 2.0
TRAIL_MIN_STEP = 0.01
TRAIL_MAX_POINTS = 20000
TRAIL_CHUNK = 200
TRAIL_RATE = 10.0
STATUS_PERIOD = 0.5
POSE_TOLERANCE = 1e-5  # largest change of a pose matrix entry (m, or rotation entry) not sent
TRAIL_TOLERANCE = 1e-4


def _stamp(header):
    return header.stamp.sec + header.stamp.nanosec * 1e-9


def _frame_prefix(topic):
    """Return ``r1/`` for ``/r1/robot_description``, '' for ``/robot_description``."""
    namespace = topic.strip('/').rpartition('/')[0]
    return namespace + '/' if namespace else ''


def _moved(last, T, tolerance):
    """Return True when ``last`` is None or a 4x4 pose entry differs by more than tolerance."""
    return last is None or float(np.max(np.abs(last - T))) > tolerance


class _Rate:
    """Arrival rate of a topic over the last RATE_WINDOW seconds (wall clock)."""

    def __init__(self):
        self.times = collections.deque()

    def tick(self, now):
        self.times.append(now)

    def hz(self, now):
        while self.times and now - self.times[0] > RATE_WINDOW:
            self.times.popleft()
        if len(self.times) < 2:
            return 0.0
        return (len(self.times) - 1) / max(self.times[-1] - self.times[0], 1e-9)


class Viewer(Node):
    """Node ``viewer`` (see the module docstring)."""

    def __init__(self):
        """
        Declare parameters, start the web page, subscribe and start the timers.

        :raises PortInUse: when the port cannot be bound (one line).
        :raises ValueError: on a bad parameter (one line).
        """
        super().__init__(NODE_NAME)
        string_array = ParameterDescriptor(type=ParameterType.PARAMETER_STRING_ARRAY)
        self.declare_parameter('fixed_frame', 'odom')
        self.declare_parameter('robot_description_topics', ['/robot_description'],
                               string_array)
        self.declare_parameter('odometry_topics', ['/odom', '/ground_truth/odom'],
                               string_array)
        self.declare_parameter('cmd_vel_topic', '/diff_drive_controller/cmd_vel')
        self.declare_parameter('frame_id', 'base_link')
        self.declare_parameter('speed', 0.5)
        self.declare_parameter('turn', 1.0)
        self.declare_parameter('host', '127.0.0.1')
        self.declare_parameter('port', 8080)
        self.declare_parameter('update_rate', 30.0)
        update_rate = float(self.get_parameter('update_rate').value)
        if not update_rate > 0.0:
            raise ValueError(f'update_rate must be > 0 Hz, found {update_rate}')
        self._frame_id = str(self.get_parameter('frame_id').value)
        self._lock = threading.Lock()
        self._buffer = TransformBuffer()
        self._robots = {}  # topic -> RobotScene
        self._robot_errors = {}  # topic -> message
        self._link_poses = {}  # (topic, link) -> last pose sent
        self._tf_axes = None  # one batched-axes scene node for every TF frame
        self._tf_frames = []  # the frames it draws, in order
        self._tf_last = None  # their poses sent last, shape (N, 4, 4)
        self._trails = {}  # topic -> {'frame': str, 'points': list, 'dirty': bool}
        self._rates = {}  # topic -> _Rate, in the status order (filled below)
        self._clock_samples = collections.deque()  # (wall, sim)
        self._sim_time = None
        self._deadman = teleop_pad.DeadMan(BUTTON_HOLD)
        self._next_status = 0.0
        self._next_trails = 0.0

        host = str(self.get_parameter('host').value)
        port = int(self.get_parameter('port').value)
        self._server = start_server(host, port)
        self.url = page_url(host, port)
        self._build_page()

        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        for topic in self.get_parameter('robot_description_topics').value:
            if topic:
                self.create_subscription(
                    String, topic, lambda msg, topic=topic: self._on_description(topic, msg),
                    latched)
        static_qos = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.create_subscription(TFMessage, '/tf', self._on_tf, 100)
        self.create_subscription(TFMessage, '/tf_static', self._on_tf_static, static_qos)
        self.create_subscription(ClockMsg, '/clock', self._on_clock, 10)
        # only counted (status rate): taken raw, never converted to a Python message
        joint_states = self.create_subscription(JointState, '/joint_states',
                                                lambda msg: self._tick(self._joint_states),
                                                qos_profile_sensor_data, raw=True)
        self._joint_states = joint_states.topic_name  # as remapped
        odometry = [t for t in self.get_parameter('odometry_topics').value if t]
        self._rated_odometry = odometry[0] if odometry else None
        for name in ('/clock', self._joint_states, self._rated_odometry, '/tf'):
            if name is not None:
                self._rates[name] = _Rate()
        for topic in odometry:
            self._add_trail(topic)
            self.create_subscription(
                Odometry, topic, lambda msg, topic=topic: self._on_odometry(topic, msg), 10)
        self._cmd_pub = self.create_publisher(
            TwistStamped, str(self.get_parameter('cmd_vel_topic').value), 10)
        wall = Clock(clock_type=ClockType.STEADY_TIME)
        self.create_timer(1.0 / update_rate, self._update_scene, clock=wall)
        self.create_timer(1.0 / PAD_RATE, self._pad_tick, clock=wall)

    # -- page ---------------------------------------------------------------------------------

    def _build_page(self):
        server = self._server
        gui = server.gui
        server.scene.set_up_direction('+z')
        # behind a robot at the origin facing +x, looking past its right side: it appears
        # left of the control panel (on the right) and drives straight up the screen
        server.initial_camera.position = (-1.9, -0.6, 1.3)
        server.initial_camera.look_at = (0.6, -0.6, 0.0)
        self._grid = server.scene.add_grid('/grid', width=10.0, height=10.0, cell_size=0.5,
                                           section_size=1.0)
        self._status = gui.add_markdown('Waiting for data...')
        with gui.add_folder('Displays'):
            self._fixed_frame = gui.add_text('Fixed Frame',
                                             str(self.get_parameter('fixed_frame').value))
            self._show_tf = gui.add_checkbox('TF axes', True)
            self._show_trails = gui.add_checkbox('Odometry trails', True)
            self._legend = gui.add_markdown('')
            clear = gui.add_button('Clear trails')
            clear.on_click(lambda _: self._clear_trails())
        with gui.add_folder('Teleop'):
            self._speed = gui.add_slider('speed (m/s)', min=0.0, max=2.0, step=0.01,
                                         initial_value=float(self.get_parameter('speed').value))
            self._turn = gui.add_slider('turn (rad/s)', min=0.0, max=4.0, step=0.01,
                                        initial_value=float(self.get_parameter('turn').value))
            for label, control in (('Forward', 'forward'), ('Left', 'left'),
                                   ('Right', 'right'), ('Back', 'back')):
                button = gui.add_button(label)
                button.on_hold(self._hold_callback(control), callback_hz=PAD_RATE)
            stop = gui.add_button('Stop')
            stop.on_click(lambda _: self._press('stop', BUTTON_HOLD))
            gui.add_markdown('Hold a button, or a key while the page has focus: arrows or '
                             '**I** forward, **J** / **L** turn, **K** stop.')
        for key, control in teleop_pad.KEYS.items():
            hotkey = key.lower() if key.startswith('Arrow') else key.upper()
            if hotkey == ',':
                continue  # not a key viser's hotkeys accept
            command = gui.add_command(f'teleop {control}', hotkey=hotkey)
            command.on_trigger(self._key_callback(control))
        server.on_client_disconnect(lambda _: self._release_all())

    def _hold_callback(self, control):
        return lambda _: self._press(control, BUTTON_HOLD)

    def _key_callback(self, control):
        return lambda _: self._press(control, KEY_HOLD)

    def _press(self, control, hold):
        with self._lock:
            self._deadman.press(control, time.monotonic(), hold)

    def _release_all(self):
        with self._lock:
            self._deadman.release_all()

    # -- subscriptions ------------------------------------------------------------------------

    def _tick(self, name):
        self._rates[name].tick(time.monotonic())

    def _on_description(self, topic, msg):
        from amr_description.core.urdf_model import parse_urdf
        from amr_description.web.robot_scene import RobotScene
        try:
            model = parse_urdf(msg.data, source=topic)
        except ValueError as exc:
            self.get_logger().error(str(exc))
            self._robot_errors[topic] = str(exc)
            self._next_status = 0.0
            return
        self._robot_errors.pop(topic, None)
        old = self._robots.pop(topic, None)
        if old is not None:
            old.remove()
        name = topic.strip('/').replace('/', '_') or 'robot'
        robot = RobotScene(self._server.scene, model, f'/robots/{name}', _frame_prefix(topic))
        for problem in robot.problems:
            self.get_logger().warning(problem)
        self._robots[topic] = robot
        self._link_poses = {k: v for k, v in self._link_poses.items() if k[0] != topic}
        self.get_logger().info(f"robot '{model.name}' from {topic}: {len(model.links)} links")
        self._next_status = 0.0

    def _store(self, msg, static):
        for t in msg.transforms:
            tr, q = t.transform.translation, t.transform.rotation
            try:
                self._buffer.set_transform(t.header.frame_id, t.child_frame_id,
                                           _stamp(t.header), (tr.x, tr.y, tr.z),
                                           (q.x, q.y, q.z, q.w), static=static)
            except ValueError as exc:
                self.get_logger().warning(f"{'/tf_static' if static else '/tf'}: {exc}",
                                          throttle_duration_sec=5.0)

    def _on_tf(self, msg):
        self._tick('/tf')
        self._store(msg, False)

    def _on_tf_static(self, msg):
        self._store(msg, True)

    def _on_clock(self, msg):
        now = time.monotonic()
        self._tick('/clock')
        sim = msg.clock.sec + msg.clock.nanosec * 1e-9
        if self._sim_time is not None and sim < self._sim_time:
            self._clock_samples.clear()  # the simulation was reset
            self._buffer.clear()
        self._sim_time = sim
        self._clock_samples.append((now, sim))
        while self._clock_samples and now - self._clock_samples[0][0] > RATE_WINDOW:
            self._clock_samples.popleft()

    def _add_trail(self, topic):
        rgb, colour = TRAIL_COLOURS[len(self._trails) % len(TRAIL_COLOURS)]
        self._trails[topic] = {'frame': '', 'points': [], 'dirty': False, 'rgb': rgb,
                               'colour': colour, 'chunks': [], 'chunk_start': 0, 'T': None,
                               'fixed': None, 'reset': False}

    def _on_odometry(self, topic, msg):
        if topic == self._rated_odometry:
            self._tick(topic)
        p = msg.pose.pose.position
        point = (p.x, p.y, p.z)
        if not all(math.isfinite(v) for v in point):
            return
        trail = self._trails[topic]
        frame = msg.header.frame_id.lstrip('/')
        if frame != trail['frame']:
            trail['frame'] = frame
            trail['points'] = []
            trail['reset'] = True
        points = trail['points']
        if points and math.dist(point, points[-1]) < TRAIL_MIN_STEP:
            return
        points.append(point)
        trail['dirty'] = True
        if len(points) > TRAIL_MAX_POINTS:  # forget the older half and redraw
            del points[:TRAIL_MAX_POINTS // 2]
            trail['reset'] = True

    def _clear_trails(self):
        with self._lock:
            for trail in self._trails.values():
                trail['points'] = []
                trail['reset'] = True

    # -- timers -------------------------------------------------------------------------------

    def _pad_tick(self):
        with self._lock:
            command = self._deadman.command(time.monotonic(), self._speed.value,
                                            self._turn.value)
        if command is None:
            return
        msg = TwistStamped()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.header.frame_id = self._frame_id
        msg.twist.linear.x, msg.twist.angular.z = command
        self._cmd_pub.publish(msg)

    def _choose_fixed_frame(self):
        """Return (frame used, note for the status or '')."""
        wanted = self._fixed_frame.value.strip().lstrip('/')
        if wanted and wanted in self._buffer.frames():
            return wanted, ''
        for robot in self._robots.values():
            root = robot.frame_id(robot.model.root)
            return root, (f'Fixed Frame [{wanted}] does not exist; showing the robot root '
                          f'[{root}]')
        return wanted, f'Fixed Frame [{wanted}] does not exist'

    def _update_scene(self):
        if not self._server.get_clients():
            return  # nobody looks: the scene is brought up to date when a page connects
        # one batch of messages per update: viser wakes its event loop once per batch, not
        # once per changed value (that wake-up was the largest single cost of an update)
        with self._server.atomic():
            self._draw()

    def _draw(self):
        fixed, note = self._choose_fixed_frame()
        poses = {}  # frame -> its pose in the fixed frame (None: no transform), this update
        missing = []
        for topic, robot in self._robots.items():
            for link in robot.model.links:
                T = self._pose_in(fixed, robot.frame_id(link), poses)
                if T is None:
                    robot.hide(link)
                    self._link_poses.pop((topic, link), None)
                    missing.append(robot.frame_id(link))
                    continue
                last = self._link_poses.get((topic, link))
                if _moved(last, T, POSE_TOLERANCE):
                    robot.set_pose(link, T)
                    self._link_poses[(topic, link)] = T
        self._update_tf_axes(fixed, poses)
        self._update_trails(fixed)
        now = time.monotonic()
        if now >= self._next_status:
            self._next_status = now + STATUS_PERIOD
            self._update_status(fixed, note, missing)

    def _pose_in(self, fixed, frame, poses):
        """Return the pose of ``frame`` in ``fixed`` (4x4) or None, looked up once per update."""
        if frame not in poses:
            try:
                poses[frame] = self._buffer.lookup(fixed, frame)[0]
            except TransformException:
                poses[frame] = None
        return poses[frame]

    def _update_tf_axes(self, fixed, poses):
        """
        Draw the axes of every frame that has a pose in the fixed frame, as one scene node.

        One batched-axes node (instanced on the page) holds every frame's axes, so an update
        sends at most two arrays instead of two messages per frame; the node is rebuilt only
        when the set of frames drawn changes.
        """
        frames, stack = [], []
        if self._show_tf.value:
            for frame in sorted(self._buffer.frames()):
                T = self._pose_in(fixed, frame, poses)
                if T is not None:
                    frames.append(frame)
                    stack.append(T)
        node = self._tf_axes
        if not frames:
            if node is not None and node.visible:
                node.visible = False
            return
        stack = np.stack(stack)
        if node is not None and frames == self._tf_frames:
            if _moved(self._tf_last, stack, POSE_TOLERANCE):
                node.batched_wxyzs, node.batched_positions = wxyzs_positions(stack)
                self._tf_last = stack
            if not node.visible:
                node.visible = True
            return
        if node is not None:
            node.remove()
        wxyzs, positions = wxyzs_positions(stack)
        self._tf_axes = self._server.scene.add_batched_axes(
            '/tf', wxyzs, positions, axes_length=0.12, axes_radius=0.006)
        self._tf_frames, self._tf_last = frames, stack

    def _update_trails(self, fixed):
        """
        Draw the odometry trails in the fixed frame, at most TRAIL_RATE times a second.

        A trail is drawn in chunks of TRAIL_CHUNK points: only the newest chunk's points are
        sent again when points arrive (as new points of its scene node, not as a new node);
        every chunk is redrawn when the trail's frame moved in the fixed frame, the fixed frame
        changed or the trail was cleared.
        """
        now = time.monotonic()
        if now < self._next_trails:
            return
        self._next_trails = now + 1.0 / TRAIL_RATE
        show = self._show_trails.value
        with self._lock:
            for topic, trail in self._trails.items():
                T, trail['in_tf'] = np.eye(4), True
                if trail['frame'] and trail['frame'] != fixed:
                    try:
                        T, _ = self._buffer.lookup(fixed, trail['frame'])
                    except TransformException:
                        trail['in_tf'] = False
                moved = _moved(trail['T'], T, TRAIL_TOLERANCE)
                if moved or trail['reset'] or trail['fixed'] != fixed:
                    for node in trail['chunks']:
                        node.remove()
                    trail['chunks'] = []
                    trail['chunk_start'] = 0
                    trail['T'], trail['fixed'], trail['reset'] = T, fixed, False
                    trail['dirty'] = True
                for node in trail['chunks']:
                    if node.visible != show:
                        node.visible = show
                if not trail['dirty']:
                    continue
                trail['dirty'] = False
                points = trail['points']
                name = topic.strip('/').replace('/', '_')
                while len(points) - trail['chunk_start'] >= 2:
                    start = trail['chunk_start']
                    chunk = np.asarray(points[start:start + TRAIL_CHUNK + 1], dtype=float)
                    chunk = chunk @ T[:3, :3].T + T[:3, 3]
                    index = start // TRAIL_CHUNK
                    segments = np.stack([chunk[:-1], chunk[1:]], axis=1).astype(np.float32)
                    if index < len(trail['chunks']):  # the growing chunk: replace its points
                        trail['chunks'][index].points = segments
                    else:
                        trail['chunks'].append(self._server.scene.add_line_segments(
                            f'/trails/{name}/{index}', segments, trail['rgb'], thickness=3.0,
                            thickness_units='screen', visible=show))
                    if len(chunk) < TRAIL_CHUNK + 1:
                        break  # the newest chunk, still growing
                    trail['chunk_start'] = start + TRAIL_CHUNK

    def _update_status(self, fixed, note, missing):
        now = time.monotonic()
        lines = []
        for topic, error in self._robot_errors.items():
            lines.append(f'**Robot description error** ({topic}): {error}')
        if not self._robots:
            lines.append('Waiting for ' + ', '.join(
                f'`{t}`' for t in self.get_parameter('robot_description_topics').value) + '...')
        lines.append(f'Fixed Frame: **{fixed}**' + (f' ({note})' if note else ''))
        if missing and self._robots:
            lines.append(f'No transform to {", ".join(sorted(set(missing))[:4])}'
                         + (' ...' if len(set(missing)) > 4 else ''))
        clock_running = bool(self._clock_samples) and \
            now - self._clock_samples[-1][0] < RATE_WINDOW
        if self._sim_time is not None and clock_running:
            rtf = ''
            if len(self._clock_samples) >= 2:
                (w0, s0), (w1, s1) = self._clock_samples[0], self._clock_samples[-1]
                if w1 > w0:
                    rtf = f', real-time factor **{(s1 - s0) / (w1 - w0):.2f}**'
            lines.append(f'Sim time **{self._sim_time:.2f} s**{rtf}')
        elif self._sim_time is not None:
            lines.append(f'Sim time **{self._sim_time:.2f} s** (paused or stopped)')
        else:
            lines.append('No `/clock`: wall time')
        lines.append(' · '.join(f'`{name}` {rate.hz(now):.1f} Hz'
                                for name, rate in self._rates.items()))
        self._status.content = '\n\n'.join(lines)
        legend = []
        for topic, trail in self._trails.items():
            extra = ''
            if trail['frame'] and not trail.get('in_tf', True):
                extra = f' (frame `{trail["frame"]}` not in TF: drawn in {fixed})'
            legend.append(f'{trail["colour"]}: `{topic}`{extra}')
        self._legend.content = '  \n'.join(legend)

    def stop_server(self):
        """Stop the web server (closes the port)."""
        if self._server is not None:
            stop_server(self._server)
            self._server = None


def main(args=None):
    """
    Run :class:`Viewer` until Ctrl-C or SIGTERM (:func:`run_web_node`).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :returns: 0 on a clean shutdown, 1 on a port in use or a bad parameter (one line).
    """
    from rclpy.experimental import EventsExecutor
    return run_web_node(Viewer, NODE_NAME, args, executor_class=EventsExecutor)


if __name__ == '__main__':
    sys.exit(main())
