# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Cameras: ``camera``, ``depth_camera`` / ``depth`` and ``rgbd_camera`` / ``rgbd`` sensor blocks.

Each is rendered by MuJoCo's ``Renderer`` (OpenGL through ``MUJOCO_GL``, EGL on Mesa without a
GPU) from the MuJoCo camera :mod:`~amr_description.sim.sensors.mount` puts at the sensor.
What reaches ROS is what ros_gz_bridge makes of gz-sensors 8's messages (``CameraSensor.cc``,
``DepthCameraSensor.cc``, ``RgbdCameraSensor.cc``; ``ros_gz_bridge`` ``convert/sensor_msgs.cpp``):

- ``camera``: ``sensor_msgs/Image`` on ``<topic>`` (``rgb8`` for R8G8B8, ``bgr8``, ``mono8`` for
  L8, ``mono16``), ``sensor_msgs/CameraInfo`` on ``<camera_info_topic>`` or the sibling
  ``camera_info`` of ``<topic>``, and ``<topic>/compressed`` (``sensor_msgs/CompressedImage``,
  JPEG, ``format`` ``'<encoding>; jpeg compressed bgr8'`` as image_transport's compressed
  plugin writes it);
- ``depth_camera``: ``32FC1`` metres on ``<topic>``, ``<topic>/points``, CameraInfo as above;
- ``rgbd_camera``: ``<topic>/image``, ``<topic>/depth_image``, ``<topic>/points``,
  ``<topic>/camera_info``.

Images are in the optical frame ``<optical_frame_id>`` (else the sensor's frame id):
row 0 at the top, column 0 at the left of the view. Depth is the distance along the optical
axis (m); where nothing is hit within ``<depth_camera><clip><far>`` it is +inf (not MuJoCo's
far plane) and a hit closer than the near clip is -inf (REP 117's convention, as gz-sensors'
depth camera). CameraInfo: ``plumb_bob`` with zero distortion, ``K = [fx 0 cx; 0 fy cy; 0 0
1]``, ``P = [K | 0]``, ``R = I`` (``CameraSensor::PopulateInfo``). PointCloud2: fields ``x``,
``y``, ``z`` (float32 at 0, 4, 8) and ``rgb`` (float32 at 16 holding the bytes b, g, r, 0),
``point_step`` 24 (gz-msgs ``InitPointCloudPacked``, word-aligned), one point per pixel,
``d * ((u - cx) / fx, (v - cy) / fy, 1)`` in the optical frame's axes when
``<optical_frame_id>`` is set, else the same point in the sensor frame's axes (x forward, y
left, z up), so the data always matches the frame it names; a depth camera's ``rgb`` is the
depth as grey (white at the near clip, black at the far clip); ``is_dense`` is false when a
depth is not finite. Gaussian ``<noise>`` is added per pixel as gz-sensors'
``ImageGaussianNoiseModel`` (colour values in [0, 1], then clamped) and to depth in m.

Rendering is MuJoCo's: the world's lights, 4x multisampling (SDF's ``<anti_aliasing>``
default), without the mirror reflection MuJoCo's viewer gives the floor (Gazebo's cameras show
none) and without shadows: MuJoCo's shadow map speckles the ground with dark pixels (shadow
acne, 47 of 28,800 floor pixels in test/data/worlds/camera_targets.sdf, whatever the map size)
and cost 50 ms of a 320x240 frame with its 4096-pixel map (22 ms with 1024) against 10 ms
without, on Mesa's CPU rasterizer (docs/sensors.md).

Rendering does not stall physics: at a due instant the simulation thread copies the state
(``qpos``, ``mocap_pos``, ``mocap_quat``) into a job for the
:class:`~amr_description.sim.sensors.camera_renderer.CameraRenderer`, whose own
thread renders and publishes it; the simulation waits only while an earlier job has not been
started, so every due frame is rendered (rates exact in sim time) at most one frame behind.
Nothing is rendered for an output nobody subscribes to (``costly``), and no OpenGL context
exists until a camera is rendered.
"""

import array

from amr_description.core.gazebo.sensor_kinds import IMAGE_FORMATS
from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import named_topic
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
from amr_description.sim.sensors.camera_renderer import CameraRenderer
from amr_description.sim.sensors.mount import camera_name
from amr_description.sim.sensors.noise import generator
import numpy as np
from sensor_msgs.msg import CameraInfo
from sensor_msgs.msg import CompressedImage
from sensor_msgs.msg import Image
from sensor_msgs.msg import PointCloud2
from sensor_msgs.msg import PointField

POINT_FIELDS = (('x', 0, PointField.FLOAT32), ('y', 4, PointField.FLOAT32),
                ('z', 8, PointField.FLOAT32), ('rgb', 16, PointField.FLOAT32))
"""PointCloud2 fields of a gz-sensors depth camera: (name, offset, datatype), step 24."""

POINT_STEP = 24
JPEG_QUALITY = 80
"""image_transport's compressed plugin default ``jpeg_quality``."""

BYTES_PER_PIXEL = {'rgb8': 3, 'bgr8': 3, 'mono8': 1, 'mono16': 2, '32FC1': 4}


def colour_image(rgb, encoding):
    """
    Return the image bytes of a rendered RGB frame in ``encoding``.

    :param rgb: (H, W, 3) uint8, row 0 at the top.
    :param encoding: ``rgb8``, ``bgr8``, ``mono8`` or ``mono16`` (grey from ITU-R BT.601
        luma ``0.299 R + 0.587 G + 0.114 B``, as OpenCV's ``cvtColor``).
    :returns: (H, W, C) uint8 or (H, W) uint8/uint16 array (C-contiguous).
    """
    if encoding == 'rgb8':
        return np.ascontiguousarray(rgb)
    if encoding == 'bgr8':
        return np.ascontiguousarray(rgb[:, :, ::-1])
    grey = rgb.astype(np.float32) @ np.array([0.299, 0.587, 0.114], dtype=np.float32)
    if encoding == 'mono8':
        return np.clip(np.rint(grey), 0, 255).astype(np.uint8)
    return (np.clip(np.rint(grey), 0, 255).astype(np.uint16) * 257)


def optical_rays(spec):
    """
    Return (H, W, 3) float32 rays ``((u - cx) / fx, (v - cy) / fy, 1)`` of every pixel.

    ``u``, ``v`` are the pixel centres' column and row (``i + 0.5``) in the optical frame of
    REP 103 (z forward, x right, y down); a point is ``depth * ray``.
    """
    fx, fy, cx, cy = spec.k()
    u = (np.arange(spec.width, dtype=np.float64) + 0.5 - cx) / fx
    v = (np.arange(spec.height, dtype=np.float64) + 0.5 - cy) / fy
    rays = np.ones((spec.height, spec.width, 3))
    rays[:, :, 0] = u[None, :]
    rays[:, :, 1] = v[:, None]
    return rays.astype(np.float32)


OPTICAL_TO_SENSOR = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]],
                             dtype=np.float32)
"""Rotation from REP 103 optical axes to the sensor's (x forward, y left, z up)."""


def camera_info(spec, frame_id):
    """Return the ``sensor_msgs/CameraInfo`` of a camera (module docstring), unstamped."""
    fx, fy, cx, cy = spec.k()
    msg = CameraInfo()
    msg.header.frame_id = frame_id
    msg.height, msg.width = spec.height, spec.width
    msg.distortion_model = 'plumb_bob'
    msg.d = [0.0] * 5
    msg.k = [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0]
    msg.r = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    msg.p = [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
    return msg


class CameraCapture:
    """
    One camera block: what to render and the outputs asking for it at the current instant.

    :param prefix: the entity's name prefix in the world (``<entity>/``).
    :param block: the :class:`~amr_description.core.gazebo.sensors.SensorBlock`.
    :param frame_id: the optical frame id (with the frame prefix).
    :param optical: True when ``frame_id`` is an optical frame (points in optical axes).
    :param renderer: the :class:`CameraRenderer` that renders it.
    :param rng: numpy ``Generator`` of its pixel noise.
    """

    def __init__(self, prefix, block, frame_id, optical, renderer, rng):
        """Keep the fields (see the class docstring)."""
        self.spec = block.camera
        self.kind = block.kind
        self.camera = prefix + camera_name(block)
        self.frame_id = frame_id
        self.optical = optical
        self.renderer = renderer
        self.rng = rng
        self.rays = None  # optical_rays, made on first use
        renderer.register(self)

    def needs(self, outputs):
        """Return ``(rgb, depth)``: which buffers ``outputs`` (CameraOutput list) need."""
        kinds = {output.part for output in outputs}
        rgb = bool(kinds & {'image', 'compressed'}) or ('points' in kinds and self.kind == 'rgbd')
        depth = bool(kinds & {'depth', 'points'})
        return rgb, depth

    def add_noise(self, frame):
        """Add the block's gaussian noise to a frame's images in place (module docstring)."""
        noise = self.spec.noise
        if not noise.active:
            return
        if frame.rgb is not None:
            values = frame.rgb.astype(np.float32) / 255.0
            values += self.rng.normal(noise.mean, noise.stddev, values.shape).astype(np.float32)
            frame.rgb = np.clip(np.rint(values * 255.0), 0, 255).astype(np.uint8)
        if frame.depth is not None:
            finite = np.isfinite(frame.depth)
            frame.depth[finite] += self.rng.normal(
                noise.mean, noise.stddev, int(finite.sum())).astype(np.float32)

    def points(self, frame):
        """
        Return (H * W, 3) float32 points of a frame's depth in the frame id's axes.

        :param frame: a :class:`Frame` with ``depth``.
        """
        if self.rays is None:
            rays = optical_rays(self.spec)
            if not self.optical:
                rays = rays @ OPTICAL_TO_SENSOR.T
            self.rays = rays.reshape(-1, 3)
        with np.errstate(invalid='ignore'):
            return self.rays * frame.depth.reshape(-1, 1)


class CameraOutput(Sensor):
    """
    One message of a camera: its image, depth image, points, camera info or JPEG.

    ``costly`` (rendered only while subscribed) and ``deferred``: the node calls
    :meth:`request` instead of :meth:`measure`; the message is published from the render
    thread.

    :param capture: the :class:`CameraCapture`.
    :param part: ``image``, ``depth``, ``points``, ``info`` or ``compressed``.
    :param name: sensor name (unique within the entity).
    :param topics: ``(ROS topic, gz topic)``.
    :param rate: Hz of sim time.
    """

    costly = True
    deferred = True
    TYPES = {'image': Image, 'depth': Image, 'points': PointCloud2, 'info': CameraInfo,
             'compressed': CompressedImage}

    def __init__(self, capture, part, name, topics, rate):
        """Prepare the reused message (see the class docstring)."""
        self.capture = capture
        self.part = part
        self.name = name
        self.topic, self.gz_name = topics
        self.frame_id = capture.frame_id
        self.rate = float(rate)
        self.message_type = self.TYPES[part]
        self._info = camera_info(capture.spec, capture.frame_id) if part == 'info' else None

    def request(self, t, publish):
        """
        Ask for this output at sim time ``t`` (s); ``publish(msg)`` is called with it later.

        :returns: the :class:`CameraRenderer` to :meth:`~CameraRenderer.flush` once every
            output of the instant has asked.
        """
        self.capture.renderer.want(self.capture, self, t, publish)
        return self.capture.renderer

    def measure(self, world, t):
        """Render and return the message of sim time ``t`` now, on the caller's thread."""
        frame = self.capture.renderer.render_now(world, self.capture, [self])
        return self.message(frame, t)

    def message(self, frame, t):
        """Return this output's message of a rendered :class:`Frame` at sim time ``t``."""
        spec = self.capture.spec
        if self.part == 'info':
            set_stamp(self._info.header.stamp, t)
            return self._info
        if self.part == 'compressed':
            return self._jpeg(frame, t)
        if self.part == 'points':
            return self._points(frame, t)
        msg = Image()
        set_stamp(msg.header.stamp, t)
        msg.header.frame_id = self.frame_id
        msg.height, msg.width = spec.height, spec.width
        msg.is_bigendian = 0
        if self.part == 'depth':
            data = frame.depth.astype('<f4', copy=False)
            msg.encoding = '32FC1'
        else:
            msg.encoding = IMAGE_FORMATS[spec.format]
            data = colour_image(frame.rgb, msg.encoding)
            if msg.encoding == 'mono16':
                data = data.astype('<u2', copy=False)
        msg.step = spec.width * BYTES_PER_PIXEL[msg.encoding]
        msg.data = array.array('B', np.ascontiguousarray(data).tobytes())
        return msg

    def _jpeg(self, frame, t):
        import io

        from PIL import Image as PilImage
        spec = self.capture.spec
        encoding = IMAGE_FORMATS[spec.format]
        msg = CompressedImage()
        set_stamp(msg.header.stamp, t)
        msg.header.frame_id = self.frame_id
        mono = encoding.startswith('mono')
        picture = PilImage.fromarray(colour_image(frame.rgb, 'mono8') if mono else frame.rgb)
        buffer = io.BytesIO()
        picture.save(buffer, format='JPEG', quality=JPEG_QUALITY)
        msg.format = f'{encoding}; jpeg compressed {"mono8" if mono else "bgr8"}'
        msg.data = array.array('B', buffer.getvalue())
        return msg

    def _points(self, frame, t):
        spec = self.capture.spec
        msg = PointCloud2()
        set_stamp(msg.header.stamp, t)
        msg.header.frame_id = self.frame_id
        msg.height, msg.width = spec.height, spec.width
        msg.fields = [PointField(name=n, offset=o, datatype=d, count=1)
                      for n, o, d in POINT_FIELDS]
        msg.is_bigendian = False
        msg.point_step = POINT_STEP
        msg.row_step = POINT_STEP * spec.width
        cloud = np.zeros((spec.height * spec.width, POINT_STEP), dtype=np.uint8)
        xyz = self.capture.points(frame)
        cloud[:, 0:12] = xyz.astype('<f4').view(np.uint8).reshape(-1, 12)
        if frame.rgb is not None and self.capture.kind == 'rgbd':
            colour = frame.rgb.reshape(-1, 3)
        else:  # grey from depth: white at the near clip, black at the far clip
            near, far = spec.depth_near, spec.depth_far
            with np.errstate(invalid='ignore'):
                level = 255.0 * (1.0 - (frame.depth.reshape(-1) - near) / (far - near))
            grey = np.clip(np.nan_to_num(level, nan=0.0, posinf=0.0, neginf=255.0),
                           0, 255).astype(np.uint8)
            colour = np.repeat(grey[:, None], 3, axis=1)
        cloud[:, 16] = colour[:, 2]
        cloud[:, 17] = colour[:, 1]
        cloud[:, 18] = colour[:, 0]
        msg.is_dense = bool(np.isfinite(frame.depth).all())
        msg.data = array.array('B', cloud.tobytes())
        return msg


def _derived(topics, suffix):
    """Return ``(ROS, gz)`` topics below ``topics`` (``/suffix``)."""
    return tuple(f'{t.rstrip("/")}/{suffix}' for t in topics)


def _sibling(topics, name):
    """Return ``(ROS, gz)`` topics beside ``topics`` (the parent's ``/name``)."""
    return tuple(f'{t.rsplit("/", 1)[0]}/{name}' for t in topics)


def create(entity, settings):
    """
    Return the outputs of every camera block of ``entity`` (module docstring).

    :param entity: the spawned entity (``description.sensors``, ``robot.prefix``).
    :param settings: dict; ``seed``, ``physics_step``, ``world`` as the lidar's; the
        simulator's :class:`CameraRenderer` under ``camera_renderer`` (one is made and kept
        there when missing).
    """
    blocks = [b for b in entity.description.sensors.sensors if b.camera is not None]
    if not blocks:
        return []
    renderer = settings.get('camera_renderer')
    if renderer is None:
        renderer = settings['camera_renderer'] = CameraRenderer()
    step = float(settings.get('physics_step', 0.001))
    outputs = []
    for block in blocks:
        spec = block.camera
        optical = spec.optical_frame_id
        frame = entity.frame_prefix + optical if optical else sensor_frame(entity, block)
        capture = CameraCapture(entity.robot.prefix, block, frame, bool(optical), renderer,
                                generator(settings.get('seed', 0), entity.name, block.name))
        topics = sensor_topic(entity, block, settings.get('world', 'empty'))
        rate = sensor_rate(block, step)
        name = block.name
        if block.kind == 'rgbd':
            parts = [('image', _derived(topics, 'image')),
                     ('depth', _derived(topics, 'depth_image')),
                     ('points', _derived(topics, 'points')),
                     ('info', _derived(topics, 'camera_info'))]
        else:
            info_topics = (named_topic(entity, spec.camera_info_topic)
                           if spec.camera_info_topic else _sibling(topics, 'camera_info'))
            main = 'depth' if block.kind == 'depth' else 'image'
            parts = [(main, topics), ('info', info_topics)]
            parts.append(('points', _derived(topics, 'points')) if block.kind == 'depth'
                         else ('compressed', _derived(topics, 'compressed')))
        if block.kind == 'rgbd':
            parts.append(('compressed', _derived(parts[0][1], 'compressed')))
        for part, part_topics in parts:
            outputs.append(CameraOutput(capture, part, f'{name}/{part}', part_topics, rate))
    return outputs
