# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 topic``: one module per group of verbs, each adding its own arguments (as ros2topic).

``listing`` (list, find, type, info), ``echo``, ``pub``, ``rates`` (hz, bw, delay); shared
helpers in ``api``.
"""

from amr_description.cli.extension import Command

COMMAND = Command('Various topic related sub-commands')
"""``ros2 topic``: its verbs are registered in ``amr_description.topic.verb``."""
