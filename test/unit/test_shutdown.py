# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The shared start/stop pattern: signals never raise inside rclpy, whole numbers for floats."""

import os
import signal

import pytest

rclpy = pytest.importorskip('rclpy')

from amr_description.ros import shutdown  # noqa: E402, I100 - after the skip
from amr_description.ros.node import Node  # noqa: E402
from conftest import next_domain_id  # noqa: E402
from conftest import release_domain_id  # noqa: E402


@pytest.fixture
def pattern(monkeypatch):
    """Run the pattern in this process on a private domain; restore signals afterwards."""
    domain = next_domain_id()
    monkeypatch.setenv('ROS_DOMAIN_ID', str(domain))
    monkeypatch.setenv('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    handlers = {signum: signal.getsignal(signum) for signum in (signal.SIGINT, signal.SIGTERM)}
    shutdown._interrupted.clear()
    yield shutdown
    rclpy.try_shutdown()
    shutdown._interrupted.clear()
    for signum, handler in handlers.items():
        signal.signal(signum, handler)
    release_domain_id(domain)


def test_signal_inside_a_callback_stops_spin_after_it(pattern):
    pattern.init(['test_shutdown'])
    node = pattern.create(Node, 'test_shutdown')
    steps = []

    def callback():
        steps.append('signal')
        os.kill(os.getpid(), signal.SIGINT)
        # Python code after the signal, as in a message's conversion inside take_message: the
        # handler must not raise here
        steps.extend(str(i) for i in range(1000))
        steps.append('done')

    node.create_timer(0.01, callback)
    with pytest.raises(KeyboardInterrupt):
        pattern.spin(node)
    assert steps[0] == 'signal' and steps[-1] == 'done' and steps.count('signal') == 1
    assert pattern.interrupted()
    pattern.shutdown(node)


def test_signal_outside_spin_raises_at_once(pattern):
    pattern.init(['test_shutdown'])
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGTERM)
        for _ in range(10 ** 7):  # the handler runs between these bytecodes
            pass
    os.kill(os.getpid(), signal.SIGINT)  # a second signal during the cleanup: ignored
    pattern.shutdown()


def test_signals_during_the_cleanup_are_ignored_without_a_race_report(pattern, monkeypatch):
    # a SIGINT caught by CPython's C handler just before the switch to SIG_IGN is reported as
    # "OSError: Signal 2 ignored due to race condition" with a traceback (teleop_twist_keyboard,
    # Ctrl-C then the orchestrator's SIGINT): that report is dropped, others are passed on
    import sys
    import types
    passed = []
    monkeypatch.setattr(sys, 'unraisablehook', lambda info: passed.append(str(info.exc_value)))
    pattern.init(['test_shutdown'])
    pattern.ignore_signals()
    for signum in (signal.SIGINT, signal.SIGTERM):
        # SIG_IGN, not a Python handler: finalization would reset that one to SIG_DFL
        assert signal.getsignal(signum) == signal.SIG_IGN
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGINT):
        os.kill(os.getpid(), signum)
    pattern.ignore_signals()  # a second call (shutdown() calls it again) changes nothing
    for text in ('Signal 2 ignored due to race condition', 'something else'):
        sys.unraisablehook(types.SimpleNamespace(
            exc_type=OSError, exc_value=OSError(text), exc_traceback=None,
            err_msg='Exception ignored in', object=None))
    assert passed == ['something else']
    assert pattern.interrupted()
    pattern.shutdown()


def test_an_error_after_a_signal_during_construction_is_the_interrupt(pattern):
    # trimesh catches a KeyboardInterrupt raised in the middle of its import and fails later
    # with a TypeError: the node's main must stop quietly, not print that traceback
    pattern.init(['test_shutdown'])

    def interrupted_import():
        try:
            os.kill(os.getpid(), signal.SIGINT)
            for _ in range(10 ** 7):  # the handler raises between these bytecodes
                pass
        except BaseException:  # noqa: B902 - as the library does
            pass
        raise TypeError("unsupported operand type(s) for |: 'ExceptionWrapper' and 'NoneType'")

    with pytest.raises(KeyboardInterrupt):
        pattern.create(interrupted_import)
    pattern._interrupted.clear()
    with pytest.raises(TypeError):  # without a signal, a bug stays a bug
        pattern.create(lambda: 1 / '2')
    pattern.shutdown()


def test_whole_number_for_a_float_parameter(pattern):
    pattern.init(['test_shutdown', '--ros-args', '-p', 'rate:=0', '-p', 'count:=2',
                  '-p', 'ratio:=3'])
    node = pattern.create(Node, 'test_shutdown')
    assert node.declare_parameter('rate', 1.5).value == 0.0
    assert isinstance(node.get_parameter('rate').value, float)
    assert node.declare_parameter('count', 1).value == 2  # integers stay integers
    assert node.declare_parameter(
        'ratio', rclpy.Parameter.Type.DOUBLE).value == 3.0
    pattern.shutdown(node)


def test_wrong_type_is_one_line_and_exit_1(pattern, capfd):
    pattern.init(['test_shutdown', '--ros-args', '-p', 'rate:=fast'])

    class Rated(Node):

        def __init__(self):
            super().__init__('test_shutdown')
            self.declare_parameter('rate', 1.5)

    with pytest.raises(SystemExit) as info:
        pattern.create(Rated)
    assert info.value.code == 1
    err = capfd.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'rate'" in err[0] and "expecting type 'DOUBLE'" in err[0]


def test_rcl_argument_error_is_one_line_and_exit_1(pattern, capfd):
    with pytest.raises(SystemExit) as info:
        pattern.init(['my_node', '--ros-args', '-p', 'robot_description:=<not xml: [>'])
    assert info.value.code == 1
    err = capfd.readouterr().err.strip().splitlines()
    assert len(err) == 1 and '[my_node]' in err[0]
    assert "Couldn't parse parameter override rule" in err[0]
    with pytest.raises(SystemExit):
        pattern.remove_ros_args(['my_node', '--ros-args', '-p', 'x:='])
    assert len(capfd.readouterr().err.strip().splitlines()) == 1


def test_a_signal_during_rclpy_init_stops_run_quietly(pattern, monkeypatch):
    # a stack stopped while a node is still starting (the viewer refused its port and the
    # orchestrator sent SIGINT): the KeyboardInterrupt that init raises is main's to catch
    real_init = rclpy.init
    built = []

    def init_then_signal(**kwargs):
        real_init(**kwargs)
        os.kill(os.getpid(), signal.SIGINT)  # deferred: init is in its rcl start-up

    monkeypatch.setattr(pattern.rclpy, 'init', init_then_signal)
    assert pattern.run(lambda: built.append(1), args=['test_shutdown']) is None
    assert built == [] and pattern.interrupted()
    assert not rclpy.ok()  # the context init made was shut down


def _calls_init(node):
    """Return True when ``node`` (an ast node) is a call of ``shutdown.init`` or ``init``."""
    import ast
    if not isinstance(node, ast.Call):
        return False
    func = node.func
    return (isinstance(func, ast.Attribute) and func.attr == 'init' and
            isinstance(func.value, ast.Name) and func.value.id == 'shutdown') or \
        (isinstance(func, ast.Name) and func.id == 'init')


def test_every_main_calls_init_inside_its_interrupt_handler():
    # init raises KeyboardInterrupt on a signal during the start-up: called before the try
    # (as every main once did), that is a traceback in a stopping stack's log
    import ast
    import pathlib
    root = pathlib.Path(shutdown.__file__).resolve().parents[1]
    outside = []
    calls = 0
    for path in sorted(root.rglob('*.py')):
        tree = ast.parse(path.read_text(), str(path))
        for function in ast.walk(tree):
            if not isinstance(function, ast.FunctionDef) or \
                    not function.name.startswith(('main', 'run')):
                continue  # a helper's interrupt goes to the main that called it
            guarded = set()
            for node in ast.walk(function):
                if isinstance(node, ast.Try) and any(
                        handler.type is not None and
                        'KeyboardInterrupt' in ast.unparse(handler.type)
                        for handler in node.handlers):
                    for statement in node.body:
                        guarded.update(id(each) for each in ast.walk(statement))
            for node in ast.walk(function):
                if _calls_init(node):
                    calls += 1
                    if id(node) not in guarded:
                        outside.append(f'{path.relative_to(root)}:{node.lineno}')
    assert calls >= 15
    assert outside == []
