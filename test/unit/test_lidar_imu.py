# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Lidar and IMU sensor blocks against closed forms (no rclpy node, no DDS)."""

import math
import os

from amr_description.core.description.files import read_description
from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.gazebo.sensor_kinds import Noise
from amr_description.sim.sensors.noise import generator
from amr_description.sim.sensors.noise import NoiseModel
from amr_description.sim.simulation import Simulation
import numpy as np
import pytest
from sim_fixtures import ListLog as _Log  # noqa: I100 - the unit tests' helpers
from sim_fixtures import PROBE_BASE  # noqa: I100 - the unit tests' helpers

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
XACRO = os.path.join(ROOT, 'urdf', 'amr.urdf.xacro')
ROOM = os.path.join(ROOT, 'test', 'data', 'worlds', 'box_room.sdf')
EAST, WEST, NORTH, SOUTH = 3.0, -2.0, 2.5, -1.5  # inner wall faces of box_room.sdf (m)


def _room_distance(angle, x=0.0, y=0.0):
    """Return the closed-form distance from (x, y) along ``angle`` to the room's walls."""
    c, s = math.cos(angle), math.sin(angle)
    candidates = []
    if c > 1e-12:
        candidates.append((EAST - x) / c)
    if c < -1e-12:
        candidates.append((WEST - x) / c)
    if s > 1e-12:
        candidates.append((NORTH - y) / s)
    if s < -1e-12:
        candidates.append((SOUTH - y) / s)
    return min(candidates)


def _robot(lidar_block='', imu_block='', extra=''):
    """Return a one-box robot (1 kg, 0.2 m cube, its centre 0.1 m up) with sensor blocks."""
    return f"""<robot name="probe">
  {PROBE_BASE}
  <link name="lidar_link"/>
  <joint name="lidar_joint" type="fixed"><parent link="base_link"/><child link="lidar_link"/>
    <origin xyz="0 0 0.2"/></joint>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/>
    <origin xyz="0.1 0 0"/></joint>
  <gazebo reference="lidar_link">{lidar_block}</gazebo>
  <gazebo reference="imu_link">{imu_block}</gazebo>
  {extra}
</robot>"""


def _lidar(samples=360, stddev=0.0, rmin=0.12, rmax=12.0, rate=10, vertical='',
           name='lidar', topic='scan'):
    noise = (f'<noise><type>gaussian</type><mean>0</mean><stddev>{stddev}</stddev></noise>'
             if stddev else '')
    return f"""<sensor name="{name}" type="gpu_lidar"><update_rate>{rate}</update_rate>
      <topic>{topic}</topic><lidar><scan><horizontal><samples>{samples}</samples>
      <min_angle>-3.141592653589793</min_angle>
      <max_angle>{math.pi - 2 * math.pi / samples}</max_angle></horizontal>{vertical}</scan>
      <range><min>{rmin}</min><max>{rmax}</max></range>{noise}</lidar></sensor>"""


def _imu(stddev=0.0, rate=100):
    axes = ''.join(f'<{a}><noise type="gaussian"><stddev>{stddev}</stddev></noise></{a}>'
                   for a in 'xyz')
    return f"""<sensor name="imu" type="imu"><update_rate>{rate}</update_rate><topic>imu</topic>
      <imu><angular_velocity>{axes}</angular_velocity>
      <linear_acceleration>{axes}</linear_acceleration></imu></sensor>"""


def _sim(world=ROOM, seed=0):
    description = read_world(world) if world else None
    return Simulation(physics_step=0.001, real_time_factor=0.0, logger=_Log(),
                      sensor_settings={'seed': seed, 'publish_ground_truth': False},
                      world=description)


def _sensors(entity):
    return {sensor.name: sensor for sensor in entity.sensors}


def _settle(sim, seconds=0.2):
    while sim.step_count * sim.physics_step < seconds - 1e-9:
        sim.run_cycle()
    return sim.step_count * sim.physics_step


# ----------------------------------------------------------------------------- reading

def test_our_xacro_robot_declares_a_lidar_and_an_imu_as_harmonic_users_write_them():
    description = RobotDescription(read_description(XACRO))
    blocks = {b.name: b for b in description.sensors.sensors}
    assert description.sensors.messages == []
    lidar, imu = blocks['lidar'], blocks['imu']
    assert (lidar.type, lidar.link, lidar.update_rate, lidar.topic, lidar.frame_id) == \
        ('gpu_lidar', 'lidar_link', 10.0, 'scan', 'lidar_link')
    assert lidar.lidar.horizontal.count == 360
    assert lidar.lidar.horizontal.angles()[1] - lidar.lidar.horizontal.angles()[0] == \
        pytest.approx(math.radians(1.0))
    assert (lidar.lidar.range_min, lidar.lidar.range_max) == (0.12, 12.0)
    assert (lidar.lidar.noise.type, lidar.lidar.noise.stddev) == ('gaussian', 0.01)
    assert (imu.type, imu.update_rate, imu.link) == ('imu', 100.0, 'imu_link')
    assert [n.stddev for n in imu.imu.angular_velocity] == [2e-4] * 3
    assert [n.stddev for n in imu.imu.linear_acceleration] == [1.7e-2] * 3
    without = RobotDescription(read_description(XACRO, {'lidar': 'false', 'imu': 'false'}))
    assert without.sensors.sensors == []
    assert set(without.model.links) == set(RobotDescription(
        open(os.path.join(ROOT, 'urdf', 'amr.urdf')).read()).model.links)


def test_sdf_defaults_apply_when_elements_are_absent():
    xml = _robot('<sensor name="bare" type="lidar"><lidar><range><max>5</max></range></lidar>'
                 '</sensor>', '<sensor name="i" type="imu"/>')
    blocks = {b.name: b for b in RobotDescription(xml).sensors.sensors}
    bare = blocks['bare']
    assert (bare.update_rate, bare.always_on, bare.topic, bare.frame_id) == (0.0, False, '', '')
    assert (bare.lidar.horizontal.samples, bare.lidar.horizontal.min_angle,
            bare.lidar.horizontal.max_angle, bare.lidar.vertical.samples) == (640, 0.0, 0.0, 1)
    assert bare.lidar.noise.type == 'none'
    assert blocks['i'].imu.enable_orientation is True
    assert all(n.type == 'none' for n in blocks['i'].imu.linear_acceleration)


@pytest.mark.parametrize('bad, field', [
    ('<samples>0</samples>', '<samples>'),
    ('<samples>-3</samples>', '<samples>'),
    ('<samples>ten</samples>', '<samples>'),
])
def test_bad_samples_skip_the_sensor_with_one_line_and_keep_the_others(bad, field):
    lidar = _lidar().replace('<samples>360</samples>', bad)
    description = RobotDescription(_robot(lidar, _imu()))
    assert [b.name for b in description.sensors.sensors] == ['imu']
    [line] = description.sensors.messages
    assert line.startswith("sensor 'lidar': ") and field in line and '\n' not in line
    assert line.endswith('the sensor is skipped')


@pytest.mark.parametrize('lidar, field', [
    (_lidar(rmin=5.0, rmax=5.0), '<range><max>'),
    (_lidar(rmin=-1.0), '<range><min>'),
    (_lidar(stddev=0.01).replace('<stddev>0.01', '<stddev>nan'), '<stddev>'),
    (_lidar(stddev=0.01).replace('>gaussian<', '>uniform<'), '<noise><type>'),
    (_lidar(samples=2000, vertical='<vertical><samples>600</samples></vertical>'), '<scan>'),
])
def test_bad_fields_name_the_sensor_and_the_field(lidar, field):
    description = RobotDescription(_robot(lidar))
    assert description.sensors.sensors == []
    [line] = description.sensors.messages
    assert line.startswith("sensor 'lidar': ") and field in line, line


def test_a_sensor_on_a_missing_link_or_of_another_type_is_one_line():
    extra = ('<gazebo reference="nowhere"><sensor name="ghost" type="imu"/></gazebo>'
             '<gazebo reference="base_link"><sensor name="cam" type="thermal_camera"/>'
             '<sensor name="odd" type="sonarx"/></gazebo>')
    description = RobotDescription(_robot(_lidar(), extra=extra))
    assert [b.name for b in description.sensors.sensors] == ['lidar']
    assert description.sensors.messages == [
        "sensor 'ghost': <gazebo reference> names link 'nowhere' that does not exist; the "
        'sensor is skipped',
        "sensor 'cam' of type 'thermal_camera' is not simulated",
        "sensor 'odd' of unknown type 'sonarx' is not simulated"]


def test_the_spawn_logs_each_skipped_sensor_and_keeps_the_rest():
    sim = _sim()
    xml = _robot(_lidar().replace('<samples>360', '<samples>0'), _imu())
    entity = sim.spawn(xml, name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    assert sorted(_sensors(entity)) == ['imu']
    assert any("entity 'probe': sensor 'lidar'" in line and '<samples>' in line
               for line in sim.logger.lines)
    sim.close()


# ----------------------------------------------------------------------------- lidar

def test_a_scan_in_a_box_room_equals_the_distances_to_the_walls():
    sim = _sim()
    entity = sim.spawn(_robot(_lidar()), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    t = _settle(sim)
    scan = _sensors(entity)['lidar'].measure(sim.world, t)
    assert (scan.header.frame_id, scan.header.stamp.sec, scan.header.stamp.nanosec) == \
        ('lidar_link', 0, 200_000_000)
    assert len(scan.ranges) == 360 and scan.angle_increment == pytest.approx(math.pi / 180)
    assert (scan.time_increment, scan.scan_time) == (0.0, 0.0)
    angles = scan.angle_min + scan.angle_increment * np.arange(360)
    expected = np.array([_room_distance(a) for a in angles])
    assert np.max(np.abs(np.array(scan.ranges) - expected)) < 1e-5  # float32 of < 4 m
    sim.close()


def test_a_noisy_scan_is_within_three_stddev_and_its_noise_has_the_declared_stddev():
    sim = _sim()
    stddev = 0.01
    entity = sim.spawn(_robot(_lidar(stddev=stddev)), name='probe',
                       pose=[0, 0, 0.1, 0, 0, 0, 1])
    lidar = _sensors(entity)['lidar']
    errors = []
    t = _settle(sim)
    angles = None
    while len(errors) < 28:  # 28 scans x 360 = 10,080 samples
        t = _settle(sim, t + 0.1)
        scan = lidar.measure(sim.world, t)
        angles = scan.angle_min + scan.angle_increment * np.arange(360)
        expected = np.array([_room_distance(a) for a in angles])
        errors.append(np.array(scan.ranges) - expected)
    errors = np.concatenate(errors)
    assert np.mean(np.abs(errors) <= 3 * stddev) > 0.99
    assert abs(np.mean(errors)) < 0.05 * stddev
    assert np.std(errors) == pytest.approx(stddev, rel=0.05)
    sim.close()


def test_rep117_plus_inf_with_nothing_in_range_minus_inf_before_range_min():
    sim = _sim(world=None)  # the empty world: nothing within 12 m at 0.3 m height
    entity = sim.spawn(_robot(_lidar(stddev=0.01)), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    scan = _sensors(entity)['lidar'].measure(sim.world, _settle(sim))
    assert all(r == math.inf for r in scan.ranges)
    sim.close()
    sim = _sim()  # south wall 1.5 m away, east 3 m: range_min 2 m
    entity = sim.spawn(_robot(_lidar(rmin=2.0)), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    scan = _sensors(entity)['lidar'].measure(sim.world, _settle(sim))
    south = scan.ranges[90]  # angle -pi/2
    east = scan.ranges[180]  # angle 0
    assert south == -math.inf and east == pytest.approx(3.0, abs=1e-5)
    sim.close()


def test_a_3d_lidar_point_cloud_has_gazebos_fields_and_rows():
    vertical = ('<vertical><samples>5</samples><min_angle>-0.2</min_angle>'
                '<max_angle>0.2</max_angle></vertical>')
    sim = _sim()
    entity = sim.spawn(_robot(_lidar(samples=64, vertical=vertical)), name='probe',
                       pose=[0, 0, 0.1, 0, 0, 0, 1])
    sensors = _sensors(entity)
    t = _settle(sim)
    cloud = sensors['lidar/points'].measure(sim.world, t)
    scan = sensors['lidar'].measure(sim.world, t)
    assert sensors['lidar/points'].topic == '/scan/points'
    assert [(f.name, f.offset, f.datatype, f.count) for f in cloud.fields] == [
        ('x', 0, 7, 1), ('y', 4, 7, 1), ('z', 8, 7, 1), ('intensity', 16, 7, 1),
        ('ring', 24, 4, 1)]
    assert (cloud.height, cloud.width, cloud.point_step, cloud.row_step) == (5, 64, 32, 2048)
    points = np.frombuffer(bytes(cloud.data), dtype=np.dtype(
        {'names': ['x', 'y', 'z', 'ring'], 'formats': ['<f4', '<f4', '<f4', '<u2'],
         'offsets': [0, 4, 8, 24], 'itemsize': 32}))
    assert list(points['ring'][::64]) == [0, 1, 2, 3, 4]
    middle = points[2 * 64:3 * 64]
    assert np.allclose(np.hypot(middle['x'], middle['y']), scan.ranges, atol=1e-5)
    # every finite point lies on the ground (0.3 m below the sensor) or on a wall
    hit = points[np.isfinite(points['x'])]
    assert len(hit) > 200
    on_wall = np.min(np.abs(np.stack([hit['x'] - EAST, hit['x'] - WEST, hit['y'] - NORTH,
                                      hit['y'] - SOUTH])), axis=0) < 1e-4
    on_ground = np.abs(hit['z'] + 0.3) < 1e-3
    assert np.all(on_wall | on_ground) and on_ground.sum() > 10 and on_wall.sum() > 100
    sim.close()


def test_one_seed_gives_identical_scans_in_lock_step_another_seed_does_not():
    def scans(seed):
        sim = _sim(seed=seed)
        entity = sim.spawn(_robot(_lidar(stddev=0.02), _imu(stddev=0.01)), name='probe',
                           pose=[0, 0, 0.1, 0, 0, 0, 1])
        sensors = _sensors(entity)
        out = []
        for k in range(1, 6):
            t = _settle(sim, 0.1 * k)
            out.append(list(sensors['lidar'].measure(sim.world, t).ranges)
                       + [sensors['imu'].measure(sim.world, t).linear_acceleration.z])
        sim.close()
        return out
    assert scans(7) == scans(7)
    assert scans(7) != scans(8)


def test_instants_nobody_hears_are_advanced_and_leave_the_heard_messages_unchanged():
    """Sensor.advance draws the noise of an unheard instant: later messages do not change."""
    def run(heard):
        sim = _sim(seed=3)
        entity = sim.spawn(_robot(_lidar(stddev=0.02), _imu(stddev=0.01)), name='probe',
                           pose=[0, 0, 0.1, 0, 0, 0, 1])
        sensors = _sensors(entity)
        out, casts = [], 0
        for k in range(1, 9):
            t = _settle(sim, 0.1 * k)
            for name in ('lidar', 'lidar/points', 'imu'):
                sensor = sensors[name]
                if name in heard(k):
                    before = sensors['lidar'].cast.time
                    message = sensor.measure(sim.world, t)
                    casts += name.startswith('lidar') and before != t
                    out.append((k, name, bytes(message.ranges) if name == 'lidar' else
                                bytes(message.data) if name == 'lidar/points' else
                                message.linear_acceleration.z))
                elif not sensor.costly:
                    sensor.advance(sim.world, t)
        sim.close()
        return out, casts

    everything, cast_all = run(lambda k: ('lidar', 'lidar/points', 'imu'))
    odd_scans, cast_odd = run(lambda k: ('lidar', 'imu') if k % 2 else ())
    points_only, cast_points = run(lambda k: ('lidar/points',) if k > 4 else ())
    assert (cast_all, cast_odd, cast_points) == (8, 4, 4)  # no ray cast for an unheard scan
    assert odd_scans == [m for m in everything if m[0] % 2 and m[1] != 'lidar/points']
    assert points_only == [m for m in everything if m[0] > 4 and m[1] == 'lidar/points']


def test_each_sensor_is_due_at_its_own_rate_in_sim_time():
    sim = _sim()
    entity = sim.spawn(_robot(_lidar(rate=10), _imu(rate=100)), name='probe',
                       pose=[0, 0, 0.1, 0, 0, 0, 1])
    sensors = _sensors(entity)
    due = dict.fromkeys(sensors, 0)
    while sim.step_count < 2000:
        sim.run_cycle()
        for name, sensor in sensors.items():
            if sim.step_count % sensor.period_steps(sim.physics_step) == 0:
                due[name] += 1
    assert due == {'lidar': 20, 'lidar/points': 20, 'imu': 200}  # 2 s: 10 Hz and 100 Hz
    sim.close()


# ----------------------------------------------------------------------------- IMU

def test_imu_at_rest_reads_plus_g_on_z_and_no_rotation():
    sim = _sim()
    entity = sim.spawn(_robot('', _imu()), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
    imu = _sensors(entity)['imu'].measure(sim.world, _settle(sim, 0.5))
    a, w, q = imu.linear_acceleration, imu.angular_velocity, imu.orientation
    g = -sim.world.model.opt.gravity[2]  # SDF's default gravity: 9.8 m/s^2
    assert g == pytest.approx(9.8)
    assert a.z == pytest.approx(g, abs=1e-3) and abs(a.x) < 1e-3 and abs(a.y) < 1e-3
    assert max(abs(w.x), abs(w.y), abs(w.z)) < 1e-3
    assert (q.x, q.y, q.z) == pytest.approx((0, 0, 0), abs=1e-4)
    assert imu.header.frame_id == 'imu_link'
    sim.close()


def _zero_g_world(tmp_path):
    path = tmp_path / 'space.sdf'
    path.write_text('<sdf version="1.9"><world name="space"><gravity>0 0 0</gravity>'
                    '</world></sdf>')
    return str(path)


def test_imu_while_accelerating_forward_reads_the_acceleration_on_x(tmp_path):
    sim = _sim(world=_zero_g_world(tmp_path))
    entity = sim.spawn(_robot('', _imu()), name='probe', pose=[0, 0, 2, 0, 0, 0, 1])
    body = sim.world.model.body('probe/base_link').id
    sim.world.data.xfrc_applied[body, 0] = 0.5  # 0.5 N on 1 kg: 0.5 m/s^2 forward
    imu = _sensors(entity)['imu'].measure(sim.world, _settle(sim, 0.3))
    a = imu.linear_acceleration
    assert a.x == pytest.approx(0.5, abs=1e-4)
    assert abs(a.y) < 1e-4 and abs(a.z) < 1e-4
    sim.close()


def test_imu_while_turning_reads_the_yaw_rate_and_the_centripetal_acceleration(tmp_path):
    sim = _sim(world=_zero_g_world(tmp_path))
    entity = sim.spawn(_robot('', _imu()), name='probe', pose=[0, 0, 2, 0, 0, 0, 1])
    omega = 2.0
    qvel = sim.world.free_joint_address('probe')[1]
    sim.world.data.qvel[qvel + 5] = omega  # yaw rate about the body centre, no forces
    t = _settle(sim, 0.25)
    imu = _sensors(entity)['imu'].measure(sim.world, t)
    w, a, q = imu.angular_velocity, imu.linear_acceleration, imu.orientation
    assert w.z == pytest.approx(omega, rel=1e-6) and abs(w.x) < 1e-9 and abs(w.y) < 1e-9
    # the IMU is 0.1 m ahead of the axis: centripetal acceleration -omega^2 r on its x
    assert a.x == pytest.approx(-omega ** 2 * 0.1, rel=1e-3) and abs(a.y) < 1e-6
    # orientation: yaw = omega (t - one physics step), the sensor stage of the last step
    yaw = 2 * math.atan2(q.z, q.w)
    assert yaw == pytest.approx(omega * (t - sim.physics_step), abs=1e-6)
    sim.close()


def test_sensors_computed_in_the_last_step_only_leave_the_same_state_and_readings():
    """World.step(n) skips MuJoCo's sensor stage but in its last step: same as n single steps."""
    import mujoco
    sims = [_sim(), _sim()]
    for sim in sims:
        sim.spawn(_robot('', _imu()), name='probe', pose=[0, 0, 0.1, 0, 0, 0, 1])
        qvel = sim.world.free_joint_address('probe')[1]
        sim.world.data.qvel[qvel:qvel + 6] = [0.3, 0.1, 0.0, 0.0, 0.0, 1.5]
    batch, single = (sim.world for sim in sims)
    for _ in range(30):
        batch.step(10)
        for _ in range(10):
            single.step(1)
        assert np.array_equal(batch.data.qpos, single.data.qpos)
        assert np.array_equal(batch.data.sensordata, single.data.sensordata)
    assert abs(batch.data.sensordata).max() > 1.0  # gravity is in the readings
    assert not batch.model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_SENSOR
    for sim in sims:
        sim.close()


def test_noise_model_mean_and_stddev_over_10000_samples():
    model = NoiseModel(Noise('gaussian', mean=0.1, stddev=0.02), generator(3, 'a', 'b'))
    samples = model.apply(np.zeros(10_000))
    assert np.mean(samples) == pytest.approx(0.1, rel=0.05)
    assert np.std(samples) == pytest.approx(0.02, rel=0.05)
    assert model.apply(np.array([np.inf, -np.inf]))[0] == np.inf
    biased = NoiseModel(Noise('gaussian', bias_mean=0.5), generator(3, 'c'))
    assert abs(biased.bias) == 0.5
    quantized = NoiseModel(Noise('gaussian_quantized', stddev=0.3, precision=0.25),
                           generator(1))
    values = quantized.apply(np.zeros(100))
    assert np.allclose(values / 0.25, np.round(values / 0.25))


def test_check_model_says_what_becomes_of_each_sensor_block():
    from amr_description.core.model_check.gazebo import check_gazebo
    from amr_description.core.description.urdf_model import parse_xml
    extra = ('<gazebo reference="base_link"><sensor name="cam" type="camera"/></gazebo>'
             '<gazebo reference="ghost"><sensor name="g" type="imu"/></gazebo>')
    xml = _robot(_lidar(rmin=5.0, rmax=1.0).replace('name="lidar"', 'name="bad"')
                 + _lidar(), _imu(), extra)
    found = {f.element: (f.severity, f.message) for f in check_gazebo(parse_xml(xml, 'x'))}
    ok = found['<gazebo reference="lidar_link"><sensor lidar>']
    assert ok[1] == 'simulated as a ray-cast lidar of 360 rays at 10 Hz (docs/sensors.md)'
    assert found['<gazebo reference="imu_link"><sensor imu>'][1].startswith('simulated as an IMU')
    bad = found['<gazebo reference="lidar_link"><sensor bad>']
    assert bad[0] != ok[0] and '<range><max>' in bad[1] and bad[1].endswith('skipped')
    assert found['<gazebo reference="base_link"><sensor cam>'][1] == \
        'simulated as a camera of 320x240 pixels at every physics step (docs/sensors.md)'
    assert 'skipped' in found['<gazebo reference="ghost"><sensor g>'][1]


def test_fortress_and_turtlebot_frame_tags_and_sensor_systems_are_understood():
    from amr_description.core.gazebo.systems import parse_gazebo_systems
    from amr_description.core.description.urdf_model import parse_xml
    lidar = _lidar().replace('<topic>', '<ignition_frame_id>laser</ignition_frame_id><topic>')
    imu = _imu().replace('<topic>', '<frame_id>imu_frame</frame_id><topic>')
    extra = ('<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors">'
             '<render_engine>ogre2</render_engine></plugin>'
             '<plugin filename="libignition-gazebo-imu-system.so" '
             'name="ignition::gazebo::systems::Imu"/>'
             '<plugin filename="gz-sim-navsat-system" name="gz::sim::systems::NavSat"/>'
             '<plugin filename="gz-sim-contact-system" name="gz::sim::systems::Contact"/>'
             '</gazebo>')
    xml = _robot(lidar, imu, extra)
    blocks = {b.name: b for b in RobotDescription(xml).sensors.sensors}
    assert (blocks['lidar'].frame_id, blocks['imu'].frame_id) == ('laser', 'imu_frame')
    assert parse_gazebo_systems(parse_xml(xml, 'x'), []).unknown == []


def test_every_sensor_kind_has_its_reader_and_a_kind_without_one_is_one_line(monkeypatch):
    from amr_description.core.gazebo import sensor_kinds
    from amr_description.core.gazebo.sensors import read_sensor
    from amr_description.core.gazebo.sensors import SensorError
    from amr_description.core.xml_document import parse_text
    assert set(sensor_kinds.KINDS.values()) == set(sensor_kinds.SENSOR_KINDS)
    assert all(callable(reader) for _, reader in sensor_kinds.SENSOR_KINDS.values())
    # a kind added to the table without its reader is refused, never read as another kind
    monkeypatch.setitem(sensor_kinds.SENSOR_KINDS, 'sonar', (('sonar',), None))
    monkeypatch.setitem(sensor_kinds.KINDS, 'sonar', 'sonar')
    sensor = parse_text('<sensor name="s1" type="sonar"><imu/></sensor>')
    with pytest.raises(SensorError) as error:
        read_sensor(sensor, 'base_link')
    assert str(error.value) == "sensor 's1': kind 'sonar' has no reader (SENSOR_KINDS)"
