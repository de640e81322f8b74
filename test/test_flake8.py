# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""ament flake8 over the package sources, as upstream ament_python packages run it."""

import os

from ament_flake8.main import main_with_errors
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Lint our sources only: the repository root also holds .venv/, build/, install/ and log/.
PATHS = [os.path.join(ROOT, name) for name in ('amr_description', 'nav2_simple_commander', 'test',
                                               'setup.py')]


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8():
    """Check that the sources pass ament_flake8's configuration (99 columns, single quotes)."""
    rc, errors = main_with_errors(argv=PATHS)
    assert rc == 0, f'{len(errors)} flake8 errors/warnings:\n' + '\n'.join(errors)
