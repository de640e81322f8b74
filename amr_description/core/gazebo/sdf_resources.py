# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Where SDF worlds are found: shipped worlds, resource path variables, Fuel names.

gz-sim looks ``model://NAME`` up in the folders of its resource path variables and downloads
``https://fuel.gazebosim.org/...`` URIs from Fuel. Nothing is downloaded here; the two Fuel
models nearly every world includes, "Ground Plane" and "Sun", are shipped in the package's
``worlds/models`` and their Fuel URIs read as ``model://ground_plane`` and ``model://sun``.
"""

import os


class WorldError(ValueError):
    """A world file that cannot be read: one line naming the file and the cause."""


RESOURCE_PATH_VARIABLES = ('GZ_SIM_RESOURCE_PATH', 'IGN_GAZEBO_RESOURCE_PATH', 'SDF_PATH')
"""Environment variables searched for ``model://`` URIs, in this order (gz-sim 8 reads all)."""

FUEL_SHIPPED = {'ground plane': 'ground_plane', 'sun': 'sun'}
"""Fuel model names (lower case) read as the package's own ``model://`` folders of the same
models: Gazebo's "Ground Plane" and "Sun", included by most worlds, are not downloaded here."""


def fuel_model_name(uri):
    """
    Return the model name of a Fuel model URI, or None when ``uri`` names no Fuel model.

    Fuel's form is ``https://fuel.gazebosim.org/1.0/OWNER/models/NAME[/VERSION[/...]]``
    (also ``fuel.ignitionrobotics.org``); the name may be URL-encoded (``Ground%20Plane``).

    :param uri: an ``<include><uri>`` text.
    :returns: the name as written in the URI, decoded (``'Ground Plane'``), or None.
    """
    from urllib.parse import unquote
    from urllib.parse import urlparse
    parsed = urlparse(uri.strip())
    parts = [unquote(p) for p in parsed.path.split('/') if p]
    if parsed.scheme not in ('http', 'https') or 'models' not in parts:
        return None
    index = parts.index('models')
    return parts[index + 1] if index + 1 < len(parts) else None


def shipped_worlds_folder():
    """
    Return the folder of the package's worlds (``share/amr_description/worlds``).

    The source tree's ``worlds/`` when the package is not installed (tests from a checkout).
    """
    try:
        from ament_index_python.packages import get_package_share_directory
        folder = os.path.join(get_package_share_directory('amr_description'), 'worlds')
        if os.path.isdir(folder):
            return folder
    except Exception:  # noqa: B902 - not installed: the checkout's folder
        pass
    return os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), 'worlds')


def find_world(value):
    """
    Return the file of a ``world`` parameter: a path, ``package://``, or a shipped world's name.

    :param value: ``warehouse`` (a file ``<name>.sdf`` of :func:`shipped_worlds_folder`),
        ``package://pkg/worlds/x.sdf``, ``file://...`` or a path.
    :returns: the file path (str).
    :raises WorldError: one line when nothing is found (naming the shipped worlds).
    """
    value = str(value).strip() or 'empty'
    folder = shipped_worlds_folder()
    if os.sep not in value and '://' not in value and not value.endswith(('.sdf', '.world')):
        path = os.path.join(folder, value + '.sdf')
        if os.path.isfile(path):
            return path
        names = sorted(f[:-4] for f in os.listdir(folder) if f.endswith('.sdf')) \
            if os.path.isdir(folder) else []
        raise WorldError(f'world {value!r}: no such file and not a shipped world '
                         f'({", ".join(names)})')
    if value.startswith('package://'):
        from amr_description.core.description.files import resolve_uri
        try:
            value = resolve_uri(value)
        except ValueError as exc:
            raise WorldError(f'world: {exc}') from None
    elif value.startswith('file://'):
        value = value[len('file://'):]
    if not os.path.isfile(value):
        raise WorldError(f'world {value!r}: no such file')
    return value
