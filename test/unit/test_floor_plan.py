# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The floor plan of docs/architecture.md, read from every import of the package.

Every ``import`` and ``from ... import`` statement of every module (also those inside
functions, and relative ones) is read with :mod:`ast`. A folder may import its own floor's
folders and the floors below, never a floor above; the folders' import graph has no circle;
core/ (pure logic) imports no other folder and ros/ (plumbing) none with project logic.
"""

import ast
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PACKAGE = os.path.join(ROOT, 'amr_description')

FLOORS = {
    'core': 1, 'ros': 1,
    'control': 2, 'sim': 2, 'web': 2, 'launch': 2, 'nav': 2,
    'nodes': 3, 'cli': 3, 'tools': 3,
}
"""Folder -> floor (1 is the ground), as drawn in docs/architecture.md."""

ONLY_ITSELF = {'core', 'ros'}
"""Ground-floor folders that import no other folder of the package."""

NO_RCLPY = {'core', 'sim', 'nav'}
"""Folders of pure logic and engines: they never import rclpy (nodes drive them)."""


def _modules():
    """Yield ``(folder, dotted module name, path)`` of every module of the package."""
    for base, _, files in os.walk(PACKAGE):
        for name in sorted(files):
            if not name.endswith('.py'):
                continue
            path = os.path.join(base, name)
            rel = os.path.relpath(path, ROOT)[:-3].split(os.sep)
            if rel[-1] == '__init__':
                rel = rel[:-1]
            folder = rel[1] if len(rel) > 2 or (len(rel) == 2 and rel[1] in FLOORS) else None
            yield folder, '.'.join(rel), path


def _imports(module, path):
    """Return every ``amr_description`` module name imported by the file at ``path``."""
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    package = module if path.endswith('__init__.py') else module.rpartition('.')[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ''
            if node.level:
                parts = package.split('.')
                parts = parts[:len(parts) - node.level + 1]
                base = '.'.join(parts + ([base] if base else []))
            found += [f'{base}.{alias.name}' for alias in node.names] + [base]
    return [name for name in found if name.split('.')[0] == 'amr_description']


def _external_imports(path):
    """Return the top-level names of every module the file at ``path`` imports."""
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found |= {alias.name.split('.')[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            found.add(node.module.split('.')[0])
    return found


def _folder_of(name):
    parts = name.split('.')
    return parts[1] if len(parts) > 1 and parts[1] in FLOORS else None


def _edges():
    """Return ``{(folder, imported folder): first 'module -> import' seen}``."""
    edges = {}
    for folder, module, path in _modules():
        for name in _imports(module, path):
            target = _folder_of(name)
            if folder is None or target is None or target == folder:
                continue
            edges.setdefault((folder, target), f'{module} -> {name}')
    return edges


def test_every_folder_has_a_floor():
    folders = {entry for entry in os.listdir(PACKAGE)
               if os.path.isdir(os.path.join(PACKAGE, entry)) and not entry.startswith('__')}
    assert folders == set(FLOORS)


def test_no_import_runs_up_a_floor():
    up = [where for (a, b), where in _edges().items() if FLOORS[b] > FLOORS[a]]
    assert not up, 'imports that run up a floor:\n' + '\n'.join(sorted(up))


def test_ground_floor_imports_no_other_folder():
    bad = [where for (a, b), where in _edges().items() if a in ONLY_ITSELF]
    assert not bad, 'ground-floor imports of other folders:\n' + '\n'.join(sorted(bad))


def test_pure_folders_import_no_rclpy():
    bad = [module for folder, module, path in _modules()
           if folder in NO_RCLPY and 'rclpy' in _external_imports(path)]
    assert not bad, 'rclpy imported by pure logic or an engine:\n' + '\n'.join(sorted(bad))


def test_no_circle_between_folders():
    edges = _edges()
    graph = {}
    for a, b in edges:
        graph.setdefault(a, set()).add(b)

    def reaches(start, goal, seen):
        for nxt in graph.get(start, ()):
            if nxt == goal:
                return True
            if nxt not in seen:
                seen.add(nxt)
                if reaches(nxt, goal, seen):
                    return True
        return False

    circles = [where for (a, b), where in edges.items() if reaches(b, a, set())]
    assert not circles, 'imports in a circle of folders:\n' + '\n'.join(sorted(circles))


@pytest.mark.parametrize('source, expected', [
    ('from amr_description.sim import world\n', 'sim'),
    ('from ..sim.world import World\n', 'sim'),
    ('def f():\n    import amr_description.nodes.viewer\n', 'nodes'),
])
def test_the_reader_sees_every_form_of_import(tmp_path, source, expected):
    path = tmp_path / 'probe.py'
    path.write_text(source)
    names = _imports('amr_description.control.probe', str(path))
    assert expected in {_folder_of(name) for name in names}


def test_test_modules_have_distinct_names():
    # test/ has no __init__.py: pytest imports each test file by its base name, so two
    # files of one name in unit/ and integration/ stop the whole suite at collection.
    seen = {}
    for folder, _, files in os.walk(os.path.join(ROOT, 'test')):
        for name in files:
            if name.startswith('test_') and name.endswith('.py'):
                seen.setdefault(name, []).append(os.path.relpath(folder, ROOT))
    twice = {name: where for name, where in seen.items() if len(where) > 1}
    assert not twice, f'test files sharing a name: {twice}'


MAX_MODULE_LINES = 500
"""Largest module (lines): a longer one is split by what its parts do."""

MAX_CORE_MODULES = 20
"""Most modules directly in core/; groups that belong together get a sub-package."""


def test_no_module_is_over_500_lines():
    long = []
    for _, module, path in _modules():
        with open(path) as f:
            count = sum(1 for _ in f)
        if count > MAX_MODULE_LINES:
            long.append(f'{module}: {count} lines')
    assert not long, 'modules over 500 lines:\n' + '\n'.join(long)


def test_core_has_rooms():
    core = os.path.join(PACKAGE, 'core')
    modules = [name for name in os.listdir(core) if name.endswith('.py') and name != '__init__.py']
    assert len(modules) <= MAX_CORE_MODULES, sorted(modules)
    for room in ('gazebo', 'description', 'model_check', 'message_yaml'):
        assert os.path.isfile(os.path.join(core, room, '__init__.py')), room


def test_one_xml_library():
    users = {}
    for _, module, path in _modules():
        for name in _external_imports(path):
            if name in ('xml', 'lxml', 'defusedxml'):
                users.setdefault(name, []).append(module)
    assert set(users) <= {'lxml'}, users
    assert users.get('lxml') == ['amr_description.core.xml_document'], users
