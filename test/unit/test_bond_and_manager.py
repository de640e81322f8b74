# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Bonds formed on a heartbeat heard just before they start; the lifecycle manager's lost answers.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes.
"""

import threading
import time

import pytest

rclpy = pytest.importorskip('rclpy')
pytest.importorskip('bond.msg')

import rclpy.executors  # noqa: E402, I100
import rclpy.node  # noqa: E402

from amr_description.core import lifecycle_plan as lp  # noqa: E402, I100
from amr_description.ros import bond as bond_module  # noqa: E402
from amr_description.ros.bond import Bond  # noqa: E402
from amr_description.ros.bond import prepare_bonds  # noqa: E402
from lifecycle_msgs.srv import ChangeState  # noqa: E402

SLOW = 30.0
"""A heartbeat period (s) longer than any test: a bond sends its first status only."""


def test_a_bond_forms_on_the_sisters_status_heard_before_it_started(ros):
    make, spin_until = ros
    server, manager = make('server'), make('manager')
    endpoint, other = prepare_bonds(manager, 'bond'), prepare_bonds(server, 'bond')
    assert spin_until(lambda: endpoint.publisher.get_subscription_count() >= 2 and
                      other.publisher.get_subscription_count() >= 2)
    sister = Bond(server, 'bond', 'server', heartbeat_period=SLOW)  # one status, now
    assert spin_until(lambda: 'server' in endpoint.last)
    bond = Bond(manager, 'bond', 'server', heartbeat_period=SLOW)
    assert bond.formed  # bondcpp would wait SLOW seconds for the next heartbeat
    assert not bond.broken
    sister.destroy()  # says active: false once
    assert spin_until(lambda: bond.broken)


def test_a_dead_or_old_status_does_not_form_or_break_a_new_bond(ros, monkeypatch):
    make, spin_until = ros
    server, manager = make('server2'), make('manager2')
    endpoint, other = prepare_bonds(manager, 'bond'), prepare_bonds(server, 'bond')
    assert spin_until(lambda: endpoint.publisher.get_subscription_count() >= 2 and
                      other.publisher.get_subscription_count() >= 2)
    sister = Bond(server, 'bond', 'server2', heartbeat_period=SLOW)
    assert spin_until(lambda: 'server2' in endpoint.last)
    monkeypatch.setattr(bond_module, 'RECENT', -1.0)  # heard too long ago
    old = Bond(manager, 'bond', 'server2', heartbeat_period=SLOW)
    assert not old.formed and not old.broken
    old.destroy()
    monkeypatch.undo()
    sister.destroy()
    assert spin_until(lambda: not endpoint.last['server2'][1].active)
    fresh = Bond(manager, 'bond', 'server2', heartbeat_period=SLOW)
    assert not fresh.formed and not fresh.broken
    fresh.destroy()


def test_composed_nodes_share_one_endpoint_per_topic_and_still_bond(ros, monkeypatch):
    make, spin_until = ros
    monkeypatch.setattr(bond_module, '_sharing', [])
    monkeypatch.setattr(bond_module, '_PROCESS_ENDPOINTS', {})
    alone = [prepare_bonds(make('alone_a'), 'bond'), prepare_bonds(make('alone_b'), 'bond')]
    assert alone[0] is not alone[1]  # a process's nodes have their own until told to share
    bond_module.share_endpoints()
    server, manager = make('server3'), make('manager3')
    endpoint = prepare_bonds(manager, 'bond')
    assert prepare_bonds(server, 'bond') is endpoint
    assert prepare_bonds(make('other_topic'), 'other_bond') is not endpoint
    # one subscription per node alone, one for all of the sharing nodes
    assert spin_until(lambda: manager.count_subscribers('/bond') == 3)
    sister = Bond(server, 'bond', 'server3', heartbeat_period=0.1)
    bond = Bond(manager, 'bond', 'server3', heartbeat_period=0.1)
    assert spin_until(lambda: bond.formed and sister.formed)
    assert not bond.broken and not sister.broken
    sister.destroy()
    assert spin_until(lambda: bond.broken)
    bond.destroy()


def test_a_nodes_bonds_share_one_heartbeat_timer_and_hear_without_its_executor(ros):
    make, spin_until = ros
    server, manager = make('server4'), make('manager4')
    timers = len(list(manager.timers))
    endpoint, other = prepare_bonds(manager, 'bond'), prepare_bonds(server, 'bond')
    assert spin_until(lambda: endpoint.publisher.get_subscription_count() >= 2 and
                      other.publisher.get_subscription_count() >= 2)
    bonds = [Bond(manager, 'bond', f'server4_{i}', heartbeat_period=SLOW) for i in range(3)]
    assert len(list(manager.timers)) == timers + 1  # bondcpp: one timer per bond
    # statuses are taken on the endpoint's thread: nothing spins the nodes here
    sister = Bond(server, 'bond', 'server4_1', heartbeat_period=SLOW)  # one status, now
    deadline = time.monotonic() + 30.0
    while not bonds[1].formed and time.monotonic() < deadline:
        time.sleep(0.02)
    assert bonds[1].formed and not bonds[0].formed
    sister.destroy()  # says active: false once
    while not bonds[1].broken and time.monotonic() < deadline:
        time.sleep(0.02)
    assert bonds[1].broken and not bonds[0].broken and not bonds[2].broken
    for bond in bonds:
        bond.destroy()
    assert len(list(manager.timers)) == timers


class _ChangeClient:
    """A change_state client whose answer never comes (dropped) or comes when told."""

    def __init__(self):
        from rclpy.task import Future
        self.futures, self.removed, self.Future = [], [], Future

    def call_async(self, request):
        assert isinstance(request, ChangeState.Request)
        self.futures.append(self.Future())
        return self.futures[-1]

    def remove_pending_request(self, future):
        self.removed.append(future)


def test_manager_waits_for_a_transition_and_counts_a_dropped_answer_by_get_state(
        ros, monkeypatch):
    from amr_description.nodes import lifecycle_manager as lm
    from lifecycle_msgs.msg import State
    from lifecycle_msgs.srv import GetState
    make, spin_until = ros
    monkeypatch.setattr(lm, 'CALL_TIMEOUT', 0.05)
    manager = lm.LifecycleManager.__new__(lm.LifecycleManager)
    rclpy.node.Node.__init__(manager, 'lifecycle_manager_t', context=make('unused').context)
    manager.node_names, manager.bonds = ['m'], {}
    manager._commands = lm.CommandThread('lifecycle_manager_t_commands', manager.get_logger())
    change = _ChangeClient()
    get = type('GetClient', (), {'ready': True, 'service_is_ready': lambda self: self.ready})()
    manager.managed = {'m': type('Managed', (), {'change_state': change, 'get_state': get})()}
    reports = [lp.ACTIVE]  # get_state's answers, the last one repeated; None: no answer

    def call(client, request, timeout=None):
        assert client is get and isinstance(request, GetState.Request)
        state = reports.pop(0) if len(reports) > 1 else reports[0]
        if state is None:
            return None
        answer = GetState.Response()
        answer.current_state = State(id=state)
        return answer

    monkeypatch.setattr(manager, '_call', call)
    step = lp.plan(lp.RESUME, ['m'])[0]
    assert manager._change(step)  # the answer was dropped, the node is active
    reports[:] = [lp.INACTIVE, lp.INACTIVE]  # the transition did not happen
    assert not manager._change(step)
    assert len(change.removed) == 2
    # busy in the transition (no answer, then "activating"): waited for until it answers
    reports[:] = [lp.INACTIVE, None, State.TRANSITION_STATE_ACTIVATING, None]
    answered = threading.Timer(0.5, lambda: change.futures[-1].set_result(
        ChangeState.Response(success=True)))
    answered.start()
    started = time.monotonic()
    assert manager._change(step)
    assert time.monotonic() - started >= 0.4 and len(change.removed) == 2
    # the node's process ended mid-transition: no answer and no service, a failure
    reports[:] = [lp.INACTIVE, None]
    get.ready = False
    assert not manager._change(step)
    assert len(change.removed) == 3
    manager.destroy_node()


def test_command_thread_runs_calls_in_order_and_hands_back_results_and_errors():
    from amr_description.nodes import lifecycle_manager as lm
    errors = []
    logger = type('Logger', (), {'error': lambda self, line: errors.append(line)})()
    commands = lm.CommandThread('t_commands', logger)
    ran = []
    gate = threading.Event()
    first = commands.submit(lambda: (gate.wait(5.0), ran.append(1), 'one')[-1])
    second = commands.submit(lambda: ran.append(2) or 2)
    failing = commands.submit(lambda: int('x'))
    assert not first.done() and not second.done()  # the first call holds the thread
    gate.set()
    deadline = time.monotonic() + 5.0
    while not failing.done() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert (first.result(), second.result(), ran) == ('one', 2, [1, 2])
    with pytest.raises(ValueError):
        failing.result()
    assert errors == ["invalid literal for int() with base 10: 'x'"]  # one line, not awaited
    commands.stop()
    commands._thread.join(5.0)
    assert not commands._thread.is_alive()
