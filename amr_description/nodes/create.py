# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``create``: spawn a robot into ``mujoco_sim`` (the ``ros_gz_sim create`` command line).

Flags as upstream ``ros_gz_sim create``: one source of ``-topic TOPIC`` (a std_msgs/String
published transient-local, e.g. ``robot_description``), ``-file PATH`` (also
``package://``), ``-string XML`` or ``-param NAME`` (a string parameter of this node);
``-name NAME``, ``-allow_renaming``, pose ``-x -y -z`` (m) and ``-R -P -Y`` (rad),
``-world NAME`` (the simulator's loaded world must have that name, SDF ``<world name>``:
else one error line, as no ``/world/NAME/create`` service would answer in Gazebo);
``-robot_namespace NS`` (as gazebo_ros ``spawn_entity.py``): the entity's ROS namespace,
sent as the request's ``entity_namespace``, so the simulator creates the robot's controller
manager as ``/NS/controller_manager``. Extra: ``-service`` (default
``/mujoco_sim/spawn_entity``) and ``-timeout`` (s to wait for the topic and the service;
default 0: as long as it takes, as upstream, which waits until interrupted). Exits 0 when
the entity was created, 1 with a one-line error otherwise.
"""

import argparse
import math
import sys
import time

from amr_description.ros import shutdown
from amr_description.ros.node import Node
from amr_description.ros.simulation_services import RETRY_PERIOD
from amr_description.ros.simulation_services import SimulationServices
from geometry_msgs.msg import PoseStamped
from rclpy.executors import ExternalShutdownException
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from std_msgs.msg import String

DEFAULT_SERVICE = '/mujoco_sim/spawn_entity'


def build_parser():
    """Return the argparse parser of the ``create`` flags (single-dash, as upstream)."""
    parser = argparse.ArgumentParser(
        prog='create', description='Spawn an entity (URDF) into mujoco_sim.')
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument('-topic', help='topic with the robot description (std_msgs/String)')
    source.add_argument('-file', help='URDF file (path or package://)')
    source.add_argument('-string', help='URDF as a string')
    source.add_argument('-param', help='string parameter of this node holding the URDF')
    parser.add_argument('-name', default='', help='entity name (default: URDF robot name)')
    parser.add_argument('-allow_renaming', action='store_true',
                        help='rename the entity when the name is taken')
    parser.add_argument('-world', default='',
                        help='world name: the simulator must run the world of this name')
    parser.add_argument('-robot_namespace', default='',
                        help="ROS namespace of the entity's nodes (e.g. r1)")
    for flag, meaning in (('x', 'x (m)'), ('y', 'y (m)'), ('z', 'z (m)'),
                          ('R', 'roll (rad)'), ('P', 'pitch (rad)'), ('Y', 'yaw (rad)')):
        parser.add_argument(f'-{flag}', type=float, default=0.0, help=meaning)
    parser.add_argument('-service', default=DEFAULT_SERVICE, help='SpawnEntity service')
    parser.add_argument('-timeout', type=float, default=0.0,
                        help='seconds to wait for the topic and the service (0: no limit)')
    return parser


def pose_from_rpy(x, y, z, roll, pitch, yaw):
    """Return a PoseStamped in frame ``world`` from position (m) and fixed-axis RPY (rad)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    msg = PoseStamped()
    msg.header.frame_id = 'world'
    msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = x, y, z
    q = msg.pose.orientation
    q.w = cr * cp * cy + sr * sp * sy
    q.x = sr * cp * cy - cr * sp * sy
    q.y = cr * sp * cy + sr * cp * sy
    q.z = cr * cp * sy - sr * sp * cy
    return msg


class Create(Node):
    """Node ``ros_gz_sim``-like ``create``: gets the URDF and calls the spawn service."""

    def __init__(self, opts):
        """
        Create the node (``-param`` is read from its parameter of that name).

        :param opts: parsed :func:`build_parser` options.
        """
        super().__init__('create')
        self.opts = opts
        from simulation_interfaces.srv import SpawnEntity
        self._srv_type = SpawnEntity
        self._simulation = SimulationServices(
            self, lambda until: shutdown.spin(self, until=until),
            sim_node=opts.service.rpartition('/')[0] or '/', spawn_service=opts.service)

    def description(self):
        """
        Return the URDF text from the chosen source.

        :raises RuntimeError: one line when it cannot be obtained in time.
        """
        opts = self.opts
        if opts.string is not None:
            return opts.string
        if opts.file is not None:
            from amr_description.core.description.files import read_description
            try:
                return read_description(opts.file)  # a URDF, or a xacro expanded
            except ValueError as exc:
                cause = str(exc).partition(f'{opts.file}: ')[2] or str(exc)
                cause = cause[len('cannot read: '):] if cause.startswith('cannot read: ') \
                    else cause
                raise RuntimeError(f'cannot read -file {opts.file}: {cause}') from None
        if opts.param is not None:
            value = self.declare_parameter(opts.param, '').value
            if not value:
                raise RuntimeError(f'parameter [{opts.param}] is empty or not set')
            return value
        return self._from_topic(opts.topic)

    def _from_topic(self, topic):
        received = []
        qos = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                         reliability=ReliabilityPolicy.RELIABLE)
        sub = self.create_subscription(String, topic, lambda m: received.append(m.data), qos)
        self.get_logger().info(f'Waiting messages on topic [{topic}].')
        deadline = time.monotonic() + (self.opts.timeout if self.opts.timeout > 0 else math.inf)
        shutdown.spin(self, until=lambda: received or time.monotonic() > deadline)
        self.destroy_subscription(sub)
        if not received:
            raise RuntimeError(f'timed out after {self.opts.timeout:g} s waiting for a message '
                               f'on topic [{topic}]')
        return received[0]

    def spawn(self, urdf):
        """Call the spawn service; return (ok, message)."""
        opts = self.opts
        self.get_logger().info(f'Waiting for service {opts.service}...')
        if not self._simulation.wait_for_spawn_service(opts.timeout if opts.timeout > 0 else None):
            return False, (f'service {opts.service} not available after {opts.timeout:g} s: '
                           'is mujoco_sim running?')
        if opts.world:
            timeout = opts.timeout if opts.timeout > 0 else 30.0
            loaded = self._simulation.current_world(timeout)
            if loaded != opts.world:
                return False, (f'world [{opts.world}] is not loaded: '
                               f'{self._simulation.sim_node} runs world [{loaded}]')
        request = self._srv_type.Request()
        request.name = opts.name
        request.allow_renaming = opts.allow_renaming
        request.entity_namespace = opts.robot_namespace
        request.entity_resource.resource_string = urdf
        request.initial_pose = pose_from_rpy(opts.x, opts.y, opts.z, opts.R, opts.P, opts.Y)
        self.get_logger().info('Requested creation of entity.')
        response, lost_answer = self._simulation.spawn(
            request, timeout=opts.timeout + 30.0 if opts.timeout > 0 else None,
            repeat=not opts.allow_renaming, on_retry=self._on_retry)
        if lost_answer:
            from amr_description.core.description.urdf_model import entity_name
            return True, (f'OK creation of entity [{entity_name(opts.name, urdf)}]. (the answer '
                          'to the first request was lost; the entity exists)')
        if response is None:
            return False, f'no answer from {opts.service}'
        if response.result.result != response.result.RESULT_OK:
            return False, f'Failed request to create entity: {response.result.error_message}'
        return True, f'OK creation of entity [{response.entity_name}].'

    def _on_retry(self, attempt):
        self.get_logger().warning(
            f'Failed getting a result from calling {self.opts.service} in {RETRY_PERIOD:g} s. '
            f'(Attempt {attempt}.) Sending it again from a new client.')


def main(args=None):
    """
    Parse the flags, spawn, and return the exit code (0 created, 1 failed).

    Clean-shutdown pattern of :mod:`amr_description.ros.shutdown`; a ``-file``, ``-string``
    or ``-param`` description the URDF loader
    (:func:`amr_description.core.description.urdf_model.parse_urdf`) refuses is one error line and
    exit code 1, before the simulator is asked; one from ``-topic`` is checked by the simulator
    with the same loader (its refusal is the one error line).
    """
    argv = sys.argv[1:] if args is None else list(args)
    own = shutdown.remove_ros_args(['create'] + argv)[1:]
    opts = build_parser().parse_args(own)
    node = None
    code = 1
    try:
        shutdown.init(['create'] + argv)
        node = shutdown.create(Create, opts)
        urdf = node.description()
        if not opts.topic:
            # the package's one loader refuses here what the simulator would refuse; a
            # description from a topic was published by robot_state_publisher, which ran
            # the same loader (the simulator runs it again), so yourdfpy's import (~0.8 s of
            # CPU per robot) is saved on the fleet's start-up
            from amr_description.core.description.urdf_model import parse_urdf
            parse_urdf(urdf, source=opts.file or opts.param or '-string')
        ok, message = node.spawn(urdf)
        if ok:
            node.get_logger().info(message)
            code = 0
        else:
            node.get_logger().error(message)
    except (RuntimeError, ValueError) as exc:
        node.get_logger().error(' '.join(str(exc).split()))
    except (KeyboardInterrupt, ExternalShutdownException):
        code = 0  # Ctrl-C while waiting: a normal stop, not a failure (as the spawner)
    finally:
        shutdown.shutdown(node)
    return code


if __name__ == '__main__':
    sys.exit(main())
