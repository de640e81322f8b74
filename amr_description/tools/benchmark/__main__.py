# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``python -m amr_description.tools.benchmark``: run the benchmark (report.main)."""

import sys

from amr_description.tools.benchmark.report import main

sys.exit(main())
