# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 daemon start|stop|status`` and the daemon the graph verbs ask, as ros2cli's.

The daemon is a background process per ``ROS_DOMAIN_ID`` holding one hidden node
(``_ros2cli_daemon_<domain>_<hex>``) that follows the ROS graph, and an XML-RPC server on
``127.0.0.1:11511 + ROS_DOMAIN_ID`` (ros2cli's port) that answers graph questions from it. A
graph verb (``topic list|find|type``, ``service list|find|type``, ``node list``) asks a running
daemon and answers at once, without a node of its own waiting for discovery; when none runs it
starts one in the background (a new session, detached from the terminal) and answers this
time from its own node, as ros2cli's ``NodeStrategy`` does; so does a verb that finds a daemon
younger than its ``--spin-time`` (it may not have discovered the graph yet); ``--no-daemon``
always uses its own node. The daemon ends after :data:`IDLE_TIMEOUT` s without a request
(ros2cli's two hours) or on ``ros2 daemon stop``. A daemon started with other discovery settings
(``ROS_AUTOMATIC_DISCOVERY_RANGE``, ``ROS_STATIC_PEERS``, the RMW) than the caller's is
stale: the caller stops it and starts one with its own.

Output lines of the verbs are ros2cli's: ``The daemon is running`` / ``The daemon is not
running``, ``The daemon has been started`` / ``The daemon is already running``, ``The daemon
has been stopped``.
"""

import contextlib
import os
import subprocess
import sys
import time

from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb


BASE_PORT = 11511
"""ros2cli's daemon port for ROS_DOMAIN_ID 0; domain N listens on ``BASE_PORT + N``."""
IDLE_TIMEOUT = 2 * 60 * 60
"""Seconds without a request after which the daemon ends (ros2cli's default)."""
START_TIMEOUT = 10.0
"""Seconds ``ros2 daemon start`` waits for a new daemon to answer."""
SETTINGS = ('ROS_DOMAIN_ID', 'ROS_AUTOMATIC_DISCOVERY_RANGE', 'ROS_STATIC_PEERS',
            'RMW_IMPLEMENTATION')
"""Environment a daemon's answers depend on; a daemon with other values is stale."""


MAX_DOMAIN_ID = 232
"""The highest domain ID Fast DDS can open ports for (with its default port base)."""


def domain_id():
    """
    Return the ``ROS_DOMAIN_ID`` of this process (0 when unset or empty).

    :raises ValueError: one line naming the variable and its value when it is not an integer
        from 0 to :data:`MAX_DOMAIN_ID` (rcl refuses a non-integer; Fast DDS a larger one).
    """
    text = (os.environ.get('ROS_DOMAIN_ID') or '0').strip()
    if not text.isdigit() or int(text) > MAX_DOMAIN_ID:
        raise ValueError(f"ROS_DOMAIN_ID '{os.environ['ROS_DOMAIN_ID']}': expected an integer "
                         f'from 0 to {MAX_DOMAIN_ID}')
    return int(text)


def daemon_port(domain=None):
    """Return the daemon's TCP port of ``domain`` (default: this process's domain)."""
    return BASE_PORT + (domain_id() if domain is None else int(domain))


def settings():
    """Return this process's values of :data:`SETTINGS` (a dict of str)."""
    values = {name: os.environ.get(name, '') for name in SETTINGS}
    values['ROS_DOMAIN_ID'] = str(domain_id())
    return values


def _proxy(domain=None, timeout=2.0):
    import xmlrpc.client

    class _Transport(xmlrpc.client.Transport):

        def make_connection(self, host):
            connection = super().make_connection(host)
            connection.timeout = timeout
            return connection

    return xmlrpc.client.ServerProxy(f'http://127.0.0.1:{daemon_port(domain)}/',
                                     transport=_Transport(), allow_none=True)


def running_daemon(domain=None):
    """
    Return an XML-RPC proxy of a domain's daemon when one answers, else None.

    :param domain: ROS domain ID (default: this process's).
    :returns: ``xmlrpc.client.ServerProxy`` or None (nothing listens, or not a daemon).
    """
    import xmlrpc.client
    proxy = _proxy(domain)
    try:
        proxy.settings()
    except (OSError, xmlrpc.client.Error):
        return None
    return proxy


def spawn_daemon():
    """Start this domain's daemon in the background (a new session); do not wait for it."""
    subprocess.Popen(  # noqa: S603 - our own interpreter and module
        [sys.executable, '-m', 'amr_description.cli.daemon_server', '--timeout',
         str(IDLE_TIMEOUT)],
        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True, close_fds=True)


def process_alive(pid):
    """Return True while process ``pid`` exists (also one of another user)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def stop_daemon(proxy, domain=None):
    """
    Ask ``proxy``'s daemon (of ``domain``, default this process's) to end.

    :returns: ``(stopped, pid)``: True once its process is gone; its pid (None if unknown).
    """
    import xmlrpc.client
    pid = None
    with contextlib.suppress(OSError, xmlrpc.client.Error):
        pid = int(proxy.pid())
        proxy.shutdown()
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        if running_daemon(domain) is None and (pid is None or not process_alive(pid)):
            return True, pid
        time.sleep(0.05)
    return False, pid


class DaemonNode:
    """
    The graph questions of an rclpy node, answered by the daemon (ros2cli's ``DaemonNode``).

    Only what the graph verbs ask: names, namespaces, topic and service names and types,
    publisher and subscriber counts, endpoint details (as text). Its own name is the daemon's
    (a hidden name).

    :param proxy: the daemon's XML-RPC proxy.
    """

    settled = True  # the daemon has followed the graph for a while: no discovery wait

    def __init__(self, proxy):
        """Keep the proxy."""
        self._proxy = proxy
        self._name, self._namespace = proxy.get_name_and_namespace()

    def get_name(self):
        """Return the daemon node's name."""
        return self._name

    def get_namespace(self):
        """Return the daemon node's namespace."""
        return self._namespace

    def get_fully_qualified_name(self):
        """Return ``/namespace/name`` of the daemon node."""
        return self._namespace.rstrip('/') + '/' + self._name

    def get_node_names_and_namespaces(self):
        """Return ``[(name, namespace)]`` of every node in the graph."""
        return [tuple(pair) for pair in self._proxy.get_node_names_and_namespaces()]

    def get_topic_names_and_types(self):
        """Return ``[(topic, [types])]``."""
        return [(name, list(types)) for name, types in self._proxy.get_topic_names_and_types()]

    def get_service_names_and_types(self):
        """Return ``[(service, [types])]``."""
        return [(name, list(types))
                for name, types in self._proxy.get_service_names_and_types()]

    def node_endpoints(self, name, namespace):
        """Return the endpoints of a node (:func:`node_endpoints`), from the daemon."""
        return [(title, [(n, list(t)) for n, t in items])
                for title, items in self._proxy.node_endpoints(name, namespace)]

    def count_publishers(self, topic):
        """Return the number of publishers of ``topic``."""
        return int(self._proxy.count_publishers(topic))

    def count_subscribers(self, topic):
        """Return the number of subscriptions of ``topic``."""
        return int(self._proxy.count_subscribers(topic))

    def get_publishers_info_by_topic(self, topic):
        """Return the publishers of ``topic``, each as the text of rclpy's TopicEndpointInfo."""
        return list(self._proxy.publishers_info(topic))

    def get_subscriptions_info_by_topic(self, topic):
        """Return the subscriptions of ``topic``, each as the text of TopicEndpointInfo."""
        return list(self._proxy.subscriptions_info(topic))


NODE_SECTIONS = ('Subscribers', 'Publishers', 'Service Servers', 'Service Clients',
                 'Action Servers', 'Action Clients')
"""The sections of ``ros2 node info``, in upstream's order."""


def node_endpoints(node, name, namespace):
    """
    Return ``[(section, [(name, [types])])]`` of a node's endpoints, :data:`NODE_SECTIONS`.

    :param node: an rclpy node whose graph is asked (the daemon's or a CLI's own).
    """
    from rclpy.action import get_action_client_names_and_types_by_node
    from rclpy.action import get_action_server_names_and_types_by_node
    found = (node.get_subscriber_names_and_types_by_node(name, namespace),
             node.get_publisher_names_and_types_by_node(name, namespace),
             node.get_service_names_and_types_by_node(name, namespace),
             node.get_client_names_and_types_by_node(name, namespace),
             get_action_server_names_and_types_by_node(node, name, namespace),
             get_action_client_names_and_types_by_node(node, name, namespace))
    return [(title, [(n, list(t)) for n, t in items])
            for title, items in zip(NODE_SECTIONS, found)]


def usable_daemon(spin_time):
    """
    Return the proxy of a daemon to ask, or None (then start one when none runs).

    :param spin_time: s a daemon must have run to have discovered the graph.
    """
    import xmlrpc.client
    proxy = running_daemon()
    if proxy is None:
        spawn_daemon()
        return None
    try:
        if proxy.settings() != settings():
            stop_daemon(proxy)  # stale: started with other discovery settings
            spawn_daemon()
            return None
        if proxy.uptime() < spin_time:
            return None  # too young to have discovered the graph: our own node this time
    except (OSError, xmlrpc.client.Error):
        return None
    return proxy


def service_relay(spin_time=0.0):
    """
    Return a service caller through the running daemon, or None when none runs.

    The caller is ``call(name, service_type, request, timeout) -> response or None``; no
    daemon is started, and one of other discovery settings is not used. The daemon's node
    calls the service (:mod:`amr_description.cli.daemon_server` ``call_service``): it
    discovered the graph long ago, where a new process's node waits for discovery (measured
    for ``list_controllers``: 0.01 to 2.8 s, bimodal, docs/benchmark.md).
    The call returns None when the daemon cannot make it (the caller then calls itself).
    """
    import xmlrpc.client
    proxy = running_daemon()
    try:
        if proxy is None or proxy.settings() != settings() or proxy.uptime() < spin_time:
            return None
    except (OSError, xmlrpc.client.Error):
        return None

    def call(name, service_type, request, timeout):
        from rclpy.serialization import deserialize_message
        from rclpy.serialization import serialize_message
        package = service_type.__module__.split('.')[0]
        try:
            answer = proxy.call_service(f'{package}/srv/{service_type.__name__}', name,
                                        xmlrpc.client.Binary(serialize_message(request)),
                                        float(timeout))
        except (OSError, xmlrpc.client.Error):
            return None
        if answer is None:
            return None
        return deserialize_message(answer.data, service_type.Response)
    call.graph = DaemonNode(proxy)  # the daemon's graph, for the verbs that also ask it
    return call


@contextlib.contextmanager
def graph_node(args, name):
    """
    Yield what answers a graph verb: the running daemon, or a node of this process.

    :param args: the verb's arguments (``no_daemon``).
    :param name: the node name when this process makes its own node.
    :returns: a context manager yielding a :class:`DaemonNode` or an rclpy node.
    """
    from amr_description.cli.common import cli_node
    if not getattr(args, 'no_daemon', False):
        proxy = usable_daemon(getattr(args, 'spin_time', 0.0))
        if proxy is not None:
            import xmlrpc.client
            from amr_description.cli.common import CliError
            try:
                yield DaemonNode(proxy)
            except (OSError, xmlrpc.client.Error) as exc:
                raise CliError(f'the daemon stopped answering ({exc}): run the command '
                               'again, or add --no-daemon') from None
            return
    with cli_node(name) as node:
        yield node


def _status(args):
    print('The daemon is running' if running_daemon() is not None
          else 'The daemon is not running')
    return 0


def _start(args):
    if running_daemon() is not None:
        print('The daemon is already running')
        return 0
    spawn_daemon()
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        if running_daemon() is not None:
            print('The daemon has been started')
            return 0
        time.sleep(0.05)
    from amr_description.cli.common import fail
    return fail(f'The daemon did not answer within {START_TIMEOUT:g} s on port '
                f'{daemon_port()}')


def _stop(args):
    proxy = running_daemon()
    if proxy is None:
        print('The daemon is not running')
        return 0
    if not stop_daemon(proxy)[0]:
        from amr_description.cli.common import fail
        return fail('The daemon did not stop')
    print('The daemon has been stopped')
    return 0


VERB_START = Verb("Start the daemon if it isn't running", _start)
"""``ros2 daemon start``."""

VERB_STATUS = Verb('Output the status of the daemon', _status)
"""``ros2 daemon status``."""

VERB_STOP = Verb('Stop the daemon if it is running', _stop)
"""``ros2 daemon stop``."""

COMMAND = Command('Various daemon related sub-commands',
                  verbs_metavar='Call `ros2 daemon <command> -h` for more detailed usage.')
"""``ros2 daemon``: its verbs are registered in ``amr_description.daemon.verb``."""
