# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Minimal publisher of the ROS 2 "writing a simple publisher and subscriber" tutorial.

Publishes ``std_msgs/msg/String`` ``'Hello World: N'`` (N from 0) on ``topic`` every 0.5 s
and logs ``Publishing: "Hello World: N"``, like the tutorial's ``minimal_publisher``.
"""

import rclpy
from rclpy._rclpy_pybind11 import RCLError
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String

TIMER_PERIOD = 0.5  # seconds


class MinimalPublisher(Node):
    """Node ``minimal_publisher``: a counter message on ``topic`` every :data:`TIMER_PERIOD` s."""

    def __init__(self):
        """Create the publisher (depth 10, as the tutorial) and the timer."""
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.timer = self.create_timer(TIMER_PERIOD, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        """Publish ``Hello World: i``, log it and increment the counter."""
        msg = String()
        msg.data = f'Hello World: {self.i}'
        self.publisher_.publish(msg)
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.i += 1


def main(args=None):
    """
    Spin :class:`MinimalPublisher` until Ctrl-C (exit code 0, no traceback).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    rclpy.init(args=args)
    node = MinimalPublisher()
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
