# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Stacks that put a simulated world and Nav2's nodes together: ``slam``, ``navigation``, ``fleet``.

``slam`` and ``navigation`` run the ``sim`` stack (:mod:`.stacks`: world, robot, controllers,
viewer reading ``config/nav2_default_view.rviz``) and nav2_bringup's or slam_toolbox's nodes
(:mod:`.nav_stacks`); ``fleet`` runs :func:`.stacks.fleet` and, with ``navigation:=true``, one
namespaced Nav2 per robot.
"""

import os

from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import parse_bool
from amr_description.launch.actions import parse_float
from amr_description.launch.actions import with_defaults
from amr_description.launch.nav_stacks import bringup
from amr_description.launch.nav_stacks import BRINGUP_ARGUMENTS
from amr_description.launch.nav_stacks import described_nodes
from amr_description.launch.nav_stacks import package_home
from amr_description.launch.nav_stacks import robot_navigation
from amr_description.launch.slam_stacks import online_async
from amr_description.launch.slam_stacks import SLAM_ARGUMENTS
from amr_description.launch.stacks import fleet
from amr_description.launch.stacks import FLEET_ARGUMENTS
from amr_description.launch.stacks import fleet_grid
from amr_description.launch.stacks import PACKAGE
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
        folder = package_home('maps')
        stem = os.path.splitext(os.path.basename(source))[0]
        yaml_path = os.path.join(folder, f'{stem}.yaml')
        if (os.path.isfile(yaml_path)
                and os.path.getmtime(yaml_path) >= os.path.getmtime(source)):
            return yaml_path
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


FLEET_NAVIGATION_ARGUMENTS = FLEET_ARGUMENTS + [
    DeclareLaunchArgument('navigation', 'false',
                          "Run Nav2 for every robot, in its namespace (nav2_bringup's "
                          'multi-robot bring-up)'),
    DeclareLaunchArgument('map', '',
                          "Full path to map yaml file to load (default: the world's true map)"),
] + [a for a in BRINGUP_ARGUMENTS if a.name in ('params_file', 'autostart')]
"""The ``fleet`` stack's arguments plus ``navigation``, ``map``, ``params_file``, ``autostart``."""


def fleet_navigation(args):
    """
    Describe the ``fleet`` stack, with Nav2 for every robot when ``navigation`` is true.

    Without ``navigation``: :func:`amr_description.launch.stacks.fleet`. With it, as
    nav2_bringup's multi-robot bring-up, every robot ``rI`` gets its own map_server, AMCL
    (starting at its spawn pose) and navigation servers in ``/rI``, composed in
    ``/rI/nav2_container`` (``use_composition``) (:func:`robot_navigation`), on ``map``
    (default: the world's true map, :func:`true_map_yaml`). Every AMCL publishes
    ``map -> rI/odom`` in the one ``map`` frame, so the static ``world -> rI/odom`` transforms
    are replaced by one ``world -> map`` identity (``/world_to_map``). Goals go to
    ``/rI/navigate_to_pose`` or ``/rI/goal_pose``; the viewer's 2D Pose Estimate and 2D Goal
    Pose tools publish ``r1``'s, as its pad drives ``r1``.

    :param args: dict of launch-argument values (:data:`FLEET_NAVIGATION_ARGUMENTS`).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(FLEET_NAVIGATION_ARGUMENTS, args)
    if not parse_bool(args['navigation'], 'navigation'):
        return fleet(args)
    actions = fleet(args, odom_in_world=False)
    for action in actions:  # the viewer's pose tools, as its pad, act on r1
        if getattr(action, 'executable', None) == 'viewer':
            action.parameters.append({'initial_pose_topic': '/r1/initialpose',
                                      'goal_pose_topic': '/r1/goal_pose'})
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    actions.append(Node(PACKAGE, 'static_transform_publisher', name='world_to_map',
                        output='screen', parameters=[{'use_sim_time': use_sim_time}],
                        arguments=['--frame-id', 'world', '--child-frame-id', 'map']))
    nav = {'map': args['map'] or true_map_yaml(args['world']), 'params_file':
           args['params_file'], 'autostart': args['autostart'],
           'use_sim_time': args['use_sim_time'], 'use_composition': args['use_composition']}
    grid = fleet_grid(int(args['robots']), parse_float(args['spacing'], 'spacing'))
    for i, (x, y) in enumerate(grid, start=1):
        actions += robot_navigation(f'r{i}', nav, (x, y, 0.0))
    return actions
