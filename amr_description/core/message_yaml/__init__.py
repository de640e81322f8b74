# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
ROS interface classes from type names, and ROS messages to/from YAML (no rclpy).

This is our stand-in for the parts of ``rosidl_runtime_py`` (not on PyPI) that ``ros2 topic
echo``/``pub`` and ``ros2 service call`` need. Reproduced upstream behaviour (jazzy):

* :func:`message_to_yaml` prints what ``ros2 topic echo`` prints: a block-style YAML mapping in
  field order, ``width`` unlimited, sequences and numpy arrays as lists, ``bytes`` as
  characters, float specials as ``.nan``/``.inf``/``-.inf``, truncation to
  ``truncate_length`` items/characters followed by ``'...'``, ``no_arr`` replacing every array
  or sequence by ``<array type: T[N]>``, ``<sequence type: T[M], length: N>`` or
  ``<sequence type: T, length: N>``, ``no_str`` replacing strings by ``<string length: <N>>``.
* :func:`set_message_fields` fills a message from a dict: an unknown field raises
  ``AttributeError("'Type' object has no attribute 'name'")`` as upstream; a ``std_msgs/Header``
  given as ``'auto'`` and a ``builtin_interfaces/Time`` given as ``'now'`` are expanded through
  setter hooks (``ros2 topic pub`` semantics).

Unlike upstream, values are type- and range-checked here (the generated setters only check
when ``ROS_PYTHON_CHECK_FIELDS=1``): a wrong value raises ``TypeError``/``ValueError`` with a
one-line message naming the field path, never a silently truncated or coerced value.

Modules, as rosidl_runtime_py's: :mod:`.utilities` (interface classes from type names),
:mod:`.convert` (messages to YAML, CSV, ordered dicts), :mod:`.set_message` (messages from
YAML values).
"""
