# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The controllers' parameter table: declared once, read and checked into a frozen object."""

import dataclasses

from amr_description.control.diff_drive_controller import PARAMETERS
from amr_description.control.parameter_table import Parameter
from amr_description.control.parameter_table import ParameterTable
from amr_description.control.parameter_table import positive
from amr_description.control.parameter_table import size
import pytest


class FakeController:
    """``auto_declare`` and ``param`` of a controller node, over a dict of overrides."""

    def __init__(self, overrides=None):
        self.overrides = dict(overrides or {})
        self.declared = []

    def auto_declare(self, name, default, description=''):
        self.declared.append((name, default, description))
        return self.overrides.get(name, default)

    def param(self, name, default=None):
        return self.overrides.get(name, default)


TABLE = ParameterTable('Example', [
    Parameter('wheel_radius', 0.1, 'Wheel radius (m)', positive),
    Parameter('linear.x.max_velocity', 1.0, 'Limit'),
    Parameter('covariance', [0.0] * 3, 'Diagonal', size(3)),
])


def test_declared_once_with_defaults_and_descriptions():
    controller = FakeController()
    TABLE.declare(controller)
    assert controller.declared == [('wheel_radius', 0.1, 'Wheel radius (m)'),
                                   ('linear.x.max_velocity', 1.0, 'Limit'),
                                   ('covariance', [0.0] * 3, 'Diagonal')]


def test_read_into_a_frozen_object():
    values = TABLE.read(FakeController({'wheel_radius': 0.2}))
    assert (values.wheel_radius, values.linear_x_max_velocity) == (0.2, 1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        values.wheel_radius = 1.0


@pytest.mark.parametrize('overrides, message', [
    ({'wheel_radius': 0.0}, "parameter 'wheel_radius' must be > 0, got 0.0"),
    ({'wheel_radius': float('nan')}, "parameter 'wheel_radius' must be > 0, got nan"),
    ({'covariance': [1.0]}, "parameter 'covariance' must have 3 elements, got 1"),
])
def test_a_broken_rule_is_one_line_naming_the_parameter(overrides, message):
    with pytest.raises(ValueError) as refused:
        TABLE.read(FakeController(overrides))
    assert str(refused.value) == message


def test_diff_drive_controller_table_has_upstream_names_and_defaults():
    controller = FakeController()
    PARAMETERS.declare(controller)
    declared = {name: default for name, default, _ in controller.declared}
    assert declared['wheel_separation'] == 0.0 and declared['publish_rate'] == 50.0
    assert declared['cmd_vel_timeout'] == 0.5 and declared['base_frame_id'] == 'base_link'
    assert declared['velocity_rolling_window_size'] == 10
    assert len(declared) == 20 + 2 * 8  # 20 parameters and 8 limits per channel
    with pytest.raises(ValueError, match="'left_wheel_names' is empty"):
        PARAMETERS.read(controller)
