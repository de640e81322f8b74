# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The clean Ctrl-C shutdown pattern shared by the nodes' ``main`` functions (not a node).

rclpy's default signal handler shuts the context down from inside the SIGINT handler, while
callbacks and other threads may still use it: publishers then fail ("publisher's context is
invalid"), a callback in flight raises from a half-destroyed handle, and the second SIGINT that
a launch-style orchestrator sends after the terminal's own raises ``KeyboardInterrupt`` in the
middle of the cleanup (a traceback and exit code 1). Here the first SIGINT or SIGTERM sets a
flag; while :func:`spin` runs, that is all it does (an exception raised inside rclpy's C++
calls, e.g. while ``take_message`` builds a message, escapes as an unrelated ``RuntimeError``),
and ``spin`` raises ``KeyboardInterrupt`` itself once ``spin_once`` returned; outside ``spin``
the handler raises ``KeyboardInterrupt`` in the main thread at once. Later signals are ignored
while ``main`` stops its threads, destroys its nodes and, last, shuts rclpy down::

    node = None
    try:
        init(args)
        node = create(MyNode)
        spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown(node)

The same pattern turns start-up errors into one line and exit code 1, never a traceback:

- :func:`init`: rcl cannot parse the command line (``--ros-args -p name:=<not YAML>``, an
  empty ``-p`` value, an unknown ``--ros-args`` flag): rcl's own message, as upstream prints
  it (``failed to initialize rcl: Couldn't parse parameter override rule: ...``);
- :func:`create`: the node refuses a parameter: a wrong type names the parameter and the
  expected type (rclpy's ``InvalidParameterTypeException`` text), an out-of-range value its
  range; a ``ValueError`` raised by the node's constructor is printed as it is;
- :class:`amr_description.ros.node.Node` (the base class of our nodes): a whole number
  given on the command line for a floating-point parameter is accepted as that float.

The one line goes to stderr through the rclpy logger named after the program, i.e.
``[ERROR] [<time>] [<name>]: <message>``.
"""

import os
import signal
import sys
import threading

import rclpy
from rclpy.exceptions import InvalidParameterTypeException
from rclpy.exceptions import InvalidParameterValueException
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.executors import SingleThreadedExecutor
from rclpy.logging import LoggingSeverity
from rclpy.signals import SignalHandlerOptions
import rclpy.utilities

SPIN_PERIOD = 0.1
"""Seconds between checks for a signal while spinning (the wait is not interrupted)."""

_SIGNALS = (signal.SIGINT, signal.SIGTERM)
_interrupted = threading.Event()
_spinning = threading.Event()


def _interrupt(signum, frame):
    if _interrupted.is_set():
        return  # the cleanup is under way
    _interrupted.set()
    if _spinning.is_set():
        # inside spin(): do not raise in the middle of rclpy's C++ calls (a KeyboardInterrupt
        # raised while pybind11 converts take_message's arguments surfaced as "RuntimeError:
        # Unable to convert call argument '0' to Python object"); spin() raises it itself
        # once spin_once() returned, at most one period later
        return
    raise KeyboardInterrupt


def interrupted():
    """Return True once SIGINT or SIGTERM was received."""
    return _interrupted.is_set()


def ignore_signals():
    """
    Ignore further SIGINT/SIGTERM (the cleanup is under way); main thread only.

    ``SIG_IGN`` stays set through the interpreter's finalization (a Python handler would be
    reset to ``SIG_DFL`` there, and a late second Ctrl-C would kill the process with -2). A
    signal caught by CPython's C handler just before the switch is then found with no Python
    handler and reported, through ``sys.unraisablehook``, as ``OSError: Signal 2 ignored due to
    race condition`` with a traceback (seen in a test run of teleop_twist_keyboard: a
    terminal's Ctrl-C, then the orchestrator's SIGINT); that report is dropped, any other is
    passed on to the previous hook.

    :raises ValueError: when called outside the main thread (``signal.signal``'s rule).
    """
    global _previous_unraisablehook
    if sys.unraisablehook is not _unraisable:
        _previous_unraisablehook = sys.unraisablehook
        sys.unraisablehook = _unraisable
    _interrupted.set()
    for signum in _SIGNALS:
        signal.signal(signum, signal.SIG_IGN)


_previous_unraisablehook = None


def _unraisable(info):
    """Drop CPython's report of a signal that came just before its switch to ``SIG_IGN``."""
    if isinstance(info.exc_value, OSError) and \
            'ignored due to race condition' in str(info.exc_value):
        return  # the signal was to be ignored, and it was
    _previous_unraisablehook(info)


def _one_line(text):
    """Return ``text`` collapsed onto one line."""
    return ' '.join(str(text).split())


def _program(args):
    """Return the program name for error lines (``args[0]`` or ``sys.argv[0]``, basename)."""
    argv = sys.argv if args is None else args
    return os.path.basename(argv[0]) if argv and argv[0] else 'amr_description'


def fail(name, message):
    """
    Log ``message`` as one error line of logger ``name`` and exit with code 1.

    :raises SystemExit: always, code 1.
    """
    rclpy.logging.get_logger(name).error(_one_line(message))
    raise SystemExit(1)


class _QuietRcl:
    """Context: rcl's own error log lines off (rcl logs before raising; we print one line)."""

    def __init__(self, args):
        self._args = sys.argv if args is None else args

    def __enter__(self):
        self._previous = rclpy.logging.get_logger_level('rcl')
        rclpy.logging.set_logger_level('rcl', LoggingSeverity.FATAL)
        return self

    def __exit__(self, kind, value, traceback):
        user_set = any('rcl:=' in str(arg) for arg in self._args)  # --log-level rcl:=...
        if kind is not None or not user_set:
            rclpy.logging.set_logger_level('rcl', self._previous)
        return False


def init(args=None):
    """
    ``rclpy.init`` without rclpy's signal handlers; SIGINT/SIGTERM raise KeyboardInterrupt.

    :param args: command-line arguments for rclpy, program name first (default
        ``sys.argv``).
    :raises KeyboardInterrupt: on a signal during the initialisation.
    :raises SystemExit: code 1 after one error line when rcl cannot parse the ROS arguments
        (rcl's text, e.g. ``failed to initialize rcl: Couldn't parse parameter override rule:
        '-p robot_description:='. ...``).
    """
    for signum in _SIGNALS:
        signal.signal(signum, _interrupt)
    # a signal during rclpy.init is deferred (as inside spin): raised in the middle of rcl's
    # start-up it would leave an initialised context that nothing shuts down
    _spinning.set()
    try:
        with _QuietRcl(args):
            rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    except RuntimeError as exc:  # rclpy's RCLError: rcl_init failed on the arguments
        rclpy.try_shutdown()
        fail(_program(args), exc)
    finally:
        _spinning.clear()
    if _interrupted.is_set():
        rclpy.try_shutdown()
        raise KeyboardInterrupt


def remove_ros_args(args=None):
    """
    Return ``args`` without the ROS arguments (``rclpy.utilities.remove_ros_args``).

    :param args: command line, program name first (default ``sys.argv``).
    :raises SystemExit: code 1 after one error line when rcl cannot parse the ROS arguments.
    """
    argv = sys.argv if args is None else list(args)
    try:
        with _QuietRcl(argv):
            return rclpy.utilities.remove_ros_args(args=argv)
    except RuntimeError as exc:  # rclpy's RCLInvalidROSArgsError
        fail(_program(argv), exc)


def create(factory, *args, **kwargs):
    """
    Return ``factory(*args, **kwargs)`` (a node); a refused parameter exits with one line.

    :param factory: the node class (or any callable building the node).
    :raises SystemExit: code 1 after one error line when the constructor raises rclpy's
        ``ParameterException`` family (wrong type, out of range, not declared...) or a
        ``ValueError`` (a parameter value the node refuses).
    :raises KeyboardInterrupt: when a signal came during the construction, whatever the
        constructor then raised: a library that catches the ``KeyboardInterrupt`` raised in
        the middle of its import fails later with an unrelated error (trimesh, interrupted
        while importing its optional parts: ``TypeError: unsupported operand type(s) for |``).
    """
    try:
        return factory(*args, **kwargs)
    except Exception as exc:  # noqa: B902 - see above
        if _interrupted.is_set():
            raise KeyboardInterrupt from None
        if isinstance(exc, (InvalidParameterTypeException, InvalidParameterValueException,
                            ParameterException, ValueError)):
            fail(_program(None), exc)
        raise


def spin(target, until=None, period=SPIN_PERIOD):
    """
    Spin a node or an executor until a signal, ``until()`` or an external rclpy shutdown.

    :param target: an rclpy ``Node`` (spun by a private single-threaded executor) or an
        ``Executor``.
    :param until: optional callable returning True to stop spinning.
    :param period: seconds of each wait (the longest delay before a signal is seen).
    :raises KeyboardInterrupt: on SIGINT/SIGTERM, raised here once ``spin_once`` returned
        (never from inside an rclpy call); an error raised by ``spin_once`` after the signal
        is part of stopping and ignored.

    The executor's nodes on sim time have their ``/clock`` taken on a thread of its own
    (:func:`amr_description.ros.sim_time.take_clock_on_thread`), not by the executor.
    """
    from amr_description.ros.sim_time import take_clock_on_thread
    executor = target
    if not hasattr(target, 'spin_once'):
        executor = SingleThreadedExecutor(context=target.context)
        executor.add_node(target)
    for node in getattr(executor, 'get_nodes', list)():
        take_clock_on_thread(node)
    _spinning.set()
    try:
        while executor.context.ok() and not _interrupted.is_set() and \
                not (until is not None and until()):
            try:
                executor.spin_once(timeout_sec=period)
            except ExternalShutdownException:
                break
            except Exception:  # noqa: B902 - see below
                if not _interrupted.is_set():
                    raise
                break  # an entity torn down by the signal's shutdown: part of stopping
    finally:
        _spinning.clear()
        if executor is not target:
            executor.shutdown(timeout_sec=0)
    if _interrupted.is_set():
        raise KeyboardInterrupt


def shutdown(*nodes, executor=None):
    """
    Stop TF listener and clock threads, destroy ``nodes`` (None skipped), shut down the rest.

    Call it after stopping the program's own threads. Errors of a context already shut down
    elsewhere are ignored.

    :param nodes: rclpy nodes to destroy, in order.
    :param executor: optional executor to shut down after the nodes; rclpy is shut down last.
    """
    try:
        ignore_signals()
    except ValueError:  # not the main thread: signals are the main thread's business
        pass
    from amr_description.ros.sim_time import stop_clock_threads
    from amr_description.ros.transforms import stop_listener_threads
    for stop in (stop_listener_threads, stop_clock_threads):
        try:
            stop()
        except Exception:  # noqa: B902 - best effort at exit
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


def run(factory, args=None, threads=1):
    """
    Run one node as a program's ``main``: :func:`init`, :func:`create`, :func:`spin`, cleanup.

    :param factory: the node class (or a callable building the node).
    :param args: command-line arguments for rclpy (default ``sys.argv``).
    :param threads: 1 spins the node on a single-threaded executor; more use rclpy's
        ``MultiThreadedExecutor`` with that many threads (a node whose callbacks wait for
        other callbacks, e.g. a service that waits for a message). A node's
        ``companion_nodes`` (Nav2's costmap nodes beside their server) are spun with it on the
        same executor and destroyed before it.
    """
    from rclpy.executors import MultiThreadedExecutor
    node = executor = None
    companions = []
    try:
        init(args)
        node = create(factory)
        companions = list(getattr(node, 'companion_nodes', ()))
        if threads > 1:
            executor = MultiThreadedExecutor(num_threads=threads, context=node.context)
        elif companions:
            executor = SingleThreadedExecutor(context=node.context)
        if executor is not None:
            for each in [node] + companions:
                executor.add_node(each)
        spin(executor or node)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown(*companions, node, executor=executor)
