# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""ROS name rules of rcl, without rclpy (namespaces of spawned robots, topic names)."""

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


_TOPIC_CHARACTERS = re.compile(r'^[A-Za-z0-9_/~{}]*$')


def topic_name_problem(name):
    """
    Return why ``name`` is not a valid ROS topic name, or '' when it is one.

    The rules of rcl's ``rcl_validate_topic_name`` (relative names allowed): not empty;
    letters, digits, ``_``, ``/``, ``~``, ``{`` and ``}`` only; no ``//`` and no trailing
    ``/``; ``~`` only first and followed by ``/``; no token starting with a digit; balanced,
    unnested ``{}`` substitutions.

    :param name: the topic name, str.
    :returns: '' or a short reason, e.g. ``"it holds ' '"``.
    """
    if not isinstance(name, str) or not name:
        return 'it is empty'
    bad = sorted({c for c in name if not _TOPIC_CHARACTERS.match(c)})
    if bad:
        return 'it holds ' + ', '.join(repr(c) for c in bad) + \
            ' (letters, digits, "_", "/", "~", "{}" only)'
    if name.endswith('/'):
        return 'it ends with "/"'
    if '//' in name:
        return 'it holds "//"'
    if '~' in name[1:] or (name.startswith('~') and len(name) > 1 and name[1] != '/'):
        return '"~" may only start it, followed by "/"'
    depth = 0
    for c in name:
        depth += {'{': 1, '}': -1}.get(c, 0)
        if depth not in (0, 1):
            return 'its "{}" are unbalanced or nested'
    if depth:
        return 'its "{}" are unbalanced or nested'
    for token in name.lstrip('~').split('/'):
        if token[:1].isdigit():
            return f'its token {token!r} starts with a digit'
    return ''


def check_topic_name(name, what):
    """
    Raise when ``name`` is not a valid ROS topic name (:func:`topic_name_problem`).

    :param name: the topic name.
    :param what: how the line names its owner, e.g. ``"sensor 'front lidar'"``.
    :raises ValueError: ``<what>: topic <name> is not a valid ROS topic name: <reason>``.
    """
    problem = topic_name_problem(name)
    if problem:
        raise ValueError(f'{what}: topic {name!r} is not a valid ROS topic name: {problem}')
    return name
