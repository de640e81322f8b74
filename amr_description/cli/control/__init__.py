# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 control`` verbs: talk to a controller manager through its services.

Output formats, messages and exit codes follow ros2controlcli (jazzy): ``list_controllers``
prints ``name type  state`` with columns padded to the longest entry, ``-v`` adds the update
rate, ``is_async`` and the interfaces; ``list_hardware_interfaces`` prints ``command
interfaces``, one tab-indented ``<name> [available] [claimed]`` line each, then ``state
interfaces``; a failing verb prints upstream's "Error ..., check controller_manager logs" and
exits 1. Every service call goes through
:mod:`amr_description.control.controller_manager_services`, shared with the spawner.
ANSI colours (as upstream) are used only when stdout is a terminal. One module per group of
verbs, as ros2controlcli: ``listing``, ``lifecycle``, ``hardware``, ``chains``; each verb's
arguments are added by the ``_args_<verb>`` function right above it; shared parts in ``api``.
"""

from amr_description.cli.control import chains
from amr_description.cli.control import hardware
from amr_description.cli.control import lifecycle
from amr_description.cli.control import listing
from amr_description.cli.control.api import common_arguments


def add_command(subparsers):
    """
    Add the ``control`` command and its verbs to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('control', help='Various control related sub-commands')
    parser.set_defaults(_command_parser=parser)
    verbs = parser.add_subparsers(title='Commands', dest='verb')
    for name, text, add_arguments, main in sorted(
            listing.VERBS + lifecycle.VERBS + hardware.VERBS + chains.VERBS):
        p = verbs.add_parser(name, help=text, description=text)
        if add_arguments is not None:
            add_arguments(p)
        common_arguments(p)
        p.set_defaults(main=main)
