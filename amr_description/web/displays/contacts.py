# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Contacts: the contact points of every ``ros_gz_interfaces/Contacts`` topic as markers.

Gazebo's contact sensor (:mod:`amr_description.sim.sensors.contact`) gives positions in the
world frame with no frame id; they are drawn in the fixed frame through TF's ``world`` when
it exists, else as if ``world`` were the fixed frame (as the odometry trails of the
simulator's ground truth). Each contact point is a red 0.04 m square, and its normal a 0.1 m
red line. Topics, QoS and rates: :mod:`~amr_description.web.displays.sensor_topics`.
"""

from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import draw_points
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
import numpy as np
from ros_gz_interfaces.msg import Contacts

POINT_SIZE = 0.04
"""m, the side of a drawn contact point."""
RED = (230, 30, 30)


def contact_points(msg):
    """Return the (N, 3) float32 contact positions and (N, 3) unit normals of a Contacts."""
    points, normals = [], []
    for contact in msg.contacts:
        for p, n in zip(contact.positions, contact.normals):
            points.append((p.x, p.y, p.z))
            normals.append((n.x, n.y, n.z))
    return (np.array(points, np.float32).reshape(-1, 3),
            np.array(normals, np.float32).reshape(-1, 3))


class ContactsDisplay(SensorTopicsDisplay):
    """The contacts of ``topics`` (ros_gz_interfaces/Contacts)."""

    message_type = Contacts
    label = 'Contacts'
    default_frame = 'world'
    order = 55
    parameters = (('contact_topics', [AUTO]),)
    topics_parameter = 'contact_topics'

    def rates(self):
        """Return ``[(topic, Rate)]`` of the topics heard so far (a bumper is optional)."""
        return [(topic, item.rate) for topic, item in self._topics.items()
                if item.data is not None]

    def render(self, name, msg, T, node):
        """Draw the contact points in the fixed frame (module docstring)."""
        points, _ = contact_points(msg)
        points = (points @ T[:3, :3].T + T[:3, 3]).astype(np.float32)
        colours = np.tile(np.array(RED, np.uint8), (len(points), 1))
        return draw_points(self.server, name, points, colours, node, POINT_SIZE)
