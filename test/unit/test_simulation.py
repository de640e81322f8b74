# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Simulation without ROS: two robots, one controller manager each, phases, determinism."""

import math
import os
import threading

from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.ros_names import normalize_namespace
from amr_description.sim.simulation import Simulation
import numpy as np
import pytest
from sim_fixtures import ListLog
from sim_fixtures import REPO
from sim_fixtures import tutorial_urdf

PARAMS = os.path.join(REPO, 'config', 'controllers.yaml')
WHEELS = ('front_left', 'rear_left', 'front_right', 'rear_right')


class FakeControllerManager:
    """
    A controller manager without rclpy: MujocoSystem hardware, wheel commands from a schedule.

    ``schedule(t) -> (left, right)`` wheel velocities (rad/s) at sim time ``t``.
    """

    def __init__(self, entity, hardware_factory, parameters_file, schedule, log):
        self.entity = entity
        self.update_rate = 100
        self.schedule = schedule
        self.log = log
        self.systems = []
        for info in parse_ros2_control(entity.description.xml):
            system = hardware_factory(info)
            assert system.on_init(info)
            self.systems.append(system)
        self.released = False

    def read(self, t, period):
        self.log.append((self.entity.name, 'read', t, period))
        for system in self.systems:
            system.read(t, period)

    def update(self, t, period):
        self.log.append((self.entity.name, 'update', t, period))
        left, right = self.schedule(t)
        for system in self.systems:
            for wheel in WHEELS:
                value = left if 'left' in wheel else right
                system.command_handles[f'joint_wheel_{wheel}/velocity'].value = value

    def write(self, t, period):
        self.log.append((self.entity.name, 'write', t, period))
        for system in self.systems:
            system.write(t, period)


def _simulation(schedules, log, released=None, **kwargs):
    def factory(entity, hardware_factory, parameters_file):
        return FakeControllerManager(entity, hardware_factory, parameters_file,
                                     schedules[entity.name], log)

    def release(cm):
        if released is not None:
            released.append(cm.entity.name)
    return Simulation(real_time_factor=0.0, controller_manager_factory=factory,
                      controller_manager_release=release, parameters_file=PARAMS, **kwargs)


def _forward(t):
    return (-5.0, -5.0)  # the tutorial's wheel axes point along -y: negative drives forward


def _turn(t):
    return (5.0, -5.0)


def _xy_yaw(sim, name):
    position, quat, _, _ = sim.world.ground_truth(name)
    x, y, z, w = quat
    return position[0], position[1], math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def test_two_robots_each_with_its_controller_manager():
    log = []
    sim = _simulation({'r1': _forward, 'r2': _turn}, log)
    r1 = sim.spawn(tutorial_urdf(), 'r1', [0, 0, 0.0, 0, 0, 0, 1], namespace='r1')
    r2 = sim.spawn(tutorial_urdf(), 'r2', [0, 2, 0.0, 0, 0, 0, 1], namespace='/r2')
    assert (r1.namespace, r2.namespace) == ('/r1', '/r2')
    assert r1.frame_prefix == 'r1/'
    assert r1.controller_manager is not r2.controller_manager
    while sim.time < 2.0 - 1e-9:
        assert sim.run_cycle() == 10  # 100 Hz control, 1 ms physics
    # every instant: read of both, then update of both, then write of both, at the same t
    first = log[:6]
    assert [(n, p) for n, p, _, _ in first] == [
        ('r1', 'read'), ('r2', 'read'), ('r1', 'update'), ('r2', 'update'),
        ('r1', 'write'), ('r2', 'write')]
    assert [t for _, _, t, _ in first] == [pytest.approx(0.01)] * 6
    assert all(period == pytest.approx(0.01) for _, _, _, period in log)
    assert len(log) == 6 * 200
    x1, y1, yaw1 = _xy_yaw(sim, 'r1')
    x2, y2, yaw2 = _xy_yaw(sim, 'r2')
    assert x1 > 0.3 and abs(y1) < 0.05 and abs(yaw1) < 0.1  # drove forward
    assert math.hypot(x2, y2 - 2) < 0.1 and abs(yaw2) > 0.3  # turned in place


def test_determinism_bit_identical_trajectories():
    def schedule(t):
        return (-5.0, -5.0) if t < 0.5 else (-2.0, -6.0) if t < 1.2 else (4.0, -4.0)

    def run():
        sim = _simulation({'a': schedule, 'b': _turn}, [])
        sim.spawn(tutorial_urdf(), 'a', [0, 0, 0.05, 0, 0, 0, 1], namespace='a')
        sim.run_cycle()
        sim.spawn(tutorial_urdf(), 'b', [0.6, 0, 0.05, 0, 0, 0, 1], namespace='b')
        trajectory = []
        while sim.time < 2.0 - 1e-9:
            sim.run_cycle()
            trajectory.append(np.array(sim.world.data.qpos))
        return np.array(trajectory)

    first, second = run(), run()
    assert first.shape == second.shape
    assert first.tobytes() == second.tobytes()


def test_robots_collide_with_each_other():
    def drive(with_obstacle):
        sim = _simulation({'a': _forward, 'b': lambda t: (0.0, 0.0)}, [])
        sim.spawn(tutorial_urdf(), 'a', [0, 0, 0.0, 0, 0, 0, 1], namespace='a')
        if with_obstacle:
            sim.spawn(tutorial_urdf(), 'b', [0.8, 0, 0.0, 0, 0, 0, 1], namespace='b')
        while sim.time < 3.0:
            sim.run_cycle()
        return sim, _xy_yaw(sim, 'a')[0]

    _, free = drive(False)
    sim, blocked = drive(True)
    assert free > 1.0  # alone, a drives on
    assert blocked < 0.75 < free  # b (at rest at x 0.8) stops it: they do not pass through
    assert blocked < _xy_yaw(sim, 'b')[0]


def test_names_and_namespaces_unique_first_keeps_running():
    log, released = [], []
    sim = _simulation({'a': _forward, 'a_0': _forward}, log, released)
    sim.spawn(tutorial_urdf(), 'a', None, namespace='r1')
    with pytest.raises(ValueError, match="an entity named 'a' already exists"):
        sim.spawn(tutorial_urdf(), 'a', None, namespace='r2')
    with pytest.raises(ValueError, match="namespace '/r1' is already used by entity 'a'"):
        sim.spawn(tutorial_urdf(), 'b', None, namespace='/r1')
    with pytest.raises(ValueError, match='not a valid ROS namespace'):
        sim.spawn(tutorial_urdf(), 'c', None, namespace='1bad')
    assert list(sim.entities) == ['a'] and len(sim.world.robots) == 1
    renamed = sim.spawn(tutorial_urdf(), 'a', None, namespace='r3', allow_renaming=True)
    assert renamed.name == 'a_0'
    sim.run_cycle()
    assert {n for n, _, _, _ in log} == {'a', 'a_0'}


def test_failed_setup_undoes_the_spawn_and_releases_the_controller_manager():
    released = []
    sim = _simulation({'a': _forward}, [], released)

    def setup(entity):
        raise RuntimeError('publisher failed\nsecond line')
    with pytest.raises(ValueError, match='^publisher failed$'):
        sim.spawn(tutorial_urdf(), 'a', None, namespace='a', setup=setup)
    assert released == ['a']
    assert sim.entities == {} and sim.world.robots == {} and sim.active == ()
    sim.spawn(tutorial_urdf(), 'a', None, namespace='a')  # the name is free again


def test_driven_wheel_without_collision_spawns_with_one_warning():
    urdf = tutorial_urdf()
    start = urdf.index('<link name="wheel_front_left">')
    start = urdf.index('<collision>', start)
    urdf = urdf[:start] + urdf[urdf.index('</collision>', start) + len('</collision>'):]
    logger = ListLog()
    sim = _simulation({'a': _forward}, [], logger=logger)
    sim.spawn(urdf, 'a', None)  # Gazebo spawns it too
    assert list(sim.entities) == ['a']
    assert logger.lines == [
        "entity 'a': link 'wheel_front_left': no <collision> on the link driven by joint "
        "'joint_wheel_front_left' (velocity command interface): it cannot touch the ground"]


def test_normalize_namespace():
    assert normalize_namespace('') == '' and normalize_namespace('/') == ''
    assert normalize_namespace('r1') == '/r1'
    assert normalize_namespace('/fleet/r_2') == '/fleet/r_2'
    for bad in ('r1/', 'a//b', '2r', 'r-1', 'r 1', '/r1/'):
        with pytest.raises(ValueError, match='not a valid ROS namespace'):
            normalize_namespace(bad)


def test_non_finite_state_pauses_once_and_names_the_body():
    class Log:

        def __init__(self):
            self.errors = []

        def info(self, text):
            pass

        warning = info

        def error(self, text):
            self.errors.append(text)

    logger = Log()
    sim = _simulation({'a': _forward}, [], logger=logger)
    sim.spawn(tutorial_urdf(), 'a', None, namespace='a')
    sim.run_cycle()
    joint = sim.world.model.joint('a/joint_wheel_front_left')
    sim.world.data.qvel[joint.dofadr[0]] = float('nan')
    sim.run_cycle()
    assert sim.paused and sim.halted
    for _ in range(5):
        assert sim.run_cycle() == 0
    assert len(logger.errors) == 1
    assert "body 'a/" in logger.errors[0] and 'paused' in logger.errors[0]
    sim.reset()
    assert sim.halted is None and sim.time == 0.0
    sim.set_paused(False)
    assert sim.run_cycle() == 10


def test_thread_pause_step_and_requests():
    sim = _simulation({'a': _forward}, [], paused=True)
    sim.start()
    try:
        entity = sim.spawn(tutorial_urdf(), 'a', None, namespace='a')  # spawn while paused
        assert sim.time == 0.0
        assert sim.request_steps(25).wait(10)
        assert sim.step_count == 25
        cycles = []
        event = threading.Event()

        def after(t):
            cycles.append(t)
            if len(cycles) >= 50:
                event.set()
        sim.after_cycle.append(after)
        sim.set_paused(False)
        assert event.wait(30)
        assert entity in sim.active
    finally:
        sim.stop()


def test_external_clock_never_ahead():
    sim = _simulation({'a': _forward}, [])
    sim.follow_external_clock()
    assert sim.run_cycle() == 0  # no external time yet
    sim.set_external_time(5.0)
    assert sim.run_cycle() == 0 and sim.time == pytest.approx(5.0)  # joined, empty world
    sim.spawn(tutorial_urdf(), 'a', None, namespace='a')
    sim.set_external_time(5.025)
    steps = 0
    while True:
        n = sim.run_cycle()
        if not n:
            break
        steps += n
    assert steps == 25 and sim.time == pytest.approx(5.025)
