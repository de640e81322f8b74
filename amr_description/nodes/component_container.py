# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``component_container``: several nodes in one process (the role of rclcpp_components').

A fleet runs one robot_state_publisher per robot. As separate processes each one pays a
Python and rclpy start-up (about a second of CPU, most of it importing the URDF loader's
yourdfpy and trimesh) and competes with the simulator for the CPU; composed in one
container the imports are paid once, the nodes share one executor (one thread) and, when
the container and a node both use sim time, the container's one /clock subscription sets
the node's clock (rclpy's ``TimeSource.attach_clock``) instead of one subscription per node.

Command line::

    component_container --nodes FILE [--ros-args ...]
    component_container_isolated --nodes FILE [--ros-args ...]

``component_container_isolated`` (nav2_bringup's container) spins each node on an executor and
thread of its own (:class:`IsolatedSpinner`), so that a node waiting in a callback (a lifecycle
manager's command) never holds up the others. A node's ``companion_nodes`` (a Nav2 server's
costmap node) are spun, shared-clocked and destroyed with it. Both containers let their nodes
share one bond endpoint per topic (:func:`amr_description.ros.bond.share_endpoints`) and one
TF listener thread (:func:`amr_description.ros.transforms.share_listener_threads`).

``FILE`` is a YAML list, one entry per node, in load order, as the orchestrator's
:class:`amr_description.launch.actions.ComposableNodeContainer` writes it::

    - plugin: amr_description::RobotStatePublisher
      ros_args: [--ros-args, -r, __ns:=/r1, --params-file, /tmp/launch_params_x]

``plugin`` names an entry point of group :data:`COMPONENT_GROUP` (the package's
composable nodes, as rclcpp_components' registry names a class). ``ros_args`` are that node's
own ROS arguments (node name and namespace remappings, ``--params-file``, other remappings);
as in rclcpp_components, a component does not take the container's global arguments. The
container's own node is named ``ComponentManager`` (upstream's default; launch renames it
with ``-r __node:=NAME``).

A node that cannot be loaded (unknown plugin, a refused parameter or description) is one
error line, ``Failed to load component 'PLUGIN' (ARGS): REASON``, and the container keeps
serving the others, as a container does when a ``LoadNode`` request fails. A file that cannot
be read or is not such a list is one error line and exit code 1. Not offered: the
``~/_container/load_node``, ``unload_node`` and ``list_nodes`` services (the
composition_interfaces package is not built here), so ``ros2 component`` does not apply; the
composed nodes themselves are ordinary nodes to ``ros2 node``, ``ros2 param`` and
``ros2 topic``.
"""

import argparse
from importlib.metadata import entry_points
import sys
import threading

from amr_description.core.yaml_text import safe_load
from amr_description.ros import bond
from amr_description.ros import shutdown
from amr_description.ros import transforms
from amr_description.ros.node import Node
from amr_description.ros.sim_time import take_over_time_source
from rclpy.exceptions import InvalidParameterTypeException
from rclpy.exceptions import InvalidParameterValueException
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.executors import SingleThreadedExecutor
import yaml

COMPONENT_GROUP = 'amr_description.components'
"""Entry-point group of the composable nodes (``amr_description::RobotStatePublisher``...)."""


class ComponentError(Exception):
    """A component list or one of its entries is not usable (one-line message)."""


def read_components(path):
    """
    Read a component list file (module docstring).

    :param path: YAML file path.
    :returns: list of ``(plugin, ros_args)``, ``plugin`` a str, ``ros_args`` a list of str.
    :raises ComponentError: unreadable file, or not a list of ``{plugin, ros_args}`` maps.
    """
    try:
        with open(path) as f:
            data = safe_load(f)
    except (OSError, yaml.YAMLError) as exc:
        raise ComponentError(f'cannot read --nodes {path}: {" ".join(str(exc).split())}')
    if not isinstance(data, list):
        raise ComponentError(f'--nodes {path}: expected a list of components')
    components = []
    for index, entry in enumerate(data):
        plugin = entry.get('plugin') if isinstance(entry, dict) else None
        ros_args = entry.get('ros_args', []) if isinstance(entry, dict) else None
        if not isinstance(plugin, str) or not isinstance(ros_args, list):
            raise ComponentError(f'--nodes {path}: entry {index}: expected a map with a '
                                 'string plugin and a list ros_args')
        components.append((plugin, [str(arg) for arg in ros_args]))
    return components


def registry():
    """Return dict plugin name -> entry point of :data:`COMPONENT_GROUP`."""
    return {ep.name: ep for ep in entry_points(group=COMPONENT_GROUP)}


def preload(components, plugins):
    """
    Import the modules of the listed components before any of them is created.

    A lifecycle manager loaded early starts its bringup at once; the later components' imports
    (numpy, SciPy, scikit-image: seconds of the interpreter lock on a loaded 2-core machine)
    then kept the managed nodes' bond threads from sending a heartbeat, and the manager gave
    up on a bond after its 2 s ("Server map_server was unable to be reached after 2.00s by
    bond", docs/navigation.md). A plugin that cannot be imported is reported by
    :meth:`ComponentContainer.load` when its turn comes.

    :param components: ``(plugin, ros_args)`` pairs, as :func:`read_components` returns.
    :param plugins: :func:`registry` result.
    """
    for plugin, _ in components:
        if plugin in plugins:
            try:
                plugins[plugin].load()
            except Exception:  # noqa: B902 - load() says what failed, in the component's turn
                pass


class ComponentContainer(Node):
    """The container's own node; loads and owns the composed nodes."""

    def __init__(self, **kwargs):
        """
        Create the node ``ComponentManager`` (renamed by the command line).

        :param kwargs: ``rclpy.node.Node`` options.
        """
        super().__init__('ComponentManager', **kwargs)
        self.components = []

    def load(self, plugin, ros_args, plugins):
        """
        Create the node ``plugin`` with its own ``ros_args``; log one line on failure.

        :param plugin: registered plugin name.
        :param ros_args: the node's ROS arguments (``--ros-args ...``).
        :param plugins: :func:`registry` result.
        :returns: the node, or None when it could not be loaded.
        """
        try:
            if plugin not in plugins:
                known = ', '.join(sorted(plugins)) or 'none'
                raise ComponentError(f'unknown plugin (registered: {known})')
            factory = plugins[plugin].load()
            node = factory(cli_args=ros_args, use_global_arguments=False)
        except (ComponentError, InvalidParameterTypeException, InvalidParameterValueException,
                ParameterException, ValueError, ImportError, RuntimeError) as exc:
            self.get_logger().error(f"Failed to load component '{plugin}' "
                                    f"({' '.join(ros_args)}): {' '.join(str(exc).split())}")
            return None
        for each in [node] + list(getattr(node, 'companion_nodes', ())):
            self._share_clock(each)
        self.components.append(node)
        self.get_logger().info(f"Loaded component '{plugin}' as "
                               f"'{node.get_fully_qualified_name()}'")
        return node

    def _share_clock(self, node):
        """
        Give ``node``'s clocks the container's sim time instead of its own /clock subscription.

        Only when both use sim time: one /clock subscription serves every composed node (each
        of its own costs a callback per /clock message, ~100 Hz of sim time per node). A node
        whose ``use_sim_time`` differs from the container's keeps its own time source.
        """
        own = self._time_source
        if not own.ros_time_is_active:
            return
        source = take_over_time_source(node)
        if source is not None:
            for clock in list(source._associated_clocks):
                own.attach_clock(clock)


class IsolatedSpinner:
    """
    One composed node spun on an executor and thread of its own (``component_container_isolated``).

    The node's ``companion_nodes`` (a Nav2 server's costmap node) share its executor, as they
    share its process when it runs alone. An exception
    escaping a callback is one error line naming the node and sets :attr:`failed`: the
    container then stops, as a process whose node raised ends.

    :param node: the loaded node.
    :param failed: ``threading.Event`` set when the node's executor raised.
    """

    def __init__(self, node, failed):
        """Create the executor with the node and its companions, and start the thread."""
        self.node = node
        self.nodes = [node] + list(getattr(node, 'companion_nodes', ()))
        self.executor = SingleThreadedExecutor(context=node.context)
        for each in self.nodes:
            self.executor.add_node(each)
        self._failed = failed
        self.thread = threading.Thread(target=self._spin, daemon=True,
                                       name=node.get_fully_qualified_name())
        self.thread.start()

    def _spin(self):
        try:
            self.executor.spin()
        except ExternalShutdownException:
            pass
        except Exception as exc:  # noqa: B902 - one line, then the container stops
            if self.node.context.ok() and not shutdown.interrupted():
                self.node.get_logger().error(
                    f'{type(exc).__name__}: {" ".join(str(exc).split())}')
                self._failed.set()

    def stop(self):
        """Shut the executor down and join the thread (up to 2 s)."""
        try:
            self.executor.shutdown(timeout_sec=1.0)
        except Exception:  # noqa: B902 - best effort at exit
            pass
        self.thread.join(timeout=2.0)


def build_parser(prog='component_container'):
    """Return the argument parser of ``component_container`` (or of ``prog``)."""
    parser = argparse.ArgumentParser(
        prog=prog,
        description='Run several composable nodes of amr_description in one process.')
    parser.add_argument('--nodes', required=True, metavar='FILE',
                        help='YAML list of {plugin, ros_args} to load, in order')
    return parser


def main(args=None, isolated=False):
    """
    Load the components of ``--nodes`` and spin them until Ctrl-C.

    :param args: command line without the program name (default ``sys.argv[1:]``).
    :param isolated: one executor and thread per component (:class:`IsolatedSpinner`), as
        rclcpp_components' ``component_container_isolated``; otherwise all share one
        single-threaded executor, as ``component_container``.
    :returns: 0 on a clean shutdown, 1 when a component's executor raised (isolated).
    :raises SystemExit: code 1 after one error line when the ROS arguments cannot be parsed
        or the component list cannot be read (:mod:`amr_description.ros.shutdown`).
    """
    prog = 'component_container_isolated' if isolated else 'component_container'
    argv = [prog] + (sys.argv[1:] if args is None else list(args))
    opts = build_parser(prog).parse_args(shutdown.remove_ros_args(argv)[1:])
    try:
        components = read_components(opts.nodes)
    except ComponentError as exc:
        shutdown.fail(prog, exc)
    container = None
    executor = None
    spinners = []
    failed = threading.Event()
    try:
        shutdown.init(argv)
        bond.share_endpoints()  # the composed nodes live as long as the container
        transforms.share_listener_threads()
        container = shutdown.create(ComponentContainer)
        executor = SingleThreadedExecutor()
        executor.add_node(container)
        plugins = registry()
        preload(components, plugins)
        for plugin, ros_args in components:
            node = container.load(plugin, ros_args, plugins)
            if node is None:
                continue
            if isolated:
                spinners.append(IsolatedSpinner(node, failed))
            else:
                for each in [node] + list(getattr(node, 'companion_nodes', ())):
                    executor.add_node(each)
        shutdown.spin(executor, until=failed.is_set)
    except KeyboardInterrupt:
        pass
    finally:
        for spinner in spinners:
            spinner.stop()
        nodes = []
        for node in (container.components if container is not None else []):
            nodes += list(getattr(node, 'companion_nodes', ())) + [node]
        shutdown.shutdown(*nodes, container, executor=executor)
    return 1 if failed.is_set() else 0


def main_isolated(args=None):
    """
    Run ``component_container_isolated``: :func:`main` with one executor per component.

    :param args: command line without the program name (default ``sys.argv[1:]``).
    :returns: :func:`main`'s exit code.
    """
    return main(args, isolated=True)


if __name__ == '__main__':
    sys.exit(main())
