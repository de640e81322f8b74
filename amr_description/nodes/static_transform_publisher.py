# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
static_transform_publisher: one fixed transform on ``/tf_static`` (tf2_ros' tool).

``ros2 run amr_description static_transform_publisher --x 2 --y 0 --yaw 0 --frame-id world
--child-frame-id r1/odom`` publishes ``world -> r1/odom`` once, as tf2_ros' program of the same
name does (ROS 2 Jazzy): command line in :mod:`amr_description.core.static_transform_args`
(``-h`` for the usage); a command line it refuses is upstream's error line,
``error parsing command line arguments: REASON``, then the usage, exit code 1. The node is
named ``static_transform_publisher_`` plus 16 random letters and digits (upstream's way to let
several run at once) unless renamed with ``--ros-args -r __node:=NAME``; it logs the transform
it publishes and spins until stopped.

The node, :class:`StaticTransformBroadcasterNode`, is also a composable node
(``amr_description::StaticTransformBroadcasterNode``, as ``tf2_ros::
StaticTransformBroadcasterNode``): read-only parameters ``translation.x/y/z`` (m, 0),
``rotation.x/y/z/w`` (quaternion, identity), ``frame_id`` (``/frame``) and ``child_frame_id``
(``/child``); a frame equal to its child is refused with upstream's message. The message goes
out once, stamped with the node's clock, on ``/tf_static`` (tf2_msgs/TFMessage, reliable,
transient local, depth 1: late subscribers get it).
"""

import random
import string
import sys

from amr_description.core import static_transform_args
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from geometry_msgs.msg import TransformStamped
from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from tf2_msgs.msg import TFMessage

STATIC_QOS = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                        reliability=ReliabilityPolicy.RELIABLE)
"""tf2_ros' ``StaticBroadcasterQoS``."""


def unique_node_name():
    """Return ``static_transform_publisher_`` plus 16 random letters and digits (upstream's)."""
    chars = string.digits + string.ascii_lowercase + string.ascii_uppercase
    return 'static_transform_publisher_' + ''.join(random.choice(chars) for _ in range(16))


class StaticTransformBroadcasterNode(Node):
    """Publish the transform given by its parameters on ``/tf_static`` (module docstring)."""

    def __init__(self, **kwargs):
        """
        Declare the parameters and publish the transform.

        :param kwargs: ``rclpy.node.Node`` options (``parameter_overrides``, ``cli_args``...).
        :raises ValueError: when ``frame_id`` equals ``child_frame_id`` (upstream's message).
        """
        super().__init__(unique_node_name(), **kwargs)
        fixed = ParameterDescriptor(read_only=True)
        msg = TransformStamped()
        msg.header.stamp = self.get_clock().now().to_msg()
        t, r = msg.transform.translation, msg.transform.rotation
        t.x = self.declare_parameter('translation.x', 0.0, fixed).value
        t.y = self.declare_parameter('translation.y', 0.0, fixed).value
        t.z = self.declare_parameter('translation.z', 0.0, fixed).value
        r.x = self.declare_parameter('rotation.x', 0.0, fixed).value
        r.y = self.declare_parameter('rotation.y', 0.0, fixed).value
        r.z = self.declare_parameter('rotation.z', 0.0, fixed).value
        r.w = self.declare_parameter('rotation.w', 1.0, fixed).value
        msg.header.frame_id = self.declare_parameter('frame_id', '/frame', fixed).value
        msg.child_frame_id = self.declare_parameter('child_frame_id', '/child', fixed).value
        if msg.header.frame_id == msg.child_frame_id:
            raise ValueError(f"cannot publish static transform from '{msg.header.frame_id}' "
                             f"to '{msg.child_frame_id}', exiting")
        self.transform = msg
        self._publisher = self.create_publisher(TFMessage, '/tf_static', STATIC_QOS)
        self._publisher.publish(TFMessage(transforms=[msg]))


def main(args=None):
    """
    Parse the command line, publish the transform and spin until Ctrl-C.

    :param args: command line, program name first (default ``sys.argv``).
    :returns: 0 on a clean shutdown or after ``--help``; 1 (after upstream's error line and the
        usage) when the command line is refused.
    :raises SystemExit: code 1 after one error line when the ROS arguments cannot be parsed.
    """
    argv = sys.argv if args is None else list(args)
    node = None
    try:
        shutdown.init(argv)
        try:
            parsed = static_transform_args.parse(shutdown.remove_ros_args(argv)[1:])
        except ValueError as exc:
            rclpy.logging.get_logger('static_transform_publisher').error(
                f'error parsing command line arguments: {exc}')
            print(static_transform_args.USAGE, flush=True)
            return 1
        if parsed.help:
            print(static_transform_args.USAGE, flush=True)
            return 0
        logger = rclpy.logging.get_logger('static_transform_publisher')
        for warning in parsed.warnings:
            logger.warning(warning)
        names = ('translation.x', 'translation.y', 'translation.z',
                 'rotation.x', 'rotation.y', 'rotation.z', 'rotation.w')
        values = list(parsed.translation) + list(parsed.rotation)
        overrides = [rclpy.parameter.Parameter(n, value=float(v)) for n, v in zip(names, values)]
        overrides += [rclpy.parameter.Parameter('frame_id', value=parsed.frame_id),
                      rclpy.parameter.Parameter('child_frame_id', value=parsed.child_frame_id)]
        node = shutdown.create(StaticTransformBroadcasterNode, parameter_overrides=overrides)
        x, y, z = parsed.translation
        qx, qy, qz, qw = parsed.rotation
        node.get_logger().info(
            f"Spinning until stopped - publishing transform\ntranslation: ('{x:f}', '{y:f}', "
            f"'{z:f}')\nrotation: ('{qx:f}', '{qy:f}', '{qz:f}', '{qw:f}')\nfrom "
            f"'{parsed.frame_id}' to '{parsed.child_frame_id}'")
        shutdown.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)
    return 0


if __name__ == '__main__':
    sys.exit(main())
