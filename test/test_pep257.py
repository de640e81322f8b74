# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""ament pep257 (docstring conventions) over the package sources."""

import os

from ament_pep257.main import main
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATHS = [os.path.join(ROOT, name) for name in ('amr_description', 'nav2_simple_commander', 'test',
                                               'setup.py')]


@pytest.mark.linter
@pytest.mark.pep257
def test_pep257():
    """Check that every docstring follows ament_pep257's conventions."""
    rc = main(argv=PATHS)
    assert rc == 0, 'found docstring errors (listed above)'
