# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
World: the SDF world's geometry under the robots (Gazebo's scene; RViz has no peer).

The viewer's ``world`` parameter names the world the simulator loaded (the stacks pass the
same ``world:=`` to both; '' or ``empty`` draws nothing but the grid). Every model's visuals
(its collisions where a link has no visual) become one triangle mesh with per-face colours,
one scene node, built once. The ground plane is left out (the grid stands for it). Models
are drawn at their initial poses (a loose box pushed in the simulation is not followed).
The world frame is ``world``; when TF has no such frame the world is drawn in the fixed
frame, as the Odometry trails of frame ``world`` are.
"""

from amr_description.web.displays.base import Display
from amr_description.web.robot_scene import wxyz_position
import numpy as np


def shape_mesh(shape, sections=24):
    """
    Return the trimesh of one SDF shape in its link frame (a plane: None).

    :param shape: :class:`~amr_description.core.sdf_world.Shape`.
    :raises ValueError: one line when a mesh file cannot be read.
    """
    import trimesh
    size = shape.size
    if shape.kind == 'box':
        mesh = trimesh.creation.box(extents=size)
    elif shape.kind == 'cylinder':
        mesh = trimesh.creation.cylinder(radius=size[0], height=size[1], sections=sections)
    elif shape.kind == 'capsule':
        mesh = trimesh.creation.capsule(radius=size[0], height=size[1], count=[sections, 8])
    elif shape.kind == 'sphere':
        mesh = trimesh.creation.icosphere(subdivisions=2, radius=size[0])
    elif shape.kind == 'ellipsoid':
        mesh = trimesh.creation.icosphere(subdivisions=2, radius=1.0)
        mesh.apply_scale(size)
    elif shape.kind == 'mesh':
        try:
            mesh = trimesh.load(shape.path, force='mesh')
        except Exception as exc:  # noqa: B902 - trimesh raises many kinds
            raise ValueError(f'mesh {shape.path!r}: cannot load ({exc})'.splitlines()[0]) \
                from None
        mesh.apply_scale(size)
    else:
        return None
    mesh.apply_transform(shape.pose)
    return mesh


def world_mesh(world):
    """
    Return the world's static geometry as one mesh and its face colours.

    :param world: :class:`~amr_description.core.sdf_world.World`.
    :returns: ``(vertices (V, 3) float32, faces (F, 3) uint32, colours (F, 3) uint8,
        problems)``; problems are one-line messages of shapes left out. Empty arrays when
        the world has nothing but a ground plane.
    """
    import trimesh
    parts, colours, problems = [], [], []
    for model in world.models:
        for link in model.links:
            T = np.asarray(model.pose) @ np.asarray(link.pose)
            for shape in link.visuals or link.collisions:
                try:
                    mesh = shape_mesh(shape)
                except ValueError as exc:
                    problems.append(f'model {model.name!r}: {exc}')
                    continue
                if mesh is None:
                    continue
                mesh.apply_transform(T)
                rgb = np.round(255 * np.asarray(shape.rgba or (0.7, 0.7, 0.7, 1.0))[:3])
                parts.append(mesh)
                colours.append(np.tile(rgb.astype(np.uint8), (len(mesh.faces), 1)))
    if not parts:
        return (np.zeros((0, 3), np.float32), np.zeros((0, 3), np.uint32),
                np.zeros((0, 3), np.uint8), problems)
    mesh = trimesh.util.concatenate(parts)
    return (np.asarray(mesh.vertices, dtype=np.float32), np.asarray(mesh.faces, np.uint32),
            np.concatenate(colours), problems)


class WorldDisplay(Display):
    """
    The world's geometry, one mesh node under ``/world``.

    :param world_value: the viewer's ``world`` parameter (a shipped name, a file, a URI).
    :ivar error: the one-line error of a world that could not be read, or ''.
    :ivar faces: number of triangles drawn.
    """

    def __init__(self, node, server, frames, world_value):
        """Read the world and build its mesh (once); an unreadable world is an error line."""
        super().__init__(node, server, frames)
        from amr_description.core.sdf_world import load_world
        from amr_description.core.sdf_world import WorldError
        self.error = ''
        self.faces = 0
        self.name = ''
        self._node = None
        self._pose = None
        value = str(world_value or '').strip()
        if value in ('', 'empty'):
            return
        log = node.get_logger()
        try:
            world = load_world(value)
        except WorldError as exc:
            self.error = str(exc)
            log.error(self.error)
            return
        self.name = world.name
        vertices, faces, colours, problems = world_mesh(world)
        for problem in problems:
            log.warning(problem)
        self.faces = len(faces)
        if not len(faces):
            return
        import trimesh
        mesh = trimesh.Trimesh(vertices, faces, process=False)
        mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=colours)
        self._node = server.scene.add_mesh_trimesh('/world', mesh)
        log.info(f'world {world.name!r}: {len(world.models)} models, {self.faces} triangles')

    def draw(self, context):
        """Place the world at the pose of frame ``world`` in the fixed frame (else identity)."""
        if self._node is None:
            return
        T = context.pose('world')
        if T is None:
            T = np.eye(4)
        if self._pose is None or not np.allclose(self._pose, T, atol=1e-6):
            self._node.wxyz, self._node.position = wxyz_position(T)
            self._pose = T
