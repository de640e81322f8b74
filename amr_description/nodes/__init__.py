# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""One rclpy node per module, each with ``main(args=None)``."""
