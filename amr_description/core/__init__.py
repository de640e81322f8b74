# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Pure logic with no rclpy: kinematics, odometry, limiters, URDF checks, YAML <-> message."""
