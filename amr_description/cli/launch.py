# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 launch PACKAGE STACK [name:=value ...]``: run one of the package's stacks.

Stands in for ros2launch: the "launch files" are the Python stack descriptions in
:mod:`amr_description.launch.registry` (``sim`` or ``sim.launch.py``, ``display``).
"""

from amr_description.cli.common import fail
from amr_description.cli.extension import Command


def _main(args):
    from amr_description.launch.bringup import run
    from amr_description.launch.stacks import PACKAGE
    if args.package_name != PACKAGE:
        return fail(f"Package '{args.package_name}' not found (stacks are provided by "
                    f"'{PACKAGE}' only)")
    return run(args.launch_file_name, args.launch_arguments, args.show_args)


def _arguments(parser):
    """Add the arguments of ``ros2 launch``."""
    parser.add_argument('package_name', help='Name of the ROS package which contains the stack')
    parser.add_argument('launch_file_name',
                        help="Name of the stack, e.g. 'sim' or 'sim.launch.py'")
    parser.add_argument('launch_arguments', nargs='*', metavar='name:=value',
                        help="Arguments to the launch file; '<name>:=<value>' (for duplicates, "
                             'last one wins)')
    parser.add_argument('-s', '--show-args', '--show-arguments', action='store_true',
                        help='Show arguments that may be given to the launch file.')


COMMAND = Command('Run a launch file', _arguments, _main,
                  description='Run a stack (launch file) of a package.')
"""``ros2 launch``."""
