# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Lidar and IMU topics through DDS, as a Gazebo user's nodes receive them from ros_gz_bridge.

Our robot with its sensor mount (urdf/amr.urdf.xacro: 2-D lidar 10 Hz, IMU 100 Hz) is spawned
with ``create -file`` into the closed room of test/data/worlds/box_room.sdf; the simulator is
paused and stepped. The scans equal the distances to the room's walls within 3 stddev, stamps
are exactly one period apart in sim time, the IMU reads gravity on z, and the point cloud has
gz-sensors' fields.
"""

import math
import os

import pytest
from test_gz_systems import GzPeer  # noqa: I100 - the gz-sim systems' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
XACRO = os.path.join(ROOT, 'urdf', 'amr.urdf.xacro')
ROOM = os.path.join(ROOT, 'test', 'data', 'worlds', 'box_room.sdf')
EAST, WEST, NORTH, SOUTH = 3.0, -2.0, 2.5, -1.5  # inner wall faces (m)
STDDEV = 0.01  # the lidar's declared noise (m)


def _stamp(msg):
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def _room_distance(angle):
    c, s = math.cos(angle), math.sin(angle)
    candidates = [(EAST if c > 0 else WEST) / c] if abs(c) > 1e-12 else []
    if abs(s) > 1e-12:
        candidates.append((NORTH if s > 0 else SOUTH) / s)
    return min(candidates)


class SensorPeer(GzPeer):
    """GzPeer plus /scan, /scan/points and /imu (reliable, volatile, as the bridge)."""

    def __init__(self, domain_id):
        from sensor_msgs.msg import Imu
        from sensor_msgs.msg import LaserScan
        from sensor_msgs.msg import PointCloud2
        super().__init__(domain_id)
        self.scans, self.clouds, self.imus = [], [], []
        self.node.create_subscription(LaserScan, '/scan', self.scans.append, 100)
        self.node.create_subscription(PointCloud2, '/scan/points', self.clouds.append, 100)
        self.node.create_subscription(Imu, '/imu', self.imus.append, 1000)


@pytest.fixture
def sensor_peer(ros_env):
    pytest.importorskip('simulation_interfaces.srv')
    p = SensorPeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def test_our_robot_in_a_room_publishes_scan_points_and_imu_at_their_rates(
        procs, exe, ros_env, sensor_peer):
    peer = sensor_peer
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={ROOM}',
                       '-p', 'real_time_factor:=0.0'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    create = procs.start([exe('create'), '-file', XACRO, '-z', '0.01'], ros_env)
    assert create.wait(60) == 0, create.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    assert peer.spin_until(lambda: peer.node.count_publishers('/scan') > 0, 30)
    peer.step(500)  # settle on the wheels
    start = peer.now
    peer.step(2000)
    # the last measurement instants (multiples of the periods) at most 2 s after the start
    last_scan = math.floor((start + 2.0) / 0.1 + 1e-6) * 0.1
    last_imu = math.floor((start + 2.0) / 0.01 + 1e-6) * 0.01
    assert peer.spin_until(lambda: peer.scans and _stamp(peer.scans[-1]) >= last_scan - 1e-6
                           and peer.imus and _stamp(peer.imus[-1]) >= last_imu - 1e-6, 30), \
        (start, [_stamp(m) for m in peer.scans[-3:]], sim.output[-2000:])
    window = (start + 1e-6, start + 2.0 + 1e-6)  # 2 s of sim time at 10 Hz and 100 Hz
    scans = [m for m in peer.scans if window[0] < _stamp(m) < window[1]]
    imus = [m for m in peer.imus if window[0] < _stamp(m) < window[1]]
    assert len(scans) == 20 and len(imus) == 200
    for messages, period in ((scans, 0.1), (imus, 0.01)):
        gaps = [_stamp(b) - _stamp(a) for a, b in zip(messages, messages[1:])]
        assert max(abs(g - period) for g in gaps) < 1e-6, gaps

    scan = scans[-1]
    assert (scan.header.frame_id, len(scan.ranges), scan.range_min, scan.range_max) == \
        ('lidar_link', 360, pytest.approx(0.12), pytest.approx(12.0))
    within = total = 0
    for message in scans:
        for i, value in enumerate(message.ranges):
            expected = _room_distance(message.angle_min + i * message.angle_increment)
            within += abs(value - expected) <= 3 * STDDEV + 0.002  # + settling on the wheels
            total += 1
    print(f'scan: {within} of {total} ranges within 3 stddev of the walls')
    assert within / total > 0.99

    g = sum(m.linear_acceleration.z for m in imus) / len(imus)
    wz = sum(m.angular_velocity.z for m in imus) / len(imus)
    imu = imus[-1]
    assert imu.header.frame_id == 'imu_link'
    assert g == pytest.approx(9.8, abs=0.01) and abs(wz) < 1e-3  # SDF's default gravity
    assert imu.linear_acceleration_covariance[0] == pytest.approx(1.7e-2 ** 2)
    assert peer.spin_until(lambda: peer.clouds, 10)
    cloud = peer.clouds[-1]
    assert (cloud.width, cloud.height, cloud.point_step) == (360, 1, 32)
    assert [f.name for f in cloud.fields] == ['x', 'y', 'z', 'intensity', 'ring']
    assert sim.popen.poll() is None


SCAN_RGB = (255, 190, 0)  # the Rainbow colours of ranges 1.5 - 3 m of a 12 m lidar


def test_the_sim_stack_viewer_draws_the_scan_and_its_rate(procs, exe, ros_env, tmp_path):
    import re
    import shutil
    import time
    from browser import colour_mask
    from browser import ensure_chromium
    from browser import free_port
    from browser import open_page
    assert ensure_chromium(), 'Debian chromium is missing: run scripts/setup'
    port = free_port()
    stack = procs.start([exe('bringup'), 'sim', f'world:={ROOM}', f'viewer_port:={port}'],
                        ros_env)
    assert stack.wait_for_output(f'viewer: open http://127.0.0.1:{port}/ in a browser', 180.0), \
        stack.output[-3000:]
    with open_page(f'http://127.0.0.1:{port}/') as page:
        assert page.wait_for_text('Fixed Frame', 120.0), page.page.inner_text('body')
        page.close_notifications()
        scan = 0
        rate = 0.0
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and (scan < 300 or rate < 5.0):
            image = page.pixels(str(tmp_path / 'scan.png'))
            mask = colour_mask(image, SCAN_RGB, 70)
            mask[:, int(mask.shape[1] * 0.6):] = False  # the panel
            scan = int(mask.sum())
            found = re.search(r'/scan\s+([0-9.]+) Hz', page.page.inner_text('body'))
            rate = float(found.group(1)) if found else 0.0
            if scan < 300 or rate < 5.0:
                page.page.wait_for_timeout(500)
        assert scan >= 300, f'{scan} scan-coloured pixels' + stack.output[-3000:]
        assert rate >= 5.0, page.page.inner_text('body')  # 10 Hz of sim time, rtf 1
        if os.environ.get('AMR_UPDATE_SCREENSHOTS'):
            shutil.copy(tmp_path / 'scan.png', os.path.join(ROOT, 'docs', 'img', 'scan.png'))
    assert stack.interrupt(timeout=30.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]


SENSOR_TOPICS = ['/scan', '/scan/points', '/imu']


def test_a_bag_of_the_sensors_round_trips_byte_identical(procs, exe, ros_env, tmp_path):
    import subprocess
    from conftest import next_domain_id
    from conftest import release_domain_id
    from test_cli_bag import _by_topic
    from test_cli_bag import _mcap_messages
    from test_cli_bag import _rosbags_messages
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={ROOM}'], ros_env)
    create = procs.start([exe('create'), '-file', XACRO, '-z', '0.01'], ros_env)
    assert create.wait(120) == 0, create.output + sim.output
    first = tmp_path / 'first'
    rec = procs.start([exe('ros2'), 'bag', 'record', '-o', str(first), '--use-sim-time',
                       '--max-duration', '3', *SENSOR_TOPICS], ros_env)
    assert rec.wait(240.0) == 0, rec.output + sim.output
    recorded = _rosbags_messages(first)
    counts = {topic: len(items) for topic, items in _by_topic(recorded).items()}
    assert counts.get('/scan', 0) >= 15 and counts.get('/scan/points', 0) >= 15 and \
        counts.get('/imu', 0) >= 150, counts
    scan = next(d for t, _, _, name, d in _mcap_messages(first) if t == '/scan')
    assert len(scan.ranges) == 360 and scan.header.frame_id == 'lidar_link'
    sim.interrupt(timeout=30.0)

    other = dict(ros_env, ROS_DOMAIN_ID=str(next_domain_id()))
    try:
        second = tmp_path / 'second'
        rec2 = procs.start([exe('ros2'), 'bag', 'record', '-o', str(second), *SENSOR_TOPICS],
                           other)
        assert rec2.wait_for_output('Listening for topics', timeout=30.0), rec2.output
        play = subprocess.run([exe('ros2'), 'bag', 'play', str(first), '-d', '5'], env=other,
                              capture_output=True, text=True, timeout=120)
        assert play.returncode == 0, play.stderr
        assert rec2.interrupt(timeout=30.0) == 0, rec2.output
    finally:
        release_domain_id(int(other['ROS_DOMAIN_ID']))
    replayed = _by_topic(_rosbags_messages(second))
    for topic, items in _by_topic(recorded).items():
        assert replayed.get(topic) == items, (topic, len(items), len(replayed.get(topic, [])))
