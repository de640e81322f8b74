# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Robot description files: URIs resolved through the ament index, xacro expanded.

Where a URDF file is accepted (``create -file``, ``check_model``, ``render --urdf``, the
stacks' ``description:=``), a ``.xacro`` file is too: it is expanded with the official xacro
(ros/xacro from PyPI, what ``Command(['xacro ', path])`` runs in a launch file) with the given
``name:=value`` arguments; ``$(find pkg)`` and ``package://`` resolve through the ament index
(this package and every package on ``AMENT_PREFIX_PATH``). A file of another name that uses
xacro (declares the ``xmlns:xacro`` namespace or has ``<xacro:`` elements) is expanded too:
courses name xacro files ``robot.urdf`` and run them through ``xacro`` in their launch files,
and read raw their includes and macros would silently be lost.
"""

import os
import re
import shlex

XACRO_SUFFIXES = ('.xacro',)
"""File names ending so are expanded with xacro (``robot.urdf.xacro``, ``robot.xacro``)."""


def resolve_uri(uri):
    """
    Resolve ``package://PKG/path``, ``$(find PKG)/path`` or ``file://path`` to a file path.

    :param uri: the URI (str).
    :returns: an absolute or relative file-system path (str).
    :raises ValueError: when the package is not in the ament index.
    """
    pkg = rest = None
    if uri.startswith('package://'):
        pkg, _, rest = uri[len('package://'):].partition('/')
    elif uri.startswith('$(find '):
        pkg, _, rest = uri[len('$(find '):].partition(')')
        rest = rest.lstrip('/')
    elif uri.startswith('file://'):
        return uri[len('file://'):]
    else:
        return uri
    from ament_index_python.packages import get_package_share_directory
    from ament_index_python.packages import PackageNotFoundError
    try:
        return os.path.join(get_package_share_directory(pkg), rest)
    except PackageNotFoundError:
        raise ValueError(f'cannot resolve {uri!r}: package {pkg!r} not found') from None


def is_xacro(path):
    """Return True when ``path`` names a xacro file (:data:`XACRO_SUFFIXES`)."""
    return str(path).endswith(XACRO_SUFFIXES)


def uses_xacro(text):
    """Return True when a description's text uses xacro (its namespace or an element)."""
    return 'xmlns:xacro' in text or '<xacro:' in text


def parse_xacro_args(text):
    """
    Return the ``name:=value`` pairs of a ``xacro_args`` string as a dict.

    :param text: e.g. ``'prefix:=r1_ use_sim:=true'`` (shell quoting allowed).
    :raises ValueError: one line naming the word that is not ``name:=value``.
    """
    mappings = {}
    try:
        words = shlex.split(text or '')
    except ValueError as exc:
        raise ValueError(f'xacro_args {text!r}: {exc}') from None
    for word in words:
        name, sep, value = word.partition(':=')
        if not sep or not name:
            raise ValueError(f'xacro_args: {word!r} is not name:=value')
        mappings[name] = value
    return mappings


def _one_line(text):
    return ' '.join(str(text).split())


def expand_xacro(path, mappings=None):
    """
    Return the URDF text of the xacro file ``path`` expanded with ``mappings``.

    :param path: the file (already resolved).
    :param mappings: dict of xacro arguments (``name:=value``).
    :raises ValueError: one line naming the file and xacro's cause (a syntax error, a missing
        argument, ``$(find nosuchpkg)``, an include that does not exist).
    """
    import xacro
    try:
        doc = xacro.process_file(path, mappings=dict(mappings or {}))
    except Exception as exc:  # noqa: B902 - xacro raises XacroException, ExpatError, OSError...
        kind = type(exc).__name__
        cause = _one_line(exc) or kind
        missing = re.search(r"package '([^']+)' not found", cause)
        if missing:  # ament_index_python's PackageNotFoundError, maybe wrapped by xacro
            cause = (f'$(find {missing.group(1)}): package {missing.group(1)!r} is not in the '
                     'ament index (AMENT_PREFIX_PATH)')
        elif kind == 'ExpatError':
            cause = f'XML parsing error: {cause}'
        raise ValueError(f'{path}: xacro: {cause}') from None
    return doc.toprettyxml(indent='  ')


def read_description(path, mappings=None):
    """
    Return the URDF text of a description file: the file itself, or its xacro expansion.

    :param path: a file path, ``package://`` or ``$(find pkg)`` URI; a ``.xacro`` file, or one
        that uses xacro (:func:`uses_xacro`), is expanded (:func:`expand_xacro`).
    :param mappings: xacro arguments (ignored for a plain URDF).
    :raises ValueError: one line naming the file: unreadable, empty, or a xacro error.
    """
    resolved = resolve_uri(path)
    if is_xacro(resolved):
        if not os.path.isfile(resolved):
            raise ValueError(f'{path}: cannot read: No such file or directory')
        text = expand_xacro(resolved, mappings)
    else:
        try:
            with open(resolved, 'rb') as f:
                text = f.read().decode('utf-8', errors='replace')
        except OSError as exc:
            raise ValueError(f'{path}: cannot read: {exc.strerror}') from None
        if uses_xacro(text):
            text = expand_xacro(resolved, mappings)
    if not text.strip():
        raise ValueError(f'{path}: empty robot description')
    return text
