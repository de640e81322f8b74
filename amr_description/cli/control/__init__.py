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

from amr_description.cli.control.api import common_arguments
from amr_description.cli.extension import Command

COMMAND = Command('Various control related sub-commands', verb_arguments=common_arguments)
"""``ros2 control``: its verbs (registered in ``amr_description.control.verb``) all take the
controller manager options of :func:`~amr_description.cli.control.api.common_arguments`."""
