# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Minimal subscriber of the ROS 2 "writing a simple publisher and subscriber" tutorial.

Subscribes to ``std_msgs/msg/String`` on ``topic`` and logs ``I heard: "<data>"``, like the
tutorial's ``minimal_subscriber``.
"""

import rclpy
from rclpy._rclpy_pybind11 import RCLError
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String


class MinimalSubscriber(Node):
    """Node ``minimal_subscriber``: logs every ``String`` received on ``topic``."""

    def __init__(self):
        """Create the subscription (depth 10, as the tutorial)."""
        super().__init__('minimal_subscriber')
        self.subscription = self.create_subscription(
            String, 'topic', self.listener_callback, 10)

    def listener_callback(self, msg):
        """
        Log the received text.

        :param msg: the received ``std_msgs/msg/String``.
        """
        self.get_logger().info(f'I heard: "{msg.data}"')


def main(args=None):
    """
    Spin :class:`MinimalSubscriber` until Ctrl-C (exit code 0, no traceback).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    rclpy.init(args=args)
    node = MinimalSubscriber()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except RCLError:
        # Ctrl-C can shut the context down while the executor builds its wait set (an
        # rclpy race); that is a normal shutdown, anything else is a real error
        if rclpy.ok():
            raise
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
