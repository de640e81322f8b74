# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The simulator's sensors: one module per sensor type, registered by entry point.

A sensor (:class:`~amr_description.sim.sensors.base.Sensor`) is made for one spawned entity
from its description by a factory registered in the entry-point group
``amr_description.sensors`` (:mod:`~amr_description.sim.sensors.registry`); it measures the
world at sim time ``t`` and returns the ROS message to publish, without rclpy, so each sensor
is unit-tested against closed forms. The ``mujoco_sim`` node makes one publisher per sensor.
"""
