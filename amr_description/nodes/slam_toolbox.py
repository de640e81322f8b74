# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``async_slam_toolbox_node``: slam_toolbox's online asynchronous mapper, node ``slam_toolbox``.

A managed (lifecycle) node as slam_toolbox's in Jazzy: it starts unconfigured. It reads
slam_toolbox's ``config/mapper_params_online_async.yaml`` unchanged: the parameters of
:class:`~amr_description.nav.slam.SlamParameters` and the node's own below, with slam_toolbox's
code defaults; the others it holds (the Ceres solver's, interactive mode, ...) are listed
once at configure ("not used by this implementation"), never an error. A parameter of the
wrong type fails configure with one line naming it.

- configure: parameters, the mapper (:class:`~amr_description.nav.slam.Mapper`); with
  ``map_file_name``, the serialized graph is loaded and continued from ``map_start_pose``
  (``[x, y, yaw]``) or its first node.
- activate: ``/scan`` (``scan_topic``, sensor-data QoS) in; ``map_name`` (``/map``) and
  ``<map_name>_metadata`` (reliable, transient local) every ``map_update_interval`` s;
  ``pose`` (PoseWithCovarianceStamped, depth 10) per processed scan;
  ``slam_toolbox/graph_visualization`` (the pose graph's markers, depth 1, with each map
  update: :mod:`amr_description.nav.graph_markers`); TF ``map_frame`` ->
  ``odom_frame`` every ``transform_publish_period`` s of wall time on a thread of its own (0:
  never), stamped with the newest scan's
  stamp + ``transform_timeout`` (every scan placed with TF, used by the mapper or not, as
  slam_toolbox's ``scan_header``), nothing before the first scan; the services
  ``slam_toolbox/save_map`` (runs ``ros2 run nav2_map_server map_saver_cli -f NAME --ros-args
  -p map_subscribe_transient_local:=true``, as slam_toolbox's ``map_saver.cpp``),
  ``serialize_map``, ``deserialize_map``, ``dynamic_map``, ``pause_new_measurements``,
  ``reset``, ``clear_changes``, ``manual_loop_closure``, ``toggle_interactive_mode``.
- The loop-closure assistant's services, as slam_toolbox's without its interactive markers:
  with ``enable_interactive_mode`` false each answers with upstream's warning; true,
  ``toggle_interactive_mode`` turns interactive mode on or off (the parameters
  ``interactive_mode`` and ``paused_processing``; while on, the graph is not drawn and the
  synchronous node holds its queue), ``manual_loop_closure`` warns that no node was moved
  (nodes cannot be moved without RViz's interactive markers), ``clear_changes`` logs
  upstream's line.
- A scan is placed with TF at its stamp: ``odom_frame`` -> ``base_frame`` and
  ``base_frame`` -> the scan's frame. Scans wait in arrival order for the odometry at their
  stamp, as in tf2's MessageFilter, but in a queue of :data:`SCAN_QUEUE` scans (1 s at 10 Hz)
  rather than upstream's ``scan_queue_size`` of 1: this node's Python TF listener has been
  measured 0.28 s behind the scans in a warehouse run, and with a queue of one a scan waits
  only until the next arrives, so a listener lagging more than a scan period would starve the
  mapper. A scan leaves the queue when it is used, when its odometry is older than the TF
  buffer holds, or when the queue is full (the oldest). Every ``throttle_scans``-th scan at
  least ``minimum_time_interval`` s after the last
  processed one goes to the mapper, which keeps it when the robot moved (see
  :mod:`amr_description.nav.slam`). Scans that cannot be used (ranges array not matching its
  angles, unknown frame, no odometry) are dropped with one warning line (at most every 5 s);
  NaN, negative and out-of-range readings are dropped ray by ray.

Source: slam_toolbox 2.8.3 ``src/slam_toolbox_common.cpp``, ``src/slam_toolbox_async.cpp``,
``src/map_saver.cpp``.
"""

import math
import threading

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav import slam
from amr_description.nav.graph_markers import graph_markers
from amr_description.nav.grid_message import occupancy_grid
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.map_saver_cli import map_saver_command
from amr_description.ros.map_saver_cli import run_map_saver
from amr_description.ros.parameters import read_parameters
from amr_description.ros.parameters import unused_parameters
from amr_description.ros.stamps import time_to_msg
from amr_description.ros.transforms import not_yet
from amr_description.ros.transforms import planar_pose
from amr_description.ros.transforms import planar_transform
from amr_description.ros.transforms import set_yaw
from amr_description.ros.transforms import stamp_seconds
from amr_description.ros.transforms import StampedQueue
from amr_description.ros.transforms import TransformListener
from amr_description.ros.worker_threads import OnRequest
from amr_description.ros.worker_threads import Periodic
from geometry_msgs.msg import PoseWithCovarianceStamped
from nav_msgs.msg import MapMetaData
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetMap
import numpy as np
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from slam_toolbox import srv
from tf2_msgs.msg import TFMessage
from visualization_msgs.msg import MarkerArray

LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)

SCAN_QUEUE = 10
"""Scans waiting for their odometry, at most (the oldest goes first when full)."""

NODE_PARAMETERS = {
    'odom_frame': 'odom', 'map_frame': 'map', 'base_frame': 'base_footprint',
    'scan_topic': '/scan', 'map_name': '/map', 'use_map_saver': True, 'mode': 'mapping',
    'map_file_name': '', 'map_start_pose': [0.0, 0.0, 0.0], 'map_start_at_dock': False,
    'debug_logging': False, 'throttle_scans': 1, 'transform_publish_period': 0.05,
    'map_update_interval': 10.0, 'minimum_time_interval': 0.5, 'transform_timeout': 0.5,
    'tf_buffer_duration': 30.0, 'use_lifecycle_manager': False,
    'position_covariance_scale': 1.0, 'yaw_covariance_scale': 1.0,
    'enable_interactive_mode': False,
}
"""The node's parameters with slam_toolbox 2.8.3's code defaults."""

ASSISTANT_PARAMETERS = ('paused_processing', 'interactive_mode')
"""Parameters the loop-closure assistant declares (false) and sets on toggle_interactive_mode."""


class SlamToolbox(ManagedNode):
    """Node ``slam_toolbox``; see the module docstring."""

    def __init__(self):
        """Hold the params file's parameters; the node starts unconfigured."""
        super().__init__('slam_toolbox',
                         automatically_declare_parameters_from_overrides=True)
        self.mapper = None
        self._active = []  # publishers, subscriptions, timers, services of the active state
        self.tf_buffer = None
        self._listener = None
        self.p = {}
        self._lock = threading.RLock()  # the mapper, for the sync node's processing thread
        self._map_to_odom = None  # the last map -> odom read from the mapper
        self._threads = []  # the map's and map -> odom's (worker_threads), while active

    def wants_bond(self):
        """Bond with a lifecycle manager only with ``use_lifecycle_manager`` (slam_toolbox)."""
        return bool(self.p.get('use_lifecycle_manager', False))

    # --- lifecycle --------------------------------------------------------------------------
    def configure(self):
        """Read the parameters and build the mapper (and load ``map_file_name``)."""
        self.get_logger().info('Configuring')
        defaults = {**NODE_PARAMETERS, **{n: getattr(slam.SlamParameters(), n)
                                          for n in slam.SlamParameters.names()}}
        values = read_parameters(self, defaults)
        unused = unused_parameters(self, {*defaults, *ASSISTANT_PARAMETERS})
        if unused:
            self.get_logger().info('Parameters not used by this implementation: '
                                   + ', '.join(unused))
        self.p = values
        self.params = slam.SlamParameters(**{n: values[n] for n in slam.SlamParameters.names()})
        if self.params.resolution <= 0.0:
            raise ValueError(f"parameter 'resolution': expected > 0, got {self.params.resolution}")
        if values['mode'] not in ('mapping', 'localization'):
            raise ValueError(f"parameter 'mode': expected mapping or localization, got "
                             f"'{values['mode']}'")
        self.mapper = self._new_mapper()
        if values['map_file_name']:
            self._load(values['map_file_name'], values['map_start_pose']
                       if not values['map_start_at_dock'] else None)
        self.tf_buffer = TransformBuffer(cache_time=values['tf_buffer_duration'])
        self._scans = 0
        self._last_stamp = None
        self._last_processed = None
        self._pending = StampedQueue(SCAN_QUEUE, self._process)
        self._paused = False
        self._interactive = False  # interactive mode on: the graph is not drawn, sync waits
        for name in ASSISTANT_PARAMETERS:
            if not self.has_parameter(name):
                self.declare_parameter(name, False)
        self._map_msg = None
        self._map_version = -1

    def _new_mapper(self):
        """Return an empty mapper (the localization node's: a Localizer)."""
        return slam.Mapper(self.params)

    def activate(self):
        """Create the publishers, subscriptions, timers and services."""
        self.get_logger().info('Activating')
        p = self.p
        self._map_pub = self.create_publisher(OccupancyGrid, p['map_name'], LATCHED)
        self._meta_pub = self.create_publisher(MapMetaData, p['map_name'] + '_metadata',
                                               LATCHED)
        self._pose_pub = self.create_publisher(PoseWithCovarianceStamped, 'pose', 10)
        self._tf_pub = self.create_publisher(TFMessage, '/tf', 100)
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)
        scan_sub = self.create_subscription(LaserScan, p['scan_topic'], self._on_scan,
                                            qos_profile_sensor_data)
        self._graph_pub = self.create_publisher(MarkerArray, 'slam_toolbox/graph_visualization', 1)
        self._active = [self._map_pub, self._meta_pub, self._pose_pub, self._tf_pub, scan_sub,
                        self._graph_pub,
                        self.create_timer(p['map_update_interval'], self._on_map_timer)]
        # off the executor, as slam_toolbox (on it, map -> odom went stale: docs/navigation.md)
        log = self.get_logger()
        self._map_worker = OnRequest('slam_map', self._publish_map_and_graph, log,
                                     'map not published')
        self._threads = [self._map_worker]
        if p['transform_publish_period'] > 0.0:
            self._threads.append(Periodic('slam_map_to_odom', p['transform_publish_period'],
                                          self._publish_tf, log, 'map -> odom not published'))
        for thread in self._threads:
            thread.start()
        prefix = 'slam_toolbox/'
        services = [
            (srv.SerializePoseGraph, 'serialize_map', self._on_serialize),
            (srv.DeserializePoseGraph, 'deserialize_map', self._on_deserialize),
            (GetMap, 'dynamic_map', self._on_dynamic_map),
            (srv.Pause, 'pause_new_measurements', self._on_pause),
            (srv.Reset, 'reset', self._on_reset),
            (srv.Clear, 'clear_changes', self._on_clear_changes),
            (srv.LoopClosure, 'manual_loop_closure', self._on_manual_loop_closure),
            (srv.ToggleInteractive, 'toggle_interactive_mode', self._on_toggle_interactive)]
        if p['use_map_saver']:
            services.append((srv.SaveMap, 'save_map', self._on_save_map))
        for kind, name, callback in services:
            self._active.append(self.create_service(kind, prefix + name, callback))

    def deactivate(self):
        """Destroy what :meth:`activate` created."""
        self.get_logger().info('Deactivating')
        self._stop_threads()
        self.destroy_entities(self._active)
        self._active = []
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    def cleanup(self):
        """Forget the map."""
        self.get_logger().info('Cleaning up')
        self.mapper = None
        self._map_to_odom = None

    def destroy_node(self):
        """Stop the map and ``map -> odom`` threads before the publishers go (Ctrl-C)."""
        self._stop_threads()
        return super().destroy_node()

    # --- scans ------------------------------------------------------------------------------
    def _on_scan(self, msg):
        # scans wait for the odometry at their stamp; each new scan lets the waiting ones try
        # again (no polling timer: it woke the node's executor 50 times a second)
        self._scans += 1
        wanted = not self._paused and not self._scans % max(1, self.p['throttle_scans'])
        self._pending.add((msg, wanted))

    def _process(self, queued):
        """Use or drop a queued scan; return False while its odometry has not arrived yet."""
        msg, wanted = queued
        stamp = stamp_seconds(msg.header.stamp)
        try:
            odom, _ = self.tf_buffer.lookup(self.p['odom_frame'], self.p['base_frame'], stamp)
            laser, _ = self.tf_buffer.lookup(self.p['base_frame'], msg.header.frame_id)
        except TransformException as exc:
            if not_yet(exc):
                return False  # wait for odometry to catch up with the scan
            self.get_logger().warning(
                f"Failed to compute odom pose of scan in frame '{msg.header.frame_id}': "
                f'{str(exc).strip()}', throttle_duration_sec=5.0)
            return True
        self._last_stamp = msg.header.stamp  # used or not: slam_toolbox's scan_header
        if not wanted:
            return True
        expected = int(round((msg.angle_max - msg.angle_min) / msg.angle_increment)) + 1 \
            if msg.angle_increment else 1
        if len(msg.ranges) != expected or not math.isfinite(msg.angle_increment):
            self.get_logger().warning(
                f"{self.p['scan_topic']}: ranges has {len(msg.ranges)} readings, its angles "
                f'({msg.angle_min:g} to {msg.angle_max:g} by {msg.angle_increment:g}) need '
                f'{expected}; scan dropped', throttle_duration_sec=5.0)
            return True
        if (self._last_processed is not None
                and stamp - self._last_processed < self.p['minimum_time_interval']):
            return True
        scan = slam.Scan(np.asarray(msg.ranges, dtype=float), msg.angle_min,
                         msg.angle_increment, msg.range_min, msg.range_max, planar_pose(laser))
        self._use(planar_pose(odom), scan, msg.header.stamp)
        return True

    def _use(self, odom, scan, header_stamp):
        """Give the mapper a scan at odometry pose ``odom`` now (:meth:`_match`)."""
        if self._match(odom, scan, header_stamp):
            self._last_processed = stamp_seconds(header_stamp)

    def _match(self, odom, scan, header_stamp):
        """
        Give the mapper a scan; publish ``pose`` if it kept it.

        :param odom: (x m, y m, yaw rad) of ``base_frame`` in ``odom_frame`` at the scan.
        :param scan: the mapper's scan (:mod:`amr_description.nav.slam`).
        :param header_stamp: the scan's ``builtin_interfaces/Time``.
        :returns: True when the mapper kept the scan.
        """
        with self._lock:
            added = self.mapper.process(odom, scan, stamp_seconds(header_stamp))
            pose = self.mapper.pose(odom)
        if added:
            self._publish_pose(header_stamp, pose)
        return added

    def _interactive_changed(self):
        """Act on interactive mode toggled (a hook: the synchronous node wakes its thread)."""

    def _publish_pose(self, stamp, pose):
        msg = PoseWithCovarianceStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = self.p['map_frame']
        msg.pose.pose.position.x, msg.pose.pose.position.y = float(pose[0]), float(pose[1])
        set_yaw(msg.pose.pose.orientation, float(pose[2]))
        cov = [0.0] * 36
        cov[0] = cov[7] = slam.LINK_SIGMA[0] ** 2 * self.p['position_covariance_scale']
        cov[35] = slam.LINK_SIGMA[2] ** 2 * self.p['yaw_covariance_scale']
        msg.pose.covariance = cov
        self._pose_pub.publish(msg)

    def _stop_threads(self):
        """Stop and join the map and ``map -> odom`` threads, if they run."""
        threads, self._threads = self._threads, []
        for thread in threads:
            thread.stop()

    def _publish_tf(self):
        """
        Publish ``map -> odom``, stamped with the newest scan + ``transform_timeout``.

        Read from the mapper when nothing holds it, else the last one read is sent again, as
        slam_toolbox's thread sends ``map_to_odom_`` while a scan is matched.
        """
        if self._lock.acquire(blocking=False):
            try:
                if self.mapper is not None:
                    self._map_to_odom = self.mapper.map_to_odom()
            finally:
                self._lock.release()
        stamp, map_to_odom = self._last_stamp, self._map_to_odom
        if stamp is None or map_to_odom is None:
            return
        t = stamp_seconds(stamp) + self.p['transform_timeout']
        self._tf_pub.publish(TFMessage(transforms=[planar_transform(
            self.p['map_frame'], self.p['odom_frame'], time_to_msg(t), map_to_odom)]))

    # --- the map ----------------------------------------------------------------------------
    def _current_map(self):
        """Return the OccupancyGrid of the graph now (rebuilt when keyframes changed)."""
        with self._lock:
            if self.mapper is None or not self.mapper.keyframes:
                return None
            version = (len(self.mapper.keyframes), self.mapper.loop_closures)
            if version != self._map_version:
                grid = self.mapper.occupancy()
                stamp = self._last_stamp or self.get_clock().now().to_msg()
                self._map_msg = occupancy_grid(grid, self.p['map_frame'], stamp)
                self._map_version = version
            return self._map_msg

    def _on_map_timer(self):
        self._map_worker.request()  # every map_update_interval of the node's clock

    def _publish_map_and_graph(self):
        self._publish_map()
        with self._lock:
            if self.mapper is None or not len(self.mapper.graph) or self._interactive:
                return
            markers = graph_markers(self.mapper.graph.poses, self.mapper.graph.edges,
                                    self.p['map_frame'], self.get_clock().now().to_msg())
        self._graph_pub.publish(markers)

    def _publish_map(self):
        msg = self._current_map()
        if msg is not None:
            self._map_pub.publish(msg)
            self._meta_pub.publish(msg.info)

    # --- services ---------------------------------------------------------------------------
    def _on_save_map(self, request, response):
        if self._current_map() is None:
            self.get_logger().warning('Map Saver: Cannot save map, no map yet received on '
                                      f"topic {self.p['map_name']}.")
            response.result = srv.SaveMap.Response.RESULT_NO_MAP_RECEIEVD
            return response
        self._publish_map()
        try:
            cmd = map_saver_command(request.name.data, self.get_namespace())
        except FileNotFoundError as exc:
            self.get_logger().error(f'Map Saver: {exc}')
            response.result = srv.SaveMap.Response.RESULT_UNDEFINED_FAILURE
            return response
        self.get_logger().info('Map Saver: ' + ' '.join(cmd[1:]))
        done = run_map_saver(cmd)
        response.result = (srv.SaveMap.Response.RESULT_SUCCESS if done.returncode == 0
                           else srv.SaveMap.Response.RESULT_UNDEFINED_FAILURE)
        return response

    def _on_serialize(self, request, response):
        try:
            with self._lock:
                slam.save_graph(self.mapper, request.filename)
            response.result = srv.SerializePoseGraph.Response.RESULT_SUCCESS
        except OSError as exc:
            self.get_logger().error(f'serialize_map: {exc}')
            response.result = srv.SerializePoseGraph.Response.RESULT_FAILED_TO_WRITE_FILE
        return response

    def _load(self, stem, start_pose):
        mapper = slam.load_graph(stem, self.params)
        pose = mapper.graph.poses[0] if start_pose is None else np.asarray(start_pose, float)
        if len(pose) != 3:
            raise ValueError(f'map_start_pose: expected [x, y, theta], got {list(pose)}')
        with self._lock:
            what = self._start(mapper, pose)
            self._map_version = -1  # the next map update publishes the loaded graph's map
        self.get_logger().info(f'Loaded pose graph {stem}: {len(mapper.graph)} nodes, '
                               f'{what} ({pose[0]:g}, {pose[1]:g}, {pose[2]:g})')

    def _start(self, mapper, pose):
        """Continue the loaded ``mapper`` at map ``pose``; return what the log line says."""
        mapper.restart_at(pose)
        self.mapper = mapper
        return 'starting at'

    def _on_deserialize(self, request, response):
        kind = srv.DeserializePoseGraph.Request
        if request.match_type == kind.LOCALIZE_AT_POSE:
            self.get_logger().error('Requested a localization deserialization in non-'
                                    'localization mode.')
            return response
        if request.match_type not in (kind.START_AT_FIRST_NODE, kind.START_AT_GIVEN_POSE):
            self.get_logger().error('Deserialization called without valid processor type '
                                    'set. Undefined behavior!')
            return response
        start = None
        if request.match_type == kind.START_AT_GIVEN_POSE:
            p = request.initial_pose
            start = (p.x, p.y, p.theta)
        try:
            self._load(request.filename, start)
        except ValueError as exc:
            self.get_logger().error(f'deserialize_map: {exc}')
        return response

    def _on_dynamic_map(self, request, response):
        msg = self._current_map()
        if msg is not None:
            response.map = msg
        return response

    def _on_pause(self, request, response):
        self._paused = not self._paused
        self.get_logger().info(f"Toggled to {'pause' if self._paused else 'active'} taking "
                               'new measurements.')
        response.status = True
        return response

    def _on_reset(self, request, response):
        with self._lock:
            self.mapper = self._new_mapper()
            self._map_version = -1
            self._map_to_odom = None
        self._last_stamp = None
        self._paused = bool(request.pause_new_measurements)
        response.result = srv.Reset.Response.RESULT_SUCCESS
        return response

    # --- the loop-closure assistant's services (no interactive markers: nodes cannot move) ---
    def _interactive_enabled(self, what):
        if not self.p['enable_interactive_mode']:
            self.get_logger().warning(f'Called {what} with interactive mode disabled. '
                                      'Ignoring.')
        return self.p['enable_interactive_mode']

    def _on_toggle_interactive(self, request, response):
        if self._interactive_enabled('toggle interactive mode'):
            self._interactive = not self._interactive
            self.get_logger().info('SlamToolbox: Toggling '
                                   f"{'on' if self._interactive else 'off'} interactive mode.")
            self.set_parameters([Parameter('interactive_mode', value=self._interactive),
                                 Parameter('paused_processing', value=self._interactive)])
            self._interactive_changed()
        return response

    def _on_manual_loop_closure(self, request, response):
        if self._interactive_enabled('manual loop closure'):
            self.get_logger().warning('No moved nodes to attempt manual loop closure.')
        return response

    def _on_clear_changes(self, request, response):
        if self._interactive_enabled('Clear changes'):
            self.get_logger().info('LoopClosureAssistant: Clearing manual loop closure nodes.')
        return response


def main(args=None):
    """
    Run the SLAM node until Ctrl-C (one executor thread; TF is heard on its own thread).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(SlamToolbox, args)


if __name__ == '__main__':
    main()
