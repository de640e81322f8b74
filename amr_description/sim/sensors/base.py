# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The sensor protocol of the simulator (no rclpy)."""

from amr_description.core.gazebo.sensors import default_topic
from amr_description.core.gazebo.sensors import lumped_link
from amr_description.ros.stamps import set_stamp


class Sensor:
    """
    One sensor of one spawned entity: what the ``mujoco_sim`` node needs to publish it.

    A subclass sets the attributes in its constructor and implements :meth:`measure`.

    :ivar name: sensor name, unique within its entity (str).
    :ivar topic: ROS topic of its messages; a relative name is resolved in the entity's
        namespace by the caller, an absolute one (``/...``) is used as is.
    :ivar frame_id: TF frame of the measurement (``header.frame_id``), with the entity's frame
        prefix.
    :ivar rate: measurements per second of sim time (Hz, > 0).
    :ivar message_type: the ROS message class :meth:`measure` returns.
    :ivar costly: True when measuring costs enough to be skipped while nobody subscribes
        (the node then calls neither :meth:`measure` nor :meth:`advance`); False when every
        due instant counts: the node calls :meth:`advance` while nobody subscribes, so that
        a noise generator's sequence does not depend on who listens.
    :ivar gz_name: the gz topic a Gazebo user's ros_gz_bridge configuration
        (``bridge_config``) maps to ROS, absolute; '' for a sensor that is only a ROS topic.
    :ivar deferred: True for a sensor measured off the simulation thread (a camera): the node
        calls ``request(t, publish)`` instead of :meth:`measure`, which returns an object
        whose ``flush(world, t)`` the node calls once every sensor of the instant has asked
        (``amr_description.sim.sensors.camera.CameraOutput``).
    """

    name = ''
    topic = ''
    frame_id = ''
    rate = 0.0
    message_type = None
    costly = False
    gz_name = ''
    deferred = False

    def period_steps(self, physics_step):
        """
        Return the number of physics steps between two measurements (>= 1).

        A measurement is due at the sim times that are multiples of this period, i.e. at
        ``step_count % period_steps == 0``.

        :param physics_step: s of one physics step (> 0).
        """
        return max(1, int(round(1.0 / (self.rate * physics_step))))

    def measure(self, world, t):
        """
        Return the message of a measurement of ``world`` at sim time ``t`` (s).

        Called on the simulation thread, between two physics steps, with the world at ``t``.
        The returned message may be reused by the next call (the caller publishes it first).

        :param world: the :class:`~amr_description.sim.world.World`.
        :param t: sim time in s; the message's stamp.
        """
        raise NotImplementedError

    def advance(self, world, t):
        """
        Account for the due instant ``t`` (s) that nobody hears, without its message.

        Afterwards the sensor is where :meth:`measure` at ``t`` would have left it (its noise
        generator drew the same numbers), so the messages heard later are the same whoever
        listened before. This default measures; a sensor whose measurement costs more than
        its noise draws overrides it.
        """
        self.measure(world, t)


def fill_odometry(msg, t, position, quaternion, linear, angular):
    """
    Write a pose and twist stamped at sim time ``t`` into a ``nav_msgs/Odometry``.

    :param msg: the message (its frame ids are left as they are); returned.
    :param t: sim time (s).
    :param position: (3,) m; ``quaternion``: (x, y, z, w); ``linear`` (3,) m/s and
        ``angular`` (3,) rad/s, in the frames the caller's Odometry convention names.
    """
    set_stamp(msg.header.stamp, t)
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    p.x, p.y, p.z = (float(v) for v in position)
    q.x, q.y, q.z, q.w = (float(v) for v in quaternion)
    lin, ang = msg.twist.twist.linear, msg.twist.twist.angular
    lin.x, lin.y, lin.z = (float(v) for v in linear)
    ang.x, ang.y, ang.z = (float(v) for v in angular)
    return msg


def sensor_rate(block, physics_step):
    """Return a block's rate in Hz of sim time: ``update_rate``, or every step for 0."""
    return block.update_rate if block.update_rate > 0 else 1.0 / physics_step


def sensor_topic(entity, block, world_name):
    """
    Return ``(ROS topic, gz topic)`` of a sensor block: ``<topic>`` or gz-sim's default name.

    The gz topic is absolute (gz-transport has no namespaces); the ROS topic, used without a
    bridge configuration, resolves a relative ``<topic>`` in the entity's namespace
    (``scan`` -> ``/r1/scan``).
    """
    topic = block.topic
    if not topic:
        description = entity.description
        link = lumped_link(description.model, block.link, description.gazebo_tags)
        topic = default_topic(world_name, entity.name, link, block)
        return topic, topic
    return named_topic(entity, topic)


def named_topic(entity, topic):
    """Return ``(ROS topic, gz topic)`` of a topic a sensor block names (:func:`sensor_topic`)."""
    if topic.startswith('/'):
        return topic, topic
    return f'{entity.namespace}/{topic}', '/' + topic


def sensor_frame(entity, block):
    """Return a sensor's frame id: ``<gz_frame_id>`` else its link, with the frame prefix."""
    return entity.frame_prefix + (block.frame_id or block.link)
