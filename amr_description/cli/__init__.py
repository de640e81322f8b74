# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``ros2`` command subset: command -> verb, upstream output formats."""
