# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Physics of urdf/amr.urdf in the MuJoCo world alone (no ROS, sim time): issue 11's targets.

Contact (all four wheels on the ground, base steady), skid-steer turning against the Coulomb
model, wheel speed tracking under turning load, rest and creep, the drive's anti-windup.
"""

from amr_description.tools import physics_report
from amr_description.tools.physics_report import Bench
from amr_description.tools.physics_report import rest_and_creep
import pytest
from sim_fixtures import AMR_URDF


@pytest.fixture(scope='module')
def urdf_xml():
    with open(AMR_URDF) as f:
        return f.read()


@pytest.fixture(scope='module')
def bench(urdf_xml):
    return Bench(urdf_xml)


def _contact_and_tracking(drive):
    assert drive.all4 >= 0.95, drive
    assert drive.jitter_mm < 1.0, drive
    assert drive.tracking < 0.02, drive


@pytest.mark.parametrize('speed', [0.1, 0.5, 10.0])
def test_turn_in_place_matches_coulomb(bench, speed):
    drive = bench.drive(-speed, speed)
    _contact_and_tracking(drive)
    # yaw rate = v b / (a^2 + b^2) for the measured wheel speeds, within 10 %
    assert drive.turn_ratio == pytest.approx(1.0, abs=0.10), drive
    assert drive.yaw_rate > 0.0  # left wheels back, right forward: counter-clockwise


@pytest.mark.parametrize('left, right', [(2.0, 6.0), (5.0, 10.0), (-2.0, 6.0)])
def test_arc_matches_integrated_coulomb_model(bench, left, right):
    drive = bench.drive(left, right)
    _contact_and_tracking(drive)
    assert drive.turn_ratio == pytest.approx(1.0, abs=0.10), drive
    # the base's sideways slide on the arc is the model's within 1 cm/s (MuJoCo's own wheel
    # friction gave 7-19 cm/s more, docs/simulation.md)
    assert drive.sideways == pytest.approx(drive.model_sideways, abs=0.01), drive


def test_straight_at_top_speed(bench):
    drive = bench.drive(10.0, 10.0)
    _contact_and_tracking(drive)
    assert abs(drive.yaw_rate) < 1e-3
    # wheel odometry against ground truth over 2 m
    assert drive.distance == pytest.approx(2.0, rel=0.01)
    assert drive.odometry_distance == pytest.approx(drive.distance, rel=0.005), drive


def test_dropped_robot_rests_within_a_second_and_does_not_creep(urdf_xml):
    rest_s, creep_mm = rest_and_creep(urdf_xml, z=0.2, creep_seconds=60.0)
    assert rest_s < 1.0
    assert creep_mm < 1.0


def test_drive_anti_windup_keeps_torque_request_in_range(urdf_xml):
    # a 0.3 N m drive cannot spin the wheels at 10 rad/s against the ground while turning in
    # place: the torque saturates, the integral must not run away
    weak = urdf_xml.replace('forcerange="-20 20"', 'forcerange="-0.3 0.3"')
    bench = Bench(weak)
    model, data = bench.world.model, bench.world.data
    names = [f'amr/joint_wheel_{n}/velocity' for n in physics_report.WHEELS]
    proportional = [model.actuator(n) for n in names]
    integral = [model.actuator(n + '/integral') for n in names]
    assert all(model.jnt_actfrclimited[p.trnid[0]] for p in proportional)
    bench.command(-10.0, 10.0)
    for _ in range(100):  # 1 s
        bench.run(physics_report.CONTROL_PERIOD)
        bench.system.write(bench.world.time, 0.0)  # the clamp is applied at every write
        for p, i, dof, qadr in zip(proportional, integral, bench.wheel_dofs, bench.wheel_qpos):
            # torque asked by kv (command - qdot) + ki (act - q)
            request = p.gainprm[0] * (data.ctrl[p.id] - data.qvel[dof]) \
                + i.gainprm[0] * (data.act[i.actadr[0]] - data.qpos[qadr])
            assert abs(request) <= 0.3 + 1e-9
    # commanded to stop, the wheels come to rest instead of paying back a stored error
    bench.command(0.0, 0.0)
    bench.run(1.0)
    assert max(abs(data.qvel[d]) for d in bench.wheel_dofs) < 0.05


def test_report_table_and_bad_file(tmp_path, capsys):
    assert physics_report.main(['--urdf', str(tmp_path / 'nope.urdf')]) == 1
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and 'nope.urdf' in err
    rows = [('case', 'quantity', '1 %', '< 2 %', True), ('c2', 'q', 'x', 'y', False)]
    text = physics_report.format_table(rows).splitlines()
    assert text[0].split() == ['case', 'quantity', 'value', 'target', 'ok']
    assert text[2].endswith('yes') and text[3].endswith('NO')


def test_arc_rows_compare_the_sideways_slip_with_the_coulomb_model():
    # an arc's row is the measured sideways velocity minus the model's, within 1 cm/s
    def arc(sideways, model):
        return physics_report.Drive(
            left=2.0, right=6.0, all4=1.0, mean_contacts=4.0, jitter_mm=0.0, yaw_rate=1.0,
            model_yaw_rate=1.0, wheel_speeds=(2.0, 2.0, 6.0, 6.0), tracking=0.0, distance=1.0,
            odometry_distance=1.0, sideways=sideways, model_sideways=model)

    def slip_rows(drive):
        result = {'turns': [], 'straights': [], 'arcs': [drive], 'rest_s': 0.1,
                  'creep_mm': 0.0}
        return [r for r in physics_report.table_rows(result) if r[1].startswith('sideways')]

    (row,) = slip_rows(arc(-0.0833, -0.0057))
    assert row[2] == '-7.76 cm/s (-8.33 vs -0.57)' and row[3] == '+- 1 cm/s' and not row[4]
    (row,) = slip_rows(arc(-0.0061, -0.0057))
    assert row[2] == '-0.04 cm/s (-0.61 vs -0.57)' and row[4]
