# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 param``: list, get, set, describe, dump, load, delete (as ros2param, jazzy).

Verbs talk to any node's parameter services (``~/list_parameters``, ``~/get_parameters``,
``~/set_parameters``, ``~/describe_parameters``), so they work with every rclpy node. Errors
are one line on stderr and exit code 1, as ros2cli does with a verb's returned string.
"""

from amr_description.cli.param import change
from amr_description.cli.param import query


def add_command(subparsers):
    """
    Add the ``param`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('param', help='Various param related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    query.add_verbs(verbs)
    change.add_verbs(verbs)
