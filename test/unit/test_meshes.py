# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Mesh files made usable (core/description/meshes.py): closed-form shapes, every bad kind."""

from amr_description.core.description import meshes
from amr_description.core.description.meshes import clean_triangles
from amr_description.core.description.meshes import decimate
from amr_description.core.description.meshes import solid
from amr_description.core.description.meshes import split_parts
from amr_description.core.description.meshes import usable_mesh
import numpy as np
import pytest
import trimesh

QUAD = (np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 1.0], [0.0, 0.0, 1.0]]),
        np.array([[0, 1, 2], [0, 2, 3]]))


def test_ascii_stl_is_read(tmp_path):
    """Read an ASCII STL (MuJoCo reads binary ones only): a unit cube: 8 vertices, 12 triangles."""
    path = tmp_path / 'cube.stl'
    trimesh.creation.box((1.0, 1.0, 1.0)).export(str(path), file_type='stl_ascii')
    assert path.read_text().startswith('solid')
    mesh = usable_mesh(str(path))
    assert mesh.vertices.shape == (8, 3) and mesh.faces.shape == (12, 3) and mesh.notes == []
    assert np.allclose(np.ptp(mesh.vertices, axis=0), 1.0)


def test_scale_applies_and_a_mirror_keeps_faces_outward(tmp_path):
    path = tmp_path / 'cube.stl'
    trimesh.creation.box((1.0, 1.0, 1.0)).export(str(path))
    mesh = usable_mesh(str(path), (2.0, -1.0, 0.5))
    assert np.allclose(np.ptp(mesh.vertices, axis=0), (2.0, 1.0, 0.5))
    assert trimesh.Trimesh(mesh.vertices, mesh.faces).volume == pytest.approx(1.0)  # outward
    with pytest.raises(ValueError, match='scale 1.0 0.0 1.0 is not usable'):
        usable_mesh(str(path), (1.0, 0.0, 1.0))


def test_non_finite_vertex_leaves_its_triangles_out():
    box = trimesh.creation.box((1.0, 1.0, 1.0))
    vertices = box.vertices.copy()
    vertices[0] = np.nan
    touching = int((box.faces == 0).any(axis=1).sum())
    v, f, notes = clean_triangles(vertices, box.faces, "'x.obj'")
    assert len(f) == 12 - touching and np.isfinite(v).all()
    assert notes == [f"'x.obj': {touching} triangle(s) with a non-finite vertex left out"]
    vertices[:] = np.inf
    with pytest.raises(ValueError, match="'x.obj': no triangle with finite vertices"):
        clean_triangles(vertices, box.faces, "'x.obj'")


def test_flat_quad_gets_the_thin_thickness_along_its_normal():
    vertices, faces, notes = solid(*QUAD, "'wall.dae'")
    assert np.ptp(vertices, axis=0) == pytest.approx((2.0, meshes.THIN, 1.0))
    assert len(faces) == 4 and 'flat (all vertices in one plane)' in notes[0]
    hull = trimesh.Trimesh(vertices, faces).convex_hull
    assert hull.volume == pytest.approx(2.0 * meshes.THIN)  # a 2 m x 1 m x THIN slab


def test_one_triangle_is_flat_and_a_line_is_refused():
    vertices, faces, _ = solid(QUAD[0][:3], QUAD[1][:1], "'tri.obj'")
    assert len(vertices) == 6 and len(faces) == 2
    line = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 1e-9, 0.0]])
    with pytest.raises(ValueError, match="'line.obj': its vertices lie on one line"):
        solid(line, np.array([[0, 1, 2], [1, 2, 3]]), "'line.obj'")


def test_zero_area_triangles_only_is_refused():
    line = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match='every triangle has zero area'):
        clean_triangles(line, np.array([[0, 1, 2]]), "'line.obj'")


def test_a_solid_is_kept_as_it_is():
    box = trimesh.creation.box((1.0, 2.0, 3.0))
    vertices, faces, notes = solid(box.vertices, box.faces, "'box.stl'")
    assert vertices is box.vertices and notes == []


def test_decimation_to_the_budget_keeps_the_shape():
    sphere = trimesh.creation.icosphere(subdivisions=4, radius=1.0)  # 5,120 triangles
    vertices, faces, notes = decimate(sphere.vertices, sphere.faces, "'ball.stl'", 1000)
    assert 900 <= len(faces) <= 1000, len(faces)
    assert notes == [f"'ball.stl': 5120 triangles, over 1000: decimated to {len(faces)}"]
    radii = np.linalg.norm(vertices, axis=1)
    assert np.abs(radii - 1.0).max() < 0.02  # still the unit sphere, within 2 cm
    same = decimate(sphere.vertices, sphere.faces, "'ball.stl'", 6000)
    assert same[1] is sphere.faces and same[2] == []


def test_parts_are_split_only_between_two_and_the_limit():
    a = trimesh.creation.box((1.0, 1.0, 1.0))
    b = a.copy()
    b.apply_translation((5.0, 0.0, 0.0))
    two = trimesh.util.concatenate([a, b])
    parts = split_parts(two.faces, len(two.vertices), 64)
    assert sorted(len(p) for p in parts) == [12, 12]
    assert split_parts(a.faces, len(a.vertices), 64) is None
    many = trimesh.util.concatenate([a.copy().apply_translation((3.0 * i, 0, 0))
                                     for i in range(5)])
    assert split_parts(many.faces, len(many.vertices), 4) is None


def test_unreadable_file_is_one_line(tmp_path):
    path = tmp_path / 'bad.stl'
    path.write_bytes(b'\x00\x01 not a mesh')
    with pytest.raises(ValueError) as info:
        usable_mesh(str(path))
    assert str(path) in str(info.value) and '\n' not in str(info.value)
    with pytest.raises(ValueError, match='cannot read .*No such file'):
        usable_mesh(str(tmp_path / 'none.stl'))
