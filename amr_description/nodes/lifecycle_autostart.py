# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What a launch file's lifecycle events do: configure, then activate, a lifecycle node.

slam_toolbox's ``online_async_launch.py`` (with ``autostart`` and no lifecycle manager)
emits ``ChangeState(TRANSITION_CONFIGURE)`` and, on the node reaching *inactive*,
``TRANSITION_ACTIVATE``; launch_ros does it through a node of its own named
``launch_ros_<pid>``. This program is that node for our stacks: ``lifecycle_autostart NODE
[TRANSITION ...]`` (default ``configure activate``) waits up to 60 s for
``NODE/change_state``, requests each transition in turn and exits 0, or 1 with one line
naming the node and the transition that failed.

Before each transition the node is asked ``get_state`` until it answers, and while the
``change_state`` has no answer it is asked again every :data:`CHECK_PERIOD` s: a node in the
transition's goal state has made it, and the wait ends there; any other answer ends it only
after :data:`SERVICE_WAIT` s, as a failure. rmw_fastrtps drops a service response whose
client reader the server has not matched within 100 ms
(:func:`amr_description.core.lifecycle_plan.settled`): on a loaded machine, in a clean-clone
test run, the SLAM node configured but its answer never came, and the stack stopped after
60 s.
"""

import os
import sys
import time

from amr_description.core import lifecycle_plan
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
from lifecycle_msgs.srv import GetState
from rclpy.executors import SingleThreadedExecutor

SERVICE_WAIT = 60.0
"""Seconds to wait for the node's services, and for each transition to end."""

CHECK_PERIOD = 2.0
"""Seconds between ``get_state`` requests while a ``change_state`` has no answer."""

TRANSITIONS = {'configure': Transition.TRANSITION_CONFIGURE,
               'activate': Transition.TRANSITION_ACTIVATE}


def _waiter(executor):
    """Return ``wait(future, timeout)``: spin ``executor`` the house way until done or late."""
    def wait(future, timeout):
        deadline = time.monotonic() + timeout
        shutdown.spin(executor, until=lambda: future.done() or time.monotonic() > deadline)
    return wait


def _call(wait, client, request, timeout):
    """Return the response of one service call, or None after ``timeout`` s."""
    future = client.call_async(request)
    wait(future, timeout)
    if not future.done():
        client.remove_pending_request(future)
        return None
    return future.result()


def _state(wait, get_state):
    """Return the node's ``current_state.id``, or None without an answer."""
    answer = _call(wait, get_state, GetState.Request(), CHECK_PERIOD)
    return None if answer is None else answer.current_state.id


def _transition(wait, change_state, get_state, transition):
    """Request ``transition`` (an id); return True when the node reached its goal state."""
    deadline = time.monotonic() + SERVICE_WAIT
    while _state(wait, get_state) is None:  # the node answers: it is up and not busy
        if time.monotonic() > deadline:
            return False
    goal = lifecycle_plan.GOAL_STATE[transition]
    future = change_state.call_async(ChangeState.Request(transition=Transition(id=transition)))
    while True:
        wait(future, CHECK_PERIOD)
        if future.done():
            return future.result().success
        # the goal state ends the wait at once; any other state only at the deadline (the
        # node may answer get_state before it takes the change_state request)
        reached = lifecycle_plan.settled(_state(wait, get_state), goal)
        if reached or time.monotonic() > deadline:
            change_state.remove_pending_request(future)
            return bool(reached)


def main(args=None):
    """Run the transitions (see the module docstring); return the exit code."""
    argv = shutdown.remove_ros_args(args if args is not None else sys.argv)[1:]
    if not argv or any(t not in TRANSITIONS for t in argv[1:]):
        print('usage: lifecycle_autostart NODE [configure|activate ...]', file=sys.stderr)
        return 2
    target, steps = argv[0], argv[1:] or ['configure', 'activate']
    node = executor = None
    code = 0
    try:
        shutdown.init(args)
        node = Node(f'launch_ros_{os.getpid()}')
        executor = SingleThreadedExecutor(context=node.context)
        executor.add_node(node)
        wait = _waiter(executor)
        change_state = node.create_client(ChangeState, f'{target}/change_state')
        get_state = node.create_client(GetState, f'{target}/get_state')
        if not change_state.wait_for_service(timeout_sec=SERVICE_WAIT) or \
                not get_state.wait_for_service(timeout_sec=SERVICE_WAIT):
            shutdown.fail('lifecycle_autostart',
                          f'{target}/change_state not offered after {SERVICE_WAIT:g} s')
        for step in steps:
            if not _transition(wait, change_state, get_state, TRANSITIONS[step]):
                shutdown.fail('lifecycle_autostart', f"{target}: transition '{step}' failed")
    except KeyboardInterrupt:
        code = 130
    finally:
        shutdown.shutdown(node, executor=executor)
    return code


if __name__ == '__main__':
    sys.exit(main())
