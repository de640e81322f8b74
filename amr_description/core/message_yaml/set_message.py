# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Messages from YAML values, as ``ros2 topic pub`` and ``ros2 service call`` fill them."""

import functools
import math

from amr_description.core.message_yaml.convert import class_of
from amr_description.core.message_yaml.convert import slot_items
from amr_description.core.message_yaml.utilities import type_name_of
from amr_description.core.yaml_text import safe_load
import rosidl_parser.definition as idl
import yaml

_INT_RANGES = {
    'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
    'char': (0, 255), 'octet': (0, 255),
}
_FLOAT32_MAX = 3.4028234663852886e+38
_FLOAT_TYPES = ('float', 'double', 'long double')


# --------------------------------------------------------------------------- type names


def parse_yaml_values(text):
    """
    Parse the YAML values argument of ``ros2 topic pub`` / ``ros2 service call``.

    :param text: YAML text of a mapping (an empty text means ``{}``).
    :returns: the dict.
    :raises ValueError: on invalid YAML (one-line message with line and column) or when the
        text is not a mapping (upstream wording).
    """
    if text is None or not str(text).strip():
        return {}
    try:
        values = safe_load(text, aliases=True)  # as ros2cli's yaml.safe_load, depth-bounded
    except yaml.YAMLError as exc:
        problem = getattr(exc, 'problem', None) or str(exc).splitlines()[0]
        mark = getattr(exc, 'problem_mark', None)
        where = f' (line {mark.line + 1}, column {mark.column + 1})' if mark else ''
        raise ValueError(f'Invalid YAML in the passed value: {problem}{where}') from None
    if not isinstance(values, dict):
        raise ValueError('The passed value needs to be a dictionary in YAML format')
    return values


def set_message_fields(msg, values, expand_header_auto=False, expand_time_now=False):
    """
    Set the fields of ``msg`` from ``values`` (a dict, possibly nested), checking types.

    :param msg: the message instance to fill (modified in place).
    :param values: dict of field name -> value; nested messages as dicts, sequences as lists,
        ``builtin_interfaces`` Time/Duration also as a number of seconds.
    :param expand_header_auto: accept ``'auto'`` for a ``std_msgs/msg/Header`` field: an empty
        header whose ``stamp`` is set by a returned setter.
    :param expand_time_now: accept ``'now'`` for a ``builtin_interfaces/msg/Time`` field, set
        by a returned setter.
    :returns: list of setters ``f(time_msg)`` to call with the current time before publishing
        (empty when nothing was expanded).
    :raises AttributeError: for an unknown field, worded as upstream
        (``'Twist' object has no attribute 'foo'``).
    :raises TypeError: for a value of the wrong type (the message names the field path).
    :raises ValueError: for a value out of range or a sequence of the wrong length.
    """
    setters = []
    _fill(msg, values, '', setters, expand_header_auto, expand_time_now)
    return setters


def _fill(msg, values, path, setters, header_auto, time_now):
    if not isinstance(values, dict):
        where = f"The '{path}' field" if path else 'The message'
        raise TypeError(
            f'{where} ({type_name_of(msg)}) must be given as a dictionary, '
            f'got {_describe(values)}')
    slots = dict(slot_items(msg))
    for name, value in values.items():
        if name not in slots:
            raise AttributeError(f"'{type(msg).__name__}' object has no attribute '{name}'")
        field_path = f'{path}.{name}' if path else name
        field_type = slots[name]
        if isinstance(field_type, idl.NamespacedType) and isinstance(value, str):
            full = '/'.join(field_type.namespaced_name())
            if header_auto and full == 'std_msgs/msg/Header' and value == 'auto':
                header = class_of(field_type)()
                setattr(msg, name, header)
                setters.append(functools.partial(setattr, header, 'stamp'))
                continue
            if time_now and full == 'builtin_interfaces/msg/Time' and value == 'now':
                setters.append(functools.partial(setattr, msg, name))
                continue
        converted = _convert(value, field_type, field_path, setters, header_auto, time_now)
        setattr(msg, name, converted)


def _describe(value):
    return f'{type(value).__name__} {value!r}'


def _convert(value, field_type, path, setters, header_auto, time_now):
    """Return ``value`` converted for a field of rosidl type ``field_type``, or raise."""
    if isinstance(field_type, idl.AbstractNestedType):
        return _convert_sequence(value, field_type, path, setters, header_auto, time_now)
    if isinstance(field_type, idl.NamespacedType):
        cls = class_of(field_type)
        if isinstance(value, cls):
            return value
        sub = cls()
        full = '/'.join(field_type.namespaced_name())
        if (full in ('builtin_interfaces/msg/Time', 'builtin_interfaces/msg/Duration')
                and isinstance(value, (int, float)) and not isinstance(value, bool)):
            return _seconds_to_time(value, sub, path)
        if not isinstance(value, dict):
            raise TypeError(
                f"The '{path}' field must be a dictionary of {full} fields, "
                f'got {_describe(value)}')
        _fill(sub, value, path, setters, header_auto, time_now)
        return sub
    if isinstance(field_type, (idl.AbstractString, idl.AbstractWString)):
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            value = str(value)
        if not isinstance(value, str):
            raise TypeError(f"The '{path}' field must be of type 'str', got {_describe(value)}")
        limit = getattr(field_type, 'maximum_size', None)
        if limit is not None and len(value) > limit:
            raise ValueError(
                f"The '{path}' field must be a string of at most {limit} characters, "
                f'got {len(value)}')
        return value
    if isinstance(field_type, idl.BasicType):
        return _convert_basic(value, field_type.typename, path)
    raise TypeError(f"The '{path}' field has an unsupported type")


def _seconds_to_time(seconds, sub, path):
    if not math.isfinite(seconds):
        raise ValueError(f"The '{path}' field must be a finite number of seconds")
    total_ns = int(round(seconds * 1e9))
    sec, nanosec = divmod(total_ns, 10 ** 9)
    if not -2 ** 31 <= sec < 2 ** 31:
        raise ValueError(f"The '{path}' field is out of range: {seconds} s")
    sub.sec = sec
    sub.nanosec = nanosec
    return sub


def _convert_basic(value, typename, path):
    if typename == 'boolean':
        if not isinstance(value, bool):
            raise TypeError(f"The '{path}' field must be of type 'bool', got {_describe(value)}")
        return value
    if typename in _FLOAT_TYPES:
        if isinstance(value, str):
            # PyYAML (YAML 1.1) reads 1e-3 and nan as strings; float() reads them as upstream
            try:
                value = float(value)
            except ValueError:
                pass
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError(
                f"The '{path}' field must be of type 'float', got {_describe(value)}")
        value = float(value)
        if typename == 'float' and math.isfinite(value) and abs(value) > _FLOAT32_MAX:
            raise ValueError(
                f"The '{path}' field must be a float in "
                f'[{-_FLOAT32_MAX}, {_FLOAT32_MAX}], got {value}')
        return value
    if typename == 'octet' and isinstance(value, bytes):
        if len(value) != 1:
            raise ValueError(f"The '{path}' field must be a single byte, got {value!r}")
        return value
    if typename in _INT_RANGES:
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"The '{path}' field must be of type 'int', got {_describe(value)}")
        low, high = _INT_RANGES[typename]
        if not low <= value <= high:
            raise ValueError(
                f"The '{path}' field must be an integer in [{low}, {high}], got {value}")
        return bytes([value]) if typename == 'octet' else value
    raise TypeError(f"The '{path}' field has an unsupported type '{typename}'")


def _convert_sequence(value, field_type, path, setters, header_auto, time_now):
    element_type = field_type.value_type
    is_bytes_like = (isinstance(element_type, idl.BasicType)
                     and element_type.typename in ('octet', 'uint8'))
    if isinstance(value, (bytes, bytearray)) and is_bytes_like:
        value = list(value)
    if isinstance(value, (str, bytes, dict)) or not hasattr(value, '__iter__'):
        raise TypeError(
            f"The '{path}' field must be a sequence (a YAML list), got {_describe(value)}")
    value = list(value)
    if isinstance(field_type, idl.Array) and len(value) != field_type.size:
        raise ValueError(
            f"The '{path}' field must be a sequence of exactly {field_type.size} elements, "
            f'got {len(value)}')
    if isinstance(field_type, idl.BoundedSequence) and len(value) > field_type.maximum_size:
        raise ValueError(
            f"The '{path}' field must be a sequence of at most {field_type.maximum_size} "
            f'elements, got {len(value)}')
    return [
        _convert(item, element_type, f'{path}[{index}]', setters, header_auto, time_now)
        for index, item in enumerate(value)]


def message_from_values(msg_class, values, expand_header_auto=False, expand_time_now=False):
    """
    Create a ``msg_class`` instance filled from ``values`` (see :func:`set_message_fields`).

    :param msg_class: the generated message class.
    :param values: dict of field values, or YAML text of one.
    :param expand_header_auto: see :func:`set_message_fields`.
    :param expand_time_now: see :func:`set_message_fields`.
    :returns: ``(message, setters)``.
    :raises ValueError: on invalid YAML or values (see :func:`parse_yaml_values`).
    :raises TypeError: on a value of the wrong type.
    :raises AttributeError: on an unknown field.
    """
    if values is None or isinstance(values, str):
        values = parse_yaml_values(values)
    msg = msg_class()
    setters = set_message_fields(msg, values, expand_header_auto, expand_time_now)
    return msg, setters
