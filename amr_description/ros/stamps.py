# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Stamps and publication helpers for realtime loops (controllers, the simulator's sensors).

Times are seconds of ROS time (sim time in the simulator), as floats >= 0.
"""

from builtin_interfaces.msg import Time as TimeMsg


def _split(time):
    """Return ``(sec, nanosec)`` of ``time`` seconds rounded to whole nanoseconds."""
    return divmod(int(round(time * 1e9)), 1_000_000_000)


def time_to_msg(time):
    """Return ``builtin_interfaces/Time`` for ``time`` in seconds (float, >= 0)."""
    sec, nanosec = _split(time)
    return TimeMsg(sec=sec, nanosec=nanosec)


def set_stamp(stamp, time):
    """
    Write ``time`` (seconds, float >= 0) into an existing ``builtin_interfaces/Time``.

    Same rounding as :func:`time_to_msg`, without creating a message: for realtime loops that
    reuse their messages.

    :param stamp: the ``builtin_interfaces/Time`` to change in place.
    :param time: seconds (float).
    """
    stamp.sec, stamp.nanosec = _split(time)


def msg_to_time(msg):
    """Return seconds (float) of a ``builtin_interfaces/Time``."""
    return msg.sec + msg.nanosec * 1e-9


def has_subscribers(publisher):
    """
    Return True when a volatile ``publisher`` has at least one matched subscription.

    A message published on a volatile topic that no subscription has matched yet is delivered
    to nobody (DDS keeps no history for late joiners), so skipping its conversion and
    publication changes nothing any subscriber sees, while it saves the rclpy message
    conversion (the largest Python cost per robot of a fleet whose topics nobody listens to).
    Not for ``transient_local`` publishers.

    :param publisher: an rclpy publisher.
    :returns: bool.
    """
    return publisher.get_subscription_count() > 0
