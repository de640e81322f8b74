# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``amcl``: Nav2's adaptive Monte Carlo localization (Jazzy), a managed (lifecycle) node.

Parameters: Nav2's (``nav2_amcl/src/amcl_node.cpp``) with its defaults; the filter's are
:class:`~amr_description.nav.amcl.AmclParameters`, the node's :data:`NODE_PARAMETERS`. The
laser models ``likelihood_field``, ``beam`` and ``likelihood_field_prob`` (another value: one
warning line, and ``likelihood_field`` runs, as upstream's ``createLaserObject``); the motion
models ``nav2_amcl::DifferentialMotionModel`` and ``nav2_amcl::OmniMotionModel`` (another value
fails configure with one line, as pluginlib does). A parameter of the wrong type fails
configure with one line naming it; out-of-range values are mended with upstream's warnings
(``initParameters``: a negative ``laser_likelihood_max_dist``, ``max_particles`` or
``min_particles``, ``min_particles`` above ``max_particles``, ``resample_interval`` below 1).

Kept from one configure to the next, as upstream: the last pose set or published (the filter
resumes there unless ``always_reset_initial_pose``); with ``set_initial_pose``, cleanup writes
it into ``initial_pose.*``. ``initialpose`` is heard from configure on; a pose heard while
inactive is used on activate. While active, ``ros2 param set`` values are taken at once, as
upstream's dynamic parameters (:meth:`Amcl._on_set_parameters`).

On activate: ``map_topic`` (``map``, transient local) in; ``scan_topic`` (``scan``, sensor data
QoS) in, placed with TF (``odom_frame_id`` -> ``base_frame_id`` at the scan's stamp,
``base_frame_id`` -> the scan's frame; up to :data:`SCAN_QUEUE` scans wait for the odometry at
their stamps, as in upstream's ``tf2_ros::MessageFilter``); ``initialpose``
(PoseWithCovarianceStamped, reliable) in, refused with one warning unless in
``global_frame_id`` and finite (its covariance's ``[0] [1] [6] [7] [35]`` are used; a pose
stamped in the past is moved on by the odometry since its stamp);
``amcl_pose`` (transient local) and ``particle_cloud`` (nav2_msgs/ParticleCloud, best effort)
out; TF ``global_frame_id`` -> ``odom_frame_id`` stamped scan stamp + ``transform_tolerance``
(with ``tf_broadcast``); services ``reinitialize_global_localization``,
``request_nomotion_update`` (std_srvs/Empty) and ``set_initial_pose``
(nav2_msgs/SetInitialPose). Until a pose is known nothing is published and a warning repeats
every 2 s. With ``set_initial_pose`` the filter starts at ``initial_pose.{x, y, yaw}`` with
zero covariance. Bad scans (ranges not matching the angles, unknown frame) are dropped with one
warning line (at most every 5 s).
"""

import math

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav import amcl
from amr_description.nav.grid_message import grid_from_message
from amr_description.nav.laser_models import LASER_MODELS
from amr_description.nav.pose_graph import between
from amr_description.nav.pose_graph import compose
from amr_description.ros import shutdown
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.parameters import checked_value
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
from amr_description.ros.transforms import yaw_of
from geometry_msgs.msg import PoseWithCovarianceStamped
from nav2_msgs.msg import ParticleCloud
from nav2_msgs.srv import SetInitialPose
from nav_msgs.msg import OccupancyGrid
import numpy as np
from rcl_interfaces.msg import SetParametersResult
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import qos_profile_system_default
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Header
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)

NODE_PARAMETERS = {
    'base_frame_id': 'base_footprint', 'global_frame_id': 'map', 'odom_frame_id': 'odom',
    'set_initial_pose': False, 'initial_pose.x': 0.0, 'initial_pose.y': 0.0,
    'initial_pose.z': 0.0, 'initial_pose.yaw': 0.0, 'always_reset_initial_pose': False,
    'save_pose_rate': 0.5, 'tf_broadcast': True, 'transform_tolerance': 1.0,
    'scan_topic': 'scan', 'map_topic': 'map', 'first_map_only': False,
}
"""amcl's node parameters with Nav2's defaults (``nav2_amcl/src/amcl_node.cpp``)."""

SCAN_QUEUE = 10
"""Scans waiting for the odometry at their stamps (1 s at 10 Hz), as the queue of 10 of
amcl_node's ``tf2_ros::MessageFilter``."""


class Amcl(ManagedNode):
    """Node ``amcl``; see the module docstring."""

    def __init__(self, **kwargs):
        """Hold the params file's parameters; starts unconfigured (``kwargs``: rclpy's)."""
        super().__init__('amcl', automatically_declare_parameters_from_overrides=True,
                         **kwargs)
        self._active = []
        self._configured = []  # what configure creates: /initialpose is heard while inactive
        self._inputs = {}  # scan_topic and map_topic while active
        self._listener = None
        self.p = {}
        self._known = None  # (pose, 3x3 covariance) last set or published: kept over cleanup
        self._inactive_pose = None  # an /initialpose heard while inactive, used on activate

    def configure(self):
        """Read and check the parameters; build the filter."""
        self.get_logger().info('Configuring')
        defaults = {**NODE_PARAMETERS, **{n: getattr(amcl.AmclParameters(), n)
                                          for n in amcl.AmclParameters.names()}}
        self.p = read_parameters(self, defaults)
        unused = unused_parameters(self, defaults)
        if unused:
            self.get_logger().info('Parameters not used by this implementation: '
                                   + ', '.join(unused))
        self._check_models(self.p)
        self._semantic_checks()
        params = amcl.AmclParameters(**{n: self.p[n] for n in amcl.AmclParameters.names()})
        if params.max_particles < 1:
            raise ValueError(f"parameter 'max_particles': expected >= 1, got "
                             f'{params.max_particles}')
        self.filter = amcl.Amcl(params)
        self.tf_buffer = TransformBuffer()
        self._pending = StampedQueue(SCAN_QUEUE, self._process)
        self._last_tf = None
        self._sent_pose = False
        if self.p['always_reset_initial_pose']:
            self._known = None
        elif self._known is not None:  # as upstream's initOdometry: resume at the last pose
            self.filter.set_initial_pose(*self._known)
        self._configured = [self.create_subscription(
            PoseWithCovarianceStamped, 'initialpose', self._on_initial_pose,
            qos_profile_system_default)]

    def _check_models(self, p):
        """Fall back to the likelihood field as upstream; refuse an unknown motion model."""
        if p['laser_model_type'] not in LASER_MODELS:
            self.get_logger().warning(
                f"parameter 'laser_model_type': '{p['laser_model_type']}' is none of "
                f"{', '.join(LASER_MODELS)}; likelihood_field runs, as upstream's")
            p['laser_model_type'] = 'likelihood_field'
        if p['robot_model_type'] not in amcl.DIFFERENTIAL + amcl.OMNI:
            raise ValueError(f"parameter 'robot_model_type': only {amcl.DIFFERENTIAL[0]} and "
                             f'{amcl.OMNI[0]} are implemented, got '
                             f"'{p['robot_model_type']}'")

    def _on_set_parameters(self, parameters):
        """
        Take ``ros2 param set`` values while active (upstream's ``dynamicParametersCallback``).

        A value of the wrong type, an unknown motion model or ``min_particles`` above
        ``max_particles`` is refused with its reason and nothing changes; the filter takes the
        others from the next scan (:meth:`~amr_description.nav.amcl.Amcl.update_parameters`),
        and a new ``scan_topic`` or ``map_topic`` is subscribed to.
        """
        defaults = {**NODE_PARAMETERS, **{n: getattr(amcl.AmclParameters(), n)
                                          for n in amcl.AmclParameters.names()}}
        values = dict(self.p)
        try:
            for parameter in parameters:
                if parameter.name in defaults:
                    values[parameter.name] = checked_value(parameter.name, parameter.value,
                                                           defaults[parameter.name])
            self._check_models(values)
        except ValueError as exc:
            return SetParametersResult(successful=False, reason=str(exc))
        if values['min_particles'] > values['max_particles']:
            reason = ("You've set min_particles to be greater than max particles, this isn't "
                      'allowed.')
            self.get_logger().error(reason)
            return SetParametersResult(successful=False, reason=reason)
        topics = {n for n in ('scan_topic', 'map_topic') if values[n] != self.p[n]}
        self.p = values
        self.filter.update_parameters(values)
        for name in topics:
            self.destroy_entities([self._inputs[name]])
            self._subscribe(name)
        return SetParametersResult(successful=True)

    def _subscribe(self, name):
        """Subscribe to ``scan_topic`` or ``map_topic`` (kept in :attr:`_inputs`)."""
        if name == 'scan_topic':
            sub = self.create_subscription(LaserScan, self.p['scan_topic'], self._on_scan,
                                           qos_profile_sensor_data)
        else:
            sub = self.create_subscription(OccupancyGrid, self.p['map_topic'], self._on_map,
                                           LATCHED)
        self._inputs[name] = sub

    def _semantic_checks(self):
        """Mend out-of-range values with upstream's warnings (``initParameters``)."""
        p, warn = self.p, self.get_logger().warning
        fixes = [
            ('laser_likelihood_max_dist', p['laser_likelihood_max_dist'] < 0, 2.0,
             'negative', 'default value 2.0'),
            ('max_particles', p['max_particles'] < 0, 2000, 'negative', 'default value 2000'),
            ('min_particles', p['min_particles'] < 0, 500, 'negative', 'default value 500'),
        ]
        for name, bad, value, what, to in fixes:
            if bad:
                warn(f"You've set {name} to be {what}, this isn't allowed so it will be set to "
                     f'{to}.')
                p[name] = value
        if p['min_particles'] > p['max_particles']:
            warn("You've set min_particles to be greater than max particles, this isn't allowed "
                 'so max_particles will be set to min_particles.')
            p['max_particles'] = p['min_particles']
        if p['resample_interval'] <= 0:
            warn("You've set resample_interval to be zero or negative, this isn't allowed so it "
                 'will be set to default value to 1.')
            p['resample_interval'] = 1

    def activate(self):
        """Create the subscriptions, publishers, services and the reminder timer."""
        self.get_logger().info('Activating')
        p = self.p
        self._pose_pub = self.create_publisher(PoseWithCovarianceStamped, 'amcl_pose', LATCHED)
        self._cloud_pub = self.create_publisher(ParticleCloud, 'particle_cloud',
                                                qos_profile_sensor_data)
        self._tf_pub = self.create_publisher(TFMessage, '/tf', 100)
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)
        self._inputs = {}
        self._subscribe('map_topic')
        self._subscribe('scan_topic')
        self._active = [
            self._pose_pub, self._cloud_pub, self._tf_pub,
            self.create_service(Empty, 'reinitialize_global_localization', self._on_global),
            self.create_service(Empty, 'request_nomotion_update', self._on_nomotion),
            self.create_service(SetInitialPose, 'set_initial_pose', self._on_set_initial_pose),
            self.create_timer(2.0, self._remind)]
        if p['set_initial_pose']:
            self.filter.set_initial_pose(
                (p['initial_pose.x'], p['initial_pose.y'], p['initial_pose.yaw']),
                np.zeros((3, 3)))
        elif self._inactive_pose is not None:
            self._use_initial_pose(self._inactive_pose)
        self._inactive_pose = None
        self.watch_parameters(self._on_set_parameters)

    def deactivate(self):
        """Destroy what :meth:`activate` created."""
        self.get_logger().info('Deactivating')
        self.unwatch_parameters()
        self.destroy_entities(self._active + list(self._inputs.values()))
        self._active = []
        self._inputs = {}
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    def cleanup(self):
        """Stop hearing ``initialpose``; with ``set_initial_pose``, keep the last pose in it."""
        self.get_logger().info('Cleaning up')
        self.destroy_entities(self._configured)
        self._configured = []
        if self.p.get('set_initial_pose') and self._known is not None:
            pose = self._known[0]  # as upstream's on_cleanup: the next activate starts there
            self.set_parameters([Parameter('initial_pose.x', value=float(pose[0])),
                                 Parameter('initial_pose.y', value=float(pose[1])),
                                 Parameter('initial_pose.z', value=0.0),
                                 Parameter('initial_pose.yaw', value=float(pose[2]))])

    # --- inputs -----------------------------------------------------------------------------
    def _remind(self):
        if not self.filter.initialized:
            self.get_logger().warning(
                'AMCL cannot publish a pose or update the transform. Please set the initial '
                'pose...')

    def _on_map(self, msg):
        if self.p['first_map_only'] and self.filter.map is not None:
            return
        try:
            grid = grid_from_message(msg)
        except ValueError as exc:
            self.get_logger().error(f"{self.p['map_topic']}: {exc}; map ignored")
            return
        self.get_logger().info(f'Received a {grid.width} X {grid.height} map @ '
                               f'{grid.resolution:.3f} m/pix')
        self.filter.set_map(grid)

    def _on_initial_pose(self, msg):
        if not msg.header.frame_id:
            self.get_logger().warning('Received initial pose with empty frame_id. You should '
                                      'always supply a frame_id.')
            return
        frame = msg.header.frame_id.lstrip('/')
        if frame != self.p['global_frame_id']:
            self.get_logger().warning(
                f'Ignoring initial pose in frame "{frame}"; initial poses must be in the '
                f"global frame, \"{self.p['global_frame_id']}\"")
            return
        pose = msg.pose.pose
        c = msg.pose.covariance
        values = [pose.position.x, pose.position.y, pose.orientation.x, pose.orientation.y,
                  pose.orientation.z, pose.orientation.w, c[0], c[1], c[6], c[7], c[35]]
        if not all(math.isfinite(v) for v in values):
            self.get_logger().warning('initialpose: NaN or infinite value in the pose or its '
                                      'covariance; ignored')
            return
        if not self.is_active():
            self._inactive_pose = msg
            self.get_logger().warning('Received initial pose request, but AMCL is not yet in '
                                      'the active state')
            return
        self._use_initial_pose(msg)

    def _use_initial_pose(self, msg):
        """Start the filter at a checked ``initialpose`` message."""
        pose = msg.pose.pose
        c = msg.pose.covariance
        cov = np.array([[c[0], c[1], 0.0], [c[6], c[7], 0.0], [0.0, 0.0, c[35]]])
        mean = compose((pose.position.x, pose.position.y, yaw_of(pose.orientation)),
                       self._odometry_since(msg.header.stamp))
        self.get_logger().info(f'Setting pose ({self.get_clock().now().nanoseconds * 1e-9:.6f})'
                               f': {mean[0]:.3f} {mean[1]:.3f} {mean[2]:.3f}')
        self.filter.set_initial_pose(mean, cov)
        self._known = (np.asarray(mean, dtype=float), np.diag([c[0], c[7], c[35]]))
        self._sent_pose = False

    def _odometry_since(self, stamp):
        """
        Return how the base moved (its own frame, planar) from ``stamp`` to the newest odometry.

        amcl_node's ``handleInitialPose`` adds this to a pose stamped in the past, looked up
        through ``odom_frame_id`` to the node's now, which tf2 reaches only when the odometry
        is stamped ahead of it; here to the newest odometry instead. A pose stamped after the
        newest odometry (RViz's, the viewer's) is current: no change. Without the odometry at
        an older ``stamp``: no change, with upstream's warning once a transform has been sent.
        """
        p = self.p
        try:
            then, _ = self.tf_buffer.lookup(p['odom_frame_id'], p['base_frame_id'],
                                            stamp_seconds(stamp))
            latest, _ = self.tf_buffer.lookup(p['odom_frame_id'], p['base_frame_id'])
        except TransformException as exc:
            if self._last_tf is not None and not not_yet(exc):
                self.get_logger().warning(
                    f'Failed to transform initial pose in time ({str(exc).strip()})')
            return (0.0, 0.0, 0.0)
        return between(planar_pose(then), planar_pose(latest))

    def _on_set_initial_pose(self, request, response):
        self._on_initial_pose(request.pose)
        return response

    def _on_global(self, request, response):
        try:
            self.filter.global_localization()
            self.get_logger().info('Initializing with uniform distribution')
            self._sent_pose = False
        except ValueError as exc:
            self.get_logger().warning(f'reinitialize_global_localization: {exc}')
        return response

    def _on_nomotion(self, request, response):
        self.filter.request_nomotion_update()
        self.get_logger().info('Requesting no-motion update')
        return response

    def _on_scan(self, msg):
        if not self.filter.initialized or self.filter.map is None:
            return
        self._pending.add(msg)

    def _process(self, msg):
        """Use or drop ``msg``; return False while its odometry has not arrived yet."""
        p = self.p
        stamp = stamp_seconds(msg.header.stamp)
        expected = int(round((msg.angle_max - msg.angle_min) / msg.angle_increment)) + 1 \
            if msg.angle_increment and math.isfinite(msg.angle_increment) else -1
        if len(msg.ranges) != expected:
            self.get_logger().warning(
                f"{p['scan_topic']}: ranges has {len(msg.ranges)} readings, its angles "
                f'({msg.angle_min:g} to {msg.angle_max:g} by {msg.angle_increment:g}) need '
                f'{expected}; scan dropped', throttle_duration_sec=5.0)
            return True
        try:
            odom, _ = self.tf_buffer.lookup(p['odom_frame_id'], p['base_frame_id'], stamp)
            laser, _ = self.tf_buffer.lookup(p['base_frame_id'], msg.header.frame_id)
        except TransformException as exc:
            if not_yet(exc):
                return False  # wait for the odometry at the scan's stamp
            self.get_logger().warning(
                f"Failed to transform scan in frame '{msg.header.frame_id}': "
                f'{str(exc).strip()}', throttle_duration_sec=5.0)
            return True
        beams, rmax = self.filter.beams(np.asarray(msg.ranges, dtype=float), msg.angle_min,
                                        msg.angle_increment, msg.range_min, msg.range_max,
                                        planar_pose(laser))
        updated = self.filter.process(planar_pose(odom), beams, rmax)
        if updated or not self._sent_pose:
            if self.filter.pose is None:
                return True
            self._publish_pose(msg.header.stamp)
            self._publish_cloud(msg.header.stamp)
            self._last_tf = self.filter.map_to_odom
            self._sent_pose = True
        if p['tf_broadcast'] and self._last_tf is not None:
            t = stamp + p['transform_tolerance']
            self._tf_pub.publish(TFMessage(transforms=[planar_transform(
                p['global_frame_id'], p['odom_frame_id'], time_to_msg(t), self._last_tf)]))
        return True

    # --- outputs ----------------------------------------------------------------------------
    def _publish_pose(self, stamp):
        pose, cov = self.filter.pose, self.filter.covariance
        if not (np.all(np.isfinite(pose)) and np.all(np.isfinite(cov))):
            return
        msg = PoseWithCovarianceStamped()
        msg.header.stamp = stamp
        msg.header.frame_id = self.p['global_frame_id']
        msg.pose.pose.position.x, msg.pose.pose.position.y = float(pose[0]), float(pose[1])
        set_yaw(msg.pose.pose.orientation, float(pose[2]))
        c = [0.0] * 36
        c[0], c[1], c[6], c[7] = cov[0, 0], cov[0, 1], cov[1, 0], cov[1, 1]
        c[35] = cov[2, 2]
        msg.pose.covariance = [float(v) for v in c]
        self._pose_pub.publish(msg)
        self._known = (np.array(pose, dtype=float), np.diag([cov[0, 0], cov[1, 1], cov[2, 2]]))

    def _publish_cloud(self, stamp):
        header = Header(stamp=stamp, frame_id=self.p['global_frame_id'])
        self._cloud_pub.publish(particle_cloud_bytes(header, self.filter.filter.particles,
                                                     self.filter.filter.weights))


def particle_cloud_bytes(header, particles, weights):
    """
    Return a ``nav2_msgs/ParticleCloud`` serialized (CDR, little endian), ready to publish.

    rclpy publishes serialized messages as they are; building 2,000 ``Particle`` objects in
    Python and serializing them took more of AMCL's CPU than the filter. The bytes are the
    serialized cloud without particles, its sequence length set to N, padding to 8 bytes and
    N records of 8 float64 (``pose.position`` x y z, ``pose.orientation`` x y z w,
    ``weight``), the layout of a sequence of fixed-size structs in CDR (OMG DDS-XTypes 1.3,
    7.4.3; the stream's alignment counts from after its 4-byte encapsulation header).

    :param header: ``std_msgs/Header`` of the cloud.
    :param particles: (N, 3) x m, y m, yaw rad in the header's frame.
    :param weights: (N,) weights.
    :returns: bytes; ``rclpy.serialization.deserialize_message`` reads them back.
    """
    from rclpy.serialization import serialize_message
    empty = bytearray(serialize_message(ParticleCloud(header=header)))
    n = len(particles)
    empty[-4:] = n.to_bytes(4, 'little')
    padding = bytes((-(len(empty) - 4)) % 8)
    records = np.zeros((n, 8))
    records[:, 0:2] = particles[:, 0:2]
    records[:, 5] = np.sin(particles[:, 2] / 2.0)
    records[:, 6] = np.cos(particles[:, 2] / 2.0)
    records[:, 7] = weights
    return bytes(empty) + padding + records.astype('<f8').tobytes()


def main(args=None):
    """
    Run amcl until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(Amcl, args)


if __name__ == '__main__':
    main()
