# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Mock hardware, as ros2_control's ``mock_components/GenericSystem``: no physics.

Each command is mirrored to the state interface of the same name; a joint with a
``velocity`` command and a ``position`` state integrates the position over the period
(``position += velocity * period``), so odometry can be tested without a simulator.
States start at their ``initial_value`` or 0.0; commands start NaN, and a NaN command leaves
the state unchanged (ros2_control's mock does the same).
"""

import math

from amr_description.control.hardware_interface import SystemInterface


class GenericSystem(SystemInterface):
    """Commands mirrored to states; position integrated from the velocity command."""

    def on_init(self, info):
        """
        Create handles from ``info``; unset state values become 0.0.

        :param info: a ``HardwareInfo``.
        :returns: True.
        """
        super().on_init(info)
        for handle in self.state_handles.values():
            if math.isnan(handle.value):
                handle.value = 0.0
        return True

    def read(self, time, period):
        """
        Copy commands to states and integrate positions.

        :param time: current time (s).
        :param period: time since the previous read (s).
        :returns: True.
        """
        for name, command in self.command_handles.items():
            if math.isnan(command.value):
                continue
            joint, iface = name.rsplit('/', 1)
            state = self.state_handles.get(name)
            if state is not None:
                state.value = command.value
            if iface == 'velocity':
                position = self.state_handles.get(f'{joint}/position')
                if position is not None and f'{joint}/position' not in self.command_handles:
                    position.value += command.value * period
        return True
