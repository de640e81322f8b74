# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The process orchestrator and the stack descriptions that replace launch files."""
