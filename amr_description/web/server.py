# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Start a viser web server on a given host and port, or fail with one clear line.

viser (PyPI, MIT) serves its bundled browser client and a websocket on one port. It silently
moves to the next port when the requested one is taken; our nodes must not (a user opens the
printed URL), so the port is checked first and the bound port verified afterwards.
"""

import contextlib
import errno
import io
import logging
import os
import socket


class PortInUse(RuntimeError):
    """The requested TCP port cannot be bound (message: one line naming port and parameter)."""


def page_url(host, port):
    """
    Return the URL a user opens for a server bound to ``host:port``.

    :param host: bind address; ``0.0.0.0``/``::`` print as ``127.0.0.1``/``[::1]``.
    :param port: TCP port.
    :returns: ``http://HOST:PORT/``.
    """
    if host in ('0.0.0.0', ''):
        host = '127.0.0.1'
    elif host == '::':
        host = '::1'
    if ':' in host:
        host = f'[{host}]'
    return f'http://{host}:{port}/'


PORT_ARGUMENT = 'AMR_PORT_ARGUMENT'
"""Environment variable with the launch argument that set a page node's port (e.g.
``viewer_port``): set by the stacks for their page nodes, so that the error names the argument
the user typed (:func:`serve_page`)."""


def _argument(parameter):
    """Return how the user sets ``parameter``: ``viewer_port:=N`` in a launch, else ``-p``."""
    launch_argument = os.environ.get(PORT_ARGUMENT, '')
    return f'{launch_argument}:=N' if launch_argument else f'-p {parameter}:=N'


def serve_page(node, default_port):
    """
    Declare a page node's ``host`` and ``port`` parameters and start its server.

    ``port`` given (``-p port:=N``, or a stack's ``viewer_port:=N``): exactly that port, or
    :class:`PortInUse` naming the argument the user typed. ``port`` not given: ``default_port``
    or the next free port above it; the parameter is then set to the port bound, so
    ``ros2 param get`` tells it.

    :param node: the rclpy node (not yet serving).
    :param default_port: TCP port tried first when ``port`` is not given.
    :returns: ``(server, url)``.
    :raises PortInUse: one line (see above).
    """
    from rclpy.exceptions import ParameterUninitializedException
    from rclpy.parameter import Parameter
    node.declare_parameter('host', '127.0.0.1')
    node.declare_parameter('port', Parameter.Type.INTEGER)
    host = str(node.get_parameter('host').value)
    try:
        given = node.get_parameter('port').value
    except ParameterUninitializedException:
        given = None
    port = int(default_port if given is None else given)
    server = start_server(host, port, fallback=given is None)
    bound = server.get_port()
    if given is None:
        node.set_parameters([Parameter('port', Parameter.Type.INTEGER, bound)])
    return server, page_url(host, bound)


def check_port(host, port, parameter='port'):
    """
    Raise :class:`PortInUse` when ``host:port`` cannot be bound.

    :param host: bind address.
    :param port: TCP port (1..65535).
    :param parameter: the node parameter to name in the message.
    :raises PortInUse: one line, e.g. ``port 8080 on 127.0.0.1 is already in use; choose
        another with -p port:=N``.
    """
    family = socket.AF_INET6 if ':' in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((host, port))
    except OSError as exc:
        if exc.errno == errno.EADDRINUSE:
            raise PortInUse(f'port {port} on {host} is already in use; choose another with '
                            f'{_argument(parameter)}') from None
        raise PortInUse(f'cannot listen on {host}:{port} ({exc.strerror}); set '
                        f'{_argument(parameter)} or -p host:=ADDRESS') from None
    finally:
        sock.close()


def start_server(host, port, parameter='port', fallback=False):
    """
    Start a ``viser.ViserServer`` on ``host:port`` (its banner off).

    :param host: bind address (127.0.0.1 keeps the page on this machine).
    :param port: TCP port.
    :param parameter: the node parameter to name in an error.
    :param fallback: False: exactly ``port`` (the user chose it); True: ``port`` or, when it
        is taken, the next free one above it (viser's own search, as development servers do;
        read the one bound with ``server.get_port()``).
    :returns: the running ``viser.ViserServer``; stop it with :func:`stop_server`.
    :raises PortInUse: when an exact port is taken (checked before and after starting).

    The page's share button is hidden and its request ignored: sharing opens a tunnel through
    a server on the internet, and nothing of the page may leave this machine.
    """
    if not fallback:
        check_port(host, port, parameter)
    import viser  # noqa: I100 - heavy import (~1 s), only once the port is known to be free
    logging.getLogger('websockets').setLevel(logging.CRITICAL)
    with contextlib.redirect_stdout(io.StringIO()):  # viser prints a banner even when quiet
        server = viser.ViserServer(host=host, port=port, verbose=False)
    if server.get_port() != port and not fallback:  # lost a race: viser moved elsewhere
        stop_server(server)
        raise PortInUse(f'port {port} on {host} is already in use; choose another with '
                        f'{_argument(parameter)}')
    server.request_share_url = lambda *args, **kwargs: None
    server.gui.configure_theme(show_share_button=False, control_width='large')
    return server


def stop_server(server):
    """Stop a server from :func:`start_server` and close its port (waits up to ~1 s)."""
    with contextlib.redirect_stdout(io.StringIO()):  # viser prints 'Server stopped'
        server.stop()


def run_web_node(node_class, node_name, args=None, executor_class=None):
    """
    Run a node that serves a page until Ctrl-C or SIGTERM (``main`` of the web nodes).

    The project's clean-shutdown pattern (:mod:`amr_description.ros.shutdown`) plus the web
    part: once the node is built (its server listens) one line ``<node_name>: open URL in a
    browser`` is printed; the server is stopped before the node is destroyed.

    :param node_class: the Node class; its instances have ``url`` and ``stop_server()``.
    :param node_name: the node's name, used in the URL line and the error line.
    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :param executor_class: rclpy executor class (called with ``context=``) that spins the
        node; default a ``SingleThreadedExecutor``.
    :returns: 0 on a clean shutdown, 1 on a port in use or a bad parameter (one line).
    """
    import rclpy
    from amr_description.ros import shutdown
    node = None
    executor = None
    try:
        shutdown.init(args)
        node = shutdown.create(node_class)
        print(f'{node_name}: open {node.url} in a browser', flush=True)
        if executor_class is not None:
            executor = executor_class(context=node.context)
            executor.add_node(node)
        shutdown.spin(node if executor is None else executor)
    except (PortInUse, ValueError) as exc:
        if node is not None:
            raise
        shutdown.ignore_signals()  # a stack stopping now must not interrupt the exit
        rclpy.logging.get_logger(node_name).error(str(exc))
        return 1
    except KeyboardInterrupt:
        pass
    finally:
        if node is not None:
            node.stop_server()
        if executor is not None:
            executor.remove_node(node)
        shutdown.shutdown(node, executor=executor)
    return 0
