# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
viewer: the RViz stand-in, a live 3D view of the robot in the browser (viser).

What RViz's displays of the tutorial show, on a web page served by this node:

- **Grid** in the fixed frame;
- **RobotModel**: every ``robot_description_topics`` entry (std_msgs/String, transient local;
  ``*``: every ``.../robot_description``) builds a robot, rebuilt when a new description
  arrives; its links are posed from ``/tf`` + ``/tf_static`` in the **Fixed Frame** (parameter
  ``fixed_frame``, ``odom``) with a tf2-like buffer
  (:mod:`amr_description.core.tf_buffer`, latest common time per link). A description
  published under a namespace (``/r1/robot_description``) uses frames ``r1/<link>``, as
  robot_state_publisher's ``frame_prefix``. When the fixed frame does not exist (yet), the
  view falls back to the first robot's root link and says so, as RViz's status does;
- **World**: the SDF world named by ``world`` (the simulator's ``world`` parameter: a
  shipped world, a file or a URI; '' draws none), its models' geometry and colours as one
  mesh under the robots, in frame ``world`` (:mod:`amr_description.web.displays.world`);
- **TF** axes of every frame (checkbox);
- **LaserScan**: the newest scan of every ``scan_topics`` entry as points in
  the fixed frame, coloured by range (:mod:`amr_description.web.displays.laser_scan`);
  **PointCloud2** of ``point_cloud_topics``, coloured by height;
  **Imu** arrows (acceleration, angular velocity) of ``imu_topics``;
  **Image** panels of ``image_topics`` (subscribed only while a page is open) and each
  camera's frustum (:mod:`amr_description.web.displays.image`);
  **NavSatFix** of ``navsat_topics`` as text; **Contacts**
  (ros_gz_interfaces) of ``contact_topics`` as red markers;
- **Map** of ``map_topics`` (nav_msgs/OccupancyGrid on the ground, RViz's palettes),
  **ParticleCloud** (nav2_msgs) and **PoseArray** arrows, **PoseWithCovariance** with its
  covariance ellipse, and RViz's **2D Pose Estimate** / **2D Goal Pose** tools
  (``/initialpose``, ``/goal_pose``; docs/navigation.md);
- **Odometry** trails of ``odometry_topics``, one colour each (``/odom`` orange,
  ``/ground_truth/odom`` green) with a legend and a Clear button. A trail whose
  ``header.frame_id`` is not in TF (the simulator's ``world``) is drawn as if that frame were
  the fixed frame, and the legend says so;
- a **status** panel: sim time and real-time factor (from ``/clock``), rates of ``/clock``,
  ``/joint_states`` (as remapped), the first of ``odometry_topics``, every scan topic and
  ``/tf``;
- a **teleop pad** (no RViz peer): hold a button, or a key while the page has focus (arrows or
  ``I J L`` and ``K`` to stop; ``,`` is not available to page hotkeys), to publish
  ``geometry_msgs/TwistStamped`` on ``cmd_vel_topic`` ('': the first controller's
  ``.../cmd_vel`` found, else ``/cmd_vel``, a ``Twist`` one as ``Twist``) at 20 Hz, stamped
  with the node clock (``use_sim_time`` aware), ``header.frame_id`` = ``frame_id``
  (``base_link``); one zero twist on release. Dead-man
  (:mod:`amr_description.core.teleop_pad`): a control that the page stops refreshing (released,
  page closed, focus lost, connection dropped) is released within 0.25 s (buttons) or
  0.6 s (keys, which repeat only after the keyboard's auto-repeat delay). Speed (m/s) and
  turn rate (rad/s) are set on the page (``speed`` 0.5, ``turn`` 1.0 to start, as
  teleop_twist_keyboard). Shown only while something subscribes to ``cmd_vel_topic``.

Topic lists default to ``['*']``: every topic of the display's message type that has a
publisher, in any namespace, subscribed as it appears in the graph (looked at every 2 s;
:mod:`amr_description.web.displays.discovery`), so a fleet's ``/r1/scan`` is drawn and no
topic the robot lacks is subscribed. Named topics (parameters, an ``.rviz`` file, the stacks)
are subscribed from the start.

Each display is a module of :mod:`amr_description.web.displays` registered in the entry-point
group ``amr_description.displays`` (RViz's display plugins,
:mod:`amr_description.web.displays.registry`); this node declares the parameters they read,
serves the page and composes them in their order.

Parameters ``host`` (127.0.0.1: only this machine can open the page; use ``ssh -L`` from
another one) and ``port`` (not set: 8080, or the next free port when 8080 is taken; the
parameter then holds the port bound); ``update_rate`` (Hz of scene updates, 30). A port set
explicitly and in use: one line naming it and the argument that set it, exit code 1. A
description that does not parse: the error on the page and in the log, the node keeps running.
Prints ``viewer: open http://HOST:PORT/ in a browser`` once serving.

An RViz configuration (``viewer -d FILE.rviz`` as ``rviz2 -d``, or parameter ``rviz_config``;
the stacks' ``rviz_config:=``) sets the Fixed Frame and the topics of the displays it enables
(:mod:`amr_description.core.rviz_config`), replacing the topic parameters' defaults; the
displays it enables that the viewer does not have are listed in the status. A config that
cannot be read: one line, exit code 1.
"""

import os
import sys
import time

from amr_description.core.rviz_config import read_rviz_config
from amr_description.ros.node import Node
from amr_description.web.displays.base import DrawContext
from amr_description.web.displays.base import FrameManager
from amr_description.web.displays.discovery import DISCOVERY_PERIOD
from amr_description.web.displays.registry import display_classes
from amr_description.web.displays.registry import display_parameters
from amr_description.web.displays.registry import rviz_topic_parameters
from amr_description.web.server import run_web_node
from amr_description.web.server import serve_page
from amr_description.web.server import stop_server
from rcl_interfaces.msg import ParameterDescriptor
from rcl_interfaces.msg import ParameterType
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.parameter import Parameter

NODE_NAME = 'viewer'
DEFAULT_PORT = 8080
"""TCP port of the page when ``port`` is not set (the next free one when it is taken)."""


class Viewer(Node):
    """Node ``viewer`` (see the module docstring)."""

    def __init__(self):
        """
        Declare parameters, start the web page, compose the displays, start the timer.

        The displays are the registered ones (:mod:`amr_description.web.displays.registry`):
        their parameters are declared, an ``.rviz`` file sets their topics, and they are
        made and drawn in their ``order``.

        :raises PortInUse: when the port cannot be bound (one line).
        :raises ValueError: on a bad parameter (one line).
        """
        super().__init__(NODE_NAME)
        classes = display_classes()
        string_array = ParameterDescriptor(type=ParameterType.PARAMETER_STRING_ARRAY)
        self.declare_parameter('fixed_frame', 'odom')
        parameters = display_parameters(classes)
        for name, default in parameters.items():
            if isinstance(default, list):
                self.declare_parameter(name, default, string_array)
            else:
                self.declare_parameter(name, default)
        self.declare_parameter('update_rate', 30.0)
        self.declare_parameter('rviz_config', '')
        update_rate = float(self.get_parameter('update_rate').value)
        if not update_rate > 0.0:
            raise ValueError(f'update_rate must be > 0 Hz, found {update_rate}')
        self.server, self.url = serve_page(self, DEFAULT_PORT)

        rviz = None
        if self.get_parameter('rviz_config').value:  # ValueError: one line, exit 1
            rviz = read_rviz_config(str(self.get_parameter('rviz_config').value),
                                    rviz_topic_parameters(classes))
        settings = {name: self.get_parameter(name).value
                    for name in ('fixed_frame', *parameters)}
        if rviz is not None:  # the config's displays replace the defaults, as in RViz
            for problem in rviz.problems:
                self.get_logger().warning(problem)
            settings.update(rviz.topics)
            if rviz.fixed_frame:
                settings['fixed_frame'] = rviz.fixed_frame
            self.set_parameters([Parameter(name, value=settings[name])
                                 for name in ('fixed_frame', *rviz.topics) if settings[name]])
        settings['rviz'] = rviz
        self._fixed_frame_default = str(settings['fixed_frame'])
        self.frames = FrameManager(self)
        # made and drawn in their order (the status last: it reports what others saw)
        self.displays = []
        self.display_named = {}
        for name, cls in classes.items():
            display = cls.create(self, settings)
            self.displays.append(display)
            self.display_named[name] = display
        self._build_page()
        self._next_discovery = 0.0
        self.create_timer(1.0 / update_rate, self._update_scene,
                          clock=Clock(clock_type=ClockType.STEADY_TIME))

    def _build_page(self):
        server = self.server
        gui = server.gui
        server.scene.set_up_direction('+z')
        # behind a robot at the origin facing +x, looking past its right side: it appears
        # left of the control panel (on the right) and drives straight up the screen
        server.initial_camera.position = (-1.9, -0.6, 1.3)
        server.initial_camera.look_at = (0.6, -0.6, 0.0)
        server.scene.add_grid('/grid', width=10.0, height=10.0, cell_size=0.5,
                              section_size=1.0)
        panels = sorted(self.displays, key=lambda d: d.order if d.panel_order is None
                        else d.panel_order)
        for display in panels:
            display.build_panel(gui)
        with gui.add_folder('Displays'):
            self._fixed_frame = gui.add_text('Fixed Frame', self._fixed_frame_default)
            for display in self.displays:
                display.build(gui)
        for display in self.displays:
            display.build_footer(gui)

    def _choose_fixed_frame(self):
        """Return (frame used, note for the status or '')."""
        wanted = self._fixed_frame.value.strip().lstrip('/')
        if wanted and wanted in self.frames.buffer.frames():
            return wanted, ''
        if wanted and wanted in self.frames.message_frames:
            return wanted, f'Fixed Frame [{wanted}] is not in TF yet: only its map is drawn'
        robot_model = self.display_named.get('robot_model')
        root = robot_model.root_frame() if robot_model is not None else None
        if root is not None:
            return root, (f'Fixed Frame [{wanted}] does not exist; showing the robot root '
                          f'[{root}]')
        return wanted, f'Fixed Frame [{wanted}] does not exist'

    def _update_scene(self):
        now = time.monotonic()
        if now >= self._next_discovery:  # topics found by type (displays/discovery.py)
            self._next_discovery = now + DISCOVERY_PERIOD
            graph = self.get_topic_names_and_types()
            for display in self.displays:
                display.discover(graph)
        if not self.server.get_clients():
            for display in self.displays:  # nobody looks: the scene is brought up to date
                display.hidden()  # when a page connects
            return
        # one batch of messages per update: viser wakes its event loop once per batch, not
        # once per changed value (that wake-up was the largest single cost of an update)
        with self.server.atomic():
            context = DrawContext(self.frames, *self._choose_fixed_frame())
            for display in self.displays:
                display.draw(context)

    def stop_server(self):
        """Stop the web server (closes the port)."""
        if self.server is not None:
            stop_server(self.server)
            self.server = None


def main(args=None):
    """
    Run :class:`Viewer` until Ctrl-C or SIGTERM (:func:`run_web_node`).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :returns: 0 on a clean shutdown, 1 on a port in use or a bad parameter (one line).
    """
    from rclpy.experimental import EventsExecutor
    try:
        args = display_config_args(args)
    except ValueError as exc:
        print(f'viewer: {exc}', file=sys.stderr)
        return 1
    return run_web_node(Viewer, NODE_NAME, args, executor_class=EventsExecutor)


def display_config_args(args=None):
    """
    Return the arguments with rviz2's ``-d FILE`` / ``--display-config FILE`` as a parameter.

    ``viewer -d robot.rviz`` is ``viewer --ros-args -p rviz_config:=robot.rviz``.

    :param args: command-line arguments (default ``sys.argv``).
    :raises ValueError: ``-d`` with no file after it (the last argument, or ``--ros-args``
        next).
    """
    args = list(sys.argv if args is None else args)
    result = []
    i = 0
    while i < len(args):
        if args[i] in ('-d', '--display-config') and '--ros-args' not in args[:i]:
            if i + 1 == len(args) or args[i + 1].startswith('-'):
                raise ValueError(f'{args[i]}: expected an RViz config file after it')
            result += ['--ros-args', '-p', f'rviz_config:={os.path.abspath(args[i + 1])}']
            i += 2
            continue
        result.append(args[i])
        i += 1
    return result


if __name__ == '__main__':
    sys.exit(main())
