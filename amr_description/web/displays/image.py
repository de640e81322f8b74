# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Image and Camera: the live picture of every image topic, and the camera's frustum in the scene.

As RViz's Image display, a panel shows the newest ``sensor_msgs/Image`` of each
``image_topics`` entry (reliable, :data:`IMAGE_QOS`; JPEG to the page, at most :data:`RATE`
times a second); as its Camera
display, the camera's view volume is drawn at the image's ``header.frame_id`` in the fixed
frame (an optical frame, REP 103: z forward, x right, y down, which is viser's camera
convention), with the vertical field of view and aspect of the sibling ``camera_info``
(``2 atan(height / (2 fy))``). Encodings shown: ``rgb8``, ``bgr8``, ``rgba8``, ``bgra8``,
``mono8``, ``mono16`` and ``32FC1`` / ``16UC1`` depth (grey, white near, black far, as RViz's
Image display normalises depth); another encoding is one throttled warning. A topic ending in
``/compressed`` is image_transport's compressed transport (``sensor_msgs/CompressedImage``,
JPEG or PNG), as RViz's displays take it; its camera_info is its base topic's sibling.

The topics are subscribed only while a page is open and the display is checked: a simulated
camera renders only while someone subscribes, so a closed page costs the simulator nothing.
"""

import threading
import time

from amr_description.web.displays.base import Display
from amr_description.web.displays.base import Rate
from amr_description.web.displays.discovery import AUTO
from amr_description.web.robot_scene import wxyz_position
import numpy as np
from rclpy.qos import qos_profile_sensor_data
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from sensor_msgs.msg import CameraInfo
from sensor_msgs.msg import CompressedImage
from sensor_msgs.msg import Image

RATE = 10.0
"""Images sent to the page per second at most."""
IMAGE_QOS = QoSProfile(depth=2, reliability=ReliabilityPolicy.RELIABLE)
"""Images are subscribed reliable, as RViz's Image display does by default: a 640x480 frame
(0.9 MB) is larger than Fast DDS's shared-memory segment, and a best-effort reader lost most
of them (measured: 3.4 of 10 Hz arrived)."""
JPEG_QUALITY = 75
FRUSTUM_SCALE = 0.15
"""m: the depth of the drawn view volume."""
CHANNELS = {'rgb8': 3, 'bgr8': 3, 'rgba8': 4, 'bgra8': 4, 'mono8': 1}


def image_array(msg):
    """
    Return an (H, W, 3) uint8 RGB picture of a ``sensor_msgs/Image``.

    Depth (``32FC1`` metres, ``16UC1`` millimetres) becomes grey between the nearest and the
    farthest finite value (white near; non-finite and zero black).

    :raises ValueError: for an encoding not shown, or a ``data`` shorter than ``step *
        height``.
    """
    height, width, step, encoding = msg.height, msg.width, msg.step, msg.encoding
    data = np.frombuffer(bytes(msg.data), np.uint8)
    if step * height > data.size or height == 0 or width == 0:
        raise ValueError(f'{encoding} image of {width}x{height}: {data.size} bytes, step {step}')
    rows = data[:step * height].reshape(height, step)
    if encoding in CHANNELS:
        channels = CHANNELS[encoding]
        pixels = rows[:, :width * channels].reshape(height, width, channels)
        if channels == 1:
            return np.repeat(pixels, 3, axis=2)
        pixels = pixels[:, :, :3]
        return np.ascontiguousarray(pixels[:, :, ::-1] if encoding.startswith('bgr') else pixels)
    order = '>' if msg.is_bigendian else '<'
    if encoding == 'mono16':
        values = rows[:, :width * 2].copy().view(order + 'u2')
        grey = (values >> 8).astype(np.uint8)
        return np.repeat(grey[:, :, None], 3, axis=2)
    if encoding in ('32FC1', '16UC1'):
        kind = order + ('f4' if encoding == '32FC1' else 'u2')
        depth = rows[:, :width * (4 if encoding == '32FC1' else 2)].copy().view(kind)
        depth = depth.astype(np.float64)
        valid = np.isfinite(depth) & (depth > 0)
        grey = np.zeros(depth.shape, np.uint8)
        if valid.any():
            near, far = depth[valid].min(), depth[valid].max()
            span = far - near if far > near else 1.0
            grey[valid] = (255 - 200 * (depth[valid] - near) / span).astype(np.uint8)
        return np.repeat(grey[:, :, None], 3, axis=2)
    raise ValueError(f'encoding {encoding!r} is not shown (rgb8, bgr8, rgba8, bgra8, mono8, '
                     'mono16, 32FC1, 16UC1)')


def compressed_array(msg):
    """
    Return an (H, W, 3) uint8 RGB picture of a ``sensor_msgs/CompressedImage`` (JPEG or PNG).

    :raises ValueError: when the data is not a picture Pillow reads.
    """
    import io

    from PIL import Image as PilImage
    from PIL import UnidentifiedImageError
    try:
        picture = PilImage.open(io.BytesIO(bytes(msg.data)))
        return np.asarray(picture.convert('RGB'))
    except (UnidentifiedImageError, OSError) as exc:
        raise ValueError(f'compressed image ({msg.format!r}) does not decode: {exc}') from None


def base_topic(topic):
    """Return image_transport's base topic: ``/camera/compressed`` -> ``/camera``."""
    return topic[:-len('/compressed')] if topic.endswith('/compressed') else topic


def frustum_fov(info):
    """Return ``(vertical fov rad, aspect)`` of a ``sensor_msgs/CameraInfo``, or None."""
    fy = info.k[4] if len(info.k) == 9 else 0.0
    if not (fy > 0 and info.width > 0 and info.height > 0):
        return None
    return 2.0 * np.arctan(0.5 * info.height / fy), info.width / info.height


def info_topic(image_topic):
    """Return the ``camera_info`` beside an image topic (image_transport's rule)."""
    return base_topic(image_topic).rsplit('/', 1)[0] + '/camera_info'


class _Camera:

    def __init__(self):
        self.image = None
        self.info = None
        self.shown = None
        self.panel = None
        self.frustum = None
        self.rate = Rate()
        self.subscriptions = []


class ImageDisplay(Display):
    """The images of ``topics`` in the panel and their cameras in the scene."""

    label = 'Image'
    order = 53
    parameters = (('image_topics', [AUTO]),)
    topics_parameter = 'image_topics'
    rviz_classes = {'rviz_default_plugins/Image': 'image_topics',
                    'rviz_default_plugins/Camera': 'image_topics'}

    def __init__(self, node, server, frames, topics):
        """Keep the topics; they are subscribed when a page opens (module docstring)."""
        super().__init__(node, server, frames)
        self._lock = threading.Lock()
        # found together, colour pictures come before depth ones (the first is the largest)
        named = self.take_topics(topics, [Image], key=lambda t: ('depth' in t, t))
        self._cameras = {topic: _Camera() for topic in named}
        self._next = 0.0
        self._show = None
        self._folder = None

    def add_topic(self, topic):
        """Add a camera (subscribed with the others while a page is open)."""
        self._cameras[topic] = _Camera()

    def build_panel(self, gui):
        """Add the folder the pictures go in (hidden until the first picture)."""
        self._folder = gui.add_folder('Camera', visible=False)

    def build(self, gui):
        """Add the checkbox."""
        self._show = gui.add_checkbox(self.label, True)

    def rates(self):
        """Return ``[(topic, Rate)]`` of the image topics (for the status)."""
        return [(topic, camera.rate) for topic, camera in list(self._cameras.items())]

    def _on_image(self, topic, msg):
        camera = self._cameras[topic]
        camera.rate.tick(time.monotonic())
        with self._lock:
            camera.image = msg

    def _on_info(self, topic, msg):
        with self._lock:
            self._cameras[topic].info = msg

    def _subscribe(self, on):
        """Create or destroy the subscriptions (executor thread)."""
        for topic, camera in list(self._cameras.items()):
            if on and not camera.subscriptions:
                kind = CompressedImage if topic.endswith('/compressed') else Image
                camera.subscriptions = [
                    self.node.create_subscription(
                        kind, topic, lambda msg, t=topic: self._on_image(t, msg), IMAGE_QOS),
                    self.node.create_subscription(
                        CameraInfo, info_topic(topic), lambda msg, t=topic: self._on_info(t, msg),
                        qos_profile_sensor_data)]
            elif not on and camera.subscriptions:
                for subscription in camera.subscriptions:
                    self.node.destroy_subscription(subscription)
                camera.subscriptions = []

    def hidden(self):
        """No page is open: stop listening (the simulator stops rendering)."""
        self._subscribe(False)

    def draw(self, context):
        """Send the newest image of each topic, at most :data:`RATE` times a second."""
        show = self._show is None or self._show.value
        self._subscribe(show)
        now = time.monotonic()
        for camera in self._cameras.values():
            for handle in (camera.panel, camera.frustum):
                if handle is not None and handle.visible != show:
                    handle.visible = show
        if not show or now < self._next:
            return
        self._next = now + 1.0 / RATE
        for topic, camera in self._cameras.items():
            with self._lock:
                image, info = camera.image, camera.info
            if image is None or image is camera.shown:
                continue
            camera.shown = image
            try:
                pixels = compressed_array(image) if isinstance(image, CompressedImage) \
                    else image_array(image)
            except ValueError as exc:
                self.node.get_logger().warning(f'Image {topic}: cannot show: {exc}',
                                               throttle_duration_sec=5.0)
                continue
            if camera.panel is None:
                with self._folder:
                    camera.panel = self.server.gui.add_image(
                        pixels, label=topic, format='jpeg', jpeg_quality=JPEG_QUALITY)
                self._folder.visible = True
            else:
                camera.panel.image = pixels
            self._draw_frustum(context, topic, camera, image, info)

    def _draw_frustum(self, context, topic, camera, image, info):
        fov = frustum_fov(info) if info is not None else None
        frame = image.header.frame_id.lstrip('/')
        T = context.pose(frame) if frame != context.fixed else np.eye(4)
        if fov is None or T is None:
            if T is None:
                context.missing.append(frame)
            return
        wxyz, position = wxyz_position(T)
        if camera.frustum is None:
            camera.frustum = self.server.scene.add_camera_frustum(
                '/camera/' + topic.strip('/').replace('/', '_'), fov=float(fov[0]),
                aspect=float(fov[1]), scale=FRUSTUM_SCALE, thickness=2.0,
                thickness_units='screen', color=(240, 160, 20), wxyz=wxyz,
                position=position)
        else:
            camera.frustum.wxyz, camera.frustum.position = wxyz, position
