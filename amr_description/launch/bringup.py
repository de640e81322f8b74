# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 run amr_description bringup STACK [name:=value ...]``: run a stack in the foreground.

Like ``ros2 launch``: ``-s``/``--show-args`` lists the stack's launch arguments, Ctrl-C shuts
the stack down (SIGINT, then SIGTERM after 5 s, then SIGKILL after 5 s more).
"""

import argparse
import sys

from amr_description.launch.actions import format_arguments
from amr_description.launch.actions import LaunchError
from amr_description.launch.orchestrator import Orchestrator
from amr_description.launch.registry import describe
from amr_description.launch.registry import stack_name
from amr_description.launch.registry import STACKS


def add_arguments(parser):
    """
    Add the stack name, its ``name:=value`` arguments and ``--show-args`` to ``parser``.

    :param parser: an :class:`argparse.ArgumentParser`.
    """
    parser.add_argument(
        'stack', help=f"stack to run: {', '.join(sorted(STACKS))} (or '<stack>.launch.py')")
    parser.add_argument(
        'launch_arguments', nargs='*', metavar='name:=value',
        help="arguments of the stack, as '<name>:=<value>'")
    parser.add_argument(
        '-s', '--show-args', '--show-arguments', action='store_true',
        help='show the arguments of the stack and exit')


def run(stack, launch_arguments, show_args=False, out=None):
    """
    Run (or describe) a stack; errors are printed on one line.

    :param stack: stack name (``sim``, ``sim.launch.py``, ...).
    :param launch_arguments: list of ``'name:=value'``.
    :param show_args: print the declared arguments instead of running.
    :param out: stream for output (default ``sys.stdout``).
    :returns: exit code (0 ok, 1 on a user error or a process that could not start).
    """
    out = out or sys.stdout
    try:
        name = stack_name(stack)
        if show_args:
            out.write(format_arguments(STACKS[name][1]))
            return 0
        actions = describe(name, launch_arguments)
    except LaunchError as exc:
        print(exc, file=sys.stderr)
        return 1
    return Orchestrator(actions, stream=out).run()


def main(argv=None):
    """
    Entry point of the ``bringup`` executable.

    :param argv: arguments without the program name (default ``sys.argv[1:]``, ROS arguments
        after ``--ros-args`` are ignored).
    :returns: the exit code (also passed to ``sys.exit`` by the console script).
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    if '--ros-args' in argv:
        argv = argv[:argv.index('--ros-args')]
    parser = argparse.ArgumentParser(
        prog='bringup', description='Run a stack of ROS processes (replaces ros2 launch).')
    add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return run(args.stack, args.launch_arguments, args.show_args)
    except KeyboardInterrupt:
        return 0


if __name__ == '__main__':
    sys.exit(main())
