# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
One client of a simulator's simulation_interfaces services: spawn, pause, step, time, world.

Used by ``create`` (spawn) and ``drive_square`` (lock-step: pause, the paused time, step).
Every wait spins the caller's node through ``spin_until(predicate)``, so the caller keeps its
own executor and signal handling (:func:`amr_description.ros.shutdown.spin`); rclpy's
``spin_until_future_complete`` with a time-out busy-loops and would starve a simulator on the
same machine.
"""

import collections
import math
import time

from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rosgraph_msgs.msg import Clock

SIM_NODE = '/mujoco_sim'
"""Fully qualified name of the simulator node whose ``~/`` services are called."""

RETRY_PERIOD = 10.0
"""Seconds without an answer after which a spawn request is sent again from a new client."""


class SimulationServices:
    """
    The simulation_interfaces services of one simulator node, called from ``node``.

    :param node: the calling rclpy node.
    :param spin_until: ``(predicate) -> None`` spinning ``node`` until ``predicate()`` is
        true; the predicates given here hold their own deadline.
    :param sim_node: fully qualified name of the simulator node.
    :param spawn_service: name of the SpawnEntity service (``create -service``).
    """

    def __init__(self, node, spin_until, sim_node=SIM_NODE, spawn_service=None):
        """Keep the node; clients are created on first use."""
        from simulation_interfaces import msg
        from simulation_interfaces import srv
        self._msg, self._srv = msg, srv
        self.node = node
        self.sim_node = sim_node
        self.spawn_service = spawn_service or f'{sim_node}/spawn_entity'
        self._spin_until = spin_until
        self._clients = {}

    def _client(self, kind, name):
        if name not in self._clients:
            self._clients[name] = self.node.create_client(kind, name)
        return self._clients[name]

    def call(self, client, request, timeout):
        """
        Call a service and return its response, or None after ``timeout`` wall seconds.

        :param client: an rclpy client.
        :param request: its request message.
        :param timeout: wall seconds for the service to appear and for the answer each.
        """
        deadline = time.monotonic() + timeout
        self._spin_until(lambda: client.service_is_ready() or time.monotonic() > deadline)
        if not client.service_is_ready():
            return None
        future = client.call_async(request)
        deadline = time.monotonic() + timeout
        self._spin_until(lambda: future.done() or time.monotonic() > deadline)
        if not future.done():
            client.remove_pending_request(future)
            return None
        return future.result()

    # ------------------------------------------------------------------ state
    def set_paused(self, paused, timeout=30.0):
        """
        Pause or play the simulator (``~/set_simulation_state``); being there already is ok.

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        kind = self._srv.SetSimulationState
        request = kind.Request()
        state = self._msg.SimulationState
        request.state.state = state.STATE_PAUSED if paused else state.STATE_PLAYING
        name = f'{self.sim_node}/set_simulation_state'
        answer = self.call(self._client(kind, name), request, timeout)
        if answer is None:
            raise RuntimeError(f'{name} did not answer')
        if answer.result.result not in (self._msg.Result.RESULT_OK,
                                        kind.Response.ALREADY_IN_TARGET_STATE):
            raise RuntimeError(f'{name}: {answer.result.error_message}')

    def step(self, steps, timeout=30.0):
        """
        Advance the paused simulator ``steps`` physics steps (``~/step_simulation``).

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        kind = self._srv.StepSimulation
        name = f'{self.sim_node}/step_simulation'
        answer = self.call(self._client(kind, name), kind.Request(steps=int(steps)), timeout)
        if answer is None:
            raise RuntimeError(f'{name} did not answer within {timeout:g} s')
        if answer.result.result != self._msg.Result.RESULT_OK:
            raise RuntimeError(f'{name}: {answer.result.error_message}')

    def physics_step(self, timeout=30.0, default=0.001):
        """Return the simulator's ``physics_step`` parameter (s), ``default`` when unread."""
        from rcl_interfaces.msg import ParameterType
        from rcl_interfaces.srv import GetParameters
        client = self.node.create_client(GetParameters, f'{self.sim_node}/get_parameters')
        try:
            answer = self.call(client, GetParameters.Request(names=['physics_step']), timeout)
        finally:
            self.node.destroy_client(client)
        if answer is not None and answer.values and \
                answer.values[0].type == ParameterType.PARAMETER_DOUBLE:
            return answer.values[0].double_value
        return default

    def paused_time(self, timeout=30.0):
        """
        Return the time (s) at which the paused simulator stands, read from ``/clock``.

        When the pause is answered, /clock messages of the running simulator may still be in
        flight; a paused ``mujoco_sim`` repeats its time on /clock every 0.1 s of wall time,
        so two equal values in a row are that time. The subscription lives only while read.

        :raises RuntimeError: one line when /clock does not repeat a value within
            ``timeout`` (the simulator is not paused or publishes no /clock).
        """
        values = collections.deque(maxlen=2)  # nanoseconds of the last two messages
        # best effort matches any /clock publisher; a lost message only delays the answer
        subscription = self.node.create_subscription(
            Clock, '/clock', lambda msg: values.append(msg.clock.sec * 1_000_000_000 +
                                                       msg.clock.nanosec),
            QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
        deadline = time.monotonic() + timeout
        try:
            self._spin_until(lambda: (len(values) == 2 and values[0] == values[1]) or
                             time.monotonic() > deadline)
        finally:
            self.node.destroy_subscription(subscription)
        if len(values) == 2 and values[0] == values[1]:
            return values[1] * 1e-9
        raise RuntimeError(f'/clock did not hold still within {timeout:g} s of pausing '
                           f'{self.sim_node}')

    def current_world(self, timeout=30.0):
        """
        Return the name of the world the simulator runs (``~/get_current_world``).

        :raises RuntimeError: one line when the service does not answer or refuses.
        """
        kind = self._srv.GetCurrentWorld
        name = f'{self.sim_node}/get_current_world'
        answer = self.call(self._client(kind, name), kind.Request(), timeout)
        if answer is None:
            raise RuntimeError(f'{name} did not answer within {timeout:g} s')
        if answer.result.result != self._msg.Result.RESULT_OK:
            raise RuntimeError(f'{name}: {answer.result.error_message}')
        return answer.world.name

    # ------------------------------------------------------------------ spawn
    def wait_for_spawn_service(self, timeout):
        """Return True once the SpawnEntity service exists (``timeout`` s; None: forever)."""
        client = self._client(self._srv.SpawnEntity, self.spawn_service)
        deadline = math.inf if timeout is None else time.monotonic() + timeout
        self._spin_until(lambda: client.service_is_ready() or time.monotonic() > deadline)
        return client.service_is_ready()

    def spawn(self, request, timeout=None, repeat=True, on_retry=None):
        """
        Send a SpawnEntity ``request``; send it again, from a new client, when unanswered.

        A request can be lost when the server has not matched this client's request writer
        (DDS discovery is not symmetric: the client may see the service first). Seen with
        fleets of 16-32 robots starting at once: the simulator never received one robot's
        request, repeated three times from the same client, while new clients were answered.
        So every :data:`RETRY_PERIOD` s without an answer the client is replaced (new DDS
        endpoints, discovered afresh) and the request sent again, until an answer or
        ``timeout``. Upstream's spawner repeats its calls for the same reason. With ``repeat``
        False (``-allow_renaming``: a lost answer would create a second robot) it is sent once.
        When a repeated request is refused because the name exists while an earlier one is
        unanswered, the earlier one created it and its answer was lost.

        :param request: ``SpawnEntity.Request``.
        :param timeout: wall seconds in all (None: no limit).
        :param repeat: send the request again when unanswered.
        :param on_retry: ``(attempt) -> None`` called before each repeated request.
        :returns: ``(response or None, lost_answer)``; ``lost_answer`` True when the entity
            was created by an earlier request whose answer was lost (``response`` is then the
            refusal of the repeated request).
        """
        kind = self._srv.SpawnEntity
        overall = math.inf if timeout is None else time.monotonic() + timeout
        futures = []
        attempt = 0
        while True:
            attempt += 1
            client = self._client(kind, self.spawn_service)
            futures.append(client.call_async(request))
            deadline = min(overall, time.monotonic() + RETRY_PERIOD) if repeat else overall
            self._spin_until(lambda: any(f.done() for f in futures) or
                             time.monotonic() > deadline)
            answered = [f for f in futures if f.done() and f.result() is not None]
            if answered:
                response = answered[0].result()
                duplicate = response.result.result == kind.Response.NAME_NOT_UNIQUE
                if duplicate and answered[0] is not futures[0]:
                    return self._first_answer(futures[0], response)
                return response, False
            if time.monotonic() > overall:
                return None, False
            if on_retry is not None:
                on_retry(attempt)
            self._clients.pop(self.spawn_service)  # a new client: new DDS endpoints
            fresh = self._client(kind, self.spawn_service)
            self._spin_until(lambda: fresh.service_is_ready() or time.monotonic() > overall)

    def _first_answer(self, first, refusal):
        """
        Wait a little for the first request's answer after a repeated one found the name taken.

        :returns: ``(first answer, False)``, or ``(refusal, True)`` when none came: the first
            request created the entity and its answer was lost.
        """
        deadline = time.monotonic() + RETRY_PERIOD
        self._spin_until(lambda: first.done() or time.monotonic() > deadline)
        if first.done() and first.result() is not None:
            return first.result(), False
        return refusal, True
