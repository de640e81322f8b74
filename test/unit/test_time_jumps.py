# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The viewer's frame manager on a backward jump of /clock (messages in, no DDS)."""

from amr_description.web.displays.base import FrameManager
from geometry_msgs.msg import TransformStamped
from rclpy.serialization import serialize_message
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage


class _Logger:

    def __init__(self):
        self.lines = []

    def info(self, text, **kwargs):
        self.lines.append(text)

    warning = info


class _Node:
    """What FrameManager uses of a node: subscriptions (not called here) and a logger."""

    def __init__(self):
        self.logger = _Logger()

    def create_subscription(self, *args, **kwargs):
        return None

    def get_logger(self):
        return self.logger


def _clock(t):
    msg = Clock()
    msg.clock.sec, msg.clock.nanosec = int(t), int(round((t - int(t)) * 1e9))
    return msg


def _tf(parent, child, t, x):
    transform = TransformStamped()
    transform.header.frame_id, transform.child_frame_id = parent, child
    transform.header.stamp.sec = int(t)
    transform.header.stamp.nanosec = int(round((t - int(t)) * 1e9))
    transform.transform.translation.x = x
    transform.transform.rotation.w = 1.0
    return serialize_message(TFMessage(transforms=[transform]))  # taken serialized


def test_a_jump_back_clears_dynamic_transforms_keeps_static_ones_and_redraws_from_new_tf():
    node = _Node()
    frames = FrameManager(node)
    frames._on_tf_static(_tf('base_footprint', 'base_link', 0.0, 0.05))
    frames._on_clock(_clock(50.0))
    frames._on_tf(_tf('odom', 'base_footprint', 50.0, 3.0))
    assert frames.buffer.lookup('odom', 'base_link')[0][0, 3] == 3.05
    frames._on_clock(_clock(20.0))  # a simulator restarted, or a bag's /clock
    assert frames.jumps == 1 and frames.last_jump[1:] == (50.0, 20.0)
    assert not frames.buffer.can_transform('odom', 'base_link')
    assert frames.buffer.can_transform('base_footprint', 'base_link')  # /tf_static stays
    # /tf stamped before the old newest sample is taken again (no "too old" for good)
    frames._on_tf(_tf('odom', 'base_footprint', 20.0, 1.0))
    assert frames.buffer.lookup('odom', 'base_link')[0][0, 3] == 1.05
    assert node.logger.lines == ['/clock jumped back in time (50.000 s -> 20.000 s): '
                                 'transforms cleared']
    frames._on_clock(_clock(20.5))  # forward: nothing cleared
    assert frames.jumps == 1 and frames.buffer.can_transform('odom', 'base_link')


def test_a_tf_message_that_cannot_be_read_is_one_warning_and_the_buffer_stays():
    node = _Node()
    frames = FrameManager(node)
    frames._on_tf(_tf('odom', 'base_footprint', 1.0, 2.0))
    frames._on_tf(_tf('odom', 'base_footprint', 2.0, 3.0)[:-20])  # ends inside a field
    assert frames.buffer.lookup('odom', 'base_footprint')[0][0, 3] == 2.0
    assert len(node.logger.lines) == 1 and node.logger.lines[0].startswith('/tf: cannot read')
