# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Velocity commands as Nav2's nodes send and take them (``nav2_util`` TwistPublisher/Subscriber).

``enable_stamped_cmd_vel`` false (Jazzy's default): geometry_msgs/Twist; true:
geometry_msgs/TwistStamped on the same topic, stamped now in the robot base frame. Publishers
are reliable with depth 1, as Nav2's.
"""

import math

from geometry_msgs.msg import Twist
from geometry_msgs.msg import TwistStamped


class TwistPublisher:
    """
    Publish ``(vx, vy, wz)`` commands as Twist or TwistStamped.

    :param node: the rclpy node.
    :param topic: e.g. ``cmd_vel``.
    :param stamped: the node's ``enable_stamped_cmd_vel``.
    :param frame: the header's frame (the robot base frame) when stamped.
    """

    def __init__(self, node, topic, stamped, frame='base_link'):
        """Create the publisher."""
        self.node = node
        self.stamped = bool(stamped)
        self.frame = frame
        self.pub = node.create_publisher(TwistStamped if self.stamped else Twist, topic, 1)

    def publish(self, vx, wz, vy=0.0, stamp=None):
        """Publish one command (m/s, rad/s); ``stamp`` defaults to the node's clock now."""
        if self.stamped:
            msg = TwistStamped()
            msg.header.stamp = stamp or self.node.get_clock().now().to_msg()
            msg.header.frame_id = self.frame
            twist = msg.twist
        else:
            msg = twist = Twist()
        twist.linear.x, twist.linear.y, twist.angular.z = float(vx), float(vy), float(wz)
        self.pub.publish(msg)

    def destroy(self):
        """Destroy the publisher."""
        self.node.destroy_publisher(self.pub)


def subscribe_twist(node, topic, stamped, callback, qos=1):
    """
    Subscribe to Twist or TwistStamped; ``callback(vx, vy, wz)`` gets finite values only.

    A command with a NaN or infinite value is dropped with a throttled warning.
    """
    def take(msg):
        t = msg.twist if stamped else msg
        values = (t.linear.x, t.linear.y, t.angular.z)
        if not all(math.isfinite(v) for v in values):
            node.get_logger().warning(f'{topic}: command with a NaN or infinite value dropped',
                                      throttle_duration_sec=5.0)
            return
        callback(*values)

    return node.create_subscription(TwistStamped if stamped else Twist, topic, take, qos)
