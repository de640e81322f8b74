# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Stacks that put a simulated world and Nav2's nodes together: ``slam`` and ``navigation``.

Both run the ``sim`` stack (:mod:`.stacks`: world, robot, controllers, viewer reading
``config/nav2_default_view.rviz``) and nav2_bringup's or slam_toolbox's nodes
(:mod:`.nav_stacks`).
"""

import os

from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import parse_float
from amr_description.launch.actions import with_defaults
from amr_description.launch.nav_stacks import bringup
from amr_description.launch.nav_stacks import BRINGUP_ARGUMENTS
from amr_description.launch.nav_stacks import described_nodes
from amr_description.launch.nav_stacks import online_async
from amr_description.launch.nav_stacks import SLAM_ARGUMENTS
from amr_description.launch.stacks import sim
from amr_description.launch.stacks import SIM_ARGUMENTS


def slam(args):
    """
    Describe the ``slam`` stack: ``sim`` (world, robot, controllers, viewer) + ``online_async``.

    The viewer reads ``config/nav2_default_view.rviz`` unless ``rviz_config`` names a file.

    :param args: dict of launch-argument values (``SIM_ARGUMENTS`` and ``SLAM_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value.
    """
    args = with_defaults(SIM_ARGUMENTS + SLAM_ARGUMENTS[1:], args)
    args['rviz_config'] = args['rviz_config'] or 'nav2_default_view.rviz'
    return sim(args) + online_async(args)


_BRINGUP_SHARED = ('map', 'slam', 'params_file', 'autostart', 'use_composition', 'use_respawn')
NAVIGATION_ARGUMENTS = SIM_ARGUMENTS + [
    DeclareLaunchArgument('map', '',
                          "Full path to map yaml file to load (default: the world's true map, "
                          'drawn from its collision shapes into $ROS_HOME/amr_description/maps)'),
] + [a for a in BRINGUP_ARGUMENTS if a.name in _BRINGUP_SHARED and a.name != 'map']
"""The ``sim`` stack's arguments plus nav2_bringup's ``map``, ``slam``, ``params_file``, ..."""


def true_map_yaml(world):
    """
    Write ``world``'s true map (:func:`amr_description.nav.world_map.world_map`) once.

    :param world: the ``world`` launch argument (a shipped name, a file or a package:// URI).
    :returns: the map's YAML path, ``$ROS_HOME/amr_description/maps/<world>.yaml`` (ROS_HOME
        defaults to ``~/.ros``); rewritten when the world file is newer.
    :raises LaunchError: an unreadable world or an unwritable folder.
    """
    from amr_description.core.gazebo.sdf_resources import find_world
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.nav.map_io import save_map
    from amr_description.nav.world_map import world_map
    try:
        source = find_world(world)
        home = os.environ.get('ROS_HOME') or os.path.join(os.path.expanduser('~'), '.ros')
        folder = os.path.join(home, 'amr_description', 'maps')
        stem = os.path.splitext(os.path.basename(source))[0]
        yaml_path = os.path.join(folder, f'{stem}.yaml')
        if (os.path.isfile(yaml_path)
                and os.path.getmtime(yaml_path) >= os.path.getmtime(source)):
            return yaml_path
        os.makedirs(folder, exist_ok=True)
        save_map(os.path.join(folder, stem), world_map(load_world(world)))
    except (ValueError, OSError) as exc:  # WorldError, MapError
        raise LaunchError(f"launch argument 'world': no map for '{world}': {exc}") from None
    return yaml_path


def navigation_sim(args):
    """
    Describe the ``navigation`` stack: ``sim`` + nav2_bringup's ``bringup_launch.py``.

    The world, robot, controllers and viewer (``config/nav2_default_view.rviz`` unless
    ``rviz_config`` names a file), then map_server + AMCL (or SLAM with ``slam:=True``) and the
    navigation servers, all on sim time. Without ``map``, the world's true map
    (:func:`true_map_yaml`); AMCL starts at the spawn pose (``set_initial_pose`` with ``x``,
    ``y``, ``yaw``), as the world frame is the map frame.

    :param args: dict of launch-argument values (:data:`NAVIGATION_ARGUMENTS`).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(NAVIGATION_ARGUMENTS, args)
    args['rviz_config'] = args['rviz_config'] or 'nav2_default_view.rviz'
    pose = {k: parse_float(args[k], k) for k in ('x', 'y', 'yaw')}
    nav = bringup({**{k: args[k] for k in _BRINGUP_SHARED}, 'use_sim_time': args['use_sim_time'],
                   'map': args['map'] or true_map_yaml(args['world'])})
    for action in described_nodes(nav):
        if getattr(action, 'node_name', None) == 'amcl':
            action.parameters.append({'set_initial_pose': True, 'initial_pose.x': pose['x'],
                                      'initial_pose.y': pose['y'],
                                      'initial_pose.yaw': pose['yaw']})
    return sim(args) + nav
