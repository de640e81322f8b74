# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
World: the SDF world's geometry under the robots (Gazebo's scene; RViz has no peer).

The viewer's ``world`` parameter names the world the simulator loaded (the stacks pass the
same ``world:=`` to both; '' or ``empty`` draws nothing but the grid). Every model's visuals
(its collisions where a link has no visual) become one triangle mesh with per-face colours,
one scene node, built once, but for the links of non-static models (loose boxes): each is
its own node, moved to the pose the simulator publishes for it. The ground plane is left out
(the grid stands for it).
The world frame is ``world``; when TF has no such frame the world is drawn in the fixed
frame, as the Odometry trails of frame ``world`` are.
"""

import math

from amr_description.core.description.meshes import prepare_mesh
from amr_description.web.displays.base import Display
from amr_description.web.displays.base import moved
from amr_description.web.displays.base import POSE_TOLERANCE
from amr_description.web.robot_scene import wxyz_position
import numpy as np


def shape_mesh(shape, sections=24):
    """
    Return the trimesh of one SDF shape in its link frame (a plane: None).

    :param shape: :class:`~amr_description.core.gazebo.sdf_elements.Shape`.
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
    elif shape.kind == 'mesh':  # as the simulator reads it: cleaned, at most 200,000 triangles
        prepared = prepare_mesh(shape.path, size)  # ValueError: one line naming the file
        mesh = trimesh.Trimesh(prepared.vertices, prepared.faces, process=False)
    else:
        return None
    mesh.apply_transform(shape.pose)
    return mesh


def _link_mesh(link, T, problems, where):
    """Return ``(mesh, face colours)`` of one link's shapes posed by ``T``, or None."""
    import trimesh
    parts, colours = [], []
    for shape in link.visuals or link.collisions:
        try:
            mesh = shape_mesh(shape)
        except ValueError as exc:
            problems.append(f'model {where!r}: {exc}')
            continue
        if mesh is None:
            continue
        mesh.apply_transform(T)
        rgb = np.round(255 * np.asarray(shape.rgba or (0.7, 0.7, 0.7, 1.0))[:3])
        parts.append(mesh)
        colours.append(np.tile(rgb.astype(np.uint8), (len(mesh.faces), 1)))
    if not parts:
        return None
    return trimesh.util.concatenate(parts), np.concatenate(colours)


def world_mesh(world):
    """
    Return the world's static geometry as one mesh and its face colours.

    The links of non-static models are left out: :func:`moving_links` draws them.

    :param world: :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :returns: ``(vertices (V, 3) float32, faces (F, 3) uint32, colours (F, 3) uint8,
        problems)``; problems are one-line messages of shapes left out. Empty arrays when
        the world has nothing but a ground plane.
    """
    import trimesh
    parts, colours, problems = [], [], []
    for model in world.models:
        if not model.static:
            continue
        for link in model.links:
            T = np.asarray(model.pose) @ np.asarray(link.pose)
            found = _link_mesh(link, T, problems, model.name)
            if found is not None:
                parts.append(found[0])
                colours.append(found[1])
    if not parts:
        return (np.zeros((0, 3), np.float32), np.zeros((0, 3), np.uint32),
                np.zeros((0, 3), np.uint8), problems)
    mesh = trimesh.util.concatenate(parts)
    return (np.asarray(mesh.vertices, dtype=np.float32), np.asarray(mesh.faces, np.uint32),
            np.concatenate(colours), problems)


def moving_links(world):
    """
    Return the links of the world's non-static models, each a mesh in its own frame.

    :param world: :class:`~amr_description.core.gazebo.sdf_elements.World`.
    :returns: ``(links, problems)``: links a list of ``(frame, mesh, face colours (F, 3)
        uint8, initial pose (4, 4) in the world frame)`` with ``frame`` = ``<model>/<link>``
        (the child frame of :mod:`amr_description.sim.sensors.world_poses`).
    """
    links, problems = [], []
    for model in world.models:
        if model.static:
            continue
        for link in model.links:
            found = _link_mesh(link, np.eye(4), problems, model.name)
            if found is not None:
                T = np.asarray(model.pose) @ np.asarray(link.pose)
                links.append((f'{model.name}/{link.name}', found[0], found[1], T))
    return links, problems


class WorldDisplay(Display):
    """
    The world's geometry: its static models as one mesh node, each moving link as its own.

    The moving links (non-static models: boxes the robots push) follow the simulator's
    ``/world/<world>/dynamic_pose/info`` (``tf2_msgs/TFMessage``, frames ``<model>/<link>``
    in frame ``world``, :mod:`amr_description.sim.sensors.world_poses`); before the first
    message they stand at their initial poses.

    :param world_value: the viewer's ``world`` parameter (a shipped name, a file, a URI).
    :ivar error: the one-line error of a world that could not be read, or ''.
    :ivar faces: number of triangles drawn.
    :ivar topic: the moving links' pose topic, '' without moving links.
    """

    order = 10
    parameters = (('world', ''),)

    @classmethod
    def create(cls, viewer, settings):
        """Make the display of the viewer's ``world``."""
        return cls(viewer, viewer.server, viewer.frames, settings['world'])

    def __init__(self, node, server, frames, world_value):
        """Read the world and build its meshes (once); an unreadable world is an error line."""
        super().__init__(node, server, frames)
        from amr_description.core.gazebo.sdf_world import load_world
        from amr_description.core.gazebo.sdf_world import WorldError
        self.error = ''
        self.faces = 0
        self.name = ''
        self.topic = ''
        self._node = None
        self._pose = None
        self._links = []  # [frame, scene node, initial pose, last pose sent]
        self._poses = {}  # frame -> (4, 4) in the world frame, from the topic
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
        links, more = moving_links(world)
        for problem in problems + more:
            log.warning(problem)
        self.faces = len(faces) + sum(len(mesh.faces) for _, mesh, _, _ in links)
        import trimesh
        if len(faces):
            mesh = trimesh.Trimesh(vertices, faces, process=False)
            mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=colours)
            self._node = server.scene.add_mesh_trimesh('/world', mesh)
        for index, (frame, mesh, colours, T) in enumerate(links):
            mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=colours)
            scene_node = server.scene.add_mesh_trimesh(f'/world_moving/{index}', mesh)
            self._links.append([frame, scene_node, T, None])
        if links:
            from rclpy.qos import QoSProfile
            from tf2_msgs.msg import TFMessage
            self.topic = f'/world/{world.name}/dynamic_pose/info'
            node.create_subscription(TFMessage, self.topic, self._on_poses, QoSProfile(depth=10))
        log.info(f'world {world.name!r}: {len(world.models)} models, {self.faces} triangles'
                 f'{f", {len(links)} moving links" if links else ""}')

    def _on_poses(self, msg):
        from amr_description.core.tf_buffer import pose_matrix
        poses = dict(self._poses)
        for transform in msg.transforms:
            t, r = transform.transform.translation, transform.transform.rotation
            values = (t.x, t.y, t.z, r.x, r.y, r.z, r.w)
            if not all(math.isfinite(v) for v in values) or not any(values[3:]):
                continue  # garbage: the link stays where it was
            poses[transform.child_frame_id] = pose_matrix(values[:3], values[3:])
        self._poses = poses

    def draw(self, context):
        """Place the world at the pose of frame ``world`` in the fixed frame (else identity)."""
        T = context.pose('world')
        if T is None:
            T = np.eye(4)
        if self._node is not None and (self._pose is None or
                                       not np.allclose(self._pose, T, atol=1e-6)):
            self._node.wxyz, self._node.position = wxyz_position(T)
            self._pose = T
        poses = self._poses
        for link in self._links:
            frame, scene_node, initial, last = link
            pose = T @ poses.get(frame, initial)
            if moved(last, pose, POSE_TOLERANCE):
                scene_node.wxyz, scene_node.position = wxyz_position(pose)
                link[3] = pose
