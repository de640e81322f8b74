# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The twist of an odometry topic, heard on a thread of its own.

Nav2's controller server and navigator keep only the latest velocity of the odometry
(``nav2_util::OdomSmoother``), which diff_drive_controller publishes 50 times a second: on an
executor that was 50 wake-ups a second of each node, 0.3-0.6 ms of CPU each in a composed
Nav2 (docs/navigation.md, "The bonds' and the odometry's threads"). A
:class:`TwistListener` takes the messages serialized on a
:class:`~amr_description.ros.take_loop.TakeLoop` and reads only their twist
(:func:`amr_description.ros.cdr.odometry_twist`).
"""

from amr_description.ros.cdr import odometry_twist
from amr_description.ros.cdr import read
from amr_description.ros.take_loop import TakeLoop
from nav_msgs.msg import Odometry
from rclpy.qos import qos_profile_sensor_data


def _twist_of(msg):
    t = msg.twist.twist
    return (t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z)


def _twist(data):
    return read(data, odometry_twist, Odometry, _twist_of)


class TwistListener:
    """
    ``handler(twist)`` with the twist of each message on ``topic``, on a thread of its own.

    :param node: the rclpy node owning the subscription (its remaps and namespace apply).
    :param topic: a nav_msgs/Odometry topic.
    :param handler: called with ``(vx, vy, vz, wx, wy, wz)`` (m/s, rad/s, in the message's
        ``child_frame_id``) on the listener's thread: it must only store what it needs.
    :param qos: the subscription's QoS (default: sensor data, as Nav2's odometry subscribers).
    """

    def __init__(self, node, topic, handler, qos=qos_profile_sensor_data):
        """Subscribe and start the thread."""
        self._loop = TakeLoop(node, f'{node.get_name()}_odometry')
        self._loop.subscribe(Odometry, topic, qos, lambda data: handler(_twist(data)))
        self._loop.start()

    def destroy(self):
        """Stop the thread and destroy the subscription."""
        self._loop.stop()
