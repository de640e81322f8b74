# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Typed parameters read at configure: a wrong type is one line, never a crash at start-up.

A node built with ``automatically_declare_parameters_from_overrides=True`` holds every
parameter of its params file, whatever its type. :func:`read_parameters` declares the ones
the file left out with the node's defaults and checks the others against the default's
type, as rclcpp's ``declare_parameter`` would refuse them (``InvalidParameterTypeException``)
but with one line naming the parameter, what was expected and what was found.
"""

_TYPE_NAMES = {bool: 'a bool', int: 'an integer', float: 'a double', str: 'a string',
               list: 'an array'}


def _check(name, value, default):
    if isinstance(default, bool):
        ok = isinstance(value, bool)
    elif isinstance(default, int):
        ok = isinstance(value, int) and not isinstance(value, bool)
    elif isinstance(default, float):
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        value = float(value) if ok else value
    elif isinstance(default, str):
        ok = isinstance(value, str)
    else:
        ok = isinstance(value, (list, tuple)) or hasattr(value, 'tolist')
        value = list(value) if ok else value
    if not ok:
        expected = _TYPE_NAMES.get(type(default), type(default).__name__)
        raise ValueError(f"parameter '{name}': expected {expected}, got "
                         f'{type(value).__name__} {value!r}')
    return value


def checked_value(name, value, default):
    """
    Return ``value`` of parameter ``name`` checked against its default's type.

    :raises ValueError: one line naming the parameter, what was expected and what was found
        (for a parameter set at run time, e.g. ``ros2 param set``).
    """
    return _check(name, value, default)


def read_parameters(node, defaults):
    """
    Return ``{name: value}`` for every name of ``defaults``, declaring missing ones.

    :param node: an rclpy node (``automatically_declare_parameters_from_overrides=True``).
    :param defaults: ``{name: default}``; the default's Python type is the expected type
        (an int is accepted for a float).
    :raises ValueError: one line naming the first parameter of the wrong type.
    """
    values = {}
    for name, default in defaults.items():
        if node.has_parameter(name):
            values[name] = _check(name, node.get_parameter(name).value, default)
        else:
            values[name] = node.declare_parameter(name, default).value
    return values


def unused_parameters(node, known):
    """
    Return the sorted names of the node's parameters that ``known`` does not list.

    rclpy's own (``use_sim_time``, ``start_type_description_service``) and Nav2's
    ``bond_heartbeat_period`` are left out.
    """
    skip = {'use_sim_time', 'bond_heartbeat_period', 'start_type_description_service'}
    names = node.list_parameters([], 0).names
    return sorted(name for name in names if name not in known and name not in skip)


def unused_overrides(node):
    """
    Return the sorted names a params file gave the node that it never declared.

    For a node built without ``automatically_declare_parameters_from_overrides``: rclpy keeps
    every value of its params files (``Node._parameter_overrides``) and silently drops those
    the node does not declare. The names :func:`unused_parameters` leaves out are left out.

    :param node: an rclpy node, after it declared what it reads.
    """
    skip = {'use_sim_time', 'bond_heartbeat_period', 'start_type_description_service'}
    overrides = getattr(node, '_parameter_overrides', None) or {}
    return sorted(name for name in overrides
                  if name not in skip and not node.has_parameter(name))
