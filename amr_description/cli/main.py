# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Entry point of the ``ros2`` command subset: ``ros2 <command> <verb> [options]``.

Commands and verbs plug in as ros2cli's do (:mod:`amr_description.cli.extension`): a
:class:`~amr_description.cli.extension.Command` registered in the entry-point group
``amr_description.command`` and its :class:`~amr_description.cli.extension.Verb` s in
``amr_description.<command>.verb``; every verb parser gets ``main=callable(args) -> int``.
"""

import argparse
import contextlib
import os
import sys

from amr_description.cli.extension import add_commands


def build_parser():
    """
    Build the top-level ``ros2`` argument parser with every available command.

    :returns: the :class:`argparse.ArgumentParser`.
    """
    parser = argparse.ArgumentParser(
        prog='ros2', description='ros2 is an extensible command-line tool for ROS 2.',
        formatter_class=argparse.RawDescriptionHelpFormatter)
    subparsers = parser.add_subparsers(
        title='Commands', dest='command',
        metavar='Call `ros2 <command> -h` for more detailed usage.')
    add_commands(subparsers)
    return parser


OFF_THE_GRAPH = ('doctor', 'interface', 'pkg', 'wtf')
"""Commands that never join a ROS domain; every other one checks ``ROS_DOMAIN_ID`` first."""


def main(argv=None):
    """
    Run ``ros2`` with ``argv`` (default ``sys.argv[1:]``).

    :param argv: command-line arguments without the program name.
    :returns: the process exit code (0 on success, 1 on a reported error).
    """
    from amr_description.cli.common import CliError
    from amr_description.cli.common import fail
    # print line by line even into a pipe (tests, `| grep`), as a terminal would
    with contextlib.suppress(AttributeError, ValueError):
        sys.stdout.reconfigure(line_buffering=True)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    parser = build_parser()
    args = parser.parse_args(argv)
    func = getattr(args, 'main', None)
    if func is None:
        # a command without a verb prints its own help, as ros2cli does
        sub = getattr(args, '_command_parser', parser)
        sub.print_help()
        return 0 if args.command is None else 1
    if args.command not in OFF_THE_GRAPH:
        from amr_description.cli.daemon import domain_id
        try:
            domain_id()
        except ValueError as exc:
            return fail(str(exc))
    try:
        return int(func(args) or 0)
    except CliError as exc:
        return fail(str(exc))
    except BrokenPipeError:
        # the reader went away (`ros2 pkg list | head`): stop quietly, as a shell tool does
        with contextlib.suppress(OSError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except KeyboardInterrupt:
        return 0


if __name__ == '__main__':
    sys.exit(main())
