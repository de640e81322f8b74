# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Minimal subscriber of the ROS 2 "writing a simple publisher and subscriber" tutorial.

Subscribes to ``std_msgs/msg/String`` on ``topic`` and logs ``I heard: "<data>"``, like the
tutorial's ``minimal_subscriber``.
"""

from amr_description.ros import shutdown
from amr_description.ros.node import Node
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
    node = None
    try:
        shutdown.init(args)
        node = shutdown.create(MinimalSubscriber)
        shutdown.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)


if __name__ == '__main__':
    main()
