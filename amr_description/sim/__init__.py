# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""MuJoCo world, URDF -> MJCF conversion and the MuJoCo hardware interface."""
