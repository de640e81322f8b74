# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
joint_state_broadcaster: publishes ``sensor_msgs/JointState`` from state interfaces.

As ros2_controllers' joint_state_broadcaster (jazzy): on every controller-manager update
(not rate-limited) it publishes ``joint_states`` in its namespace (``/joint_states`` for
the controller without one; ``~/joint_states`` with
``use_local_topics``), stamped with the update time, one entry per joint in URDF order
(joints absent from the URDF follow, in interface order, unless ``use_urdf_to_filter``
removes them), with ``position``/``velocity``/``effort`` arrays holding NaN where a joint has
no such interface; ``extra_joints`` are appended with 0.0. The message is built once at
activation; each update only copies the handle values and the stamp into it.

Parameters: ``joints``, ``interfaces`` (both set: only those; otherwise every available state
interface), ``extra_joints``, ``use_local_topics`` (false), ``map_interface_to_joint_state.
{position,velocity,effort}`` (interface name read for each field), ``use_urdf_to_filter``
(true), ``frame_id`` ('base_link').
"""

from array import array
import math

from amr_description.control.controller_interface import ControllerInterface
from amr_description.control.controller_interface import TransitionCallbackReturn
from amr_description.control.parameter_table import Parameter
from amr_description.control.parameter_table import ParameterTable
from amr_description.core.xml_document import parse_text
from amr_description.core.xml_document import XMLError
from amr_description.ros.stamps import has_subscribers
from amr_description.ros.stamps import set_stamp
from rclpy.qos import QoSProfile
from sensor_msgs.msg import JointState

FIELDS = ('position', 'velocity', 'effort')

PARAMETERS = ParameterTable('JointStateBroadcasterParameters', [
    Parameter('joints', [''], 'Joints to publish; empty: every joint with state interfaces'),
    Parameter('interfaces', [''], 'State interfaces to publish; empty: all'),
    Parameter('extra_joints', [''], 'Joints published with zero state, e.g. passive joints'),
    Parameter('use_local_topics', False, 'Publish on ~/joint_states instead of /joint_states'),
] + [Parameter(f'map_interface_to_joint_state.{field}', field,
               f'State interface published as the JointState {field}') for field in FIELDS] + [
    Parameter('use_urdf_to_filter', True, 'Publish only the joints of the robot description'),
    Parameter('frame_id', 'base_link', 'frame_id of the published messages'),
])
"""The parameters of upstream's joint_state_broadcaster (jazzy), names and defaults."""


class JointStateBroadcaster(ControllerInterface):
    """Broadcast joint states of the robot (see the module docstring)."""

    def on_init(self):
        """Declare the upstream parameters; returns True."""
        PARAMETERS.declare(self)
        self._publisher = None
        self._rows = []
        self._msg = None
        self._slots = ()
        return True

    def _list(self, name):
        return [v for v in self.param(name, ['']) if v]

    def state_interface_configuration(self):
        """Return ``joint/interface`` for every listed joint and interface, None for all."""
        joints, interfaces = self._list('joints'), self._list('interfaces')
        if joints and interfaces:
            return [f'{j}/{i}' for j in joints for i in interfaces]
        return None

    def on_configure(self, state):
        """Read parameters and create the publisher."""
        joints, interfaces = self._list('joints'), self._list('interfaces')
        if bool(joints) != bool(interfaces):
            self.get_logger().info(
                "'joints' or 'interfaces' parameter is empty. All available state interfaces "
                'will be published')
        self._map = {f: self.param(f'map_interface_to_joint_state.{f}', f) for f in FIELDS}
        self._extra = self._list('extra_joints')
        self._frame_id = self.param('frame_id', 'base_link')
        self._use_urdf = self.param('use_urdf_to_filter', True)
        topic = '~/joint_states' if self.param('use_local_topics', False) else 'joint_states'
        if self._publisher is None:
            self._publisher = self.create_publisher(JointState, topic, QoSProfile(depth=10))
        return TransitionCallbackReturn.SUCCESS

    def _urdf_joints(self):
        if self.description is not None:  # parsed once by the simulator
            return self.description.joint_names(moving_only=True)
        try:
            root = parse_text(self.robot_description)
        except XMLError:
            return []
        return [j.get('name') for j in root.findall('joint')
                if j.get('type') not in ('fixed', None)]

    def on_activate(self, state):
        """Build the joint table from the assigned state interfaces."""
        joints = []
        for name in self.state_interfaces:
            joint = name.rsplit('/', 1)[0]
            if joint not in joints:
                joints.append(joint)
        urdf = self._urdf_joints()
        if urdf:
            ordered = [j for j in urdf if j in joints]
            if not self._use_urdf:
                ordered += [j for j in joints if j not in urdf]
            joints = ordered
        self._rows = []
        for joint in joints:
            handles = tuple(self.state_interfaces.get(f'{joint}/{self._map[f]}') for f in FIELDS)
            if any(h is not None for h in handles):
                self._rows.append((joint, handles))
        if not self._rows and not self._extra:
            self.get_logger().warn('No joint state interfaces to publish')
        self._build_message()
        return TransitionCallbackReturn.SUCCESS

    def _build_message(self):
        """Create the JointState published by every update and the handle -> slot table."""
        names = [joint for joint, _ in self._rows]
        extras = []
        for joint in self._extra:
            if joint not in names and joint not in extras:
                extras.append(joint)
        columns = tuple(array('d', [math.nan] * len(names) + [0.0] * len(extras))
                        for _ in FIELDS)
        msg = JointState()
        msg.header.frame_id = self._frame_id
        msg.name = names + extras
        msg.position, msg.velocity, msg.effort = columns
        columns = (msg.position, msg.velocity, msg.effort)  # the setters copy the arrays
        self._msg = msg
        self._stamp = msg.header.stamp
        # (array, index, handle) for every value read at each update; NaN slots stay NaN
        self._slots = tuple((columns[f], i, handle)
                            for i, (_, handles) in enumerate(self._rows)
                            for f, handle in enumerate(handles) if handle is not None)

    def on_deactivate(self, state):
        """Stop publishing."""
        self._rows = []
        self._slots = ()
        return TransitionCallbackReturn.SUCCESS

    def update(self, time, period):
        """Publish one JointState stamped ``time`` (when subscribed, see heard); True."""
        if not has_subscribers(self._publisher):
            return True
        for column, index, handle in self._slots:
            column[index] = handle.value
        set_stamp(self._stamp, time)
        self._publisher.publish(self._msg)
        return True
