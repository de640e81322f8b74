# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
ParticleCloud and PoseArray: a flat arrow per pose, as nav2_rviz_plugins and RViz draw them.

- **ParticleCloud** (``nav2_msgs/ParticleCloud``, AMCL's ``/particle_cloud``): each particle
  an arrow of length ``weight * (0.3 - 0.02) + 0.02`` m held within [0.02, 0.3] m, raised
  ``5 * weight`` m, as nav2_rviz_plugins' ParticleCloud display (``Min Arrow Length``,
  ``Max Arrow Length``, ``Arrow Height Scale``), colour (255, 25, 0);
- **PoseArray** (``geometry_msgs/PoseArray``): arrows of 0.3 m (RViz's PoseArray
  ``Arrow (Flat)``), colour (255, 25, 0).

A flat arrow is three lines in the pose's xy-plane: the shaft along x and two head lines from
the tip back to (0.75, +-0.2) of the length (nav2_rviz_plugins' ``FlatWeightedArrowsArray``).
Both subscribe with the sensor-data QoS (AMCL publishes best effort). Their newest message is
read straight into arrays (:func:`amr_description.ros.cdr.stamped_poses`), without rclpy's
Python object per pose.
"""

import collections

from amr_description.core.kinematics import quaternions_to_matrices
from amr_description.ros import cdr
from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_segments
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
from geometry_msgs.msg import PoseArray
from nav2_msgs.msg import ParticleCloud
import numpy as np

COLOUR = (255, 25, 0)
"""RViz's and nav2_rviz_plugins' default arrow colour."""
MIN_LENGTH = 0.02
"""m, nav2_rviz_plugins' ``Min Arrow Length``."""
MAX_LENGTH = 0.3
"""m, its ``Max Arrow Length`` (and RViz's PoseArray ``Arrow Length``)."""
HEIGHT_SCALE = 5.0
"""m per unit weight, its ``Arrow Height Scale``."""
THICKNESS = 2.0
"""Pixels, the lines' width."""


Poses = collections.namedtuple('Poses', 'header records')
"""The frame of a PoseArray or ParticleCloud (``header.frame_id``) and its (N, 7 or 8) pose
records (position x y z, orientation x y z w and, in a cloud, the weight)."""

_Header = collections.namedtuple('_Header', 'frame_id')


def read_poses(data, message_type):
    """
    Return the :data:`Poses` of a serialized PoseArray or ParticleCloud.

    :param data: the message's CDR bytes; what is not plain CDR is read by rclpy.
    :param message_type: ``PoseArray`` or ``ParticleCloud``.
    :raises ValueError: a message that ends inside a field (rclpy's errors for bytes it
        cannot read pass).
    """
    width = 8 if message_type is ParticleCloud else 7

    def of_message(msg):
        poses = msg.particles if width == 8 else msg.poses
        records = np.array([_record(p, width) for p in poses], float).reshape(-1, width)
        return msg.header.frame_id, records

    frame_id, records = cdr.read(data, lambda d: cdr.stamped_poses(d, width), message_type,
                                 of_message)
    return Poses(_Header(frame_id), records)


def _record(item, width):
    pose = item.pose if width == 8 else item
    p, q = pose.position, pose.orientation
    values = (p.x, p.y, p.z, q.x, q.y, q.z, q.w)
    return values + (item.weight,) if width == 8 else values


def record_arrays(records):
    """
    Return the positions (N, 3) and rotations (N, 3, 3) of (N, >= 7) pose records.

    :raises ValueError: on a value that is not finite.
    """
    positions = np.array(records[:, 0:3], float)
    quaternions = records[:, 3:7]
    if not (np.isfinite(positions).all() and np.isfinite(quaternions).all()):
        raise ValueError('a pose that is not finite (NaN or infinite values)')
    return positions, quaternions_to_matrices(quaternions)


def flat_arrows(positions, rotations, lengths):
    """
    Return the line segments of flat arrows: (3 N, 2, 3) float32, in the poses' frame.

    :param positions: (N, 3) arrow tails, m.
    :param rotations: (N, 3, 3) pose rotations (the arrow points along x).
    :param lengths: (N,) arrow lengths, m.
    """
    lengths = np.asarray(lengths, float).reshape(-1, 1)
    x, y = rotations[:, :, 0], rotations[:, :, 1]
    tip = positions + lengths * x
    back = positions + 0.75 * lengths * x
    segments = np.stack([
        np.stack([positions, tip], axis=1),
        np.stack([tip, back + 0.2 * lengths * y], axis=1),
        np.stack([tip, back - 0.2 * lengths * y], axis=1)], axis=1)
    return segments.reshape(-1, 2, 3).astype(np.float32)


def particle_lengths(weights):
    """Return the arrow length (m) of each particle weight (nav2_rviz_plugins' rule)."""
    weights = np.asarray(weights, float)
    return np.clip(weights * (MAX_LENGTH - MIN_LENGTH) + MIN_LENGTH, MIN_LENGTH, MAX_LENGTH)


def draw_arrows(server, name, segments, T, node):
    """Create or update the line-segment node of arrows placed with ``T`` (4x4)."""
    return draw_segments(server, name, segments, T, COLOUR, node, THICKNESS)


class PoseArrayDisplay(SensorTopicsDisplay):
    """The poses of ``pose_array_topics`` (geometry_msgs/PoseArray) as 0.3 m arrows."""

    message_type = PoseArray
    label = 'PoseArray'
    order = 62
    parameters = (('pose_array_topics', [AUTO]),)
    topics_parameter = 'pose_array_topics'
    rviz_classes = {'rviz_default_plugins/PoseArray': 'pose_array_topics'}

    def read(self, data):
        """Return the :data:`Poses` of the serialized ``data``."""
        return read_poses(data, PoseArray)

    def render(self, name, msg, T, node):
        """Draw an arrow per pose of ``msg`` (:data:`Poses`)."""
        positions, rotations = record_arrays(msg.records)
        segments = flat_arrows(positions, rotations, np.full(len(positions), MAX_LENGTH))
        return draw_arrows(self.server, name, segments, T, node)


class ParticleCloudDisplay(SensorTopicsDisplay):
    """The particles of ``particle_cloud_topics`` (nav2_msgs/ParticleCloud), by weight."""

    message_type = ParticleCloud
    label = 'ParticleCloud'
    order = 60
    parameters = (('particle_cloud_topics', [AUTO]),)
    topics_parameter = 'particle_cloud_topics'
    rviz_classes = {'nav2_rviz_plugins/ParticleCloud': 'particle_cloud_topics'}

    def read(self, data):
        """Return the :data:`Poses` of the serialized ``data`` (weights in column 7)."""
        return read_poses(data, ParticleCloud)

    def render(self, name, msg, T, node):
        """Draw an arrow per particle of ``msg`` (:data:`Poses`), sized by its weight."""
        positions, rotations = record_arrays(msg.records)
        weights = msg.records[:, 7]
        if not np.isfinite(weights).all():
            raise ValueError('a particle weight that is not finite')
        positions[:, 2] = weights * HEIGHT_SCALE
        segments = flat_arrows(positions, rotations, particle_lengths(weights))
        return draw_arrows(self.server, name, segments, T, node)
