# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
nav2_simple_commander's Python API (Jazzy), so that a Nav2 user's script runs unchanged.

Installed with amr_description when no upstream nav2_simple_commander is; the navigator is
:mod:`nav2_simple_commander.robot_navigator`.
"""
