# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The mapping and localization stacks: slam_toolbox's and nav2_bringup's launch files.

Registered in :data:`amr_description.launch.registry.STACKS` with their declared arguments
(upstream's names and defaults); the ``slam`` stack (``sim`` + ``online_async``) is in
:mod:`.stacks`, which imports this module.
"""

import os

from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import parse_bool
from amr_description.launch.actions import with_defaults

PACKAGE = 'amr_description'

SLAM_ARGUMENTS = [
    DeclareLaunchArgument('use_sim_time', 'true', 'Use simulation/Gazebo clock'),
    DeclareLaunchArgument('slam_params_file', '',
                          'Full path to the ROS2 parameters file to use for the slam_toolbox '
                          "node (default: the package's config/mapper_params_online_async.yaml)"),
    DeclareLaunchArgument('autostart', 'true',
                          'Automatically startup the slamtoolbox. Ignored when '
                          'use_lifecycle_manager is true.'),
    DeclareLaunchArgument('use_lifecycle_manager', 'false',
                          'Enable bond connection during node activation'),
]
"""slam_toolbox's ``online_async_launch.py`` arguments, its names, defaults and descriptions."""


MAP_ARGUMENT = DeclareLaunchArgument('map', '', 'Full path to map yaml file to load')
USE_SIM_TIME_ARGUMENT = DeclareLaunchArgument('use_sim_time', 'false',
                                              'Use simulation (Gazebo) clock if true')
PARAMS_FILE_ARGUMENT = DeclareLaunchArgument(
    'params_file', '', 'Full path to the ROS2 parameters file to use for all launched nodes '
    "(default: the package's config/nav2_params.yaml)")
AUTOSTART_ARGUMENT = DeclareLaunchArgument('autostart', 'true',
                                           'Automatically startup the nav2 stack')
USE_RESPAWN_ARGUMENT = DeclareLaunchArgument(
    'use_respawn', 'False',
    'Whether to respawn if a node crashes. Applied when composition is disabled.')
# the arguments nav2_bringup's launch files declare alike (names, defaults, descriptions)

LOCALIZATION_ARGUMENTS = [MAP_ARGUMENT, USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT,
                          AUTOSTART_ARGUMENT, USE_RESPAWN_ARGUMENT]
"""nav2_bringup's ``localization_launch.py`` arguments (names, defaults, descriptions)."""


def _params_file(args):
    params = os.path.expanduser(args['params_file'] or share_file('config', 'nav2_params.yaml'))
    if not os.path.isfile(params):
        raise LaunchError(f"launch argument 'params_file': no such file '{params}'")
    return params


def localization(args):
    """
    Describe the ``localization`` stack (nav2_bringup's ``localization_launch.py``).

    ``map_server`` (``yaml_filename`` = ``map``) and ``amcl`` reading ``params_file``
    (default ``config/nav2_params.yaml``), and ``lifecycle_manager_localization``
    (``node_names: [map_server, amcl]``, ``autostart``), all with ``use_sim_time``.

    :param args: dict of launch-argument values (see ``LOCALIZATION_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(LOCALIZATION_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    respawn = parse_bool(args['use_respawn'], 'use_respawn')
    params = _params_file(args)
    map_yaml = os.path.expanduser(args['map'])
    if map_yaml and not os.path.isfile(map_yaml):
        raise LaunchError(f"launch argument 'map': no such file '{args['map']}'")
    common = {'use_sim_time': use_sim_time}
    options = {'output': 'screen', 'respawn': respawn, 'respawn_delay': 2.0}
    return [
        Node(PACKAGE, 'map_server', name='map_server',
             parameters=[params, {'yaml_filename': map_yaml, **common}], **options),
        Node(PACKAGE, 'amcl', name='amcl', parameters=[params, common], **options),
        Node(PACKAGE, 'lifecycle_manager', name='lifecycle_manager_localization',
             output='screen', parameters=[{'autostart': autostart,
                                           'node_names': ['map_server', 'amcl'], **common}]),
    ]


def share_file(folder, name):
    """
    Return the path of ``folder/name`` in the package's share directory.

    :raises LaunchError: when the package is not installed.
    """
    from ament_index_python.packages import get_package_share_directory
    from ament_index_python.packages import PackageNotFoundError
    try:
        share = get_package_share_directory(PACKAGE)
    except (PackageNotFoundError, ValueError, LookupError):
        raise LaunchError(f"package '{PACKAGE}' not found") from None
    return os.path.join(share, folder, name)


def online_async(args):
    """
    Describe the ``online_async`` stack (slam_toolbox's ``online_async_launch.py``).

    ``async_slam_toolbox_node`` named ``slam_toolbox`` with ``slam_params_file`` (default
    ``config/mapper_params_online_async.yaml``), ``use_sim_time`` and
    ``use_lifecycle_manager``; with ``autostart`` and no lifecycle manager it is configured
    then activated (``lifecycle_autostart``, launch_ros' lifecycle events), as upstream's
    launch file does.

    :param args: dict of launch-argument values (see ``SLAM_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing params file.
    """
    args = with_defaults(SLAM_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    managed = parse_bool(args['use_lifecycle_manager'], 'use_lifecycle_manager')
    params = args['slam_params_file'] or share_file('config', 'mapper_params_online_async.yaml')
    if not os.path.isfile(os.path.expanduser(params)):
        raise LaunchError(f"launch argument 'slam_params_file': no such file '{params}'")
    actions = [Node(PACKAGE, 'async_slam_toolbox_node', name='slam_toolbox', namespace='',
                    output='screen',
                    parameters=[os.path.expanduser(params),
                                {'use_lifecycle_manager': managed,
                                 'use_sim_time': use_sim_time}])]
    if autostart and not managed:
        actions.append(Node(PACKAGE, 'lifecycle_autostart', output='screen',
                            arguments=['/slam_toolbox', 'configure', 'activate']))
    return actions


NAMESPACE_ARGUMENT = DeclareLaunchArgument('namespace', '', 'Top-level namespace')
LOG_LEVEL_ARGUMENT = DeclareLaunchArgument('log_level', 'info', 'log level')

NAVIGATION_ARGUMENTS = [
    NAMESPACE_ARGUMENT, USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT, AUTOSTART_ARGUMENT,
    DeclareLaunchArgument('use_composition', 'False',
                          'Use composed bringup if True (here: one process each either way)'),
    DeclareLaunchArgument('container_name', 'nav2_container',
                          'the name of conatiner that nodes will load in if use composition'),
    USE_RESPAWN_ARGUMENT, LOG_LEVEL_ARGUMENT,
]
"""nav2_bringup's ``navigation_launch.py`` arguments (names, defaults, descriptions)."""

NAVIGATION_NODES = ['controller_server', 'planner_server', 'behavior_server',
                    'velocity_smoother', 'bt_navigator', 'waypoint_follower']
"""The servers, in nav2_bringup's ``lifecycle_nodes`` order (those built here)."""

ROBOT_CMD_VEL = 'diff_drive_controller/cmd_vel'
"""Where the smoothed command goes: the robot's diff_drive_controller (no collision monitor)."""


def navigation(args):
    """
    Describe the ``navigation_launch`` stack (nav2_bringup's ``navigation_launch.py``).

    controller_server, planner_server, behavior_server, velocity_smoother, bt_navigator and
    waypoint_follower reading ``params_file`` (default ``config/nav2_params.yaml``) in
    ``namespace``, and ``lifecycle_manager_navigation`` (``autostart``). As upstream,
    controller_server, behavior_server and velocity_smoother have ``cmd_vel`` remapped to
    ``cmd_vel_nav``; the smoother's ``cmd_vel_smoothed`` goes to :data:`ROBOT_CMD_VEL` (upstream
    sends it through the collision monitor, not built here). ``use_composition`` is accepted; each
    server runs in its own process.

    :param args: dict of launch-argument values (see ``NAVIGATION_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(NAVIGATION_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    respawn = parse_bool(args['use_respawn'], 'use_respawn')
    parse_bool(args['use_composition'], 'use_composition')
    params = _params_file(args)
    ns = args['namespace'].strip('/') or None
    common = {'use_sim_time': use_sim_time}
    options = {'output': 'screen', 'respawn': respawn, 'respawn_delay': 2.0, 'namespace': ns,
               'parameters': [params, common]}
    to_nav = [('cmd_vel', 'cmd_vel_nav')]
    return [
        Node(PACKAGE, 'controller_server', name='controller_server', remappings=to_nav,
             **options),
        Node(PACKAGE, 'planner_server', name='planner_server', **options),
        Node(PACKAGE, 'behavior_server', name='behavior_server', remappings=to_nav,
             **options),
        Node(PACKAGE, 'velocity_smoother', name='velocity_smoother',
             remappings=to_nav + [('cmd_vel_smoothed', ROBOT_CMD_VEL)], **options),
        Node(PACKAGE, 'bt_navigator', name='bt_navigator', **options),
        Node(PACKAGE, 'waypoint_follower', name='waypoint_follower', **options),
        Node(PACKAGE, 'lifecycle_manager', name='lifecycle_manager_navigation',
             output='screen', namespace=ns,
             parameters=[{'autostart': autostart, 'node_names': NAVIGATION_NODES, **common}]),
    ]


BRINGUP_ARGUMENTS = [
    NAMESPACE_ARGUMENT,
    DeclareLaunchArgument('use_namespace', 'false',
                          'Whether to apply a namespace to the navigation stack'),
    DeclareLaunchArgument('slam', 'False', 'Whether run a SLAM'),
    MAP_ARGUMENT,
    DeclareLaunchArgument('use_localization', 'True',
                          'Whether to enable localization or not'),
    USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT, AUTOSTART_ARGUMENT,
    DeclareLaunchArgument('use_composition', 'True',
                          'Whether to use composed bringup (here: one process each)'),
    USE_RESPAWN_ARGUMENT, LOG_LEVEL_ARGUMENT,
]
"""nav2_bringup's ``bringup_launch.py`` arguments (names, defaults, descriptions)."""


def bringup(args):
    """
    Describe the ``bringup`` stack (nav2_bringup's ``bringup_launch.py``).

    ``slam`` false: :func:`localization` (map_server with ``map`` + amcl) when
    ``use_localization``; true: slam_toolbox (:func:`online_async`, managed by no lifecycle
    manager, as ``slam_launch.py`` runs it with autostart). Then :func:`navigation`.
    ``namespace`` applies when ``use_namespace`` is true.

    :param args: dict of launch-argument values (see ``BRINGUP_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(BRINGUP_ARGUMENTS, args)
    slam = parse_bool(args['slam'], 'slam')
    use_ns = parse_bool(args['use_namespace'], 'use_namespace')
    shared = {k: args[k] for k in ('use_sim_time', 'params_file', 'autostart', 'use_respawn')}
    actions = []
    if slam:
        actions += online_async({'use_sim_time': args['use_sim_time'],
                                 'autostart': args['autostart']})
    elif parse_bool(args['use_localization'], 'use_localization'):
        actions += localization({**shared, 'map': args['map']})
    return actions + navigation({**shared, 'namespace': args['namespace'] if use_ns else '',
                                 'use_composition': args['use_composition']})


NAV2_STACKS = {
    'localization': (localization, LOCALIZATION_ARGUMENTS,
                     "nav2_bringup's map_server + amcl + lifecycle_manager_localization"),
    'navigation_launch': (navigation, NAVIGATION_ARGUMENTS,
                          "nav2_bringup's navigation servers + lifecycle_manager_navigation"),
    'bringup': (bringup, BRINGUP_ARGUMENTS,
                "nav2_bringup's localization (or SLAM) + navigation on a running simulator"),
}
"""nav2_bringup's launch files as stacks (see :data:`amr_description.launch.registry.STACKS`)."""
