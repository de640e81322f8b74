# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
An SDF world into a MuJoCo spec (no rclpy).

The world is a :class:`~amr_description.core.gazebo.sdf_elements.World`.

Names are gz-sim's scoped names: collision geoms ``<model>::<link>::<collision>`` in
:data:`COLLISION_GROUP`, visual geoms ``<model>::<link>::visual::<visual>`` in
:data:`VISUAL_GROUP` that take part in no contact (MuJoCo's renderer shows the visual group
as the robots'). A visual of the same geometry at the same place as a collision of its link
(the usual case) is that collision geom moved to the visual group with the visual's colour:
each geom costs every physics step. The geoms of a static model's links are the world
body's (posed in the world frame); a link of a non-static model is a body
``<model>::<link>`` with a free joint (SDF: a link without a joint moves on its own) and its
``<inertial>`` (SDF's defaults where absent: 1 kg, 1 kg m^2).

The ground: the first plane of a static model facing up (+z) becomes the world's
``ground_plane`` geom, as the empty world's (friction as below); it is infinite for contacts,
as Gazebo's plane.

Friction: Gazebo combines two surfaces by the smaller ``mu``, MuJoCo by the larger (of two
geoms of equal ``priority``). A world surface with ``mu`` >= 1 keeps MuJoCo's default 1 (so a
robot link's own value, 1 by default in Gazebo too, decides, as the minimum would); one with
``mu`` < 1 (ice) gets priority 1, so its value decides against an untagged robot link, as the
minimum would. A robot link with ``<mu1>``/``<mu2>`` tags has priority 1 too (the larger then
decides). docs/worlds.md.

Collision meshes are convex hulls in MuJoCo: a mesh is split into its connected parts, each
its own hull of at most :data:`MAX_HULL_VERTICES` vertices (docs/worlds.md).
"""

import logging

from amr_description.core.description.meshes import prepare_mesh
from amr_description.core.description.meshes import solid
from amr_description.core.description.meshes import split_parts
from amr_description.core.description.meshes import THIN
from amr_description.core.gazebo.sdf_elements import shape_bounds
from amr_description.sim.urdf_to_mjcf import add_mesh
from amr_description.sim.urdf_to_mjcf import add_mesh_asset
import mujoco
import numpy as np

_LOG = logging.getLogger(__name__)

#: friction of the ground plane: sliding, torsional, rolling (MuJoCo geom friction)
GROUND_FRICTION = (1.0, 0.005, 0.0001)

COLLISION_GROUP = 3
"""MuJoCo geom group of world collision geoms (hidden by default, as the robots')."""

VISUAL_GROUP = 2
"""MuJoCo geom group of world visual geoms (shown, no contacts)."""

MAX_HULL_VERTICES = 256
"""Vertex limit of one convex hull of a collision mesh (MuJoCo ``maxhullvert``)."""

MAX_MESH_PARTS = 64
"""At most this many connected parts of one collision mesh get their own hull."""

SEPARATOR = '::'
"""Scope separator of world body and geom names (``model::link::collision``)."""

DEFAULT_RGBA = (0.7, 0.7, 0.7, 1.0)

LARGE_SHARE = 0.5
"""A static link longer than this share of the static world gets its own body."""

GROUND_BODY = 'ground_plane'
"""The static body of the ground plane geom (a body of its own: see sim/world.py)."""


def _quat(rotation):
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(rotation, dtype=float).ravel())
    return quat


def _place(element, T):
    element.pos = np.asarray(T[:3, 3], dtype=float)
    element.quat = _quat(T[:3, :3])


def _z_to(normal):
    """Return a 3x3 rotation taking +z to ``normal``."""
    n = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    quat = np.zeros(4)
    mujoco.mju_quatZ2Vec(quat, n)
    matrix = np.zeros(9)
    mujoco.mju_quat2Mat(matrix, quat)
    return matrix.reshape(3, 3)


def _mesh_parts(spec, shape, label, messages):
    """
    Return the meshes of one collision mesh: one per connected part (at most 64).

    Each part is its own convex hull; a flat part (a wall made of one quad) is thickened
    (:func:`amr_description.core.description.meshes.solid`), a part on one line is left out
    with a line in ``messages``. Parts are only built when there are 2 to 64 of them.
    """
    mesh = prepare_mesh(shape.path, shape.size)
    messages.extend(f'{label}: {note}' for note in mesh.notes)
    parts = split_parts(mesh.faces, len(mesh.vertices), MAX_MESH_PARTS)
    groups = [mesh.faces] if parts is None else [mesh.faces[index] for index in parts]
    meshes, flat = [], []
    for number, faces in enumerate(groups):
        part = repr(shape.path) if parts is None else f'{shape.path!r} part {number}'
        try:
            vertices, faces, notes = solid(mesh.vertices, faces, part)
        except ValueError as exc:
            messages.append(f'{label}: {exc}: that part skipped')
            continue
        flat += notes
        used, faces = np.unique(faces, return_inverse=True)
        part_mesh = add_mesh(spec, vertices[used], faces.reshape(-1, 3))
        part_mesh.maxhullvert = MAX_HULL_VERTICES
        meshes.append(part_mesh)
    if len(flat) > 1:
        flat = [f'{shape.path!r}: {len(flat)} of its {len(groups)} parts are flat: each given '
                f'a thickness of {THIN} m']
    messages.extend(f'{label}: {note}' for note in flat)
    if not meshes:
        raise ValueError(f'{shape.path!r}: no part of it is usable')
    return meshes


def _add_shape(spec, body, shape, name, collision, frame, messages):
    """
    Add the geoms of one shape to ``body``, posed ``frame @ shape.pose``; return them.

    A mesh trimesh cannot read adds no geom and one line to ``messages``.
    """
    kinds = {'box': mujoco.mjtGeom.mjGEOM_BOX, 'cylinder': mujoco.mjtGeom.mjGEOM_CYLINDER,
             'capsule': mujoco.mjtGeom.mjGEOM_CAPSULE, 'sphere': mujoco.mjtGeom.mjGEOM_SPHERE,
             'ellipsoid': mujoco.mjtGeom.mjGEOM_ELLIPSOID, 'plane': mujoco.mjtGeom.mjGEOM_PLANE,
             'mesh': mujoco.mjtGeom.mjGEOM_MESH}
    size = np.asarray(shape.size, dtype=float)
    T = np.asarray(frame, dtype=float) @ np.asarray(shape.pose, dtype=float)
    if shape.kind == 'box':
        sizes = [size / 2.0]
    elif shape.kind in ('cylinder', 'capsule'):
        sizes = [[size[0], size[1] / 2.0, 0.0]]
    elif shape.kind == 'sphere':
        sizes = [[size[0], 0.0, 0.0]]
    elif shape.kind == 'ellipsoid':
        sizes = [size]
    elif shape.kind == 'plane':
        T[:3, :3] = T[:3, :3] @ _z_to(size[:3])
        sizes = [[size[3] / 2.0, size[4] / 2.0, 0.5]]
    else:
        try:
            if collision:
                meshes = _mesh_parts(spec, shape, name, messages)
            else:
                notes = []
                meshes = [add_mesh_asset(spec, shape.path, shape.size, notes)]
                messages.extend(f'{name}: {note}' for note in notes)
        except ValueError as exc:
            messages.append(f'{name}: {exc}: skipped')
            return []
        sizes = [None] * len(meshes)
    geoms = []
    for index, geom_size in enumerate(sizes):
        suffix = f'#{index}' if len(sizes) > 1 else ''
        geom = body.add_geom(name=f'{name}{suffix}', type=kinds[shape.kind])
        if geom_size is not None:
            geom.size = geom_size
        else:
            geom.meshname = meshes[index].name
        _place(geom, T)
        geoms.append(geom)
    return geoms


def make_world_spec(physics_step=0.001, gravity=(0.0, 0.0, -9.81)):
    """
    Return the spec of the empty world: ground plane, light, sky.

    The ground plane is the geom ``ground_plane`` in a static body of the same name.

    :param physics_step: physics time step in seconds (> 0).
    :param gravity: m/s^2 in the world frame (3 floats).
    :returns: a ``mujoco.MjSpec`` (integrator ``implicitfast``, elliptic friction cones).
    :raises ValueError: when ``physics_step`` is not a positive number.
    """
    if not physics_step > 0:
        raise ValueError(f'physics_step must be > 0 s, found {physics_step!r}')
    spec = mujoco.MjSpec()
    spec.modelname = 'empty_world'
    spec.option.timestep = float(physics_step)
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.gravity = [float(g) for g in gravity]
    # elliptic friction cones: isotropic Coulomb friction at the wheel contacts. MuJoCo's
    # default pyramidal cones resist the sideways slip of a skid-steer turn far more than
    # Coulomb friction does (measured: 0.3x the rotation rate); see docs/simulation.md
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    # MuJoCo's sleeping: a world model at rest (a loose box in warehouse.sdf) leaves the
    # dynamics and the contact solver until something touches it; robots never sleep
    # (add_robot). Measured: one robot in warehouse.sdf 19.6 -> 8.9 us per mj_step (the three
    # resting boxes' twelve contacts), docs/worlds.md
    spec.option.enableflags |= mujoco.mjtEnableBit.mjENBL_SLEEP
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.add_texture(name='skybox', type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
                     builtin=mujoco.mjtBuiltin.mjBUILTIN_GRADIENT,
                     rgb1=[0.6, 0.8, 1.0], rgb2=[0.1, 0.15, 0.25], width=64, height=64)
    spec.add_texture(name='grid', type=mujoco.mjtTexture.mjTEXTURE_2D,
                     builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
                     rgb1=[0.35, 0.35, 0.38], rgb2=[0.45, 0.45, 0.48], width=256, height=256)
    grid = spec.add_material(name='grid', texrepeat=[2, 2], reflectance=0.1)
    grid.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = 'grid'
    # the ground plane in a static body of its own: a robot link with an explicit ground
    # contact pair (its friction reference) excludes its dynamic contact with this body
    # only, and still collides with the world body's walls and shelves
    spec.worldbody.add_body(name=GROUND_BODY).add_geom(
        name='ground_plane', type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05],
        friction=list(GROUND_FRICTION), material='grid', group=0)
    spec.worldbody.add_light(name='sun', pos=[0, 0, 10], dir=[0.3, 0.2, -1],
                             type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL,
                             diffuse=[0.8, 0.8, 0.8], castshadow=True)
    return spec


def add_world(spec, world):
    """
    Add the models of an SDF world to a world spec.

    :param spec: the ``mujoco.MjSpec`` of :func:`make_world_spec`;
        its ``ground_plane`` becomes the SDF world's ground, or is deleted when the SDF
        world has none (see the module docstring).
    :param world: a :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :returns: one-line messages about shapes that could not be built (a mesh trimesh cannot
        read); those shapes are left out.
    """
    messages = []
    ground_done = False
    ground = spec.geom('ground_plane')
    large = large_static_links(world)
    for model in world.models:
        for link in model.links:
            name = f'{model.name}{SEPARATOR}{link.name}'
            T = np.asarray(model.pose, dtype=float) @ np.asarray(link.pose, dtype=float)
            # a static link's geoms go to the world body: MuJoCo then never tests them
            # against each other nor keeps a body per link (measured: docs/worlds.md);
            # a large one gets a static body of its own (see large_static_links)
            body, frame = spec.worldbody, T
            if name in large:
                body = spec.worldbody.add_body(name=name)
            if not model.static:
                body, frame = spec.worldbody.add_body(name=name), np.eye(4)
                _place(body, T)
                body.add_freejoint(name=name)
                body.explicitinertial = True
                body.mass = float(link.mass)
                ixx, iyy, izz, ixy, ixz, iyz = link.inertia
                rotation = np.asarray(link.inertial_pose, dtype=float)[:3, :3]
                tensor = rotation @ np.array([[ixx, ixy, ixz], [ixy, iyy, iyz],
                                              [ixz, iyz, izz]]) @ rotation.T
                body.ipos = np.asarray(link.inertial_pose, dtype=float)[:3, 3]
                body.fullinertia = [tensor[0, 0], tensor[1, 1], tensor[2, 2],
                                    tensor[0, 1], tensor[0, 2], tensor[1, 2]]
            drawn = {}  # collision shape key -> its geoms, for visuals of the same shape
            for shape in link.collisions:
                where = f'{name}{SEPARATOR}{shape.name}'
                if shape.kind == 'plane' and model.static and not ground_done and \
                        _faces_up(T @ shape.pose, shape.size):
                    ground_done = True
                    _ground(spec, shape)
                    continue
                geoms = _add_shape(spec, body, shape, where, True, frame, messages)
                for geom in geoms:
                    geom.group = COLLISION_GROUP
                    geom.rgba = DEFAULT_RGBA
                    _friction(geom, shape.friction)
                drawn.setdefault(_key(shape), geoms)
            for shape in link.visuals:
                if shape.kind == 'plane' and model.static and ground_done:
                    continue  # the ground is drawn with the empty world's grid
                same = drawn.pop(_key(shape), None)
                if same is not None:  # the collision geom shows it: one geom less per step
                    for geom in same:
                        geom.group = VISUAL_GROUP
                        geom.rgba = shape.rgba or DEFAULT_RGBA
                    continue
                where = f'{name}{SEPARATOR}visual{SEPARATOR}{shape.name}'
                geoms = _add_shape(spec, body, shape, where, False, frame, messages)
                for geom in geoms:
                    geom.group = VISUAL_GROUP
                    geom.contype = geom.conaffinity = 0
                    geom.mass = 0.0
                    geom.rgba = shape.rgba or DEFAULT_RGBA
            if link.missing_visuals and not link.visuals:
                for geoms in drawn.values():  # its visual meshes are missing: show what it is
                    for geom in geoms:
                        geom.group = VISUAL_GROUP
    if not ground_done and ground is not None:
        # a world without a ground: robots fall, as in Gazebo
        spec.delete(spec.body(GROUND_BODY))
    return messages


def large_static_links(world):
    """
    Return the static links with a collision shape spanning over half the static world.

    MuJoCo tests every moving body against the world body's geoms through one bounding
    volume tree; a shape that long (the walls around a hall) makes the tree's boxes cover
    most of the world, so every robot link descends deep into it every step. In a static
    body of its own, the link is passed over by MuJoCo's sweep-and-prune broadphase unless
    a moving body is near it (measured in warehouse.sdf: docs/worlds.md).

    :param world: a :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :returns: set of ``'<model>::<link>'`` names; spans are compared along x and y, over the
        primitive collision shapes of static models (planes and meshes are not measured).
    """
    spans = {}
    for model in world.models:
        if not model.static:
            continue
        for link in model.links:
            T = np.asarray(model.pose, dtype=float) @ np.asarray(link.pose, dtype=float)
            for shape in link.collisions:
                bounds = shape_bounds(shape, T)
                if bounds is not None:
                    spans.setdefault(f'{model.name}{SEPARATOR}{link.name}', []).append(bounds)
    if not spans:
        return set()
    every = [b for bounds in spans.values() for b in bounds]
    extent = np.max([b[1] for b in every], axis=0) - np.min([b[0] for b in every], axis=0)
    return {name for name, bounds in spans.items()
            if any(np.any((high - low)[:2] > LARGE_SHARE * extent[:2]) for low, high in bounds)}


def _key(shape):
    """Return what makes two shapes the same geometry at the same place (a dict key)."""
    return (shape.kind, tuple(np.round(shape.size, 9)), shape.path,
            tuple(np.round(np.asarray(shape.pose, dtype=float).ravel(), 9)))


def _faces_up(T, size):
    normal = np.asarray(T[:3, :3], dtype=float) @ (np.asarray(size[:3]) / np.linalg.norm(
        size[:3]))
    return normal[2] > 0.999 and abs(T[2, 3]) < 1e-9


def _ground(spec, shape):
    """Make ``shape`` the world's ``ground_plane`` (infinite, the empty world's look)."""
    _friction(spec.geom('ground_plane'), shape.friction)


def _friction(geom, mu):
    """Set a world collision geom's friction from SDF's ``min(mu, mu2)`` (module docstring)."""
    friction = list(GROUND_FRICTION)
    if mu is not None and mu < 1.0:
        friction[0] = mu
        geom.priority = 1
    geom.friction = friction
