# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The navsat (GPS) sensor and the WGS84 geodesy under it, against closed forms.

On the ellipsoid (a = 6378137 m, e^2 = f (2 - f), f = 1 / 298.257223563) a small step north of
d metres at latitude phi changes the latitude by ``d / M`` rad, ``M = a (1 - e^2) / (1 - e^2
sin^2 phi)^1.5`` (the meridian radius of curvature), a step east the longitude by ``d / (N cos
phi)``, ``N = a / sqrt(1 - e^2 sin^2 phi)``; the world of test/data/worlds/navsat_origin.sdf
has its origin at 47.397742 N, 8.545594 E, 488 m.
"""

import math
import os

from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.geodesy import ecef_to_geodetic
from amr_description.core.geodesy import geodetic_to_ecef
from amr_description.core.geodesy import local_to_geodetic
from amr_description.core.geodesy import SphericalCoordinates
from amr_description.core.geodesy import WGS84_A
from amr_description.core.geodesy import WGS84_E2
from amr_description.sim.simulation import Simulation
import numpy as np
import pytest
from sim_fixtures import ListLog as _Log  # noqa: I100 - the unit tests' helpers
from sim_fixtures import PROBE_BASE  # noqa: I100 - the unit tests' helpers

HERE = os.path.dirname(os.path.abspath(__file__))
WORLDS = os.path.join(os.path.dirname(HERE), 'data', 'worlds')
ORIGIN = SphericalCoordinates(47.397742, 8.545594, 488.0, 0.0)
MAST = 0.3  # m, the receiver above the probe's base_link


def _radii(latitude_deg):
    s = math.sin(math.radians(latitude_deg))
    m = WGS84_A * (1 - WGS84_E2) / (1 - WGS84_E2 * s * s) ** 1.5
    n = WGS84_A / math.sqrt(1 - WGS84_E2 * s * s)
    return m, n


def _robot(noise=''):
    return f"""<robot name="probe">
  {PROBE_BASE}
  <link name="gps_link"/>
  <joint name="gps_joint" type="fixed"><parent link="base_link"/><child link="gps_link"/>
    <origin xyz="0 0 {MAST}"/></joint>
  <gazebo reference="gps_link">
    <sensor name="gps" type="navsat"><update_rate>5</update_rate><topic>gps/fix</topic>
      <navsat>{noise}</navsat></sensor>
    <sensor name="imu" type="imu"><update_rate>100</update_rate></sensor>
  </gazebo>
</robot>"""


def _spawn(world, x=0.0, y=0.0, noise=''):
    sim = Simulation(physics_step=0.001, real_time_factor=0.0, logger=_Log(),
                     sensor_settings={'publish_ground_truth': False},
                     world=read_world(os.path.join(WORLDS, world)))
    entity = sim.spawn(_robot(noise), name='probe', pose=[x, y, 0.1, 0, 0, 0, 1])
    while sim.step_count < 300:
        sim.run_cycle()
    return sim, {s.name: s for s in entity.sensors}


def test_ecef_round_trip_and_the_equator_and_pole_in_closed_form():
    assert geodetic_to_ecef(0.0, 0.0, 0.0) == pytest.approx((WGS84_A, 0.0, 0.0))
    b = WGS84_A * (1 - 1 / 298.257223563)
    assert geodetic_to_ecef(90.0, 0.0, 0.0) == pytest.approx((0.0, 0.0, b), abs=1e-6)
    for lat, lon, alt in ((47.397742, 8.545594, 488.0), (-33.9, 151.2, 10.0), (89.9, -120, 0)):
        back = ecef_to_geodetic(*geodetic_to_ecef(lat, lon, alt))
        assert back[:2] == pytest.approx((lat, lon), abs=1e-9)  # deg: 0.1 mm
        assert back[2] == pytest.approx(alt, abs=1e-6)


def test_steps_north_east_and_up_move_latitude_longitude_and_altitude_by_the_closed_form():
    m, n = _radii(ORIGIN.latitude_deg)
    lat, lon, alt = local_to_geodetic(ORIGIN, 0.0, 0.0, 0.0)
    assert (lat, lon) == pytest.approx((47.397742, 8.545594), abs=1e-9)
    assert alt == pytest.approx(488.0, abs=1e-6)
    north = local_to_geodetic(ORIGIN, 0.0, 10.0, 0.0)
    # on the tangent plane 488 m above the ellipsoid: the radii grow by the height
    assert north[0] - lat == pytest.approx(math.degrees(10.0 / (m + 488.0)), rel=1e-5)
    assert north[1] == pytest.approx(lon, abs=1e-12)
    east = local_to_geodetic(ORIGIN, 10.0, 0.0, 0.0)
    assert east[1] - lon == pytest.approx(
        math.degrees(10.0 / ((n + 488.0) * math.cos(math.radians(lat)))), rel=1e-5)
    assert local_to_geodetic(ORIGIN, 0.0, 0.0, 5.0)[2] == pytest.approx(493.0, abs=1e-6)
    turned = SphericalCoordinates(ORIGIN.latitude_deg, ORIGIN.longitude_deg, 488.0, 90.0)
    assert local_to_geodetic(turned, 10.0, 0.0, 0.0)[0] == pytest.approx(
        north[0] - 2 * (north[0] - lat), rel=1e-9)  # heading 90: the world's x points south


def test_the_world_reads_its_spherical_coordinates():
    world = read_world(os.path.join(WORLDS, 'navsat_origin.sdf'))
    assert world.spherical_coordinates == ORIGIN
    assert 'spherical_coordinates' not in world.not_simulated
    assert read_world(os.path.join(WORLDS, 'box_room.sdf')).spherical_coordinates is None


def test_the_fix_at_the_origin_is_the_declared_position_and_10_m_north_moves_the_latitude():
    sim, sensors = _spawn('navsat_origin.sdf')
    fix = sensors['gps'].measure(sim.world, 0.3)
    height = sim.world.data.site('probe/sensor/gps').xpos[2]
    assert (fix.latitude, fix.longitude) == pytest.approx((47.397742, 8.545594), abs=1e-9)
    assert fix.altitude == pytest.approx(488.0 + height, abs=1e-6)
    assert height == pytest.approx(0.1 + MAST, abs=0.01)
    assert (fix.status.status, fix.status.service, fix.position_covariance_type) == (0, 0, 0)
    assert (fix.header.frame_id, sensors['gps'].topic) == ('gps_link', '/gps/fix')
    sim.close()
    m, _ = _radii(47.397742)
    sim, sensors = _spawn('navsat_origin.sdf', y=10.0)
    moved = sensors['gps'].measure(sim.world, 0.3)
    assert moved.latitude - fix.latitude == pytest.approx(
        math.degrees(10.0 / (m + fix.altitude)), rel=1e-5)
    assert moved.longitude == pytest.approx(fix.longitude, abs=1e-10)
    sim.close()


def test_horizontal_noise_is_in_degrees_and_vertical_in_metres_as_gz_sensors():
    noise = ('<position_sensing><horizontal><noise type="gaussian"><stddev>1e-5</stddev>'
             '</noise></horizontal><vertical><noise type="gaussian"><stddev>0.5</stddev>'
             '</noise></vertical></position_sensing>')
    sim, sensors = _spawn('navsat_origin.sdf', noise=noise)
    fixes = [(f.latitude, f.altitude) for f in
             (sensors['gps'].measure(sim.world, 0.3) for _ in range(400))]
    lat, alt = np.array(fixes).T
    assert np.std(lat) == pytest.approx(1e-5, rel=0.15)
    assert np.std(alt) == pytest.approx(0.5, rel=0.15)
    sim.close()


def test_a_navsat_in_a_world_without_spherical_coordinates_is_one_line_and_skipped():
    sim, sensors = _spawn('box_room.sdf')
    assert sorted(sensors) == ['imu']
    lines = [line for line in sim.logger.lines if "sensor 'gps'" in line]
    assert lines == ["entity 'probe': sensor 'gps': the world has no <spherical_coordinates> "
                     '(the origin of latitude and longitude); the sensor is skipped']
    sim.close()
