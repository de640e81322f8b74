# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""One parse per description: a spawn with its controllers parses the URDF text once."""

import os
import xml.etree.ElementTree as ET

from conftest import next_domain_id
from conftest import release_domain_id
import pytest

rclpy = pytest.importorskip('rclpy')

from amr_description.control.controller_manager import ControllerManager  # noqa: E402, I100
from amr_description.core.description.robot_description import RobotDescription  # noqa: E402
from amr_description.ros.sim_time import SimTime  # noqa: E402
from amr_description.ros.sim_time import SimTimeExecutor  # noqa: E402
from amr_description.sim.simulation import Simulation  # noqa: E402
from lxml import etree  # noqa: E402
from sim_fixtures import REPO  # noqa: E402
from sim_fixtures import tutorial_urdf  # noqa: E402


def test_parts_of_a_description():
    description = RobotDescription(tutorial_urdf())
    assert description.name == 'amr' and description.model.root == 'base_footprint'
    assert [info.plugin for info in description.hardware] == ['amr_description/MujocoSystem']
    assert description.joint_names(moving_only=True) == [
        'joint_wheel_front_left', 'joint_wheel_front_right', 'joint_wheel_rear_left',
        'joint_wheel_rear_right']
    assert description.mujoco.contact['condim'] == 3  # no block: the defaults


def test_a_bad_description_is_one_line_naming_the_source():
    with pytest.raises(ValueError) as refused:
        RobotDescription('<robot name="r"><link name="a"/></robot', source='r.urdf')
    assert str(refused.value).startswith('r.urdf: not well-formed XML') and \
        '\n' not in str(refused.value)


@pytest.fixture
def count_parses(monkeypatch):
    """Count every XML parse of lxml and of the standard library from here on."""
    counts = []
    for module, name in ((etree, 'fromstring'), (etree, 'parse'), (etree, 'XML'),
                         (ET, 'fromstring'), (ET, 'parse'), (ET, 'XML')):
        original = getattr(module, name)

        def counted(*args, _original=original, _name=name, **kwargs):
            counts.append(_name)
            return _original(*args, **kwargs)
        monkeypatch.setattr(module, name, counted)
    return counts


def test_one_spawn_with_its_controllers_parses_the_urdf_once(count_parses, monkeypatch):
    domain = next_domain_id()
    monkeypatch.setenv('ROS_DOMAIN_ID', str(domain))
    monkeypatch.setenv('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    context = rclpy.context.Context()
    rclpy.init(context=context)
    executor = SimTimeExecutor(SimTime(), context=context)

    def factory(entity, hardware_factory, parameters_file):
        return ControllerManager(entity.description, executor, hardware_factory,
                                 parameters_file, entity.namespace)
    sim = Simulation(real_time_factor=0.0, controller_manager_factory=factory,
                     controller_manager_release=lambda cm: cm.destroy(),
                     parameters_file=os.path.join(REPO, 'config', 'controllers.yaml'))
    try:
        urdf = tutorial_urdf()
        del count_parses[:]
        entity = sim.spawn(urdf, 'amr', None)
        cm = entity.controller_manager
        names = ['joint_state_broadcaster']  # the controller that reads the URDF
        for name in names:
            assert cm.load_controller(name) is not None
            assert cm.configure_controller(name)
        assert cm.switch_controller(names, [], wait=False)[0]
        for _ in range(3):
            sim.run_cycle()
        assert cm.controllers['joint_state_broadcaster'].lifecycle_state == 'active'
        assert count_parses == ['fromstring'], count_parses
    finally:
        sim.close()
        executor.shutdown()
        rclpy.shutdown(context=context)
        release_domain_id(domain)
        os.environ.pop('ROS_DOMAIN_ID', None)
