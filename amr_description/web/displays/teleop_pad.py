# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Teleop pad (no RViz peer): drive the robot from the page.

Hold a button, or a key while the page has focus (arrows or ``I J L`` and ``K`` to stop; ``,``
is not available to page hotkeys), to publish ``geometry_msgs/TwistStamped`` on
``cmd_vel_topic`` at :data:`RATE` Hz, stamped with the node clock (``use_sim_time`` aware),
``header.frame_id`` = ``frame_id``; one zero twist on release. Dead-man
(:mod:`amr_description.core.teleop_pad`): a control that the page stops refreshing (released,
page closed, focus lost, connection dropped) is released within :data:`BUTTON_HOLD` s
(buttons) or :data:`KEY_HOLD` s (keys, which repeat only after the keyboard's auto-repeat
delay). Speed (m/s) and turn rate (rad/s) are set on the page. The pad is shown only while
something subscribes to ``cmd_vel_topic`` (a controller or a simulated robot that would move;
the display stack has none), checked every :data:`VISIBILITY_PERIOD` s.

``cmd_vel_topic`` '' (the default) finds the topic in the graph: the first topic named
``.../cmd_vel`` of type ``geometry_msgs/TwistStamped`` or ``Twist`` that something
subscribes to, a controller's (``/diff_drive_controller/cmd_vel``,
``/diff_drive_base_controller/cmd_vel`` of gz_ros2_control_demos, ``/r1/...`` in a fleet)
before a bare ``/cmd_vel`` (gz-sim's DiffDrive), stamped before unstamped, then by name; the
pad then publishes that topic's type (a ``Twist`` has no header).
"""

import threading
import time

from amr_description.core import teleop_pad
from amr_description.core.message_yaml.utilities import get_message
from amr_description.web.displays.base import Display
from amr_description.web.displays.discovery import choose_cmd_vel
from geometry_msgs.msg import Twist
from geometry_msgs.msg import TwistStamped
from rclpy.clock import Clock
from rclpy.clock import ClockType

RATE = 20.0
"""Hz of the commands while a control is held."""
BUTTON_HOLD = 0.25
"""Seconds a button press lasts unless the page refreshes it."""
VISIBILITY_PERIOD = 1.0
"""Seconds (wall) between two looks at the subscribers of ``cmd_vel_topic``."""
KEY_HOLD = 0.6
"""Seconds a key press lasts unless the page refreshes it."""


class TeleopPadDisplay(Display):
    """
    The pad: a ``Teleop`` folder with sliders and buttons, and hotkeys.

    :param cmd_vel_topic: where the commands go.
    :param frame_id: their ``header.frame_id``.
    :param speed: initial speed, m/s.
    :param turn: initial turn rate, rad/s.
    """

    order = 90
    parameters = (('cmd_vel_topic', ''), ('frame_id', 'base_link'),
                  ('speed', 0.5), ('turn', 1.0))

    @classmethod
    def create(cls, viewer, settings):
        """Make the pad of the viewer's ``cmd_vel_topic``, ``frame_id``, ``speed``, ``turn``."""
        return cls(viewer, viewer.server, viewer.frames, str(settings['cmd_vel_topic']),
                   str(settings['frame_id']), float(settings['speed']),
                   float(settings['turn']))

    def __init__(self, node, server, frames, cmd_vel_topic, frame_id, speed, turn):
        """Create the publisher (the :data:`RATE` Hz timer starts with the page)."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        self._deadman = teleop_pad.DeadMan(BUTTON_HOLD)
        self._frame_id = frame_id
        self._initial = (speed, turn)
        self._publisher = None
        self.topic = None
        if cmd_vel_topic:
            self._publish_on(cmd_vel_topic, TwistStamped)

    def _publish_on(self, topic, msg_class):
        self.topic, self._type = topic, msg_class
        self._publisher = self.node.create_publisher(msg_class, topic, 10)

    def discover(self, graph):
        """Without a ``cmd_vel_topic``, take the one found in ``graph`` (module docstring)."""
        if self._publisher is not None:
            return
        chosen = choose_cmd_vel(graph, self.node.count_subscribers)
        if chosen is not None:
            topic, kind = chosen
            self._publish_on(topic, get_message(kind))
            self.node.get_logger().info(f'teleop pad: publishing {kind} on {topic}')

    def build_footer(self, gui):
        """Add the ``Teleop`` folder and the hotkeys; a disconnected page releases all."""
        self._folder = gui.add_folder('Teleop', visible=self._heard())
        self._next_look = time.monotonic() + VISIBILITY_PERIOD
        with self._folder:
            self._speed = gui.add_slider('speed (m/s)', min=0.0, max=2.0, step=0.01,
                                         initial_value=self._initial[0])
            self._turn = gui.add_slider('turn (rad/s)', min=0.0, max=4.0, step=0.01,
                                        initial_value=self._initial[1])
            for label, control in (('Forward', 'forward'), ('Left', 'left'),
                                   ('Right', 'right'), ('Back', 'back')):
                button = gui.add_button(label)
                button.on_hold(self._callback(control, BUTTON_HOLD), callback_hz=RATE)
            stop = gui.add_button('Stop')
            stop.on_click(self._callback('stop', BUTTON_HOLD))
            gui.add_markdown('Hold a button, or a key while the page has focus: arrows or '
                             '**I** forward, **J** / **L** turn, **K** stop.')
        for key, control in teleop_pad.KEYS.items():
            hotkey = key.lower() if key.startswith('Arrow') else key.upper()
            if hotkey == ',':
                continue  # not a key viser's hotkeys accept
            command = gui.add_command(f'teleop {control}', hotkey=hotkey)
            command.on_trigger(self._callback(control, KEY_HOLD))
        self.server.on_client_disconnect(lambda _: self._release_all())
        self.node.create_timer(1.0 / RATE, self._tick,
                               clock=Clock(clock_type=ClockType.STEADY_TIME))

    def _heard(self):
        return self._publisher is not None and self._publisher.get_subscription_count() > 0

    def draw(self, context):
        """Show the pad while ``cmd_vel_topic`` has a subscriber, hide it otherwise."""
        now = time.monotonic()
        if now < self._next_look:
            return
        self._next_look = now + VISIBILITY_PERIOD
        heard = self._heard()
        if self._folder.visible != heard:
            self._folder.visible = heard

    def _callback(self, control, hold):
        def press(_):
            with self._lock:
                self._deadman.press(control, time.monotonic(), hold)
        return press

    def _release_all(self):
        with self._lock:
            self._deadman.release_all()

    def _tick(self):
        with self._lock:
            command = self._deadman.command(time.monotonic(), self._speed.value,
                                            self._turn.value)
        if command is None or self._publisher is None:
            return
        if self._type is Twist:
            msg = twist = Twist()
        else:
            msg = TwistStamped()
            msg.header.stamp = self.node.get_clock().now().to_msg()
            msg.header.frame_id = self._frame_id
            twist = msg.twist
        twist.linear.x, twist.angular.z = command
        self._publisher.publish(msg)
