# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 bag record|play|info`` on ``rosbags`` (rosbag2 directories, MCAP or SQLite 3).

One module per verb, each adding its own arguments, as ros2bag does; shared helpers in
``api``.
"""

from amr_description.cli.bag import info
from amr_description.cli.bag import play
from amr_description.cli.bag import record


def add_command(subparsers):
    """
    Add the ``bag`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('bag', help='Various rosbag related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    for module in (info, play, record):
        module.add_verbs(verbs)
