# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""controllers.yaml (ros2_control format): reading it and finding a node's parameters."""

from amr_description.core.model_check.findings import DIFF_DRIVE_TYPE
from amr_description.core.yaml_text import safe_load
import yaml


def node_parameters(controllers, name):
    """
    Return the ``ros__parameters`` of node ``name`` in a parameter file, or None.

    The section may be keyed by the plain name, the root-namespace name (``/name``) or the
    any-namespace wildcard (``/**/name``, what namespaced robots need, as upstream).

    :param controllers: the parsed YAML (dict).
    :param name: node name without namespace.
    """
    for key in (name, '/' + name, '/**/' + name):
        section = controllers.get(key)
        if isinstance(section, dict):
            return section.get('ros__parameters')
    return None


def diff_drive_params(controllers):
    """
    Return the ros__parameters of every diff_drive_controller in a controllers.yaml.

    :param controllers: the parsed YAML (dict), ros2_control format.
    :returns: dict controller name -> its ``ros__parameters`` dict (empty when absent).
    """
    cm = node_parameters(controllers, 'controller_manager') or {}
    result = {}
    for name, value in cm.items():
        if isinstance(value, dict) and value.get('type') == DIFF_DRIVE_TYPE:
            result[name] = dict(node_parameters(controllers, name) or {})
    return result


def load_controllers(path):
    """
    Read a controllers.yaml.

    :returns: the parsed dict.
    :raises ValueError: one line naming ``path`` when unreadable or not a YAML mapping.
    """
    try:
        with open(path) as f:
            data = safe_load(f)
    except OSError as exc:
        raise ValueError(f'{path}: cannot read: {exc.strerror}') from None
    except yaml.YAMLError as exc:
        raise ValueError(f'{path}: invalid YAML: {" ".join(str(exc).split())}') from None
    if not isinstance(data, dict):
        raise ValueError(f'{path}: expected a YAML mapping of controller sections')
    return data
