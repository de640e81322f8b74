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
  (10.0), ``inflate_unknown``, ``inflate_around_unknown``.

Relative input topics (``map_topic``, a source's ``topic``) are resolved in the server's
namespace, not the costmap's (``map`` is ``/map``, or ``/r1/map`` for a server in ``r1``).
Another plugin type is said in one line and skipped. Topics (relative to the node's
namespace): ``costmap`` (OccupancyGrid, Nav2's translation) and ``costmap_raw``
(nav2_msgs/Costmap), reliable + transient local, depth 1; ``published_footprint``
(PolygonStamped). Services: ``clear_entirely_<name>`` (nav2_msgs/ClearEntireCostmap),
``get_costmap`` (nav2_msgs/GetCostmap). The layers' arithmetic is
:mod:`amr_description.nav.costmap`.

Activation waits, as ``Costmap2DROS::on_activate`` (``nav2_costmap_2d/src/costmap_2d_ros.cpp``)
does, until TF joins ``robot_base_frame`` to ``global_frame``: it says "Timed out waiting for
transform from BASE to GLOBAL to become available, tf error: ..." twice a second, and after
``initial_transform_timeout`` seconds of the node's clock (counted from its first /clock
with ``use_sim_time``: a time of 0 starts no timeout) it fails the server's activation
("Failed to activate NAME because transform from BASE to GLOBAL did not become available before
timeout"), so a lifecycle manager becomes active only once SLAM or AMCL publishes ``map``.
"""

import array
import collections
import math
import time

from amr_description.core.tf_buffer import TransformException
from amr_description.nav import costmap as cm
from amr_description.nav.grid_message import grid_from_message
from amr_description.ros.node import Node
from amr_description.ros.transforms import planar_pose
from geometry_msgs.msg import Point32
from geometry_msgs.msg import PolygonStamped
# imported with the module, not in the update: two costmaps updating on their own threads in
# one container imported it at once and one saw matplotlib half initialised ('no attribute
# rcParams'), which stopped the container
from matplotlib.path import Path
from nav2_msgs.msg import Costmap as CostmapMsg
from nav2_msgs.srv import ClearEntireCostmap
from nav2_msgs.srv import GetCostmap
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


class CostmapNode(Node):
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
        self._footprint()
        res = self.p['resolution']
        self.grid = cm.Costmap.empty(self.p['width'], self.p['height'], res,
                                     (self.p['origin_x'], self.p['origin_y']),
                                     self.p['global_frame'],
                                     self._unknown())
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
        if self.p['footprint'] not in ('', '[]'):
            try:
                points = cm.parse_footprint(self.p['footprint'])
            except ValueError as exc:
                self.get_logger().error(f'{exc}; using robot_radius')
        if points is None:
            points = cm.footprint_from_radius(self.p['robot_radius'])
        self.footprint = cm.pad_footprint(points, self.p['footprint_padding'])
        self.inscribed, self.circumscribed = cm.footprint_radii(self.footprint)

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
            self.create_service(ClearEntireCostmap, f'clear_entirely_{self.name}',
                                self._on_clear),
            self.create_service(GetCostmap, 'get_costmap', self._on_get),
            self.create_timer(1.0 / max(self.p['update_frequency'], 1e-3), self.update,
                              clock=Clock(clock_type=ClockType.STEADY_TIME)),
            self.create_timer(1.0 / max(self.p['publish_frequency'], 1e-3), self.publish)]

    def _parent_topic(self, topic):
        """Resolve a relative input topic in the server's namespace (Nav2's parent namespace)."""
        return topic if topic.startswith('/') else f'{self.parent_ns}/{topic}'

    def stop(self):
        """Remove what :meth:`start` made (the server's deactivate)."""
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

    def _roll(self, pose):
        g = self.grid
        res = g.resolution
        h, w = g.shape
        ox = math.floor((pose[0] - w * res / 2.0) / res) * res
        oy = math.floor((pose[1] - h * res / 2.0) / res) * res
        dx = int(round((ox - g.origin[0]) / res))
        dy = int(round((oy - g.origin[1]) / res))
        if dx or dy:
            moved = np.full_like(self.obstacles, self._unknown())
            src = self.obstacles[max(dy, 0):h + min(dy, 0), max(dx, 0):w + min(dx, 0)]
            moved[max(-dy, 0):max(-dy, 0) + src.shape[0],
                  max(-dx, 0):max(-dx, 0) + src.shape[1]] = src
            self.obstacles = moved
        self.grid = cm.Costmap(g.costs, res, (ox, oy), g.frame)

    def _queue(self, src):
        """Return ``src``'s scans waiting for their transform (oldest first, at most 10)."""
        return self.scans.setdefault(src, collections.deque(maxlen=SCAN_QUEUE))

    def _transformable(self, src, sp):
        """
        Return ``(scan, T)``: ``src``'s newest scan whose stamp TF can transform, or None.

        As the tf2 MessageFilter in front of Nav2's observation buffers: a scan waits for the
        transform at its own stamp, and the buffer keeps the newest one transformed. Older
        scans go; newer ones, still waiting, stay. Taking the latest transform instead (up to
        ``transform_tolerance``, 0.3 s, old) could turn the rays of a robot turning at
        1.8 rad/s 0.54 rad and mark obstacles where there are none.
        """
        queue = self._queue(src)
        for k in range(len(queue) - 1, -1, -1):
            scan = queue[k]
            frame = sp['sensor_frame'] or scan.header.frame_id
            stamp = scan.header.stamp.sec + scan.header.stamp.nanosec * 1e-9
            try:
                T, _ = self.tf.lookup(self.p['global_frame'], frame, stamp)
            except TransformException as exc:
                if k == 0 and not self._transform_pending(frame, stamp):
                    self.get_logger().warning(f"{sp['topic']}: {str(exc).strip()}",
                                              throttle_duration_sec=5.0)
                    queue.popleft()  # it never will be
                continue
            for _ in range(k + 1):
                queue.popleft()
            return scan, T
        return None

    def _transform_pending(self, frame, stamp):
        """Return True when TF's latest ``global_frame <- frame`` is older than ``stamp``."""
        try:
            _, latest = self.tf.lookup(self.p['global_frame'], frame)
        except TransformException:
            return True  # not connected yet: wait for it too
        return latest < stamp

    def _observe(self, params):
        layer = cm.Costmap(self.obstacles, self.grid.resolution, self.grid.origin)
        for src, sp in params['sources'].items():
            found = self._transformable(src, sp)
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
            self._clear_footprint(layer)

    def _clear_footprint(self, layer):
        x, y, yaw = self.robot
        c, s = math.cos(yaw), math.sin(yaw)
        poly = self.footprint @ np.array([[c, s], [-s, c]]) + (x, y)
        h, w = layer.shape
        mx, my, _ = layer.cells_of(poly)
        i0, i1 = np.clip([mx.min(), mx.max() + 1], 0, w)
        j0, j1 = np.clip([my.min(), my.max() + 1], 0, h)
        if i0 >= i1 or j0 >= j1:
            return
        ii, jj = np.meshgrid(np.arange(i0, i1), np.arange(j0, j1))
        cx, cy = layer.map_to_world(ii, jj)
        inside = Path(poly).contains_points(np.column_stack((cx.ravel(), cy.ravel())))
        layer.costs[jj.ravel()[inside], ii.ravel()[inside]] = cm.FREE_SPACE

    def update(self):
        """Run the layers in order into the master grid (the update timer)."""
        self.robot = self._robot_pose()
        if self.p['rolling_window']:
            if self.robot is None:
                return
            self._roll(self.robot)
        master = np.full(self.grid.shape, self._unknown(), np.uint8)
        for kind, layer, params in self.layers:
            if kind == 'static' and self.static is not None:
                self._paint_static(master)
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

    def _paint_static(self, master):
        g, static = self.grid, self.static
        if static.costs.shape == g.shape and static.origin == g.origin and \
                static.resolution == g.resolution:
            master[:] = static.costs  # the global costmap: the map's own geometry
            return
        h, w = g.shape
        ii, jj = np.meshgrid(np.arange(w), np.arange(h))
        cx, cy = g.map_to_world(ii, jj)
        mx, my, inside = static.cells_of(np.column_stack((cx.ravel(), cy.ravel())))
        flat = master.reshape(-1)
        flat[inside] = static.costs[my[inside], mx[inside]]

    # outputs
    def messages(self):
        """Return ``(OccupancyGrid, nav2_msgs/Costmap)`` of the master grid, stamped now."""
        g = self.grid
        now = self.get_clock().now().to_msg()
        grid = OccupancyGrid()
        grid.header.frame_id = g.frame
        grid.header.stamp = now
        grid.info.map_load_time = now
        grid.info.resolution = g.resolution
        grid.info.height, grid.info.width = g.shape
        grid.info.origin.position.x, grid.info.origin.position.y = g.origin
        grid.info.origin.orientation.w = 1.0
        grid.data = array.array('b', cm.to_occupancy(g.costs).ravel().tobytes())
        raw = CostmapMsg()
        raw.header = grid.header
        raw.metadata.map_load_time = raw.metadata.update_time = now
        raw.metadata.layer = 'master'
        raw.metadata.resolution = g.resolution
        raw.metadata.size_y, raw.metadata.size_x = g.shape
        raw.metadata.origin = grid.info.origin
        raw.data = array.array('B', g.costs.ravel().tobytes())
        return grid, raw

    def publish(self):
        """Publish the costmap, the raw costmap and the footprint (the publish timer)."""
        grid, raw = self.messages()
        self.costmap_pub.publish(grid)
        self.raw_pub.publish(raw)
        if self.robot is not None:
            x, y, yaw = self.robot
            c, s = math.cos(yaw), math.sin(yaw)
            msg = PolygonStamped()
            msg.header = grid.header
            msg.polygon.points = [Point32(x=float(x + c * px - s * py),
                                          y=float(y + s * px + c * py))
                                  for px, py in self.footprint]
            self.footprint_pub.publish(msg)

    def _on_clear(self, request, response):
        self.get_logger().info(f'Received request to clear entirely the {self.name}')
        self.obstacles = self._blank()
        self.update()
        return response

    def _on_get(self, request, response):
        response.map = self.messages()[1]
        return response
