# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Mesh files made usable by a physics engine: read, cleaned, bounded, given a volume (no rclpy).

Gazebo loads every mesh format its asset importer reads and keeps going past a bad one; MuJoCo
reads binary STL and OBJ only, at most 200,000 faces per STL file, and refuses the whole model
for one mesh with a non-finite vertex, fewer than 4 vertices, or all its vertices in one plane
("coplanar vertices, cannot compute convex hull", "mesh volume is too small"). This module
turns any file trimesh reads into triangles MuJoCo accepts, and says in one line what it
changed:

- triangles with a non-finite vertex, and triangles of zero area, are left out;
- a mesh over :data:`MAX_FACES` triangles is decimated to that many (quadric decimation,
  trimesh's ``simplify_quadric_decimation`` with the fast-simplification package);
- a flat mesh (all vertices within :data:`FLAT_TOLERANCE` of one plane, a wall or a floor
  tile made of one quad) gets :data:`THIN` of thickness along its normal: a thin shape, not
  the empty hull of a plane;
- a mesh whose vertices lie on one line or one point cannot be used (:class:`ValueError`).

Units: the file's units times the ``scale`` of the URDF ``<mesh>`` / SDF ``<mesh><scale>``
(metres for the usual files).
"""

import dataclasses
import functools
import os
import time

import numpy as np

MAX_FACES = 200000
"""Triangle budget of one mesh: MuJoCo's limit for an STL file, kept for every format (more
costs seconds at every load and buys nothing in a robot's contacts)."""

THIN = 0.01
"""Thickness in metres given to a flat mesh (a plane-like wall or tile)."""

FLAT_TOLERANCE = 1e-6
"""A mesh is flat when its extent across its best-fit plane is below this many metres (or
this fraction of its largest extent, for large meshes)."""

SLOW = 2.0
"""Seconds of preparation above which a line says what took long."""


@dataclasses.dataclass
class Mesh:
    """
    Triangles ready for a physics engine.

    :ivar vertices: ``(N, 3)`` float array, metres (scale applied).
    :ivar faces: ``(M, 3)`` int array of vertex indices, counter-clockwise seen from outside.
    :ivar notes: one-line remarks on what was changed (left-out triangles, decimation,
        thickening, time taken), each naming the file; empty for a clean mesh.
    """

    vertices: np.ndarray
    faces: np.ndarray
    notes: list = dataclasses.field(default_factory=list)


def read_triangles(path):
    """
    Return the triangles of any mesh file trimesh reads (STL binary or ASCII, OBJ, COLLADA...).

    The parts of a scene are joined in one mesh in the file's frame; nothing is merged or
    left out (see :func:`clean_triangles` and :func:`merge_vertices`).

    :param path: mesh file path.
    :returns: ``(vertices (N, 3) float, faces (M, 3) int)``.
    :raises ValueError: one line naming the file when it cannot be read or holds no triangle.
    """
    import trimesh
    try:
        mesh = trimesh.load(path, force='mesh', process=False)
    except Exception as exc:  # noqa: B902 - trimesh raises many types; one line for all
        raise ValueError(f'cannot read {path!r}: {exc}'.splitlines()[0]) from None
    faces = np.asarray(getattr(mesh, 'faces', np.zeros((0, 3))), dtype=np.int64)
    if not len(faces):
        raise ValueError(f'{path!r} holds no triangle')
    return np.asarray(mesh.vertices, dtype=float), faces.reshape(-1, 3)


def clean_triangles(vertices, faces, label):
    """
    Leave out triangles with a non-finite vertex and triangles of zero area.

    :param vertices: ``(N, 3)`` floats.
    :param faces: ``(M, 3)`` ints.
    :param label: how the notes name the mesh (its file).
    :returns: ``(vertices, faces, notes)``; unused vertices are kept (engines ignore them).
    :raises ValueError: when no triangle is left.
    """
    notes = []
    finite = np.isfinite(vertices).all(axis=1)
    bad = ~finite[faces].all(axis=1)
    if bad.any():
        notes.append(f'{label}: {int(bad.sum())} triangle(s) with a non-finite vertex left out')
        faces = faces[~bad]
    if len(faces):
        safe = np.where(finite[:, None], vertices, 0.0)
        a, b, c = safe[faces[:, 0]], safe[faces[:, 1]], safe[faces[:, 2]]
        area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
        zero = area <= 1e-12 * max(1.0, float(np.abs(safe).max()) ** 2)
        if zero.all():
            raise ValueError(f'{label}: every triangle has zero area')
        faces = faces[~zero]
    if not len(faces):
        raise ValueError(f'{label}: no triangle with finite vertices')
    vertices = np.where(finite[:, None], vertices, 0.0)
    return vertices, faces, notes


def merge_vertices(vertices, faces):
    """
    Return ``(vertices, faces)`` with coincident vertices merged (trimesh's ``process``).

    An STL file stores each triangle's corners apart; merged, the triangles of one surface
    share vertices, so connected parts can be told apart (:func:`split_parts`).
    """
    import trimesh
    mesh = trimesh.Trimesh(vertices, faces, process=True)
    return np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64)


def decimate(vertices, faces, label, max_faces=MAX_FACES):
    """
    Return ``(vertices, faces, notes)`` with at most ``max_faces`` triangles.

    Quadric decimation (trimesh's ``simplify_quadric_decimation``, fast-simplification).

    :param label: how the note names the mesh.
    """
    if len(faces) <= max_faces:
        return vertices, faces, []
    import trimesh
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    try:
        smaller = mesh.simplify_quadric_decimation(face_count=max_faces)
    except Exception as exc:  # noqa: B902 - an optional package; keep the mesh, say why
        return vertices, faces, [f'{label}: {len(faces)} triangles, over {max_faces}, kept '
                                 f'(decimation failed: {exc})'.splitlines()[0]]
    note = (f'{label}: {len(faces)} triangles, over {max_faces}: decimated to '
            f'{len(smaller.faces)}')
    return np.asarray(smaller.vertices, float), np.asarray(smaller.faces, np.int64), [note]


def principal_extents(vertices):
    """
    Return ``(centre (3,), axes (3, 3) rows, extents (3,))`` of points along their principal axes.

    Extents are the points' spans along the rows of ``axes``, largest first (SVD of the
    centred points).
    """
    points = np.asarray(vertices, dtype=float)
    centre = points.mean(axis=0)
    _, _, axes = np.linalg.svd(points - centre, full_matrices=False)
    along = (points - centre) @ axes.T
    return centre, axes, along.max(axis=0) - along.min(axis=0)


def solid(vertices, faces, label, thin=THIN):
    """
    Give a flat set of triangles a thickness ``thin`` along its normal; keep any other.

    :param vertices: ``(N, 3)`` floats (only the vertices ``faces`` uses are considered).
    :param faces: ``(M, 3)`` ints.
    :param label: how the note or the error names the mesh.
    :returns: ``(vertices, faces, notes)``.
    :raises ValueError: when the triangles' vertices lie on one line or at one point.
    """
    used = np.unique(faces)
    _, axes, extents = principal_extents(vertices[used])
    tolerance = max(FLAT_TOLERANCE, FLAT_TOLERANCE * float(extents[0]))
    if extents[1] <= tolerance:
        raise ValueError(f'{label}: its vertices lie on one line (no area, no volume)')
    if extents[2] > tolerance:
        return vertices, faces, []
    normal = axes[2]
    count = len(vertices)
    both = np.concatenate([vertices + normal * thin / 2.0, vertices - normal * thin / 2.0])
    faces = np.concatenate([faces, faces[:, ::-1] + count])
    return both, faces, [f'{label}: flat (all vertices in one plane): given a thickness of '
                         f'{thin} m']


def split_parts(faces, vertex_count, max_parts):
    """
    Return the connected parts of a mesh as lists of face indices, or None when too many.

    Parts share no vertex (scipy's connected components of the vertex graph, cheap for a
    million triangles); only when ``1 < parts <= max_parts`` are they listed.

    :returns: None (one part, or more than ``max_parts``) or a list of index arrays.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]]])
    graph = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])),
                       shape=(vertex_count, vertex_count))
    count, labels = connected_components(graph, directed=False)
    face_labels = labels[faces[:, 0]]
    present = np.unique(face_labels)
    if not 1 < len(present) <= max_parts:
        return None
    return [np.flatnonzero(face_labels == label) for label in present]


def apply_scale(vertices, faces, scale):
    """
    Scale vertices by ``scale`` (None, a number or 3 numbers); a mirror keeps faces outward.

    :raises ValueError: when a scale factor is zero or not finite.
    """
    if scale is None:
        return vertices, faces
    factors = np.broadcast_to(np.asarray(scale, dtype=float), (3,))
    if not np.isfinite(factors).all() or (factors == 0).any():
        raise ValueError(f'scale {" ".join(repr(float(f)) for f in factors)} is not usable '
                         '(expected finite, non-zero factors)')
    if np.prod(factors) < 0:
        faces = faces[:, ::-1]
    return vertices * factors, faces


@functools.lru_cache(maxsize=64)
def _prepared(path, stamp, scale):
    """Prepare a file as :func:`prepare_mesh` says, once per ``stamp`` (size, mtime)."""
    start = time.monotonic()
    label = repr(path)
    vertices, faces = read_triangles(path)
    vertices, faces, notes = clean_triangles(vertices, faces, label)
    vertices, faces = merge_vertices(vertices, faces)
    vertices, faces = apply_scale(vertices, faces, scale)
    vertices, faces, more = decimate(vertices, faces, label)
    notes += more
    took = time.monotonic() - start
    if took > SLOW:
        notes.append(f'{label}: {len(faces)} triangles took {took:.1f} s to read and prepare')
    return vertices, faces, tuple(notes)


def prepare_mesh(path, scale=None):
    """
    Read a mesh file into triangles an engine accepts (see the module docstring).

    Flatness is not handled here (a collision mesh is split into parts first, each made
    :func:`solid`); results are cached per file, modification time and scale.

    :param path: an existing mesh file.
    :param scale: None, a number or 3 numbers.
    :returns: :class:`Mesh` (its arrays are shared with the cache: do not modify them).
    :raises ValueError: one line naming the file: unreadable, no usable triangle, bad scale.
    """
    try:
        info = os.stat(path)
    except OSError as exc:
        raise ValueError(f'cannot read {path!r}: {exc.strerror}') from None
    key = None if scale is None else tuple(np.broadcast_to(np.asarray(scale, float), (3,)))
    vertices, faces, notes = _prepared(os.path.abspath(path), (info.st_size, info.st_mtime_ns),
                                       key)
    return Mesh(vertices, faces, list(notes))


def usable_mesh(path, scale=None):
    """
    Return a :class:`Mesh` of a file, flat ones thickened: one engine mesh for the file.

    :raises ValueError: as :func:`prepare_mesh`, or its vertices lie on one line.
    """
    mesh = prepare_mesh(path, scale)
    vertices, faces, notes = solid(mesh.vertices, mesh.faces, repr(os.path.abspath(path)))
    return Mesh(vertices, faces, mesh.notes + notes)
