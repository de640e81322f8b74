# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``<gazebo reference="LINK"><sensor>`` blocks of a robot description, as Harmonic reads them.

Elements and defaults are SDF 1.11's (``sensor.sdf``, ``lidar.sdf``, ``imu.sdf``,
``noise.sdf`` of sdformat 14): ``<update_rate>`` 0 (every physics step), ``<always_on>``
false, ``<topic>`` unset (gz's default name, :func:`default_topic`), ``<pose>`` ``x y z roll
pitch yaw`` in the link frame (m, rad; ``degrees="true"``), ``<gz_frame_id>`` (gz-sensors 8
``Sensor::PopulateFromSDF``; :data:`FRAME_TAGS`). A lidar is ``<lidar>`` or its older name
``<ray>``: ``<scan><horizontal>`` and optional ``<vertical>`` (``samples`` 640 / 1,
``resolution`` 1, ``min_angle``/``max_angle`` 0), ``<range>`` (``min``, ``max``,
``resolution``) and a
``<noise>`` whose type is a child element; an IMU has ``<angular_velocity>`` and
``<linear_acceleration>``, each ``<x>/<y>/<z>`` holding a ``<noise type="...">`` (the type
is an attribute there) with ``mean``, ``stddev``, ``bias_mean``, ``bias_stddev`` and
``precision``, and ``<enable_orientation>`` (true). A camera (``camera``, ``depth_camera`` /
``depth``, ``rgbd_camera`` / ``rgbd``) has ``<camera>``: ``horizontal_fov`` 1.047 rad,
``<image>`` ``width`` 320, ``height`` 240, ``format`` R8G8B8, ``<clip>`` ``near`` 0.1 m and
``far`` 100 m, ``<depth_camera><clip>`` for the depth image, ``<noise>`` (type a child
element), ``<lens><intrinsics>``, ``<optical_frame_id>`` and ``<camera_info_topic>``
(:class:`CameraSpec`).

A sensor that cannot be simulated as written is left out with one line naming the sensor and
the field (:attr:`SensorBlocks.messages`); the robot keeps its other sensors.
"""

from dataclasses import dataclass
from dataclasses import field
import math

from amr_description.core.gazebo_tags import tag_text

SDF_SENSOR_TYPES = (
    'air_pressure', 'air_speed', 'altimeter', 'boundingbox_camera', 'camera', 'contact',
    'custom', 'depth', 'depth_camera', 'force_torque', 'gps', 'gpu_lidar', 'gpu_ray', 'imu',
    'lidar', 'logical_camera', 'magnetometer', 'multicamera', 'navsat', 'ray', 'rfid',
    'rfidtag', 'rgbd', 'rgbd_camera', 'segmentation_camera', 'sonar', 'thermal',
    'thermal_camera', 'wide_angle_camera', 'wireless_receiver', 'wireless_transmitter')
"""Sensor types SDF 1.11 names (``sensor.sdf``)."""

KINDS = {'gpu_lidar': 'lidar', 'lidar': 'lidar', 'ray': 'lidar', 'gpu_ray': 'lidar',
         'imu': 'imu', 'camera': 'camera', 'depth_camera': 'depth', 'depth': 'depth',
         'rgbd_camera': 'rgbd', 'rgbd': 'rgbd', 'navsat': 'navsat', 'contact': 'contact'}
"""Simulated sensor types -> the simulator's kind: every lidar type is ray-cast."""

CAMERA_KINDS = ('camera', 'depth', 'rgbd')
"""Kinds rendered by a camera (``<camera>`` element)."""

DEFAULT_TOPIC_SUFFIX = {'lidar': 'scan', 'imu': 'imu', 'camera': 'image',
                        'depth': 'depth_image', 'rgbd': '', 'navsat': 'navsat',
                        'contact': 'contact'}
"""Last part of gz-sim's default topic per kind (gz-sim 8 ``RenderUtil.cc``, ``Imu.cc``);
an RGB-D camera's topics are below its base name (``<base>/image``, ...)."""

IMAGE_FORMATS = {'R8G8B8': 'rgb8', 'RGB_INT8': 'rgb8', 'B8G8R8': 'bgr8', 'BGR_INT8': 'bgr8',
                 'L8': 'mono8', 'L_INT8': 'mono8', 'L16': 'mono16', 'L_INT16': 'mono16'}
"""SDF ``<image><format>`` values simulated -> the ``sensor_msgs/Image`` encoding
ros_gz_bridge gives them (``ros_gz_bridge`` ``convert/sensor_msgs.cpp``)."""

MAX_IMAGE_SIZE = 4096
"""Largest image width or height (pixels): the offscreen buffer is sized for the largest."""

FRAME_TAGS = ('gz_frame_id', 'ignition_frame_id', 'frame_id')
"""``<sensor>`` children naming the frame id, first found wins: gz-sensors 8 reads only
``gz_frame_id``; ``ignition_frame_id`` is Fortress's and ``frame_id`` the one TurtleBot
descriptions write (both ignored by Harmonic, which then says ``model/link/sensor``)."""

MAX_RAYS = 10 ** 6
"""Most rays of one lidar scan."""

NOISE_TYPES = ('none', 'gaussian', 'gaussian_quantized')
"""SDF ``<noise type>`` values; the simulator applies ``gaussian`` (and its quantized form)."""


class SensorError(ValueError):
    """A sensor block that cannot be simulated: one line naming the sensor and the field."""


@dataclass
class Noise:
    """
    One SDF ``<noise>``: ``value + bias + N(mean, stddev)``, rounded to ``precision``.

    :param type: ``none``, ``gaussian`` or ``gaussian_quantized``.
    :param mean: of the gaussian noise (unit of the value).
    :param stddev: of the gaussian noise (>= 0).
    :param bias_mean: mean of the constant bias drawn once per sensor.
    :param bias_stddev: stddev of that bias (>= 0).
    :param precision: quantization step of ``gaussian_quantized`` (0: none).
    """

    type: str = 'none'  # noqa: A003 - SDF's element name
    mean: float = 0.0
    stddev: float = 0.0
    bias_mean: float = 0.0
    bias_stddev: float = 0.0
    precision: float = 0.0

    @property
    def active(self):
        """Return True when the noise changes values."""
        return self.type != 'none' and (self.stddev > 0.0 or self.mean != 0.0
                                        or self.bias_mean != 0.0 or self.bias_stddev > 0.0)


@dataclass
class ScanAxis:
    """
    One SDF ``<scan><horizontal>`` or ``<vertical>``: ``samples`` rays over [min, max] rad.

    :param samples: rays (>= 1).
    :param resolution: multiplies ``samples`` into the published count (gz-sensors 8
        ``Lidar::RangeCount``).
    :param min_angle: rad, first ray.
    :param max_angle: rad, last ray (>= ``min_angle``).
    """

    samples: int = 1
    resolution: float = 1.0
    min_angle: float = 0.0
    max_angle: float = 0.0

    @property
    def count(self):
        """Return the rays published along this axis (``samples * resolution``, >= 1)."""
        return max(1, int(self.samples * self.resolution))

    def angles(self):
        """Return the directions of the ``count`` rays in rad, min to max, both included (list)."""
        n = self.count
        if n == 1:
            return [self.min_angle]
        step = (self.max_angle - self.min_angle) / (n - 1)
        return [self.min_angle + i * step for i in range(n)]


@dataclass
class LidarSpec:
    """
    SDF ``<lidar>`` (or ``<ray>``).

    :param horizontal: :class:`ScanAxis` (default 640 samples).
    :param vertical: :class:`ScanAxis` (default 1 sample at 0 rad).
    :param range_min: m (>= 0).
    :param range_max: m (> ``range_min``).
    :param range_resolution: m (read, not applied: gz-sensors 8 does not either).
    :param noise: :class:`Noise` of every range (gaussian only).
    """

    horizontal: ScanAxis = field(default_factory=lambda: ScanAxis(samples=640))
    vertical: ScanAxis = field(default_factory=ScanAxis)
    range_min: float = 0.0
    range_max: float = 0.0
    range_resolution: float = 0.0
    noise: Noise = field(default_factory=Noise)


@dataclass
class ImuSpec:
    """
    SDF ``<imu>``.

    :param angular_velocity: three :class:`Noise`, x y z (rad/s).
    :param linear_acceleration: three :class:`Noise`, x y z (m/s^2).
    :param enable_orientation: publish the orientation (else it stays all zero).
    """

    angular_velocity: tuple = (Noise(), Noise(), Noise())
    linear_acceleration: tuple = (Noise(), Noise(), Noise())
    enable_orientation: bool = True


@dataclass
class CameraSpec:
    """
    SDF ``<camera>`` (sdformat 14 ``camera.sdf`` defaults).

    :param horizontal_fov: rad, in (0.01, pi) (a pinhole image).
    :param width: pixels (1..:data:`MAX_IMAGE_SIZE`).
    :param height: pixels (1..:data:`MAX_IMAGE_SIZE`).
    :param format: ``<image><format>`` (a key of :data:`IMAGE_FORMATS`).
    :param near: m, ``<clip><near>`` (> 0).
    :param far: m, ``<clip><far>`` (> near).
    :param depth_near: m, ``<depth_camera><clip><near>`` of a depth image (default ``near``).
    :param depth_far: m, ``<depth_camera><clip><far>`` (default ``far``).
    :param noise: :class:`Noise` of every pixel (gaussian only; colour values in [0, 1],
        depth in m).
    :param optical_frame_id: ``<optical_frame_id>``, '' when unset.
    :param camera_info_topic: ``<camera_info_topic>``, '' when unset.
    :param intrinsics: ``(fx, fy, cx, cy)`` in pixels from ``<lens><intrinsics>``, or None:
        from the field of view, ``fx = fy = width / (2 tan(hfov / 2))``, ``cx = width / 2``,
        ``cy = height / 2`` (sdformat's ``Camera::LensIntrinsicsFx`` and its defaults).
    """

    horizontal_fov: float = 1.047
    width: int = 320
    height: int = 240
    format: str = 'R8G8B8'  # noqa: A003 - SDF's element name
    near: float = 0.1
    far: float = 100.0
    depth_near: float = 0.1
    depth_far: float = 100.0
    noise: Noise = field(default_factory=Noise)
    optical_frame_id: str = ''
    camera_info_topic: str = ''
    intrinsics: tuple = None

    @property
    def encoding(self):
        """Return the ``sensor_msgs/Image`` encoding of the colour image (e.g. ``rgb8``)."""
        return IMAGE_FORMATS[self.format]

    def k(self):
        """Return ``(fx, fy, cx, cy)`` in pixels (:attr:`intrinsics` or from the fov)."""
        if self.intrinsics is not None:
            return self.intrinsics
        f = self.width / (2.0 * math.tan(0.5 * self.horizontal_fov))
        return f, f, 0.5 * self.width, 0.5 * self.height


@dataclass
class NavSatSpec:
    """
    SDF ``<navsat>``: the noise of the position (sdformat 14 ``navsat.sdf``).

    :param horizontal: :class:`Noise` of ``<position_sensing><horizontal>``, added to the
        latitude and to the longitude in degrees (as gz-sensors 8 ``NavSatSensor::Update``).
    :param vertical: :class:`Noise` of ``<position_sensing><vertical>``, added to the
        altitude in m.
    """

    horizontal: Noise = field(default_factory=Noise)
    vertical: Noise = field(default_factory=Noise)


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


def _text(parent, path, default=None):
    element = parent.find(path)
    return default if element is None else tag_text(element)


def _tags(path):
    return ''.join(f'<{part}>' for part in path.split('/'))


def _number(parent, path, default, where, low=None, positive=False, integer=False):
    text = _text(parent, path)
    if text is None or text == '':
        return default
    where += _tags(path)
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        value = math.nan
    if integer and isinstance(value, float):
        raise SensorError(f'{where}: expected an integer, found {text!r}')
    if math.isnan(value) or math.isinf(value):
        raise SensorError(f'{where}: expected a finite number, found {text!r}')
    if positive and not value > 0:
        raise SensorError(f'{where}: expected a number > 0, found {text!r}')
    if low is not None and value < low:
        raise SensorError(f'{where}: expected a number >= {low:g}, found {text!r}')
    return value


def _bool(parent, path, default, where):
    text = _text(parent, path)
    if text is None or text == '':
        return default
    value = text.strip().lower()
    if value in ('true', '1'):
        return True
    if value in ('false', '0'):
        return False
    raise SensorError(f'{where}{_tags(path)}: expected true or false, found {text!r}')


def _noise(element, where, type_text):
    """Read one ``<noise>`` (its type given by the caller: child element or attribute)."""
    if element is None:
        return Noise()
    kind = (type_text or 'none').strip().lower()
    if kind not in NOISE_TYPES:
        raise SensorError(f'{where}<noise><type>: expected one of {", ".join(NOISE_TYPES)}, '
                          f'found {type_text!r}')
    where = f'{where}<noise>'
    return Noise(kind, _number(element, 'mean', 0.0, where),
                 _number(element, 'stddev', 0.0, where, low=0.0),
                 _number(element, 'bias_mean', 0.0, where),
                 _number(element, 'bias_stddev', 0.0, where, low=0.0),
                 _number(element, 'precision', 0.0, where, low=0.0))


def _axis(element, where, default_samples):
    if element is None:
        return ScanAxis(samples=default_samples)
    axis = ScanAxis(_number(element, 'samples', default_samples, where, positive=True,
                            integer=True),
                    _number(element, 'resolution', 1.0, where, positive=True),
                    _number(element, 'min_angle', 0.0, where),
                    _number(element, 'max_angle', 0.0, where))
    if axis.max_angle < axis.min_angle:
        raise SensorError(f'{where}<max_angle>: expected >= min_angle {axis.min_angle:g}, '
                          f'found {axis.max_angle:g}')
    return axis


def _lidar(sensor, where):
    element = sensor.find('lidar')
    if element is None:
        element = sensor.find('ray')
    tag = 'lidar' if sensor.find('lidar') is not None else 'ray'
    if element is None:
        return LidarSpec()
    where = f'{where}<{tag}>'
    spec = LidarSpec(
        _axis(element.find('scan/horizontal'), f'{where}<scan><horizontal>', 640),
        _axis(element.find('scan/vertical'), f'{where}<scan><vertical>', 1),
        _number(element, 'range/min', 0.0, where, low=0.0),
        _number(element, 'range/max', 0.0, where, low=0.0),
        _number(element, 'range/resolution', 0.0, where, low=0.0))
    if not spec.range_max > spec.range_min:
        raise SensorError(f'{where}<range><max>: expected > min {spec.range_min:g}, found '
                          f'{spec.range_max:g}')
    noise = element.find('noise')
    spec.noise = _noise(noise, where, None if noise is None else _text(noise, 'type'))
    if spec.noise.type not in ('none', 'gaussian'):
        raise SensorError(f'{where}<noise><type>: a lidar takes gaussian noise only '
                          '(gz-sensors 8), found ' + repr(spec.noise.type))
    rays = spec.horizontal.count * spec.vertical.count
    if rays > MAX_RAYS:
        raise SensorError(f'{where}<scan>: {rays} rays per scan, at most {MAX_RAYS} are '
                          'simulated')
    return spec


def _imu(sensor, where):
    element = sensor.find('imu')
    if element is None:
        return ImuSpec()
    where = f'{where}<imu>'
    groups = []
    for group in ('angular_velocity', 'linear_acceleration'):
        noises = []
        for axis in 'xyz':
            noise = element.find(f'{group}/{axis}/noise')
            noises.append(_noise(noise, f'{where}<{group}><{axis}>',
                                 None if noise is None else noise.get('type', 'none')))
        groups.append(tuple(noises))
    return ImuSpec(groups[0], groups[1],
                   _bool(element, 'enable_orientation', True, where))


def _camera(sensor, where):
    element = sensor.find('camera')
    if element is None:
        return CameraSpec()
    where = f'{where}<camera>'
    fov = _number(element, 'horizontal_fov', 1.047, where, positive=True)
    if not 0.01 <= fov < math.pi:
        raise SensorError(f'{where}<horizontal_fov>: expected 0.01 to pi rad (a pinhole '
                          f'camera), found {fov:g}')
    size = []
    for axis, default in (('width', 320), ('height', 240)):
        value = _number(element, f'image/{axis}', default, where, integer=True)
        if not 1 <= value <= MAX_IMAGE_SIZE:
            raise SensorError(f'{where}<image><{axis}>: expected 1 to {MAX_IMAGE_SIZE} pixels, '
                              f'found {value}')
        size.append(value)
    image_format = (_text(element, 'image/format', '') or 'R8G8B8').strip()
    if image_format not in IMAGE_FORMATS:
        raise SensorError(f'{where}<image><format>: expected one of '
                          f'{", ".join(IMAGE_FORMATS)}, found {image_format!r}')
    near = _number(element, 'clip/near', 0.1, where, positive=True)
    far = _number(element, 'clip/far', 100.0, where, positive=True)
    if not far > near:
        raise SensorError(f'{where}<clip><far>: expected > near {near:g}, found {far:g}')
    depth_near = _number(element, 'depth_camera/clip/near', near, where, positive=True)
    depth_far = _number(element, 'depth_camera/clip/far', far, where, positive=True)
    if not depth_far > depth_near:
        raise SensorError(f'{where}<depth_camera><clip><far>: expected > near {depth_near:g}, '
                          f'found {depth_far:g}')
    noise_element = element.find('noise')
    noise = _noise(noise_element, where,
                   None if noise_element is None else _text(noise_element, 'type'))
    if noise.type not in ('none', 'gaussian'):
        raise SensorError(f'{where}<noise><type>: a camera takes gaussian noise only '
                          f'(gz-sensors 8), found {noise.type!r}')
    intrinsics = None
    lens = element.find('lens/intrinsics')
    if lens is not None:
        lens_where = f'{where}<lens>'
        f0 = size[0] / (2.0 * math.tan(0.5 * fov))
        intrinsics = (_number(lens, 'fx', f0, lens_where + '<intrinsics>', positive=True),
                      _number(lens, 'fy', f0, lens_where + '<intrinsics>', positive=True),
                      _number(lens, 'cx', 0.5 * size[0], lens_where + '<intrinsics>'),
                      _number(lens, 'cy', 0.5 * size[1], lens_where + '<intrinsics>'))
    return CameraSpec(fov, size[0], size[1], image_format, near, far, depth_near, depth_far,
                      noise, (_text(element, 'optical_frame_id', '') or '').strip(),
                      (_text(element, 'camera_info_topic', '') or '').strip(), intrinsics)


def _navsat(sensor, where):
    element = sensor.find('navsat')
    spec = NavSatSpec()
    if element is None:
        return spec
    for axis in ('horizontal', 'vertical'):
        noise = element.find(f'position_sensing/{axis}/noise')
        value = _noise(noise, f'{where}<navsat><position_sensing><{axis}>',
                       None if noise is None else (noise.get('type') or _text(noise, 'type')))
        setattr(spec, axis, value)
    return spec


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
        update_rate=_number(sensor, 'update_rate', 0.0, where, low=0.0),
        always_on=_bool(sensor, 'always_on', False, where),
        topic=(_text(sensor, 'topic', '') or '').strip(),
        frame_id=next((text.strip() for text in (_text(sensor, tag, '') for tag in FRAME_TAGS)
                       if text and text.strip()), ''),
        xyz=xyz, rpy=rpy)
    if block.topic == '__default__':
        block.topic = ''
    if block.kind == 'lidar':
        block.lidar = _lidar(sensor, where)
    elif block.kind in CAMERA_KINDS:
        block.camera = _camera(sensor, where)
    elif block.kind == 'navsat':
        block.navsat = _navsat(sensor, where)
    elif block.kind == 'contact':
        block.contact_collision = (_text(sensor, 'contact/collision', '') or '').strip()
        if not block.contact_collision:
            raise SensorError(f'{where}<contact><collision>: expected the name of a collision '
                              'of the link, found none')
        topic = (_text(sensor, 'contact/topic', '') or '').strip()
        if topic and topic != '__default_topic__' and not block.topic:
            block.topic = topic
    else:
        block.imu = _imu(sensor, where)
    return block


def parse_sensors(root, links):
    """
    Return the sensor blocks of a URDF (:class:`SensorBlocks`).

    :param root: the ``<robot>`` element.
    :param links: the URDF link names (a container).
    """
    result = SensorBlocks()
    names = set()
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
            names.add(block.name)
            result.sensors.append(block)
    return result


def lumped_link(model, link, tags):
    """
    Return the link a sensor's link is merged into by sdformat's fixed-joint lumping.

    sdformat 14's URDF reader merges the child of a fixed joint into its parent unless the
    joint's ``<gazebo reference>`` sets ``preserveFixedJoint`` or
    ``disableFixedJointLumping`` (``src/parser_urdf.cc``).

    :param model: the :class:`~amr_description.core.urdf_model.RobotModel`.
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

    :param model: the :class:`~amr_description.core.urdf_model.RobotModel`.
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
