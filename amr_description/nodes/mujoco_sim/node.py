# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``mujoco_sim`` node: parameters, wiring of the engine's hooks, sensor publishers, ``main``.

Parameters, topics, services and threads: see :mod:`amr_description.nodes.mujoco_sim`.
"""

import threading

from amr_description.core.gazebo.bridge_config import read_bridge_config
from amr_description.core.gazebo.sdf_world import collapse_repeats
from amr_description.core.gazebo.sdf_world import load_world
from amr_description.core.ros_names import topic_name_problem
from amr_description.nodes.mujoco_sim.bridge import bridged_inputs
from amr_description.nodes.mujoco_sim.bridge import bridged_outputs
from amr_description.nodes.mujoco_sim.clock import ClockFollower
from amr_description.nodes.mujoco_sim.clock import ClockGuard
from amr_description.nodes.mujoco_sim.passive_viewer import PassiveViewer
from amr_description.nodes.mujoco_sim.services import SimulationServices
from amr_description.ros import shutdown
from amr_description.ros.node import Node
from amr_description.ros.sim_time import SimTime
from amr_description.ros.sim_time import SimTimeExecutor
from amr_description.ros.stamps import has_subscribers
from amr_description.sim.sensors.world_poses import WorldPoses
from amr_description.sim.simulation import Simulation
from rclpy.time import Time
from rosgraph_msgs.msg import Clock

PREWARM_MODULES = ('yourdfpy', 'amr_description.control.controller_manager',
                   'amr_description.control.joint_state_broadcaster',
                   'amr_description.control.diff_drive_controller')
"""Modules a spawn needs, imported while the node waits for the first one."""


def _prewarm_imports():
    """Import :data:`PREWARM_MODULES` (yourdfpy pulls trimesh: seconds on a loaded machine)."""
    import importlib
    for module in PREWARM_MODULES:
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


class _Published:
    """One sensor of one entity with its publisher and its period in physics steps."""

    __slots__ = ('sensor', 'publisher', 'steps')

    def __init__(self, sensor, publisher, steps):
        self.sensor = sensor
        self.publisher = publisher
        self.steps = steps


def _guarded(callback, topic, logger):
    """Return ``callback`` that logs (once per kind of error) instead of raising."""
    seen = set()

    def call(msg):
        try:
            callback(msg)
        except Exception as exc:  # noqa: B902 - garbage on a topic must not stop the node
            if type(exc) not in seen:
                seen.add(type(exc))
                logger.error(f'{topic}: message ignored: {exc!r}')
    return call


class MujocoSim(Node):
    """Node ``mujoco_sim``: see :mod:`amr_description.nodes.mujoco_sim`."""

    def __init__(self, executor):
        """
        Declare parameters, build the engine, create publishers and services.

        :param executor: the :class:`~amr_description.ros.sim_time.SimTimeExecutor` spinning
            this node (controller manager nodes are added to it).
        """
        super().__init__('mujoco_sim')
        self._executor = executor
        world_value = self.declare_parameter('world', 'empty').value
        world = load_world(world_value)  # WorldError (a ValueError): exit 1, one line
        self.physics_step = self.declare_parameter('physics_step', world.physics_step).value
        self.real_time_factor = self.declare_parameter(
            'real_time_factor', world.real_time_factor).value
        self.headless = self.declare_parameter('headless', True).value
        self.parameters_file = self.declare_parameter('parameters_file', '').value
        paused = self.declare_parameter('paused', False).value
        publish_ground_truth = self.declare_parameter('publish_ground_truth', True).value
        ground_truth_rate = self.declare_parameter('ground_truth_rate', 50.0).value
        self.clock_source = self.declare_parameter('clock_source', 'internal').value
        self.bridge_config = self.declare_parameter('bridge_config', '').value
        self.seed = self.declare_parameter('seed', 0).value
        self._check_parameters()
        self.external_clock = self.clock_source == 'external'
        self.refused = None  # one-line reason to exit 1
        self.quit_requested = threading.Event()
        self._published = []  # _Published of every active entity's sensors
        self._pending = {}  # entity name -> its _Published, between setup and spawned
        self._clock_msg = Clock()

        # the node's own clock follows the simulation (its sim time), without subscribing to
        # the /clock it publishes itself
        self.get_clock()._set_ros_time_is_active(True)
        self.get_clock().set_ros_time_override(Time(nanoseconds=0))

        self.sim = Simulation(
            self.physics_step, self.real_time_factor, paused,
            controller_manager_factory=self._make_cm,
            controller_manager_release=lambda cm: cm.destroy(),
            parameters_file=self.parameters_file, logger=_Logger(self.get_logger()),
            sensor_settings={'publish_ground_truth': publish_ground_truth,
                             'ground_truth_rate': ground_truth_rate, 'seed': self.seed},
            world=world)
        self._report_world(world)
        self.sim.before_update.append(executor.sim_time.set_time)
        self.sim.after_cycle.append(self._after_cycle)
        self.sim.paused_tick.append(self._publish_clock)
        self.sim.on_reset.append(self._on_sim_reset)
        self._clock_guard = None
        self._follower = None
        if self.external_clock:
            self.sim.follow_external_clock()
            self._follower = ClockFollower(self, self.sim.set_external_time)
        else:
            self._clock_guard = ClockGuard(self, self._refuse)
        self._viewer = None
        self._simulation_services = SimulationServices(self, self.sim, executor, self._on_spawned)
        self._publish_world_poses()
        if not self.headless:
            self._viewer = PassiveViewer(self.sim.world, self.get_logger())
            self.sim.after_cycle.append(self._viewer.sync)
        threading.Thread(target=_prewarm_imports, name='prewarm', daemon=True).start()
        self.sim.start('mujoco_sim')
        self.get_logger().info(
            f'MuJoCo {self.physics_step * 1000:g} ms physics, real_time_factor '
            f'{self.real_time_factor:g}{" (paused)" if paused else ""}'
            f'{", following the external /clock" if self.external_clock else ""}; '
            f'spawn with {self.get_fully_qualified_name()}/spawn_entity')

    def _report_world(self, world):
        """Log what the world file gave (one line each) and what is not simulated."""
        log = self.get_logger()
        for message in collapse_repeats(world.messages + self.sim.world.messages):
            log.warning(message)
        if world.not_simulated:
            log.info(f'world {world.name!r} ({world.source}): not simulated: '
                     f'{", ".join(world.not_simulated)}')
        log.info(f'world {world.name!r}: {len(world.models)} models from {world.source}')

    def _check_parameters(self):
        """Replace an invalid parameter by its default, with one error line each."""
        log = self.get_logger()
        if not self.physics_step > 0:
            log.error(
                f'parameter physics_step must be > 0 s, found {self.physics_step}; using 0.001')
            self.physics_step = 0.001
        if not self.real_time_factor >= 0:
            log.error(f'parameter real_time_factor must be >= 0, found '
                      f'{self.real_time_factor}; using 1.0')
            self.real_time_factor = 1.0
        self._bridge = None  # the ros_gz_bridge entries, None: every gz topic as it is
        if self.bridge_config:
            try:
                self._bridge = read_bridge_config(self.bridge_config)
            except ValueError as exc:
                log.error(f'parameter bridge_config: {exc}; gz topics keep their names')
        if not isinstance(self.seed, int) or self.seed < 0:
            log.error(f'parameter seed must be an integer >= 0, found {self.seed!r}; using 0')
            self.seed = 0
        if self.clock_source not in ('internal', 'external'):
            log.error(f"parameter clock_source must be 'internal' or 'external', found "
                      f"{self.clock_source!r}; using 'internal'")
            self.clock_source = 'internal'

    @property
    def paused(self):
        """Return True while the simulation is paused."""
        return self.sim.paused

    def _refuse(self, reason):
        self.refused = reason
        self.quit_requested.set()

    # ---------------------------------------------------------------- spawn (executor)
    def _make_cm(self, entity, hardware_factory, parameters_file):
        """Create the controller manager of ``entity`` in its namespace (executor thread)."""
        try:
            from amr_description.control.controller_manager import ControllerManager
        except ImportError as exc:
            raise ValueError(f'controller manager not available: {exc}') from None
        plugin = entity.description.control_plugin  # gz_ros2_control's, or None
        return ControllerManager(
            entity.description, self._executor, hardware_factory=hardware_factory,
            parameters_file=parameters_file, namespace=entity.namespace, use_sim_time=True,
            name=plugin.controller_manager_name if plugin else 'controller_manager',
            remappings=plugin.remappings if plugin else ())

    def setup_entity(self, entity):
        """
        Create the publishers and subscriptions of ``entity`` (executor thread, before it runs).

        One publisher per sensor, one subscription per input of its gz-sim systems; both use
        ros_gz_bridge's ROS-side QoS: reliable, volatile, keep last 10.
        """
        outputs = bridged_outputs(entity.sensors, self._bridge)
        inputs = bridged_inputs(entity.inputs, self._bridge)
        pending = []
        for sensor, topic in outputs:
            problem = topic_name_problem(topic)
            if problem:  # a world or model name in gz-sim's default topic, a bridge entry
                self.get_logger().error(f'{entity.name}: sensor {sensor.name!r}: topic '
                                        f'{topic!r} is not a valid ROS topic name: {problem}; '
                                        'the sensor is skipped')
                continue
            pending.append(_Published(sensor, self.create_publisher(
                sensor.message_type, topic, 10), sensor.period_steps(self.physics_step)))
        self._pending[entity.name] = pending
        for topic, message_type, callback in inputs:
            self.create_subscription(message_type, topic,
                                     _guarded(callback, topic, self.get_logger()), 10)

    def _publish_world_poses(self):
        """Publish the poses of the world's moving models, when it has any (gz-sim's)."""
        sensor = WorldPoses(self.sim.world)
        if not sensor.bodies:
            return
        for sensor, topic in bridged_outputs([sensor], self._bridge):
            self._published = self._published + [_Published(
                sensor, self.create_publisher(sensor.message_type, topic, 10),
                sensor.period_steps(self.physics_step))]

    def _on_spawned(self, entity):
        """Publish the new entity's sensors from the next cycle on (executor thread)."""
        self._published = self._published + self._pending.pop(entity.name, [])
        if self._viewer is not None:
            self._viewer.model_changed()

    # ---------------------------------------------------------------- hooks (sim thread)
    def _publish_clock(self, t):
        """Publish /clock at sim time ``t`` (s) and set this node's clock to it."""
        nanoseconds = int(round(t * 1e9))
        stamp = self._clock_msg.clock
        stamp.sec, stamp.nanosec = divmod(nanoseconds, 1_000_000_000)
        publisher = self._clock_guard.publisher if self._clock_guard is not None else None
        if publisher is not None:
            publisher.publish(self._clock_msg)
        self.get_clock().set_ros_time_override(Time(nanoseconds=nanoseconds))

    def _after_cycle(self, t):
        """Publish /clock, then every sensor due at ``t`` (simulation thread)."""
        self._publish_clock(t)
        if self.sim.halted is None:  # never a non-finite measurement
            self._publish_sensors(t, self.sim.step_count)

    def _publish_sensors(self, t, step_count=None):
        """
        Measure and publish the sensors due at step ``step_count`` (all when None).

        A sensor is measured and published only while its topic has a subscriber (volatile:
        an unheard message reaches nobody); otherwise a sensor that is not costly advances
        its noise generator past the instant (``Sensor.advance``). A deferred sensor (a
        camera) is requested, and its renderer given the instant's state once all have asked.
        """
        world = self.sim.world
        deferred = []
        for item in self._published:
            if step_count is not None and step_count % item.steps:
                continue
            if has_subscribers(item.publisher):
                if item.sensor.deferred:
                    target = item.sensor.request(t, item.publisher.publish)
                    if target not in deferred:
                        deferred.append(target)
                else:
                    item.publisher.publish(item.sensor.measure(world, t))
            elif not item.sensor.costly:
                item.sensor.advance(world, t)
        for target in deferred:
            target.flush(world, t)

    def _on_sim_reset(self):
        self._publish_clock(0.0)
        self._publish_sensors(0.0)

    # ---------------------------------------------------------------- shutdown
    def stop(self):
        """Stop the simulation thread, then destroy the controller managers (caller thread)."""
        if self._follower is not None:
            self._follower.stop()
            self._follower = None
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
    executor = None
    node = None
    try:
        shutdown.init(args)
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
