# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``<gazebo reference="LINK"><sensor>`` blocks of a robot description, as Harmonic reads them.

Every ``<sensor>`` gets the elements all kinds share (SDF 1.11's ``sensor.sdf`` of
sdformat 14): ``<update_rate>`` 0 (every physics step), ``<always_on>`` false, ``<topic>``
unset (gz's default name, :func:`default_topic`), ``<pose>`` ``x y z roll pitch yaw`` in the
link frame (m, rad; ``degrees="true"``), ``<gz_frame_id>`` (gz-sensors 8
``Sensor::PopulateFromSDF``; :data:`FRAME_TAGS`); then its kind's own element is read by the
reader that :data:`~amr_description.core.gazebo.sensor_kinds.SENSOR_KINDS` pairs with the kind
(lidar, IMU, cameras, navsat, contact: their elements and defaults are documented there).

A sensor that cannot be simulated as written is left out with one line naming the sensor and
the field (:attr:`SensorBlocks.messages`); the robot keeps its other sensors.
"""

from dataclasses import dataclass
from dataclasses import field
import math

from amr_description.core.gazebo.sensor_kinds import CameraSpec
from amr_description.core.gazebo.sensor_kinds import element_bool
from amr_description.core.gazebo.sensor_kinds import element_number
from amr_description.core.gazebo.sensor_kinds import element_text
from amr_description.core.gazebo.sensor_kinds import ImuSpec
from amr_description.core.gazebo.sensor_kinds import KINDS
from amr_description.core.gazebo.sensor_kinds import LidarSpec
from amr_description.core.gazebo.sensor_kinds import NavSatSpec
from amr_description.core.gazebo.sensor_kinds import read_kind
from amr_description.core.gazebo.sensor_kinds import SensorError
from amr_description.core.ros_names import topic_name_problem

SDF_SENSOR_TYPES = (
    'air_pressure', 'air_speed', 'altimeter', 'boundingbox_camera', 'camera', 'contact',
    'custom', 'depth', 'depth_camera', 'force_torque', 'gps', 'gpu_lidar', 'gpu_ray', 'imu',
    'lidar', 'logical_camera', 'magnetometer', 'multicamera', 'navsat', 'ray', 'rfid',
    'rfidtag', 'rgbd', 'rgbd_camera', 'segmentation_camera', 'sonar', 'thermal',
    'thermal_camera', 'wide_angle_camera', 'wireless_receiver', 'wireless_transmitter')
"""Sensor types SDF 1.11 names (``sensor.sdf``)."""

CAMERA_KINDS = ('camera', 'depth', 'rgbd')
"""Kinds rendered by a camera (``<camera>`` element)."""

DEFAULT_TOPIC_SUFFIX = {'lidar': 'scan', 'imu': 'imu', 'camera': 'image',
                        'depth': 'depth_image', 'rgbd': '', 'navsat': 'navsat',
                        'contact': 'contact'}
"""Last part of gz-sim's default topic per kind (gz-sim 8 ``RenderUtil.cc``, ``Imu.cc``);
an RGB-D camera's topics are below its base name (``<base>/image``, ...)."""

FRAME_TAGS = ('gz_frame_id', 'ignition_frame_id', 'frame_id')
"""``<sensor>`` children naming the frame id, first found wins: gz-sensors 8 reads only
``gz_frame_id``; ``ignition_frame_id`` is Fortress's and ``frame_id`` the one TurtleBot
descriptions write (both ignored by Harmonic, which then says ``model/link/sensor``)."""


@dataclass
class SensorBlock:
    """
    One ``<sensor>`` of a ``<gazebo reference="LINK">`` block.

    :param name: ``<sensor name>``.
    :param type: ``<sensor type>`` as written.
    :param link: the URDF link named by ``reference``.
    :param update_rate: Hz of sim time; 0 means every physics step.
    :param always_on: ``<always_on>``.
    :param topic: ``<topic>``, '' when unset.
    :param frame_id: ``<gz_frame_id>`` (else ``<ignition_frame_id>``, else ``<frame_id>``),
        '' when unset.
    :param xyz: (3,) m, ``<pose>`` in the link frame.
    :param rpy: (3,) rad, ``<pose>`` fixed-axis roll pitch yaw.
    :param lidar: :class:`LidarSpec` of a lidar, else None.
    :param imu: :class:`ImuSpec` of an IMU, else None.
    :param camera: :class:`CameraSpec` of a camera, depth or RGB-D camera, else None.
    :param navsat: :class:`NavSatSpec` of a navsat sensor, else None.
    :param contact_collision: ``<contact><collision>`` of a contact sensor (the SDF name of
        one collision of the link, :func:`collision_names`), else ''.
    """

    name: str
    type: str  # noqa: A003 - SDF's attribute name
    link: str
    update_rate: float = 0.0
    always_on: bool = False
    topic: str = ''
    frame_id: str = ''
    xyz: tuple = (0.0, 0.0, 0.0)
    rpy: tuple = (0.0, 0.0, 0.0)
    lidar: LidarSpec = None
    imu: ImuSpec = None
    camera: CameraSpec = None
    navsat: NavSatSpec = None
    contact_collision: str = ''

    @property
    def kind(self):
        """Return the simulator's name of the type (a value of KINDS), None if not simulated."""
        return KINDS.get(self.type)


@dataclass
class SensorBlocks:
    """
    The sensors of a description.

    :param sensors: list of :class:`SensorBlock` the simulator simulates, document order.
    :param messages: one line per sensor left out (not simulated, or a field at fault).
    """

    sensors: list = field(default_factory=list)
    messages: list = field(default_factory=list)


def _pose(sensor, where):
    element = sensor.find('pose')
    if element is None or not (element.text or '').strip():
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    try:
        values = [float(v) for v in element.text.split()]
    except ValueError:
        values = []
    if len(values) != 6 or not all(math.isfinite(v) for v in values):
        raise SensorError(f'{where}<pose>: expected 6 numbers x y z roll pitch yaw, found '
                          f'{element.text.strip()!r}')
    rpy = values[3:]
    if (element.get('degrees') or '').strip().lower() in ('true', '1'):
        rpy = [math.radians(v) for v in rpy]
    return tuple(values[:3]), tuple(rpy)


def read_sensor(sensor, link):
    """
    Return the :class:`SensorBlock` of one ``<sensor>`` element on URDF link ``link``.

    :raises SensorError: one line naming the sensor and the field at fault (module
        docstring), or saying that its type is not simulated.
    """
    name = sensor.get('name') or ''
    kind_name = sensor.get('type') or ''
    where = f'sensor {name!r}: '
    if not name:
        raise SensorError(f'a <sensor> on link {link!r} has no name')
    if kind_name not in KINDS:
        known = 'of' if kind_name in SDF_SENSOR_TYPES else 'of unknown'
        raise SensorError(f'sensor {name!r} {known} type {kind_name!r} is not simulated')
    xyz, rpy = _pose(sensor, where)
    block = SensorBlock(
        name, kind_name, link,
        update_rate=element_number(sensor, 'update_rate', 0.0, where, low=0.0),
        always_on=element_bool(sensor, 'always_on', False, where),
        topic=(element_text(sensor, 'topic', '') or '').strip(),
        frame_id=next((text.strip() for text in (element_text(sensor, tag, '')
                                                 for tag in FRAME_TAGS)
                       if text and text.strip()), ''),
        xyz=xyz, rpy=rpy)
    if block.topic == '__default__':
        block.topic = ''
    if block.topic:
        problem = topic_name_problem(block.topic)
        if problem:
            raise SensorError(f'{where}<topic>: {block.topic!r} is not a valid ROS topic name: '
                              f'{problem}')
    elif topic_name_problem(f'/sensor/{name}'):
        raise SensorError(f"sensor {name!r}: its name makes no valid ROS topic (gz-sim's "
                          f'default topic ends in .../sensor/<name>/...): '
                          f'{topic_name_problem(name)}; set <topic>')
    read_kind(block.kind, sensor, where, block)
    return block


def parse_sensors(root, links):
    """
    Return the sensor blocks of a URDF (:class:`SensorBlocks`).

    :param root: the ``<robot>`` element.
    :param links: the URDF link names (a container).
    """
    result = SensorBlocks()
    names, topics = set(), {}
    for gazebo in root.findall('gazebo'):
        reference = gazebo.get('reference')
        for sensor in gazebo.findall('sensor'):
            name = sensor.get('name') or ''
            if not reference or reference not in links:
                shown = f'link {reference!r}' if reference else 'no link (no reference)'
                result.messages.append(f'sensor {name!r}: <gazebo reference> names {shown} '
                                       'that does not exist; the sensor is skipped')
                continue
            try:
                block = read_sensor(sensor, reference)
            except SensorError as exc:
                text = str(exc)
                result.messages.append(text if text.endswith('not simulated')
                                       else f'{text}; the sensor is skipped')
                continue
            if block.name in names:
                result.messages.append(f'sensor {block.name!r}: a second sensor of that name; '
                                       'the sensor is skipped')
                continue
            if block.topic and block.topic.lstrip('/') in topics:
                first = topics[block.topic.lstrip('/')]
                result.messages.append(f'sensor {block.name!r}: <topic> {block.topic!r} is '
                                       f'already the topic of sensor {first!r} (one topic, one '
                                       'sensor); the sensor is skipped')
                continue
            if block.topic:
                topics[block.topic.lstrip('/')] = block.name
            names.add(block.name)
            result.sensors.append(block)
    return result


def lumped_link(model, link, tags):
    """
    Return the link a sensor's link is merged into by sdformat's fixed-joint lumping.

    sdformat 14's URDF reader merges the child of a fixed joint into its parent unless the
    joint's ``<gazebo reference>`` sets ``preserveFixedJoint`` or
    ``disableFixedJointLumping`` (``src/parser_urdf.cc``).

    :param model: the :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param link: a link name of the model.
    :param tags: the ``<gazebo reference>`` tags, dict reference -> dict tag -> value.
    """
    seen = set()
    while link in model.parent_joint and link not in seen:
        seen.add(link)
        joint = model.parent_joint[link]
        if joint.type != 'fixed':
            break
        joint_tags = tags.get(joint.name, {})
        if any(joint_tags.get(t, '').strip().lower() in ('true', '1')
               for t in ('preserveFixedJoint', 'disableFixedJointLumping')):
            break
        link = joint.parent
    return link


def default_topic(world, model_name, link, block):
    """
    Return gz-sim's topic of a sensor without ``<topic>``.

    ``/world/<world>/model/<model>/link/<link>/sensor/<sensor>/<scan|imu|image|depth_image>``
    (gz-sim 8 ``RenderUtil.cc`` and ``Imu.cc``), ``link`` being the link after lumping
    (:func:`lumped_link`); an RGB-D camera's base name ends at ``<sensor>``.
    """
    base = f'/world/{world}/model/{model_name}/link/{link}/sensor/{block.name}'
    suffix = DEFAULT_TOPIC_SUFFIX[block.kind]
    return f'{base}/{suffix}' if suffix else base


def collision_names(model, tags):
    """
    Return the SDF names of a URDF's collisions: dict name -> (URDF link, collision index).

    sdformat 14's URDF reader names a link's collisions ``<link>_collision`` (the first),
    ``<link>_collision_<i>`` (the i-th after it) unless the URDF names them; a collision of a
    link lumped into its parent by a fixed joint (:func:`lumped_link`) becomes
    ``<parent>_fixed_joint_lump__<link>_collision`` (and ``_<i>``). Every form is accepted,
    as is the URDF ``<collision name>`` itself.

    :param model: the :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param tags: the ``<gazebo reference>`` tags (for the lumping).
    """
    names = {}
    for link_name, link in model.links.items():
        parent = lumped_link(model, link_name, tags)
        for index, collision in enumerate(link.collisions):
            suffix = '' if index == 0 else f'_{index}'
            forms = [f'{link_name}_collision{suffix}']
            if parent != link_name:
                forms.append(f'{parent}_fixed_joint_lump__{link_name}_collision{suffix}')
            if collision.name:
                forms.append(collision.name)
            for form in forms:
                names.setdefault(form, (link_name, index))
    return names
