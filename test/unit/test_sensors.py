# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The sensor seam: registry, ground truth against closed forms, spawn result codes."""

import math

from amr_description.sim.entity import SpawnError
from amr_description.sim.sensors import ground_truth
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.registry import make_sensors
from amr_description.sim.sensors.registry import sensor_factories
from amr_description.sim.simulation import Simulation
import pytest
from sim_fixtures import tutorial_urdf


def _sim(**settings):
    return Simulation(real_time_factor=0.0, sensor_settings=settings)


def test_ground_truth_is_registered_under_the_entry_point_group():
    assert sensor_factories()['ground_truth'] is ground_truth.create


def test_period_in_physics_steps():
    sensor = Sensor()
    sensor.rate = 50.0
    assert sensor.period_steps(0.001) == 20
    sensor.rate = 3000.0  # faster than the physics: every step
    assert sensor.period_steps(0.001) == 1


def test_ground_truth_of_a_robot_at_rest_at_its_spawn_pose():
    sim = _sim()
    half = math.sqrt(0.5)  # yaw 90 deg
    entity = sim.spawn(tutorial_urdf(), 'r1', [1.0, 2.0, 0.0, 0, 0, half, half],
                       namespace='r1')
    [sensor] = entity.sensors
    assert (sensor.name, sensor.topic) == ('ground_truth', '/r1/ground_truth/odom')
    assert sensor.rate == 50.0
    msg = sensor.measure(sim.world, 1.25)
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (1, 250_000_000)
    assert (msg.header.frame_id, msg.child_frame_id) == ('world', 'r1/base_footprint')
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    assert (p.x, p.y, p.z) == pytest.approx((1.0, 2.0, 0.0), abs=1e-9)
    assert (q.x, q.y, q.z, q.w) == pytest.approx((0.0, 0.0, half, half), abs=1e-9)
    twist = msg.twist.twist
    assert (twist.linear.x, twist.linear.y, twist.angular.z) == (0.0, 0.0, 0.0)


def test_ground_truth_of_a_falling_robot_is_free_fall():
    """Spawned 1 m up, after 0.2 s the root has fallen g t^2 / 2 and moves at -g t (world z)."""
    sim = _sim(ground_truth_rate=100.0)
    entity = sim.spawn(tutorial_urdf(), 'amr', [0.0, 0.0, 1.0, 0, 0, 0, 1])
    [sensor] = entity.sensors
    assert sensor.topic == '/ground_truth/odom' and sensor.period_steps(0.001) == 10
    while sim.time < 0.2 - 1e-9:
        sim.run_cycle()
    msg = sensor.measure(sim.world, sim.time)
    g, t = 9.81, 0.2
    assert msg.pose.pose.position.z == pytest.approx(1.0 - g * t * t / 2, abs=2e-3)
    # twist in the root link frame: with no rotation, the world's -z
    assert msg.twist.twist.linear.z == pytest.approx(-g * t, abs=2e-2)


def test_ground_truth_switched_off():
    for settings in ({'publish_ground_truth': False}, {'ground_truth_rate': 0.0}):
        entity = _sim(**settings).spawn(tutorial_urdf(), 'amr', None)
        assert entity.sensors == []


def test_every_factory_is_asked_in_name_order():
    asked = []

    def factory(tag):
        def make(entity, settings):
            asked.append((tag, entity, settings['k']))
            return [tag]
        return make
    assert make_sensors('e', {'k': 1}, {'a': factory('a'), 'b': factory('b')}) == ['a', 'b']
    assert asked == [('a', 'e', 1), ('b', 'e', 1)]


@pytest.mark.parametrize('name, namespace, urdf, code', [
    ('a', 'r1', tutorial_urdf(), 'NAME_NOT_UNIQUE'),
    ('b', '/r0', tutorial_urdf(), 'NAME_NOT_UNIQUE'),
    ('c', '1bad', tutorial_urdf(), 'NAMESPACE_INVALID'),
    ('d', 'r2', '<robot name="x"><link', 'RESOURCE_PARSE_ERROR'),
])
def test_a_refused_spawn_carries_its_result_code(name, namespace, urdf, code):
    sim = _sim()
    sim.spawn(tutorial_urdf(), 'a', None, namespace='r0')
    with pytest.raises(SpawnError) as refused:
        sim.spawn(urdf, name, None, namespace=namespace)
    assert refused.value.code == code
    assert '\n' not in str(refused.value)
