# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Benchmarks, stress runs, profiles and reports (console scripts and scripts/ call them)."""
