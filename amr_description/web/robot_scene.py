# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
A URDF robot drawn in a viser scene, one scene node per link, posed link by link.

Like RViz's RobotModel display: every link gets a node ``<root>/<link>`` directly under the
robot's root node (not nested), holding the link's ``<visual>`` geometry at its visual
origin; the caller poses each link node (from TF in the viewer, from forward kinematics in
joint_state_publisher_gui). Geometry: ``box``, ``cylinder`` (axis z, URDF), ``sphere`` and
``mesh`` (files loaded with trimesh; ``package://`` resolved through the ament index) as
viser meshes; colours from the URDF materials (grey when unset).
"""

import os

from amr_description.core.kinematics import matrix_to_quaternion
import numpy as np

DEFAULT_RGB = (180, 180, 180)


def wxyz_position(T):
    """
    Return viser's pose arguments of a 4x4 pose.

    :param T: homogeneous matrix, shape (4, 4).
    :returns: ``(wxyz quaternion, position)``, numpy arrays of 4 and 3.
    """
    x, y, z, w = matrix_to_quaternion(T)
    return np.array([w, x, y, z]), np.asarray(T, dtype=float)[:3, 3].copy()


def wxyzs_positions(poses):
    """
    Return viser's batched pose arguments (``add_batched_axes``) of N 4x4 poses.

    :param poses: homogeneous matrices, shape (N, 4, 4).
    :returns: ``(wxyzs, positions)``, float32 arrays of shape (N, 4) and (N, 3).
    """
    pairs = [wxyz_position(T) for T in poses]
    return (np.array([q for q, _ in pairs], dtype=np.float32).reshape(-1, 4),
            np.array([p for _, p in pairs], dtype=np.float32).reshape(-1, 3))


def _resolve(filename):
    """Return a mesh file path for ``package://PKG/...`` or ``file://...`` or a plain path."""
    if filename.startswith('package://'):
        package, _, rest = filename[len('package://'):].partition('/')
        from ament_index_python.packages import get_package_share_directory
        return os.path.join(get_package_share_directory(package), rest)
    if filename.startswith('file://'):
        return filename[len('file://'):]
    return filename


def visual_mesh(geometry, sections=16):
    """
    Return the triangle mesh of a URDF visual geometry.

    :param geometry: yourdfpy ``Geometry`` (one of box, cylinder, sphere, mesh set).
    :param sections: facets around cylinders (flat shaded, so a turning wheel shows).
    :returns: ``(vertices (V, 3) float32, faces (F, 3) uint32)`` in the visual frame (m).
    :raises ValueError: one line when the geometry is empty or a mesh file cannot be loaded.
    """
    import trimesh
    if geometry.box is not None:
        mesh = trimesh.creation.box(extents=geometry.box.size)
    elif geometry.cylinder is not None:
        mesh = trimesh.creation.cylinder(radius=geometry.cylinder.radius,
                                         height=geometry.cylinder.length, sections=sections)
    elif geometry.sphere is not None:
        mesh = trimesh.creation.icosphere(subdivisions=2, radius=geometry.sphere.radius)
    elif geometry.mesh is not None:
        path = _resolve(geometry.mesh.filename)
        try:
            mesh = trimesh.load(path, force='mesh')
        except Exception as exc:  # noqa: B902 - trimesh raises many kinds
            raise ValueError(f"mesh '{geometry.mesh.filename}': cannot load ({exc})") from None
        if geometry.mesh.scale is not None:
            mesh.apply_scale(geometry.mesh.scale)
    else:
        raise ValueError('visual without geometry')
    return (np.asarray(mesh.vertices, dtype=np.float32),
            np.asarray(mesh.faces, dtype=np.uint32))


class RobotScene:
    """
    The links of one robot model in a viser scene.

    :param scene: a viser ``SceneApi`` (``server.scene``).
    :param model: :class:`amr_description.core.description.urdf_model.RobotModel`.
    :param root: scene path of the robot, e.g. ``/robot``.
    :param frame_prefix: prepended to link names to form TF frame ids (``r1/``), as
        robot_state_publisher's ``frame_prefix``.
    """

    def __init__(self, scene, model, root='/robot', frame_prefix=''):
        """Create a node per link and a mesh per visual; collect per-visual problems."""
        self.scene = scene
        self.model = model
        self.root = root.rstrip('/')
        self.frame_prefix = frame_prefix
        self.links = {}  # link name -> viser FrameHandle
        self.problems = []  # one-line messages about visuals that could not be drawn
        for name, link in model.links.items():
            node = scene.add_frame(f'{self.root}/{name}', show_axes=False, visible=False)
            self.links[name] = node
            for index, visual in enumerate(link.visuals):
                try:
                    vertices, faces = visual_mesh(visual.geometry)
                except ValueError as exc:
                    self.problems.append(f"link '{name}': {exc}")
                    continue
                rgba = model.visual_rgba(visual)
                rgb = DEFAULT_RGB if rgba is None else tuple(
                    int(round(255 * float(c))) for c in rgba[:3])
                origin = visual.origin if visual.origin is not None else np.eye(4)
                wxyz, position = wxyz_position(origin)
                scene.add_mesh_simple(
                    f'{self.root}/{name}/visual_{index}', vertices, faces, color=rgb,
                    flat_shading=True, wxyz=wxyz, position=position,
                    opacity=None if rgba is None or rgba[3] >= 1.0 else float(rgba[3]))

    def frame_id(self, link):
        """Return the TF frame id of ``link`` (``frame_prefix + link``)."""
        return self.frame_prefix + link

    def set_pose(self, link, T):
        """
        Pose the node of ``link`` and show it.

        :param link: link name.
        :param T: pose of the link in the scene's fixed frame, shape (4, 4).
        """
        node = self.links[link]
        wxyz, position = wxyz_position(T)
        node.wxyz = wxyz
        node.position = position
        if not node.visible:
            node.visible = True

    def hide(self, link):
        """Hide ``link`` (its pose is unknown)."""
        node = self.links[link]
        if node.visible:
            node.visible = False

    def remove(self):
        """Remove every node of this robot from the scene."""
        for node in self.links.values():
            node.remove()
        self.links = {}
