# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Model, simulate and drive a four-wheeled skid-steer robot with ROS 2 Jazzy.

Importing the package chooses MuJoCo's OpenGL platform before any module imports MuJoCo
(MuJoCo reads ``MUJOCO_GL`` once, at its own import): EGL, which renders on a machine
without a display, unless the user's ``MUJOCO_GL`` says otherwise (``glfw``, ``osmesa``).
"""

import os

os.environ.setdefault('MUJOCO_GL', 'egl')
