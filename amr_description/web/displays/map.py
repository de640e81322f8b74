# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Map: every ``nav_msgs/OccupancyGrid`` topic as a textured plane in its frame (RViz's Map).

Each grid is drawn on the ground (z 0 of its ``header.frame_id``, placed by its
``info.origin``: the lower-left corner of cell (0, 0), with its yaw) as one picture of one
pixel per cell, coloured as RViz's Map display colours it, with RViz's default alpha 0.7
(:data:`ALPHA`):

- the ``map`` scheme: 0 (free) white to 100 (occupied) black, -1 (unknown) grey-green
  ``#708986``;
- the ``costmap`` scheme (topics whose name holds ``costmap``, as Nav2's RViz configuration
  sets for ``/global_costmap/costmap`` and ``/local_costmap/costmap``): 0 transparent, 1..98
  blue to red, 99 (inscribed) cyan, 100 (lethal) purple, -1 as above;
- in both, values 101..127 green and -128..-2 red to yellow (not valid occupancy).

The palettes are those of RViz's ``palette_builder.cpp`` (rviz_default_plugins). A new
message redraws the picture; between messages the plane follows its frame (a map under
``map -> odom`` as AMCL corrects it). The subscription takes the publishers' QoS (best
available: ``map_server``'s and slam_toolbox's ``/map`` are reliable and transient local,
so a page opened late still has the map). ``<topic>_updates`` (map_msgs) is not read:
map_msgs is not installed here.
"""

from amr_description.core.kinematics import quaternion_to_matrix
from amr_description.web.displays.discovery import AUTO
from amr_description.web.displays.sensor_topics import BEST_AVAILABLE
from amr_description.web.displays.sensor_topics import SensorTopicsDisplay
from amr_description.web.robot_scene import wxyz_position
from nav_msgs.msg import OccupancyGrid
import numpy as np

ALPHA = 0.7
"""RViz's Map display default alpha."""
HEIGHT = 0.002
"""m above z 0 of the map's frame (over the grid lines)."""
UNKNOWN_RGB = (0x70, 0x89, 0x86)
"""The colour of -1 (unknown) cells in both schemes."""


def palette(scheme):
    """
    Return RViz's palette of a colour scheme: (256, 4) uint8 RGBA, indexed by the cell byte.

    The index is the ``int8`` value read as ``uint8`` (-1 is 255).

    :param scheme: ``'map'`` or ``'costmap'``.
    :raises ValueError: on another scheme.
    """
    colours = np.zeros((256, 4), np.uint8)
    values = np.arange(101)
    if scheme == 'map':
        grey = 255 - (255 * values) // 100
        colours[:101] = np.stack([grey, grey, grey, np.full(101, 255)], axis=1)
    elif scheme == 'costmap':
        v = (255 * values[1:99]) // 100
        colours[1:99] = np.stack([v, np.zeros(98), 255 - v, np.full(98, 255)], axis=1)
        colours[99] = (0, 255, 255, 255)
        colours[100] = (255, 0, 255, 255)
    else:
        raise ValueError(f"unknown colour scheme '{scheme}', expected 'map' or 'costmap'")
    colours[101:128] = (0, 255, 0, 255)
    i = np.arange(128, 255)
    colours[128:255] = np.stack([np.full(127, 255), (255 * (i - 128)) // 126,
                                 np.zeros(127), np.full(127, 255)], axis=1)
    colours[255] = (*UNKNOWN_RGB, 255)
    return colours


def scheme_of(topic):
    """Return the colour scheme of a topic: ``'costmap'`` when its name says so."""
    return 'costmap' if 'costmap' in topic else 'map'


def grid_picture(msg, scheme, alpha=ALPHA):
    """
    Return the picture of an OccupancyGrid: (height, width, 4) uint8 RGBA, one pixel per cell.

    Row 0 of the picture is the grid's row 0 (its smallest y): viser lays a picture's row 0
    along the -y edge of its plane and column 0 along the -x edge (measured: a top-down
    screenshot of a picture with a coloured first row and column), as the grid's cells lie
    from its origin.

    :param msg: ``nav_msgs/OccupancyGrid``.
    :param scheme: ``'map'`` or ``'costmap'`` (:func:`palette`).
    :param alpha: opacity 0..1 applied over the palette's own.
    :raises ValueError: when ``data`` does not hold ``width * height`` cells, or a size is 0.
    """
    width, height = msg.info.width, msg.info.height
    data = np.asarray(msg.data, dtype=np.int8)
    if width == 0 or height == 0 or data.size != width * height:
        raise ValueError(f'{data.size} cells for a {width} x {height} grid')
    colours = palette(scheme)[data.view(np.uint8).reshape(height, width)]
    colours[..., 3] = (colours[..., 3] * alpha).astype(np.uint8)
    return colours


def grid_placement(info, T, height=HEIGHT):
    """
    Return where the picture of a grid goes: its centre, orientation and size.

    :param info: ``nav_msgs/MapMetaData`` (``origin``: the lower-left corner of cell (0, 0)
        in the grid's frame; ``resolution`` m per cell).
    :param T: 4x4 pose of the grid's frame in the fixed frame.
    :param height: m above the frame's z 0.
    :returns: ``(position (3,), wxyz (4,), (width m, height m))`` in the fixed frame.
    """
    o = info.origin
    q = (o.orientation.x, o.orientation.y, o.orientation.z, o.orientation.w)
    origin = np.eye(4)
    origin[:3, :3] = quaternion_to_matrix(q)  # an all-zero one (unset) is no rotation
    origin[:3, 3] = (o.position.x, o.position.y, o.position.z)
    size = (info.width * info.resolution, info.height * info.resolution)
    centre = np.eye(4)
    centre[:3, 3] = (size[0] / 2, size[1] / 2, height)
    wxyz, position = wxyz_position(T @ origin @ centre)
    return position, wxyz, size


class MapDisplay(SensorTopicsDisplay):
    """The OccupancyGrids of ``map_topics`` (module docstring)."""

    message_type = OccupancyGrid
    label = 'Map'
    order = 20
    parameters = (('map_topics', [AUTO]),)
    topics_parameter = 'map_topics'
    rviz_classes = {'rviz_default_plugins/Map': 'map_topics'}
    qos = BEST_AVAILABLE
    placed = True
    serialized = False  # a map's frame is needed when it arrives (below); maps are rare

    def _on_message(self, topic, msg):
        # a map's frame is a fixed frame even before TF has it (map_server alone), as in RViz
        self.frames.message_frames.add(msg.header.frame_id.lstrip('/'))
        super()._on_message(topic, msg)

    def render(self, name, msg, T, node):
        """Draw the grid's picture on its frame's ground; return the image node."""
        picture = grid_picture(msg, scheme_of(name))
        position, wxyz, size = grid_placement(msg.info, T)
        return self.server.scene.add_image(name, picture, size[0], size[1], format='png',
                                           position=position, wxyz=wxyz,
                                           cast_shadow=False, receive_shadow=False)

    def place(self, node, msg, T):
        """Move the picture with its frame."""
        position, wxyz, _ = grid_placement(msg.info, T)
        if np.max(np.abs(np.asarray(node.position) - position)) > 1e-4 or \
                np.max(np.abs(np.asarray(node.wxyz) - wxyz)) > 1e-5:
            node.position, node.wxyz = position, wxyz
