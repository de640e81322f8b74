# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 topic``: one module per group of verbs, each adding its own arguments (as ros2topic).

``listing`` (list, find, type, info), ``echo``, ``pub``, ``rates`` (hz, bw, delay); shared
helpers in ``api``.
"""

from amr_description.cli.topic import echo
from amr_description.cli.topic import listing
from amr_description.cli.topic import pub
from amr_description.cli.topic import rates


def add_command(subparsers):
    """
    Add the ``topic`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('topic', help='Various topic related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    for module in (listing, echo, pub, rates):
        module.add_verbs(verbs)
