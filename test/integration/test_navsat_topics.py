# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A navsat sensor through DDS: NavSatFix at the world's declared origin, as ros_gz_bridge gives it.

A probe with a navsat block (5 Hz, topic gps/fix) is spawned at the origin of
test/data/worlds/navsat_origin.sdf (47.397742 N, 8.545594 E, 488 m) and another 10 m north of
it; their fixes differ by 10 m / (M + h) in latitude (M the meridian radius of curvature).
"""

import math
import os

import pytest
from test_gz_systems import GzPeer  # noqa: I100 - the gz-sim systems' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
WORLD = os.path.join(ROOT, 'test', 'data', 'worlds', 'navsat_origin.sdf')


def _probe(name):
    return f"""<robot name="{name}">
  <link name="base_link">
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <inertial><mass value="1.0"/>
      <inertia ixx="0.00667" iyy="0.00667" izz="0.00667" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <gazebo reference="base_link">
    <sensor name="gps" type="navsat"><update_rate>5</update_rate><topic>gps/fix</topic>
    </sensor>
  </gazebo>
</robot>"""


@pytest.fixture
def peer(ros_env):
    pytest.importorskip('simulation_interfaces.srv')
    from sensor_msgs.msg import NavSatFix
    p = GzPeer(int(ros_env['ROS_DOMAIN_ID']))
    p.fixes = {'/a/gps/fix': [], '/b/gps/fix': []}
    for topic, fixes in p.fixes.items():
        p.node.create_subscription(NavSatFix, topic, fixes.append, 10)
    yield p
    p.close()


def test_two_probes_10_m_apart_report_fixes_10_m_apart_in_latitude(procs, exe, ros_env, peer):
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', f'world:={WORLD}'], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 60), sim.output
    for name, y in (('a', 0.0), ('b', 10.0)):
        create = procs.start([exe('create'), '-string', _probe(name), '-name', name,
                              '-robot_namespace', name, '-y', str(y), '-z', '0.1'], ros_env)
        assert create.wait(60) == 0, create.output + sim.output
    assert peer.spin_until(lambda: all(len(f) >= 3 for f in peer.fixes.values()), 60), \
        sim.output[-2000:]
    a, b = peer.fixes['/a/gps/fix'][-1], peer.fixes['/b/gps/fix'][-1]
    assert (a.latitude, a.longitude) == pytest.approx((47.397742, 8.545594), abs=1e-8)
    assert a.altitude == pytest.approx(488.1, abs=0.02)  # the probe's base_link, 0.1 m up
    assert (a.status.status, a.position_covariance_type, a.header.frame_id) == \
        (0, 0, 'a/base_link')
    s = math.sin(math.radians(47.397742))
    e2 = (1 / 298.257223563) * (2 - 1 / 298.257223563)
    m = 6378137.0 * (1 - e2) / (1 - e2 * s * s) ** 1.5
    assert b.latitude - a.latitude == pytest.approx(math.degrees(10.0 / (m + a.altitude)),
                                                    rel=1e-4)
    assert b.longitude == pytest.approx(a.longitude, abs=1e-9)
    assert sim.popen.poll() is None
