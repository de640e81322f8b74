# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The plain data an SDF world is read into, and the readers of its small elements.

:class:`World` holds :class:`Model` s of :class:`Link` s of :class:`Shape` s (the world's
frame, SI units, REP 103 axes); :func:`pose_matrix` reads a ``<pose>`` (SDFormat 1.7+ pose
semantics, see :mod:`amr_description.core.gazebo.sdf_world`, which reads whole files).
What cannot be used raises :class:`PartError`, one line naming the element.
"""

from dataclasses import dataclass
from dataclasses import field
import math
import os

from amr_description.core.geodesy import SphericalCoordinates
from amr_description.core.kinematics import quaternion_to_matrix
from amr_description.core.kinematics import rpy_to_matrix
import numpy as np

SDF_GRAVITY = (0.0, 0.0, -9.8)
"""SDF's default ``<world><gravity>`` (m/s^2)."""

MAX_SIZE = 1e5
"""Largest size of a shape in metres (100 km: larger ones overflow the renderer's and the
simulator's arithmetic)."""

SHAPES = ('box', 'cylinder', 'sphere', 'capsule', 'ellipsoid', 'plane', 'mesh')
"""SDF geometries simulated; the others (cone, heightmap, polyline, image) are reported."""


class PartError(ValueError):
    """One model (or one shape, one element) that cannot be used: its one-line reason."""


@dataclass
class Shape:
    """
    One ``<collision>`` or ``<visual>`` of a link.

    :param name: its SDF name.
    :param kind: one of :data:`SHAPES`.
    :param size: box ``(x, y, z)`` full lengths; cylinder and capsule ``(radius, length)``;
        sphere ``(radius,)``; ellipsoid ``(a, b, c)`` radii; plane ``(nx, ny, nz, sx, sy)``
        normal and size; mesh ``(sx, sy, sz)`` scale. Metres.
    :param pose: pose in the link frame, shape (4, 4).
    :param path: the mesh file (resolved path), '' for primitives.
    :param rgba: visual colour (4 floats in 0..1) or None (unset).
    :param friction: ``min(mu, mu2)`` of ``<surface><friction><ode>``, or None (unset).
    """

    name: str
    kind: str
    size: tuple
    pose: np.ndarray
    path: str = ''
    rgba: tuple = None
    friction: float = None


def shape_bounds(shape, T):
    """
    Return the axis-aligned bounds of a primitive shape posed at ``T @ shape.pose``.

    The shape's own bounding box (box: its half sizes; cylinder ``(r, r, l/2)``; capsule
    ``(r, r, l/2 + r)``; sphere ``(r, r, r)``; ellipsoid its radii) has its 8 corners moved
    by the pose; their smallest and largest coordinates are the bounds.

    :param shape: a :class:`Shape`.
    :param T: the pose of the shape's link in the world frame, shape (4, 4).
    :returns: ``(low, high)``, two arrays of shape (3,) in metres in the world frame, or
        None for a plane (infinite) or a mesh (its size is known once the file is read).
    """
    size = np.asarray(shape.size, dtype=float)
    if shape.kind == 'box':
        half = size / 2.0
    elif shape.kind == 'cylinder':
        half = np.array([size[0], size[0], size[1] / 2.0])
    elif shape.kind == 'capsule':
        half = np.array([size[0], size[0], size[1] / 2.0 + size[0]])
    elif shape.kind == 'sphere':
        half = np.full(3, size[0])
    elif shape.kind == 'ellipsoid':
        half = size[:3]
    else:
        return None
    pose = np.asarray(T, dtype=float) @ np.asarray(shape.pose, dtype=float)
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    corners = (signs * half) @ pose[:3, :3].T + pose[:3, 3]
    return corners.min(axis=0), corners.max(axis=0)


@dataclass
class Link:
    """
    One ``<link>``: pose in its model's frame (4, 4), inertial, shapes.

    :param mass: kg (SDF default 1).
    :param inertia: (ixx, iyy, izz, ixy, ixz, iyz) kg m^2 (SDF default 1, 1, 1, 0, 0, 0).
    :param inertial_pose: centre of mass frame in the link frame, shape (4, 4).
    :param missing_visuals: visuals left out (a mesh not found): with none left, the link's
        collisions are drawn instead.
    """

    name: str
    pose: np.ndarray
    mass: float = 1.0
    inertia: tuple = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)
    inertial_pose: np.ndarray = field(default_factory=lambda: np.eye(4))
    collisions: list = field(default_factory=list)
    visuals: list = field(default_factory=list)
    missing_visuals: int = 0


@dataclass
class Model:
    """
    One model of the world: its name, world pose (4, 4), ``static`` and links.

    Nested models are flattened: their links join the outer model, named ``inner::link``.
    """

    name: str
    pose: np.ndarray
    static: bool = False
    links: list = field(default_factory=list)
    relative_to: str = ''


@dataclass
class World:
    """
    A world read from SDF.

    :param name: ``<world name>`` (gz topics: ``/world/<name>/...``).
    :param physics_step: ``<physics><max_step_size>`` (s, SDF default 0.001).
    :param real_time_factor: ``<physics><real_time_factor>`` (SDF default 1).
    :param gravity: ``<gravity>`` (m/s^2, 3 floats; SDF default 0 0 -9.8).
    :param models: :class:`Model` list, in document order.
    :param source: the world file.
    :param messages: one-line warnings (models left out, shapes skipped, ...).
    :param not_simulated: names of ``<world>`` children not simulated (lights, gui, ...).
    :param spherical_coordinates: the world origin on the Earth
        (:class:`~amr_description.core.geodesy.SphericalCoordinates`), None without
        ``<spherical_coordinates>`` (navsat sensors then have nothing to report).
    """

    name: str = 'default'
    physics_step: float = 0.001
    real_time_factor: float = 1.0
    gravity: tuple = SDF_GRAVITY
    models: list = field(default_factory=list)
    source: str = ''
    messages: list = field(default_factory=list)
    not_simulated: list = field(default_factory=list)
    spherical_coordinates: SphericalCoordinates = None

    def model(self, name):
        """Return the model named ``name`` or None."""
        return next((m for m in self.models if m.name == name), None)


def sdf_floats(text, count, where):
    """Return ``count`` floats of a whitespace-separated text; raise :class:`PartError`."""
    try:
        values = tuple(float(v) for v in (text or '').split())
    except ValueError:
        raise PartError(f'{where}: expected {count} numbers, found {text!r}') from None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise PartError(f'{where}: expected {count} finite numbers, found {text!r}')
    return values


def child_text(element, tag, default=None):
    """Return the stripped text of ``element``'s child ``tag``, ``default`` when absent."""
    child = element.find(tag)
    return default if child is None or child.text is None else child.text.strip()


def child_number(element, tag, default, where):
    """Return the number in child ``tag`` (``default`` when absent); raise PartError."""
    text = child_text(element, tag)
    return default if text is None else sdf_floats(text, 1, f'{where} <{tag}>')[0]


def sdf_bool(text):
    """Return SDF's boolean of a text: ``true`` or ``1`` (any case) is True."""
    return (text or '').strip().lower() in ('true', '1')


def pose_matrix(element, where):
    """
    Return the 4x4 matrix of an SDF ``<pose>`` element (identity for None or empty text).

    :param element: the ``<pose>`` element or None.
    :param where: the element's place, for the error line.
    :raises ValueError: one line when the text is not 6 (or 7 with ``quat_xyzw``) numbers.
    """
    T = np.eye(4)
    if element is None or not (element.text or '').strip():
        return T
    if element.get('rotation_format', 'euler_rpy') == 'quat_xyzw':
        x, y, z, qx, qy, qz, qw = sdf_floats(element.text, 7, f'{where} <pose>')
        T[:3, :3] = quaternion_to_matrix((qx, qy, qz, qw))
    else:
        x, y, z, roll, pitch, yaw = sdf_floats(element.text, 6, f'{where} <pose>')
        if sdf_bool(element.get('degrees')):
            roll, pitch, yaw = (math.radians(v) for v in (roll, pitch, yaw))
        T[:3, :3] = rpy_to_matrix((roll, pitch, yaw))
    T[:3, 3] = (x, y, z)
    return T


def read_geometry(geometry, where, mesh_path):
    """
    Read an SDF ``<geometry>`` (its first child): one of :data:`SHAPES`.

    Sizes are SDF's with its defaults (``box`` size 1 1 1 m, ``cylinder``/``capsule`` radius
    0.5 m length 1 m, ``sphere`` radius 1 m, ``ellipsoid`` radii 1 1 1 m, ``plane`` normal
    0 0 1 and size 1 1 m, ``mesh`` scale 1 1 1).

    :param geometry: the ``<geometry>`` element or None.
    :param where: the element's place, for the error line.
    :param mesh_path: callable ``mesh_path(uri) -> file path`` resolving a mesh ``<uri>``.
    :returns: ``(kind, size tuple, mesh file path or '')``; a plane's size is its normal then
        its extent.
    :raises PartError: one line: no geometry, a kind not simulated, a bad or non-positive
        size, a mesh without ``<uri>`` or whose file is missing.
    """
    if geometry is None or not len(geometry):
        raise PartError(f'{where}: no <geometry>')
    kind_element = geometry[0]
    kind = kind_element.tag
    if kind not in SHAPES:
        raise PartError(f'{where}: <{kind}> geometry is not simulated')
    path = ''
    if kind == 'box':
        size = sdf_floats(child_text(kind_element, 'size', '1 1 1'), 3, f'{where} <box><size>')
    elif kind in ('cylinder', 'capsule'):
        size = (child_number(kind_element, 'radius', 0.5, f'{where} <{kind}>'),
                child_number(kind_element, 'length', 1.0, f'{where} <{kind}>'))
    elif kind == 'sphere':
        size = (child_number(kind_element, 'radius', 1.0, f'{where} <sphere>'),)
    elif kind == 'ellipsoid':
        size = sdf_floats(child_text(kind_element, 'radii', '1 1 1'), 3,
                          f'{where} <ellipsoid><radii>')
    elif kind == 'plane':
        normal = sdf_floats(child_text(kind_element, 'normal', '0 0 1'), 3,
                            f'{where} <plane><normal>')
        extent = sdf_floats(child_text(kind_element, 'size', '1 1'), 2,
                            f'{where} <plane><size>')
        if not np.linalg.norm(normal) > 0:
            raise PartError(f'{where} <plane><normal> must not be zero')
        size = tuple(normal) + tuple(extent)
    else:
        uri = child_text(kind_element, 'uri')
        if not uri:
            raise PartError(f'{where}: <mesh> without <uri>')
        path = mesh_path(uri)
        if not os.path.isfile(path):
            raise PartError(f'{where}: mesh {uri!r} not found ({path})')
        size = sdf_floats(child_text(kind_element, 'scale', '1 1 1'), 3,
                          f'{where} <mesh><scale>')
    checked = size[3:] if kind == 'plane' else size
    if not all(0 < v <= MAX_SIZE for v in checked):
        raise PartError(f'{where}: <{kind}> sizes must be > 0 and at most {MAX_SIZE:g}, found '
                        f'{" ".join(f"{v:g}" for v in checked)}')
    return kind, tuple(size), path
