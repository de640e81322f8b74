# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
joint_state_publisher (no GUI): sensor_msgs/JointState of every movable joint at ``rate``.

Follows upstream ``joint_state_publisher`` (ROS 2):

- the model comes from the ``robot_description`` parameter when set, else from the
  ``/robot_description`` topic (std_msgs/String, transient local), re-read when it changes;
- it publishes ``/joint_states`` at ``rate`` Hz (10) with every revolute, continuous and
  prismatic joint that is not a mimic joint, in URDF order, stamped with the node clock;
- positions start at ``zeros`` (dict joint -> value, default 0; clamped into joint limits like
  upstream: 0 when inside the limits, else the limit nearest 0) and are overridden by the
  latest message on any ``source_list`` topic (positions, velocities, efforts merged by name).
"""

import sys

from amr_description.core.description.urdf_model import parse_urdf
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from rcl_interfaces.msg import ParameterDescriptor
from rcl_interfaces.msg import ParameterType
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from sensor_msgs.msg import JointState
from std_msgs.msg import String


class JointStatePublisher(Node):
    """Node ``joint_state_publisher`` (see the module docstring)."""

    def __init__(self, node_name='joint_state_publisher'):
        """
        Declare parameters, subscribe to the sources and the description, start the timer.

        :param node_name: the node name (``joint_state_publisher_gui`` extends this node).
        """
        super().__init__(node_name)
        self.declare_parameter('robot_description', '')
        self.declare_parameter('rate', 10.0)
        self.declare_parameter('source_list', [''], ParameterDescriptor(
            type=ParameterType.PARAMETER_STRING_ARRAY))
        self._joints = []
        self._zeros = self._read_zeros()
        self._positions = {}
        self._velocities = {}
        self._efforts = {}
        description = self.get_parameter('robot_description').value
        if description:
            self._set_model(description)
        else:
            latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
            self.create_subscription(String, 'robot_description',
                                     lambda msg: self._set_model(msg.data), latched)
        for topic in self.get_parameter('source_list').value:
            if topic:
                self.create_subscription(JointState, topic, self._on_source, 10)
        self._pub = self.create_publisher(JointState, 'joint_states', 10)
        rate = float(self.get_parameter('rate').value)
        if rate <= 0.0:
            raise ValueError(f'rate must be > 0 Hz, found {rate}')
        self.create_timer(1.0 / rate, self._publish)

    def _read_zeros(self):
        """Return the ``zeros.<joint>`` parameters (given as a dict in a params file)."""
        zeros = {}
        for name, parameter in self.get_parameters_by_prefix('zeros').items():
            zeros[name] = float(parameter.value)
        return zeros

    def _set_model(self, description):
        """Parse the URDF and reset the joint list; a bad model is logged and ignored."""
        try:
            model = parse_urdf(description, source='robot_description')
        except ValueError as exc:
            self.get_logger().error(str(exc))
            return
        self._joints = []
        self._positions = {}
        for joint in model.moving_joints():
            if joint.mimic is not None:
                continue
            self._joints.append(joint.name)
            self._positions[joint.name] = self._initial(joint)
        self.get_logger().info(f'publishing {len(self._joints)} joints')

    def _initial(self, joint):
        """Return the start position: ``zeros`` value or 0, clamped into the joint limits."""
        if joint.name in self._zeros:
            return self._zeros[joint.name]
        limit = joint.limit
        if joint.type == 'continuous' or limit is None or limit.lower is None:
            return 0.0
        if limit.lower > 0.0 or limit.upper < 0.0:
            return limit.lower if abs(limit.lower) < abs(limit.upper) else limit.upper
        return 0.0

    def _on_source(self, msg):
        """Merge a source JointState by name (lengths that do not match are skipped)."""
        for values, store in ((msg.position, self._positions), (msg.velocity, self._velocities),
                              (msg.effort, self._efforts)):
            if len(values) == len(msg.name):
                for name, value in zip(msg.name, values):
                    if name in self._positions:
                        store[name] = float(value)

    def _publish(self):
        """Publish the current joint states (nothing before a model arrived)."""
        if not self._joints:
            return
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = list(self._joints)
        msg.position = [self._positions[n] for n in self._joints]
        if self._velocities:
            msg.velocity = [self._velocities.get(n, 0.0) for n in self._joints]
        if self._efforts:
            msg.effort = [self._efforts.get(n, 0.0) for n in self._joints]
        self._pub.publish(msg)


def main(args=None):
    """
    Run :class:`JointStatePublisher` until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :returns: 0 on a clean shutdown.
    :raises SystemExit: code 1 after one error line on bad ROS arguments or a bad parameter
        (:mod:`amr_description.ros.shutdown`).
    """
    node = None
    try:
        shutdown.init(args)
        node = shutdown.create(JointStatePublisher)
        shutdown.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)
    return 0


if __name__ == '__main__':
    sys.exit(main())
