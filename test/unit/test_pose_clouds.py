# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""ParticleCloud and PoseArray read into arrays, and the displays read only the newest message."""

import threading

from amr_description.nodes.amcl import particle_cloud_bytes
from amr_description.ros import cdr
from amr_description.web.displays import particle_cloud
from amr_description.web.displays.particle_cloud import ParticleCloudDisplay
from amr_description.web.displays.particle_cloud import read_poses
from amr_description.web.displays.sensor_topics import _Topic
from geometry_msgs.msg import Pose
from geometry_msgs.msg import PoseArray
from nav2_msgs.msg import Particle
from nav2_msgs.msg import ParticleCloud
import numpy as np
import pytest
from rclpy.serialization import serialize_message
from std_msgs.msg import Header

FRAMES = ['', 'm', 'map', 'abcdefgh', 'r12/map']  # every padding to 8 bytes


def _pose(i):
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = 1.0 + i, -2.0 * i, 0.5
    pose.orientation.z, pose.orientation.w = 0.6, 0.8
    return pose


def _cloud(frame, n):
    return ParticleCloud(header=Header(frame_id=frame),
                         particles=[Particle(pose=_pose(i), weight=1.0 / (i + 2))
                                    for i in range(n)])


def _expected(n, weights):
    rows = [(1.0 + i, -2.0 * i, 0.5, 0.0, 0.0, 0.6, 0.8) for i in range(n)]
    if weights:
        rows = [row + (1.0 / (i + 2),) for i, row in enumerate(rows)]
    return np.array(rows, float).reshape(n, 8 if weights else 7)


@pytest.mark.parametrize('frame', FRAMES)
@pytest.mark.parametrize('n', [0, 1, 3])
def test_a_cloud_and_a_pose_array_read_back_as_rclpy_wrote_them(frame, n):
    poses = read_poses(serialize_message(_cloud(frame, n)), ParticleCloud)
    assert poses.header.frame_id == frame
    assert np.array_equal(poses.records, _expected(n, True))
    array = PoseArray(header=Header(frame_id=frame), poses=[_pose(i) for i in range(n)])
    poses = read_poses(serialize_message(array), PoseArray)
    assert poses.header.frame_id == frame
    assert np.array_equal(poses.records, _expected(n, False))


@pytest.mark.parametrize('frame', FRAMES)
def test_amcls_cloud_bytes_read_back(frame):
    particles = np.array([[1.0, 2.0, np.pi / 2], [-3.0, 0.5, 0.0]])
    poses = read_poses(particle_cloud_bytes(Header(frame_id=frame), particles,
                                            np.array([0.25, 0.75])), ParticleCloud)
    assert poses.header.frame_id == frame
    assert poses.records[:, [0, 1, 7]].tolist() == [[1.0, 2.0, 0.25], [-3.0, 0.5, 0.75]]
    assert poses.records[0, 5:7] == pytest.approx([np.sqrt(0.5), np.sqrt(0.5)])


def test_what_is_not_plain_cdr_is_read_by_rclpy_alike(monkeypatch):
    data = serialize_message(_cloud('map', 3))

    def refuse(data, width):
        raise ValueError('not plain CDR')

    monkeypatch.setattr(cdr, 'stamped_poses', refuse)
    poses = particle_cloud.read_poses(data, ParticleCloud)
    assert poses.header.frame_id == 'map'
    assert np.array_equal(poses.records, _expected(3, True))


def test_a_truncated_cloud_is_a_value_error():
    data = serialize_message(_cloud('map', 3))
    with pytest.raises(ValueError, match='does not fit'):
        cdr.stamped_poses(data[:-8], 8)


class _Logger:

    def __init__(self):
        self.lines = []

    def warning(self, text, **kwargs):
        self.lines.append(text)


class _Node:

    def __init__(self):
        self.logger = _Logger()

    def get_logger(self):
        return self.logger


def test_only_the_newest_message_is_read_and_garbage_is_one_warning():
    display = object.__new__(ParticleCloudDisplay)  # no viewer: only what reading needs
    display._lock, display.node, display._topics = threading.Lock(), _Node(), {}
    display._topics['/particle_cloud'] = item = _Topic()
    reads = []
    display.read = lambda data: reads.append(data) or read_poses(data, ParticleCloud)
    clouds = [serialize_message(_cloud('map', n)) for n in (1, 2, 3)]
    for data in clouds:
        display._on_message('/particle_cloud', data)
    newest = display._newest('/particle_cloud', item)
    assert len(newest.records) == 3 and reads == [clouds[2]]
    assert display._newest('/particle_cloud', item) is newest and len(reads) == 1
    display._on_message('/particle_cloud', b'\x00\x01\x00\x00\x05')
    assert display._newest('/particle_cloud', item) is None
    assert len(display.node.logger.lines) == 1
    assert 'ParticleCloud /particle_cloud: cannot read' in display.node.logger.lines[0]
