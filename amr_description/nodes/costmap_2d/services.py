# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A costmap's services and its footprint topic, as ``Costmap2DROS`` and ``ClearCostmapService``.

:class:`CostmapServices` is mixed into
:class:`amr_description.nodes.costmap_2d.node.CostmapNode`. Services (relative to the costmap's
namespace, ``<name>`` the costmap's name):

- ``clear_entirely_<name>`` (ClearEntireCostmap): the obstacle layers reset;
- ``clear_around_<name>`` (ClearCostmapAroundRobot): the obstacle layers' cells inside a square
  of side ``reset_distance`` m around the robot reset to the layer's default value (unknown
  with ``track_unknown_space``, else free), ``clear_except_<name>``
  (ClearCostmapExceptRegion) those outside it, ``clear_around_pose_<name>``
  (ClearCostmapAroundPose) those inside a square around a pose (transformed into the
  costmap's frame); the static and inflation layers are not clearable, as upstream's;
- ``get_costmap`` (GetCostmap): the master grid;
- ``get_cost_<name>`` (GetCost): the cost at ``(x, y)`` of the costmap's frame (-1 and a
  warning outside it), or with ``use_footprint`` the highest cost under the footprint's
  outline at heading ``theta`` (``FootprintCollisionChecker::footprintCostAtPose``).

Topic ``footprint`` (geometry_msgs/Polygon) replaces the footprint (padded by
``footprint_padding``), as ``Costmap2DROS::setRobotFootprintPolygon``. Sources:
``nav2_costmap_2d/src/clear_costmap_service.cpp`` and ``costmap_2d_ros.cpp``.
"""

import math

from amr_description.core.tf_buffer import TransformException
from amr_description.nav import costmap as cm
from amr_description.ros.transforms import transform_planar
from geometry_msgs.msg import Polygon
from nav2_msgs.srv import ClearCostmapAroundPose
from nav2_msgs.srv import ClearCostmapAroundRobot
from nav2_msgs.srv import ClearCostmapExceptRegion
from nav2_msgs.srv import ClearEntireCostmap
from nav2_msgs.srv import GetCost
from nav2_msgs.srv import GetCostmap
import numpy as np


class CostmapServices:
    """The costmap node's services and footprint subscription (a mixin of the node)."""

    def make_services(self):
        """Create the services and the ``footprint`` subscription; return them."""
        name = self.name
        return [
            self.create_service(ClearEntireCostmap, f'clear_entirely_{name}', self._on_clear),
            self.create_service(ClearCostmapAroundRobot, f'clear_around_{name}',
                                self._on_clear_around),
            self.create_service(ClearCostmapExceptRegion, f'clear_except_{name}',
                                self._on_clear_except),
            self.create_service(ClearCostmapAroundPose, f'clear_around_pose_{name}',
                                self._on_clear_around_pose),
            self.create_service(GetCostmap, 'get_costmap', self._on_get),
            self.create_service(GetCost, f'get_cost_{name}', self._on_get_cost),
            self.create_subscription(Polygon, 'footprint', self._on_footprint, 10)]

    def _on_clear(self, request, response):
        self.get_logger().info(f'Received request to clear entirely the {self.name}')
        with self._lock:
            self.obstacles = self._blank()
            self.update()
        return response

    def _clear(self, x, y, side, invert):
        if not all(math.isfinite(v) for v in (x, y, side)):
            self.get_logger().error(f'clear {self.name}: expected a finite pose and '
                                    f'reset_distance, got ({x}, {y}) and {side}; not cleared')
            return
        with self._lock:
            layer = cm.Costmap(self.obstacles, self.grid.resolution, self.grid.origin)
            layer.clear_square(x, y, side, self._unknown(), invert)
            self.update()

    def _clear_at_robot(self, side, invert):
        robot = self._robot_pose()
        if robot is None:
            self.get_logger().error('Cannot clear map because robot pose cannot be retrieved.')
            return
        self._clear(robot[0], robot[1], side, invert)

    def _on_clear_around(self, request, response):
        self._clear_at_robot(request.reset_distance, False)
        return response

    def _on_clear_except(self, request, response):
        self.get_logger().info(f'Received request to clear except a region the {self.name}')
        self._clear_at_robot(request.reset_distance, True)
        return response

    def _on_clear_around_pose(self, request, response):
        self.get_logger().info(f'Received request to clear around pose for {self.name}')
        frame = self.p['global_frame']
        try:
            T, _ = self.tf.lookup(frame, request.pose.header.frame_id or frame)
            x, y, _ = transform_planar(T, request.pose.pose)
        except (TransformException, ValueError) as exc:
            self.get_logger().error(f'Cannot clear map around pose: {str(exc).strip()}')
            return response
        self._clear(x, y, request.reset_distance, False)
        return response

    def _on_get(self, request, response):
        response.map = self.messages()[1]
        return response

    def _on_get_cost(self, request, response):
        grid = self.grid
        if request.use_footprint:
            response.cost = float(cm.footprint_cost(grid, self.footprint,
                                                    (request.x, request.y, request.theta)))
            return response
        cost = grid.cost_at(request.x, request.y)
        if cost is None:
            self.get_logger().warning(f'Point ({request.x:f}, {request.y:f}) is out of bounds')
            cost = -1.0
        response.cost = float(cost)
        return response

    def _on_footprint(self, msg):
        points = np.array([[p.x, p.y] for p in msg.points], float).reshape(-1, 2)
        if len(points) < 3 or not np.isfinite(points).all():
            self.get_logger().error(f'footprint: expected at least 3 finite points, got '
                                    f'{len(points)}; footprint unchanged')
            return
        self._set_footprint(points)
