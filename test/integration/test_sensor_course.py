# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A held-out sensor course robot run as its course runs it: its xacro, its world, its bridge.

test/data/sensor_course: gz-sim DiffDrive, gpu_lidar, IMU, a 640x480 camera and a navsat
receiver (robot.urdf.xacro) in its own world (world.sdf, with <spherical_coordinates> and a
blue pillar whose near face is 2 m ahead), bridged by its ros_gz_bridge YAML (bridge.yaml) and
viewed with its RViz config (view.rviz). Every sensor reaches ROS on the topic the bridge
names; the camera sees the pillar at the image centre; the fix is the world's declared
origin; the viewer opened with ``-d view.rviz`` uses its Fixed Frame, shows the camera and
lists the Map display it does not have.
"""

import os

import pytest
from test_gz_systems import GzPeer  # noqa: I100 - the gz-sim systems' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
COURSE = os.path.join(ROOT, 'test', 'data', 'sensor_course')


class CoursePeer(GzPeer):
    """GzPeer plus the course's bridged sensor topics."""

    def __init__(self, domain_id):
        from sensor_msgs.msg import CameraInfo
        from sensor_msgs.msg import Image
        from sensor_msgs.msg import Imu
        from sensor_msgs.msg import LaserScan
        from sensor_msgs.msg import NavSatFix
        super().__init__(domain_id)
        self.seen = {}
        for topic, kind in (('/scan', LaserScan), ('/imu', Imu), ('/camera/image_raw', Image),
                            ('/camera/camera_info', CameraInfo), ('/gps/fix', NavSatFix)):
            self.seen[topic] = []
            self.node.create_subscription(kind, topic, self.seen[topic].append, 10)


@pytest.fixture
def peer(ros_env):
    pytest.importorskip('simulation_interfaces.srv')
    p = CoursePeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def test_the_course_robot_publishes_every_sensor_where_its_bridge_says_and_its_rviz_opens(
        procs, exe, ros_env, peer, tmp_path):
    import re
    import time
    import numpy as np
    from browser import colour_mask
    from browser import ensure_chromium
    from browser import free_port
    from browser import open_page
    sim = procs.start([exe('mujoco_sim'), '--ros-args',
                       '-p', f'world:={os.path.join(COURSE, "world.sdf")}',
                       '-p', f'bridge_config:={os.path.join(COURSE, "bridge.yaml")}'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    create = procs.start([exe('create'), '-file', os.path.join(COURSE, 'robot.urdf.xacro'),
                          '-z', '0.01'], ros_env)
    assert create.wait(90) == 0, create.output + sim.output
    assert peer.spin_until(lambda: all(peer.seen.values()), 120), \
        ({t: len(m) for t, m in peer.seen.items()}, sim.output[-3000:])
    image, info = peer.seen['/camera/image_raw'][-1], peer.seen['/camera/camera_info'][-1]
    assert (image.width, image.height, image.encoding, image.header.frame_id) == \
        (640, 480, 'rgb8', 'camera_link_optical')
    assert (info.width, info.height) == (640, 480)
    pixels = np.frombuffer(bytes(image.data), np.uint8).reshape(480, 640, 3).astype(int)
    r, g, b = pixels[240, 320]
    assert b > 120 and r < 80 and g < 80, (r, g, b)  # the blue pillar straight ahead
    scan = peer.seen['/scan'][-1]
    ahead = scan.ranges[len(scan.ranges) // 2]  # -3.14 .. 3.14: the middle ray looks ahead
    assert ahead == pytest.approx(2.0, abs=0.05)  # the pillar's face, 2 m from the lidar
    fix = peer.seen['/gps/fix'][-1]
    assert (fix.latitude, fix.longitude) == pytest.approx((-22.986687, -43.202501), abs=2e-6)
    # at rest the IMU reads the world's gravity; the first 0.2 s after the 1 cm drop of the
    # spawn bounce (8.8-14.5 m/s^2 measured), so read it a second of sim time after its first
    imu = peer.seen['/imu']

    def stamp(msg):
        return msg.header.stamp.sec + 1e-9 * msg.header.stamp.nanosec
    assert peer.spin_until(lambda: stamp(imu[-1]) >= stamp(imu[0]) + 1.0, 60), sim.output[-2000:]
    assert imu[-1].linear_acceleration.z == pytest.approx(9.8, abs=0.3)
    assert all(peer.node.count_publishers(t) == 0 for t in ('/navsat', '/camera/image'))

    assert ensure_chromium(), 'Debian chromium is missing: run scripts/setup'
    port = free_port()
    viewer = procs.start([exe('viewer'), '-d', os.path.join(COURSE, 'view.rviz'),
                          '--ros-args', '-p', f'port:={port}', '-p', 'use_sim_time:=true'],
                         ros_env)
    assert viewer.wait_for_output(f'viewer: open http://127.0.0.1:{port}/ in a browser',
                                  180.0), viewer.output[-3000:]
    with open_page(f'http://127.0.0.1:{port}/') as page:
        assert page.wait_for_text('RViz config', 120.0), page.page.inner_text('body')
        page.close_notifications()
        text = page.page.inner_text('body')
        assert 'RViz config view.rviz: every display shown' in text, text  # Map too
        assert 'Fixed Frame: odom' in text, text
        blue = rate = 0
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and (blue < 50 or rate < 2.0):
            shot = page.image_pixels(str(tmp_path / 'course.png'))  # the camera picture
            blue = 0 if shot is None else int(colour_mask(shot, (0, 0, 255), 60).sum())
            found = re.search(r'/camera/image_raw\s+([0-9.]+) Hz', page.page.inner_text('body'))
            rate = float(found.group(1)) if found else 0.0
            if blue < 50 or rate < 2.0:
                page.page.wait_for_timeout(500)
        assert blue >= 50 and rate >= 2.0, (blue, rate, page.page.inner_text('body'))
    assert sim.popen.poll() is None and viewer.popen.poll() is None
