# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim system plugins of a URDF's ``<gazebo>`` elements: names, parameters and defaults.

Read as gz-sim 8 reads them (``src/systems/diff_drive``, ``joint_state_publisher``,
``odometry_publisher``; docs/gazebo.md lists every element):

- names: a ``filename`` loses a ``lib`` prefix and a ``.so`` suffix, and the old
  ``ignition-gazebo-`` / ``ignition::gazebo::`` spellings become ``gz-sim-`` / ``gz::sim::``
  (gz-sim's ``SystemLoader``); a plugin is known by its class ``name`` or its ``filename``;
- defaults that name the model (``/model/<model>/cmd_vel``, ``<model>/odom``) are left
  ``None`` here and filled in by :func:`resolve_defaults` once the spawned entity's name is
  known;
- a relative topic gets a leading ``/`` (gz-transport resolves it against an empty
  namespace).

gz_ros2_control's plugin is :mod:`amr_description.core.gazebo.tags`'s. Every other plugin is
kept by name in :attr:`GazeboSystems.unknown`, to be reported once as not simulated.
"""

from dataclasses import dataclass
from dataclasses import field
import math

from amr_description.core.description.ros2_control_info import ComponentInfo
from amr_description.core.description.ros2_control_info import HardwareInfo
from amr_description.core.description.ros2_control_info import InterfaceInfo
from amr_description.core.gazebo.tags import is_control_plugin
from amr_description.core.gazebo.tags import tag_text

DIFF_DRIVE = 'gz::sim::systems::DiffDrive'
JOINT_STATE_PUBLISHER = 'gz::sim::systems::JointStatePublisher'
ODOMETRY_PUBLISHER = 'gz::sim::systems::OdometryPublisher'

FILENAMES = {'gz-sim-diff-drive-system': DIFF_DRIVE,
             'gz-sim-joint-state-publisher-system': JOINT_STATE_PUBLISHER,
             'gz-sim-odometry-publisher-system': ODOMETRY_PUBLISHER}
"""Normalised ``filename`` -> class name of the systems the simulator runs."""

SENSOR_SYSTEMS = {'gz-sim-sensors-system': 'gz::sim::systems::Sensors',
                  'gz-sim-imu-system': 'gz::sim::systems::Imu',
                  'gz-sim-navsat-system': 'gz::sim::systems::NavSat',
                  'gz-sim-contact-system': 'gz::sim::systems::Contact'}
"""gz-sim systems that make sensors run (rendering sensors, IMUs, navsat receivers, contact
sensors): Gazebo needs them, here every simulated ``<sensor>`` block runs without them
(docs/sensors.md); neither system nor warning."""


def is_sensor_system(plugin):
    """Return True for a ``<plugin>`` of one of :data:`SENSOR_SYSTEMS`."""
    name = normalize_class(plugin.get('name'))
    return name in SENSOR_SYSTEMS.values() or \
        normalize_filename(plugin.get('filename')) in SENSOR_SYSTEMS


LIMIT_KINDS = ('velocity', 'acceleration', 'jerk')


def normalize_filename(filename):
    """
    Return a plugin ``filename`` as gz-sim 8 looks it up: ``gz-sim-diff-drive-system``.

    ``libignition-gazebo-diff-drive-system.so`` -> ``gz-sim-diff-drive-system``.
    """
    name = (filename or '').strip()
    if name.startswith('lib'):
        name = name[3:]
    if name.endswith('.so'):
        name = name[:-3]
    if name.startswith('ignition-gazebo-'):
        name = 'gz-sim-' + name[len('ignition-gazebo-'):]
    for version in ('6', '7', '8'):  # ignition-gazebo6-..., gz-sim8-...
        for stem in ('gz-sim', 'ignition-gazebo'):
            if name.startswith(f'{stem}{version}-'):
                name = 'gz-sim-' + name[len(stem) + len(version) + 1:]
    return name


def normalize_class(name):
    """Return a plugin class ``name`` in gz-sim 8's spelling (``gz::sim::systems::X``)."""
    name = (name or '').strip()
    if name.startswith('ignition::gazebo::'):
        name = 'gz::sim::' + name[len('ignition::gazebo::'):]
    return name


def system_class(plugin):
    """Return the gz-sim class name a ``<plugin>`` element loads ('' when unknown)."""
    name = normalize_class(plugin.get('name'))
    if name in FILENAMES.values():
        return name
    return FILENAMES.get(normalize_filename(plugin.get('filename')), name)


def absolute_topic(topic):
    """Return a gz topic as gz-transport resolves it: a leading ``/`` added, '' kept."""
    topic = (topic or '').strip()
    return topic if not topic or topic.startswith('/') else '/' + topic


@dataclass
class DiffDriveParams:
    """
    gz-sim 8 DiffDrive's ``<plugin>`` elements (``DiffDrive.cc`` Configure).

    :param left_joints: every ``<left_joint>`` (repeatable, at least one).
    :param right_joints: every ``<right_joint>``.
    :param wheel_separation: m between the left and right wheels (default 1.0).
    :param wheel_radius: m (default 0.2).
    :param odom_publish_frequency: Hz of sim time of odometry and TF (default 50).
    :param topic: Twist command topic (default ``/model/<model>/cmd_vel``).
    :param odom_topic: Odometry topic (default ``/model/<model>/odometry``).
    :param tf_topic: TF topic (default ``/model/<model>/tf``).
    :param frame_id: odometry frame (default ``<model>/odom``).
    :param child_frame_id: robot frame (default ``<model>/<canonical link>``).
    :param linear: dict of linear limits, ``min_velocity`` ... ``max_jerk`` (m/s, m/s^2,
        m/s^3); absent keys are no limit.
    :param angular: the same for the yaw rate (rad/s, ...).
    """

    left_joints: list = field(default_factory=list)
    right_joints: list = field(default_factory=list)
    wheel_separation: float = 1.0
    wheel_radius: float = 0.2
    odom_publish_frequency: float = 50.0
    topic: str = None
    odom_topic: str = None
    tf_topic: str = None
    frame_id: str = None
    child_frame_id: str = None
    linear: dict = field(default_factory=dict)
    angular: dict = field(default_factory=dict)

    def joints(self):
        """Return the wheel joints, left then right (the joints the system commands)."""
        return list(self.left_joints) + list(self.right_joints)


@dataclass
class JointStatePublisherParams:
    """
    gz-sim 8 JointStatePublisher's ``<plugin>`` elements.

    :param joint_names: every ``<joint_name>``; empty: every moving joint of the model.
    :param topic: JointState topic (default ``/world/<world>/model/<model>/joint_state``).
    :param update_rate: Hz of sim time (``<update_rate>``, gz-sim 8.14); 0: every update of
        the simulator's systems.
    """

    joint_names: list = field(default_factory=list)
    topic: str = None
    update_rate: float = 0.0


@dataclass
class OdometryPublisherParams:
    """
    gz-sim 8 OdometryPublisher's ``<plugin>`` elements: ground-truth odometry.

    :param odom_frame: default ``<model>/odom``.
    :param robot_base_frame: default ``<model>/base_footprint``.
    :param odom_publish_frequency: Hz of sim time (default 50).
    :param odom_topic: Odometry topic (default ``/model/<model>/odometry``).
    :param odom_covariance_topic: Odometry with covariance (default
        ``/model/<model>/odometry_with_covariance``).
    :param tf_topic: TF topic (default ``/model/<model>/pose``).
    :param dimensions: 2 (x, y, yaw) or 3.
    :param xyz_offset: m added to the position in the odometry frame.
    :param rpy_offset: rad, rotation composed with the orientation.
    :param gaussian_noise: standard deviation of the noise added to the pose and twist.
    """

    odom_frame: str = None
    robot_base_frame: str = None
    odom_publish_frequency: float = 50.0
    odom_topic: str = None
    odom_covariance_topic: str = None
    tf_topic: str = None
    dimensions: int = 2
    xyz_offset: tuple = (0.0, 0.0, 0.0)
    rpy_offset: tuple = (0.0, 0.0, 0.0)
    gaussian_noise: float = 0.0


@dataclass
class GazeboSystems:
    """
    The gz-sim systems of one description.

    :param diff_drives: list of :class:`DiffDriveParams`.
    :param joint_state_publishers: list of :class:`JointStatePublisherParams`.
    :param odometry_publishers: list of :class:`OdometryPublisherParams`.
    :param unknown: class names (or filenames) of the other system plugins, in order.
    """

    diff_drives: list = field(default_factory=list)
    joint_state_publishers: list = field(default_factory=list)
    odometry_publishers: list = field(default_factory=list)
    unknown: list = field(default_factory=list)

    def __bool__(self):
        """Return True when the description has a system the simulator runs."""
        return bool(self.diff_drives or self.joint_state_publishers or self.odometry_publishers)

    def driven_joints(self):
        """Return the joints commanded by a system (DiffDrive wheels), in order, once each."""
        joints = []
        for params in self.diff_drives:
            joints += [j for j in params.joints() if j not in joints]
        return joints

    def hardware(self):
        """
        Return the joints the systems command as a ``<ros2_control>``-like block.

        One :class:`~amr_description.core.description.ros2_control_info.HardwareInfo` (the
        simulator's system) with a velocity command interface per driven joint, so the converter
        gives each its velocity servo as it does a ros2_control velocity joint; [] without one.
        """
        joints = self.driven_joints()
        if not joints:
            return []
        return [HardwareInfo(
            name='gz-sim DiffDrive', type='system', plugin='amr_description/MujocoSystem',
            joints=[ComponentInfo(joint, [InterfaceInfo('velocity')],
                                  [InterfaceInfo('position'), InterfaceInfo('velocity')])
                    for joint in joints])]


def _number(element, where, positive=False):
    text = tag_text(element)
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or (positive and value <= 0):
        kind = 'a number > 0' if positive else 'a number'
        raise ValueError(f'{where}<{element.tag}>: expected {kind}, found {text!r}')
    return value


def _children(plugin, tag):
    return [tag_text(element) for element in plugin.findall(tag)]


def _optional_text(plugin, tag):
    element = plugin.find(tag)
    return tag_text(element) if element is not None and tag_text(element) else None


def _optional_number(plugin, tag, where, default, positive=False):
    element = plugin.find(tag)
    return default if element is None else _number(element, where, positive)


def _read_diff_drive(plugin, where, joint_names):
    params = DiffDriveParams(left_joints=_children(plugin, 'left_joint'),
                             right_joints=_children(plugin, 'right_joint'))
    for side in ('left', 'right'):
        names = getattr(params, f'{side}_joints')
        if not names or not all(names):
            raise ValueError(f'{where}: <{side}_joint> is required (the wheel joints of the '
                             f'{side} side)')
        for name in names:
            if name not in joint_names:
                raise ValueError(f'{where}<{side}_joint>: joint {name!r} is not a moving joint '
                                 'of the URDF')
    params.wheel_separation = _optional_number(plugin, 'wheel_separation', where, 1.0, True)
    params.wheel_radius = _optional_number(plugin, 'wheel_radius', where, 0.2, True)
    params.odom_publish_frequency = _optional_number(plugin, 'odom_publish_frequency', where,
                                                     50.0)
    for tag in ('topic', 'odom_topic', 'tf_topic'):
        setattr(params, tag, absolute_topic(_optional_text(plugin, tag)) or None)
    params.frame_id = _optional_text(plugin, 'frame_id')
    params.child_frame_id = _optional_text(plugin, 'child_frame_id')
    for bound in ('min', 'max'):
        for kind in LIMIT_KINDS:  # <max_velocity> sets both, <max_linear_velocity> one
            key = f'{bound}_{kind}'
            if plugin.find(key) is not None:
                value = _number(plugin.find(key), where)
                params.linear[key] = params.angular[key] = value
    for bound in ('min', 'max'):
        for kind in LIMIT_KINDS:
            key = f'{bound}_{kind}'
            for channel in ('linear', 'angular'):
                element = plugin.find(f'{bound}_{channel}_{kind}')
                if element is not None:
                    getattr(params, channel)[key] = _number(element, where)
    return params


def _read_joint_state_publisher(plugin, where, joint_names):
    params = JointStatePublisherParams(joint_names=_children(plugin, 'joint_name'))
    for name in params.joint_names:
        if name not in joint_names:
            raise ValueError(f'{where}<joint_name>: joint {name!r} is not a moving joint of '
                             'the URDF')
    params.topic = absolute_topic(_optional_text(plugin, 'topic')) or None
    params.update_rate = _optional_number(plugin, 'update_rate', where, 0.0)
    return params


def _triple(plugin, tag, where):
    element = plugin.find(tag)
    if element is None:
        return (0.0, 0.0, 0.0)
    try:
        values = tuple(float(v) for v in tag_text(element).split())
    except ValueError:
        values = ()
    if len(values) != 3 or not all(map(math.isfinite, values)):
        raise ValueError(f'{where}<{tag}>: expected 3 numbers, found {tag_text(element)!r}')
    return values


def _read_odometry_publisher(plugin, where, joint_names):
    params = OdometryPublisherParams()
    params.odom_frame = _optional_text(plugin, 'odom_frame')
    params.robot_base_frame = _optional_text(plugin, 'robot_base_frame')
    params.odom_publish_frequency = _optional_number(plugin, 'odom_publish_frequency', where,
                                                     50.0)
    for tag in ('odom_topic', 'odom_covariance_topic', 'tf_topic'):
        setattr(params, tag, absolute_topic(_optional_text(plugin, tag)) or None)
    dimensions = _optional_number(plugin, 'dimensions', where, 2)
    if dimensions not in (2, 3):
        raise ValueError(f'{where}<dimensions>: expected 2 or 3, found {dimensions:g}')
    params.dimensions = int(dimensions)
    params.xyz_offset = _triple(plugin, 'xyz_offset', where)
    params.rpy_offset = _triple(plugin, 'rpy_offset', where)
    params.gaussian_noise = _optional_number(plugin, 'gaussian_noise', where, 0.0)
    return params


_READERS = {DIFF_DRIVE: ('diff_drives', _read_diff_drive),
            JOINT_STATE_PUBLISHER: ('joint_state_publishers', _read_joint_state_publisher),
            ODOMETRY_PUBLISHER: ('odometry_publishers', _read_odometry_publisher)}


def parse_gazebo_systems(root, moving_joints):
    """
    Return the :class:`GazeboSystems` of a URDF ``<robot>`` element.

    Only model-level plugins (``<gazebo>`` without ``reference``) are model systems, as in
    sdformat's URDF conversion; gz_ros2_control's plugin is left out (it is not a system the
    simulator runs here but the controller manager).

    :param root: the ``<robot>`` element (standard library or lxml).
    :param moving_joints: names of the URDF's non-fixed joints (a collection).
    :raises ValueError: one line naming the plugin and element: a missing ``<left_joint>``
        or ``<right_joint>``, a joint that is not a moving URDF joint, a value that is not a
        number (or not > 0 where gz-sim needs it).
    """
    systems = GazeboSystems()
    for gazebo in root.findall('gazebo'):
        for plugin in gazebo.findall('plugin'):
            if is_control_plugin(plugin) or is_sensor_system(plugin):
                continue
            name = system_class(plugin)
            if gazebo.get('reference') or name not in _READERS:
                systems.unknown.append(name or normalize_filename(plugin.get('filename'))
                                       or '?')
                continue
            where = f'<gazebo><plugin name="{plugin.get("name", "")}">'
            attribute, reader = _READERS[name]
            getattr(systems, attribute).append(reader(plugin, where, set(moving_joints)))
    return systems


def resolve_defaults(systems, model_name, canonical_link, world_name):
    """
    Fill the defaults that name the model, as gz-sim 8 does at Configure (in place).

    :param systems: the :class:`GazeboSystems` (a copy per spawned entity).
    :param model_name: the entity name (``/model/<model_name>/...``, ``<model_name>/odom``).
    :param canonical_link: the model's canonical link (the URDF root link).
    :param world_name: the world's name (``/world/<world_name>/model/...``).
    :returns: ``systems``.
    """
    model = f'/model/{model_name}'
    for params in systems.diff_drives:
        params.topic = params.topic or f'{model}/cmd_vel'
        params.odom_topic = params.odom_topic or f'{model}/odometry'
        params.tf_topic = params.tf_topic or f'{model}/tf'
        params.frame_id = params.frame_id or f'{model_name}/odom'
        params.child_frame_id = params.child_frame_id or f'{model_name}/{canonical_link}'
    for params in systems.joint_state_publishers:
        params.topic = params.topic or f'/world/{world_name}{model}/joint_state'
    for params in systems.odometry_publishers:
        params.odom_frame = params.odom_frame or f'{model_name}/odom'
        params.robot_base_frame = params.robot_base_frame or f'{model_name}/base_footprint'
        params.odom_topic = params.odom_topic or f'{model}/odometry'
        params.odom_covariance_topic = params.odom_covariance_topic or \
            f'{model}/odometry_with_covariance'
        params.tf_topic = params.tf_topic or f'{model}/pose'
    return systems


def frame_id_gz_to_ros(frame_id):
    """Return a gz frame id as ros_gz_bridge delivers it: ``::`` becomes ``/``."""
    return frame_id.replace('::', '/')
