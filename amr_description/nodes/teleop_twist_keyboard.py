# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Keyboard teleoperation: keys in the terminal -> velocity commands on ``cmd_vel``.

Behaves as the upstream ROS 2 ``teleop_twist_keyboard`` (jazzy): parameters ``stamped``
(false: ``geometry_msgs/Twist``; true: ``geometry_msgs/TwistStamped`` stamped with the node's
clock), ``frame_id`` ('' -- only allowed with ``stamped``), ``speed`` (0.5 m/s) and ``turn``
(1.0 rad/s); one message per key press; a zero twist and the terminal restored on exit (the
zero waits up to 2 s for reliable subscriptions to acknowledge it, so that it is not lost with
the process's writer). The key map is in :mod:`amr_description.core.teleop_keys`.

Added: ``key_timeout`` (seconds, 0 = off, default 0): when no key arrives for that long after a
key press, one zero twist is published (a dead-man stop).

Usage with the simulated robot::

    ros2 run amr_description teleop_twist_keyboard --ros-args -p stamped:=true
        -r /cmd_vel:=/diff_drive_controller/cmd_vel   (on one line)
"""

import os
import select
import sys
import termios
import threading
import tty

from amr_description.core.teleop_keys import apply_key
from amr_description.core.teleop_keys import BANNER
from amr_description.core.teleop_keys import check_parameters
from amr_description.core.teleop_keys import format_speeds
from amr_description.core.teleop_keys import stop
from amr_description.core.teleop_keys import TeleopState
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from geometry_msgs.msg import Twist
from geometry_msgs.msg import TwistStamped
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor

STOP_ACK_TIMEOUT = 2.0
"""Seconds the zero twist sent on exit may wait for reliable subscriptions' acknowledgement."""


class TeleopTwistKeyboard(Node):
    """
    Node ``teleop_twist_keyboard`` publishing Twist or TwistStamped on ``cmd_vel``.

    :raises ValueError: on invalid parameters (one-line message naming the parameter).
    """

    def __init__(self):
        """Declare the parameters, validate them and create the publisher."""
        super().__init__('teleop_twist_keyboard')
        number = ParameterDescriptor(dynamic_typing=True)
        self.stamped = bool(self.declare_parameter('stamped', False).value)
        self.frame_id = str(self.declare_parameter('frame_id', '').value)
        speed = self.declare_parameter('speed', 0.5, number).value
        turn = self.declare_parameter('turn', 1.0, number).value
        key_timeout = self.declare_parameter('key_timeout', 0.0, number).value
        check_parameters(self.stamped, self.frame_id, speed, turn, key_timeout)
        self.speed = float(speed)
        self.turn = float(turn)
        self.key_timeout = float(key_timeout)
        msg_type = TwistStamped if self.stamped else Twist
        self.publisher = self.create_publisher(msg_type, 'cmd_vel', 10)

    def publish_twist(self, linear_x, linear_y, linear_z, angular_z):
        """
        Publish one command.

        :param linear_x: m/s, forward.
        :param linear_y: m/s, left.
        :param linear_z: m/s, up.
        :param angular_z: rad/s, counter-clockwise.
        """
        if self.stamped:
            msg = TwistStamped()
            msg.header.stamp = self.get_clock().now().to_msg()
            msg.header.frame_id = self.frame_id
            twist = msg.twist
        else:
            msg = Twist()
            twist = msg
        twist.linear.x = float(linear_x)
        twist.linear.y = float(linear_y)
        twist.linear.z = float(linear_z)
        twist.angular.z = float(angular_z)
        self.publisher.publish(msg)


def read_key(fd, settings, timeout):
    """
    Read one key from terminal ``fd`` in raw mode, restoring ``settings`` afterwards.

    :param fd: file descriptor of the terminal.
    :param settings: termios attributes to restore.
    :param timeout: seconds to wait, or None to wait forever.
    :returns: the key (one character), ``''`` on timeout, None at end of input.
    """
    tty.setraw(fd, termios.TCSANOW)  # TCSAFLUSH would drop keys typed ahead
    try:
        ready, _, _ = select.select([fd], [], [], timeout)
        if not ready:
            return ''
        data = os.read(fd, 1)
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, settings)
    if not data:
        return None
    return data.decode('latin-1')


def _loop(node, fd, settings):
    state = TeleopState(speed=node.speed, turn=node.turn)
    print(BANNER)
    print(format_speeds(state.speed, state.turn))
    waiting = False  # a key was pressed and the key timeout is counting
    while True:
        timeout = node.key_timeout if (waiting and node.key_timeout > 0) else None
        key = read_key(fd, settings, timeout)
        if key is None:
            return
        if key == '':
            stop(state)
            node.publish_twist(*state.twist())
            waiting = False
            continue
        result = apply_key(state, key)
        for message in result.messages:
            print(message)
        if result.finished:
            return
        node.publish_twist(*state.twist())
        waiting = True


def main(args=None):
    """
    Run the keyboard teleop until Ctrl-C; publish a zero twist and restore the terminal.

    The clean-shutdown pattern of :mod:`amr_description.ros.shutdown`: the executor spins
    in a thread, keys are read in the main thread, where SIGINT/SIGTERM raise
    KeyboardInterrupt.

    :param args: ROS command-line arguments (default ``sys.argv``).
    :returns: exit code: 0, or 1 when stdin is not a terminal.
    :raises SystemExit: code 1 after one error line on bad ROS arguments or an invalid
        parameter.
    """
    if not sys.stdin.isatty():
        print('teleop_twist_keyboard: stdin is not a terminal; run it in an interactive '
              'terminal (it reads single key presses)', file=sys.stderr)
        return 1
    fd = sys.stdin.fileno()
    settings = termios.tcgetattr(fd)
    node = executor = spinner = None
    try:
        shutdown.init(args)
        node = shutdown.create(TeleopTwistKeyboard)
        executor = SingleThreadedExecutor()
        executor.add_node(node)
        spinner = threading.Thread(target=executor.spin, daemon=True)
        spinner.start()
        _loop(node, fd, settings)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.ignore_signals()
        if node is not None:
            try:
                node.publish_twist(0.0, 0.0, 0.0, 0.0)
                # the stop must reach the robot: wait (briefly) until every reliable
                # subscription acknowledged it, or it may die with this process's writer
                node.publisher.wait_for_all_acked(Duration(seconds=STOP_ACK_TIMEOUT))
            except Exception:  # noqa: B902 - the context may already be gone
                pass
        termios.tcsetattr(fd, termios.TCSADRAIN, settings)
        if executor is not None:
            executor.shutdown(timeout_sec=1.0)
            spinner.join(2.0)
        shutdown.shutdown(node)
    return 0


if __name__ == '__main__':
    sys.exit(main())
