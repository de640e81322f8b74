# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 param``: list, get, set, describe, dump, load, delete (as ros2param, jazzy).

Verbs talk to any node's parameter services (``~/list_parameters``, ``~/get_parameters``,
``~/set_parameters``, ``~/describe_parameters``), so they work with every rclpy node. Errors
are one line on stderr and exit code 1, as ros2cli does with a verb's returned string.
"""

from amr_description.cli.extension import Command

COMMAND = Command('Various param related sub-commands')
"""``ros2 param``: its verbs are registered in ``amr_description.param.verb``."""
