# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A Nav2 costmap node (``nav2_costmap_2d::Costmap2DROS``, Jazzy) that a server runs beside itself.

:class:`CostmapNode` is the rclpy node ``<name>`` in namespace ``<name>`` (Nav2's
``/global_costmap/global_costmap``), so a Nav2 params file's ``global_costmap: global_costmap:
ros__parameters:`` section reaches it. Parameters, with Nav2's code defaults: ``global_frame``
(map), ``robot_base_frame`` (base_link), ``robot_radius`` (0.1), ``footprint`` ("[]"; a valid
one overrides the radius), ``footprint_padding`` (0.01), ``width``/``height`` (5, m, int),
``resolution`` (0.1), ``origin_x``/``origin_y`` (0.0), ``rolling_window`` (false),
``track_unknown_space`` (false), ``lethal_cost_threshold`` (100), ``unknown_cost_value``
(255), ``trinary_costmap`` (true), ``update_frequency`` (5.0 Hz), ``publish_frequency``
(1.0 Hz), ``transform_tolerance`` (0.3 s), ``initial_transform_timeout`` (60.0 s), ``map_topic``
(map), ``plugins`` ([static_layer, obstacle_layer, inflation_layer]) and each layer's
``<layer>.plugin``. As ``Costmap2DROS``: ``use_sim_time`` is the server's; the layers update
every ``1 / update_frequency`` seconds of wall time (its ``mapUpdateLoop`` runs on a
``WallRate``), and the costmap is published every ``1 / publish_frequency`` seconds of the
node's clock, stamped with that clock (sim time in a simulation):

- ``nav2_costmap_2d::StaticLayer``: the map on ``map_topic`` (reliable, transient local unless
  ``map_subscribe_transient_local`` is false); a costmap that is not a rolling window takes
  the map's size, resolution and origin;
- ``nav2_costmap_2d::ObstacleLayer`` (and ``VoxelLayer``, run as one, said once):
  ``observation_sources``, each ``<source>.topic``, ``data_type`` (LaserScan),
  ``marking``/``clearing``, ``obstacle_max_range``/``min``, ``raytrace_max_range``/``min``,
  ``inf_is_valid``; scans are heard with sensor-data QoS and wait (up to 10 per source) for
  TF at their own stamp, as behind Nav2's tf2 MessageFilter; at each update the newest one
  TF can place is ray-traced and marked; the footprint is cleared
  (``footprint_clearing_enabled``);
- ``nav2_costmap_2d::InflationLayer``: ``inflation_radius`` (0.55), ``cost_scaling_factor``
  (10.0), ``inflate_unknown``, ``inflate_around_unknown``;

and each layer's ``enabled`` (true; false: the layer leaves the grid as it is). While active,
``ros2 param set`` reaches the costmap as upstream's
(:mod:`amr_description.nodes.costmap_2d.parameters`).

Relative input topics (``map_topic``, a source's ``topic``) are resolved in the server's
namespace, not the costmap's (``map`` is ``/map``, or ``/r1/map`` for a server in ``r1``).
Another plugin type is said in one line and skipped. Topics (relative to the node's
namespace): ``costmap`` (OccupancyGrid, Nav2's translation) and ``costmap_raw``
(nav2_msgs/Costmap), reliable + transient local, depth 1; ``published_footprint``
(PolygonStamped). The clear and cost services and the ``footprint`` topic:
:mod:`amr_description.nodes.costmap_2d.services`. The layers' arithmetic is
:mod:`amr_description.nav.costmap`.

Activation waits, as ``Costmap2DROS::on_activate`` (``nav2_costmap_2d/src/costmap_2d_ros.cpp``)
does, until TF joins ``robot_base_frame`` to ``global_frame``: it says "Timed out waiting for
transform from BASE to GLOBAL to become available, tf error: ..." twice a second, and after
``initial_transform_timeout`` seconds of the node's clock (counted from its first /clock
with ``use_sim_time``: a time of 0 starts no timeout) it fails the server's activation
("Failed to activate NAME because transform from BASE to GLOBAL did not become available before
timeout"), so a lifecycle manager becomes active only once SLAM or AMCL publishes ``map``.
"""

import threading
import time

from amr_description.core.tf_buffer import TransformException
from amr_description.nav import costmap as cm
from amr_description.nav.grid_message import costmap_messages
from amr_description.nav.grid_message import grid_from_message
from amr_description.nodes.costmap_2d.parameters import CostmapParameters
from amr_description.nodes.costmap_2d.services import CostmapServices
from amr_description.ros.node import Node
from amr_description.ros.transforms import planar_pose
from geometry_msgs.msg import Point32
from geometry_msgs.msg import PolygonStamped
from nav2_msgs.msg import Costmap as CostmapMsg
from nav_msgs.msg import OccupancyGrid
import numpy as np
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from sensor_msgs.msg import LaserScan

LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
DEFAULTS = {
    'global_frame': 'map', 'robot_base_frame': 'base_link', 'robot_radius': 0.1,
    'footprint': '[]', 'footprint_padding': 0.01, 'width': 5, 'height': 5, 'resolution': 0.1,
    'origin_x': 0.0, 'origin_y': 0.0, 'rolling_window': False, 'track_unknown_space': False,
    'lethal_cost_threshold': 100, 'unknown_cost_value': 255, 'trinary_costmap': True,
    'update_frequency': 5.0, 'publish_frequency': 1.0, 'transform_tolerance': 0.3,
    'initial_transform_timeout': 60.0,
    'map_topic': 'map', 'always_send_full_costmap': False,
    'plugins': ['static_layer', 'obstacle_layer', 'inflation_layer'],
}
SOURCE_DEFAULTS = {
    'topic': '', 'data_type': 'LaserScan', 'marking': True, 'clearing': False,
    'obstacle_max_range': 2.5, 'obstacle_min_range': 0.0, 'raytrace_max_range': 3.0,
    'raytrace_min_range': 0.0, 'inf_is_valid': False, 'sensor_frame': '',
}
SCAN_QUEUE = 10
"""Scans kept per observation source while they wait for TF (a MessageFilter's queue)."""
INFLATION_DEFAULTS = {'inflation_radius': 0.55, 'cost_scaling_factor': 10.0,
                      'inflate_unknown': False, 'inflate_around_unknown': False}


class CostmapNode(CostmapServices, CostmapParameters, Node):
    """
    The costmap node; see the module docstring.

    :param name: ``global_costmap`` or ``local_costmap``.
    :param tf_buffer: the server's :class:`amr_description.core.tf_buffer.TransformBuffer`.
    :param namespace: the server's namespace ('' at the root).
    :param cli_args: the server's own ROS arguments (a composed server's ``--params-file``
        and remappings), or None.
    :param use_sim_time: the server's ``use_sim_time``, which overrides the costmap's own
        (Nav2's servers hand theirs to ``Costmap2DROS``), or None to keep the costmap's.
    :param kwargs: the server's other rclpy node options (``use_global_arguments``).
    """

    def __init__(self, name, tf_buffer, namespace='', cli_args=None, use_sim_time=None,
                 **kwargs):
        """Declare the parameters and the layers' parameters."""
        if use_sim_time is not None:
            kwargs['parameter_overrides'] = list(kwargs.get('parameter_overrides') or []) + [
                Parameter('use_sim_time', value=bool(use_sim_time))]
        ns = f'{namespace.rstrip("/")}/{name}' if namespace else name
        # node-local remaps win over the process's ``-r __node:=<server>`` (as Nav2's
        # Costmap2DROS does with ``<name>:__node:=<name>``), and the first matching rule wins
        # over the server's own ``__node`` and ``__ns`` remaps that follow
        ns = '/' + ns.lstrip('/')
        own = ['--ros-args', '-r', f'__node:={name}', '-r', f'__ns:={ns}']
        super().__init__(name, namespace=ns, cli_args=own + list(cli_args or []), **kwargs)
        self.name = name
        self.parent_ns = namespace.rstrip('/')
        self.tf = tf_buffer
        self.p = {k: self.declare_parameter(k, v).value for k, v in DEFAULTS.items()}
        self.layers = []
        for layer in self.p['plugins']:
            kind = str(self.declare_parameter(f'{layer}.plugin', '').value)
            kind = kind.replace('/', '::').split('::')[-1]
            if kind in ('VoxelLayer', 'ObstacleLayer'):
                if kind == 'VoxelLayer':
                    self.get_logger().info(f'{layer}: VoxelLayer runs as a 2-D ObstacleLayer')
                self.layers.append(('obstacle', layer, self._obstacle_params(layer)))
            elif kind == 'StaticLayer':
                self.layers.append(('static', layer, {
                    'map_topic': self.declare_parameter(f'{layer}.map_topic', '').value,
                    'map_subscribe_transient_local': self.declare_parameter(
                        f'{layer}.map_subscribe_transient_local', True).value}))
            elif kind == 'InflationLayer':
                self.layers.append(('inflation', layer, {
                    k: self.declare_parameter(f'{layer}.{k}', v).value
                    for k, v in INFLATION_DEFAULTS.items()}))
            else:
                self.get_logger().warning(f"{layer}: plugin '{kind or '(none)'}' is not "
                                          'available here; layer skipped')
                continue
            self.layers[-1][2]['enabled'] = self.declare_parameter(f'{layer}.enabled',
                                                                   True).value
        self._lock = threading.RLock()  # the update timer, the map and ros2 param set
        self._footprint()
        self.grid = self._empty_grid()
        self.static = None  # (costs, Costmap of the map)
        self.obstacles = self._blank()
        self.scans = {}
        self.robot = None
        self._entities = []

    def _obstacle_params(self, layer):
        sources = str(self.declare_parameter(f'{layer}.observation_sources', '').value).split()
        out = {'footprint_clearing_enabled': self.declare_parameter(
            f'{layer}.footprint_clearing_enabled', True).value, 'sources': {}}
        for src in sources:
            params = {k: self.declare_parameter(f'{layer}.{src}.{k}', v).value
                      for k, v in SOURCE_DEFAULTS.items()}
            params['topic'] = params['topic'] or src
            if params['data_type'] != 'LaserScan':
                self.get_logger().warning(
                    f"{layer}.{src}: data_type '{params['data_type']}' is not read here "
                    '(LaserScan only); source skipped')
                continue
            out['sources'][src] = params
        return out

    def _footprint(self):
        points = None
        self.use_radius = True  # as Costmap2DROS's use_radius_, fixed at start-up
        if self.p['footprint'] not in ('', '[]'):
            try:
                points = cm.parse_footprint(self.p['footprint'])
                self.use_radius = False
            except ValueError as exc:
                self.get_logger().error(f'{exc}; using robot_radius')
        if points is None:
            points = cm.footprint_from_radius(self.p['robot_radius'])
        self._set_footprint(points)

    def _set_footprint(self, points):
        """Take an unpadded ``(n, 2)`` footprint, m, and pad it (``setRobotFootprint``)."""
        self.unpadded = np.asarray(points, float)
        self.footprint = cm.pad_footprint(self.unpadded, self.p['footprint_padding'])
        self.inscribed, self.circumscribed = cm.footprint_radii(self.footprint)

    def _empty_grid(self):
        """Return a grid of the parameters' size, resolution and origin, unknown or free."""
        p = self.p
        return cm.Costmap.empty(p['width'], p['height'], p['resolution'],
                                (p['origin_x'], p['origin_y']), p['global_frame'],
                                self._unknown())

    def _unknown(self):
        return cm.NO_INFORMATION if self.p['track_unknown_space'] else cm.FREE_SPACE

    def _blank(self):
        return np.full(self.grid.shape, self._unknown(), np.uint8)

    # lifecycle, driven by the server
    def wait_for_transform(self, period=0.5):
        """
        Wait until TF joins ``robot_base_frame`` to ``global_frame`` (Costmap2DROS's activate).

        :param period: seconds of wall time between two checks (upstream's 2 Hz rate).
        :raises RuntimeError: when ``initial_transform_timeout`` seconds of the node's clock
            pass first.
        """
        base, frame = self.p['robot_base_frame'], self.p['global_frame']
        self.get_logger().info('Checking transform')
        deadline = None
        while True:
            try:
                self.tf.lookup(frame, base)
                return
            except TransformException as exc:
                error = str(exc).strip()
            self.get_logger().info(f'Timed out waiting for transform from {base} to {frame} '
                                   f'to become available, tf error: {error}')
            now = self.get_clock().now().nanoseconds * 1e-9
            if now == 0.0:
                pass  # use_sim_time and no /clock yet: the timeout starts with the clock
            elif deadline is None or now < deadline - self.p['initial_transform_timeout']:
                deadline = now + self.p['initial_transform_timeout']  # first check, or a reset
            elif now > deadline:
                raise RuntimeError(f'Failed to activate {self.name} because transform from '
                                   f'{base} to {frame} did not become available before '
                                   'timeout')
            time.sleep(period)

    def start(self):
        """Wait for TF, then subscribe, publish and update (the server's activate)."""
        self.wait_for_transform()
        for kind, layer, params in self.layers:
            if kind == 'static':
                qos = LATCHED if params['map_subscribe_transient_local'] else 10
                self._entities.append(self.create_subscription(
                    OccupancyGrid, self._parent_topic(params['map_topic'] or
                                                      self.p['map_topic']), self._on_map, qos))
            elif kind == 'obstacle':
                for src, sp in params['sources'].items():
                    self._entities.append(self.create_subscription(
                        LaserScan, self._parent_topic(sp['topic']),
                        lambda m, s=src: self._queue(s).append(m), qos_profile_sensor_data))
        self.costmap_pub = self.create_publisher(OccupancyGrid, 'costmap', LATCHED)
        self.raw_pub = self.create_publisher(CostmapMsg, 'costmap_raw', LATCHED)
        self.footprint_pub = self.create_publisher(PolygonStamped, 'published_footprint', 1)
        self._entities += [
            self.costmap_pub, self.raw_pub, self.footprint_pub,
            *self.make_services(),
            self.create_timer(1.0 / max(self.p['update_frequency'], 1e-3), self.update,
                              clock=Clock(clock_type=ClockType.STEADY_TIME))]
        self._publish_timer = self.create_timer(1.0 / max(self.p['publish_frequency'], 1e-3),
                                                self.publish)
        self._entities.append(self._publish_timer)
        self.watch_parameters(self._on_set_parameters)

    def _parent_topic(self, topic):
        """Resolve a relative input topic in the server's namespace (Nav2's parent namespace)."""
        return topic if topic.startswith('/') else f'{self.parent_ns}/{topic}'

    def stop(self):
        """Remove what :meth:`start` made (the server's deactivate)."""
        self.unwatch_parameters()
        for entity in self._entities:
            for destroy in (self.destroy_subscription, self.destroy_publisher,
                            self.destroy_service, self.destroy_timer):
                if destroy(entity):
                    break
        self._entities = []

    # layers
    def _on_map(self, msg):
        try:
            grid = grid_from_message(msg)
        except ValueError as exc:
            self.get_logger().error(f'{self.p["map_topic"]}: {exc}; map ignored')
            return
        p = self.p
        costs = cm.static_costs(np.asarray(grid.data), p['track_unknown_space'],
                                p['lethal_cost_threshold'], p['trinary_costmap'],
                                p['unknown_cost_value'])
        placed = cm.Costmap(costs, grid.resolution, grid.origin[:2], msg.header.frame_id)
        with self._lock:
            self.static = placed
            if not p['rolling_window']:
                self.grid = cm.Costmap(costs.copy(), grid.resolution, grid.origin[:2],
                                       p['global_frame'])
                self.obstacles = self._blank()
            self.update()

    def _robot_pose(self):
        try:
            T, _ = self.tf.lookup(self.p['global_frame'], self.p['robot_base_frame'])
        except TransformException as exc:
            self.get_logger().warning(f'{self.name}: robot pose: {str(exc).strip()}',
                                      throttle_duration_sec=5.0)
            return None
        return planar_pose(T)

    def _queue(self, src):
        """Return ``src``'s :class:`~amr_description.nav.costmap.ScanQueue`."""
        return self.scans.setdefault(src, cm.ScanQueue(SCAN_QUEUE))

    def _observe(self, params):
        layer = cm.Costmap(self.obstacles, self.grid.resolution, self.grid.origin)
        for src, sp in params['sources'].items():
            queue = self._queue(src)
            found = queue.take(self.tf, self.p['global_frame'], sp['sensor_frame'])
            if queue.dropped:
                self.get_logger().warning(f"{sp['topic']}: {queue.dropped}",
                                          throttle_duration_sec=5.0)
            if found is None:
                continue
            scan, T = found
            points, hit = cm.scan_rays(scan.ranges, scan.angle_min, scan.angle_increment,
                                       scan.range_min, scan.range_max, sp['inf_is_valid'],
                                       sp['raytrace_max_range'])
            world = points @ T[:2, :2].T + T[:2, 3]
            origin = T[:2, 3]
            if sp['clearing']:
                layer.raytrace(origin, world, sp['raytrace_max_range'],
                               sp['raytrace_min_range'])
            if sp['marking']:
                layer.mark(world[hit], origin, sp['obstacle_max_range'],
                           sp['obstacle_min_range'])
        if params['footprint_clearing_enabled'] and self.robot is not None:
            layer.clear_polygon(cm.place_footprint(self.footprint, self.robot))

    def update(self):
        """Run the enabled layers in order into the master grid (the update timer)."""
        with self._lock:
            self._update()

    def _update(self):
        self.robot = self._robot_pose()
        if self.p['rolling_window']:
            if self.robot is None:
                return
            self.grid, self.obstacles = self.grid.rolled(self.obstacles, self.robot,
                                                         self._unknown())
        master = np.full(self.grid.shape, self._unknown(), np.uint8)
        for kind, layer, params in self.layers:
            if not params['enabled']:
                continue
            if kind == 'static' and self.static is not None:
                self.grid.paint(master, self.static)
            elif kind == 'obstacle':
                self._observe(params)
                known = self.obstacles != cm.NO_INFORMATION
                take = known & ((master == cm.NO_INFORMATION) | (master < self.obstacles))
                master[take] = self.obstacles[take]
            elif kind == 'inflation':
                master = cm.inflate(master, self.grid.resolution, params['inflation_radius'],
                                    params['cost_scaling_factor'], self.inscribed,
                                    params['inflate_unknown'], params['inflate_around_unknown'])
        self.grid = cm.Costmap(master, self.grid.resolution, self.grid.origin,
                               self.p['global_frame'])

    # outputs
    def messages(self):
        """Return ``(OccupancyGrid, nav2_msgs/Costmap)`` of the master grid, stamped now."""
        return costmap_messages(self.grid, self.get_clock().now().to_msg())

    def publish(self):
        """Publish the costmap, the raw costmap and the footprint (the publish timer)."""
        if self.p['publish_frequency'] <= 0.0:
            return  # upstream's publish cycle of -1 s: not published
        grid, raw = self.messages()
        self.costmap_pub.publish(grid)
        self.raw_pub.publish(raw)
        if self.robot is not None:
            msg = PolygonStamped()
            msg.header = grid.header
            msg.polygon.points = [Point32(x=float(px), y=float(py)) for px, py in
                                  cm.place_footprint(self.footprint, self.robot)]
            self.footprint_pub.publish(msg)
