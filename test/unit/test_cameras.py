# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Cameras against closed forms: reading ``<camera>``, pixels, depth, K, frames and threads.

The world is test/data/worlds/camera_targets.sdf: a red wall with its front face on the plane
x = 3 m and a green 0.1 m cube whose front face is at x = 2.5 m, centred at y = 0.6, z = 0.5.
A pinhole camera at (0, 0, h) looking along +x with ``fx = fy = W / (2 tan(hfov / 2))``,
``cx = W / 2``, ``cy = H / 2`` sees a point (x, y, z) at column ``cx - fx y / x`` and row
``cy - fy (z - h) / x``; the wall at depth ``3`` everywhere; the ground (z = 0) in row v at
depth ``h fy / (v + 0.5 - cy)``.
"""

import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from amr_description.core.description.files import read_description
from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.gazebo.sensors import read_sensor
from amr_description.core.gazebo.sensors import SensorError
from amr_description.sim.simulation import Simulation
import numpy as np
import pytest
from sim_fixtures import ListLog as _Log  # noqa: I100 - the unit tests' helpers
from sim_fixtures import PROBE_BASE  # noqa: I100 - the unit tests' helpers

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
XACRO = os.path.join(ROOT, 'urdf', 'amr.urdf.xacro')
TARGETS = os.path.join(ROOT, 'test', 'data', 'worlds', 'camera_targets.sdf')
HEIGHT = 0.5  # m, the camera above the ground: the probe's base (0.1) + 0.4


def _camera(kind='rgbd_camera', size=(320, 240), fov=1.047, optical='camera_optical',
            extra='', depth_clip=(0.1, 10.0), noise=''):
    optical_tag = f'<optical_frame_id>{optical}</optical_frame_id>' if optical else ''
    return f"""<sensor name="cam" type="{kind}"><update_rate>10</update_rate><topic>cam</topic>
      <camera><horizontal_fov>{fov}</horizontal_fov>
      <image><width>{size[0]}</width><height>{size[1]}</height></image>
      <clip><near>0.1</near><far>100</far></clip>
      <depth_camera><clip><near>{depth_clip[0]}</near><far>{depth_clip[1]}</far></clip>
      </depth_camera>{noise}{optical_tag}{extra}</camera></sensor>"""


def _robot(camera_block):
    return f"""<robot name="probe">
  {PROBE_BASE}
  <link name="camera_link"/>
  <joint name="camera_joint" type="fixed"><parent link="base_link"/><child link="camera_link"/>
    <origin xyz="0 0 0.4"/></joint>
  <link name="camera_optical"/>
  <joint name="optical_joint" type="fixed"><parent link="camera_link"/>
    <child link="camera_optical"/><origin rpy="-1.5707963267948966 0 -1.5707963267948966"/>
  </joint>
  <gazebo reference="camera_link">{camera_block}</gazebo>
</robot>"""


def _spawn(camera_block, seed=0):
    sim = Simulation(physics_step=0.001, real_time_factor=0.0, logger=_Log(),
                     sensor_settings={'seed': seed, 'publish_ground_truth': False},
                     world=read_world(TARGETS))
    entity = sim.spawn(_robot(camera_block), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    while sim.step_count < 100:
        sim.run_cycle()
    return sim, entity, {sensor.name: sensor for sensor in entity.sensors}


def _image(msg):
    channels = {'rgb8': 3, 'bgr8': 3, 'mono8': 1}[msg.encoding]
    return np.frombuffer(bytes(msg.data), np.uint8).reshape(msg.height, msg.width, channels)


def _depth(msg):
    assert msg.encoding == '32FC1' and msg.step == 4 * msg.width
    return np.frombuffer(bytes(msg.data), '<f4').reshape(msg.height, msg.width)


def _points(msg):
    dtype = np.dtype({'names': ['x', 'y', 'z', 'rgb'], 'formats': ['<f4'] * 4,
                      'offsets': [0, 4, 8, 16], 'itemsize': 24})
    return np.frombuffer(bytes(msg.data), dtype).reshape(msg.height, msg.width)


@pytest.fixture(scope='module')
def rgbd():
    sim, entity, sensors = _spawn(_camera())
    yield sim, sensors
    sim.close()


# ----------------------------------------------------------------------------- reading

def _read(block):
    return read_sensor(ET.fromstring(block), 'camera_link')


def test_sdf_defaults_and_the_intrinsics_from_the_field_of_view():
    block = _read('<sensor name="c" type="camera"/>')
    camera = block.camera
    assert (block.kind, camera.width, camera.height, camera.format) == \
        ('camera', 320, 240, 'R8G8B8')
    assert (camera.horizontal_fov, camera.near, camera.far) == (1.047, 0.1, 100.0)
    fx, fy, cx, cy = camera.k()
    assert fx == fy == pytest.approx(320 / (2 * math.tan(1.047 / 2)))
    assert (cx, cy) == (160.0, 120.0)
    assert fx == pytest.approx(277.19, abs=0.01)  # sdformat's camera.sdf default fx, 277
    given = _read(_camera(extra='<lens><intrinsics><fx>300</fx><fy>310</fy><cx>150</cx>'
                                '<cy>110</cy></intrinsics></lens>')).camera
    assert given.k() == (300.0, 310.0, 150.0, 110.0)


@pytest.mark.parametrize('block, field', [
    (_camera(size=(5000, 240)), '<image><width>: expected 1 to 4096 pixels, found 5000'),
    (_camera(size=(320, 0)), '<image><height>: expected 1 to 4096 pixels, found 0'),
    (_camera(size=(-3, 240)), '<image><width>: expected 1 to 4096 pixels, found -3'),
    (_camera(depth_clip=(5, 2)), '<depth_camera><clip><far>: expected > near 5'),
    (_camera(extra='').replace('<far>100</far>', '<far>0.05</far>'),
     '<clip><far>: expected > near 0.1'),
    (_camera(extra='').replace('</image>', '<format>YUV_WEIRD</format></image>'),
     '<image><format>: expected one of R8G8B8'),
    (_camera(fov=4.0), '<horizontal_fov>: expected 0.01 to pi rad'),
])
def test_bad_camera_fields_are_one_line_naming_the_sensor_and_the_field(block, field):
    with pytest.raises(SensorError) as error:
        _read(block)
    text = str(error.value)
    assert text.startswith("sensor 'cam': <camera>") and field in text, text
    assert '\n' not in text


def test_a_bad_camera_is_skipped_and_the_robot_spawns_with_its_other_sensors():
    imu = '<sensor name="imu" type="imu"><update_rate>100</update_rate></sensor>'
    sim = Simulation(physics_step=0.001, real_time_factor=0.0, logger=_Log(),
                     sensor_settings={'publish_ground_truth': False}, world=read_world(TARGETS))
    entity = sim.spawn(_robot(_camera(size=(5000, 240)) + imu), name='probe',
                       pose=[0, 0, 0.1, 0, 0, 0, 1])
    assert [s.name for s in entity.sensors] == ['imu']
    assert any("sensor 'cam': <camera><image><width>" in line and 'skipped' in line
               for line in sim.logger.lines), sim.logger.lines
    sim.close()


def test_our_robot_mounts_an_rgbd_camera_with_camera_true_and_its_optical_frame():
    description = RobotDescription(read_description(XACRO, {'camera': 'true'}))
    (block,) = [b for b in description.sensors.sensors if b.camera is not None]
    camera = block.camera
    assert (block.kind, block.link, block.update_rate, block.topic) == \
        ('rgbd', 'camera_link', 10.0, 'camera')
    assert (camera.width, camera.height, camera.horizontal_fov) == (320, 240, 1.047)
    assert camera.optical_frame_id == 'camera_optical_link'
    joint = description.model.parent_joint['camera_optical_link']
    rotation = np.asarray(joint.origin)[:3, :3]  # optical axes in camera_link's (REP 103)
    assert np.allclose(rotation @ [0, 0, 1], [1, 0, 0], atol=1e-9)  # z forward
    assert np.allclose(rotation @ [1, 0, 0], [0, -1, 0], atol=1e-9)  # x right
    assert np.allclose(rotation @ [0, 1, 0], [0, 0, -1], atol=1e-9)  # y down
    without = RobotDescription(read_description(XACRO))
    assert not [b for b in without.sensors.sensors if b.camera is not None]


# ----------------------------------------------------------------------------- topics

def test_rgbd_topics_are_gz_sensors_and_camera_topics_have_siblings(rgbd):
    _, sensors = rgbd
    topics = {s.name: (s.topic, s.message_type.__name__) for s in sensors.values()}
    assert topics == {'cam/image': ('/cam/image', 'Image'),
                      'cam/depth': ('/cam/depth_image', 'Image'),
                      'cam/points': ('/cam/points', 'PointCloud2'),
                      'cam/info': ('/cam/camera_info', 'CameraInfo'),
                      'cam/compressed': ('/cam/image/compressed', 'CompressedImage')}
    sim, entity, plain = _spawn(_camera(kind='camera', optical='').replace(
        '<topic>cam</topic>', '<topic>front/image_raw</topic>'))
    assert {s.topic for s in plain.values()} == {
        '/front/image_raw', '/front/camera_info', '/front/image_raw/compressed'}
    sim.close()


def test_camera_info_k_and_p_from_the_field_of_view_and_the_same_stamp_as_the_image(rgbd):
    sim, sensors = rgbd
    info = sensors['cam/info'].measure(sim.world, 0.1)
    image = sensors['cam/image'].measure(sim.world, 0.1)
    f = 320 / (2 * math.tan(1.047 / 2))
    assert (info.width, info.height, info.distortion_model) == (320, 240, 'plumb_bob')
    assert list(info.d) == [0.0] * 5
    assert list(info.k) == pytest.approx([f, 0, 160, 0, f, 120, 0, 0, 1])
    assert list(info.p) == pytest.approx([f, 0, 160, 0, 0, f, 120, 0, 0, 0, 1, 0])
    assert info.header == image.header
    assert (image.header.frame_id, image.header.stamp.sec, image.header.stamp.nanosec) == \
        ('camera_optical', 0, 100_000_000)


# ----------------------------------------------------------------------------- pixels

def test_the_green_cube_is_at_the_pinhole_projection_and_the_wall_is_red(rgbd):
    sim, sensors = rgbd
    image = sensors['cam/image'].measure(sim.world, 0.1)
    assert (image.encoding, image.step) == ('rgb8', 960)
    rgb = _image(image).astype(int)
    green = np.argwhere((rgb[:, :, 1] > 120) & (rgb[:, :, 0] < 80) & (rgb[:, :, 2] < 80))
    f = 320 / (2 * math.tan(1.047 / 2))
    x = 2.5  # the cube's front face (the face the camera sees)
    row, column = green.mean(axis=0) + 0.5  # pixel centres
    assert column == pytest.approx(160 - f * 0.6 / x, abs=1.0)
    assert row == pytest.approx(120 - f * (0.5 - HEIGHT) / x, abs=1.0)
    width = green[:, 1].max() - green[:, 1].min() + 1
    assert width == pytest.approx(f * 0.1 / x, abs=1.5)
    r, g, b = rgb[120, 160]
    assert r > 150 and g < 100 and b < 100  # the red wall straight ahead


def test_depth_is_the_distance_along_the_axis_inf_without_a_hit_and_the_ground_in_closed_form(
        rgbd):
    sim, sensors = rgbd
    depth = _depth(sensors['cam/depth'].measure(sim.world, 0.1))
    f = 320 / (2 * math.tan(1.047 / 2))
    wall = depth[100:140, 200:260]  # the red wall, right of the cube
    assert np.max(np.abs(wall - 3.0)) < 1e-3  # one depth-buffer step ~ 6e-5 m at 3 m
    assert np.isposinf(depth[0]).all()  # the sky above the wall: +inf, not the far plane
    for v in (230, 239):
        expected = HEIGHT * f / (v + 0.5 - 120)
        assert depth[v, 160] == pytest.approx(expected, abs=2e-3)


def test_points_in_the_optical_frame_and_in_the_sensor_frame_without_one(rgbd):
    sim, sensors = rgbd
    cloud = sensors['cam/points'].measure(sim.world, 0.1)
    assert [(f.name, f.offset, f.datatype) for f in cloud.fields] == \
        [('x', 0, 7), ('y', 4, 7), ('z', 8, 7), ('rgb', 16, 7)]
    assert (cloud.point_step, cloud.row_step, cloud.height, cloud.width) == \
        (24, 24 * 320, 240, 320)
    assert cloud.header.frame_id == 'camera_optical' and not cloud.is_dense
    points = _points(cloud)
    centre = points[119, 159]  # the pixel left of and above the centre
    f = 320 / (2 * math.tan(1.047 / 2))
    assert (centre['x'], centre['y'], centre['z']) == pytest.approx(
        (-0.5 * 3 / f, -0.5 * 3 / f, 3.0), abs=2e-3)  # optical: z forward, x right, y down
    colour = np.frombuffer(cloud.data, np.uint8).reshape(240, 320, 24)[120, 240, 16:20]
    assert colour[2] > 150 and colour[0] < 100 and colour[1] < 100, colour  # b, g, r: red
    sim2, _, plain = _spawn(_camera(kind='depth_camera', optical=''))
    cloud = plain['cam/points'].measure(sim2.world, 0.1)
    assert cloud.header.frame_id == 'camera_link'
    centre = _points(cloud)[119, 159]
    assert (centre['x'], centre['y'], centre['z']) == pytest.approx(
        (3.0, 0.5 * 3 / f, 0.5 * 3 / f), abs=2e-3)  # the link: x forward, y left, z up
    sim2.close()


def test_mono8_is_the_luma_of_rgb8_and_jpeg_decodes_to_the_image(rgbd):
    from io import BytesIO

    from PIL import Image
    sim, sensors = rgbd
    rgb = _image(sensors['cam/image'].measure(sim.world, 0.1)).astype(float)
    jpeg = sensors['cam/compressed'].measure(sim.world, 0.1)
    assert jpeg.format == 'rgb8; jpeg compressed bgr8'
    decoded = np.asarray(Image.open(BytesIO(bytes(jpeg.data))))
    assert decoded.shape == (240, 320, 3)
    assert np.mean(np.abs(decoded - rgb)) < 4.0  # JPEG quality 80
    simm, _, mono = _spawn(_camera(kind='camera').replace(
        '</image>', '<format>L8</format></image>'))
    grey = _image(mono['cam/image'].measure(simm.world, 0.1))[:, :, 0].astype(float)
    luma = rgb @ [0.299, 0.587, 0.114]
    assert np.max(np.abs(grey - luma)) <= 0.5 + 1e-9
    simm.close()


def test_gaussian_depth_noise_has_the_declared_stddev():
    noise = '<noise><type>gaussian</type><mean>0</mean><stddev>0.05</stddev></noise>'
    sim, _, sensors = _spawn(_camera(kind='depth_camera', noise=noise))
    depth = _depth(sensors['cam/depth'].measure(sim.world, 0.1))
    error = depth[100:140, 200:260] - 3.0
    assert abs(float(np.mean(error))) < 0.01
    assert float(np.std(error)) == pytest.approx(0.05, rel=0.1)
    sim.close()


# ----------------------------------------------------------------------------- threads

def test_the_render_thread_publishes_every_due_frame_with_shared_stamps():
    sim, entity, sensors = _spawn(_camera())
    renderer = sim.sensor_settings['camera_renderer']
    stamps = {}

    def publish(name):  # a publisher serializes at once: the message may be reused
        return lambda msg: stamps.setdefault(name, []).append(
            msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9)

    for k in range(1, 11):  # 1 s of sim time at 10 Hz
        t = round(k * 0.1, 9)
        for name in ('cam/image', 'cam/info', 'cam/depth'):
            target = sensors[name].request(t, publish(name))
        target.flush(sim.world, t)
    assert renderer.idle(60.0) and renderer.started
    assert stamps['cam/image'] == pytest.approx([k * 0.1 for k in range(1, 11)])
    assert stamps['cam/info'] == stamps['cam/image'] == stamps['cam/depth']
    assert renderer.errors == []
    sim.close()
    assert not renderer._thread.is_alive()


def test_no_gl_context_without_a_camera():
    """
    A robot without a camera makes no OpenGL context (mujoco_ros2_control#198).

    Observed as Mesa's software rasterizer threads (``llvmpipe-N``), which a context starts.
    """
    script = f"""
import glob, os, sys
sys.path.insert(0, {HERE!r})
from test_cameras import _spawn, _camera
lidar = '<sensor name="imu" type="imu"><update_rate>100</update_rate></sensor>'
sim, entity, sensors = _spawn(lidar if sys.argv[1] == 'none' else _camera())
for sensor in sensors.values():
    sensor.measure(sim.world, 0.1)
threads = [open(p).read() for p in glob.glob('/proc/self/task/*/comm')]
print('GL' if any('llvmpipe' in t for t in threads) else 'no GL',
      sim.sensor_settings['camera_renderer'].started)
sim.close()
"""
    env = dict(os.environ)
    runs = {kind: subprocess.run([sys.executable, '-c', script, kind], env=env,
                                 capture_output=True, text=True, timeout=120)
            for kind in ('none', 'camera')}
    assert runs['none'].stdout.split() == ['no', 'GL', 'False'], runs['none'].stderr[-2000:]
    assert runs['camera'].stdout.split()[0] == 'GL', runs['camera'].stderr[-2000:]


def test_the_ground_has_no_speckles():
    """No dark specks on the lit floor (MuJoCo's shadow map left 47 in this view)."""
    sim, _, sensors = _spawn(_camera(kind='camera'))
    rgb = _image(sensors['cam/image'].measure(sim.world, 0.1)).astype(int)
    grey = rgb[150:240].mean(axis=2)  # the ground below the wall
    assert int((grey < np.median(grey, axis=1, keepdims=True) - 40).sum()) == 0
    sim.close()
