# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The benchmark's observer: a node in its own context sampling /clock and driving."""

import time

from amr_description.tools.benchmark.common import CMD_LEAD
from amr_description.tools.benchmark.common import sample_clock
from amr_description.tools.benchmark.common import TURN_TWIST


class Observer:
    """A node in its own context: samples /clock and publishes every robot's cmd_vel."""

    def __init__(self, domain_id, robot_namespaces, listen=()):
        """
        Create the node, one cmd_vel publisher per robot and the subscriptions of ``listen``.

        :param domain_id: ROS domain of the stack.
        :param robot_namespaces: list of namespaces ('' for the robot without one).
        :param listen: ``(topic, message class)`` pairs to subscribe to (reliable, depth 10),
            or ``(topic, message class, QoS profile)``, so that the stack publishes them as to
            any listener; DDS delivers them into the subscriptions' queues, which the
            observer does not take (its CPU stays out of the figures as much as a
            listener's can).
        """
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from geometry_msgs.msg import TwistStamped

        self.rclpy = rclpy
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('benchmark_observer', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.publishers = [self.node.create_publisher(
            TwistStamped, (f'/{ns}' if ns else '') + '/diff_drive_controller/cmd_vel', 10)
            for ns in robot_namespaces]
        self.twist = TwistStamped()
        self.twist.header.frame_id = 'base_link'
        self.twist.twist.linear.x, self.twist.twist.angular.z = TURN_TWIST
        self.subscriptions = [self.node.create_subscription(
            item[1], item[0], lambda msg: None, item[2] if len(item) > 2 else 10)
            for item in listen]

    def clock_sample(self, timeout=10.0):
        """Return ``(wall, sim)`` of one /clock message, or None (:func:`sample_clock`)."""
        return sample_clock(self.node, self.executor, timeout)

    def drive(self, sim_now):
        """Publish every robot's command, stamped :data:`CMD_LEAD` after ``sim_now`` (s)."""
        stamp = sim_now + CMD_LEAD
        self.twist.header.stamp.sec = int(stamp)
        self.twist.header.stamp.nanosec = int((stamp - int(stamp)) * 1e9)
        for publisher in self.publishers:
            publisher.publish(self.twist)

    def wait(self, seconds, sim_now):
        """Wait ``seconds`` wall seconds, re-publishing the commands every 0.5 s."""
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.drive(sim_now)
            time.sleep(max(0.0, min(0.5, end - time.monotonic())))

    def close(self):
        """Destroy the node and shut the context down."""
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)
