# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Mapping and navigation logic, no rclpy: maps, costmaps, planning, path following, SLAM, AMCL.

Floor 2, beside control/ (docs/architecture.md): it may use core/ and nothing above; the
nodes that serve it over ROS (map_server, amcl, the SLAM node, Nav2's servers) live in
nodes/ and drive these plain classes, as mujoco_sim drives sim/.

- :mod:`.map_io`: map files (YAML + image) as nav2_map_server reads and map_saver writes them.
"""
