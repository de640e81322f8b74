# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The ``mujoco_sim`` node: ROS plumbing around the simulation engine (gz sim's role).

The engine (:class:`amr_description.sim.simulation.Simulation`, no rclpy) owns the MuJoCo
world, the robots and one controller manager per robot with ``<ros2_control>``, and runs the
physics / ``read -> update -> write`` cycle in its own thread. This node adds parameters,
services, the /clock and ground-truth publishers (called by the simulation thread through
hooks, nothing else is woken per update) and the in-process sim time of the controller nodes.

Parameters (read at start):
  ``physics_step`` (double, 0.001 s), ``real_time_factor`` (double, 1.0; 0 = as fast as
  possible), ``headless`` (bool, true; false opens the MuJoCo viewer when a display exists),
  ``parameters_file`` (string, '' = the URDF's ``<mujoco><ros2_control parameters=...>``),
  ``paused`` (bool, false), ``publish_ground_truth`` (bool, true), ``ground_truth_rate``
  (double, 50.0 Hz of sim time), ``clock_source`` (string, ``internal``: this node publishes
  /clock and refuses to start, exit code 1, when it finds another node publishing /clock
  in its first 10 s, publishing none of its own in the first 1.5 s; ``external``: follow the
  /clock of another simulator, never running ahead of it, and publish none).

Topics: ``/clock`` (rosgraph_msgs/Clock, reliable, depth 10) after every cycle, at least 100 Hz
of sim time, and at 10 Hz (wall) with an unchanged time while paused (an empty world runs in
real time even with ``real_time_factor`` 0: fast-forward starts with the first spawned
entity); ``<namespace>/ground_truth/odom`` (nav_msgs/Odometry) of every spawned robot: pose of
its root link in frame ``world``, twist in the root link frame (REP 105 / Odometry
convention); child frame ``base_footprint`` (``r1/base_footprint`` in namespace ``/r1``).

Services (simulation_interfaces): ``~/spawn_entity`` (SpawnEntity; ``entity_namespace``
gives the robot's controller manager ``<namespace>/controller_manager``, its controllers
``<namespace>/<controller>``; each robot needs its own name and namespace),
``~/reset_simulation`` (ResetSimulation: resets poses, velocities and time to the spawn
state; removing spawned entities is unsupported), ``~/set_simulation_state``
(SetSimulationState: playing, paused, stopped = paused + reset, quitting),
``~/step_simulation`` (StepSimulation: N physics steps while paused; answers when done).

Threads: the rclpy executor runs in the main thread and is the only thread that creates or
destroys rclpy entities (spawn builds the controller manager in the service callback, a
coroutine that awaits the simulation thread's world change, so that the executor serves the
other robots' controller-manager services meanwhile). The
simulation thread publishes /clock and the ground truth and sets the controller nodes' clocks;
their /clock subscriptions are removed before the executor ever sees them
(:class:`SimTimeExecutor`).
"""

import math
import os
import threading
import time

from amr_description.ros import shutdown
from amr_description.ros.node import Node
from amr_description.ros.sim_time import SimTime
from amr_description.ros.sim_time import SimTimeExecutor
from amr_description.ros.stamps import has_subscribers
from amr_description.sim.simulation import IDLE_RATE
from amr_description.sim.simulation import normalize_namespace
from amr_description.sim.simulation import Simulation
from amr_description.sim.urdf_to_mjcf import resolve_uri
from nav_msgs.msg import Odometry
import rclpy.clock
from rclpy.executors import SingleThreadedExecutor
from rclpy.task import Future
from rclpy.time import Time
from rosgraph_msgs.msg import Clock

NO_ROBOT_CLOCK_RATE = IDLE_RATE  # Hz of sim time while no controller manager runs
REQUEST_TIMEOUT = 30.0  # s a service waits for the simulation thread
CLOCK_CHECK_TIME = 1.5  # s (wall) looking for another /clock publisher before publishing
CLOCK_WATCH_TIME = 10.0  # s (wall) after which a late-found /clock publisher is not checked
CLOCK_CHECK_PERIOD = 0.1  # s (wall) between those looks


def _sim_msgs():
    """Import the simulation_interfaces message and service modules."""
    from simulation_interfaces import msg
    from simulation_interfaces import srv
    return msg, srv


def make_controller_manager(urdf_xml, executor, hardware_factory, parameters_file, namespace):
    """
    Create an in-sim controller manager (``amr_description.control.controller_manager``).

    :returns: the ControllerManager node, added with its controllers to ``executor``.
    :raises ValueError: one line, on bad input (unknown plugin, missing joint, bad YAML).
    """
    from amr_description.control.controller_manager import ControllerManager
    return ControllerManager(urdf_xml, executor, hardware_factory=hardware_factory,
                             parameters_file=parameters_file, namespace=namespace,
                             use_sim_time=True)


def _prewarm_imports():
    """Import the modules used at spawn time (URDF parser, controller manager, controllers)."""
    import importlib
    for module in ('yourdfpy', 'amr_description.control.controller_manager',
                   'amr_description.control.joint_state_broadcaster',
                   'amr_description.control.diff_drive_controller'):
        try:
            importlib.import_module(module)
        except Exception:  # noqa: B902 - only a warm-up; the real import reports errors
            pass


class _Logger:
    """Adapts an rclpy logger to the ``logging`` method names the engine uses."""

    def __init__(self, logger):
        self.info = logger.info
        self.warning = logger.warning
        self.error = logger.error


class MujocoSim(Node):
    """Node ``mujoco_sim``: see the module docstring for parameters, topics and services."""

    def __init__(self, executor):
        """
        Declare parameters, build the engine, create publishers and services.

        :param executor: the :class:`SimTimeExecutor` spinning this node (controller
            manager nodes are added to it).
        """
        super().__init__('mujoco_sim')
        self._executor = executor
        self.physics_step = self.declare_parameter('physics_step', 0.001).value
        self.real_time_factor = self.declare_parameter('real_time_factor', 1.0).value
        self.headless = self.declare_parameter('headless', True).value
        self.parameters_file = self.declare_parameter('parameters_file', '').value
        paused = self.declare_parameter('paused', False).value
        self.publish_ground_truth = self.declare_parameter('publish_ground_truth', True).value
        self.ground_truth_rate = self.declare_parameter('ground_truth_rate', 50.0).value
        self.clock_source = self.declare_parameter('clock_source', 'internal').value
        log = self.get_logger()
        if not self.physics_step > 0:
            log.error(
                f'parameter physics_step must be > 0 s, found {self.physics_step}; using 0.001')
            self.physics_step = 0.001
        if not self.real_time_factor >= 0:
            log.error(f'parameter real_time_factor must be >= 0, found '
                      f'{self.real_time_factor}; using 1.0')
            self.real_time_factor = 1.0
        if self.clock_source not in ('internal', 'external'):
            log.error(f"parameter clock_source must be 'internal' or 'external', found "
                      f"{self.clock_source!r}; using 'internal'")
            self.clock_source = 'internal'
        self.external_clock = self.clock_source == 'external'
        self.refused = None  # one-line reason to exit 1
        self.quit_requested = threading.Event()
        self._viewer = None
        self._viewer_stale = False
        self._last_viewer_sync = 0.0

        # the node's own clock follows the simulation (its sim time), without subscribing to
        # the /clock it publishes itself
        self.get_clock()._set_ros_time_is_active(True)
        self.get_clock().set_ros_time_override(Time(nanoseconds=0))

        self.sim = Simulation(
            self.physics_step, self.real_time_factor, paused,
            controller_manager_factory=self._make_cm,
            controller_manager_release=lambda cm: cm.destroy(),
            parameters_file=self.parameters_file, logger=_Logger(log))
        self.sim.before_update.append(executor.sim_time.set_time)
        self.sim.after_cycle.append(self._after_cycle)
        self.sim.paused_tick.append(self._publish_clock)
        self.sim.on_reset.append(self._on_sim_reset)
        self._gt_steps = max(1, int(round(1.0 / (self.ground_truth_rate * self.physics_step)))) \
            if self.ground_truth_rate > 0 and self.publish_ground_truth else 0
        self._clock_msg = Clock()
        self._clock_pub = None
        self._clock_check = None
        self._follower = None
        if self.external_clock:
            self.sim.follow_external_clock()
            self._start_clock_follower()
        else:
            self._clock_check_start = None
            # a wall-clock timer: this node's own clock is the (maybe paused) sim time
            self._clock_check = self.create_timer(
                CLOCK_CHECK_PERIOD, self._check_clock,
                clock=rclpy.clock.Clock(clock_type=rclpy.clock.ClockType.STEADY_TIME))
        msg, srv = _sim_msgs()
        self._result_type = msg.Result
        self._state_type = msg.SimulationState
        self.create_service(srv.SpawnEntity, '~/spawn_entity', self._on_spawn)
        self.create_service(srv.ResetSimulation, '~/reset_simulation', self._on_reset)
        self.create_service(srv.SetSimulationState, '~/set_simulation_state', self._on_state)
        self.create_service(srv.StepSimulation, '~/step_simulation', self._on_step)
        if not self.headless:
            self._open_viewer()
        # import the heavy modules a spawn needs (yourdfpy pulls trimesh) while waiting for it
        threading.Thread(target=_prewarm_imports, name='prewarm', daemon=True).start()
        self.sim.start('mujoco_sim')
        log.info(
            f'MuJoCo {self.physics_step * 1000:g} ms physics, real_time_factor '
            f'{self.real_time_factor:g}{" (paused)" if paused else ""}'
            f'{", following the external /clock" if self.external_clock else ""}; '
            f'spawn with {self.get_fully_qualified_name()}/spawn_entity')

    @property
    def paused(self):
        """Return True while the simulation is paused."""
        return self.sim.paused

    # ---------------------------------------------------------------- one clock
    def _check_clock(self):
        """
        Look for another /clock publisher in the domain; refuse to run next to one.

        Runs every CLOCK_CHECK_PERIOD s of wall time from the first spin: for CLOCK_CHECK_TIME s
        this node publishes no /clock (the usual discovery time), then it publishes and keeps
        looking until CLOCK_WATCH_TIME s (discovery on a loaded machine can take seconds).
        """
        now = time.monotonic()
        if self._clock_check_start is None:
            self._clock_check_start = now
        others = self.count_publishers('/clock') - (1 if self._clock_pub is not None else 0)
        if others > 0:
            self._clock_check.cancel()
            self.refused = (
                'another node already publishes /clock in this ROS domain: run one simulator '
                'per domain, or start this one with clock_source:=external to follow it')
            self.get_logger().error(self.refused)
            self.quit_requested.set()
            return
        elapsed = now - self._clock_check_start
        if self._clock_pub is None and elapsed >= CLOCK_CHECK_TIME:
            self._clock_pub = self.create_publisher(Clock, '/clock', 10)
        if elapsed >= CLOCK_WATCH_TIME:
            self._clock_check.cancel()

    def _start_clock_follower(self):
        """
        Receive the external /clock in a hidden node spun by its own thread.

        Not on this node's executor: that one blocks in service callbacks that wait for the
        simulation (a controller switch waits for the next update), and the simulation waits
        for the external time, so one thread for both would stall until the service times out.
        """
        node = rclpy.create_node(f'_{self.get_name()}_clock_follower', context=self.context,
                                 namespace=self.get_namespace())
        node.create_subscription(Clock, '/clock', self._on_external_clock, 10)
        executor = SingleThreadedExecutor(context=self.context)
        executor.add_node(node)
        running = threading.Event()
        running.set()

        def spin():
            try:
                while running.is_set() and self.context.ok():
                    executor.spin_once(timeout_sec=0.1)
            except Exception as exc:  # noqa: B902 - e.g. the context shut down meanwhile
                if running.is_set():
                    self.get_logger().error(f'external /clock follower stopped: {exc!r}')
        thread = threading.Thread(target=spin, name='clock_follower', daemon=True)
        self._follower = (node, executor, running, thread)
        thread.start()

    def _stop_clock_follower(self):
        if self._follower is None:
            return
        node, executor, running, thread = self._follower
        self._follower = None
        running.clear()
        thread.join(timeout=5.0)
        executor.shutdown(timeout_sec=0)
        node.destroy_node()

    def _on_external_clock(self, msg):
        self.sim.set_external_time(msg.clock.sec + msg.clock.nanosec * 1e-9)

    # ---------------------------------------------------------------- hooks (sim thread)
    def _publish_clock(self, t):
        """Publish /clock at sim time ``t`` (s) and set this node's clock to it."""
        nanoseconds = int(round(t * 1e9))
        stamp = self._clock_msg.clock
        stamp.sec, stamp.nanosec = divmod(nanoseconds, 1_000_000_000)
        publisher = self._clock_pub
        if publisher is not None:
            publisher.publish(self._clock_msg)
        self.get_clock().set_ros_time_override(Time(nanoseconds=nanoseconds))
        return stamp

    def _after_cycle(self, t):
        """Publish /clock, then the ground truth when due (simulation thread)."""
        stamp = self._publish_clock(t)
        if self._gt_steps and self.sim.step_count % self._gt_steps == 0 and \
                self.sim.halted is None:  # never a non-finite ground truth
            self._publish_ground_truths(stamp)
        if self._viewer is not None:
            self._sync_viewer()

    def _publish_ground_truths(self, stamp):
        world = self.sim.world
        for entity in self.sim.active:
            publisher = entity.user.get('ground_truth')
            if publisher is None or not has_subscribers(publisher):
                continue  # volatile: unheard messages reach nobody
            position, quat, linear, angular = world.ground_truth(entity.name)
            msg = entity.user['ground_truth_msg']
            msg.header.stamp = stamp
            p, q = msg.pose.pose.position, msg.pose.pose.orientation
            p.x, p.y, p.z = (float(v) for v in position)
            q.x, q.y, q.z, q.w = (float(v) for v in quat)
            lin, ang = msg.twist.twist.linear, msg.twist.twist.angular
            lin.x, lin.y, lin.z = (float(v) for v in linear)
            ang.x, ang.y, ang.z = (float(v) for v in angular)
            publisher.publish(msg)

    def _on_sim_reset(self):
        stamp = self._publish_clock(0.0)
        if self._gt_steps:
            self._publish_ground_truths(stamp)

    # ---------------------------------------------------------------- services
    def _result(self, code, message=''):
        result = self._result_type()
        result.result = code
        result.error_message = message
        return result

    def _in_sim(self, function):
        """Return an rclpy Future of ``function()``, run by the simulation thread (no wait)."""
        future = Future(executor=self._executor)
        future.add_done_callback(lambda _: None)  # its completion then wakes the executor

        def done(result, error):  # simulation thread
            if error is None:
                future.set_result(result)
            else:
                future.set_exception(error)
        self.sim.submit(function, done)
        return future

    async def _spawn(self, *args, **kwargs):
        """
        Run :meth:`Simulation.spawn` in the executor without blocking it.

        While the simulation thread changes the world, the executor serves other callbacks,
        e.g. the controller-manager services of the robots spawned before (with a fleet
        started at once, a spawner otherwise waits behind every later robot's spawn).
        """
        stages = self.sim.spawn_stages(*args, **kwargs)
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
        R = self._result_type
        _, srv = _sim_msgs()
        Response = srv.SpawnEntity.Response
        try:
            urdf = self._resource(request.entity_resource)
        except ValueError as exc:
            code = Response.NO_RESOURCE if 'empty' in str(exc) else R.RESULT_OPERATION_FAILED
            return self._spawn_failed(response, code, str(exc))
        pose = request.initial_pose.pose
        frame = request.initial_pose.header.frame_id
        if frame not in ('', 'world'):
            return self._spawn_failed(response, Response.INVALID_POSE,
                                      f'initial_pose frame {frame!r} is not "world"')
        values = [pose.position.x, pose.position.y, pose.position.z, pose.orientation.x,
                  pose.orientation.y, pose.orientation.z, pose.orientation.w]
        if not all(math.isfinite(v) for v in values) or \
                math.sqrt(sum(v * v for v in values[3:])) < 1e-9:
            return self._spawn_failed(response, Response.INVALID_POSE,
                                      'initial_pose must be finite with a non-zero quaternion')
        try:
            normalize_namespace(request.entity_namespace)
        except ValueError as exc:
            return self._spawn_failed(response, Response.NAMESPACE_INVALID, str(exc))
        try:
            # this coroutine runs on the executor's thread: the controller manager and the
            # publishers are created here, the world is changed by the simulation thread
            # (awaited: the executor serves other nodes' callbacks meanwhile)
            entity = await self._spawn(urdf, request.name, values, request.entity_namespace,
                                       request.allow_renaming, setup=self._setup_entity)
        except (ValueError, TimeoutError, RuntimeError) as exc:
            text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            code = R.RESULT_OPERATION_FAILED
            if 'already exists' in text or 'already used' in text:
                code = Response.NAME_NOT_UNIQUE
            elif text.startswith(('URDF', 'robot description')):
                code = Response.RESOURCE_PARSE_ERROR
            return self._spawn_failed(response, code, text)
        world = self.sim.world
        ok = f'spawned {entity.name!r}'
        if entity.namespace:
            ok += f' in namespace {entity.namespace!r}'
        ok += f' ({world.model.nbody - 1} bodies, {world.model.nu} actuators in the world)'
        if entity.controller_manager is not None:
            ok += f'; controller manager {entity.controller_manager.get_fully_qualified_name()}'
        if self.sim.paused:
            ok += '; the simulation is paused: it moves when played or stepped'
        response.result = self._result(R.RESULT_OK, ok)
        response.entity_name = entity.name
        self.get_logger().info(ok)
        self._viewer_stale = self._viewer is not None
        return response

    def _make_cm(self, entity, hardware_factory, parameters_file):
        """Create the controller manager of ``entity`` in its namespace (executor thread)."""
        try:
            return make_controller_manager(entity.urdf, self._executor, hardware_factory,
                                           parameters_file, entity.namespace)
        except ImportError as exc:
            raise ValueError(f'controller manager not available: {exc}') from None

    def _setup_entity(self, entity):
        """Create the entity's ground-truth publisher (executor thread)."""
        if not self.publish_ground_truth:
            return
        topic = f'{entity.namespace}/ground_truth/odom'
        msg = Odometry()
        msg.header.frame_id = 'world'
        msg.child_frame_id = entity.frame_prefix + entity.robot.root
        entity.user['ground_truth_msg'] = msg
        entity.user['ground_truth'] = self.create_publisher(Odometry, topic, 10)

    def _spawn_failed(self, response, code, message):
        self.get_logger().error(f'spawn_entity: {message}')
        response.result = self._result(code, message)
        return response

    @staticmethod
    def _resource(resource):
        """Return the URDF text of a simulation_interfaces/Resource (content or URI)."""
        if resource.uri:
            path = resolve_uri(resource.uri)
            try:
                with open(path, 'r') as f:
                    return f.read()
            except OSError as exc:
                raise ValueError(f'cannot read {resource.uri!r}: {exc.strerror}') from None
        if resource.resource_string.strip():
            return resource.resource_string
        raise ValueError('entity_resource is empty: give uri or resource_string')

    def _on_reset(self, request, response):
        R = self._result_type
        if request.scope != 0 and not request.scope & 0b11:
            response.result = self._result(
                R.RESULT_FEATURE_UNSUPPORTED,
                'removing spawned entities is not supported; scopes TIME and STATE are')
            return response
        self.sim.reset()
        self.get_logger().info('simulation reset')
        response.result = self._result(R.RESULT_OK)
        return response

    def _on_state(self, request, response):
        S = self._state_type
        _, srv = _sim_msgs()
        R = self._result_type
        target = request.state.state
        if target == S.STATE_QUITTING:
            self.quit_requested.set()
            response.result = self._result(R.RESULT_OK)
            return response
        if target not in (S.STATE_PLAYING, S.STATE_PAUSED, S.STATE_STOPPED):
            response.result = self._result(
                srv.SetSimulationState.Response.INCORRECT_TRANSITION,
                f'cannot go to state {target}')
            return response
        if target == S.STATE_PLAYING and self.sim.halted:
            response.result = self._result(R.RESULT_OPERATION_FAILED, self.sim.halted)
            return response
        want_paused = target != S.STATE_PLAYING
        if target != S.STATE_STOPPED and want_paused == self.sim.paused:
            response.result = self._result(
                srv.SetSimulationState.Response.ALREADY_IN_TARGET_STATE,
                'already ' + ('paused' if self.sim.paused else 'playing'))
            return response
        self.sim.set_paused(want_paused)
        if target == S.STATE_STOPPED:
            self.sim.reset()
        self.get_logger().info('simulation ' + {S.STATE_PLAYING: 'playing', S.STATE_PAUSED:
                                                'paused', S.STATE_STOPPED: 'stopped'}[target])
        response.result = self._result(R.RESULT_OK)
        return response

    def _on_step(self, request, response):
        R = self._result_type
        if not self.sim.paused:
            response.result = self._result(R.RESULT_OPERATION_FAILED,
                                           'step_simulation needs a paused simulation')
            return response
        if self.sim.halted:
            response.result = self._result(R.RESULT_OPERATION_FAILED, self.sim.halted)
            return response
        if request.steps < 1:
            response.result = self._result(R.RESULT_OK)
            return response
        done = self.sim.request_steps(request.steps)
        timeout = REQUEST_TIMEOUT + request.steps * 1e-3
        if not done.wait(timeout):
            response.result = self._result(R.RESULT_OPERATION_FAILED, 'stepping timed out')
            return response
        response.result = self._result(R.RESULT_OK)
        return response

    # ---------------------------------------------------------------- viewer
    def _open_viewer(self):
        if not os.environ.get('DISPLAY') and not os.environ.get('WAYLAND_DISPLAY'):
            self.get_logger().warning('headless:=false but no display; running headless')
            return
        try:
            import mujoco.viewer
            world = self.sim.world
            self._viewer = mujoco.viewer.launch_passive(world.model, world.data)
        except Exception as exc:  # noqa: B902 - the viewer is optional
            self.get_logger().warning(f'cannot open the MuJoCo viewer: {exc}')
            self._viewer = None

    def _sync_viewer(self):
        """Sync (or after a spawn reopen) the MuJoCo viewer, at most 30 Hz (sim thread)."""
        now = time.monotonic()
        if now - self._last_viewer_sync < 1 / 30:
            return
        self._last_viewer_sync = now
        if self._viewer_stale:
            self._viewer_stale = False
            try:
                self._viewer.close()
            except Exception:  # noqa: B902 - the viewer is optional
                pass
            self._viewer = None
            self._open_viewer()
            return
        if not self._viewer.is_running():
            self._viewer = None
            return
        self._viewer.sync()

    # ---------------------------------------------------------------- shutdown
    def stop(self):
        """Stop the simulation thread, then destroy the controller managers (caller thread)."""
        self._stop_clock_follower()
        self.sim.close()
        if self._viewer is not None:
            self._viewer.close()


def main(args=None):
    """
    Run the simulator until Ctrl-C/SIGTERM (or a SetSimulationState QUITTING request).

    Shutdown order (:mod:`amr_description.ros.shutdown`): the simulation thread is stopped
    and joined, then the controllers are deactivated and their nodes,
    the controller managers and this node destroyed, and rclpy is shut down last, so no
    update or publication meets a dead context.

    :returns: 0; 1 when another simulator already publishes /clock in the domain (one line).
    """
    shutdown.init(args)
    executor = None
    node = None
    try:
        executor = SimTimeExecutor(SimTime())
        node = shutdown.create(MujocoSim, executor)
        executor.exempt.add(node)
        executor.add_node(node)
        shutdown.spin(executor, until=node.quit_requested.is_set)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.ignore_signals()
        if node is not None:
            node.stop()
        shutdown.shutdown(node, executor=executor)
    return 1 if node is not None and node.refused else 0


if __name__ == '__main__':
    import sys
    sys.exit(main())
