# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The stacks that replace the tutorial's launch files: ``display``, ``sim`` and ``fleet``.

Each stack is a function ``stack(arguments) -> list of actions`` plus its declared launch
arguments, registered in :data:`amr_description.launch.registry.STACKS`. Arguments are the str
values of ``name:=value`` pairs (see
:func:`amr_description.launch.actions.parse_launch_arguments`). Run a stack with
:class:`amr_description.launch.orchestrator.Orchestrator`::

    args = resolve('sim', ['rtf:=0', 'headless:=true'])
    with Orchestrator(sim(args)) as stack:
        ...
"""

import math
import os

from amr_description.core.description.files import parse_xacro_args
from amr_description.core.description.files import read_description
from amr_description.core.description.urdf_model import parse_xml
from amr_description.launch.actions import ComposableNode
from amr_description.launch.actions import ComposableNodeContainer
from amr_description.launch.actions import DeclareLaunchArgument
from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import Node
from amr_description.launch.actions import OnProcessExit
from amr_description.launch.actions import parse_bool
from amr_description.launch.actions import parse_float
from amr_description.launch.actions import with_defaults
from amr_description.launch.nav_stacks import share_file
from amr_description.web.server import PORT_ARGUMENT

PACKAGE = 'amr_description'

CONTROLLERS = ('joint_state_broadcaster', 'diff_drive_controller')
"""The controllers every stack spawns, in spawn order (one ``spawner`` with both names)."""


def urdf_path():
    """
    Return the stacks' default description, ``<share>/amr_description/urdf/amr.urdf.xacro``.

    The tutorial robot (``urdf/amr.urdf``) with its sensor mount: a 2-D lidar and an IMU
    (xacro arguments ``lidar`` and ``imu``, both true by default).

    :returns: the path (str).
    :raises LaunchError: when the package is not installed.
    """
    return share_file('urdf', 'amr.urdf.xacro')


def read_urdf(path=None, xacro_args=''):
    """
    Return the URDF text given to robot_state_publisher as ``robot_description``.

    As ``Command(['xacro ', path])`` in a launch file: a ``.xacro`` file is expanded with
    ``xacro_args`` (``'name:=value ...'``); a URDF file is read as it is.

    :param path: URDF or xacro file, path or ``package://`` URI (default: :func:`urdf_path`).
    :param xacro_args: xacro arguments, ``name:=value`` words.
    :returns: the URDF text, str.
    :raises LaunchError: one line when the file cannot be read, is empty or xacro fails.
    """
    path = path or urdf_path()
    try:
        return read_description(path, parse_xacro_args(xacro_args))
    except ValueError as exc:
        cause = str(exc).partition(f'{path}: ')[2] or str(exc)
        if cause.startswith('cannot read: '):
            raise LaunchError(f"cannot read URDF '{path}': {cause[13:]}") from None
        raise LaunchError(f"robot description '{path}': {cause}") from None


DESCRIPTION_ARGUMENTS = [
    DeclareLaunchArgument('description', '', 'Robot description file, URDF or xacro (path or '
                          'package:// URI); empty: urdf/amr.urdf.xacro of this package (the '
                          'tutorial robot with a lidar and an IMU)'),
    DeclareLaunchArgument('model', '', 'The same as description (the name used by '
                          'urdf_tutorial display.launch.py)'),
    DeclareLaunchArgument('xacro_args', '', 'Arguments of a xacro description, '
                          '"name:=value name:=value"'),
]
"""The robot description arguments every stack declares."""


def _description(args):
    """Return the URDF text the stack's ``description``/``model``/``xacro_args`` name."""
    path = args.get('description') or args.get('model') or None
    return read_urdf(path, args.get('xacro_args', ''))


DISPLAY_ARGUMENTS = [
    DeclareLaunchArgument('use_sim_time', 'false', 'Use simulation (/clock) time if true'),
    DeclareLaunchArgument('gui', 'true',
                          'Flag to enable joint_state_publisher_gui (sliders in the browser)'),
    DeclareLaunchArgument('viewer', 'true', 'Start the viewer (RViz stand-in in the browser)'),
    DeclareLaunchArgument('viewer_port', '8080', 'TCP port of the viewer page'),
    DeclareLaunchArgument('rviz_config', '',
                          'RViz config (.rviz) the viewer reads, as rviz2 -d: its Fixed Frame '
                          'and displays'),
    DeclareLaunchArgument('gui_port', '8081', 'TCP port of the joint_state_publisher_gui page'),
] + DESCRIPTION_ARGUMENTS

SIM_ARGUMENTS = [
    DeclareLaunchArgument('use_sim_time', 'true', 'Use simulation (/clock) time if true'),
    DeclareLaunchArgument('rtf', '1.0',
                          'Real-time factor of the simulation (0 = as fast as possible)'),
    DeclareLaunchArgument('headless', 'true', 'Run the simulator without a viewer window'),
    DeclareLaunchArgument('robot', 'amr', 'Name of the spawned robot'),
    DeclareLaunchArgument('x', '0.0', 'Spawn position x in the world frame (m)'),
    DeclareLaunchArgument('y', '0.0', 'Spawn position y in the world frame (m)'),
    DeclareLaunchArgument('z', '0.2', 'Spawn position z in the world frame (m)'),
    DeclareLaunchArgument('yaw', '0.0', 'Spawn heading about z (rad)'),
    DeclareLaunchArgument('viewer', 'true', 'Start the viewer (RViz stand-in in the browser)'),
    DeclareLaunchArgument('viewer_port', '8080', 'TCP port of the viewer page'),
    DeclareLaunchArgument('rviz_config', '',
                          'RViz config (.rviz) the viewer reads, as rviz2 -d: its Fixed Frame '
                          'and displays'),
    DeclareLaunchArgument('controllers', ','.join(CONTROLLERS),
                          'Controllers to spawn, in that order (comma-separated names)'),
    DeclareLaunchArgument('world', 'empty',
                          'SDF world: a shipped world (empty, arena, warehouse), a file or a '
                          'package:// URI'),
    DeclareLaunchArgument('bridge_config', '',
                          'ros_gz_bridge YAML naming the ROS side of the gz-sim topics'),
] + DESCRIPTION_ARGUMENTS


FLEET_ARGUMENTS = [
    DeclareLaunchArgument('use_sim_time', 'true', 'Use simulation (/clock) time if true'),
    DeclareLaunchArgument('rtf', '1.0',
                          'Real-time factor of the simulation (0 = as fast as possible)'),
    DeclareLaunchArgument('headless', 'true', 'Run the simulator without a viewer window'),
    DeclareLaunchArgument('robots', '2', 'Number of robots, namespaces r1 ... rN'),
    DeclareLaunchArgument('spacing', '2.0', 'Distance between neighbours on the grid (m)'),
    DeclareLaunchArgument('world', 'empty',
                          'SDF world: a shipped world (empty, arena, warehouse), a file or a '
                          'package:// URI'),
    DeclareLaunchArgument('use_composition', 'true',
                          'Whether to run the robot_state_publishers and static transform '
                          'publishers as composed nodes in one container process (one process '
                          'each if false)'),
    DeclareLaunchArgument('viewer', 'true', 'Start the viewer (RViz stand-in in the browser)'),
    DeclareLaunchArgument('viewer_port', '8080', 'TCP port of the viewer page'),
    DeclareLaunchArgument('rviz_config', '',
                          'RViz config (.rviz) the viewer reads, as rviz2 -d: its Fixed Frame '
                          'and displays'),
] + DESCRIPTION_ARGUMENTS


def _rviz(args):
    """Return the viewer's ``rviz_config`` (a bare name not found here: the package's)."""
    path = args['rviz_config']
    if path and os.path.basename(path) == path and not os.path.exists(path):
        shipped = share_file('config', path)
        path = shipped if os.path.isfile(shipped) else path
    return {'rviz_config': path} if path else {}


def _page(args, name):
    """
    Return the ``parameters`` entry and ``env`` of a page node whose port is argument ``name``.

    The port goes to the node only when the user gave ``name``: then it is exact, and the
    node's error for a port in use names ``name:=N`` (:data:`PORT_ARGUMENT`); otherwise the
    node takes its default port or the next free one.

    :raises LaunchError: when the given value is not a TCP port 1..65535.
    """
    env = {PORT_ARGUMENT: name}
    if name not in args.given:
        return {}, env
    try:
        port = int(args[name])
    except ValueError:
        port = 0
    if not 0 < port < 65536:
        raise LaunchError(f"launch argument '{name}': expected a TCP port 1..65535, got "
                          f"'{args[name]}'")
    return {'port': port}, env


def display(args):
    """
    Describe the ``display`` stack (the tutorial's display.launch.py without RViz).

    robot_state_publisher with ``robot_description`` = the installed URDF;
    joint_state_publisher_gui (``gui:=true``, port ``gui_port``) or joint_state_publisher
    (``gui:=false``), as the tutorial's ``gui`` argument; the viewer with Fixed Frame
    ``base_footprint`` as the tutorial's RViz configuration (``viewer:=true``, port
    ``viewer_port``). Each page's node prints the URL to open.

    :param args: dict of launch-argument values (see ``DISPLAY_ARGUMENTS``; missing ones take
        their declared defaults).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or an unreadable URDF.
    """
    args = with_defaults(DISPLAY_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    gui = parse_bool(args['gui'], 'gui')
    viewer = parse_bool(args['viewer'], 'viewer')
    description = _description(args)
    actions = [
        Node(PACKAGE, 'robot_state_publisher', output='screen',
             parameters=[{'robot_description': description, 'use_sim_time': use_sim_time}]),
    ]
    if gui:
        port, env = _page(args, 'gui_port')
        actions.append(Node(PACKAGE, 'joint_state_publisher_gui', output='screen', env=env,
                            parameters=[{'use_sim_time': use_sim_time, **port}]))
    else:
        actions.append(Node(PACKAGE, 'joint_state_publisher', output='screen',
                            parameters=[{'use_sim_time': use_sim_time}]))
    if viewer:
        port, env = _page(args, 'viewer_port')
        actions.append(Node(PACKAGE, 'viewer', output='screen', env=env,
                            parameters=[{'use_sim_time': use_sim_time,
                                         'fixed_frame': 'base_footprint', **port,
                                         **_rviz(args)}]))
    return actions


def sim(args):
    """
    Describe the ``sim`` stack (the tutorial's Gazebo + ros2_control launch file).

    mujoco_sim (``real_time_factor``, ``headless``, ``/diff_drive_controller/odom`` remapped
    to ``/odom``); robot_state_publisher with ``use_sim_time``; ``create -topic
    robot_description -name ROBOT -x X -y Y -z Z -Y YAW``; when ``create`` exits successfully
    ``spawner joint_state_broadcaster diff_drive_controller`` (the tutorial chains two
    spawners with ``OnProcessExit``; upstream's spawner takes several names and activates
    them in that order, and one process instead of two started one after the other saves a
    Python start-up, ~0.3 s of CPU, from the critical path); the viewer (Fixed Frame
    ``odom``, port ``viewer_port``) unless ``viewer:=false``. A description without
    ``<ros2_control>`` (driven by gz-sim systems) gets no spawner; ``bridge_config:=FILE``
    is the simulator's ``bridge_config`` parameter.

    :param args: dict of launch-argument values (see ``SIM_ARGUMENTS``; missing ones take
        their declared defaults).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or an unreadable URDF.
    """
    args = with_defaults(SIM_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    rtf = parse_float(args['rtf'], 'rtf')
    if rtf < 0:
        raise LaunchError(f"launch argument 'rtf': expected a number >= 0, got '{args['rtf']}'")
    headless = parse_bool(args['headless'], 'headless')
    robot = args['robot'] or 'amr'
    pose = {k: parse_float(args[k], k) for k in ('x', 'y', 'z', 'yaw')}
    viewer = parse_bool(args['viewer'], 'viewer')
    viewer_port, viewer_env = _page(args, 'viewer_port')
    description = _description(args)

    mujoco_sim = Node(
        PACKAGE, 'mujoco_sim', output='screen', required=True,
        parameters=[{'real_time_factor': rtf, 'headless': headless,
                     'bridge_config': args['bridge_config'], 'world': args['world']}],
        remappings=[('/diff_drive_controller/odom', '/odom')])
    robot_state_publisher = Node(
        PACKAGE, 'robot_state_publisher', output='screen',
        parameters=[{'robot_description': description, 'use_sim_time': use_sim_time}])
    create = Node(
        PACKAGE, 'create', output='screen',
        arguments=['-topic', 'robot_description', '-name', robot,
                   '-x', repr(pose['x']), '-y', repr(pose['y']), '-z', repr(pose['z']),
                   '-Y', repr(pose['yaw'])])
    controllers = [name.strip() for name in args['controllers'].split(',') if name.strip()]
    if not controllers:
        raise LaunchError("launch argument 'controllers': expected comma-separated controller "
                          f"names, got '{args['controllers']}'")
    spawner = Node(
        PACKAGE, 'spawner', output='screen',
        arguments=controllers)
    actions = [mujoco_sim, robot_state_publisher, create]
    if parse_xml(description, 'description').find('ros2_control') is not None:
        actions.append(OnProcessExit(create, [spawner], only_on_success=True))
    if viewer:
        actions.append(Node(PACKAGE, 'viewer', output='screen', env=viewer_env,
                            parameters=[{'use_sim_time': use_sim_time, 'fixed_frame': 'odom',
                                         'world': args['world'], **viewer_port,
                                         **_rviz(args)}]))
    return actions


def fleet_grid(count, spacing):
    """
    Return the spawn positions of ``count`` robots on a square grid.

    Robots fill rows of ``ceil(sqrt(count))`` along +x, rows stacked along +y, starting at the
    world origin.

    :param count: number of robots, >= 1.
    :param spacing: distance between neighbours, m (> 0).
    :returns: list of ``(x, y)`` in m, robot ``rI`` at index ``I - 1``.
    """
    columns = max(1, math.ceil(math.sqrt(count)))
    return [((i % columns) * spacing, (i // columns) * spacing) for i in range(count)]


def fleet(args, odom_in_world=True):
    """
    Describe the ``fleet`` stack: one simulator and ``robots`` namespaced robots on a grid.

    mujoco_sim (``real_time_factor``, ``headless``; ``/rI/diff_drive_controller/odom``
    remapped to ``/rI/odom`` for every robot). For each robot ``rI`` (I = 1 ... N), in
    namespace ``/rI``: robot_state_publisher with ``frame_prefix`` ``rI/`` (publishes
    ``/rI/robot_description``, listens to ``/rI/joint_states``), all of them composed in one
    ``component_container`` process named ``robot_state_publisher_container`` unless
    ``use_composition:=false`` (one process per robot; a process costs about a second of CPU
    to start and competes with the simulator for the CPU); ``create -topic
    /rI/robot_description -name rI -robot_namespace rI -x X -y Y -z 0.2`` at its grid
    position (:func:`fleet_grid`); when it exits successfully one ``spawner -c
    /rI/controller_manager joint_state_broadcaster diff_drive_controller`` (one process per
    robot rather than two: a Python process start costs about a second of CPU). The
    controllers run in ``/rI`` (diff_drive_controller's default ``tf_frame_prefix_enable``
    gives frames ``rI/odom`` and ``rI/base_link``), cmd_vel is
    ``/rI/diff_drive_controller/cmd_vel``. A static transform ``world -> rI/odom`` per robot,
    at its grid position (``/rI/static_transform_publisher``, tf2_ros'
    ``StaticTransformBroadcasterNode``, composed with the robot_state_publishers unless
    ``use_composition:=false``), joins the robots' TF trees in the simulator's ``world``
    frame, as a multi-robot launch file does with tf2_ros' static_transform_publisher. The
    viewer (unless ``viewer:=false``, port ``viewer_port``) shows every robot with Fixed Frame
    ``world``, each robot's ground-truth trail, and its pad drives ``r1`` (its status counts
    ``/r1/joint_states``).

    :param args: dict of launch-argument values (see ``FLEET_ARGUMENTS``; missing ones take
        their declared defaults).
    :param odom_in_world: publish the static ``world -> rI/odom`` transforms (False when each
        robot's AMCL publishes ``map -> rI/odom``).
    :returns: list of actions.
    :raises LaunchError: on a bad argument value or an unreadable URDF.
    """
    args = with_defaults(FLEET_ARGUMENTS, args)
    use_sim_time = parse_bool(args['use_sim_time'], 'use_sim_time')
    rtf = parse_float(args['rtf'], 'rtf')
    if rtf < 0:
        raise LaunchError(f"launch argument 'rtf': expected a number >= 0, got '{args['rtf']}'")
    headless = parse_bool(args['headless'], 'headless')
    try:
        count = int(args['robots'])
    except ValueError:
        count = 0
    if count < 1:
        raise LaunchError(f"launch argument 'robots': expected an integer >= 1, got "
                          f"'{args['robots']}'")
    spacing = parse_float(args['spacing'], 'spacing')
    if not spacing > 0:
        raise LaunchError(f"launch argument 'spacing': expected a number > 0, got "
                          f"'{args['spacing']}'")
    use_composition = parse_bool(args['use_composition'], 'use_composition')
    viewer = parse_bool(args['viewer'], 'viewer')
    viewer_port, viewer_env = _page(args, 'viewer_port')
    description = _description(args)
    names = [f'r{i}' for i in range(1, count + 1)]
    grid = fleet_grid(count, spacing)
    actions = [Node(
        PACKAGE, 'mujoco_sim', output='screen', required=True,
        parameters=[{'real_time_factor': rtf, 'headless': headless, 'world': args['world']}],
        remappings=[(f'/{ns}/diff_drive_controller/odom', f'/{ns}/odom') for ns in names])]

    def rsp_parameters(ns):
        return [{'robot_description': description, 'use_sim_time': use_sim_time,
                 'frame_prefix': f'{ns}/'}]

    def odom_frame(ns, x, y):
        return {'translation.x': float(x), 'translation.y': float(y), 'frame_id': 'world',
                'child_frame_id': f'{ns}/odom', 'use_sim_time': use_sim_time}

    if use_composition:
        composed = [ComposableNode(PACKAGE, 'amr_description::RobotStatePublisher',
                                   namespace=ns, parameters=rsp_parameters(ns))
                    for ns in names]
        composed += [ComposableNode(PACKAGE, 'amr_description::StaticTransformBroadcasterNode',
                                    name='static_transform_publisher', namespace=ns,
                                    parameters=[odom_frame(ns, x, y)])
                     for ns, (x, y) in zip(names, grid) if odom_in_world]
        actions.append(ComposableNodeContainer(
            'robot_state_publisher_container', output='screen',
            parameters=[{'use_sim_time': use_sim_time}],
            composable_node_descriptions=composed))
    for ns, (x, y) in zip(names, grid):
        create = Node(
            PACKAGE, 'create', output='screen',
            arguments=['-topic', f'/{ns}/robot_description', '-name', ns,
                       '-robot_namespace', ns, '-x', repr(x), '-y', repr(y), '-z', '0.2'])
        spawner = Node(
            PACKAGE, 'spawner', output='screen',
            arguments=['-c', f'/{ns}/controller_manager', *CONTROLLERS])
        if not use_composition:
            actions.append(Node(PACKAGE, 'robot_state_publisher', namespace=ns,
                                output='screen', parameters=rsp_parameters(ns)))
        if not use_composition and odom_in_world:
            actions.append(Node(PACKAGE, 'static_transform_publisher',
                                name='static_transform_publisher', namespace=ns,
                                output='screen',
                                parameters=[{'use_sim_time': use_sim_time}],
                                arguments=['--x', repr(float(x)), '--y', repr(float(y)),
                                           '--frame-id', 'world',
                                           '--child-frame-id', f'{ns}/odom']))
        actions += [create, OnProcessExit(create, [spawner], only_on_success=True)]
    if viewer:
        actions.append(Node(PACKAGE, 'viewer', output='screen', env=viewer_env, parameters=[{
            'use_sim_time': use_sim_time, 'fixed_frame': 'world', **viewer_port,
            'world': args['world'], **_rviz(args),
            'robot_description_topics': [f'/{ns}/robot_description' for ns in names],
            'odometry_topics': [f'/{ns}/ground_truth/odom' for ns in names],
            'cmd_vel_topic': f'/{names[0]}/diff_drive_controller/cmd_vel',
            'frame_id': f'{names[0]}/base_link'}],
            remappings=[('/joint_states', f'/{names[0]}/joint_states')]))
    return actions
