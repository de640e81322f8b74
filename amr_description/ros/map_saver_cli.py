# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 run nav2_map_server map_saver_cli``, run as slam_toolbox's ``save_map`` service runs it.

slam_toolbox 2.8.3 ``src/map_saver.cpp`` starts the CLI with ``-f NAME`` and
``--ros-args -p map_subscribe_transient_local:=true``; ``save_map_timeout`` is 10 s here
(upstream's 2 s: a new process on a busy two-core machine once took longer to match the
latched ``/map``).
"""

import os
import shutil
import subprocess


def map_saver_command(name='', namespace='/', ros_args=()):
    """
    Return the command line that saves the map on ``<namespace>/map`` to ``name``.

    :param name: the ``-f`` file stem ('' for the CLI's default ``map_<time>``).
    :param namespace: the node's namespace; '/' for none.
    :param ros_args: more ``--ros-args`` items, e.g. ``('-p', 'use_sim_time:=true')``.
    :raises FileNotFoundError: when ``ros2`` is not on PATH (one line to print).
    """
    ros2 = shutil.which('ros2')
    if ros2 is None:
        raise FileNotFoundError("no 'ros2' on PATH to run map_saver_cli "
                                '(source scripts/env.sh)')
    cmd = [ros2, 'run', 'nav2_map_server', 'map_saver_cli']
    if name:
        cmd += ['-f', name]
    cmd += ['--ros-args', '-p', 'map_subscribe_transient_local:=true',
            '-p', 'save_map_timeout:=10.0', *ros_args]
    if namespace not in ('', '/'):
        cmd += ['-r', f'__ns:={namespace}']
    return cmd


def run_map_saver(cmd, capture=False, timeout=None):
    """
    Run ``cmd`` (:func:`map_saver_command`) to its end; return the ``CompletedProcess``.

    :param capture: keep stdout and stderr (text) instead of passing them through.
    :param timeout: seconds, or None to wait as long as it takes.
    :raises subprocess.TimeoutExpired: past ``timeout``.
    """
    return subprocess.run(cmd, env=os.environ.copy(), stdin=subprocess.DEVNULL, check=False,
                          capture_output=capture, text=capture, timeout=timeout)
