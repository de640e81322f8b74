# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 bag record|play|info`` on ``rosbags`` (rosbag2 directories, MCAP or SQLite 3).

One module per verb, each adding its own arguments, as ros2bag does; shared helpers in
``api``.
"""

from amr_description.cli.extension import Command

COMMAND = Command('Various rosbag related sub-commands')
"""``ros2 bag``: its verbs are registered in ``amr_description.bag.verb``."""
