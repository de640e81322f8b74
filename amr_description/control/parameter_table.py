# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A controller's parameters, written once: name, default, description, check.

As upstream controllers describe theirs once in a generate_parameter_library YAML (name,
type from the default, description, validation), a :class:`ParameterTable` is declared on the
controller node (:meth:`ParameterTable.declare`, in ``on_init``) and read, validated, into a
frozen object (:meth:`ParameterTable.read`, in ``on_configure``). No rclpy here: the node is
only asked for ``auto_declare(name, default, description)`` and ``param(name)``.
"""

from dataclasses import make_dataclass
from typing import Any
from typing import Callable
from typing import NamedTuple


class Parameter(NamedTuple):
    """
    One parameter of a table.

    :param name: the ROS parameter name (``linear.x.max_velocity``).
    :param default: its default; its type is the parameter's type.
    :param description: the descriptor's text (``ros2 param describe``).
    :param check: ``(value) -> None or the rule it breaks`` (``'must be > 0, got -1.0'``),
        or None.
    """

    name: str
    default: Any
    description: str = ''
    check: Callable = None


def positive(value):
    """Return the rule a value <= 0 (or NaN) breaks, else None."""
    return None if value > 0.0 else f'must be > 0, got {value}'


def not_negative(value):
    """Return the rule a negative (or NaN) value breaks, else None."""
    return None if value >= 0.0 else f'must be >= 0, got {value}'


def at_least_one(value):
    """Return the rule a whole number < 1 breaks, else None."""
    return None if value >= 1 else f'must be >= 1, got {value}'


def size(count):
    """Return a check that an array has ``count`` elements."""
    def check(values):
        return None if len(values) == count else \
            f'must have {count} elements, got {len(values)}'
    return check


def not_empty(values):
    """Return the rule a list without a non-empty string breaks, else None."""
    return None if any(values) else 'is empty: wheel names are required'


def attribute(name):
    """Return the attribute name of parameter ``name`` in the read object (``.`` -> ``_``)."""
    return name.replace('.', '_')


class ParameterTable:
    """
    The parameters of one controller type.

    :param class_name: name of the frozen class :meth:`read` returns.
    :param parameters: the :class:`Parameter` entries, in declaration order.
    """

    def __init__(self, class_name, parameters):
        """Make the frozen class with one field per parameter."""
        self.parameters = tuple(parameters)
        self.values_type = make_dataclass(
            class_name, [(attribute(p.name), type(p.default)) for p in self.parameters],
            frozen=True)

    def declare(self, controller):
        """Declare every parameter on ``controller`` (``auto_declare``) with its default."""
        for p in self.parameters:
            controller.auto_declare(p.name, p.default, p.description)

    def read(self, controller):
        """
        Return the parameters' values as a frozen object, after checking each.

        :param controller: the node (``param(name, default)``).
        :raises ValueError: ``parameter 'NAME' RULE, got VALUE`` for the first broken rule.
        """
        values = {}
        for p in self.parameters:
            value = controller.param(p.name, p.default)
            problem = p.check(value) if p.check is not None else None
            if problem is not None:
                raise ValueError(f"parameter '{p.name}' {problem}")
            values[attribute(p.name)] = value
        return self.values_type(**values)
