# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The simulator's simulation_interfaces services: spawn, state, step and current world.

Callbacks run on the node's executor thread; every change of the world is run by the
simulation thread (:meth:`~amr_description.sim.simulation.Simulation.submit`), and a spawn is
a coroutine awaiting it, so the executor serves other callbacks meanwhile.
"""

import math

from amr_description.core.description.files import read_description
from amr_description.core.ros_names import normalize_namespace
from amr_description.sim.entity import SpawnError
from rclpy.task import Future
from simulation_interfaces import msg
from simulation_interfaces import srv

REQUEST_TIMEOUT = 30.0  # s a step request waits for the simulation thread


def read_resource(resource):
    """
    Return the URDF text of a ``simulation_interfaces/Resource`` (content or URI).

    A URI names a URDF or xacro file (path, ``package://``, ``file://``).

    :raises SpawnError: ``NO_RESOURCE`` when both are empty; ``RESULT_OPERATION_FAILED``
        when the URI cannot be read or expanded (one line naming it).
    """
    if resource.uri:
        try:
            return read_description(resource.uri)  # a URDF, or a xacro expanded
        except ValueError as exc:
            raise SpawnError(str(exc)) from None
    if resource.resource_string.strip():
        return resource.resource_string
    raise SpawnError('entity_resource is empty: give uri or resource_string', 'NO_RESOURCE')


def _result(code, message=''):
    return msg.Result(result=code, error_message=message)


class SimulationServices:
    """
    The simulation_interfaces services of the ``mujoco_sim`` node (package docstring).

    ``~/spawn_entity``, ``~/reset_simulation``, ``~/set_simulation_state`` and
    ``~/step_simulation``.

    :param node: the simulator node (services, logger, ``setup_entity``, ``quit_requested``).
    :param sim: its :class:`~amr_description.sim.simulation.Simulation`.
    :param executor: the executor spinning ``node`` (the spawn's futures).
    :param on_spawned: ``(entity) -> None`` after a successful spawn (executor thread).
    """

    def __init__(self, node, sim, executor, on_spawned):
        """Create the five services on ``node``."""
        self._node = node
        self._sim = sim
        self._executor = executor
        self._on_spawned = on_spawned
        node.create_service(srv.SpawnEntity, '~/spawn_entity', self._on_spawn)
        node.create_service(srv.ResetSimulation, '~/reset_simulation', self._on_reset)
        node.create_service(srv.SetSimulationState, '~/set_simulation_state', self._on_state)
        node.create_service(srv.StepSimulation, '~/step_simulation', self._on_step)
        node.create_service(srv.GetCurrentWorld, '~/get_current_world', self._on_world)

    def _on_world(self, request, response):
        """GetCurrentWorld: the loaded world's name (SDF ``<world name>``) and source."""
        world = self._sim.world
        response.world.name = world.name
        description = world.description
        response.world.uri = description.source if description is not None else ''
        response.result.result = response.result.RESULT_OK
        return response

    # ---------------------------------------------------------------- spawn
    def _in_sim(self, function):
        """Return an rclpy Future of ``function()``, run by the simulation thread (no wait)."""
        future = Future(executor=self._executor)
        future.add_done_callback(lambda _: None)  # its completion then wakes the executor

        def done(result, error):  # simulation thread
            if error is None:
                future.set_result(result)
            else:
                future.set_exception(error)
        self._sim.submit(function, done)
        return future

    async def _spawn(self, *args, **kwargs):
        """
        Run :meth:`Simulation.spawn` in the executor without blocking it.

        While the simulation thread changes the world, the executor serves other callbacks,
        e.g. the controller-manager services of the robots spawned before (with a fleet
        started at once, a spawner otherwise waits behind every later robot's spawn).
        """
        stages = self._sim.spawn_stages(*args, **kwargs)
        result, error = None, None
        while True:
            try:
                function = stages.send(result) if error is None else stages.throw(error)
            except StopIteration as stop:
                return stop.value
            try:
                result, error = await self._in_sim(function), None
            except Exception as exc:  # noqa: B902 - thrown into the stages (spawn_stages)
                result, error = None, exc

    async def _on_spawn(self, request, response):
        try:
            urdf = read_resource(request.entity_resource)
            values = _initial_pose(request.initial_pose)
            normalize_namespace(request.entity_namespace)
        except SpawnError as exc:
            return self._spawn_failed(response, exc.code, str(exc))
        except ValueError as exc:
            return self._spawn_failed(response, 'NAMESPACE_INVALID', str(exc))
        try:
            # this coroutine runs on the executor's thread: the controller manager and the
            # publishers are created here, the world is changed by the simulation thread
            # (awaited: the executor serves other nodes' callbacks meanwhile)
            entity = await self._spawn(urdf, request.name, values, request.entity_namespace,
                                       request.allow_renaming, setup=self._node.setup_entity)
        except SpawnError as exc:
            return self._spawn_failed(response, exc.code, str(exc))
        except (ValueError, TimeoutError, RuntimeError) as exc:
            text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            return self._spawn_failed(response, 'RESULT_OPERATION_FAILED', text)
        world = self._sim.world
        ok = f'spawned {entity.name!r}'
        if entity.namespace:
            ok += f' in namespace {entity.namespace!r}'
        ok += f' ({world.model.nbody - 1} bodies, {world.model.nu} actuators in the world)'
        if entity.controller_manager is not None:
            ok += f'; controller manager {entity.controller_manager.get_fully_qualified_name()}'
        if self._sim.paused:
            ok += '; the simulation is paused: it moves when played or stepped'
        response.result = _result(msg.Result.RESULT_OK, ok)
        response.entity_name = entity.name
        self._node.get_logger().info(ok)
        self._on_spawned(entity)
        return response

    def _spawn_failed(self, response, code, message):
        self._node.get_logger().error(f'spawn_entity: {message}')
        owner = srv.SpawnEntity.Response if hasattr(srv.SpawnEntity.Response, code) \
            else msg.Result
        response.result = _result(getattr(owner, code), message)
        return response

    # ---------------------------------------------------------------- state
    def _on_reset(self, request, response):
        if request.scope != 0 and not request.scope & 0b11:
            response.result = _result(
                msg.Result.RESULT_FEATURE_UNSUPPORTED,
                'removing spawned entities is not supported; scopes TIME and STATE are')
            return response
        self._sim.reset()
        self._node.get_logger().info('simulation reset')
        response.result = _result(msg.Result.RESULT_OK)
        return response

    def _on_state(self, request, response):
        State, Result = msg.SimulationState, msg.Result
        Response = srv.SetSimulationState.Response
        target = request.state.state
        if target == State.STATE_QUITTING:
            self._node.quit_requested.set()
            response.result = _result(Result.RESULT_OK)
            return response
        if target not in (State.STATE_PLAYING, State.STATE_PAUSED, State.STATE_STOPPED):
            response.result = _result(Response.INCORRECT_TRANSITION,
                                      f'cannot go to state {target}')
            return response
        if target == State.STATE_PLAYING and self._sim.halted:
            response.result = _result(Result.RESULT_OPERATION_FAILED, self._sim.halted)
            return response
        want_paused = target != State.STATE_PLAYING
        if target != State.STATE_STOPPED and want_paused == self._sim.paused:
            response.result = _result(
                Response.ALREADY_IN_TARGET_STATE,
                'already ' + ('paused' if self._sim.paused else 'playing'))
            return response
        self._sim.set_paused(want_paused)
        if target == State.STATE_STOPPED:
            self._sim.reset()
        self._node.get_logger().info('simulation ' + {
            State.STATE_PLAYING: 'playing', State.STATE_PAUSED: 'paused',
            State.STATE_STOPPED: 'stopped'}[target])
        response.result = _result(Result.RESULT_OK)
        return response

    def _on_step(self, request, response):
        Result = msg.Result
        if not self._sim.paused:
            response.result = _result(Result.RESULT_OPERATION_FAILED,
                                      'step_simulation needs a paused simulation')
            return response
        if self._sim.halted:
            response.result = _result(Result.RESULT_OPERATION_FAILED, self._sim.halted)
            return response
        if request.steps < 1:
            response.result = _result(Result.RESULT_OK)
            return response
        done = self._sim.request_steps(request.steps)
        if not done.wait(REQUEST_TIMEOUT + request.steps * 1e-3):
            response.result = _result(Result.RESULT_OPERATION_FAILED, 'stepping timed out')
            return response
        response.result = _result(Result.RESULT_OK)
        return response


def _initial_pose(initial_pose):
    """
    Return ``[x, y, z, qx, qy, qz, qw]`` of a SpawnEntity ``initial_pose`` (PoseStamped).

    :raises SpawnError: ``INVALID_POSE`` for a frame other than ``world`` (or empty), a
        non-finite value or a zero quaternion.
    """
    pose, frame = initial_pose.pose, initial_pose.header.frame_id
    if frame not in ('', 'world'):
        raise SpawnError(f'initial_pose frame {frame!r} is not "world"', 'INVALID_POSE')
    values = [pose.position.x, pose.position.y, pose.position.z, pose.orientation.x,
              pose.orientation.y, pose.orientation.z, pose.orientation.w]
    if not all(math.isfinite(v) for v in values) or \
            math.sqrt(sum(v * v for v in values[3:])) < 1e-9:
        raise SpawnError('initial_pose must be finite with a non-zero quaternion',
                         'INVALID_POSE')
    return values
