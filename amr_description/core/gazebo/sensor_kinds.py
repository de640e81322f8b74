# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The simulated sensor kinds: each kind's SDF element read next to the kind, in one table.

Elements and defaults are SDF 1.11's (``sensor.sdf``, ``lidar.sdf``, ``imu.sdf``,
``noise.sdf`` of sdformat 14): ``<update_rate>`` 0 (every physics step), ``<always_on>``
false, ``<topic>`` unset (gz's default name, :func:`default_topic`), ``<pose>`` ``x y z roll
pitch yaw`` in the link frame (m, rad; ``degrees="true"``), ``<gz_frame_id>`` (gz-sensors 8
``Sensor::PopulateFromSDF``; ``sensors.FRAME_TAGS``). A lidar is ``<lidar>`` or its older name
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

:data:`SENSOR_KINDS` is the table: kind -> (the SDF ``<sensor type>`` values simulated as that
kind, the reader of its element). A kind is added with one row; a kind without a reader is a
one-line :class:`SensorError`, never read as another kind. Every field at fault is a
:class:`SensorError` naming the sensor and the element
(:mod:`amr_description.core.gazebo.sensors` leaves that sensor out).
"""

from dataclasses import dataclass
from dataclasses import field
import math

from amr_description.core.gazebo.tags import tag_text

IMAGE_FORMATS = {'R8G8B8': 'rgb8', 'RGB_INT8': 'rgb8', 'B8G8R8': 'bgr8', 'BGR_INT8': 'bgr8',
                 'L8': 'mono8', 'L_INT8': 'mono8', 'L16': 'mono16', 'L_INT16': 'mono16'}
"""SDF ``<image><format>`` values simulated -> the ``sensor_msgs/Image`` encoding
ros_gz_bridge gives them (``ros_gz_bridge`` ``convert/sensor_msgs.cpp``)."""

MAX_IMAGE_SIZE = 4096
"""Largest image width or height (pixels): the offscreen buffer is sized for the largest."""

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


def element_text(parent, path, default=None):
    element = parent.find(path)
    return default if element is None else tag_text(element)


def _tags(path):
    return ''.join(f'<{part}>' for part in path.split('/'))


def element_number(parent, path, default, where, low=None, positive=False, integer=False):
    text = element_text(parent, path)
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


def element_bool(parent, path, default, where):
    text = element_text(parent, path)
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
    return Noise(kind, element_number(element, 'mean', 0.0, where),
                 element_number(element, 'stddev', 0.0, where, low=0.0),
                 element_number(element, 'bias_mean', 0.0, where),
                 element_number(element, 'bias_stddev', 0.0, where, low=0.0),
                 element_number(element, 'precision', 0.0, where, low=0.0))


def _axis(element, where, default_samples):
    if element is None:
        return ScanAxis(samples=default_samples)
    axis = ScanAxis(element_number(element, 'samples', default_samples, where, positive=True,
                                   integer=True),
                    element_number(element, 'resolution', 1.0, where, positive=True),
                    element_number(element, 'min_angle', 0.0, where),
                    element_number(element, 'max_angle', 0.0, where))
    if axis.max_angle < axis.min_angle:
        raise SensorError(f'{where}<max_angle>: expected >= min_angle {axis.min_angle:g}, '
                          f'found {axis.max_angle:g}')
    return axis


def _lidar_spec(sensor, where):
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
        element_number(element, 'range/min', 0.0, where, low=0.0),
        element_number(element, 'range/max', 0.0, where, low=0.0),
        element_number(element, 'range/resolution', 0.0, where, low=0.0))
    if not spec.range_max > spec.range_min:
        raise SensorError(f'{where}<range><max>: expected > min {spec.range_min:g}, found '
                          f'{spec.range_max:g}')
    noise = element.find('noise')
    spec.noise = _noise(noise, where, None if noise is None else element_text(noise, 'type'))
    if spec.noise.type not in ('none', 'gaussian'):
        raise SensorError(f'{where}<noise><type>: a lidar takes gaussian noise only '
                          '(gz-sensors 8), found ' + repr(spec.noise.type))
    rays = spec.horizontal.count * spec.vertical.count
    if rays > MAX_RAYS:
        raise SensorError(f'{where}<scan>: {rays} rays per scan, at most {MAX_RAYS} are '
                          'simulated')
    return spec


def _imu_spec(sensor, where):
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
                   element_bool(element, 'enable_orientation', True, where))


def _camera_spec(sensor, where):
    element = sensor.find('camera')
    if element is None:
        return CameraSpec()
    where = f'{where}<camera>'
    fov = element_number(element, 'horizontal_fov', 1.047, where, positive=True)
    if not 0.01 <= fov < math.pi:
        raise SensorError(f'{where}<horizontal_fov>: expected 0.01 to pi rad (a pinhole '
                          f'camera), found {fov:g}')
    size = []
    for axis, default in (('width', 320), ('height', 240)):
        value = element_number(element, f'image/{axis}', default, where, integer=True)
        if not 1 <= value <= MAX_IMAGE_SIZE:
            raise SensorError(f'{where}<image><{axis}>: expected 1 to {MAX_IMAGE_SIZE} pixels, '
                              f'found {value}')
        size.append(value)
    image_format = (element_text(element, 'image/format', '') or 'R8G8B8').strip()
    if image_format not in IMAGE_FORMATS:
        raise SensorError(f'{where}<image><format>: expected one of '
                          f'{", ".join(IMAGE_FORMATS)}, found {image_format!r}')
    near = element_number(element, 'clip/near', 0.1, where, positive=True)
    far = element_number(element, 'clip/far', 100.0, where, positive=True)
    if not far > near:
        raise SensorError(f'{where}<clip><far>: expected > near {near:g}, found {far:g}')
    depth_near = element_number(element, 'depth_camera/clip/near', near, where, positive=True)
    depth_far = element_number(element, 'depth_camera/clip/far', far, where, positive=True)
    if not depth_far > depth_near:
        raise SensorError(f'{where}<depth_camera><clip><far>: expected > near {depth_near:g}, '
                          f'found {depth_far:g}')
    noise_element = element.find('noise')
    noise = _noise(noise_element, where,
                   None if noise_element is None else element_text(noise_element, 'type'))
    if noise.type not in ('none', 'gaussian'):
        raise SensorError(f'{where}<noise><type>: a camera takes gaussian noise only '
                          f'(gz-sensors 8), found {noise.type!r}')
    intrinsics = None
    lens = element.find('lens/intrinsics')
    if lens is not None:
        lens_where = f'{where}<lens>'
        f0 = size[0] / (2.0 * math.tan(0.5 * fov))
        intrinsics = (element_number(lens, 'fx', f0, lens_where + '<intrinsics>', positive=True),
                      element_number(lens, 'fy', f0, lens_where + '<intrinsics>', positive=True),
                      element_number(lens, 'cx', 0.5 * size[0], lens_where + '<intrinsics>'),
                      element_number(lens, 'cy', 0.5 * size[1], lens_where + '<intrinsics>'))
    return CameraSpec(fov, size[0], size[1], image_format, near, far, depth_near, depth_far,
                      noise, (element_text(element, 'optical_frame_id', '') or '').strip(),
                      (element_text(element, 'camera_info_topic', '') or '').strip(), intrinsics)


def _navsat_spec(sensor, where):
    element = sensor.find('navsat')
    spec = NavSatSpec()
    if element is None:
        return spec
    for axis in ('horizontal', 'vertical'):
        noise = element.find(f'position_sensing/{axis}/noise')
        type_text = None
        if noise is not None:
            type_text = noise.get('type') or element_text(noise, 'type')
        value = _noise(noise, f'{where}<navsat><position_sensing><{axis}>', type_text)
        setattr(spec, axis, value)
    return spec


def read_lidar(sensor, where, block):
    """Fill ``block.lidar`` (:class:`LidarSpec`) from ``<lidar>`` (or its older name ``<ray>``)."""
    block.lidar = _lidar_spec(sensor, where)


def read_imu(sensor, where, block):
    """Fill ``block.imu`` (:class:`ImuSpec`) from ``<imu>``."""
    block.imu = _imu_spec(sensor, where)


def read_camera(sensor, where, block):
    """Fill ``block.camera`` (:class:`CameraSpec`) from ``<camera>`` (camera, depth, RGB-D)."""
    block.camera = _camera_spec(sensor, where)


def read_navsat(sensor, where, block):
    """Fill ``block.navsat`` (:class:`NavSatSpec`) from ``<navsat>``."""
    block.navsat = _navsat_spec(sensor, where)


def read_contact(sensor, where, block):
    """
    Fill ``block.contact_collision`` from ``<contact><collision>`` (required).

    ``<contact><topic>`` (other than gz's ``__default_topic__``) is the topic when the
    sensor has no ``<topic>`` of its own.
    """
    block.contact_collision = (element_text(sensor, 'contact/collision', '') or '').strip()
    if not block.contact_collision:
        raise SensorError(f'{where}<contact><collision>: expected the name of a collision '
                          'of the link, found none')
    topic = (element_text(sensor, 'contact/topic', '') or '').strip()
    if topic and topic != '__default_topic__' and not block.topic:
        block.topic = topic


SENSOR_KINDS = {
    'lidar': (('gpu_lidar', 'lidar', 'ray', 'gpu_ray'), read_lidar),
    'imu': (('imu',), read_imu),
    'camera': (('camera',), read_camera),
    'depth': (('depth_camera', 'depth'), read_camera),
    'rgbd': (('rgbd_camera', 'rgbd'), read_camera),
    'navsat': (('navsat',), read_navsat),
    'contact': (('contact',), read_contact),
}
"""The simulator's sensor kinds: kind -> (SDF ``<sensor type>`` values, reader). A reader
``reader(sensor, where, block)`` reads the kind's element of ``<sensor>`` into the
:class:`~amr_description.core.gazebo.sensors.SensorBlock`, ``where`` prefixing its errors.
Every lidar type is ray-cast."""

KINDS = {sdf_type: kind for kind, (types, _) in SENSOR_KINDS.items() for sdf_type in types}
"""Simulated SDF sensor types -> the simulator's kind (from :data:`SENSOR_KINDS`)."""


def read_kind(kind, sensor, where, block):
    """
    Read the element of ``kind`` into ``block`` with the reader :data:`SENSOR_KINDS` gives.

    :raises SensorError: one line when the kind has no reader (never read as another kind),
        or naming the field at fault.
    """
    _, reader = SENSOR_KINDS.get(kind, ((), None))
    if reader is None:
        raise SensorError(f'{where}kind {kind!r} has no reader (SENSOR_KINDS)')
    reader(sensor, where, block)
