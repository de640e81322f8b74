# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The simulation engine without rclpy: one MuJoCo world, its robots, their controller managers.

:class:`Simulation` owns a :class:`~amr_description.sim.world.World`, the spawned entities and
one controller manager per entity whose URDF has ``<ros2_control>`` (as gz_ros2_control creates
one per model). Its cycle, run by one simulation thread (:meth:`Simulation.start`) or by the
caller (:meth:`Simulation.run_cycle`, for tests and benchmarks)::

    step physics (mj_step batch) to the next control instant
    for every controller manager due at that instant: read(t, period)
    for every controller manager due:                 update(t, period)
    for every controller manager due:                 write(t, period)
    after_cycle(t) hook (the ROS plumbing publishes /clock and ground truth here)
    pace to the real-time factor (or to an external clock)

``read``/``update``/``write`` are the phases of ros2_control's ``controller_manager`` (its
``ros2_control_node`` loop calls them in this order); a controller manager that only has
``update`` (all three phases in one call) is called once per instant instead.

Threads: everything that changes the world (spawn, reset, step while paused, pause/play) is
a request run by the simulation thread between two cycles (:meth:`Simulation.call`). The
controller-manager factory and the entity ``setup``/``release`` callbacks run on the thread
that calls :meth:`Simulation.spawn` (the ROS node's executor thread), so that a user of rclpy
creates and destroys its entities on one thread and the simulation thread never does.

A robot's gz-sim systems (:class:`~amr_description.sim.systems.SystemGroup`: DiffDrive and
the like) are stepped as a controller manager with ``update`` only, at their own rate.

Time: sim time ``t = step_count * physics_step`` (s), exact multiples of the physics step;
MuJoCo's ``data.time`` is not used for it. Control instants are the multiples of each
controller manager's ``1 / update_rate`` (rounded to physics steps); with no controller
manager the cycle is :data:`IDLE_RATE` Hz of sim time. A cycle also ends at every multiple
of a sensor's period, so that each sensor is measured at its own rate.
"""

import logging
import math
import threading
import time

from amr_description.sim.entity import place_entity
from amr_description.sim.entity import spawn_stages
from amr_description.sim.non_finite import BAD_STATE_WARNINGS
from amr_description.sim.non_finite import first_bad_body
from amr_description.sim.pacing import Pacer
from amr_description.sim.requests import Request
from amr_description.sim.requests import RequestQueue
from amr_description.sim.world import World

IDLE_RATE = 100.0
"""Hz of sim time of the cycle (and of the ``after_cycle`` hook) while no controller runs."""

REQUEST_TIMEOUT = 30.0
"""Seconds :meth:`Simulation.call` waits for the simulation thread."""

PAUSED_TICK = 0.1
"""Seconds (wall) between ``paused_tick`` hook calls while paused."""


class Simulation:
    """
    A MuJoCo world with robots and their controller managers, stepped by one thread.

    :param physics_step: physics step in s (> 0).
    :param real_time_factor: target sim-time/wall-time ratio; 0 = as fast as possible (an
        empty world runs in real time even then: fast-forward starts with the first entity).
    :param paused: start paused.
    :param controller_manager_factory: ``(entity, hardware_factory, parameters_file) ->
        controller manager`` called on the spawning thread for an entity with
        ``<ros2_control>``; ``hardware_factory(info)`` builds the ``MujocoSystem`` of the
        entity. None: entities get no controller manager.
    :param controller_manager_release: ``(controller manager) -> None`` destroying one (on a
        failed spawn and in :meth:`close`), or None.
    :param parameters_file: controllers YAML for every entity (``''``: each URDF's
        ``<mujoco><ros2_control parameters=...>``).
    :param logger: a ``logging.Logger``-like object (``info``, ``warning``, ``error``).
    :param sensor_settings: dict of simulator-wide sensor settings handed to the sensor
        factories (:func:`~amr_description.sim.sensors.registry.make_sensors`); the
        cameras' shared render thread is kept there as ``camera_renderer`` (a
        :class:`~amr_description.sim.sensors.camera_renderer.CameraRenderer`, made when missing and
        closed by :meth:`close`).
    :param world: an SDF world (:class:`~amr_description.core.gazebo.sdf_elements.World`) or None
        (the empty world); its physics step is ``physics_step``, not its own (the caller chooses).
    :raises ValueError: one line on a bad ``real_time_factor`` or a world MuJoCo cannot build.

    Hooks (lists of listeners, called in order on the simulation thread; append to them):
    ``before_update(t)`` before the controller managers' ``read`` at an instant where any is
    due; ``after_cycle(t)`` after every cycle; ``paused_tick(t)`` every :data:`PAUSED_TICK`
    s of wall time while paused; ``on_reset()`` after :meth:`reset`.
    """

    def __init__(self, physics_step=0.001, real_time_factor=1.0, paused=False,
                 controller_manager_factory=None, controller_manager_release=None,
                 parameters_file='', logger=None, sensor_settings=None, world=None):
        """Build the world (see the class docstring)."""
        if not real_time_factor >= 0:
            raise ValueError(f'real_time_factor must be >= 0, found {real_time_factor!r}')
        self.world = World(physics_step, world)
        self.physics_step = self.world.physics_step
        self.real_time_factor = float(real_time_factor)
        self.paused = bool(paused)
        self.parameters_file = parameters_file
        self.logger = logger or logging.getLogger('simulation')
        self.sensor_settings = dict(sensor_settings or {})
        if 'camera_renderer' not in self.sensor_settings:  # no thread, no GL until a camera
            from amr_description.sim.sensors.camera_renderer import CameraRenderer
            self.sensor_settings['camera_renderer'] = CameraRenderer()
        self.controller_manager_factory = controller_manager_factory
        self.controller_manager_release = controller_manager_release
        self.entities = {}          # name -> Entity (spawned; possibly still being set up)
        self.active = ()            # Entities set up and stepped with their controllers
        self._managers = ()         # (cm, steps_per_update, read, update, write)
        self._periods = (self._steps(IDLE_RATE),)  # steps between the cycle's instants
        self.step_count = 0
        self.before_update = []
        self.after_cycle = []
        self.paused_tick = []
        self.on_reset = []
        self._wake = threading.Event()
        self._requests = RequestQueue(self._wake)
        self._running = False
        self._thread = None
        self._pending_steps = 0
        self._step_waiters = []
        self._pacer = Pacer(self.logger)
        self._external_time = None   # s, the clock we must not run ahead of (None: own clock)
        self._external = False
        self._halted = None          # message of the non-finite state that paused us
        self._warnings_seen = 0
        self._rebind()
        self.update_errors = 0
        self.thread_error = None

    # ------------------------------------------------------------------ properties
    @property
    def time(self):
        """Return the sim time in s (``step_count * physics_step``)."""
        return self.step_count * self.physics_step

    @property
    def halted(self):
        """Return the one-line report of a non-finite state that paused the world, or None."""
        return self._halted

    # ------------------------------------------------------------------ thread
    def start(self, name='simulation'):
        """Start the simulation thread (daemon) running :meth:`run`."""
        self._running = True
        self._thread = threading.Thread(target=self.run, name=name, daemon=True)
        self._thread.start()

    def stop(self, timeout=5.0):
        """Stop and join the simulation thread (no-op when not started)."""
        self._running = False
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout)
            self._thread = None

    def close(self):
        """Stop the thread and the camera render thread, then release every controller manager."""
        self.stop()
        renderer = self.sensor_settings.get('camera_renderer')
        if renderer is not None:
            renderer.close()
        self.active = ()
        self._managers = ()
        for entity in list(self.entities.values()):
            cm, entity.controller_manager = entity.controller_manager, None
            if cm is not None and self.controller_manager_release is not None:
                try:
                    self.controller_manager_release(cm)
                except Exception as exc:  # noqa: B902 - best effort at exit
                    self.logger.warning(f'controller manager of {entity.name!r}: {exc!r}')

    def call(self, function, timeout=REQUEST_TIMEOUT):
        """
        Run ``function()`` on the simulation thread between two cycles; return its result.

        Runs it directly when no simulation thread is running (tests, before :meth:`start`)
        or when called from the simulation thread itself.

        :raises TimeoutError: when the simulation thread does not answer in ``timeout`` s.
        :raises Exception: whatever ``function`` raised.
        """
        if self._thread is None or threading.current_thread() is self._thread:
            return function()
        request = Request(function)
        self._requests.put(request)
        if not request.done.wait(timeout):
            raise TimeoutError('the simulation thread did not answer')
        if request.error is not None:
            raise request.error
        return request.result

    def submit(self, function, callback):
        """
        Queue ``function()`` for the simulation thread without waiting for it.

        ``callback(result, error)`` is called on the simulation thread once it ran (``error``
        the exception it raised, or None), or with a ``RuntimeError`` when the thread stops
        first. Both run directly on the caller's thread when no simulation thread is running.
        An event-driven caller (an rclpy coroutine) can go on serving other requests meanwhile.
        """
        request = Request(function, callback)
        if self._thread is None or threading.current_thread() is self._thread:
            request.run()
            return
        self._requests.put(request)
        if self._thread is None:  # stopped meanwhile: nobody else will answer it
            self._requests.fail_all()

    # ------------------------------------------------------------------ spawn
    def spawn(self, urdf, name='', pose=None, namespace='', allow_renaming=False, setup=None):
        """
        Add a robot to the world with its controller manager (call from one thread at a time).

        :param urdf: URDF text (str).
        :param name: entity name; ``''`` takes the URDF's ``<robot name>``.
        :param pose: ``[x, y, z, qx, qy, qz, qw]`` in the world frame (m), or None.
        :param namespace: ROS namespace of its controller manager and topics (``''``: root).
        :param allow_renaming: add ``_1``, ``_2``... to a taken name instead of failing.
        :param setup: optional ``(entity) -> None`` run on this thread once the controller
            manager exists, before the entity is stepped with its controllers (the owner
            creates its publishers here); an exception undoes the spawn.
        :returns: the :class:`Entity`.
        :raises ValueError: one line: malformed URDF, taken name or namespace, invalid
            namespace, a robot MuJoCo cannot compile, a controller manager that fails. The
            world and every other robot are left as they were.
        """
        stages = self.spawn_stages(urdf, name, pose, namespace, allow_renaming, setup)
        result, error = None, None
        while True:
            try:
                function = stages.send(result) if error is None else stages.throw(error)
            except StopIteration as stop:
                return stop.value
            try:
                result, error = self.call(function), None
            except Exception as exc:  # noqa: B902 - thrown into the stages, as spawn_stages says
                result, error = None, exc

    def spawn_stages(self, urdf, name='', pose=None, namespace='', allow_renaming=False,
                     setup=None):
        """
        Return :meth:`spawn` as a generator, for a caller that must not block while it runs.

        See :func:`amr_description.sim.entity.spawn_stages` (same arguments and errors as
        :meth:`spawn`).
        """
        return spawn_stages(self, urdf, name, pose, namespace, allow_renaming, setup)

    def add_entity(self, description, name, pose, namespace, allow_renaming):
        """
        Add a robot's bodies to the world; return its :class:`Entity` (simulation thread).

        :raises SpawnError: a taken name or namespace, a description MuJoCo cannot build.
        """
        entity = place_entity(self.world, self.entities, description, name, pose, namespace,
                              allow_renaming, self.logger)
        self.entities[entity.name] = entity
        self._rebind()
        return entity

    def remove_entity(self, entity):
        """Take a (not yet active) entity out of the world (simulation thread)."""
        self.entities.pop(entity.name, None)
        if entity.name in self.world.robots:
            self.world.remove(entity.name)
        self._rebind()

    def activate_entity(self, entity):
        """Start stepping the entity's controller manager (simulation thread)."""
        cm = entity.controller_manager
        if cm is not None:
            rate = float(getattr(cm, 'update_rate', IDLE_RATE) or IDLE_RATE)
            entity.steps_per_update = max(1, int(round(1.0 / (rate * self.physics_step))))
        self.active = self.active + (entity,)
        managers = []
        for e in self.active:
            if e.controller_manager is not None:
                managers.append((e.controller_manager, e.steps_per_update)
                                + _phases(e.controller_manager))
            if e.gz_systems is not None:
                managers.append((e.gz_systems, self._steps(e.gz_systems.update_rate), None,
                                 e.gz_systems.update, None))
        self._managers = tuple(managers)
        self._periods = tuple(sorted(
            {m[1] for m in managers} | {s.period_steps(self.physics_step)
                                        for e in self.active for s in e.sensors}
            | (set() if managers else {self._steps(IDLE_RATE)})))

    def _steps(self, rate):
        """Return the physics steps of one period at ``rate`` Hz of sim time (>= 1)."""
        return max(1, int(round(1.0 / (rate * self.physics_step))))

    def _rebind(self):
        model, data = self.world.model, self.world.data
        self._warning_stats = tuple(data.warning[i] for i in BAD_STATE_WARNINGS)
        for entity in self.entities.values():
            for system in entity.systems:
                system.rebind(model, data)

    # ------------------------------------------------------------------ state changes
    def reset(self):
        """Reset every robot to its spawn pose at rest and the time to 0 s (thread-safe)."""
        def apply():
            self.world.reset()
            self.step_count = 0
            self._pacer.reset()
            self._halted = None
            self._warnings_seen = 0
            for entity in self.entities.values():
                if entity.gz_systems is not None:
                    entity.gz_systems.reset()
            for listener in self.on_reset:
                listener()
        self.call(apply)

    def set_paused(self, paused):
        """Pause or play (thread-safe). Playing after a non-finite halt needs a reset first."""
        def apply():
            self.paused = bool(paused)
            self._pacer.reset()
        self.call(apply)

    def request_steps(self, steps):
        """
        Queue ``steps`` physics steps while paused (thread-safe).

        :returns: a ``threading.Event`` set when they are done (or the world halted).
        """
        done = threading.Event()

        def apply():
            self._pending_steps += int(steps)
            self._step_waiters.append((self.step_count + int(steps), done))
        self.call(apply)
        return done

    def follow_external_clock(self):
        """Never run ahead of the time given to :meth:`set_external_time` (lock-step)."""
        self._external = True

    def set_external_time(self, t):
        """
        Let the simulation advance up to ``t`` s (from another simulator's /clock).

        Before the first entity is spawned, the simulation jumps to ``t`` (it joins the
        running time of the other simulator). Thread-safe; wakes the simulation thread.
        """
        self._external_time = t
        self._wake.set()

    # ------------------------------------------------------------------ the cycle
    def _due_steps(self):
        """Return physics steps to the next instant a manager or a sensor is due (>= 1)."""
        count = self.step_count
        return min(per - count % per for per in self._periods)

    def run_cycle(self):
        """
        Step to the next control instant and run the controller managers due there.

        Honours pause (only queued steps), the external clock and a halted world; does not
        pace. Called by :meth:`run`, or directly when no simulation thread runs.

        :returns: the number of physics steps taken (0 when nothing could be stepped).
        """
        count = self._due_steps()
        if self.paused:
            count = min(count, self._pending_steps)
            self._pending_steps -= count
        if self._external:
            limit = self._external_time
            if limit is None:
                return 0
            if not self.active and self.step_count * self.physics_step < limit:
                self.step_count = int(round(limit / self.physics_step))
                return 0
            count = min(count, int(math.floor(limit / self.physics_step + 1e-6))
                        - self.step_count)
        if count <= 0:
            return 0
        self.world.step(count)
        self.step_count += count
        self._check_finite()
        step_count = self.step_count
        t = step_count * self.physics_step
        due = [m for m in self._managers if step_count % m[1] == 0]
        if due and self._halted is None:
            for listener in self.before_update:
                listener(t)
            dt = self.physics_step
            try:
                for cm, per, read, update, write in due:
                    if read is not None:
                        read(t, per * dt)
                for cm, per, read, update, write in due:
                    update(t, per * dt)
                for cm, per, read, update, write in due:
                    if write is not None:
                        write(t, per * dt)
            except Exception as exc:  # noqa: B902 - a controller bug must not stop physics
                self.update_errors += 1
                n = self.update_errors
                if n in (1, 10, 100) or n % 1000 == 0:
                    self.logger.error(f'controller manager update failed ({n}x): {exc!r}')
        for listener in self.after_cycle:
            listener(t)
        if self._step_waiters:
            self._release_step_waiters()
        return count

    def _check_finite(self):
        """
        Pause once the state is not finite, naming the first non-finite body.

        ``mj_step`` checks qpos, qvel and qacc; on a non-finite (or huge) value it counts a
        warning (``mjWARN_BADQPOS/BADQVEL/BADQACC``) and resets the data; a non-finite model
        (e.g. a NaN in the robot's description) produces one at every step. A new warning
        halts the world. Reading the three counters costs far less than scanning the state.
        """
        qpos, qvel, qacc = self._warning_stats  # live views into data.warning
        seen = qpos.number + qvel.number + qacc.number
        if seen == self._warnings_seen:
            return
        self._warnings_seen = seen
        if self._halted is not None:
            return
        self._halted = (f'non-finite state at t = {self.time:.3f} s in body '
                        f'{first_bad_body(self.world.model, self.world.data)!r}: the '
                        'simulation is paused (reset it to go on)')
        self.paused = True
        self._pending_steps = 0
        self.logger.error(self._halted)

    def _release_step_waiters(self):
        waiting = []
        for target, event in self._step_waiters:
            if self.step_count >= target or self._pending_steps == 0:
                event.set()
            else:
                waiting.append((target, event))
        self._step_waiters = waiting

    def run(self):
        """Run cycles until :meth:`stop`: requests, step, controllers, hooks, pacing."""
        requests = self._requests
        last_tick = 0.0
        try:
            while self._running:
                if requests:
                    requests.run_all()
                if self.paused and self._pending_steps == 0:
                    if self._step_waiters:
                        self._release_step_waiters()
                    now = time.monotonic()
                    if now - last_tick > PAUSED_TICK:
                        last_tick = now
                        for listener in self.paused_tick:
                            listener(self.time)
                    self._wake.wait(0.05)
                    self._wake.clear()
                    continue
                if self.run_cycle() == 0:
                    # waiting for the external clock (or a request)
                    self._wake.wait(0.05)
                    self._wake.clear()
                    continue
                if not self.paused and not self._external:
                    if self.real_time_factor > 0:
                        self._pacer.pace(self.time, self.real_time_factor, len(self.active))
                    elif not self.active:
                        self._pacer.pace(self.time, 1.0, 0)  # fast-forward starts with a robot
                    else:
                        self._pacer.reset()
        except Exception as exc:  # noqa: B902 - report instead of a silent thread death
            if self._running:
                self.thread_error = exc
                self.logger.error(f'simulation thread stopped: {exc!r}')
        finally:
            self._requests.fail_all()
            for _, event in self._step_waiters:
                event.set()


def _phases(cm):
    """Return the (read, update, write) bound methods of a controller manager."""
    read = getattr(cm, 'read', None)
    write = getattr(cm, 'write', None)
    if read is None or write is None:
        return None, cm.update, None  # one call does read -> update -> write
    return read, cm.update, write
