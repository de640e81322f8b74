# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Model, simulate and drive a four-wheeled skid-steer robot with ROS 2 Jazzy."""
