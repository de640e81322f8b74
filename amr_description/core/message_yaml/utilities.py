# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""ROS interface classes from type names (``rosidl_runtime_py.utilities``)."""

import importlib
import importlib.util


#: The interface kinds accepted in a type name ``pkg/<kind>/Type``.
INTERFACE_KINDS = ('msg', 'srv', 'action')


# --------------------------------------------------------------------------- type names


def split_type_name(identifier, default_kind='msg'):
    """
    Split ``pkg/kind/Type`` (or ``pkg/Type``, meaning ``default_kind``) into its parts.

    :param identifier: the interface type name, e.g. ``'geometry_msgs/msg/Twist'``.
    :param default_kind: the kind assumed for a two-part name.
    :returns: ``(package, kind, name)``.
    :raises ValueError: when the name does not have that shape.
    """
    parts = str(identifier).split('/')
    if len(parts) == 2:
        parts.insert(1, default_kind)
    if len(parts) != 3 or not all(parts) or parts[1] not in INTERFACE_KINDS:
        raise ValueError(
            f"Invalid interface type '{identifier}': expected 'package/msg/Type' "
            "(or 'package/srv/Type', 'package/action/Type', 'package/Type')")
    return tuple(parts)


def get_interface(identifier, default_kind='msg'):
    """
    Import and return the Python class of an interface type.

    :param identifier: ``'pkg/msg/Type'``, ``'pkg/srv/Type'``, ``'pkg/action/Type'`` or
        ``'pkg/Type'`` (kind ``default_kind``).
    :param default_kind: the kind assumed for a two-part name.
    :returns: the generated class (e.g. ``geometry_msgs.msg.Twist``).
    :raises ValueError: on a malformed name or when no such interface is installed.
    """
    package, kind, name = split_type_name(identifier, default_kind)
    try:
        module = importlib.import_module(f'{package}.{kind}')
    except ImportError:
        installed = importlib.util.find_spec(package) is not None
        raise ValueError(f"Unknown interface type '{package}/{kind}/{name}': " + (
            f"package '{package}' has no {kind} interfaces" if installed else
            f"package '{package}' is not installed")) from None
    cls = getattr(module, name, None)
    if cls is None:
        raise ValueError(f"Unknown interface type '{package}/{kind}/{name}': package "
                         f"'{package}' has no {kind} '{name}'")
    if not isinstance(cls, type):
        raise ValueError(f"Unknown interface type '{package}/{kind}/{name}'")
    return cls


def get_message(identifier):
    """
    Return the message class named ``'pkg/msg/Type'`` or ``'pkg/Type'``.

    :param identifier: the message type name.
    :returns: the generated message class.
    :raises ValueError: on a malformed name, a non-message kind, or an unknown type.
    """
    if split_type_name(identifier)[1] != 'msg':
        raise ValueError(f"'{identifier}' is not a message type")
    return get_interface(identifier, 'msg')


def get_service(identifier):
    """
    Return the service class named ``'pkg/srv/Type'`` or ``'pkg/Type'``.

    :param identifier: the service type name.
    :returns: the generated service class (with ``Request`` and ``Response``).
    :raises ValueError: on a malformed name, a non-service kind, or an unknown type.
    """
    if split_type_name(identifier, 'srv')[1] != 'srv':
        raise ValueError(f"'{identifier}' is not a service type")
    cls = get_interface(identifier, 'srv')
    if not hasattr(cls, 'Request'):
        raise ValueError(f"'{identifier}' is not a service type")
    return cls


def get_action(identifier):
    """
    Return the action class named ``'pkg/action/Type'``.

    :param identifier: the action type name.
    :returns: the generated action class (with ``Goal``, ``Result`` and ``Feedback``).
    :raises ValueError: on a malformed name, a non-action kind, or an unknown type.
    """
    if split_type_name(identifier, 'action')[1] != 'action':
        raise ValueError(f"'{identifier}' is not an action type")
    cls = get_interface(identifier, 'action')
    if not hasattr(cls, 'Goal'):
        raise ValueError(f"'{identifier}' is not an action type")
    return cls


def type_name_of(msg_or_class):
    """
    Return the ``pkg/msg/Type`` name of a message instance or class.

    :param msg_or_class: a generated message (or service) instance or class.
    :returns: e.g. ``'std_msgs/msg/String'``.
    """
    cls = msg_or_class if isinstance(msg_or_class, type) else type(msg_or_class)
    parts = cls.__module__.split('.')
    return f'{parts[0]}/{parts[1]}/{cls.__name__}'
