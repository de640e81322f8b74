# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Robot descriptions: reading a URDF (or xacro) once, and its parts.

- :mod:`.files`: description files: URIs through the ament index, xacro expanded;
- :mod:`.urdf_model`: the one URDF loader (``parse_urdf``) and ``RobotModel``;
- :mod:`.ros2_control_info`: the ``<ros2_control>`` blocks (``HardwareInfo``);
- :mod:`.mujoco_block`: the simulator extension block ``<mujoco>``;
- :mod:`.robot_description`: ``RobotDescription``, every part of one parse.

Pure logic, no rclpy (docs/architecture.md).
"""
