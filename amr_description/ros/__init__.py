# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""rclpy plumbing with no project logic: Node base, shutdown, sim time, stamps, clients."""
