# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The stacks ``ros2 launch amr_description NAME`` runs, by name, and their arguments.

``STACKS[name] = (function, declared_arguments, description)``: :mod:`.stacks` (display, sim,
fleet), :mod:`.nav_stacks` (slam_toolbox's and nav2_bringup's launch files) and
:mod:`.world_stacks` (a world with SLAM or navigation).
"""

import os

from amr_description.launch.actions import Arguments
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import parse_launch_arguments
from amr_description.launch.nav_stacks import NAV2_STACKS
from amr_description.launch.slam_stacks import online_async
from amr_description.launch.slam_stacks import SLAM_ARGUMENTS
from amr_description.launch.stacks import display
from amr_description.launch.stacks import DISPLAY_ARGUMENTS
from amr_description.launch.stacks import PACKAGE
from amr_description.launch.stacks import sim
from amr_description.launch.stacks import SIM_ARGUMENTS
from amr_description.launch.world_stacks import fleet_navigation
from amr_description.launch.world_stacks import FLEET_NAVIGATION_ARGUMENTS
from amr_description.launch.world_stacks import NAVIGATION_ARGUMENTS
from amr_description.launch.world_stacks import navigation_sim
from amr_description.launch.world_stacks import slam

STACKS = {
    'display': (display, DISPLAY_ARGUMENTS,
                'robot_state_publisher + joint_state_publisher(_gui) + viewer for the '
                'installed URDF'),
    'sim': (sim, SIM_ARGUMENTS,
            'MuJoCo simulation, robot_state_publisher, spawn and ros2_control controllers'),
    'fleet': (fleet_navigation, FLEET_NAVIGATION_ARGUMENTS,
              'MuJoCo simulation with N namespaced robots (r1 ... rN) on a grid, with Nav2 '
              'for each (navigation:=true)'),
    'online_async': (online_async, SLAM_ARGUMENTS,
                     "slam_toolbox's online asynchronous mapper, configured and activated"),
    'slam': (slam, SIM_ARGUMENTS + SLAM_ARGUMENTS[1:],
             'the sim stack (world:=, viewer) with SLAM from its lidar'),
    'navigation': (navigation_sim, NAVIGATION_ARGUMENTS,
                   'the sim stack (world:=, viewer) with localization and the navigation '
                   'servers on its map'),
    **NAV2_STACKS,
}
"""Every stack ``ros2 launch amr_description`` runs: ``name: (function, arguments, text)``."""


def stack_name(name):
    """
    Map ``sim``, ``sim.launch.py`` or ``sim_launch.py`` to a stack name.

    :param name: what the user typed.
    :returns: the key of :data:`STACKS`.
    :raises LaunchError: when no such stack exists.
    """
    base = os.path.basename(name)
    if base.endswith('_launch.py') and base[:-3] in STACKS:
        return base[:-3]  # navigation_launch.py: upstream's file, not our 'navigation'
    for suffix in ('.launch.py', '_launch.py', '.py'):
        if base.endswith(suffix):
            base = base[:-len(suffix)]
            break
    if base not in STACKS:
        raise LaunchError(f"file '{name}' was not found in the share directory of package "
                          f"'{PACKAGE}' (stacks: {', '.join(sorted(STACKS))})")
    return base


def resolve(name, argv=()):
    """
    Parse ``name:=value`` arguments for a stack.

    :param name: stack name (see :func:`stack_name`).
    :param argv: list of ``'name:=value'``.
    :returns: dict of argument values with defaults filled in; its ``given`` attribute holds
        the names set in ``argv`` (a port left at its default may move to the next free one).
    :raises LaunchError: on an unknown stack or a bad argument.
    """
    _, declared, _ = STACKS[stack_name(name)]
    values = Arguments(parse_launch_arguments(declared, list(argv)))
    values.given = frozenset(arg.partition(':=')[0] for arg in argv)
    return values


def describe(name, argv=()):
    """
    Return the actions of stack ``name`` for ``name:=value`` arguments ``argv``.

    :param name: stack name (see :func:`stack_name`).
    :param argv: list of ``'name:=value'``.
    :returns: list of actions for :class:`~amr_description.launch.orchestrator.Orchestrator`.
    :raises LaunchError: on an unknown stack, a bad argument or an unreadable URDF.
    """
    function = STACKS[stack_name(name)][0]
    return function(resolve(name, argv))
