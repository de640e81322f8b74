# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The poses of the world's moving models: gz-sim's ``/world/<world>/dynamic_pose/info``.

gz-sim's SceneBroadcaster publishes the poses of the dynamic entities of a world as a
``gz.msgs.Pose_V``, which ros_gz_bridge delivers as ``tf2_msgs/TFMessage`` (one transform per
pose, ``::`` in frame ids turned into ``/``). Here the simulator publishes, for every link of
a non-static SDF model (a box the robots can push), one transform ``world`` ->
``<model>/<link>`` at :data:`RATE` Hz of sim time (gz-sim: 60 Hz of wall time), only while
someone subscribes. The viewer draws those links where they are.
"""

from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import Sensor
from tf2_msgs.msg import TFMessage

RATE = 50.0
"""Hz of sim time: the ground truth's rate, a whole number of 1 ms physics steps."""


class WorldPoses(Sensor):
    """
    The poses of the world's moving links, one ``TransformStamped`` each.

    :param world: the :class:`~amr_description.sim.world.World` (its name and free bodies).
    """

    message_type = TFMessage
    costly = True  # no state: an unheard instant costs nothing

    def __init__(self, world):
        """Read the moving bodies' names once (see the module docstring)."""
        from geometry_msgs.msg import TransformStamped
        self.name = 'dynamic_pose'
        self.topic = f'/world/{world.name}/dynamic_pose/info'
        self.frame_id = 'world'
        self.rate = RATE
        self.gz_name = self.topic  # bridged like every gz topic (bridge_config)
        self.bodies = world.world_free_bodies()
        self._msg = TFMessage()
        for body in self.bodies:
            transform = TransformStamped()
            transform.header.frame_id = 'world'
            transform.child_frame_id = body.replace('::', '/')
            self._msg.transforms.append(transform)

    def measure(self, world, t):
        """Return the TFMessage of the moving links at sim time ``t`` (s)."""
        for body, transform in zip(self.bodies, self._msg.transforms):
            position, quat = world.body_pose(body)
            set_stamp(transform.header.stamp, t)
            v = transform.transform.translation
            v.x, v.y, v.z = (float(c) for c in position)
            r = transform.transform.rotation
            r.x, r.y, r.z, r.w = quat
        return self._msg
