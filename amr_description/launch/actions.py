# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Descriptions of what a stack starts: processes, ROS nodes, exit handlers, launch arguments.

These mirror the entities of upstream ``launch`` / ``launch_ros`` (ROS 2 Jazzy) that the
tutorial's launch files use: ``ExecuteProcess``, ``launch_ros.actions.Node``,
``RegisterEventHandler(OnProcessExit(...))`` and ``DeclareLaunchArgument``. They only describe;
:class:`amr_description.launch.orchestrator.Orchestrator` runs them. Nothing here imports rclpy.
"""

import os
import tempfile

import yaml

_TRUE = ('true', '1', 'yes', 'on')
_FALSE = ('false', '0', 'no', 'off')


class LaunchError(Exception):
    """A user error in a stack description or its arguments (printed as one line)."""


def parse_bool(text, name='value'):
    """
    Parse a launch-argument boolean as upstream launch conditions do.

    :param text: ``'true'``/``'false'``/``'1'``/``'0'`` (any case; also yes/no/on/off), or bool.
    :param name: argument name, for the error message.
    :returns: the bool.
    :raises LaunchError: when ``text`` is not a boolean.
    """
    if isinstance(text, bool):
        return text
    value = str(text).strip().lower()
    if value in _TRUE:
        return True
    if value in _FALSE:
        return False
    raise LaunchError(f"launch argument '{name}': expected true or false, got '{text}'")


def parse_float(text, name='value'):
    """
    Parse a launch-argument number.

    :param text: a decimal number as str (or a number).
    :param name: argument name, for the error message.
    :returns: the float.
    :raises LaunchError: when ``text`` is not a finite number.
    """
    try:
        value = float(text)
    except (TypeError, ValueError):
        value = float('nan')
    if value != value or value in (float('inf'), float('-inf')):
        raise LaunchError(f"launch argument '{name}': expected a number, got '{text}'")
    return value


class Arguments(dict):
    """Launch-argument values; ``given`` holds the names the user set."""

    given = frozenset()


def with_defaults(declared, args):
    """
    Return ``args`` completed with the default values of the ``declared`` arguments.

    :param declared: :class:`DeclareLaunchArgument` list.
    :param args: dict of values (an :class:`Arguments` keeps its ``given``).
    :returns: :class:`Arguments`.
    """
    values = Arguments((d.name, d.default_value) for d in declared)
    values.update(args)
    values.given = args.given if isinstance(args, Arguments) else frozenset(args)
    return values


class DeclareLaunchArgument:
    """
    A launch argument set as ``name:=value`` (``launch.actions.DeclareLaunchArgument``).

    :param name: argument name.
    :param default_value: default as str (None: the argument is mandatory).
    :param description: one-line help shown by ``--show-args``.
    :param choices: optional list of allowed str values.
    """

    def __init__(self, name, default_value=None, description='no description given',
                 choices=None):
        """Store the declaration; see the class docstring for the parameters."""
        self.name = name
        self.default_value = None if default_value is None else str(default_value)
        self.description = description
        self.choices = list(choices) if choices else None


def parse_launch_arguments(declared, argv):
    """
    Resolve ``name:=value`` command-line arguments against declared launch arguments.

    :param declared: list of :class:`DeclareLaunchArgument`.
    :param argv: list of ``'name:=value'`` strings.
    :returns: dict name -> str value, with defaults filled in.
    :raises LaunchError: on a malformed argument, an undeclared name, a value outside
        ``choices`` or a missing mandatory argument (message as ``ros2 launch`` words it).
    """
    by_name = {d.name: d for d in declared}
    values = {}
    for arg in argv:
        name, sep, value = arg.partition(':=')
        if not sep or not name:
            raise LaunchError(
                f"malformed launch argument '{arg}', expected format '<name>:=<value>'")
        if name not in by_name:
            known = ', '.join(sorted(by_name)) or 'none'
            raise LaunchError(f"unknown launch argument '{name}' (declared: {known})")
        values[name] = value
    for decl in declared:
        if decl.name not in values:
            if decl.default_value is None:
                raise LaunchError(
                    f"Included launch description missing required argument '{decl.name}' "
                    f"(description: '{decl.description}'), given: [{', '.join(values)}]")
            values[decl.name] = decl.default_value
        if decl.choices is not None and values[decl.name] not in decl.choices:
            raise LaunchError(
                f"Argument '{decl.name}' provided value '{values[decl.name]}' is not valid. "
                'Valid options are: ' + str(decl.choices))
    return values


def format_arguments(declared):
    """
    Format declared launch arguments the way ``ros2 launch --show-args`` prints them.

    :param declared: list of :class:`DeclareLaunchArgument`.
    :returns: the text, ending with a newline.
    """
    if not declared:
        return 'No arguments.\n'
    lines = ["Arguments (pass arguments as '<name>:=<value>'):", '']
    for decl in declared:
        lines.append(f"    '{decl.name}':")
        lines.append(f'        {decl.description}')
        if decl.choices is not None:
            lines.append(f'        Valid choices are: {decl.choices}')
        if decl.default_value is None:
            lines.append('        (no default)')
        else:
            lines.append(f"        (default: '{decl.default_value}')")
        lines.append('')
    return '\n'.join(lines)


class Process:
    """
    A process to run (like ``launch.actions.ExecuteProcess``).

    :param cmd: argv, a list of str (the first is the executable).
    :param name: base of the process label; the orchestrator appends ``-N`` (default: the
        basename of ``cmd[0]``), so output reads ``[name-N] ...`` as in launch.
    :param output: ``'screen'`` (stdout and stderr printed with the ``[name-N]`` prefix) or
        ``'log'`` (stdout only to the orchestrator's log file, stderr still on screen).
    :param respawn: restart the process whenever it exits (until shutdown).
    :param respawn_delay: seconds to wait before a respawn.
    :param required: when the process exits, shut the whole stack down (launch's
        ``on_exit=Shutdown()``).
    :param env: extra environment variables, dict (merged over the orchestrator's).
    :param cwd: working directory or None.
    """

    def __init__(self, cmd, name=None, output='screen', respawn=False, respawn_delay=0.0,
                 required=False, env=None, cwd=None):
        """Store the description; see the class docstring for the parameters."""
        if not cmd:
            raise LaunchError('a process needs a non-empty command')
        if output not in ('screen', 'log', 'both'):
            raise LaunchError(f"output must be 'screen', 'log' or 'both', got '{output}'")
        self._cmd = [str(c) for c in cmd]
        self.name = name or os.path.basename(self._cmd[0])
        self.output = output
        self.respawn = bool(respawn)
        self.respawn_delay = float(respawn_delay or 0.0)
        self.required = bool(required)
        self.env = dict(env or {})
        self.cwd = cwd

    def build_cmd(self, params_dir=None):
        """
        Return the argv to execute.

        :param params_dir: unused for plain processes (see :meth:`Node.build_cmd`).
        :returns: list of str.
        """
        return list(self._cmd)

    def temp_files(self):
        """Return files created by :meth:`build_cmd` that the orchestrator removes at the end."""
        return []


def find_executable(package, executable):
    """
    Find ``<prefix>/lib/<package>/<executable>`` through the ament index, as ``ros2 run``.

    :param package: package name.
    :param executable: executable name.
    :returns: the absolute path.
    :raises LaunchError: when the package or the executable is not found.
    """
    from ament_index_python.packages import get_package_prefix
    from ament_index_python.packages import PackageNotFoundError
    try:
        prefix = get_package_prefix(package)
    except (PackageNotFoundError, ValueError, LookupError):
        raise LaunchError(f"package '{package}' not found") from None
    libexec = os.path.join(prefix, 'lib', package)
    path = os.path.join(libexec, executable)
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        raise LaunchError(
            f"executable '{executable}' not found on the libexec directory '{libexec}'")
    return path


def params_key(node_name, namespace):
    """
    Return the YAML key of a node's parameter dict, as ``launch_ros`` Node writes it.

    ``launch_ros``' ``_create_params_file_from_dict`` keys the dict with the node's full name
    when both name and namespace are given (``is_node_name_fully_specified``), so that only
    that node of the process takes the parameters (a process may hold more nodes: the
    simulator's controller manager and controllers); otherwise with ``/**`` (every node).

    :param node_name: node name or None.
    :param namespace: namespace (leading ``/``) or None.
    :returns: e.g. ``/mujoco_sim``, ``/r1/mujoco_sim`` or ``/**``.
    """
    if node_name is None or namespace is None:
        return '/**'
    return ('' if namespace in ('', '/') else namespace.rstrip('/')) + '/' + node_name


def write_params_file(params, directory=None, key='/**'):
    """
    Write a parameter dict to a temporary YAML file as ``launch_ros`` does.

    The file holds ``{key: {'ros__parameters': params}}`` (:func:`params_key`).

    :param params: dict parameter name -> value (bool, int, float, str or lists of those).
    :param directory: where to create the file (default: the system temp directory).
    :param key: the node name the parameters are for, ``/**`` for any node.
    :returns: the file path (prefix ``launch_params_``).
    """
    with tempfile.NamedTemporaryFile(mode='w', prefix='launch_params_', dir=directory,
                                     delete=False) as f:
        yaml.safe_dump({key: {'ros__parameters': dict(params)}}, f, default_flow_style=False)
        return f.name


def _normalize_namespace(namespace):
    if namespace is None:
        return None
    return namespace if namespace.startswith('/') else '/' + namespace


def _node_identity(owner, label, name, namespace, parameters, remappings):
    """Set a node description's name, namespace, parameters and remappings (checked)."""
    owner.node_name = name
    owner.namespace = _normalize_namespace(namespace)
    owner.parameters = list(parameters or [])
    owner.remappings = [(str(a), str(b)) for a, b in (remappings or [])]
    for params in owner.parameters:
        if not isinstance(params, (dict, str, os.PathLike)):
            raise LaunchError(f'parameters of {label}: expected dicts or file paths, '
                              f'got {type(params).__name__}')


def _ros_args(node_name, namespace, parameters, remappings, params_dir, temp_files):
    """
    Return ``--ros-args`` and the node's remappings and parameter files (launch_ros order).

    Parameter dicts are written with :func:`write_params_file` under :func:`params_key`; their
    paths are appended to ``temp_files``.
    """
    args = ['--ros-args']
    if node_name is not None:
        args += ['-r', f'__node:={node_name}']
    if namespace is not None:
        args += ['-r', f'__ns:={namespace}']
    for params in parameters:
        if isinstance(params, dict):
            file_path = write_params_file(params, params_dir, params_key(node_name, namespace))
            temp_files.append(file_path)
        else:
            file_path = os.fspath(params)
        args += ['--params-file', file_path]
    for source, target in remappings:
        args += ['-r', f'{source}:={target}']
    return args


class Node(Process):
    """
    A ROS node to run (like ``launch_ros.actions.Node``).

    The command line is built as launch_ros builds it::

        <prefix>/lib/<package>/<executable> [arguments] --ros-args [-r __node:=NAME]
            [-r __ns:=/NS] [--params-file FILE]... [-r FROM:=TO]...

    :param package: package name.
    :param executable: executable name, resolved with :func:`find_executable`.
    :param name: node name (``-r __node:=``), or None to keep the node's own.
    :param namespace: node namespace (``-r __ns:=``, a leading ``/`` is added), or None.
    :param parameters: list of dicts (each written to a ``launch_params_*`` YAML file) and
        parameter-file paths (str or path-like), passed in order with ``--params-file``.
    :param remappings: list of ``(from, to)`` pairs.
    :param arguments: extra arguments placed before ``--ros-args``.
    :param exe_path: use this path instead of resolving the executable (tests).
    :param kwargs: :class:`Process` options (output, respawn, respawn_delay, required, env,
        cwd).
    """

    def __init__(self, package, executable, name=None, namespace=None, parameters=None,
                 remappings=None, arguments=None, exe_path=None, **kwargs):
        """Store the description; see the class docstring for the parameters."""
        self.package = package
        self.executable = executable
        _node_identity(self, executable, name, namespace, parameters, remappings)
        self.arguments = [str(a) for a in (arguments or [])]
        self.exe_path = exe_path
        self._temp_files = []
        super().__init__([exe_path or executable], name=executable, **kwargs)

    def build_cmd(self, params_dir=None):
        """
        Return the argv; parameter dicts are written to fresh temporary YAML files.

        :param params_dir: directory for the parameter files (default: system temp dir).
        :returns: list of str.
        :raises LaunchError: when the executable cannot be found.
        """
        path = self.exe_path or find_executable(self.package, self.executable)
        return [path] + self.arguments + _ros_args(
            self.node_name, self.namespace, self.parameters, self.remappings, params_dir,
            self._temp_files)

    def temp_files(self):
        """Return the parameter files written so far by :meth:`build_cmd`."""
        return list(self._temp_files)


class ComposableNode:
    """
    A node to load into a container (like ``launch_ros.descriptions.ComposableNode``).

    :param package: package of the plugin (documentation; the plugin name says it).
    :param plugin: registered plugin name, e.g. ``amr_description::RobotStatePublisher``
        (:data:`amr_description.nodes.component_container.COMPONENT_GROUP`).
    :param name: node name (``-r __node:=``), or None to keep the node's own.
    :param namespace: node namespace (``-r __ns:=``, a leading ``/`` is added), or None.
    :param parameters: list of dicts and parameter-file paths, as :class:`Node`.
    :param remappings: list of ``(from, to)`` pairs.
    """

    def __init__(self, package, plugin, name=None, namespace=None, parameters=None,
                 remappings=None):
        """Store the description; see the class docstring for the parameters."""
        self.package = package
        self.plugin = plugin
        _node_identity(self, plugin, name, namespace, parameters, remappings)


class ComposableNodeContainer(Node):
    """
    A container process with nodes loaded into it (like ``launch_ros``'s action).

    The container is ``component_container`` of this package
    (:mod:`amr_description.nodes.component_container`); the composable nodes are handed to it
    in a ``launch_components_*`` YAML file (``--nodes FILE``), each with its own ROS
    arguments, instead of ``LoadNode`` service calls.

    :param name: the container's node name.
    :param namespace: the container's namespace (``''`` or None: none).
    :param composable_node_descriptions: list of :class:`ComposableNode`.
    :param package: package of the container executable (default ``amr_description``).
    :param executable: container executable (default ``component_container``).
    :param kwargs: :class:`Node` options (parameters, remappings, output, exe_path...).
    """

    def __init__(self, name, namespace=None, composable_node_descriptions=None,
                 package='amr_description', executable='component_container', **kwargs):
        """Store the description; see the class docstring for the parameters."""
        self.composable_node_descriptions = list(composable_node_descriptions or [])
        super().__init__(package, executable, name=name, namespace=namespace or None,
                         **kwargs)

    def build_cmd(self, params_dir=None):
        """
        Return the argv; writes the component list and the nodes' parameter files.

        :param params_dir: directory for the files (default: system temp dir).
        :returns: list of str.
        :raises LaunchError: when the executable cannot be found.
        """
        entries = [{'plugin': node.plugin,
                    'ros_args': _ros_args(node.node_name, node.namespace, node.parameters,
                                          node.remappings, params_dir, self._temp_files)}
                   for node in self.composable_node_descriptions]
        with tempfile.NamedTemporaryFile(mode='w', prefix='launch_components_', dir=params_dir,
                                         suffix='.yaml', delete=False) as f:
            yaml.safe_dump(entries, f, default_flow_style=False)
        self._temp_files.append(f.name)
        self.arguments = ['--nodes', f.name]
        return super().build_cmd(params_dir)


class OnProcessExit:
    """
    Start actions when a target process exits (like ``launch.event_handlers.OnProcessExit``).

    :param target_action: the :class:`Process` to watch.
    :param on_exit: list of :class:`Process` (or other handlers) to start then.
    :param only_on_success: start them only when the exit code is 0 (otherwise log that they
        are skipped); upstream starts them on any exit.
    """

    def __init__(self, target_action, on_exit, only_on_success=False):
        """Store the handler; see the class docstring for the parameters."""
        self.target_action = target_action
        self.on_exit = list(on_exit) if isinstance(on_exit, (list, tuple)) else [on_exit]
        self.only_on_success = only_on_success


def share_file(folder, name, package='amr_description'):
    """
    Return the path of ``folder/name`` in ``package``'s share directory (ament index).

    :raises LaunchError: when the package is not installed.
    """
    from ament_index_python.packages import get_package_share_directory
    from ament_index_python.packages import PackageNotFoundError
    try:
        share = get_package_share_directory(package)
    except (PackageNotFoundError, ValueError, LookupError):
        raise LaunchError(f"package '{package}' not found") from None
    return os.path.join(share, folder, name)
