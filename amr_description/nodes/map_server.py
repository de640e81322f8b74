# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``map_server``: nav2_map_server's map server (Jazzy), a managed (lifecycle) node.

Parameters: ``yaml_filename`` (the map YAML; empty: load nothing and wait for
``~/load_map``), ``topic_name`` (``map``) and ``frame_id`` (``map``). On configure the map
file is read (:mod:`amr_description.nav.map_io`; a bad file fails the transition with one
line naming the file and field) and the publisher (``topic_name``, reliable + transient local,
depth 1) and the services ``map_server/map`` (``nav_msgs/srv/GetMap``) and
``map_server/load_map`` (``nav2_msgs/srv/LoadMap``) are created; on activate the map is
published once. ``load_map`` works only while active (else result 255): it loads the file,
publishes the map and returns it with result 0, or returns LoadMap's code (1 missing file,
2 bad image, 3 bad YAML) and keeps the previous map. ``map`` answers only while active.
Source: ``nav2_map_server/src/map_server/map_server.cpp``.
"""

from amr_description.nav import map_io
from amr_description.nav.grid_message import occupancy_grid
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from nav2_msgs.srv import LoadMap
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetMap
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy

LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
"""Nav2's map QoS: reliable, transient local, keep last 1."""


class MapServer(ManagedNode):
    """Node ``map_server``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters; starts unconfigured (``kwargs``: rclpy's node options)."""
        super().__init__('map_server', **kwargs)
        self.declare_parameter('yaml_filename', '')
        self.declare_parameter('topic_name', 'map')
        self.declare_parameter('frame_id', 'map')
        self.map_msg = None
        self._publisher = None
        self._map_services = []

    def configure(self):
        """Read the map file and create the publisher and the services."""
        self.get_logger().info('Configuring')
        self.frame_id = self.get_parameter('frame_id').value
        path = self.get_parameter('yaml_filename').value
        if path:
            result, msg = self._load(path)
            if msg is None:
                raise RuntimeError(f'Failed to load map yaml file: {path}')
            self.map_msg = msg
        else:
            self.get_logger().info(
                "yaml-filename parameter is empty, set 'yaml-filename' to load map at "
                'activation or use services')
        prefix = self.get_name() + '/'
        self._publisher = self.create_publisher(
            OccupancyGrid, self.get_parameter('topic_name').value, LATCHED)
        self._map_services = [
            self.create_service(GetMap, prefix + 'map', self._on_get_map),
            self.create_service(LoadMap, prefix + 'load_map', self._on_load_map)]

    def activate(self):
        """Publish the map, if one is loaded."""
        self.get_logger().info('Activating')
        if self.map_msg is not None:
            self._publisher.publish(self.map_msg)

    def deactivate(self):
        """Nothing to stop: the services refuse to answer while inactive."""
        self.get_logger().info('Deactivating')

    def cleanup(self):
        """Remove the publisher and the services and forget the map."""
        self.get_logger().info('Cleaning up')
        for service in self._map_services:
            self.destroy_service(service)
        self._map_services = []
        if self._publisher is not None:
            self.destroy_publisher(self._publisher)
            self._publisher = None
        self.map_msg = None

    def _load(self, path):
        """Return ``(LoadMap result, OccupancyGrid or None)``; errors are logged."""
        self.get_logger().info(f'Loading yaml file: {path}')
        try:
            grid, metadata = map_io.load_map(path)
        except map_io.MapError as exc:
            self.get_logger().error(str(exc))
            return exc.code, None
        self.get_logger().info(
            f'Read map {metadata.image}: {grid.width} by {grid.height}, '
            f'{grid.resolution:g} m/cell, mode {metadata.mode}')
        msg = occupancy_grid(grid, self.frame_id, self.get_clock().now().to_msg())
        return LoadMap.Response.RESULT_SUCCESS, msg

    def _on_get_map(self, request, response):
        if not self.is_active():
            self.get_logger().warn('Received GetMap request but not in ACTIVE state, ignoring!')
            return response
        if self.map_msg is not None:
            response.map = self.map_msg
        return response

    def _on_load_map(self, request, response):
        if not self.is_active():
            self.get_logger().warn(
                'Received LoadMap request but not in ACTIVE state, ignoring!')
            response.result = LoadMap.Response.RESULT_UNDEFINED_FAILURE
            return response
        result, msg = self._load(request.map_url)
        response.result = result
        if msg is not None:
            self.map_msg = msg
            response.map = msg
            self._publisher.publish(msg)
        return response


def main(args=None):
    """
    Run the map server until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(MapServer, args)


if __name__ == '__main__':
    main()
