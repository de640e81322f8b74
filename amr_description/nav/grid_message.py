# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
nav_msgs/OccupancyGrid to and from :class:`amr_description.nav.map_io.GridMap`.

``info.origin`` is the pose of cell (0, 0)'s lower-left corner (REP 103, the map frame); its
yaw is the rotation about z, as nav2_map_server writes it from the YAML's ``origin``. Cell
``(x, y)`` is ``data[y * width + x]`` (nav_msgs/msg/OccupancyGrid.msg).
"""

import array
import math

from amr_description.nav.costmap import to_occupancy
from amr_description.nav.map_io import GridMap
from nav2_msgs.msg import Costmap as CostmapMsg
from nav_msgs.msg import OccupancyGrid
import numpy as np


def occupancy_grid(grid, frame_id, stamp):
    """
    Return an OccupancyGrid message holding ``grid``.

    :param grid: :class:`GridMap`.
    :param frame_id: ``header.frame_id``.
    :param stamp: ``builtin_interfaces/Time`` for ``header.stamp`` and ``info.map_load_time``.
    """
    msg = OccupancyGrid()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.info.map_load_time = stamp
    msg.info.resolution = float(grid.resolution)
    msg.info.width = grid.width
    msg.info.height = grid.height
    x, y, yaw = grid.origin
    msg.info.origin.position.x = float(x)
    msg.info.origin.position.y = float(y)
    msg.info.origin.orientation.z = math.sin(yaw / 2.0)
    msg.info.origin.orientation.w = math.cos(yaw / 2.0)
    msg.data = np.ascontiguousarray(grid.data, dtype=np.int8).ravel().tolist()
    return msg


def grid_from_message(msg):
    """
    Return the :class:`GridMap` of an OccupancyGrid message.

    :param msg: nav_msgs/OccupancyGrid.
    :raises ValueError: when ``data`` does not hold ``width * height`` cells, or the
        resolution is not a positive number.
    """
    width, height = int(msg.info.width), int(msg.info.height)
    if len(msg.data) != width * height:
        raise ValueError(f'OccupancyGrid data has {len(msg.data)} cells, expected width '
                         f'{width} x height {height} = {width * height}')
    if not msg.info.resolution > 0.0 or not math.isfinite(msg.info.resolution):
        raise ValueError(f'OccupancyGrid resolution must be above 0, found '
                         f'{msg.info.resolution}')
    q = msg.info.origin.orientation
    yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    data = np.asarray(msg.data, dtype=np.int8).reshape(height, width)
    origin = (msg.info.origin.position.x, msg.info.origin.position.y, yaw)
    return GridMap(data, float(msg.info.resolution), origin)


def costmap_from_message(msg):
    """
    Return a :class:`amr_description.nav.costmap.Costmap` of a nav2_msgs/Costmap.

    :raises ValueError: when ``data`` does not hold ``size_x * size_y`` cells or the resolution
        is not positive.
    """
    from amr_description.nav.costmap import Costmap
    meta = msg.metadata
    w, h = int(meta.size_x), int(meta.size_y)
    if len(msg.data) != w * h:
        raise ValueError(f'costmap has {len(msg.data)} cells, expected {w} x {h}')
    if not meta.resolution > 0.0:
        raise ValueError(f'costmap resolution {meta.resolution} is not positive')
    costs = np.frombuffer(bytes(msg.data), np.uint8).reshape(h, w).copy()
    return Costmap(costs, meta.resolution, (meta.origin.position.x, meta.origin.position.y),
                   msg.header.frame_id)


def costmap_messages(costmap, stamp):
    """
    Return ``(OccupancyGrid, nav2_msgs/Costmap)`` of a costmap's master grid.

    The OccupancyGrid holds ``costmap_2d_publisher.cpp``'s translation of the costs
    (:func:`amr_description.nav.costmap.to_occupancy`), the Costmap message the costs as they
    are, layer ``master``; both in the costmap's frame, origin unrotated.

    :param costmap: :class:`amr_description.nav.costmap.Costmap`.
    :param stamp: ``builtin_interfaces/Time`` for the headers and the load and update times.
    """
    grid = OccupancyGrid()
    grid.header.frame_id = costmap.frame
    grid.header.stamp = stamp
    grid.info.map_load_time = stamp
    grid.info.resolution = costmap.resolution
    grid.info.height, grid.info.width = costmap.shape
    grid.info.origin.position.x, grid.info.origin.position.y = costmap.origin
    grid.info.origin.orientation.w = 1.0
    grid.data = array.array('b', to_occupancy(costmap.costs).ravel().tobytes())
    raw = CostmapMsg()
    raw.header = grid.header
    raw.metadata.map_load_time = raw.metadata.update_time = stamp
    raw.metadata.layer = 'master'
    raw.metadata.resolution = costmap.resolution
    raw.metadata.size_y, raw.metadata.size_x = costmap.shape
    raw.metadata.origin = grid.info.origin
    raw.data = array.array('B', costmap.costs.ravel().tobytes())
    return grid, raw
