# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ROS side of a robot's gz-sim topics, as the user's ros_gz_bridge would make it.

Without a bridge configuration every gz topic of a system is the ROS topic of the same name.
With one (``bridge_config`` parameter, :mod:`amr_description.core.gazebo.bridge_config`), a
system's topic reaches ROS only when an entry bridges it in that direction, under the entry's ROS
name; the entry's ROS type must be the type the bridge would convert to (a command topic may
also be bridged as ``geometry_msgs/msg/TwistStamped``, whose ``twist`` is used, as
ros_gz_bridge's TwistStamped <-> gz.msgs.Twist conversion does).
"""

from amr_description.core.gazebo.bridge_config import ros_side
from geometry_msgs.msg import Twist
from geometry_msgs.msg import TwistStamped


def type_name(message_type):
    """Return the ROS name of a message class, e.g. ``'nav_msgs/msg/Odometry'``."""
    return f'{message_type.__module__.split(".")[0]}/msg/{message_type.__name__}'


def _unstamped(callback):
    return lambda msg: callback(msg.twist)


def bridged_outputs(sensors, entries):
    """
    Return ``(sensor, ROS topic)`` for every sensor published under a ROS name.

    :param sensors: the entity's sensors; those with a ``gz_name`` (gz-sim system outputs,
        ``<gazebo><sensor>`` blocks) are looked up in the bridge entries.
    :param entries: the bridge entries, or None without a bridge configuration.
    :raises ValueError: one line naming the topic when the entry's ROS type is not the
        sensor's.
    """
    result = []
    for sensor in sensors:
        if entries is None or not sensor.gz_name:
            result.append((sensor, sensor.topic))
            continue
        entry = ros_side(entries, sensor.gz_name, to_ros=True)
        if entry is None:
            continue  # not bridged: it does not reach ROS
        if entry.ros_type != type_name(sensor.message_type):
            raise ValueError(f'bridge_config: gz topic {sensor.gz_name!r} carries '
                             f'{type_name(sensor.message_type)}, not {entry.ros_type}')
        result.append((sensor, entry.ros_topic))
    return result


def bridged_inputs(inputs, entries):
    """
    Return ``(ROS topic, message type, callback)`` for every input subscribed from ROS.

    :param inputs: the entity's :class:`~amr_description.sim.systems.base.Input` list.
    :param entries: the bridge entries, or None without a bridge configuration.
    :raises ValueError: one line naming the topic when the entry's ROS type cannot carry it.
    """
    result = []
    for item in inputs:
        if entries is None:
            result.append((item.topic, item.message_type, item.callback))
            continue
        entry = ros_side(entries, item.topic, to_ros=False)
        if entry is None:
            continue
        if entry.ros_type == type_name(item.message_type):
            result.append((entry.ros_topic, item.message_type, item.callback))
        elif item.message_type is Twist and entry.ros_type == type_name(TwistStamped):
            result.append((entry.ros_topic, TwistStamped, _unstamped(item.callback)))
        else:
            raise ValueError(f'bridge_config: gz topic {item.topic!r} takes '
                             f'{type_name(item.message_type)}, not {entry.ros_type}')
    return result
