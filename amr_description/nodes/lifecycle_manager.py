# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``lifecycle_manager``: Nav2's lifecycle manager (nav2_lifecycle_manager, Jazzy).

Parameters: ``node_names`` (string array, the managed nodes relative to this node's
namespace), ``autostart`` (false: STARTUP at start-up when true), ``bond_timeout`` (4.0 s;
0 disables bonds), ``bond_respawn_max_duration`` (10.0 s) and
``attempt_respawn_reconnection`` (true). Services ``~/manage_nodes``
(``nav2_msgs/srv/ManageLifecycleNodes``) and ``~/is_active`` (``std_srvs/srv/Trigger``,
success when the managed nodes are active).

Each node is driven through its ``<node>/change_state`` and checked with ``<node>/get_state``
(the plan is :mod:`amr_description.core.lifecycle_plan`); a transition that fails, or leaves
the node in another state, stops the command with ``Failed to change state for node: X``.
A transition is waited for without a limit, as Nav2's manager does (a costmap's activation
waits for TF up to its ``initial_transform_timeout``). Unlike Nav2, before each transition a
node is asked ``get_state`` (every second, for up to 10 s) until it answers, and while a
``change_state`` has no answer the node is asked ``get_state`` every 10 s: a node reporting a
primary state has finished, and the transition counts as done when that is the goal state;
one whose services are gone (its process ended) counts as failed.
rmw_fastrtps drops a service response whose client reader the server has not matched within
100 ms ("failed to send response ... (timeout)", also reported against Nav2's bring-up in
ros2/rmw_fastrtps#706), which a loaded machine met in one of six bring-ups.
After a node is activated and ``bond_timeout`` is above 0, a bond (topic ``bond``, id = the
node's name, heartbeat period 0.1 s, timeout ``bond_timeout``) must form within
``bond_timeout / 2``. While the system is active the bonds are checked every 0.2 s; a broken
one resets every node (deactivate, cleanup) and, with ``attempt_respawn_reconnection``, the
manager starts them up again once all of them answer, for up to ``bond_respawn_max_duration``.
The commands (start-up, ``~/manage_nodes``, the bond checks and the respawn) run one after
the other on a thread of their own while a single-threaded executor keeps answering, as
Nav2's manager runs its service callbacks apart from the executor that hears the managed
nodes' responses. (rclpy's ``MultiThreadedExecutor``, used before, woke 20-50 times for each
message, timer and ``/clock`` tick it dispatched: 49-74 % of a core for a manager that sits
idle; docs/navigation.md, "The lifecycle managers' executor".)
Source: ``nav2_lifecycle_manager/src/lifecycle_manager.cpp``.
"""

import queue
import threading
import time

from amr_description.core import lifecycle_plan
from amr_description.ros import shutdown
from amr_description.ros.bond import Bond
from amr_description.ros.bond import prepare_bonds
from amr_description.ros.node import Node
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
from lifecycle_msgs.srv import GetState
from nav2_msgs.srv import ManageLifecycleNodes
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup
from rclpy.task import Future
from std_srvs.srv import Trigger

SERVICE_WAIT = 2.0
"""Seconds between "Waiting for ..." lines while a managed node's services are absent."""

CALL_TIMEOUT = 10.0
"""Seconds a change_state or get_state call may take before it counts as failed."""

FIRST_CALL_RETRY = 1.0
"""Seconds between the get_state requests sent until a managed node first answers one."""

BOND_HEARTBEAT_PERIOD = 0.1
BOND_CHECK_PERIOD = 0.2
RESPAWN_CHECK_PERIOD = 1.0


class _Managed:
    """The lifecycle service clients of one managed node."""

    def __init__(self, node, name):
        self.name = name
        self.change_state = node.create_client(ChangeState, f'{name}/change_state')
        self.get_state = node.create_client(GetState, f'{name}/get_state')

    def ready(self):
        return self.change_state.service_is_ready() and self.get_state.service_is_ready()


class CommandThread:
    """
    One daemon thread that runs the calls handed to it, one at a time, in order.

    A call waits there for the managed nodes' answers, which the node's executor (another
    thread) takes meanwhile. :meth:`submit` returns an rclpy ``Future`` of the call's result
    (or of the exception it raised), completed through ``executor`` so that a coroutine
    callback awaiting it is woken. An exception raised by a call is also one error line on
    ``logger`` (none is awaited for the timers' calls).
    """

    def __init__(self, name, logger):
        """Start the thread (named ``name``); ``logger``: an rclpy logger for the errors."""
        self._logger = logger
        self._queue = queue.SimpleQueue()
        self._thread = threading.Thread(target=self._loop, daemon=True, name=name)
        self._thread.start()

    def submit(self, call, executor=None):
        """Queue ``call()``; return its ``Future``."""
        future = Future(executor=executor)
        future.add_done_callback(lambda _: None)  # wakes the executor when it is set
        self._queue.put((future, call))
        return future

    def _loop(self):
        while True:
            item = self._queue.get()
            if item is None:
                return
            future, call = item
            try:
                future.set_result(call())
            except Exception as exc:  # noqa: B902 - one line, and handed to the awaiting
                self._logger.error(str(exc) or type(exc).__name__)
                future.set_exception(exc)

    def stop(self):
        """Let the thread end after the call it runs (the queued ones are dropped)."""
        while True:
            try:
                self._queue.get_nowait()
            except queue.Empty:
                break
        self._queue.put(None)


class LifecycleManager(Node):
    """Node ``lifecycle_manager``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters, create the clients and services, start up if asked."""
        super().__init__('lifecycle_manager', **kwargs)
        self.node_names = list(self.declare_parameter('node_names', ['']).value or [])
        self.node_names = [n for n in self.node_names if n]
        self.autostart = bool(self.declare_parameter('autostart', False).value)
        self.bond_timeout = float(self.declare_parameter('bond_timeout', 4.0).value)
        self.respawn_max = float(
            self.declare_parameter('bond_respawn_max_duration', 10.0).value)
        self.attempt_respawn = bool(
            self.declare_parameter('attempt_respawn_reconnection', True).value)
        self._commands = CommandThread(f'{self.get_name()}_commands', self.get_logger())
        self._checking = False  # a bond check is queued or running
        self.system_active = False
        self.bonds = {}  # touched only on the command thread
        if self.bond_timeout > 0.0:
            prepare_bonds(self, 'bond')  # matched with the nodes' long before a bond forms
        self._respawn_since = self._respawn_timer = None
        self.get_logger().info('Creating and initializing lifecycle service clients')
        self.managed = {name: _Managed(self, name) for name in self.node_names}
        # a group of its own: its callback stays in execution while it awaits the command, and
        # the clients' and bonds' callbacks (the default group) must run meanwhile
        self.create_service(ManageLifecycleNodes, '~/manage_nodes', self._on_manage,
                            callback_group=MutuallyExclusiveCallbackGroup())
        self.create_service(Trigger, '~/is_active', self._on_is_active)
        self._bond_timer = self.create_timer(BOND_CHECK_PERIOD, self._on_bond_timer)
        if self.autostart:
            self._autostart_timer = self.create_timer(0.0, self._autostart)

    # services
    def _autostart(self):
        self._autostart_timer.cancel()
        self._commands.submit(lambda: self.run(lifecycle_plan.STARTUP))

    async def _on_manage(self, request, response):
        done = self._commands.submit(lambda: self.run(request.command), self.executor)
        try:
            response.success = bool(await done)
        except Exception:  # noqa: B902 - the command thread logged it
            response.success = False
        return response

    def _on_is_active(self, request, response):
        response.success = self.system_active
        return response

    # commands
    def run(self, command, hard=False):
        """
        Carry out a ``ManageLifecycleNodes`` command on the managed nodes.

        :param command: the command (0..6).
        :param hard: keep going after a failed step (a reset after a broken bond).
        :returns: True when every step succeeded.
        :raises ValueError: for an unknown command.
        """
        steps = lifecycle_plan.plan(command, self.node_names)
        before, after = lifecycle_plan.MESSAGES[command]
        log = self.get_logger()
        log.info(before)
        if command != lifecycle_plan.STARTUP:
            self.system_active = False
        if lifecycle_plan.DEACTIVATE in {s.transition for s in steps}:
            self._destroy_bonds()
        ok = True
        for step in steps:
            if hard and not self.managed[step.node].ready():
                log.error(f'Failed to change state for node: {step.node}')
                ok = False
                continue  # a node that is gone cannot be reset
            if not self._wait_for(self.managed[step.node]):
                return False
            log.info(step.line)
            if not self._change(step):
                log.error(f'Failed to change state for node: {step.node}')
                ok = False
                if hard:
                    continue
                if command == lifecycle_plan.STARTUP:
                    log.error('Failed to bring up all requested nodes. Aborting bringup.')
                return False
            if step.transition == lifecycle_plan.ACTIVATE and not self._bond(step.node):
                return False
        if ok:
            log.info(after)
        self.system_active = ok and lifecycle_plan.ACTIVE_AFTER[command]
        return ok

    def _wait_for(self, managed):
        while not managed.ready():
            if not self.context.ok() or shutdown.interrupted():
                return False
            self.get_logger().info(f'Waiting for service {managed.name}/get_state...')
            managed.get_state.wait_for_service(timeout_sec=SERVICE_WAIT)
            managed.change_state.wait_for_service(timeout_sec=0.1)
        return True

    def _call(self, client, request, timeout=CALL_TIMEOUT):
        done = threading.Event()
        future = client.call_async(request)
        future.add_done_callback(lambda _: done.set())
        if not done.wait(timeout):
            client.remove_pending_request(future)
            return None
        return future.result()

    def _first_answer(self, managed):
        """Ask get_state until it answers: then the node's responses reach this node."""
        deadline = time.monotonic() + CALL_TIMEOUT
        while time.monotonic() < deadline and self.context.ok() and not shutdown.interrupted():
            if self._call(managed.get_state, GetState.Request(), FIRST_CALL_RETRY) is not None:
                return True
        return False

    def _change(self, step):
        managed = self.managed[step.node]
        if not self._first_answer(managed):  # a respawned node is a new process: ask each time
            return False
        request = ChangeState.Request()
        request.transition = Transition(id=step.transition)
        done = threading.Event()
        future = managed.change_state.call_async(request)
        future.add_done_callback(lambda _: done.set())
        # as Nav2's, no limit on the transition itself (a costmap's activate waits up to its
        # initial_transform_timeout for TF); every CALL_TIMEOUT without an answer the node is
        # asked for its state: a node busy in the transition does not answer, or answers with
        # a transition state, and is waited for; a finished one (its response dropped: rmw
        # fastrtps drops one whose reader it has not matched within 100 ms) ends the wait
        while not done.wait(CALL_TIMEOUT):
            if not self.context.ok() or shutdown.interrupted():
                managed.change_state.remove_pending_request(future)
                return False
            state = self._call(managed.get_state, GetState.Request(), FIRST_CALL_RETRY)
            if state is None and not managed.get_state.service_is_ready():
                managed.change_state.remove_pending_request(future)
                return False  # the node is gone (its process ended mid-transition)
            ended = lifecycle_plan.settled(
                None if state is None else state.current_state.id, step.goal)
            if ended is not None:
                managed.change_state.remove_pending_request(future)
                return ended
        answer = future.result()
        return answer is not None and answer.success

    # bonds
    def _bond(self, name):
        if self.bond_timeout <= 0.0:
            return True
        bond = Bond(self, 'bond', name, heartbeat_period=BOND_HEARTBEAT_PERIOD,
                    heartbeat_timeout=self.bond_timeout)
        self.bonds[name] = bond
        if not bond.wait_until_formed(self.bond_timeout / 2.0):
            self.get_logger().error(
                f'Server {name} was unable to be reached after {self.bond_timeout / 2.0:.2f}s '
                'by bond. This server may be misconfigured.')
            return False
        self.get_logger().info(f'Server {name} connected with bond.')
        return True

    def _destroy_bonds(self):
        bonds, self.bonds = self.bonds, {}
        for bond in bonds.values():
            bond.destroy()

    def _on_bond_timer(self):
        if self._checking or not self.system_active:
            return
        self._checking = True
        self._commands.submit(self._check_bonds)

    def _check_bonds(self):
        try:
            self._check_bonds_now()
        finally:
            self._checking = False

    def _check_bonds_now(self):
        if not self.system_active or not self.bonds:
            return
        broken = [name for name, bond in self.bonds.items() if bond.broken]
        if not broken:
            return
        name = broken[0]
        log = self.get_logger()
        log.info(f'Have not received a heartbeat from {name}.')
        log.error(f'CRITICAL FAILURE: SERVER {name} IS DOWN after not receiving a heartbeat '
                  f'for {int(self.bond_timeout * 1000)} ms. Shutting down related nodes.')
        self.run(lifecycle_plan.RESET, hard=True)
        if self.attempt_respawn:
            self._respawn_since = time.monotonic()
            self._respawn_timer = self.create_timer(
                RESPAWN_CHECK_PERIOD,
                lambda: self._commands.submit(self._check_respawn))

    def _check_respawn(self):
        if self._respawn_timer is None:
            return  # a check queued before the timer went
        if all(m.ready() for m in self.managed.values()):
            self._stop_respawn()
            self.run(lifecycle_plan.STARTUP)
        elif time.monotonic() - self._respawn_since > self.respawn_max:
            self._stop_respawn()
            self.get_logger().error(
                f'Failed to bring up all requested nodes after {self.respawn_max:.2f} seconds. '
                'Check that all nodes are functioning properly.')

    def _stop_respawn(self):
        timer, self._respawn_timer = self._respawn_timer, None
        self.destroy_timer(timer)

    def destroy_node(self):
        """Stop the command thread, destroy the bonds, then the node."""
        self._commands.stop()
        self._destroy_bonds()
        super().destroy_node()


def main(args=None):
    """
    Run the lifecycle manager until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(LifecycleManager, args)


if __name__ == '__main__':
    main()
