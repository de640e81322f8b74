# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The SLAM stacks: slam_toolbox's launch files.

``online_async_launch.py``, ``online_sync_launch.py`` and ``localization_launch.py``,
registered in :data:`amr_description.launch.registry.STACKS` with their declared arguments
(upstream's names, defaults and descriptions); nav2_bringup's ``bringup_launch.py`` with
``slam:=True`` (:mod:`.nav_stacks`) runs :func:`online_sync`, as its ``slam_launch.py`` does.
"""

import os

from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import parse_bool
from amr_description.launch.actions import share_file
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

SLAM_LOCALIZATION_ARGUMENTS = [
    SLAM_ARGUMENTS[0],
    DeclareLaunchArgument('slam_params_file', '',
                          'Full path to the ROS2 parameters file to use for the slam_toolbox '
                          "node (default: the package's config/mapper_params_localization.yaml)"),
    *SLAM_ARGUMENTS[2:],
]
"""slam_toolbox's ``localization_launch.py`` arguments (those of ``online_async_launch.py``)."""

SLAM_SYNC_ARGUMENTS = [
    SLAM_ARGUMENTS[0],
    DeclareLaunchArgument('slam_params_file', '',
                          'Full path to the ROS2 parameters file to use for the slam_toolbox '
                          "node (default: the package's config/mapper_params_online_sync.yaml)"),
    *SLAM_ARGUMENTS[2:],
]
"""slam_toolbox's ``online_sync_launch.py`` arguments (those of ``online_async_launch.py``)."""


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
    return _slam_toolbox(with_defaults(SLAM_ARGUMENTS, args), 'async_slam_toolbox_node',
                         'mapper_params_online_async.yaml')


def online_sync(args):
    """
    Describe the ``online_sync`` stack (slam_toolbox's ``online_sync_launch.py``).

    As :func:`online_async` with ``sync_slam_toolbox_node`` and
    ``config/mapper_params_online_sync.yaml``.

    :param args: dict of launch-argument values (see ``SLAM_SYNC_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing params file.
    """
    return _slam_toolbox(with_defaults(SLAM_SYNC_ARGUMENTS, args), 'sync_slam_toolbox_node',
                         'mapper_params_online_sync.yaml')


def slam_toolbox_localization(args):
    """
    Describe ``slam_toolbox_localization`` (slam_toolbox's ``localization_launch.py``).

    As :func:`online_async` with ``localization_slam_toolbox_node`` and
    ``config/mapper_params_localization.yaml``; named so beside nav2_bringup's
    ``localization_launch.py`` (``localization``).

    :param args: dict of launch-argument values (see ``SLAM_LOCALIZATION_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing params file.
    """
    return _slam_toolbox(with_defaults(SLAM_LOCALIZATION_ARGUMENTS, args),
                         'localization_slam_toolbox_node', 'mapper_params_localization.yaml')


def _slam_toolbox(args, executable, config):
    """Return the actions of a slam_toolbox node named ``slam_toolbox`` and its autostart."""
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    managed = parse_bool(args['use_lifecycle_manager'], 'use_lifecycle_manager')
    params = args['slam_params_file'] or share_file('config', config)
    if not os.path.isfile(os.path.expanduser(params)):
        raise LaunchError(f"launch argument 'slam_params_file': no such file '{params}'")
    actions = [Node(PACKAGE, executable, name='slam_toolbox', namespace='',
                    output='screen',
                    parameters=[os.path.expanduser(params),
                                {'use_lifecycle_manager': managed,
                                 'use_sim_time': use_sim_time}])]
    if autostart and not managed:
        actions.append(Node(PACKAGE, 'lifecycle_autostart', output='screen',
                            arguments=['/slam_toolbox', 'configure', 'activate']))
    return actions
