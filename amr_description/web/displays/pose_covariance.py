# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
PoseWithCovariance: a pose, its position covariance ellipse and its yaw wedge (RViz's).

Every ``geometry_msgs/PoseWithCovarianceStamped`` topic (AMCL's ``/amcl_pose``,
slam_toolbox's ``/pose``) is drawn as RViz's PoseWithCovariance display draws it with its
defaults:

- an arrow along the pose's x axis: shaft 1 m (radius 0.05 m) and head 0.3 m (radius 0.1 m),
  colour (255, 25, 0);
- the position covariance as an ellipse in the header frame's xy-plane: its semi-axes are
  one standard deviation (the square roots of the eigenvalues of the xy block), colour
  (204, 51, 204) at alpha 0.3 (RViz draws a sphere scaled to twice the standard deviations);
- the yaw covariance (a 2-D pose: no roll or pitch variance) as a wedge of +-1 standard
  deviation around the heading, 1 m long (RViz's ``Orientation`` ``Offset``), colour
  (255, 255, 127) at alpha 0.5, held under 89 degrees.

rviz_rendering's ``covariance_visual.cpp`` is the source of these rules. A covariance that
is not positive semidefinite draws no ellipse (RViz hides it too). The subscription takes
the publishers' QoS (best available: AMCL's ``amcl_pose`` is transient local).
"""

import math

from amr_description.core.kinematics import quaternion_to_matrix
from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import BEST_AVAILABLE
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
from amr_description.web.robot_scene import wxyz_position
from geometry_msgs.msg import PoseWithCovarianceStamped
import numpy as np

ARROW_RGB = (255, 25, 0)
ELLIPSE_RGB = (204, 51, 204)
WEDGE_RGB = (255, 255, 127)
SHAFT_LENGTH = 1.0
HEAD_LENGTH = 0.3
MAX_WEDGE = math.radians(89.0)
"""The largest half-angle of the yaw wedge (RViz bounds its cone the same way)."""
SEGMENTS = 48
"""Sides of the ellipse's polygon."""


def covariance_ellipse(covariance):
    """
    Return the position ellipse of a 6x6 pose covariance: semi-axes (2,) m and angle rad.

    :param covariance: 36 values, row-major (x, y, z, roll, pitch, yaw).
    :returns: ``(radii, angle)``: one standard deviation along each eigenvector of the xy
        block, the first axis at ``angle`` from x; None when the block is not positive
        semidefinite or not finite.
    """
    c = np.asarray(covariance, float).reshape(6, 6)[:2, :2]
    if not np.isfinite(c).all():
        return None
    values, vectors = np.linalg.eigh((c + c.T) / 2.0)
    if values.min() < -1e-12:
        return None
    return np.sqrt(np.clip(values, 0.0, None)), math.atan2(vectors[1, 0], vectors[0, 0])


def ellipse_mesh(centre, radii, angle, segments=SEGMENTS):
    """
    Return a filled ellipse as a triangle fan: vertices (S + 1, 3) and faces (S, 3).

    :param centre: (3,) m.
    :param radii: semi-axes (2,) m along ``angle`` and perpendicular to it.
    :param angle: rad from x of the first semi-axis.
    """
    t = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    c, s = math.cos(angle), math.sin(angle)
    u, v = radii[0] * np.cos(t), radii[1] * np.sin(t)
    rim = np.stack([c * u - s * v, s * u + c * v, np.zeros(segments)], axis=1)
    vertices = np.vstack([[0.0, 0.0, 0.0], rim]) + np.asarray(centre, float)
    i = np.arange(segments)
    faces = np.stack([np.zeros(segments, int), 1 + i, 1 + (i + 1) % segments], axis=1)
    return vertices.astype(np.float32), faces.astype(np.uint32)


def yaw_wedge(origin, heading, sigma, length=SHAFT_LENGTH, segments=16):
    """
    Return the wedge of +-``sigma`` around ``heading``: vertices (S + 2, 3) and faces (S, 3).

    :param origin: (3,) m, the wedge's tip.
    :param heading: rad, yaw of the pose.
    :param sigma: rad, the yaw standard deviation (held within :data:`MAX_WEDGE`).
    :param length: m, the wedge's radius.
    """
    half = min(max(sigma, 0.0), MAX_WEDGE)
    t = heading + np.linspace(-half, half, segments + 1)
    rim = np.stack([length * np.cos(t), length * np.sin(t), np.zeros(segments + 1)], axis=1)
    vertices = np.vstack([[0.0, 0.0, 0.0], rim]) + np.asarray(origin, float)
    i = np.arange(segments)
    faces = np.stack([np.zeros(segments, int), 1 + i, 2 + i], axis=1)
    return vertices.astype(np.float32), faces.astype(np.uint32)


def _mesh(server, name, mesh, rgb, opacity):
    vertices, faces = mesh
    return server.scene.add_mesh_simple(name, vertices, faces, color=rgb, opacity=opacity,
                                        side='double', cast_shadow=False,
                                        receive_shadow=False)


class PoseWithCovarianceDisplay(SensorTopicsDisplay):
    """The poses of ``pose_covariance_topics`` (module docstring)."""

    message_type = PoseWithCovarianceStamped
    label = 'PoseWithCovariance'
    order = 64
    parameters = (('pose_covariance_topics', [AUTO]),)
    topics_parameter = 'pose_covariance_topics'
    rviz_classes = {'rviz_default_plugins/PoseWithCovariance': 'pose_covariance_topics'}
    qos = BEST_AVAILABLE

    def render(self, name, msg, T, node):
        """Draw the arrow, the ellipse and the wedge under a frame placed with ``T``."""
        pose = msg.pose.pose
        p = np.array([pose.position.x, pose.position.y, pose.position.z])
        q = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
        covariance = np.asarray(msg.pose.covariance, float)
        if not (np.isfinite(p).all() and np.isfinite(q).all()):
            raise ValueError('a pose that is not finite (NaN or infinite values)')
        wxyz, position = wxyz_position(T)
        scene = self.server.scene
        frame = scene.add_frame(name, show_axes=False, wxyz=wxyz, position=position)
        x_axis = quaternion_to_matrix(q)[:, 0]
        tip = p + (SHAFT_LENGTH + HEAD_LENGTH) * x_axis
        scene.add_arrows(f'{name}/arrow', np.array([[p, tip]], np.float32), ARROW_RGB,
                         shaft_radius=0.05, head_radius=0.1, head_length=HEAD_LENGTH)
        ellipse = covariance_ellipse(covariance)
        if ellipse is not None:
            _mesh(self.server, f'{name}/ellipse', ellipse_mesh(p + (0, 0, 0.01), *ellipse),
                  ELLIPSE_RGB, 0.3)
        yaw_variance = covariance[35]
        if math.isfinite(yaw_variance) and yaw_variance >= 0.0:
            heading = math.atan2(x_axis[1], x_axis[0])
            _mesh(self.server, f'{name}/wedge',
                  yaw_wedge(p + (0, 0, 0.02), heading, math.sqrt(yaw_variance)),
                  WEDGE_RGB, 0.5)
        return frame
