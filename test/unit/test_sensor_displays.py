# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The viewer's sensor displays: what they draw from a message, against closed forms."""

import array
import math

from amr_description.web.displays.image import frustum_fov
from amr_description.web.displays.image import image_array
from amr_description.web.displays.image import info_topic
from amr_description.web.displays.imu import ACCEL_SCALE
from amr_description.web.displays.imu import GYRO_SCALE
from amr_description.web.displays.imu import imu_segments
from amr_description.web.displays.laser_scan import scan_points
from amr_description.web.displays.point_cloud import cloud_points
from amr_description.web.displays.sensor_topics import rainbow
import numpy as np
import pytest
from sensor_msgs.msg import CameraInfo
from sensor_msgs.msg import Image
from sensor_msgs.msg import Imu
from sensor_msgs.msg import LaserScan
from sensor_msgs.msg import PointCloud2
from sensor_msgs.msg import PointField


def test_scan_points_keep_the_valid_ranges_at_their_angles():
    msg = LaserScan(angle_min=-math.pi / 2, angle_increment=math.pi / 2, range_min=0.1,
                    range_max=5.0)
    msg.ranges = array.array('f', [1.0, math.inf, 2.0, -math.inf, 6.0, 0.05])
    points, ranges = scan_points(msg)
    assert ranges.tolist() == [1.0, 2.0]
    assert points == pytest.approx(np.array([[0.0, -1.0, 0.0], [0.0, 2.0, 0.0]]), abs=1e-6)


def test_cloud_points_read_gazebos_layout_and_drop_non_finite_points():
    data = np.zeros(3, dtype=np.dtype({'names': ['x', 'y', 'z', 'intensity', 'ring'],
                                       'formats': ['<f4', '<f4', '<f4', '<f4', '<u2'],
                                       'offsets': [0, 4, 8, 16, 24], 'itemsize': 32}))
    data['x'] = [1.0, np.inf, 3.0]
    data['y'] = [2.0, 0.0, -1.0]
    data['z'] = [0.5, 0.0, 0.25]
    msg = PointCloud2(height=1, width=3, point_step=32, row_step=96)
    msg.fields = [PointField(name=n, offset=o, datatype=PointField.FLOAT32, count=1)
                  for n, o in (('x', 0), ('y', 4), ('z', 8), ('intensity', 16))]
    msg.data = array.array('B', data.tobytes())
    assert cloud_points(msg).tolist() == [[1.0, 2.0, 0.5], [3.0, -1.0, 0.25]]
    msg.fields = msg.fields[1:]
    with pytest.raises(ValueError, match="without a float32 'x' field"):
        cloud_points(msg)


def test_imu_arrows_are_scaled_and_turned_into_the_fixed_frame():
    msg = Imu()
    msg.linear_acceleration.z = 9.8
    msg.angular_velocity.z = 1.0
    msg.linear_acceleration.x = math.nan
    T = np.eye(4)
    T[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]  # yaw 90 deg
    T[:3, 3] = [1.0, 2.0, 0.3]
    segments = imu_segments(msg, T)
    assert segments[0, 0] == pytest.approx([1.0, 2.0, 0.3])
    assert segments[0, 1] == pytest.approx([1.0, 2.0, 0.3 + 9.8 * ACCEL_SCALE])
    assert segments[1, 1] == pytest.approx([1.0, 2.0, 0.3 + GYRO_SCALE])
    msg.linear_acceleration.x, msg.linear_acceleration.z = 2.0, 0.0
    assert imu_segments(msg, T)[0, 1] == pytest.approx([1.0, 2.0 + 2 * ACCEL_SCALE, 0.3])


def test_rainbow_runs_from_red_to_blue():
    colours = rainbow([0.0, 0.5, 1.0], 0.0, 1.0)
    assert colours.tolist() == [[255, 0, 0], [0, 255, 0], [0, 0, 255]]


def _image_msg(encoding, pixels, step=None, bigendian=False):
    pixels = np.ascontiguousarray(pixels)
    msg = Image(height=pixels.shape[0], width=pixels.shape[1], encoding=encoding,
                is_bigendian=int(bigendian))
    raw = pixels.tobytes()
    msg.step = step or len(raw) // pixels.shape[0]
    if step:  # padded rows
        row = len(raw) // pixels.shape[0]
        raw = b''.join(raw[i * row:(i + 1) * row] + bytes(step - row)
                       for i in range(pixels.shape[0]))
    msg.data = array.array('B', raw)
    return msg


def test_images_of_every_shown_encoding_become_rgb():
    rgb = np.array([[[255, 0, 0], [0, 255, 0], [0, 0, 255]]], np.uint8)
    assert (image_array(_image_msg('rgb8', rgb)) == rgb).all()
    assert (image_array(_image_msg('bgr8', rgb[:, :, ::-1], step=12)) == rgb).all()
    rgba = np.concatenate([rgb, np.full((1, 3, 1), 7, np.uint8)], axis=2)
    assert (image_array(_image_msg('rgba8', rgba)) == rgb).all()
    grey = np.array([[0, 128, 255]], np.uint8)
    assert (image_array(_image_msg('mono8', grey))[:, :, 1] == grey).all()
    wide = np.array([[0, 32896, 65535]], '>u2')
    assert list(image_array(_image_msg('mono16', wide, bigendian=True))[0, :, 0]) == \
        [0, 128, 255]


def test_depth_images_are_grey_white_near_black_far_and_black_without_a_hit():
    depth = np.array([[1.0, 2.0, 3.0, np.inf, np.nan]], '<f4')
    grey = image_array(_image_msg('32FC1', depth))[0, :, 0]
    assert list(grey) == [255, 155, 55, 0, 0]


def test_an_unknown_encoding_or_short_data_is_a_value_error():
    with pytest.raises(ValueError, match="encoding 'yuv422'"):
        image_array(_image_msg('yuv422', np.zeros((2, 2, 2), np.uint8)))
    msg = _image_msg('rgb8', np.zeros((2, 2, 3), np.uint8))
    msg.height = 3
    with pytest.raises(ValueError, match='12 bytes, step 6'):
        image_array(msg)


def test_the_frustum_takes_the_vertical_fov_of_k_and_the_sibling_camera_info():
    f = 320 / (2 * math.tan(1.047 / 2))
    info = CameraInfo(width=320, height=240, k=[f, 0, 160, 0, f, 120, 0, 0, 1])
    fov, aspect = frustum_fov(info)
    assert fov == pytest.approx(2 * math.atan(120 / f)) and aspect == pytest.approx(4 / 3)
    assert frustum_fov(CameraInfo()) is None
    assert info_topic('/camera/image') == '/camera/camera_info'
    assert info_topic('/r1/front/image_raw') == '/r1/front/camera_info'


def test_a_fix_is_one_line_of_degrees_hemispheres_and_metres():
    from amr_description.web.displays.navsat import fix_text
    from sensor_msgs.msg import NavSatFix
    fix = NavSatFix(latitude=47.397742, longitude=-8.545594, altitude=488.4)
    assert fix_text('/gps/fix', fix) == '`/gps/fix` 47.3977420° N, 8.5455940° W, 488.40 m'
    fix.status.status = -1
    assert fix_text('/gps/fix', fix).endswith('(no fix)')


def test_contact_points_are_the_positions_and_normals_of_every_contact():
    from amr_description.web.displays.contacts import contact_points
    from geometry_msgs.msg import Vector3
    from ros_gz_interfaces.msg import Contact
    from ros_gz_interfaces.msg import Contacts
    msg = Contacts(contacts=[
        Contact(positions=[Vector3(x=1.0, y=2.0, z=0.0), Vector3(x=1.5, y=2.0, z=0.0)],
                normals=[Vector3(z=-1.0), Vector3(z=-1.0)]),
        Contact(positions=[Vector3(x=0.3, y=0.0, z=0.1)], normals=[Vector3(x=1.0)])])
    points, normals = contact_points(msg)
    assert np.allclose(points, [[1, 2, 0], [1.5, 2, 0], [0.3, 0, 0.1]])
    assert normals.tolist() == [[0, 0, -1], [0, 0, -1], [1, 0, 0]]
    assert contact_points(Contacts())[0].shape == (0, 3)


def test_a_compressed_topic_decodes_and_its_camera_info_is_the_base_topics_sibling():
    import io

    from amr_description.web.displays.image import compressed_array
    from PIL import Image as PilImage
    from sensor_msgs.msg import CompressedImage
    buffer = io.BytesIO()
    PilImage.fromarray(np.full((4, 6, 3), (200, 10, 10), np.uint8)).save(buffer, format='PNG')
    msg = CompressedImage(format='rgb8; png compressed bgr8',
                          data=array.array('B', buffer.getvalue()))
    assert compressed_array(msg).shape == (4, 6, 3)
    assert compressed_array(msg)[0, 0].tolist() == [200, 10, 10]
    with pytest.raises(ValueError, match='does not decode'):
        compressed_array(CompressedImage(format='jpeg', data=array.array('B', b'junk')))
    assert info_topic('/camera/compressed') == '/camera_info'
    assert info_topic('/camera/image/compressed') == '/camera/camera_info'


class _FakeLogger:

    def __init__(self):
        self.lines = []

    def info(self, text):
        self.lines.append(text)

    warning = error = info


class _FakeNode:

    def __init__(self):
        self.logger = _FakeLogger()
        self.subscriptions = {}

    def get_logger(self):
        return self.logger

    def create_subscription(self, kind, topic, callback, qos):
        self.subscriptions[topic] = callback


class _FakeSceneNode:

    def __init__(self):
        self.wxyz, self.position = None, None


class _FakeScene:

    def __init__(self):
        self.nodes = {}

    def add_mesh_trimesh(self, name, mesh):
        self.nodes[name] = _FakeSceneNode()
        return self.nodes[name]


class _FakeServer:

    def __init__(self):
        self.scene = _FakeScene()


class _FixedFrameIsWorld:

    def pose(self, frame):
        return None  # no TF: the world is drawn in the fixed frame


def test_the_world_display_moves_a_pushed_box_to_its_published_pose():
    from amr_description.web.displays.world import WorldDisplay
    from geometry_msgs.msg import TransformStamped
    from tf2_msgs.msg import TFMessage
    node, server = _FakeNode(), _FakeServer()
    display = WorldDisplay(node, server, None, 'warehouse')
    assert display.topic == '/world/warehouse/dynamic_pose/info'
    assert '/world' in server.scene.nodes  # the shelves and walls, one node
    boxes = [n for name, n in server.scene.nodes.items() if name.startswith('/world_moving/')]
    assert len(boxes) == 3
    display.draw(_FixedFrameIsWorld())
    assert list(boxes[0].position) == pytest.approx([1.0, -1.2, 0.2])  # warehouse.sdf box_0
    box_1 = list(boxes[1].position)
    moved_box = TransformStamped(child_frame_id='box_0/link')
    moved_box.transform.translation.x, moved_box.transform.translation.y = 1.0, -1.9
    moved_box.transform.rotation.z, moved_box.transform.rotation.w = math.sin(0.25), \
        math.cos(0.25)
    garbage = TransformStamped(child_frame_id='box_1/link')
    garbage.transform.translation.x = math.nan
    node.subscriptions[display.topic](TFMessage(transforms=[moved_box, garbage]))
    display.draw(_FixedFrameIsWorld())
    assert list(boxes[0].position) == pytest.approx([1.0, -1.9, 0.0])
    assert list(boxes[0].wxyz) == pytest.approx([math.cos(0.25), 0, 0, math.sin(0.25)])
    assert list(boxes[1].position) == box_1  # a non-finite pose is ignored
