# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Minimal publisher of the ROS 2 "writing a simple publisher and subscriber" tutorial.

Publishes ``std_msgs/msg/String`` ``'Hello World: N'`` (N from 0) on ``topic`` every 0.5 s
and logs ``Publishing: "Hello World: N"``, like the tutorial's ``minimal_publisher``.
"""

from amr_description.ros import shutdown
from amr_description.ros.node import Node
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
    node = None
    try:
        shutdown.init(args)
        node = shutdown.create(MinimalPublisher)
        shutdown.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)


if __name__ == '__main__':
    main()
