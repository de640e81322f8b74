# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Helpers shared by the ``ros2`` verbs: a short-lived node, errors in upstream style."""

import contextlib
import sys


class CliError(Exception):
    """A user error; the message is printed on one line to stderr and the verb exits 1."""


def fail(message):
    """Print ``message`` to stderr on one line and return exit code 1.

    :param message: the error text, without a trailing newline.
    :returns: 1
    """
    print(message, file=sys.stderr)
    return 1


@contextlib.contextmanager
def cli_node(name='_ros2cli', args=None):
    """Create rclpy context + node for one CLI call and tear both down afterwards.

    :param name: node name (ros2cli uses a hidden name starting with ``_``).
    :param args: extra rcl arguments, e.g. ``['--ros-args', '-p', 'use_sim_time:=true']``.
    :returns: a context manager yielding an :class:`rclpy.node.Node`.
    """
    import rclpy
    from rclpy.context import Context

    context = Context()
    rclpy.init(args=args, context=context)
    node = rclpy.create_node(name, context=context, start_parameter_services=False)
    try:
        yield node
    finally:
        node.destroy_node()
        with contextlib.suppress(Exception):
            rclpy.shutdown(context=context)
