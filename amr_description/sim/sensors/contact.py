# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
A contact sensor: ``contact`` sensor blocks (a bumper).

``<contact><collision>`` names one collision of the sensor's link by its SDF name
(:func:`~amr_description.core.gazebo.sensors.collision_names`: ``base_link_collision``, ...).
At each due instant the sensor reports MuJoCo's contacts of that collision's geom, one
``ros_gz_interfaces/Contact`` per touching collision, as ros_gz_bridge delivers gz-sim's
``gz.msgs.Contacts`` (``ros_gz_interfaces/msg/Contacts``, built field for field in
interfaces/ros_gz_interfaces):

- ``collision1``: the sensor's collision, ``collision2``: the one it touches, each an
  ``Entity`` of type COLLISION named with gz's scoped name (``model::link::collision``: the
  entity name, the URDF link and the SDF collision name for a robot; the SDF model, link and
  collision for a world model; ``ground_plane::link::collision`` for the ground) and the
  MuJoCo geom id;
- ``positions``, ``normals`` (unit, from collision1 towards collision2) and ``depths``
  (penetration, m, >= 0), one per MuJoCo contact point of the pair, in the world frame
  (``header.frame_id`` is empty, as the bridge leaves it: gz-sim's Contact system stamps its
  message and names no frame);
- ``wrenches``: one ``JointWrench`` per contact point, ``body_1_wrench.force`` the force on
  collision1 and ``body_2_wrench.force`` the force on collision2 (N, world frame,
  ``mj_contactForce``), torques zero.

An empty ``contacts`` list when nothing touches. A collision name the link does not have is
one line naming the sensor and the field; the sensor is skipped.
"""

from amr_description.core.gazebo.sensors import collision_names
from amr_description.core.gazebo.sensors import lumped_link
from amr_description.ros.stamps import set_stamp
from amr_description.sim.sensors.base import Sensor
from amr_description.sim.sensors.base import sensor_frame
from amr_description.sim.sensors.base import sensor_rate
from amr_description.sim.sensors.base import sensor_topic
from geometry_msgs.msg import Vector3
import mujoco
import numpy as np
from ros_gz_interfaces.msg import Contact
from ros_gz_interfaces.msg import Contacts
from ros_gz_interfaces.msg import Entity
from ros_gz_interfaces.msg import JointWrench

GROUND_NAME = 'ground_plane::link::collision'
"""gz's scoped name of the ground of gz-sim's ``empty.sdf``."""


def gz_collision_name(geom_name, robots):
    """
    Return gz's scoped collision name of a MuJoCo geom.

    :param geom_name: ``<entity>/<link>/<collision>`` of a robot, ``model::link::collision``
        of a world model, ``ground_plane``.
    :param robots: dict entity name -> dict (link, geom suffix) -> SDF collision name.
    """
    if geom_name == 'ground_plane':
        return GROUND_NAME
    parts = geom_name.split('/')
    if len(parts) == 3 and parts[0] in robots:
        entity, link, suffix = parts
        return f'{entity}::{link}::{robots[entity].get((link, suffix), suffix)}'
    return geom_name.replace('/', '::')


def _vector(values):
    x, y, z = (float(v) for v in values)
    return Vector3(x=x, y=y, z=z)


class ContactSensor(Sensor):
    """The Contacts of one contact block (module docstring)."""

    message_type = Contacts

    def __init__(self, entity, block, geom, topics, frame_id, rate, sdf_names):
        """Keep the geom to watch (``(URDF link, geom suffix)``); its id is looked up per model."""
        self.name = block.name
        self.topic, self.gz_name = topics
        self.frame_id = frame_id
        self.rate = float(rate)
        self._entity = entity.name
        self._geom = f'{entity.robot.prefix}{geom[0]}/{geom[1]}'
        self._own = f'{entity.name}::{block.link}::{block.contact_collision}'
        self._sdf_names = {entity.name: sdf_names}
        self._model = None
        self._force = np.zeros(6)

    def measure(self, world, t):
        """Return the Contacts of sim time ``t`` (s): the touching contacts of the collision."""
        model, data = world.model, world.data
        if self._model is not model:
            self._id = model.geom(self._geom).id
            self._model = model
        msg = Contacts()
        set_stamp(msg.header.stamp, t)  # no frame id: gz-sim's Contact system sets none
        pairs = {}
        for index in range(data.ncon):
            contact = data.contact[index]
            if contact.exclude != 0 or self._id not in (contact.geom1, contact.geom2):
                continue
            first = contact.geom1 == self._id
            other = int(contact.geom2 if first else contact.geom1)
            mujoco.mj_contactForce(model, data, index, self._force)
            frame = contact.frame.reshape(3, 3)
            force_on_geom2 = frame.T @ self._force[:3]  # the contact frame's x is the normal
            sign = 1.0 if first else -1.0  # normal from geom1 to geom2: ours to the other
            item = pairs.get(other)
            if item is None:
                item = pairs[other] = Contact()
                item.collision1 = Entity(id=self._id, name=self._own, type=Entity.COLLISION)
                item.collision2 = Entity(id=other, type=Entity.COLLISION, name=gz_collision_name(
                    model.geom(other).name, self._sdf_names))
            item.positions.append(_vector(contact.pos))
            item.normals.append(_vector(sign * frame[0]))
            item.depths.append(float(max(0.0, -contact.dist)))
            wrench = JointWrench()
            wrench.header = msg.header
            wrench.body_1_name.data = item.collision1.name
            wrench.body_2_name.data = item.collision2.name
            wrench.body_1_wrench.force = _vector(-sign * force_on_geom2)
            wrench.body_2_wrench.force = _vector(sign * force_on_geom2)
            item.wrenches.append(wrench)
        msg.contacts = list(pairs.values())
        return msg


def create(entity, settings):
    """
    Return the sensors of every contact block of ``entity``.

    :param entity: the spawned entity.
    :param settings: dict; ``physics_step``, ``world`` as the lidar's; ``messages``.
    """
    blocks = [b for b in entity.description.sensors.sensors if b.kind == 'contact']
    if not blocks:
        return []
    description = entity.description
    names = collision_names(description.model, description.gazebo_tags)
    sdf_names = {}
    for name, (link, index) in names.items():
        collision = description.model.links[link].collisions[index]
        suffix = collision.name or f'collision_{index}'
        sdf_names.setdefault((link, suffix), name)
    sensors = []
    for block in blocks:
        found = names.get(block.contact_collision)
        model, tags = description.model, description.gazebo_tags
        if found is None or lumped_link(model, found[0], tags) != \
                lumped_link(model, block.link, tags):
            own = sorted(n for n, (link, _) in names.items()
                         if lumped_link(model, link, tags) == lumped_link(model, block.link, tags))
            settings.setdefault('messages', []).append(
                f'sensor {block.name!r}: <contact><collision> {block.contact_collision!r} is '
                f'not a collision of link {block.link!r} (its collisions: '
                f'{", ".join(own) or "none"}); the sensor is skipped')
            continue
        link, index = found
        collision = description.model.links[link].collisions[index]
        sensors.append(ContactSensor(
            entity, block, (link, collision.name or f'collision_{index}'),
            sensor_topic(entity, block, settings.get('world', 'empty')),
            sensor_frame(entity, block),
            sensor_rate(block, float(settings.get('physics_step', 0.001))), sdf_names))
    return sensors
