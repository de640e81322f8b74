# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A spawned robot (:class:`Entity`) and the stages of spawning one (:func:`spawn_stages`).

No rclpy: the controller-manager factory and ``setup`` callbacks given to the
:class:`~amr_description.sim.simulation.Simulation` bring the ROS side.
"""

import os

from amr_description.control.resource_manager import default_hardware_factory
from amr_description.core.description.files import resolve_uri
from amr_description.core.description.robot_description import RobotDescription
from amr_description.core.gazebo.tags import ControlPlugin
from amr_description.core.gazebo.tags import GAZEBO_SYSTEMS
from amr_description.core.gazebo.tags import SIMULATOR_SYSTEMS
from amr_description.core.ros_names import normalize_namespace
from amr_description.sim.mujoco_system import MujocoSystem
from amr_description.sim.sensors.registry import make_sensors
from amr_description.sim.systems import make_systems
from amr_description.sim.systems import SystemGroup


class SpawnError(ValueError):
    """
    A refused spawn: one line, and the SpawnEntity result it stands for.

    :ivar code: the name of the ``simulation_interfaces`` result constant:
        ``'NAME_NOT_UNIQUE'``, ``'NAMESPACE_INVALID'``, ``'RESOURCE_PARSE_ERROR'`` (constants
        of ``SpawnEntity.Response``) or ``'RESULT_OPERATION_FAILED'`` (of ``Result``).
    """

    def __init__(self, message, code='RESULT_OPERATION_FAILED'):
        """Keep the one-line ``message`` and the result ``code`` (see the class docstring)."""
        super().__init__(message)
        self.code = code


class Entity:
    """
    A spawned robot: its world entry, its namespace and its controller manager.

    :ivar name: entity name, unique in the simulation (str).
    :ivar namespace: ROS namespace, ``''`` or ``'/r1'`` (unique in the simulation).
    :ivar robot: the :class:`~amr_description.sim.world.Robot` (bodies prefixed ``name/``).
    :ivar description: the
        :class:`~amr_description.core.description.robot_description.RobotDescription` it was
        spawned from (parsed once; ``description.xml`` is the URDF text).
    :ivar controller_manager: the controller manager, or None (no ``<ros2_control>``).
    :ivar systems: the ``MujocoSystem`` hardware components bound to the world.
    :ivar sensors: its :class:`~amr_description.sim.sensors.base.Sensor` instances, made from
        its description by the registered sensor factories.
    :ivar steps_per_update: physics steps between two controller-manager updates (0: none).
    :ivar gz_systems: its gz-sim systems
        (:class:`~amr_description.sim.systems.SystemGroup`), or None without any.
    :ivar inputs: the topics its systems listen to
        (:class:`~amr_description.sim.systems.base.Input` list).
    """

    def __init__(self, name, namespace, robot, description):
        """Keep the fields (see the class docstring)."""
        self.name = name
        self.namespace = namespace
        self.robot = robot
        self.description = description
        self.controller_manager = None
        self.steps_per_update = 0
        self.systems = []
        self.sensors = []
        self.gz_systems = None
        self.inputs = []

    @property
    def frame_prefix(self):
        """Return the TF frame prefix of the entity, ``''`` or ``'r1/'`` (REP 105 fleets)."""
        return self.namespace[1:] + '/' if self.namespace else ''


def spawn_stages(sim, urdf, name='', pose=None, namespace='', allow_renaming=False, setup=None):
    """
    Return :meth:`Simulation.spawn` of ``sim`` as a generator (caller must not block).

    Stages: parse the description once, add the robot to the world (simulation thread),
    create its controller manager, sensors and the caller's ``setup`` (driving thread; on a
    failure the robot is taken out again), activate it (simulation thread). The generator
    yields functions to run on the simulation thread and is sent their results (``send``); it
    returns the :class:`Entity` (``StopIteration.value``). Same arguments and errors as
    :meth:`Simulation.spawn`; an error of a yielded function must be thrown into the
    generator.
    """
    try:
        namespace = normalize_namespace(namespace)
    except ValueError as exc:
        raise SpawnError(str(exc), 'NAMESPACE_INVALID') from None
    try:
        description = RobotDescription(urdf, source='URDF')  # the spawn's one parse
    except ValueError as exc:
        raise SpawnError(str(exc).splitlines()[0], 'RESOURCE_PARSE_ERROR') from None
    name = name or description.name
    plugin = description.control_plugin
    if not namespace and plugin is not None and plugin.namespace:
        namespace = plugin.namespace  # gz_ros2_control's <ros><namespace>
    has_control = bool(description.hardware)
    entity = yield lambda: sim.add_entity(description, name, pose, namespace, allow_renaming)
    cm = None
    try:
        if has_control and sim.controller_manager_factory is not None:
            cm = sim.controller_manager_factory(
                entity, hardware_factory(sim.world, entity),
                parameters_file(sim.parameters_file, description))
            entity.controller_manager = cm
        systems = make_systems(entity, sim.world, sim.world.name)
        skipped = []
        spherical = getattr(sim.world.description, 'spherical_coordinates', None)
        entity.sensors = make_sensors(entity, dict(
            sim.sensor_settings, world=sim.world.name, physics_step=sim.physics_step,
            spherical_coordinates=spherical, messages=skipped))
        # gz-sim would run it, or use it: say so
        for line in description.sensors.messages + description.messages + skipped:
            sim.logger.warning(f'entity {entity.name!r}: {line}')
        if systems:
            entity.gz_systems = SystemGroup(systems)
            entity.sensors += [output for system in systems for output in system.outputs]
            entity.inputs = [item for system in systems for item in system.inputs]
        for name in description.gz_systems.unknown:  # gz-sim would run it: say it does not
            sim.logger.warning(f'entity {entity.name!r}: gz-sim system plugin {name!r} is not '
                               'simulated (docs/gazebo.md)')
        if setup is not None:
            setup(entity)
    except Exception as exc:  # noqa: B902 - any failure: undo, report one line
        entity.controller_manager = None
        if cm is not None and sim.controller_manager_release is not None:
            try:
                sim.controller_manager_release(cm)
            except Exception:  # noqa: B902 - the original error is what matters
                pass
        yield lambda: sim.remove_entity(entity)
        text = str(exc).splitlines()[0] if str(exc) else repr(exc)
        raise SpawnError(text) from None
    yield lambda: sim.activate_entity(entity)
    return entity


def place_entity(world, entities, description, name, pose, namespace, allow_renaming, logger):
    """
    Add a robot's bodies to ``world`` and return its :class:`Entity` (simulation thread).

    A taken name gets ``_0``, ``_1``, ... with ``allow_renaming`` (gz-sim's UserCommands);
    initial joint states are applied; a robot spawned overlapping a world model is warned
    about and kept, as gz-sim does.

    :param world: the :class:`~amr_description.sim.world.World`.
    :param entities: dict name -> :class:`Entity` already in the world (not changed).
    :param description: the spawn's
        :class:`~amr_description.core.description.robot_description.RobotDescription`.
    :param name: entity name; ``pose``: ``[x, y, z, qx, qy, qz, qw]`` or None.
    :param namespace: its ROS namespace (normalized).
    :param logger: ``logging.Logger``-like (``warning``).
    :raises SpawnError: a taken name or namespace, a description MuJoCo cannot build.
    """
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    if name in entities and allow_renaming:  # gz-sim's UserCommands: X_0, X_1, ...
        index = 0
        while f'{name}_{index}' in entities:
            index += 1
        name = f'{name}_{index}'
    if name in entities:
        raise SpawnError(f'an entity named {name!r} already exists', 'NAME_NOT_UNIQUE')
    for other in entities.values():
        if other.namespace == namespace:
            shown = namespace or '/'
            raise SpawnError(
                f'namespace {shown!r} is already used by entity {other.name!r}; give each '
                'robot its own namespace (entity_namespace / -robot_namespace)',
                'NAME_NOT_UNIQUE')
    try:
        spec = urdf_to_spec(description, name=name,
                            pose=(0, 0, 0, 0, 0, 0) if pose is None else pose)
        self_collide = description.self_collide_links()
    except ValueError as exc:
        raise SpawnError(str(exc).splitlines()[0], 'RESOURCE_PARSE_ERROR') from None
    robot = world.spawn(spec, name, description.xml, self_collide=self_collide)
    for joint, position, velocity in description.initial_joint_states():
        world.set_initial_joint_state(robot.prefix + joint, position, velocity)
    overlapping = world.overlapping_models(name)
    if overlapping:  # spawned all the same, as gz-sim does
        logger.warning(f'robot {name!r} is spawned overlapping world model'
                       f'{"s" if len(overlapping) > 1 else ""} '
                       f'{", ".join(repr(m) for m in overlapping)}')
    return Entity(name, namespace, robot, description)


def hardware_factory(world, entity):
    """Return ``(HardwareInfo) -> SystemInterface`` building MujocoSystem for ``entity``."""

    def factory(info):
        if info.plugin in SIMULATOR_SYSTEMS:
            gazebo = None
            if info.plugin in GAZEBO_SYSTEMS:
                gazebo = entity.description.control_plugin or ControlPlugin()
            system = MujocoSystem(world.model, world.data,
                                  prefix=entity.robot.prefix, gazebo=gazebo)
            entity.systems.append(system)
            return system
        return default_hardware_factory(info)
    return factory


def parameters_file(default, description):
    """
    Return the controllers YAML paths of a robot, in order ([] when there is none).

    :param default: the simulator's ``parameters_file`` ('' = each description's own).
    :param description: the robot's RobotDescription (``<mujoco><ros2_control parameters>``,
        else every ``<parameters>`` of gz_ros2_control's plugin).
    :raises ValueError: one line naming a file that does not exist.
    """
    paths = [default] if default else description.parameters_files()
    resolved = []
    for path in paths:
        found = resolve_uri(path)
        if not os.path.isfile(found):
            raise ValueError(f'controller parameters file {found!r} not found')
        resolved.append(found)
    return resolved
