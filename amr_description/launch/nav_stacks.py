# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The localization and navigation stacks: nav2_bringup's launch files.

Registered in :data:`amr_description.launch.registry.STACKS` with their declared arguments
(upstream's names and defaults), with slam_toolbox's of :mod:`.slam_stacks`; the ``slam``
stack (``sim`` + ``online_async``) is in :mod:`.world_stacks`, which imports this module.
"""

import os

from amr_description.launch.actions import ComposableNode
from amr_description.launch.actions import ComposableNodeContainer
from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import parse_bool
from amr_description.launch.actions import share_file
from amr_description.launch.actions import with_defaults
from amr_description.launch.slam_stacks import online_sync
from amr_description.launch.slam_stacks import SLAM_LOCALIZATION_ARGUMENTS
from amr_description.launch.slam_stacks import SLAM_SYNC_ARGUMENTS
from amr_description.launch.slam_stacks import slam_toolbox_localization

PACKAGE = 'amr_description'

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

USE_COMPOSITION_ARGUMENT = DeclareLaunchArgument(
    'use_composition', 'False', 'Use composed bringup if True')
CONTAINER_NAME_ARGUMENT = DeclareLaunchArgument(
    'container_name', 'nav2_container',
    'the name of conatiner that nodes will load in if use composition')

LOCALIZATION_ARGUMENTS = [MAP_ARGUMENT, USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT,
                          AUTOSTART_ARGUMENT, USE_COMPOSITION_ARGUMENT, CONTAINER_NAME_ARGUMENT,
                          USE_RESPAWN_ARGUMENT]
"""nav2_bringup's ``localization_launch.py`` arguments (names, defaults, descriptions)."""


def _params_file(args):
    params = os.path.expanduser(args['params_file'] or share_file('config', 'nav2_params.yaml'))
    if not os.path.isfile(params):
        raise LaunchError(f"launch argument 'params_file': no such file '{params}'")
    return params


COMPONENTS = {
    'map_server': 'nav2_map_server::MapServer',
    'amcl': 'nav2_amcl::AmclNode',
    'lifecycle_manager': 'nav2_lifecycle_manager::LifecycleManager',
    'controller_server': 'nav2_controller::ControllerServer',
    'planner_server': 'nav2_planner::PlannerServer',
    'behavior_server': 'behavior_server::BehaviorServer',
    'velocity_smoother': 'nav2_velocity_smoother::VelocitySmoother',
    'bt_navigator': 'nav2_bt_navigator::BtNavigator',
    'waypoint_follower': 'nav2_waypoint_follower::WaypointFollower',
}
"""Executable -> the plugin name nav2_bringup loads it by when composed (upstream's names)."""


class _Spec:
    """One node of a Nav2 launch file, started as a process or loaded into a container."""

    def __init__(self, executable, name, parameters, remappings=(), managed=True):
        self.executable = executable
        self.name = name
        self.parameters = parameters
        self.remappings = list(remappings)
        self.managed = managed  # respawned with use_respawn (not the lifecycle manager)


def _start(specs, args, namespace=None):
    """
    Return the actions of ``specs``: processes, or one container with ``use_composition``.

    As nav2_bringup: with ``use_composition`` the nodes load into ``container_name``
    (``component_container_isolated``: each node on an executor and thread of its own) and
    ``use_respawn`` does not apply; otherwise one process each, respawned after 2 s with
    ``use_respawn`` (the lifecycle managers never). Here the launch file starts the container
    it loads into (upstream's bringup_launch.py starts it, navigation_launch.py alone expects
    it running).
    """
    ns = namespace or None
    if parse_bool(args['use_composition'], 'use_composition'):
        use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
        return [ComposableNodeContainer(
            args['container_name'] or 'nav2_container', namespace=ns, output='screen',
            executable='component_container_isolated',
            parameters=[{'use_sim_time': use_sim_time}],
            composable_node_descriptions=[
                ComposableNode(PACKAGE, COMPONENTS[spec.executable], name=spec.name,
                               namespace=ns, parameters=spec.parameters,
                               remappings=spec.remappings) for spec in specs])]
    respawn = parse_bool(args['use_respawn'], 'use_respawn')
    return [Node(PACKAGE, spec.executable, name=spec.name, namespace=ns, output='screen',
                 parameters=spec.parameters, remappings=spec.remappings,
                 **({'respawn': respawn, 'respawn_delay': 2.0} if spec.managed else {}))
            for spec in specs]


def described_nodes(actions):
    """
    Yield the node descriptions of ``actions``: each ``Node``, and the nodes of containers.

    :param actions: list of launch actions.
    :returns: iterator of :class:`Node` and :class:`ComposableNode` (both have ``node_name``
        and a ``parameters`` list to append to).
    """
    for action in actions:
        yield action
        yield from getattr(action, 'composable_node_descriptions', ())


def _localization_specs(args):
    args = with_defaults(LOCALIZATION_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    params = _params_file(args)
    map_yaml = os.path.expanduser(args['map'])
    if map_yaml and not os.path.isfile(map_yaml):
        raise LaunchError(f"launch argument 'map': no such file '{args['map']}'")
    common = {'use_sim_time': use_sim_time}
    return [
        _Spec('map_server', 'map_server', [params, {'yaml_filename': map_yaml, **common}]),
        _Spec('amcl', 'amcl', [params, common]),
        _Spec('lifecycle_manager', 'lifecycle_manager_localization',
              [{'autostart': autostart, 'node_names': ['map_server', 'amcl'], **common}],
              managed=False),
    ]


def localization(args):
    """
    Describe the ``localization`` stack (nav2_bringup's ``localization_launch.py``).

    ``map_server`` (``yaml_filename`` = ``map``) and ``amcl`` reading ``params_file``
    (default ``config/nav2_params.yaml``), and ``lifecycle_manager_localization``
    (``node_names: [map_server, amcl]``, ``autostart``), all with ``use_sim_time``; one
    process each, or with ``use_composition`` composed in ``container_name`` (:func:`_start`).

    :param args: dict of launch-argument values (see ``LOCALIZATION_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(LOCALIZATION_ARGUMENTS, args)
    return _start(_localization_specs(args), args)


NAMESPACE_ARGUMENT = DeclareLaunchArgument('namespace', '', 'Top-level namespace')
LOG_LEVEL_ARGUMENT = DeclareLaunchArgument('log_level', 'info', 'log level')

NAVIGATION_ARGUMENTS = [
    NAMESPACE_ARGUMENT, USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT, AUTOSTART_ARGUMENT,
    USE_COMPOSITION_ARGUMENT, CONTAINER_NAME_ARGUMENT, USE_RESPAWN_ARGUMENT,
    LOG_LEVEL_ARGUMENT,
]
"""nav2_bringup's ``navigation_launch.py`` arguments (names, defaults, descriptions)."""

NAVIGATION_NODES = ['controller_server', 'planner_server', 'behavior_server',
                    'velocity_smoother', 'bt_navigator', 'waypoint_follower']
"""The servers, in nav2_bringup's ``lifecycle_nodes`` order (those built here)."""

ROBOT_CMD_VEL = 'diff_drive_controller/cmd_vel'
"""Where the smoothed command goes: the robot's diff_drive_controller (no collision monitor)."""


def _navigation_specs(args):
    args = with_defaults(NAVIGATION_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    autostart = parse_bool(args['autostart'], 'autostart')
    params = [_params_file(args), {'use_sim_time': use_sim_time}]
    to_nav = [('cmd_vel', 'cmd_vel_nav')]
    return [
        _Spec('controller_server', 'controller_server', params, to_nav),
        _Spec('planner_server', 'planner_server', params),
        _Spec('behavior_server', 'behavior_server', params, to_nav),
        _Spec('velocity_smoother', 'velocity_smoother', params,
              to_nav + [('cmd_vel_smoothed', ROBOT_CMD_VEL)]),
        _Spec('bt_navigator', 'bt_navigator', params),
        _Spec('waypoint_follower', 'waypoint_follower', params),
        _Spec('lifecycle_manager', 'lifecycle_manager_navigation',
              [{'autostart': autostart, 'node_names': NAVIGATION_NODES,
                'use_sim_time': use_sim_time}], managed=False),
    ]


def navigation(args):
    """
    Describe the ``navigation_launch`` stack (nav2_bringup's ``navigation_launch.py``).

    controller_server, planner_server, behavior_server, velocity_smoother, bt_navigator and
    waypoint_follower reading ``params_file`` (default ``config/nav2_params.yaml``) in
    ``namespace``, and ``lifecycle_manager_navigation`` (``autostart``). As upstream,
    controller_server, behavior_server and velocity_smoother have ``cmd_vel`` remapped to
    ``cmd_vel_nav``; the smoother's ``cmd_vel_smoothed`` goes to :data:`ROBOT_CMD_VEL` (upstream
    sends it through the collision monitor, not built here). One process each, or with
    ``use_composition`` composed in ``container_name`` (:func:`_start`).

    :param args: dict of launch-argument values (see ``NAVIGATION_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(NAVIGATION_ARGUMENTS, args)
    return _start(_navigation_specs(args), args, args['namespace'].strip('/'))


BRINGUP_ARGUMENTS = [
    NAMESPACE_ARGUMENT,
    DeclareLaunchArgument('use_namespace', 'false',
                          'Whether to apply a namespace to the navigation stack'),
    DeclareLaunchArgument('slam', 'False', 'Whether run a SLAM'),
    MAP_ARGUMENT,
    DeclareLaunchArgument('use_localization', 'True',
                          'Whether to enable localization or not'),
    USE_SIM_TIME_ARGUMENT, PARAMS_FILE_ARGUMENT, AUTOSTART_ARGUMENT,
    DeclareLaunchArgument('use_composition', 'True', 'Whether to use composed bringup'),
    USE_RESPAWN_ARGUMENT, LOG_LEVEL_ARGUMENT,
]
"""nav2_bringup's ``bringup_launch.py`` arguments (names, defaults, descriptions)."""


def bringup(args):
    """
    Describe the ``bringup`` stack (nav2_bringup's ``bringup_launch.py``).

    ``slam`` false: :func:`localization` (map_server with ``map`` + amcl) when
    ``use_localization``; true: slam_toolbox's synchronous mapper (:func:`online_sync`,
    managed by no lifecycle manager, as ``slam_launch.py`` runs ``online_sync_launch.py`` with
    autostart). Then :func:`navigation`.
    ``namespace`` applies when ``use_namespace`` is true. With ``use_composition`` (the
    default, as upstream's) localization and the navigation servers load into one
    ``component_container_isolated`` named ``nav2_container``; SLAM runs in its own process
    either way, as upstream's ``slam_launch.py``.

    :param args: dict of launch-argument values (see ``BRINGUP_ARGUMENTS``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or a missing file.
    """
    args = with_defaults(BRINGUP_ARGUMENTS, args)
    slam = parse_bool(args['slam'], 'slam')
    use_ns = parse_bool(args['use_namespace'], 'use_namespace')
    shared = {k: args[k] for k in ('use_sim_time', 'params_file', 'autostart', 'use_respawn',
                                   'use_composition')}
    shared['container_name'] = 'nav2_container'
    namespace = args['namespace'].strip('/') if use_ns else ''
    actions, specs = [], []
    if slam:
        actions += online_sync({'use_sim_time': args['use_sim_time'],
                                'autostart': args['autostart']})
    elif parse_bool(args['use_localization'], 'use_localization'):
        specs += _localization_specs({**shared, 'map': args['map']})
    specs += _navigation_specs({**shared, 'namespace': namespace})
    return actions + _start(specs, shared, namespace)


FRAME_KEYS = frozenset({'base_frame_id', 'odom_frame_id', 'global_frame_id', 'frame_id',
                        'robot_base_frame', 'global_frame', 'local_frame', 'sensor_frame'})
"""Nav2 parameters naming a TF frame (AMCL, map_server, costmaps and their sources, servers)."""


def robot_params(params, namespace, frame_prefix, map_frame='map'):
    """
    Return a Nav2 params file's content for one robot of a fleet.

    Nested under ``namespace`` (nav2_bringup's ``RewrittenYaml(root_key=namespace)``), with
    each frame parameter (:data:`FRAME_KEYS`) other than ``map_frame`` prefixed with
    ``frame_prefix`` (the fleet's robots publish ``rI/odom -> rI/base_footprint`` on the one
    ``/tf``, diff_drive_controller's ``tf_frame_prefix``), and each absolute topic (a
    parameter named ``topic``, ``topic_name`` or ``*_topic``, e.g. an observation source's
    ``/scan``) moved into the namespace. Relative topics resolve in the namespace already.

    :param params: the params file as loaded (dict).
    :param namespace: the robot's namespace without slashes, e.g. ``r1``.
    :param frame_prefix: e.g. ``r1/``.
    :param map_frame: the frame every robot's AMCL localizes in, shared.
    :returns: ``{namespace: params rewritten}`` (a new dict).
    """
    def topic(key):
        return key in ('topic', 'topic_name') or key.endswith('_topic')

    def walk(value, key):
        if isinstance(value, dict):
            return {k: walk(v, k) for k, v in value.items()}
        if isinstance(value, str) and value and isinstance(key, str):
            if key in FRAME_KEYS and value.lstrip('/') != map_frame and \
                    not value.lstrip('/').startswith(frame_prefix):
                return frame_prefix + value.lstrip('/')
            if topic(key) and value.startswith('/') and \
                    not value.startswith(f'/{namespace}/'):
                return f'/{namespace}{value}'
        return value

    return {namespace: walk(params, None)}


def package_home(folder):
    """
    Return ``$ROS_HOME/amr_description/<folder>`` (ROS_HOME defaults to ``~/.ros``), made.

    Where stacks keep the files they derive (a world's true map, a robot's params file).

    :raises OSError: when the folder cannot be made.
    """
    home = os.environ.get('ROS_HOME') or os.path.join(os.path.expanduser('~'), '.ros')
    path = os.path.join(home, PACKAGE, folder)
    os.makedirs(path, exist_ok=True)
    return path


def _robot_params_file(args, namespace):
    """Write ``params_file`` rewritten for ``namespace`` (:func:`robot_params`); its path."""
    import hashlib
    import yaml
    from amr_description.core.yaml_text import safe_load
    path = _params_file(args)
    try:
        with open(path) as f:
            params = safe_load(f)
    except (OSError, yaml.YAMLError) as exc:
        raise LaunchError(f"launch argument 'params_file': cannot read '{path}': "
                          f"{' '.join(str(exc).split())}") from None
    if not isinstance(params, dict):
        raise LaunchError(f"launch argument 'params_file': '{path}' is not a YAML map")
    text = yaml.safe_dump(robot_params(params, namespace, f'{namespace}/'))
    digest = hashlib.sha1(text.encode()).hexdigest()[:12]  # same content, same file
    try:
        out = os.path.join(package_home('params'), f'nav2_params_{namespace}_{digest}.yaml')
        if not os.path.isfile(out):
            with open(out, 'w') as f:
                f.write(text)
    except OSError as exc:
        raise LaunchError(f"launch argument 'params_file': cannot write the params of "
                          f"'{namespace}': {exc}") from None
    return out


def robot_navigation(namespace, args, pose):
    """
    Describe Nav2 for one namespaced robot of a fleet (nav2_bringup's multi-robot bring-up).

    map_server (``map``), AMCL starting at ``pose`` and the navigation servers in
    ``/<namespace>``, composed in ``/<namespace>/nav2_container`` unless
    ``use_composition`` is false, reading ``params_file`` rewritten by :func:`robot_params`
    (frames prefixed ``<namespace>/``), as nav2_bringup's ``RewrittenYaml``, into
    ``$ROS_HOME/amr_description/params/nav2_params_<namespace>_<digest>.yaml``.

    :param namespace: e.g. ``r1``.
    :param args: dict with ``map``, ``params_file``, ``use_sim_time``, ``autostart``,
        ``use_composition`` (missing ones take ``bringup_launch.py``'s defaults).
    :param pose: ``(x, y, yaw)`` of the robot's spawn in the map frame (m, m, rad).
    :returns: list of actions.
    :raises LaunchError: on a missing or unreadable params file or map.
    """
    args = with_defaults(BRINGUP_ARGUMENTS, args)
    shared = {k: args[k] for k in ('use_sim_time', 'autostart', 'use_respawn',
                                   'use_composition')}
    shared.update(params_file=_robot_params_file(args, namespace),
                  container_name='nav2_container')
    specs = _localization_specs({**shared, 'map': args['map']})
    specs += _navigation_specs({**shared, 'namespace': namespace})
    for spec in specs:
        if spec.name == 'amcl':
            spec.parameters.append({'set_initial_pose': True, 'initial_pose.x': pose[0],
                                    'initial_pose.y': pose[1], 'initial_pose.yaw': pose[2]})
    return _start(specs, shared, namespace)


NAV2_STACKS = {
    'online_sync': (online_sync, SLAM_SYNC_ARGUMENTS,
                    "slam_toolbox's online synchronous mapper (no scan the mapper would keep "
                    'is dropped), configured and activated'),
    'slam_toolbox_localization': (
        slam_toolbox_localization, SLAM_LOCALIZATION_ARGUMENTS,
        "slam_toolbox's localization_launch.py: localization on a serialized pose graph "
        '(map_file_name)'),
    'localization': (localization, LOCALIZATION_ARGUMENTS,
                     "nav2_bringup's map_server + amcl + lifecycle_manager_localization"),
    'navigation_launch': (navigation, NAVIGATION_ARGUMENTS,
                          "nav2_bringup's navigation servers + lifecycle_manager_navigation"),
    'bringup': (bringup, BRINGUP_ARGUMENTS,
                "nav2_bringup's localization (or SLAM) + navigation on a running simulator"),
}
"""nav2_bringup's launch files as stacks (see :data:`amr_description.launch.registry.STACKS`)."""
