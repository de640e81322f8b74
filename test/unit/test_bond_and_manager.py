# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Bonds formed on a heartbeat heard just before they start; the lifecycle manager's lost answers.

In-process rclpy (own ROS_DOMAIN_ID, localhost discovery), no processes.
"""

import os
import time

from conftest import next_domain_id
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


@pytest.fixture
def ros():
    os.environ['ROS_DOMAIN_ID'] = str(next_domain_id())
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    context = rclpy.context.Context()
    rclpy.init(context=context)
    executor = rclpy.executors.SingleThreadedExecutor(context=context)
    nodes = []

    def make(name):
        node = rclpy.node.Node(name, context=context)
        executor.add_node(node)
        nodes.append(node)
        return node

    def spin_until(condition, timeout=30.0):
        deadline = time.monotonic() + timeout
        while not condition() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
        return condition()

    yield make, spin_until
    for node in nodes:
        node.destroy_node()
    executor.shutdown()
    rclpy.shutdown(context=context)


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


def test_manager_counts_an_unanswered_transition_done_when_get_state_says_so(ros, monkeypatch):
    from amr_description.nodes.lifecycle_manager import LifecycleManager
    from lifecycle_msgs.msg import State
    from lifecycle_msgs.srv import GetState
    make, spin_until = ros
    manager = LifecycleManager.__new__(LifecycleManager)
    rclpy.node.Node.__init__(manager, 'lifecycle_manager_t', context=make('unused').context)
    manager.node_names, manager.bonds = ['m'], {}
    manager.managed = {'m': type('Managed', (), {'change_state': 'change',
                                                 'get_state': 'get'})()}
    reports = {'state': lp.ACTIVE}

    def call(client, request, timeout=None):
        if client == 'change':
            assert isinstance(request, ChangeState.Request)
            return None  # the answer was dropped
        answer = GetState.Response()
        answer.current_state = State(id=reports['state'])
        return answer

    monkeypatch.setattr(manager, '_call', call)
    step = lp.plan(lp.RESUME, ['m'])[0]
    assert manager._change(step)
    reports['state'] = lp.INACTIVE  # the transition did not happen
    assert not manager._change(step)
    manager.destroy_node()
