# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Helpers shared by the ``ros2`` verbs: a short-lived node, errors in upstream style."""

import contextlib
import os
import signal
import sys
import threading
import time


class CliError(Exception):
    """A user error; the message is printed on one line to stderr and the verb exits 1."""


def fail(message):
    """
    Print ``message`` to stderr on one line and return exit code 1.

    :param message: the error text, without a trailing newline.
    :returns: 1
    """
    print(message, file=sys.stderr)
    return 1


def is_hidden_name(name):
    """
    Tell whether a node, topic or service name is hidden (a token starts with ``_``).

    :param name: a fully qualified or relative ROS name.
    :returns: True when any ``/``-separated token starts with an underscore, as in rclpy.
    """
    return any(token.startswith('_') for token in name.split('/'))


def default_node_name():
    """
    Return a hidden, per-process node name like ros2cli's direct node.

    :returns: ``_ros2cli_<pid>``.
    """
    return f'_ros2cli_{os.getpid()}'


def wait_for_graph(node, query, settle=0.4, minimum=0.3, maximum=3.0, ready=None):
    """
    Spin ``node`` until the answer of ``query(node)`` has settled, then return it.

    A node that has followed the graph all along (the daemon's, ``settled``) answers at once.

    Discovery over DDS takes a while (measured here: 0.3 to 2.7 s before a new participant
    sees an existing one); ros2cli's direct node also spins before asking the graph. This
    polls every 50 ms and returns once the answer is ``ready`` and has not changed for
    ``settle`` seconds (after at least ``minimum`` and at most ``maximum`` seconds).

    :param node: an rclpy node.
    :param query: callable ``query(node) -> value`` comparable with ``==``.
    :param settle: seconds the answer must stay unchanged (0: return as soon as ready).
    :param minimum: seconds to spin at least.
    :param maximum: seconds to spin at most.
    :param ready: optional predicate on the answer; the settle clock starts only when true.
    :returns: the last value of ``query(node)``.
    """
    if getattr(node, 'settled', False):
        return query(node)  # the daemon's graph (amr_description.cli.daemon)
    start = last_change = time.monotonic()
    value = query(node)
    while True:
        now = time.monotonic()
        is_ready = ready is None or ready(value)
        if now - start >= maximum or (
                is_ready and now - start >= minimum and now - last_change >= settle):
            return value
        spin_once(node, timeout_sec=0.05)
        new_value = query(node)
        if new_value != value:
            value, last_change = new_value, time.monotonic()


def add_spin_time_argument(parser, default=3.0):
    """
    Add ``-s/--spin-time`` and ``--no-daemon``, as ros2cli's ``NodeStrategy``.

    The spin time is what a verb listens to discovery before answering from its own node;
    ``--no-daemon`` never asks the daemon (:mod:`amr_description.cli.daemon`).

    :param parser: the verb's argparse parser.
    :param default: default seconds.
    """
    parser.add_argument(
        '-s', '--spin-time', type=float, default=default, metavar='SECONDS',
        help='Spin time in seconds to wait for discovery (only applies when not using an '
             f'already running daemon; default: {default})')
    add_no_daemon_argument(parser)


def add_no_daemon_argument(parser):
    """Add ros2cli's ``--no-daemon`` (:mod:`amr_description.cli.daemon`)."""
    parser.add_argument('--no-daemon', action='store_true',
                        help='Do not spawn nor use an already running daemon')


def _ignore(signum, frame):
    """Ignore a signal (a Python handler that does nothing)."""


class _Interrupts:
    """
    SIGINT for the CLI: ``KeyboardInterrupt`` at once, except inside :func:`spin_once`.

    A ``KeyboardInterrupt`` raised in the middle of rclpy's executor (while it holds entity
    handles in its wait set, or inside a subscription callback) would reach the cleanup that
    follows with the executor and the node half torn down (a precaution: the Ctrl-C'd
    ``topic echo`` that once did not exit came from a test run with SIGINT ignored, see
    ``test/conftest.py``). Inside ``spin_once`` the signal only sets a flag and
    ``spin_once`` raises ``KeyboardInterrupt`` once rclpy returned (the nodes' pattern,
    :mod:`amr_description.ros.shutdown`). A handler a verb installed itself (``ros2 bag``'s
    stop flag) is left alone.
    """

    spinning = False
    pending = False

    @classmethod
    def install(cls):
        """Install the handler when SIGINT still has Python's default (main thread only)."""
        if threading.current_thread() is not threading.main_thread():
            return
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            signal.signal(signal.SIGINT, cls._handler)

    @classmethod
    def _handler(cls, signum, frame):
        if cls.spinning:
            cls.pending = True
            return
        raise KeyboardInterrupt

    @classmethod
    def raise_pending(cls):
        """Raise the ``KeyboardInterrupt`` deferred while rclpy was spinning, if any."""
        if cls.pending:
            cls.pending = False
            raise KeyboardInterrupt


def spin_once(node, timeout_sec=None):
    """
    Execute at most one callback of ``node`` in the context it was created in.

    :param node: a node made by :func:`cli_node` (or any node; a private executor is created
        for its context on first use).
    :param timeout_sec: seconds to wait for work (None: forever).
    :raises KeyboardInterrupt: after ``spin_once`` returned, when SIGINT arrived meanwhile.
    """
    executor = getattr(node, '_cli_executor', None)
    if executor is None:
        from rclpy.executors import SingleThreadedExecutor
        executor = SingleThreadedExecutor(context=node.context)
        executor.add_node(node)
        node._cli_executor = executor
    _Interrupts.spinning = True
    try:
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        _Interrupts.spinning = False
    _Interrupts.raise_pending()


@contextlib.contextmanager
def cli_node(name='_ros2cli', args=None):
    """
    Create rclpy context + node for one CLI call and tear both down afterwards.

    :param name: node name (ros2cli uses a hidden name starting with ``_``).
    :param args: extra rcl arguments, e.g. ``['--ros-args', '-p', 'use_sim_time:=true']``.
    :returns: a context manager yielding an :class:`rclpy.node.Node`.
    """
    import rclpy
    from rclpy.context import Context

    _Interrupts.install()
    context = Context()
    rclpy.init(args=args, context=context)
    node = rclpy.create_node(name, context=context, start_parameter_services=False)
    try:
        yield node
    finally:
        # a second Ctrl-C must not cut the teardown short (main thread only); a no-op Python
        # handler, not SIG_IGN: a SIGINT caught by CPython just before a switch to SIG_IGN is
        # reported with a traceback ('OSError: Signal 2 ignored due to race condition');
        # the previous handler is restored below, so finalization is not concerned
        main = threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGINT, _ignore) if main else None
        try:
            executor = getattr(node, '_cli_executor', None)
            if executor is not None:
                executor.shutdown(timeout_sec=0.1)
            node.destroy_node()
            with contextlib.suppress(Exception):
                rclpy.shutdown(context=context)
        finally:
            _Interrupts.spinning = _Interrupts.pending = False
            if main:
                signal.signal(signal.SIGINT, previous)
