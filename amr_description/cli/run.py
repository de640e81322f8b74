# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 run PKG EXE [args] [--ros-args ...]``: run a package executable (as ros2run).

The executable is ``<prefix>/lib/PKG/EXE`` of the package's prefix in the ament index. It
runs as a child in the same process group, so a terminal Ctrl-C reaches it directly; SIGTERM
to ``ros2`` is passed on. The exit code is the child's; a failure or a signal is reported as
``[ros2run] ...`` like upstream.
"""

import argparse
import os
import signal
import subprocess

from amr_description.cli.common import fail
from amr_description.cli.pkg import executable_paths
from amr_description.cli.pkg import package_prefixes


def find_executable(package, executable):
    """
    Return the path of ``executable`` of ``package``.

    :param package: package name.
    :param executable: executable file name.
    :returns: the absolute path, or None when the package has no such executable.
    :raises LookupError: ``Package 'p' not found``; or several executables of that name.
    """
    prefix = package_prefixes().get(package)
    if prefix is None:
        raise LookupError(f"Package '{package}' not found")
    paths = [p for p in executable_paths(package, prefix) if os.path.basename(p) == executable]
    if len(paths) > 1:
        raise LookupError('Multiple executables found: ' + ', '.join(paths))
    return paths[0] if paths else None


def _main(args):
    try:
        path = find_executable(args.package_name, args.executable_name)
    except LookupError as exc:
        return fail(str(exc))
    if path is None:
        return fail('No executable found')
    cmd = ([*args.prefix.split()] if args.prefix else []) + [path, *args.argv]
    child = subprocess.Popen(cmd)
    signal.signal(signal.SIGTERM, lambda signum, frame: child.send_signal(signal.SIGTERM))
    while True:
        try:
            child.wait()
            break
        except KeyboardInterrupt:
            # the child got the same Ctrl-C (same process group): wait for it to finish
            continue
    code = child.returncode
    if code < 0:
        print('[ros2run]', signal.strsignal(-code))
    elif code != 0:
        print('[ros2run]', f'Process exited with failure {code}')
    return code if code >= 0 else 128 - code


def add_command(subparsers):
    """
    Add the ``run`` command to the ``ros2`` parser.

    :param subparsers: the top-level ``add_subparsers()`` object.
    """
    parser = subparsers.add_parser('run', help='Run a package specific executable')
    parser.add_argument('--prefix', help='Prefix command, which should go before the '
                        'executable. Command must be wrapped in quotes if it contains spaces '
                        "(e.g. --prefix 'gdb -ex run --args').")
    parser.add_argument('package_name', help='Name of the ROS package')
    parser.add_argument('executable_name', help='Name of the executable')
    parser.add_argument('argv', nargs=argparse.REMAINDER,
                        help='Pass arbitrary arguments to the executable')
    parser.set_defaults(main=_main, _command_parser=parser)
