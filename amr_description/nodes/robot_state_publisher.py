# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
robot_state_publisher: URDF + /joint_states -> /tf, /tf_static and /robot_description.

Reproduces the behaviour of upstream ``robot_state_publisher`` (ROS 2 Jazzy):

- parameters ``robot_description`` (URDF text, must not be empty), ``publish_frequency``
  (Hz, 20.0, range 0..1000; 0 publishes every message), ``ignore_timestamp`` (false),
  ``frame_prefix`` ('' , prepended verbatim to every frame id), plus the standard
  ``use_sim_time``;
- ``/robot_description`` (std_msgs/String, reliable, transient local, depth 1) so late joiners
  get the model;
- ``/tf_static`` (tf2_msgs/TFMessage, transient local, depth 1): every fixed joint, once per
  model, stamped with the node's clock;
- ``/tf`` (depth 100): for each ``/joint_states`` message (sensor-data QoS) the transform
  parent -> child of every revolute/continuous/prismatic joint it names, and of the mimic
  joints following them (``multiplier * parent + offset``), stamped with the message stamp and
  rate-limited per joint to ``publish_frequency`` (by message stamps; ``ignore_timestamp``
  turns the limit off). A message whose ``name`` and ``position`` lengths differ is rejected
  with an error; a joint missing from a message gets no transform; a stamp older than the
  last one re-publishes every joint, with upstream's warning ``Moved backwards in time,
  re-publishing joint transforms!`` at most once per :data:`BACKWARDS_WARNING_PERIOD` s (two
  interleaved sources, e.g. a bag played beside the simulator, would print it per message);
- setting ``robot_description`` at runtime re-parses the model (an invalid one is rejected and
  the old one kept) and republishes the description and the static transforms.

``/joint_states`` is taken serialized on a thread of its own
(:class:`~amr_description.ros.take_loop.TakeLoop`) and only its stamp, names and positions are
read (:func:`amr_description.ros.cdr.joint_state`): the joint_state_broadcaster sends it at the
controller manager's 100 Hz, five times the default ``publish_frequency``, and on the node's
executor each message cost a wake-up (docs/navigation.md, "The joint states' thread").

Forward kinematics: :mod:`amr_description.core.kinematics`; URDF: yourdfpy through
:mod:`amr_description.core.description.urdf_model`.
"""

import sys
import threading

from amr_description.core.description.urdf_model import parse_urdf
from amr_description.core.kinematics import joint_transform
from amr_description.core.kinematics import matrix_to_translation_quaternion
from amr_description.core.kinematics import MOVING_JOINT_TYPES
from amr_description.ros import shutdown
from amr_description.ros.cdr import joint_state
from amr_description.ros.cdr import read
from amr_description.ros.node import Node
from amr_description.ros.take_loop import TakeLoop
from builtin_interfaces.msg import Time
from geometry_msgs.msg import TransformStamped
from rcl_interfaces.msg import FloatingPointRange
from rcl_interfaces.msg import ParameterDescriptor
from rcl_interfaces.msg import SetParametersResult
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from tf2_msgs.msg import TFMessage

BACKWARDS_WARNING_PERIOD = 10.0
"""Seconds (wall) between two ``Moved backwards in time`` warnings."""

LATCHED_QOS = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                         reliability=ReliabilityPolicy.RELIABLE)
TF_QOS = QoSProfile(depth=100)


class RobotStatePublisher(Node):
    """Node ``robot_state_publisher`` (see the module docstring for its interface)."""

    def __init__(self, **kwargs):
        """
        Declare the parameters, parse the model and create publishers and subscription.

        :param kwargs: ``rclpy.node.Node`` options (``cli_args``, ``use_global_arguments``...),
            as :mod:`amr_description.nodes.component_container` passes them.
        :raises ValueError: when ``robot_description`` is empty or not a valid URDF (one line).
        """
        super().__init__('robot_state_publisher', **kwargs)
        self.declare_parameter('robot_description', '', ParameterDescriptor(
            description='The original description of the robot'))
        self.declare_parameter('publish_frequency', 20.0, ParameterDescriptor(
            description='Maximum frequency (Hz) of /tf per joint',
            floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1000.0)]))
        self.declare_parameter('ignore_timestamp', False)
        self.declare_parameter('frame_prefix', '')
        self._model = None
        self._lock = threading.Lock()  # the joint states' thread and parameter changes
        self._last_publish = {}  # joint name -> last published stamp (ns)
        self._last_callback_ns = 0
        self._description = self.get_parameter('robot_description').value
        if not self._description:
            raise ValueError('robot_description parameter must not be empty')
        self._model = parse_urdf(self._description, source='robot_description')
        self._description_pub = self.create_publisher(String, 'robot_description', LATCHED_QOS)
        self._static_pub = self.create_publisher(TFMessage, '/tf_static', LATCHED_QOS)
        self._tf_pub = self.create_publisher(TFMessage, '/tf', TF_QOS)
        self.add_on_set_parameters_callback(self._validate_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)
        self._publish_model()
        self._joint_states = TakeLoop(self, f'{self.get_name()}_joint_states')
        self._joint_states.subscribe(JointState, 'joint_states', qos_profile_sensor_data,
                                     self._on_joint_state_data)
        self._joint_states.start()

    # -- model --------------------------------------------------------------------------------

    def _publish_model(self):
        """Log the segments, publish /robot_description and the fixed joints on /tf_static."""
        for joint in self._model.joints.values():
            self.get_logger().info(f'got segment {joint.child}')
        self._description_pub.publish(String(data=self._description))
        stamp = self.get_clock().now().to_msg()
        transforms = [self._transform(joint, 0.0, stamp) for joint in self._model.fixed_joints()]
        self._static_pub.publish(TFMessage(transforms=transforms))

    def _validate_parameters(self, parameters):
        """Reject an empty or unparsable ``robot_description`` (the old model stays)."""
        for parameter in parameters:
            if parameter.name == 'robot_description':
                if not parameter.value:
                    return SetParametersResult(
                        successful=False, reason='robot_description must not be empty')
                try:
                    parse_urdf(parameter.value, source='robot_description')
                except ValueError as exc:
                    return SetParametersResult(successful=False, reason=str(exc))
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters):
        """Re-read the model after ``robot_description`` changed."""
        for parameter in parameters:
            if parameter.name == 'robot_description':
                with self._lock:
                    self._description = parameter.value
                    self._model = parse_urdf(self._description, source='robot_description')
                    self._last_publish.clear()
                    self._publish_model()

    # -- transforms ---------------------------------------------------------------------------

    def _transform(self, joint, position, stamp):
        """Return the TransformStamped parent -> child of ``joint`` at ``position``."""
        prefix = self.get_parameter('frame_prefix').value
        xyz, quat = matrix_to_translation_quaternion(
            joint_transform(joint.origin, joint.type, joint.axis, position))
        msg = TransformStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = prefix + joint.parent
        msg.child_frame_id = prefix + joint.child
        t = msg.transform.translation
        t.x, t.y, t.z = (float(v) for v in xyz)
        r = msg.transform.rotation
        r.x, r.y, r.z, r.w = (float(v) for v in quat)
        return msg

    def _on_joint_state_data(self, data):
        """Read a serialized ``/joint_states`` message and publish its transforms."""
        stamp, names, positions = read(data, joint_state, JointState, _joint_values)
        with self._lock:
            self._on_joint_values(stamp, names, positions)

    def _on_joint_values(self, stamp, names, positions):
        """
        Publish /tf for the moving joints of one message (upstream rules, module doc).

        :param stamp: ``header.stamp`` as ``(sec, nanosec)``.
        :param names: the joints' names.
        :param positions: their positions (rad or m), as many as ``names`` or it is refused.
        """
        if len(names) != len(positions):
            self.get_logger().error(
                f'Ignored an invalid JointState message on {self._joint_states_topic()}: '
                f'{len(names)} names but {len(positions)} positions')
            return
        stamp_ns = stamp[0] * 1_000_000_000 + stamp[1]
        if stamp_ns < self._last_callback_ns:
            self.get_logger().warning('Moved backwards in time, re-publishing joint transforms!',
                                      throttle_duration_sec=BACKWARDS_WARNING_PERIOD)
            self._last_publish.clear()
        self._last_callback_ns = stamp_ns
        frequency = self.get_parameter('publish_frequency').value
        ignore_timestamp = self.get_parameter('ignore_timestamp').value
        interval_ns = int(1e9 / frequency) if frequency > 0.0 else 0
        model = self._model
        moving = {}
        for name, position in zip(names, positions):
            joint = model.joints.get(name)
            if joint is not None and joint.type in MOVING_JOINT_TYPES:
                moving[name] = float(position)
        if not moving:
            return
        last = min(self._last_publish.get(name, -1) for name in moving)
        if not ignore_timestamp and last >= 0 and stamp_ns < last + interval_ns:
            return
        resolved = model.resolve_mimic(moving)
        stamp = Time(sec=stamp[0], nanosec=stamp[1])
        transforms = []
        for name, position in resolved.items():
            joint = model.joints[name]
            if joint.type in MOVING_JOINT_TYPES:
                transforms.append(self._transform(joint, position, stamp))
        for name in moving:
            self._last_publish[name] = stamp_ns
        self._tf_pub.publish(TFMessage(transforms=transforms))

    def _joint_states_topic(self):
        """Return the resolved name of the joint states topic (for messages)."""
        return self.resolve_topic_name('joint_states')


def _joint_values(msg):
    """Return a JointState's ``((sec, nanosec), names, positions)``, as ``cdr.joint_state``."""
    return (msg.header.stamp.sec, msg.header.stamp.nanosec), list(msg.name), tuple(msg.position)


def main(args=None):
    """
    Run :class:`RobotStatePublisher` until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :returns: 0 on a clean shutdown.
    :raises SystemExit: code 1 after one error line when the ROS arguments cannot be parsed,
        ``robot_description`` is empty or refused by the URDF loader, or a parameter has the
        wrong type or is out of range (:mod:`amr_description.ros.shutdown`).
    """
    node = None
    try:
        shutdown.init(args)
        node = shutdown.create(RobotStatePublisher)
        shutdown.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.shutdown(node)
    return 0


if __name__ == '__main__':
    sys.exit(main())
