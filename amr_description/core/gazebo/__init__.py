# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The Gazebo dialect, read without Gazebo: SDF worlds, sensor blocks, gz-sim systems, tags.

- :mod:`.sdf_world`: SDF worlds and models (``<include>``, ``model://``);
- :mod:`.sdf_resources`: where includes are found (resource path variables, Fuel names);
- :mod:`.sensors`: ``<gazebo reference><sensor>`` blocks, one reader per kind;
- :mod:`.systems`: the gz-sim system plugins a description names;
- :mod:`.tags`: ``<gazebo>`` reference tags (materials, friction, gravity, gz_ros2_control);
- :mod:`.bridge_config`: ros_gz_bridge YAML files.

Pure logic, no rclpy and no MuJoCo: sim/ builds what these read (docs/gazebo.md).
"""
