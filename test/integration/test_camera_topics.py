# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Camera topics through DDS, as a Gazebo user's nodes receive them from ros_gz_bridge.

Our robot with ``camera:=true`` (urdf/amr.urdf.xacro: RGB-D camera, 320x240, 10 Hz, optical
frame camera_optical_link, 0.26 m ahead of base_link) is spawned with ``create -string`` into
test/data/worlds/camera_targets.sdf, whose red wall's front face is the plane x = 3 m. The
simulator is paused and stepped 1 s: ten images, depth images and camera infos arrive, stamped
0.1 s apart with shared stamps, and the depth straight ahead is the distance from the lens to
the wall.
"""

import math
import os

import pytest
from test_gz_systems import GzPeer  # noqa: I100 - the gz-sim systems' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
XACRO = os.path.join(ROOT, 'urdf', 'amr.urdf.xacro')
TARGETS = os.path.join(ROOT, 'test', 'data', 'worlds', 'camera_targets.sdf')
LENS_X = 0.26  # m, camera_link ahead of base_link (urdf/amr.urdf.xacro)


def _stamp(msg):
    return round(msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9, 6)


class CameraPeer(GzPeer):
    """GzPeer plus the RGB-D camera's topics (reliable, volatile, as the bridge)."""

    def __init__(self, domain_id):
        from sensor_msgs.msg import CameraInfo
        from sensor_msgs.msg import Image
        super().__init__(domain_id)
        self.images, self.depths, self.infos = [], [], []
        self.node.create_subscription(Image, '/camera/image', self.images.append, 100)
        self.node.create_subscription(Image, '/camera/depth_image', self.depths.append, 100)
        self.node.create_subscription(CameraInfo, '/camera/camera_info', self.infos.append,
                                      100)


@pytest.fixture
def camera_peer(ros_env):
    pytest.importorskip('simulation_interfaces.srv')
    p = CameraPeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def test_our_robot_with_camera_true_publishes_rgbd_topics_at_their_rate(
        procs, exe, ros_env, camera_peer):
    import numpy as np
    from amr_description.core.description.files import read_description
    peer = camera_peer
    urdf = read_description(XACRO, {'camera': 'true'})
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={TARGETS}',
                       '-p', 'real_time_factor:=0.0'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    create = procs.start([exe('create'), '-string', urdf, '-z', '0.01'], ros_env)
    assert create.wait(60) == 0, create.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: all(peer.node.count_publishers(t) for t in (
        '/camera/image', '/camera/depth_image', '/camera/camera_info')), 30)
    peer.step(500)  # settle on the wheels
    start = peer.now
    peer.step(1000)
    last = math.floor((start + 1.0) / 0.1 + 1e-6) * 0.1
    assert peer.spin_until(lambda: all(
        messages and _stamp(messages[-1]) >= round(last, 6)
        for messages in (peer.images, peer.depths, peer.infos)), 120), \
        (start, [_stamp(m) for m in peer.images[-3:]], sim.output[-2000:])
    window = (start + 1e-6, start + 1.0 + 1e-6)
    stamps = {}
    for name, messages in (('image', peer.images), ('depth', peer.depths),
                           ('info', peer.infos)):
        stamps[name] = [_stamp(m) for m in messages if window[0] < _stamp(m) < window[1]]
    assert len(stamps['image']) == 10, stamps
    assert stamps['image'] == stamps['depth'] == stamps['info']
    gaps = [b - a for a, b in zip(stamps['image'], stamps['image'][1:])]
    assert max(abs(g - 0.1) for g in gaps) < 1e-6, gaps

    image, depth, info = peer.images[-1], peer.depths[-1], peer.infos[-1]
    assert (image.header.frame_id, image.encoding, image.width, image.height) == \
        ('camera_optical_link', 'rgb8', 320, 240)
    assert (depth.header.frame_id, depth.encoding) == ('camera_optical_link', '32FC1')
    assert info.k[0] == pytest.approx(320 / (2 * math.tan(1.047 / 2)))
    pixels = np.frombuffer(bytes(image.data), np.uint8).reshape(240, 320, 3).astype(int)
    r, g, b = pixels[120, 200]
    assert r > 150 and g < 100 and b < 100, (r, g, b)  # the red wall ahead
    depths = np.frombuffer(bytes(depth.data), '<f4').reshape(240, 320)
    assert depths[120, 200] == pytest.approx(3.0 - LENS_X, abs=0.01)  # robot settled at x 0
    assert sim.popen.poll() is None


GREEN = (0, 255, 0)  # the cube of camera_targets.sdf


def test_the_viewer_shows_the_live_image_only_while_its_page_is_open(
        procs, exe, ros_env, camera_peer):
    """
    The sim stack with camera:=true: the panel shows the camera's picture at its rate.

    The picture holds the green cube on the red wall; /camera/image loses the viewer's
    subscription when the page closes (the simulator then renders nothing).
    """
    import re
    import time
    from browser import colour_mask
    from browser import ensure_chromium
    from browser import free_port
    from browser import open_page
    assert ensure_chromium(), 'Debian chromium is missing: run scripts/setup'
    peer = camera_peer
    port = free_port()
    stack = procs.start([exe('bringup'), 'sim', f'world:={TARGETS}', 'xacro_args:=camera:=true',
                         f'viewer_port:={port}'], ros_env)
    assert stack.wait_for_output(f'viewer: open http://127.0.0.1:{port}/ in a browser', 180.0), \
        stack.output[-3000:]

    def viewer_subscriptions():
        infos = peer.node.get_subscriptions_info_by_topic('/camera/image')
        return [i for i in infos if i.node_name == 'viewer']

    assert peer.spin_until(lambda: peer.node.count_publishers('/camera/image') > 0, 90), \
        stack.output[-3000:]
    assert not viewer_subscriptions()  # no page: the viewer does not listen
    with open_page(f'http://127.0.0.1:{port}/') as page:
        assert page.wait_for_text('Fixed Frame', 120.0), page.page.inner_text('body')
        page.close_notifications()
        green = rate = 0
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and (green < 20 or rate < 3.0):
            # the panel's pictures: /camera/image and /camera/depth_image, in the order their
            # first messages came (on a loaded machine the depth one may come first)
            green = max((int(colour_mask(image, GREEN, 60).sum())
                         for image in page.all_image_pixels()), default=0)
            found = re.search(r'/camera/image\s+([0-9.]+) Hz', page.page.inner_text('body'))
            rate = float(found.group(1)) if found else 0.0
            if green < 20 or rate < 3.0:
                page.page.wait_for_timeout(500)
        assert green >= 20 and rate >= 3.0, (  # 10 Hz of sim time
            f'{green} green pixels in the panel, {rate} Hz; page: '
            + page.page.inner_text('body')[:1500] + stack.output[-3000:])
        assert peer.spin_until(lambda: len(viewer_subscriptions()) == 1, 10)
    assert peer.spin_until(lambda: not viewer_subscriptions(), 30), \
        'the viewer still subscribes /camera/image after its page closed'
    assert stack.interrupt(timeout=30.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]
