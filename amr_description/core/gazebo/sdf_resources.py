# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Where SDF worlds find their ``<include>`` models: resource path variables and Fuel names.

gz-sim looks ``model://NAME`` up in the folders of its resource path variables and downloads
``https://fuel.gazebosim.org/...`` URIs from Fuel. Nothing is downloaded here; the two Fuel
models nearly every world includes, "Ground Plane" and "Sun", are shipped in the package's
``worlds/models`` and their Fuel URIs read as ``model://ground_plane`` and ``model://sun``.
"""

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
