# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Messages to YAML, CSV and ordered dicts, as ``ros2 topic echo`` prints them."""

import array
from collections import OrderedDict
import importlib
import sys

import numpy
import rosidl_parser.definition as idl
import yaml


# --------------------------------------------------------------------------- type names


def slot_items(msg):
    """Yield ``(field_name, rosidl slot type)`` in definition order."""
    return zip(msg.get_fields_and_field_types().keys(), msg.SLOT_TYPES)


def class_of(namespaced_type):
    """Import the class of a :class:`rosidl_parser.definition.NamespacedType`."""
    module = importlib.import_module('.'.join(namespaced_type.namespaces))
    return getattr(module, namespaced_type.name)


def _type_label(value_type):
    """Name of an element type as upstream prints it in ``--no-arr`` abbreviations."""
    if isinstance(value_type, idl.BasicType):
        return value_type.typename
    if isinstance(value_type, idl.AbstractString):
        return 'string'
    if isinstance(value_type, idl.AbstractWString):
        return 'wstring'
    if isinstance(value_type, idl.NamedType):
        return value_type.name
    if isinstance(value_type, idl.NamespacedType):
        return '/'.join(value_type.namespaced_name())
    return 'unknown'


def _abbreviate_sequence(value, field_type):
    """Upstream ``--no-arr`` text for an array or sequence field."""
    label = _type_label(field_type.value_type)
    if isinstance(field_type, idl.Array):
        return f'<array type: {label}[{field_type.size}]>'
    if isinstance(field_type, idl.BoundedSequence):
        return f'<sequence type: {label}[{field_type.maximum_size}], length: {len(value)}>'
    if isinstance(field_type, idl.UnboundedSequence):
        return f'<sequence type: {label}, length: {len(value)}>'
    return 'unknown'


# --------------------------------------------------------------------------- message -> YAML


def message_to_ordereddict(msg, *, truncate_length=None, no_arr=False, no_str=False):
    """
    Convert a message into an :class:`OrderedDict` of plain Python values, in field order.

    :param msg: a generated message instance.
    :param truncate_length: keep at most this many items/characters of every sequence,
        string and bytes value and append ``'...'`` (None: no truncation).
    :param no_arr: replace arrays and sequences by their upstream abbreviation.
    :param no_str: replace strings by ``<string length: <N>>``.
    :returns: nested OrderedDicts, lists, str, int, float and bool.
    """
    result = OrderedDict()
    for name, field_type in slot_items(msg):
        result[name] = _to_plain(
            getattr(msg, name), field_type, truncate_length, no_arr, no_str)
    return result


def _to_plain(value, field_type, truncate_length, no_arr, no_str):
    """Convert one field value as upstream's ``message_to_ordereddict`` does."""
    if isinstance(value, bytes):
        text = ''.join(chr(c) for c in value)
        if truncate_length is not None and len(value) > truncate_length:
            text = text[:truncate_length] + '...'
        return text
    if isinstance(value, str):
        if no_str:
            return f'<string length: <{len(value)}>>'
        if truncate_length is not None and len(value) > truncate_length:
            return value[:truncate_length] + '...'
        return value
    if isinstance(value, (list, tuple, array.array, numpy.ndarray)):
        if no_arr and field_type is not None:
            return _abbreviate_sequence(value, field_type)
        items = list(value)
        truncated = truncate_length is not None and len(items) > truncate_length
        if truncated:
            items = items[:truncate_length]
        items = [_to_plain(v, None, truncate_length, no_arr, no_str) for v in items]
        return items + ['...'] if truncated else items
    if isinstance(value, numpy.generic):
        return value.item()
    if isinstance(value, (bool, int, float)):
        return value
    if isinstance(value, dict):
        return OrderedDict(
            (k, _to_plain(v, None, truncate_length, no_arr, no_str)) for k, v in value.items())
    return message_to_ordereddict(
        value, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)


class _EchoDumper(yaml.SafeDumper):
    """SafeDumper that writes OrderedDicts as plain mappings, keeping their order."""


def _represent_ordereddict(dumper, data):
    return dumper.represent_mapping('tag:yaml.org,2002:map', data.items(), flow_style=None)


_EchoDumper.add_representer(OrderedDict, _represent_ordereddict)


def to_yaml(data, flow_style=False):
    """
    Dump plain data (as made by :func:`message_to_ordereddict`) like ``ros2 topic echo``.

    :param data: OrderedDicts, lists and scalars.
    :param flow_style: True for one-line flow style (``--flow-style``).
    :returns: the YAML text, ending with a newline.
    """
    return yaml.dump(
        data, Dumper=_EchoDumper, allow_unicode=True, width=sys.maxsize,
        default_flow_style=flow_style, sort_keys=False)


def message_to_yaml(msg, *, truncate_length=None, no_arr=False, no_str=False,
                    flow_style=False):
    """
    Return the YAML text ``ros2 topic echo`` prints for ``msg`` (without the ``---``).

    :param msg: a generated message instance.
    :param truncate_length: see :func:`message_to_ordereddict`.
    :param no_arr: see :func:`message_to_ordereddict`.
    :param no_str: see :func:`message_to_ordereddict`.
    :param flow_style: True for one-line flow style.
    :returns: the YAML text, ending with a newline.
    """
    return to_yaml(
        message_to_ordereddict(
            msg, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str),
        flow_style=flow_style)


def message_to_csv(msg, *, truncate_length=None, no_arr=False, no_str=False):
    """
    Return the one CSV line ``ros2 topic echo --csv`` prints for ``msg`` (no newline).

    As upstream rosidl_runtime_py (jazzy): the values of every field, depth-first in field
    order, joined by commas, with no quoting; a sequence contributes its items (after
    ``truncate_length`` items a single ``...``), or its ``--no-arr`` abbreviation; strings and
    bytes longer than ``truncate_length`` are cut and get ``...``; ``no_str`` writes
    ``<string length: <N>>``; numbers and booleans as Python's ``str``.

    :param msg: a generated message instance.
    :param truncate_length: see :func:`message_to_ordereddict`.
    :param no_arr: abbreviate arrays and sequences.
    :param no_str: abbreviate strings.
    :returns: the CSV text.
    """
    def to_string(value, field_type=None):
        if isinstance(value, (list, tuple, array.array, numpy.ndarray)):
            if no_arr and field_type is not None:
                return _abbreviate_sequence(value, field_type)
            parts = []
            for index, item in enumerate(value):
                if truncate_length is not None and index >= truncate_length:
                    parts.append('...')
                    break
                parts.append(to_string(item))
            return ','.join(parts)
        if isinstance(value, (bool, bytes, float, int, str, numpy.number, numpy.bool_)):
            if no_str and isinstance(value, str):
                return f'<string length: <{len(value)}>>'
            if isinstance(value, (bytes, str)) and truncate_length is not None \
                    and len(value) > truncate_length:
                value = value[:truncate_length] + (b'...' if isinstance(value, bytes) else '...')
            return str(value)
        return message_to_csv(
            value, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)

    return ','.join(to_string(getattr(msg, name), field_type)
                    for name, field_type in slot_items(msg))


# --------------------------------------------------------------------------- YAML -> message
