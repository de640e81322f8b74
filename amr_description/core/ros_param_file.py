# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
ROS 2 parameter files (``--params-file`` YAML): which parameters apply to which node.

Format as rcl's parameter-file parser (jazzy)::

    /**:                      # wildcard: every node
      ros__parameters: {use_sim_time: true}
    controller_manager:       # relative name = root namespace
      ros__parameters:
        update_rate: 100
        diff_drive_controller:
          type: diff_drive_controller/DiffDriveController
    /robot1/diff_drive_controller:
      ros__parameters:
        linear: {x: {max_velocity: 1.0}}   # nested keys flatten to 'linear.x.max_velocity'

Node keys may nest (``ns: {node: {ros__parameters: ...}}``), may use ``*`` (one name token)
and ``/**`` (any number of namespace levels). Later matches override earlier ones; exact
names override wildcards of the same file. ``.nan`` in YAML is a float NaN.
"""

import re

from amr_description.core.yaml_text import safe_load
import yaml

ROS_PARAMS_KEY = 'ros__parameters'


def load_yaml(path):
    """
    Return the parsed YAML of a parameter file.

    :param path: file path.
    :returns: dict.
    :raises ValueError: one line naming the file when it cannot be read or is not a mapping.
    """
    try:
        with open(path, 'r') as f:
            data = safe_load(f)
    except OSError as exc:
        raise ValueError(f'cannot read parameter file {path}: {exc.strerror}') from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, 'problem_mark', None)
        where = f' line {mark.line + 1}' if mark is not None else ''
        problem = f' ({exc.problem})' if getattr(exc, 'problem', None) else ''
        raise ValueError(f'parameter file {path}{where}: invalid YAML{problem}') from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ValueError(f'parameter file {path}: expected a mapping of node names')
    return data


def _flatten(params, prefix=''):
    flat = {}
    for key, value in params.items():
        name = f'{prefix}{key}'
        if isinstance(value, dict):
            flat.update(_flatten(value, name + '.'))
        else:
            flat[name] = value
    return flat


def node_sections(data, path='parameter file'):
    """
    Return ``[(node_pattern, flat_params), ...]`` in file order.

    :param data: the parsed YAML (dict).
    :param path: file name for error messages.
    :returns: list of (str pattern with a leading '/', dict name -> value).
    :raises ValueError: naming the node key whose ``ros__parameters`` is not a mapping.
    """
    sections = []

    def walk(node, keys):
        if not isinstance(node, dict):
            return
        if ROS_PARAMS_KEY in node:
            params = node[ROS_PARAMS_KEY]
            pattern = '/' + '/'.join(k.strip('/') for k in keys if k.strip('/'))
            if params is None:
                params = {}
            if not isinstance(params, dict):
                raise ValueError(f'{path}: {pattern}: ros__parameters must be a mapping')
            sections.append((pattern, _flatten(params)))
        for key, value in node.items():
            if key != ROS_PARAMS_KEY and isinstance(value, dict):
                walk(value, keys + [str(key)])

    walk(data, [])
    return sections


def _pattern_regex(pattern):
    out = ''
    i = 0
    while i < len(pattern):
        if pattern.startswith('/**', i):
            out += '(/[^/]+)*'
            i += 3
        elif pattern[i] == '*':
            out += '[^/]*'
            i += 1
        else:
            out += re.escape(pattern[i])
            i += 1
    return re.compile(out + '$')


def fully_qualified(name, namespace=''):
    """Return ``/namespace/name`` ('' or '/' namespace gives ``/name``)."""
    namespace = namespace.strip('/')
    return f'/{namespace}/{name}' if namespace else f'/{name}'


def parameters_for_node(data, name, namespace='', path='parameter file'):
    """
    Return the flat parameters a node gets from one parsed parameter file.

    :param data: the parsed YAML (dict).
    :param name: node name.
    :param namespace: node namespace.
    :param path: file name for error messages.
    :returns: dict name -> value (wildcard sections first, exact ones override).
    """
    fqn = fully_qualified(name, namespace)
    wild, exact = {}, {}
    for pattern, params in node_sections(data, path):
        if pattern == fqn:
            exact.update(params)
        elif ('*' in pattern) and _pattern_regex(pattern).match(fqn):
            wild.update(params)
    wild.update(exact)
    return wild


def parse_params_file_value(value):
    """
    Return the list of paths in a ``<controller>.params_file`` parameter value.

    The upstream spawner (jazzy) sets it to ``str(list)`` (e.g. ``"['/a.yaml']"``); a plain
    path or a list of paths is also accepted.

    :param value: str or list of str.
    :returns: list of str (possibly empty).
    """
    if value is None:
        return []
    if isinstance(value, (list, tuple)):
        return [str(v) for v in value if str(v)]
    text = str(value).strip()
    if text.startswith('[') and text.endswith(']'):
        try:
            items = safe_load(text)
        except yaml.YAMLError:
            items = None
        if isinstance(items, list):
            return [str(v) for v in items if str(v)]
    return [text] if text else []
