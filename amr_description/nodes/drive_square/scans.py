# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The main job's lidar map: every scan of the drive placed with ``/odom`` and with ground truth.

Scans (``/scan``) are placed at the robot pose of their stamp, interpolated between the
odometry (or ground-truth) messages around it, composed with the lidar's mount on the root
link (from the robot description). Odometry poses are mapped into the world with the course
start (odometry start -> ground-truth start). The picture (``out/scans.png``) draws both over
the horizontal section of the world's collision shapes at the lidar's height
(:mod:`amr_description.core.scan_map`); the table line is the share of scan points within 3
stddev + 1 cm of a true surface.
"""

import math

from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.scan_map import compose
from amr_description.core.scan_map import interpolate
from amr_description.core.scan_map import scan_to_world
from amr_description.core.scan_map import surface_distance
from amr_description.nodes.drive_square.driver import ODOM_TOPIC
from amr_description.nodes.drive_square.driver import planar_pose
from amr_description.nodes.drive_square.driver import stamp_seconds
from amr_description.nodes.drive_square.driver import TRUTH_TOPIC
from nav_msgs.msg import Odometry
import numpy as np
from sensor_msgs.msg import LaserScan

MARGIN = 0.01
"""m added to 3 stddev of the lidar's noise for a point to count as on a true surface."""
SCAN_TOPIC = '/scan'


def lidar_mount(urdf_xml):
    """
    Return the first lidar of a description: ``(block, (x, y, yaw), height)`` or None.

    ``(x, y, yaw)`` is its frame in the root link's frame (planar), ``height`` m above the
    root link (the sensor's ``<pose>`` included).
    """
    description = RobotDescription(urdf_xml)
    block = next((b for b in description.sensors.sensors if b.kind == 'lidar'), None)
    if block is None:
        return None
    T = np.eye(4)
    for joint in description.model.chain(block.link):
        if joint.origin is not None:
            T = T @ np.asarray(joint.origin, dtype=float)
    x, y, z = block.xyz
    yaw = block.rpy[2]
    cy, sy = math.cos(yaw), math.sin(yaw)
    sensor = np.array([[cy, -sy, 0, x], [sy, cy, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])
    T = T @ sensor
    return block, (T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])), T[2, 3]


class ScanRecorder:
    """
    Keeps the scans and the odometry and ground-truth poses of one robot (no namespace).

    :param node: the driving node (subscriptions).
    """

    def __init__(self, node):
        """Subscribe ``/scan``, ``/odom`` and ``/ground_truth/odom``."""
        self.scans = []
        self.odom = []
        self.truth = []
        node.create_subscription(LaserScan, SCAN_TOPIC, self._on_scan, 50)
        node.create_subscription(Odometry, ODOM_TOPIC,
                                 lambda m: self.odom.append(self._sample(m)), 100)
        node.create_subscription(Odometry, TRUTH_TOPIC,
                                 lambda m: self.truth.append(self._sample(m)), 100)

    @staticmethod
    def _sample(msg):
        return stamp_seconds(msg.header.stamp), planar_pose(msg)

    def _on_scan(self, msg):
        self.scans.append((stamp_seconds(msg.header.stamp), msg.angle_min,
                           msg.angle_increment, np.array(msg.ranges, dtype=float)))

    def placed(self, samples, mount, to_world=(0.0, 0.0, 0.0), start=None, end=None):
        """
        Return the world points of every scan placed with ``samples``, as one (N, 2) array.

        :param samples: ``self.odom`` or ``self.truth``.
        :param mount: the lidar's ``(x, y, yaw)`` on the root link.
        :param to_world: planar pose mapping the samples' frame into the world.
        :param start: sim s; scans before it are left out (None: none); ``end`` likewise.
        """
        samples = sorted(samples)
        points = []
        for t, angle_min, increment, ranges in self.scans:
            if (start is not None and t < start) or (end is not None and t > end):
                continue
            pose = interpolate(samples, t)
            if pose is None:
                continue
            frame = compose(compose(to_world, pose), mount)
            points.append(scan_to_world(ranges, angle_min, increment, frame))
        return np.concatenate(points) if points else np.zeros((0, 2))


def on_surface_share(points, sections, stddev):
    """Return the share (0..1) of points within 3 stddev + :data:`MARGIN` of a surface."""
    if len(points) == 0:
        return 0.0
    return float(np.mean(surface_distance(points, sections) <= 3.0 * stddev + MARGIN))


def write_scan_map(path, sections, placed, title):
    """
    Draw the world's sections and the placed scan points side by side into a PNG.

    :param path: output PNG.
    :param sections: :func:`~amr_description.core.scan_map.world_sections`.
    :param placed: list of ``(label, points (N, 2), share, colour)``.
    :param title: the figure's title.
    """
    import matplotlib
    matplotlib.use('Agg')
    from matplotlib.patches import Circle
    from matplotlib.patches import Rectangle
    from matplotlib.transforms import Affine2D
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(placed), figsize=(6.5 * len(placed), 6.5), dpi=100,
                             squeeze=False)
    for ax, (label, points, share, colour) in zip(axes[0], placed):
        for section in sections:
            if section[0] == 'box':
                _, (cx, cy), yaw, (hx, hy) = section
                patch = Rectangle((-hx, -hy), 2 * hx, 2 * hy, facecolor='0.85',
                                  edgecolor='0.4', linewidth=0.8)
                patch.set_transform(Affine2D().rotate(yaw).translate(cx, cy) + ax.transData)
            else:
                _, (cx, cy), r = section
                patch = Circle((cx, cy), r, facecolor='0.85', edgecolor='0.4', linewidth=0.8)
            ax.add_patch(patch)
        if len(points):
            ax.scatter(points[:, 0], points[:, 1], s=0.3, color=colour, linewidths=0)
        ax.set_title(f'scans placed with {label}: {100 * share:.1f} % on a true surface')
        ax.set_aspect('equal')
        ax.autoscale_view()
        ax.set_xlabel('x [m] (world)')
        ax.set_ylabel('y [m] (world)')
        ax.grid(True, alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
