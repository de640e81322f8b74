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
Both subscribe with the sensor-data QoS (AMCL publishes best effort).
"""

from amr_description.core.kinematics import quaternions_to_matrices
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


def pose_arrays(poses):
    """
    Return the positions (N, 3) and rotations (N, 3, 3) of ``geometry_msgs/Pose`` objects.

    :raises ValueError: on a value that is not finite.
    """
    positions = np.array([(p.position.x, p.position.y, p.position.z) for p in poses],
                         float).reshape(-1, 3)
    quaternions = np.array([(p.orientation.x, p.orientation.y, p.orientation.z,
                             p.orientation.w) for p in poses], float).reshape(-1, 4)
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

    def render(self, name, msg, T, node):
        """Draw an arrow per pose."""
        positions, rotations = pose_arrays(msg.poses)
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

    def render(self, name, msg, T, node):
        """Draw an arrow per particle, its length and height from its weight."""
        positions, rotations = pose_arrays([p.pose for p in msg.particles])
        weights = np.array([p.weight for p in msg.particles], float)
        if not np.isfinite(weights).all():
            raise ValueError('a particle weight that is not finite')
        positions[:, 2] = weights * HEIGHT_SCALE
        segments = flat_arrows(positions, rotations, particle_lengths(weights))
        return draw_arrows(self.server, name, segments, T, node)
