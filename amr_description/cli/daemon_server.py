# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``ros2`` daemon process (ros2cli's ``_ros2_daemon``): one node, an XML-RPC server.

Started by :func:`amr_description.cli.daemon.spawn_daemon` as
``python -m amr_description.cli.daemon_server [--timeout S]``; serves this domain's graph on
``127.0.0.1:`` :func:`~amr_description.cli.daemon.daemon_port` until ``shutdown`` is called,
SIGINT/SIGTERM, or ``--timeout`` s pass without a request. The node's graph cache is kept by
the RMW's discovery threads; the node is spun in a thread so that it stays a live participant.
Exit code 0; 1 when the port is taken (another daemon won the race to start).
"""

import argparse
import os
import signal
import sys
import threading
import time
import uuid


def _service_relay(node):
    """
    Return ``call_service(type, name, request, timeout)`` calling a service from ``node``.

    The daemon's node has discovered the graph long ago, so its client is ready at once where
    a new process's node waits for discovery (up to seconds). ``type`` is
    ``pkg/srv/Name``, ``request`` and the result are CDR bytes (``xmlrpc.client.Binary``);
    None when the service is not ready or does not answer within ``timeout`` s (the caller
    then calls it itself). Clients are kept per service.
    """
    import importlib
    import xmlrpc.client

    from rclpy.serialization import deserialize_message
    from rclpy.serialization import serialize_message
    clients = {}

    def call_service(type_name, name, request, timeout):
        package, _, class_name = type_name.split('/')
        kind = getattr(importlib.import_module(f'{package}.srv'), class_name)
        client = clients.get((type_name, name))
        if client is None:
            client = clients[(type_name, name)] = node.create_client(kind, name)
        if not client.service_is_ready():
            return None
        done = threading.Event()
        future = client.call_async(deserialize_message(request.data, kind.Request))
        future.add_done_callback(lambda _: done.set())
        if not done.wait(float(timeout)) or future.result() is None:
            future.cancel()
            return None
        return xmlrpc.client.Binary(serialize_message(future.result()))
    return call_service


def _functions(node, stop):
    """Return the XML-RPC functions answering from ``node``; ``stop`` ends the server."""
    from amr_description.cli.daemon import node_endpoints
    from amr_description.cli.daemon import settings
    own = settings()
    started = time.monotonic()

    def endpoints_count(method):
        return lambda topic: int(method(topic))

    return {
        'settings': lambda: own,
        'pid': os.getpid,
        'uptime': lambda: time.monotonic() - started,
        'get_name_and_namespace': lambda: [node.get_name(), node.get_namespace()],
        'get_node_names_and_namespaces': lambda: [
            list(pair) for pair in node.get_node_names_and_namespaces()],
        'get_topic_names_and_types': lambda: [
            [name, list(types)] for name, types in node.get_topic_names_and_types()],
        'get_service_names_and_types': lambda: [
            [name, list(types)] for name, types in node.get_service_names_and_types()],
        'count_publishers': endpoints_count(node.count_publishers),
        'count_subscribers': endpoints_count(node.count_subscribers),
        'publishers_info': lambda topic: [
            str(info) for info in node.get_publishers_info_by_topic(topic)],
        'subscriptions_info': lambda topic: [
            str(info) for info in node.get_subscriptions_info_by_topic(topic)],
        'node_endpoints': lambda name, namespace: [
            [title, [[n, t] for n, t in items]]
            for title, items in node_endpoints(node, name, namespace)],
        'call_service': _service_relay(node),
        'shutdown': stop,
    }


def main(argv=None):
    """Run the daemon (see the module docstring); return its exit code."""
    parser = argparse.ArgumentParser(prog='_ros2_daemon')
    parser.add_argument('--timeout', type=float, default=2 * 60 * 60,
                        help='seconds without a request before the daemon ends')
    args = parser.parse_args(argv)
    import xmlrpc.server

    from amr_description.cli.daemon import daemon_port
    from amr_description.cli.daemon import domain_id
    try:
        server = xmlrpc.server.SimpleXMLRPCServer(
            ('127.0.0.1', daemon_port()), logRequests=False, allow_none=True)
    except OSError:
        return 1
    done = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: done.set())
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    rclpy.init(args=[], signal_handler_options=rclpy.signals.SignalHandlerOptions.NO)
    node = rclpy.create_node(f'_ros2cli_daemon_{domain_id()}_{uuid.uuid4().hex}',
                             start_parameter_services=False)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    spinner = threading.Thread(target=lambda: _spin(executor, done), daemon=True)
    spinner.start()

    def stop():
        done.set()
        return True

    for name, function in _functions(node, stop).items():
        server.register_function(function, name)
    server.timeout = 0.5
    last = time.monotonic()
    handled = [0]
    original = server.finish_request

    def finish_request(request, client_address):
        handled[0] += 1
        original(request, client_address)

    server.finish_request = finish_request
    try:
        while not done.is_set():
            before = handled[0]
            server.handle_request()
            now = time.monotonic()
            if handled[0] != before:
                last = now
            elif now - last > args.timeout:
                break
    finally:
        done.set()
        server.server_close()
        spinner.join(timeout=2.0)
        executor.shutdown(timeout_sec=0.5)
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


def _spin(executor, done):
    while not done.is_set():
        try:
            executor.spin_once(timeout_sec=0.2)
        except Exception:  # noqa: B902 - the context went away at shutdown
            return


if __name__ == '__main__':
    sys.exit(main())
