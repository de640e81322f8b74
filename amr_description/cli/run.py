# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 run PKG EXE [args] [--ros-args ...]``: run a package executable (as ros2run).

The executable is ``<prefix>/lib/PKG/EXE`` of the package's prefix in the ament index. It
runs as a child in the same process group, so a terminal Ctrl-C reaches it directly (and is
not sent twice). A SIGINT, SIGTERM or SIGHUP sent to ``ros2`` alone (``kill PID``, a
supervisor) is passed on to the child, and the child is tied to ``ros2``'s life with
``prctl(PR_SET_PDEATHSIG, SIGKILL)`` (as the orchestrator in ``launch/`` does), so no signal
reaching ``ros2 run`` alone leaves an orphan; upstream ros2run does neither. The exit code is
the child's; a failure or a signal is reported as ``[ros2run] ...`` like upstream.
"""

import argparse
import os
import signal
import subprocess

from amr_description.cli.common import fail
from amr_description.cli.extension import Command
from amr_description.cli.pkg import executable_paths
from amr_description.cli.pkg import package_prefixes
from amr_description.launch.child_process import tie_to_parent


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


_FORWARDED = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
_SI_KERNEL = 0x80
"""``siginfo.si_code`` of a signal the kernel raised itself (a terminal's Ctrl-C)."""


def run_child(cmd):
    """
    Run ``cmd`` as a child, forwarding the signals ``ros2 run`` receives alone.

    SIGINT, SIGTERM and SIGHUP are blocked and taken with ``sigtimedwait`` so their origin is
    known: one the kernel raised for the terminal (``si_code == SI_KERNEL``, e.g. Ctrl-C)
    already reached the child through the process group and is not sent again; any other
    (``kill``) is forwarded to the child.

    :param cmd: the command line, a list of str.
    :returns: the child's return code (negative: killed by that signal).
    :raises OSError: when the executable cannot be started.
    """
    signal.pthread_sigmask(signal.SIG_BLOCK, _FORWARDED)
    try:
        child = subprocess.Popen(cmd, preexec_fn=tie_to_parent(os.getpid(), _FORWARDED))
    except BaseException:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _FORWARDED)
        raise
    while child.poll() is None:
        info = signal.sigtimedwait(_FORWARDED, 0.1)
        if info is not None and info.si_code != _SI_KERNEL:
            try:
                child.send_signal(info.si_signo)
            except ProcessLookupError:
                pass
    return child.returncode


def _main(args):
    try:
        path = find_executable(args.package_name, args.executable_name)
    except LookupError as exc:
        return fail(str(exc))
    if path is None:
        return fail('No executable found')
    cmd = ([*args.prefix.split()] if args.prefix else []) + [path, *args.argv]
    try:
        code = run_child(cmd)
    except OSError as exc:
        return fail(f'[ros2run] {exc}')
    if code < 0:
        print('[ros2run]', signal.strsignal(-code))
    elif code != 0:
        print('[ros2run]', f'Process exited with failure {code}')
    return code if code >= 0 else 128 - code


def _arguments(parser):
    """Add the arguments of ``ros2 run``."""
    parser.add_argument('--prefix', help='Prefix command, which should go before the '
                        'executable. Command must be wrapped in quotes if it contains spaces '
                        "(e.g. --prefix 'gdb -ex run --args').")
    parser.add_argument('package_name', help='Name of the ROS package')
    parser.add_argument('executable_name', help='Name of the executable')
    parser.add_argument('argv', nargs=argparse.REMAINDER,
                        help='Pass arbitrary arguments to the executable')


COMMAND = Command('Run a package specific executable', _arguments, _main)
"""``ros2 run``."""
