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
(``qpos``, ``mocap_pos``, ``mocap_quat``) into a job for :class:`CameraRenderer`, whose own
thread renders and publishes it; the simulation waits only while an earlier job has not been
started, so every due frame is rendered (rates exact in sim time) at most one frame behind.
Nothing is rendered for an output nobody subscribes to (``costly``), and no OpenGL context
exists until a camera is rendered.
"""

import array
import copy
import threading

from amr_description.core.gazebo.sensor_kinds import IMAGE_FORMATS
from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import named_topic
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
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


def depth_from_buffer(depth, near, far):
    """
    Return REP 117 depths (m) from MuJoCo's linearized depth buffer.

    :param depth: (H, W) float32, m along the optical axis; MuJoCo writes the far plane where
        nothing was drawn.
    :param near: m, closer hits are -inf.
    :param far: m, the far plane: hits at or beyond it are +inf.
    :returns: (H, W) float32.
    """
    out = depth.astype(np.float32, copy=True)
    out[depth >= far * (1.0 - 1e-5)] = np.inf
    out[depth < near] = -np.inf
    return out


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


class Frame:
    """
    What one render of a camera produced, before its messages are made.

    :ivar rgb: (H, W, 3) uint8 or None.
    :ivar depth: (H, W) float32 m (REP 117) or None.
    """

    def __init__(self, rgb=None, depth=None):
        """Keep the arrays."""
        self.rgb = rgb
        self.depth = depth


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


class _Job:
    """One instant's renders: the state copy and, per capture, its outputs and publishers."""

    __slots__ = ('model', 'qpos', 'mocap_pos', 'mocap_quat', 't', 'wanted')

    def __init__(self, t):
        self.t = t
        self.wanted = {}  # capture -> list of (output, publish)
        self.model = None


class CameraRenderer:
    """
    The render thread of a simulator's cameras (module docstring).

    Its OpenGL context (through ``mujoco.Renderer``, one per image size, reused; the
    offscreen buffer is sized for the largest registered camera) is made by the render
    thread at its first job, never when no camera renders. A model change (a spawn) makes
    new renderers over a private copy of the new model.

    :ivar frames: camera renders done (int).
    """

    def __init__(self):
        """Start nothing yet."""
        self._captures = []
        self._lock = threading.Condition()
        self._pending = None  # the _Job being filled by the simulation thread
        self._queue = []  # jobs submitted, not yet started
        self._busy = False
        self._thread = None
        self._closed = False
        self._model = None  # the simulation's model the renderers were made for
        self._copy = None  # its private copy (clip planes change per camera)
        self._data = None
        self._renderers = {}
        self.frames = 0
        self.errors = []

    @property
    def started(self):
        """Return True once the render thread (and so an OpenGL context) exists."""
        return self._thread is not None

    def register(self, capture):
        """Count a camera in (its size sizes the offscreen buffer)."""
        self._captures.append(capture)

    def want(self, capture, output, t, publish):
        """Add ``output`` of ``capture`` to the job of instant ``t`` (simulation thread)."""
        if self._pending is None or self._pending.t != t:
            self._pending = _Job(t)
        self._pending.wanted.setdefault(capture, []).append((output, publish))

    def flush(self, world, t):
        """
        Hand the job of instant ``t`` to the render thread with a copy of the state.

        Waits while an earlier job has not been started (module docstring).
        """
        job, self._pending = self._pending, None
        if job is None or job.t != t or self._closed:
            return
        data = world.data
        job.model = world.model
        job.qpos = data.qpos.copy()
        job.mocap_pos = data.mocap_pos.copy()
        job.mocap_quat = data.mocap_quat.copy()
        with self._lock:
            while self._queue and not self._closed:
                self._lock.wait(0.5)
            if self._closed:
                return
            self._queue.append(job)
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name='camera_render',
                                                daemon=True)
                self._thread.start()
            self._lock.notify_all()

    def idle(self, timeout=10.0):
        """Wait until every submitted job is rendered and published; return True if so."""
        with self._lock:
            return self._lock.wait_for(lambda: not self._queue and not self._busy, timeout)

    def close(self):
        """
        Stop the render thread after its current job and free its renderers.

        Without a render thread the renderers were made by :meth:`render_now` on the caller's
        thread, which holds their OpenGL context: they are freed here, on that thread (freed
        later by the garbage collector on another thread, EGL refuses: EGL_BAD_ACCESS).
        """
        with self._lock:
            self._closed = True
            self._queue.clear()
            self._lock.notify_all()
        if self._thread is None:
            self._free()
        elif self._thread is not threading.current_thread():
            self._thread.join(timeout=10.0)

    def _run(self):
        try:
            while True:
                with self._lock:
                    self._lock.wait_for(lambda: self._queue or self._closed)
                    if self._closed:
                        return
                    job = self._queue.pop(0)
                    self._busy = True
                    self._lock.notify_all()
                try:
                    self._render_job(job)
                except Exception as exc:  # noqa: B902 - one bad frame must not end the thread
                    if len(self.errors) < 10:
                        self.errors.append(f'camera render failed: {exc!r}')
                finally:
                    with self._lock:
                        self._busy = False
                        self._lock.notify_all()
        finally:
            self._free()

    def _render_job(self, job):
        import mujoco
        self._bind(job.model)
        data = self._data
        data.qpos[:] = job.qpos
        data.mocap_pos[:] = job.mocap_pos
        data.mocap_quat[:] = job.mocap_quat
        mujoco.mj_kinematics(self._copy, data)
        mujoco.mj_camlight(self._copy, data)
        for capture, wanted in job.wanted.items():
            frame = self._render(capture, [output for output, _ in wanted])
            for output, publish in wanted:
                publish(output.message(frame, job.t))

    def render_now(self, world, capture, outputs):
        """
        Render ``capture`` for ``outputs`` on the calling thread, from ``world``'s state.

        For tools and tests that have no render thread (the caller's thread then holds the
        OpenGL context); not mixed with :meth:`flush` on one renderer.
        """
        import mujoco
        self._bind(world.model)
        self._data.qpos[:] = world.data.qpos
        self._data.mocap_pos[:] = world.data.mocap_pos
        self._data.mocap_quat[:] = world.data.mocap_quat
        mujoco.mj_kinematics(self._copy, self._data)
        mujoco.mj_camlight(self._copy, self._data)
        return self._render(capture, outputs)

    def _bind(self, model):
        """Make the renderers for ``model`` unless they exist (render thread)."""
        import mujoco
        if model is self._model:
            return
        self._free()
        self._copy = copy.deepcopy(model)
        sizes = [(c.spec.width, c.spec.height) for c in self._captures]
        visual = self._copy.vis.global_
        visual.offwidth = max([w for w, _ in sizes] + [1])
        visual.offheight = max([h for _, h in sizes] + [1])
        self._data = mujoco.MjData(self._copy)
        self._model = model

    def _renderer(self, width, height):
        import mujoco
        key = (width, height)
        if key not in self._renderers:
            self._renderers[key] = mujoco.Renderer(self._copy, height=height, width=width)
        return self._renderers[key]

    def _render(self, capture, outputs):
        """Render what ``outputs`` of ``capture`` need; return a :class:`Frame` with noise."""
        import mujoco
        spec = capture.spec
        need_rgb, need_depth = capture.needs(outputs)
        renderer = self._renderer(spec.width, spec.height)
        camera = self._copy.camera(capture.camera).id
        clip = self._copy.vis.map
        extent = float(self._copy.stat.extent)
        frame = Frame()
        if need_rgb:
            clip.znear, clip.zfar = spec.near / extent, spec.far / extent
            renderer.update_scene(self._data, camera=camera)
            flags = renderer.scene.flags
            flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = flags[mujoco.mjtRndFlag.mjRND_SHADOW] = 0
            frame.rgb = renderer.render().copy()
        if need_depth:
            # rendered from a tenth of the near clip, so that nearer hits show as -inf
            clip.znear, clip.zfar = 0.1 * spec.depth_near / extent, spec.depth_far / extent
            renderer.enable_depth_rendering()
            try:
                renderer.update_scene(self._data, camera=camera)
                frame.depth = depth_from_buffer(renderer.render(), spec.depth_near,
                                                spec.depth_far)
            finally:
                renderer.disable_depth_rendering()
        capture.add_noise(frame)
        self.frames += 1
        return frame

    def _free(self):
        for renderer in self._renderers.values():
            renderer.close()
        self._renderers = {}
        self._model = None


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
