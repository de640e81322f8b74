# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim 8's JointStatePublisher system: the joints' states as ``sensor_msgs/JointState``.

As gz-sim 8 ``src/systems/joint_state_publisher`` with ros_gz_bridge's ``gz.msgs.Model`` ->
``sensor_msgs/JointState`` conversion: one entry per ``<joint_name>`` (default: every moving
joint, in URDF order), ``position`` (rad or m), ``velocity`` (rad/s or m/s) and ``effort``
(the actuator's force, N m or N); ``header.stamp`` is the sim time, ``header.frame_id`` empty.
gz-sim publishes at every iteration unless ``<update_rate>`` (gz-sim 8.14) is given; here
"every iteration" is every update of the robot's systems
(:data:`~amr_description.sim.systems.base.SYSTEM_RATE`).
"""

from amr_description.ros.stamps import set_stamp
from amr_description.sim.systems.base import joint_hardware
from amr_description.sim.systems.base import ModelSystem
from amr_description.sim.systems.base import Output
from amr_description.sim.systems.base import SYSTEM_RATE
from sensor_msgs.msg import JointState


class JointStatePublisher(ModelSystem):
    """
    One JointStatePublisher of one robot (see the module docstring).

    :param params: :class:`~amr_description.core.gazebo.systems.JointStatePublisherParams`
        with its defaults resolved.
    :param world: the :class:`~amr_description.sim.world.World`.
    :param entity: the spawned entity.
    """

    def __init__(self, params, world, entity):
        """Bind the joints and prepare the message (see the class docstring)."""
        super().__init__()
        joints = params.joint_names or entity.description.joint_names(moving_only=True)
        self.rate = float(params.update_rate) if params.update_rate > 0 else SYSTEM_RATE
        self.hardware = joint_hardware(world, entity,
                                       f'entity {entity.name!r} JointStatePublisher', joints,
                                       states=('position', 'velocity', 'effort'))
        handles = self.hardware.state_handles
        self._handles = [(handles[f'{j}/position'], handles[f'{j}/velocity'],
                          handles[f'{j}/effort']) for j in joints]
        self._msg = JointState(name=list(joints))
        self.outputs = [Output('joint_state_publisher', params.topic, JointState, self.rate,
                               self.message)]

    def message(self, world, t):
        """Return the joints' states at sim time ``t`` (s)."""
        self.hardware.read(t, 0.0)
        msg = self._msg
        set_stamp(msg.header.stamp, t)
        msg.position = [h[0].value for h in self._handles]
        msg.velocity = [h[1].value for h in self._handles]
        msg.effort = [h[2].value for h in self._handles]
        return msg
