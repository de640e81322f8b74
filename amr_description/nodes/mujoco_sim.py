# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The ``mujoco_sim`` node: MuJoCo physics + in-process controller manager (gz sim's role).

Parameters (read at start):
  ``physics_step`` (double, 0.001 s), ``real_time_factor`` (double, 1.0; 0 = as fast as
  possible), ``headless`` (bool, true; false opens the MuJoCo viewer when a display exists),
  ``parameters_file`` (string, '' = the URDF's ``<mujoco><ros2_control parameters=...>``),
  ``paused`` (bool, false), ``publish_ground_truth`` (bool, true), ``ground_truth_rate``
  (double, 50.0 Hz of sim time).

Topics: ``/clock`` (rosgraph_msgs/Clock, reliable, depth 10) after every control update, at
least 100 Hz of sim time, and at 10 Hz (wall) with an unchanged time while paused (an empty
world runs in real time even with ``real_time_factor`` 0: fast-forward starts with the
first spawned entity); ``/ground_truth/odom``
(nav_msgs/Odometry) of the first spawned robot: pose of its root link (``base_footprint``)
in frame ``world``, twist in the root link frame (REP 105 / Odometry convention).

Services (simulation_interfaces): ``~/spawn_entity`` (SpawnEntity), ``~/reset_simulation``
(ResetSimulation: resets poses, velocities and time to the spawn state; removing spawned
entities is unsupported), ``~/set_simulation_state`` (SetSimulationState: playing, paused,
stopped = paused + reset, quitting), ``~/step_simulation`` (StepSimulation: N physics steps
while paused; answers when done). With the node name ``mujoco_sim`` they are
``/mujoco_sim/spawn_entity`` and so on.

Simulation loop (docs/architecture.md): one thread steps MuJoCo in ``mj_step`` batches up to
the next control instant (every ``1/update_rate`` s of sim time), then runs
``cm.update(t, period)`` (read -> controllers -> write) and publishes ``/clock``, paced to
``real_time_factor``. The rclpy executor runs in the main thread; requests that touch the
model (spawn, reset, step) are queued to the simulation thread. The simulation thread also
publishes /clock and the ground truth itself, in order (no publisher thread: on a 2-core machine
waking another thread for every update costs more than the publishing).
"""

import collections
import math
import os
import threading
import time

from amr_description.nodes import shutdown
from amr_description.sim.urdf_to_mjcf import resolve_uri
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.world import World
from nav_msgs.msg import Odometry
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.time import Time
from rosgraph_msgs.msg import Clock

NO_ROBOT_CLOCK_RATE = 100.0  # Hz of sim time while no controller manager runs
REQUEST_TIMEOUT = 30.0  # s a service waits for the simulation thread
PAUSED_CLOCK_PERIOD = 0.1  # s (wall) between /clock messages while paused


def _sim_msgs():
    """Import the simulation_interfaces message and service modules."""
    from simulation_interfaces import msg
    from simulation_interfaces import srv
    return msg, srv


def make_controller_manager(urdf_xml, executor, hardware_factory, parameters_file, namespace):
    """
    Create the in-sim controller manager (``amr_description.control.controller_manager``).

    :returns: the ControllerManager node, added with its controllers to ``executor``.
    :raises ValueError: one line, on bad input (unknown plugin, missing joint, bad YAML).
    :raises ImportError: when the controller manager module is not available.
    """
    from amr_description.control.controller_manager import ControllerManager
    return ControllerManager(urdf_xml, executor, hardware_factory=hardware_factory,
                             parameters_file=parameters_file, namespace=namespace,
                             use_sim_time=True)


def take_over_time_source(node):
    """
    Stop a node's /clock subscription so the caller can drive its sim time directly.

    Only for nodes in this process with ``use_sim_time`` true; the caller then sets the time
    of the source's clocks at every /clock instant, as rclpy ``TimeSource.clock_callback``
    does.

    :param node: an rclpy node.
    :returns: the node's ``TimeSource``, or None when the node does not use sim time (then it
        is left alone).
    """
    source = getattr(node, '_time_source', None)
    if source is None or not source.ros_time_is_active:
        return None
    subscription = getattr(source, '_clock_sub', None)
    if subscription is not None:
        node.destroy_subscription(subscription)
        source._clock_sub = None
    return source


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


class _Request:
    """A function to run in the simulation thread and its outcome."""

    def __init__(self, function):
        self.function = function
        self.done = threading.Event()
        self.result = None
        self.error = None


class MujocoSim(Node):
    """Node ``mujoco_sim``: see the module docstring for parameters, topics and services."""

    def __init__(self, executor):
        """
        Declare parameters, build the empty world, create publishers and services.

        :param executor: the rclpy executor spinning this node (controller manager nodes are
            added to it).
        """
        super().__init__('mujoco_sim')
        self._executor = executor
        self.physics_step = self.declare_parameter('physics_step', 0.001).value
        self.real_time_factor = self.declare_parameter('real_time_factor', 1.0).value
        self.headless = self.declare_parameter('headless', True).value
        self.parameters_file = self.declare_parameter('parameters_file', '').value
        self.paused = self.declare_parameter('paused', False).value
        self.publish_ground_truth = self.declare_parameter('publish_ground_truth', True).value
        self.ground_truth_rate = self.declare_parameter('ground_truth_rate', 50.0).value
        if not self.physics_step > 0:
            self.get_logger().error(
                f'parameter physics_step must be > 0 s, found {self.physics_step}; using 0.001')
            self.physics_step = 0.001
        if not self.real_time_factor >= 0:
            self.get_logger().error(
                f'parameter real_time_factor must be >= 0, found {self.real_time_factor}; '
                'using 1.0')
            self.real_time_factor = 1.0
        self.world = World(self.physics_step)
        self.controller_manager = None
        self._systems = []  # MujocoSystem instances to rebind after a recompile
        self._gt_robot = None
        self._step_count = 0
        self._pending_steps = 0
        self._step_waiters = []
        self._requests = collections.deque()  # _Request; appended by services, run by _run
        self._wake = threading.Event()
        self._running = True
        self.quit_requested = threading.Event()
        self._viewer = None
        self._update_errors = 0
        self._clock_nodes = []
        self._clock_sources = []

        # the node's own clock follows the simulation (its sim time), without subscribing to
        # the /clock it publishes itself
        self.get_clock()._set_ros_time_is_active(True)
        self.get_clock().set_ros_time_override(Time(nanoseconds=0))

        self._clock_pub = self.create_publisher(Clock, '/clock', 10)
        self._odom_pub = self.create_publisher(Odometry, '/ground_truth/odom', 10)
        self._clock_msg = Clock()
        self._odom_msg = Odometry()
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
        self._thread = threading.Thread(target=self._run, name='mujoco_sim', daemon=True)
        self._thread.start()
        self.get_logger().info(
            f'MuJoCo {self.physics_step * 1000:g} ms physics, real_time_factor '
            f'{self.real_time_factor:g}{" (paused)" if self.paused else ""}; '
            f'spawn with {self.get_fully_qualified_name()}/spawn_entity')

    # ---------------------------------------------------------------- requests from services
    def _call(self, function, timeout=REQUEST_TIMEOUT):
        """
        Run ``function()`` in the simulation thread and return its result.

        :raises TimeoutError: when the simulation thread does not answer in ``timeout`` s.
        """
        request = _Request(function)
        self._requests.append(request)
        self._wake.set()
        if not request.done.wait(timeout):
            raise TimeoutError('the simulation thread did not answer')
        if request.error is not None:
            raise request.error
        return request.result

    def _process_requests(self):
        """Run the queued requests (simulation thread)."""
        requests = self._requests
        while requests:
            request = requests.popleft()
            try:
                request.result = request.function()
            except Exception as exc:  # noqa: B902 - reported to the caller, loop goes on
                request.error = exc
            request.done.set()

    def _result(self, code, message=''):
        result = self._result_type()
        result.result = code
        result.error_message = message
        return result

    # ---------------------------------------------------------------- spawn
    def _on_spawn(self, request, response):
        R = self._result_type
        _, srv = _sim_msgs()
        try:
            urdf = self._resource(request.entity_resource)
        except ValueError as exc:
            code = srv.SpawnEntity.Response.NO_RESOURCE if 'empty' in str(exc) \
                else R.RESULT_OPERATION_FAILED
            return self._spawn_failed(response, code, str(exc))
        pose = request.initial_pose.pose
        frame = request.initial_pose.header.frame_id
        if frame not in ('', 'world'):
            return self._spawn_failed(response, srv.SpawnEntity.Response.INVALID_POSE,
                                      f'initial_pose frame {frame!r} is not "world"')
        values = [pose.position.x, pose.position.y, pose.position.z, pose.orientation.x,
                  pose.orientation.y, pose.orientation.z, pose.orientation.w]
        if not all(math.isfinite(v) for v in values) or \
                math.sqrt(sum(v * v for v in values[3:])) < 1e-9:
            return self._spawn_failed(response, srv.SpawnEntity.Response.INVALID_POSE,
                                      'initial_pose must be finite with a non-zero quaternion')
        try:
            name, ok = self._call(lambda: self._spawn(
                urdf, request.name, request.allow_renaming, values, request.entity_namespace))
        except (ValueError, TimeoutError) as exc:
            text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            code = R.RESULT_OPERATION_FAILED
            if 'already exists' in text:
                code = srv.SpawnEntity.Response.NAME_NOT_UNIQUE
            elif text.startswith(('URDF', 'robot description')):
                code = srv.SpawnEntity.Response.RESOURCE_PARSE_ERROR
            return self._spawn_failed(response, code, text)
        response.result = self._result(R.RESULT_OK, ok)
        response.entity_name = name
        self.get_logger().info(ok)
        return response

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

    def _unique_name(self, name, allow_renaming, urdf):
        """Return the entity name: the request's, the URDF's, or a renamed one."""
        if not name:
            import xml.etree.ElementTree as ET
            try:
                name = ET.fromstring(urdf).get('name') or ''
            except ET.ParseError as exc:
                raise ValueError(f'URDF is not well-formed XML: {exc}') from None
        if not name:
            raise ValueError('no entity name given and the URDF <robot> has no name')
        if name in self.world.robots and allow_renaming:
            index = 1
            while f'{name}_{index}' in self.world.robots:
                index += 1
            name = f'{name}_{index}'
        return name

    def _spawn(self, urdf, name, allow_renaming, pose, namespace):
        """Build, add and wire a robot (simulation thread); return (name, message)."""
        name = self._unique_name(name, allow_renaming, urdf)
        if name in self.world.robots:
            raise ValueError(f'an entity named {name!r} already exists')
        spec = urdf_to_spec(urdf, name=name, pose=pose)
        robot = self.world.spawn(spec, name, urdf)
        self._rebind()
        message = f'spawned {name!r} ({self.world.model.nbody - 1} bodies, ' \
                  f'{self.world.model.nu} actuators in the world)'
        from amr_description.core.ros2_control_info import parse_ros2_control
        if parse_ros2_control(urdf):
            if self.controller_manager is not None:
                self.world.remove(name)
                self._rebind()
                raise ValueError(
                    'a robot with <ros2_control> is already controlled; one controller '
                    'manager per simulator')
            try:
                self.controller_manager = self._make_cm(urdf, robot, namespace)
            except ImportError as exc:
                message += f'; no controller manager ({exc})'
                self.get_logger().warning(f'controller manager not available: {exc}')
            except Exception as exc:  # noqa: B902 - any failure: remove the robot, report
                self.world.remove(name)
                self._systems = [s for s in self._systems if s.prefix != robot.prefix]
                self._rebind()
                raise ValueError(str(exc).splitlines()[0] if str(exc) else repr(exc)) from None
        if self._gt_robot is None:
            self._gt_robot = name
        if self._viewer is not None:
            self._reopen_viewer()
        return name, message

    def _make_cm(self, urdf, robot, namespace):
        """Create the controller manager with MujocoSystem hardware for ``robot``."""
        from amr_description.control.resource_manager import default_hardware_factory
        from amr_description.sim.mujoco_system import MujocoSystem

        def hardware_factory(info):
            if info.plugin == 'amr_description/MujocoSystem':
                system = MujocoSystem(self.world.model, self.world.data, prefix=robot.prefix)
                self._systems.append(system)
                return system
            return default_hardware_factory(info)

        parameters_file = self.parameters_file
        if not parameters_file:
            import xml.etree.ElementTree as ET
            from amr_description.sim.urdf_to_mjcf import parse_mujoco_block
            parameters_file = parse_mujoco_block(ET.fromstring(urdf)).parameters
        if parameters_file:
            parameters_file = resolve_uri(parameters_file)
            if not os.path.isfile(parameters_file):
                raise ValueError(f'controller parameters file {parameters_file!r} not found')
        return make_controller_manager(urdf, self._executor, hardware_factory,
                                       parameters_file or None, namespace)

    def _rebind(self):
        """Point every MujocoSystem at the current model/data."""
        for system in self._systems:
            system.rebind(self.world.model, self.world.data)

    # ---------------------------------------------------------------- reset / state / step
    def _on_reset(self, request, response):
        R = self._result_type
        if request.scope != 0 and not request.scope & 0b11:
            response.result = self._result(
                R.RESULT_FEATURE_UNSUPPORTED,
                'removing spawned entities is not supported; scopes TIME and STATE are')
            return response
        self._call(self._reset)
        self.get_logger().info('simulation reset')
        response.result = self._result(R.RESULT_OK)
        return response

    def _reset(self):
        """Reset the world to its spawn state at t = 0 (simulation thread)."""
        self.world.reset()
        self._step_count = 0
        self._anchor = None
        self._publish(0.0, force_gt=True)

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
        want_paused = target != S.STATE_PLAYING
        if target != S.STATE_STOPPED and want_paused == self.paused:
            response.result = self._result(
                srv.SetSimulationState.Response.ALREADY_IN_TARGET_STATE,
                'already ' + ('paused' if self.paused else 'playing'))
            return response

        def apply():
            self.paused = want_paused
            self._anchor = None
            if target == S.STATE_STOPPED:
                self._reset()
        self._call(apply)
        self.get_logger().info('simulation ' + {S.STATE_PLAYING: 'playing', S.STATE_PAUSED:
                                                'paused', S.STATE_STOPPED: 'stopped'}[target])
        response.result = self._result(R.RESULT_OK)
        return response

    def _on_step(self, request, response):
        R = self._result_type
        if not self.paused:
            response.result = self._result(R.RESULT_OPERATION_FAILED,
                                           'step_simulation needs a paused simulation')
            return response
        if request.steps < 1:
            response.result = self._result(R.RESULT_OK)
            return response
        done = threading.Event()

        def queue_steps():
            self._pending_steps += int(request.steps)
            self._step_waiters.append((self._step_count + int(request.steps), done))
        self._call(queue_steps)
        timeout = REQUEST_TIMEOUT + request.steps * 1e-3
        if not done.wait(timeout):
            response.result = self._result(R.RESULT_OPERATION_FAILED, 'stepping timed out')
            return response
        response.result = self._result(R.RESULT_OK)
        return response

    # ---------------------------------------------------------------- simulation thread
    def _control_steps(self):
        """Return physics steps per control update (controller manager rate or 100 Hz)."""
        rate = NO_ROBOT_CLOCK_RATE
        if self.controller_manager is not None:
            rate = float(getattr(self.controller_manager, 'update_rate', rate) or rate)
        return max(1, int(round(1.0 / (rate * self.world.physics_step))))

    def _run(self):
        """Run the simulation thread: step, update controllers, publish, pace, serve requests."""
        self._anchor = None
        gt_steps = max(1, int(round(1.0 / (self.ground_truth_rate * self.physics_step)))) \
            if self.ground_truth_rate > 0 else 0
        self._gt_steps = gt_steps
        last_viewer_sync = 0.0
        physics_step = self.world.physics_step
        last_paused_clock = 0.0
        requests = self._requests
        rate_of = None  # the controller manager per_update was computed for
        per_update = self._control_steps()
        try:
            while self._running:
                if requests:
                    self._process_requests()
                if self.paused and self._pending_steps == 0:
                    # paused: /clock keeps being published (same time, ~10 Hz wall), as gz does
                    if time.monotonic() - last_paused_clock > PAUSED_CLOCK_PERIOD:
                        last_paused_clock = time.monotonic()
                        self._publish(self._step_count * physics_step, clock_only=True)
                    self._wake.wait(0.05)
                    self._wake.clear()
                    continue
                cm = self.controller_manager
                if cm is not rate_of:  # update_rate is fixed when a controller manager starts
                    rate_of = cm
                    per_update = self._control_steps()
                count = per_update - self._step_count % per_update
                if self.paused:
                    count = min(count, self._pending_steps)
                    self._pending_steps -= count
                self.world.step(count)
                self._step_count += count
                t = self._step_count * physics_step
                if cm is not None and self._step_count % per_update == 0:
                    self._drive_node_clocks(t)
                    self._update_controllers(t, per_update * physics_step)
                self._publish(t)
                if self._step_waiters:
                    self._release_step_waiters()
                if self._viewer is not None and time.monotonic() - last_viewer_sync > 1 / 30:
                    last_viewer_sync = time.monotonic()
                    self._sync_viewer()
                if not self.paused:
                    if self.real_time_factor > 0:
                        self._pace(t, self.real_time_factor)
                    elif not self.world.robots:
                        self._pace(t, 1.0)  # fast-forward starts with the first entity
                    else:
                        self._anchor = None
        except Exception as exc:  # noqa: B902 - log instead of a silent thread death
            if self._running:  # e.g. not publishing after the context shut down
                self.get_logger().fatal(f'simulation thread stopped: {exc!r}')
                self.quit_requested.set()

    def _update_controllers(self, t, period):
        """Run one controller-manager update; errors are logged (throttled), never raised."""
        try:
            self.controller_manager.update(t, period)
        except Exception as exc:  # noqa: B902 - a controller bug must not stop physics
            self._update_errors += 1
            if self._update_errors in (1, 10, 100) or self._update_errors % 1000 == 0:
                self.get_logger().error(
                    f'controller manager update failed ({self._update_errors}x): {exc!r}')

    def _release_step_waiters(self):
        waiting = []
        for target, event in self._step_waiters:
            if self._step_count >= target or self._pending_steps == 0:
                event.set()
            else:
                waiting.append((target, event))
        self._step_waiters = waiting

    def _pace(self, t, factor):
        """Sleep so that sim time ``t`` (s) advances at ``factor`` times wall time."""
        now = time.perf_counter()
        if self._anchor is None:
            self._anchor = (now, t)
            return
        target = self._anchor[0] + (t - self._anchor[1]) / factor
        if target > now:
            time.sleep(target - now)
        elif now - target > 0.25:  # far behind (e.g. a spawn): do not try to catch up
            self._anchor = (now, t)

    def _drive_node_clocks(self, t):
        """
        Give the in-process controller nodes the current sim time, without DDS.

        The controller manager and controllers run in this process with ``use_sim_time``
        true. Instead of each receiving every /clock message through its own subscription
        (three executor callbacks per control update, which halves fast-forward speed), the
        simulation thread feeds their time source the /clock time it is about to publish,
        right before ``cm.update``. Their ROS clocks therefore equal the update time.

        :param t: sim time in s.
        """
        cm = self.controller_manager
        nodes = [cm]
        nodes.extend(getattr(cm, 'controllers', {}).values())
        if len(nodes) != len(self._clock_sources) or \
                any(n is not known for n, known in zip(nodes, self._clock_nodes)):
            self._clock_nodes = nodes
            self._clock_sources = [take_over_time_source(n) for n in nodes]
        now = Time(nanoseconds=int(round(t * 1e9)))
        for source in self._clock_sources:
            if source is not None:
                source._last_time_set = now  # what TimeSource.clock_callback does
                for clock in source._associated_clocks:
                    clock.set_ros_time_override(now)

    def _publish(self, t, force_gt=False, clock_only=False):
        """
        Publish /clock at sim time ``t`` (s), then the ground truth when due (sim thread).

        Also sets this node's own clock to ``t``.

        :param force_gt: publish the ground truth even when it is not due (after a reset).
        :param clock_only: publish /clock only (paused).
        """
        nanoseconds = int(round(t * 1e9))
        msg = self._clock_msg
        stamp = msg.clock
        stamp.sec, stamp.nanosec = divmod(nanoseconds, 1_000_000_000)
        self._clock_pub.publish(msg)
        self.get_clock().set_ros_time_override(Time(nanoseconds=nanoseconds))
        if clock_only or not self.publish_ground_truth or self._gt_robot is None or \
                not self._gt_steps or not (force_gt or self._step_count % self._gt_steps == 0):
            return
        self._publish_ground_truth(stamp, self.world.robots[self._gt_robot].root,
                                   self.world.ground_truth(self._gt_robot))

    def _publish_ground_truth(self, stamp, root, state):
        position, quat, linear, angular = state
        msg = self._odom_msg
        msg.header.stamp = stamp
        msg.header.frame_id = 'world'
        msg.child_frame_id = root
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        p.x, p.y, p.z = (float(v) for v in position)
        q.x, q.y, q.z, q.w = (float(v) for v in quat)
        lin, ang = msg.twist.twist.linear, msg.twist.twist.angular
        lin.x, lin.y, lin.z = (float(v) for v in linear)
        ang.x, ang.y, ang.z = (float(v) for v in angular)
        self._odom_pub.publish(msg)

    # ---------------------------------------------------------------- viewer
    def _open_viewer(self):
        if not os.environ.get('DISPLAY') and not os.environ.get('WAYLAND_DISPLAY'):
            self.get_logger().warning('headless:=false but no display; running headless')
            return
        try:
            import mujoco.viewer
            self._viewer = mujoco.viewer.launch_passive(self.world.model, self.world.data)
        except Exception as exc:  # noqa: B902 - the viewer is optional
            self.get_logger().warning(f'cannot open the MuJoCo viewer: {exc}')
            self._viewer = None

    def _reopen_viewer(self):
        try:
            self._viewer.close()
        except Exception:  # noqa: B902 - the viewer is optional
            pass
        self._viewer = None
        self._open_viewer()

    def _sync_viewer(self):
        if not self._viewer.is_running():
            self._viewer = None
            return
        self._viewer.sync()

    # ---------------------------------------------------------------- shutdown
    def stop(self):
        """Stop the simulation thread and the controller manager."""
        self._running = False
        self._wake.set()
        self._thread.join(timeout=5.0)
        cm, self.controller_manager = self.controller_manager, None
        if cm is not None:
            try:
                cm.shutdown()  # deactivates the controllers and destroys their nodes
            except Exception as exc:  # noqa: B902 - best effort at exit
                self.get_logger().warning(f'controller manager shutdown: {exc!r}')
            try:
                self._executor.remove_node(cm)
                cm.destroy_node()
            except Exception:  # noqa: B902 - best effort at exit
                pass
        if self._viewer is not None:
            self._viewer.close()


def main(args=None):
    """
    Run the simulator until Ctrl-C/SIGTERM (or a SetSimulationState QUITTING request).

    Shutdown order (:mod:`amr_description.nodes.shutdown`): the simulation thread is stopped
    and joined, then the controllers are deactivated and their nodes,
    the controller manager and this node destroyed, and rclpy is shut down last, so no
    update or publication meets a dead context.

    :returns: 0.
    """
    shutdown.init(args)
    executor = None
    node = None
    try:
        executor = SingleThreadedExecutor()
        node = MujocoSim(executor)
        executor.add_node(node)
        shutdown.spin(executor, until=node.quit_requested.is_set)
    except KeyboardInterrupt:
        pass
    finally:
        shutdown.ignore_signals()
        if node is not None:
            node.stop()
        shutdown.shutdown(node, executor=executor)
    return 0


if __name__ == '__main__':
    main()
