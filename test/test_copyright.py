# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Every Python source of the project starts with the project's copyright and license lines.

Stands in for ament_copyright, which is not on PyPI.
"""

import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADER = (
    '# Copyright 2026 The amr_description Authors',
    '# Licensed under the Apache License, Version 2.0',
)


def python_sources():
    """
    Return the repository-relative paths of the Python files that need the header.

    :returns: sorted list of paths under ``amr_description/``, ``test/``, plus ``setup.py``.
    """
    found = ['setup.py']
    for top in ('amr_description', 'test'):
        for folder, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [d for d in dirs if not d.startswith(('.', '__pycache__'))]
            found += [os.path.relpath(os.path.join(folder, name), ROOT)
                      for name in files if name.endswith('.py')]
    return sorted(found)


def header_problem(path):
    """
    Return why ``path`` lacks the header, or None when it has it.

    A ``#!`` line may precede the header.

    :param path: file path, relative to the repository root.
    :returns: a one-line description of the problem, or None.
    """
    with open(os.path.join(ROOT, path), encoding='utf-8') as f:
        lines = f.read().splitlines()
    if lines and lines[0].startswith('#!'):
        lines = lines[1:]
    head = tuple(line.rstrip() for line in lines[:2])
    if head != HEADER:
        return f'{path}: first lines must be {HEADER[0]!r} and {HEADER[1]!r}'
    return None


@pytest.mark.copyright
@pytest.mark.linter
def test_copyright():
    """Check the copyright/license header of every Python source."""
    problems = [p for p in map(header_problem, python_sources()) if p]
    assert not problems, '\n'.join(problems)
