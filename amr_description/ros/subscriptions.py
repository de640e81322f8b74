# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The messages already waiting in a subscription's queue, taken from a callback.

rclpy's executor takes one message per subscription each time it wakes, and runs a node's
ready timers before its subscriptions. A timer that reads the newest value of a faster topic
(controller_server's 20 Hz loop reading the 50 Hz odometry, on an executor shared with its local
costmap) can then see a value several periods old while newer messages wait in the queue:
measured in ``navigate_job --rtf 0``, controller_server's odometry was a median 0.05 s old at
its cycles with 1-7 messages waiting (docs/navigation.md). Nav2's C++ servers do not have this:
the odometry callback runs on the executor while the control loop runs on the action server's
own thread (``nav2_controller/src/controller_server.cpp``). :func:`take_waiting` lets a timer
callback catch up first.
"""

from rclpy.exceptions import InvalidHandle


def take_waiting(subscription):
    """
    Take every message waiting in ``subscription``'s queue, oldest first, without its callback.

    :param subscription: an ``rclpy.subscription.Subscription`` (message or raw).
    :returns: a list of the messages (the subscription's type; bytes when raw); empty when none
        waits or the subscription was destroyed.
    """
    taken = []
    try:
        with subscription.handle:
            while True:
                got = subscription.handle.take_message(subscription.msg_type, subscription.raw)
                if got is None:
                    return taken
                taken.append(got[0])
    except InvalidHandle:
        return taken
