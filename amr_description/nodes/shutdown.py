# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The clean Ctrl-C shutdown pattern shared by the nodes' ``main`` functions (not a node).

rclpy's default signal handler shuts the context down from inside the SIGINT handler, while
callbacks and other threads may still use it: publishers then fail ("publisher's context is
invalid"), a callback in flight raises from a half-destroyed handle, and the second SIGINT that
a launch-style orchestrator sends after the terminal's own raises ``KeyboardInterrupt`` in the
middle of the cleanup (a traceback and exit code 1). Here SIGINT and SIGTERM only raise
``KeyboardInterrupt`` in the main thread, once, and set a flag that :func:`spin` checks (in case
a library swallowed the exception); later signals are ignored while ``main`` stops its
threads, destroys its nodes and, last, shuts rclpy down::

    init(args)
    node = None
    try:
        node = MyNode()
        spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown(node)
"""

import signal
import threading

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.executors import SingleThreadedExecutor
from rclpy.signals import SignalHandlerOptions

SPIN_PERIOD = 0.1
"""Seconds between checks for a signal while spinning (the wait is not interrupted)."""

_SIGNALS = (signal.SIGINT, signal.SIGTERM)
_interrupted = threading.Event()


def _interrupt(signum, frame):
    if _interrupted.is_set():
        return  # the cleanup is under way
    _interrupted.set()
    raise KeyboardInterrupt


def interrupted():
    """Return True once SIGINT or SIGTERM was received."""
    return _interrupted.is_set()


def ignore_signals():
    """Ignore further SIGINT/SIGTERM (the cleanup is under way); main thread only."""
    _interrupted.set()
    for signum in _SIGNALS:
        signal.signal(signum, signal.SIG_IGN)


def init(args=None):
    """
    ``rclpy.init`` without rclpy's signal handlers; SIGINT/SIGTERM raise KeyboardInterrupt.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :raises KeyboardInterrupt: on a signal during the initialisation.
    """
    for signum in _SIGNALS:
        signal.signal(signum, _interrupt)
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)


def spin(target, until=None, period=SPIN_PERIOD):
    """
    Spin a node or an executor until a signal, ``until()`` or an external rclpy shutdown.

    :param target: an rclpy ``Node`` (spun by a private single-threaded executor) or an
        ``Executor``.
    :param until: optional callable returning True to stop spinning.
    :param period: seconds of each wait (the longest delay before a signal is seen).
    :raises KeyboardInterrupt: on SIGINT/SIGTERM.
    """
    executor = target
    if not hasattr(target, 'spin_once'):
        executor = SingleThreadedExecutor(context=target.context)
        executor.add_node(target)
    try:
        while executor.context.ok() and not _interrupted.is_set() and \
                not (until is not None and until()):
            executor.spin_once(timeout_sec=period)
    except ExternalShutdownException:
        pass
    finally:
        if executor is not target:
            executor.shutdown(timeout_sec=0)


def shutdown(*nodes, executor=None):
    """
    Destroy ``nodes`` (None entries skipped), shut ``executor`` and rclpy down; signals ignored.

    Call it after stopping the program's own threads. Errors of a context already shut down
    elsewhere are ignored.

    :param nodes: rclpy nodes to destroy, in order.
    :param executor: optional executor to shut down after the nodes.
    """
    try:
        ignore_signals()
    except ValueError:  # not the main thread: signals are the main thread's business
        pass
    for node in nodes:
        if node is None:
            continue
        try:
            node.destroy_node()
        except Exception:  # noqa: B902 - best effort at exit
            pass
    if executor is not None:
        try:
            executor.shutdown(timeout_sec=1.0)
        except Exception:  # noqa: B902 - best effort at exit
            pass
    rclpy.try_shutdown()
