# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""ROS name rules of rcl, without rclpy (namespaces of spawned robots)."""

import re

_NAME_TOKEN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def normalize_namespace(namespace):
    """
    Return a ROS namespace in its absolute form, ``''`` for the root namespace.

    Rules of rcl's ``rmw_validate_namespace`` as they apply to a node namespace: tokens of
    letters, digits and ``_``, not starting with a digit, separated by single ``/``; no
    trailing ``/``. A relative namespace (``r1``) is made absolute (``/r1``).

    :param namespace: str, e.g. ``'r1'``, ``'/fleet/r1'``, ``''`` or ``'/'``.
    :returns: ``''`` or ``'/r1'``-style str.
    :raises ValueError: one line naming the namespace and the rule it breaks.
    """
    if namespace in ('', '/'):
        return ''
    text = namespace if namespace.startswith('/') else '/' + namespace
    for token in text[1:].split('/'):
        if not _NAME_TOKEN.match(token):
            raise ValueError(
                f'namespace {namespace!r} is not a valid ROS namespace: tokens of letters, '
                'digits and "_" not starting with a digit, separated by single "/"')
    return text
