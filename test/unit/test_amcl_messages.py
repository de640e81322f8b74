# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""AMCL's particle cloud, serialized by hand, reads back as the nav2_msgs message."""

import math

from amr_description.nodes.amcl import particle_cloud_bytes
from nav2_msgs.msg import ParticleCloud
import numpy as np
import pytest
from rclpy.serialization import deserialize_message
from rclpy.serialization import serialize_message
from std_msgs.msg import Header


@pytest.mark.parametrize('frame', ['', 'm', 'map', 'abcdefgh'])  # every padding to 8 bytes
def test_the_bytes_are_the_messages_serialization(frame):
    header = Header(frame_id=frame)
    header.stamp.sec, header.stamp.nanosec = 7, 9
    particles = np.array([[1.0, 2.0, math.pi / 2], [-3.0, 0.5, 0.0]])
    data = particle_cloud_bytes(header, particles, np.array([0.25, 0.75]))
    msg = deserialize_message(data, ParticleCloud)
    assert msg.header == header and len(msg.particles) == 2
    first, second = msg.particles
    assert (first.pose.position.x, first.pose.position.y) == (1.0, 2.0)
    assert first.pose.orientation.z == pytest.approx(math.sqrt(0.5))
    assert first.pose.orientation.w == pytest.approx(math.sqrt(0.5))
    assert second.weight == 0.75 and second.pose.orientation.w == 1.0
    assert len(serialize_message(msg)) == len(data)  # the same layout (padding bytes differ)
