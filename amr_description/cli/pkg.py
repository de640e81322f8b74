# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 pkg list|prefix|executables|xml``: packages of the ament index (formats of ros2pkg).

The index is the one ament_index_python reads: every prefix of ``AMENT_PREFIX_PATH``.
"""

import os

from amr_description.cli.common import fail
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb


def package_prefixes():
    """
    Return every package of the ament index with its prefix.

    :returns: dict package name -> install prefix (the first prefix wins, as in ament).
    """
    from ament_index_python.packages import get_packages_with_prefixes
    return get_packages_with_prefixes()


def executable_paths(package, prefix):
    """
    Find the executables of ``package``: files with the exec bit under ``prefix/lib/PKG``.

    :param package: the package name.
    :param prefix: its install prefix.
    :returns: sorted list of absolute paths.
    """
    base = os.path.join(prefix, 'lib', package)
    found = []
    for dirpath, dirnames, filenames in os.walk(base):
        dirnames[:] = [d for d in dirnames if not d.startswith('.')]
        for filename in filenames:
            path = os.path.join(dirpath, filename)
            if os.path.isfile(path) and os.access(path, os.X_OK):
                found.append(path)
    return sorted(found)


def _list(args):
    for name in sorted(package_prefixes()):
        print(name)
    return 0


def _prefix(args):
    prefix = package_prefixes().get(args.package_name)
    if prefix is None:
        return fail('Package not found')
    print(os.path.join(prefix, 'share', args.package_name) if args.share else prefix)
    return 0


def _executables(args):
    prefixes = package_prefixes()
    if args.package_name is not None:
        if args.package_name not in prefixes:
            return fail('Package not found')
        names = [args.package_name]
    else:
        names = sorted(prefixes)
    for name in names:
        paths = executable_paths(name, prefixes[name])
        if args.full_path:
            lines = paths
        else:
            lines = sorted(f'{name} {os.path.basename(p)}' for p in paths)
        for line in lines:
            print(line)
    return 0


def _xml(args):
    from amr_description.core.xml_document import parse_text
    from amr_description.core.xml_document import XMLError
    prefix = package_prefixes().get(args.package_name)
    if prefix is None:
        return fail('Package not found')
    path = os.path.join(prefix, 'share', args.package_name, 'package.xml')
    try:
        with open(path, 'r') as f:
            text = f.read()
    except OSError as exc:
        return fail(f'{path}: {exc.strerror}')
    if args.tag is None:
        print(text, end='' if text.endswith('\n') else '\n')
        return 0
    try:
        root = parse_text(text)
    except XMLError as exc:
        return fail(f'{path}: {exc}')
    for element in root.findall(args.tag):
        print((element.text or '').strip())
    return 0


VERB_LIST = Verb('Output a list of available packages', _list)
"""``ros2 pkg list``."""


def _arguments_prefix(p):
    """Add the arguments of ``ros2 pkg prefix``."""
    p.add_argument('package_name', help='The package name')
    p.add_argument('--share', action='store_true',
                   help='Show share directory for the package')


VERB_PREFIX = Verb('Output the prefix path of a package', _prefix, _arguments_prefix)
"""``ros2 pkg prefix``."""


def _arguments_executables(p):
    """Add the arguments of ``ros2 pkg executables``."""
    p.add_argument('package_name', nargs='?', help='The package name')
    p.add_argument('--full-path', action='store_true',
                   help='Show the full path of each executable')


VERB_EXECUTABLES = Verb(
    'Output a list of package specific executables',
    _executables, _arguments_executables)
"""``ros2 pkg executables``."""


def _arguments_xml(p):
    """Add the arguments of ``ros2 pkg xml``."""
    p.add_argument('package_name', help='The package name')
    p.add_argument('-t', '--tag', help='The XML tag to output (e.g. version)')


VERB_XML = Verb('Output the XML of the package manifest or a specific tag', _xml, _arguments_xml)
"""``ros2 pkg xml``."""


COMMAND = Command('Various package related sub-commands')
"""``ros2 pkg``: its verbs are registered in ``amr_description.pkg.verb``."""
