# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Headless picture of a URDF robot with MuJoCo's renderer (no rclpy).

The robot comes from :func:`amr_description.sim.urdf_to_mjcf.urdf_to_spec` (welded to the
world, zero joint positions, URDF colours); this module adds a checkered ground plane at z = 0,
a directional light and a free camera that frames the robot (looking at the centre of its
bounding box from the front left, above). It renders without a display: the package
chooses EGL unless ``MUJOCO_GL`` says otherwise (:mod:`amr_description`).
"""

import numpy as np


def build_scene(urdf_xml, width=640, height=480, pose=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                path=(), others=(), world=None):
    """
    Return a compiled ``(model, data)`` of the robot on a ground plane with a light.

    :param urdf_xml: URDF text (str or bytes).
    :param width: image width the offscreen buffer must hold, pixels.
    :param height: image height, pixels.
    :param pose: root-link pose in the world, ``(x, y, z, roll, pitch, yaw)`` in m and rad.
    :param path: planar points ``(x, y)`` in m drawn as small green markers on the ground.
    :param others: ``(pose, path)`` pairs of more copies of the robot (a fleet), as above.
    :param world: None, or a :class:`~amr_description.core.gazebo.sdf_elements.World` whose models
        (walls, pillars, shelves, loose boxes at their initial poses) stand around the robot;
        its ground, when it has one, is drawn as the checkered plane.
    :returns: ``(mujoco.MjModel, mujoco.MjData)`` after ``mj_forward``.
    :raises ValueError: one line when the URDF cannot be converted.
    """
    import mujoco
    from amr_description.sim.sdf_to_mjcf import add_world
    from amr_description.sim.sdf_to_mjcf import GROUND_BODY
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import mujoco_error

    spec = urdf_to_spec(urdf_xml, name='render', pose=pose, free=False)
    spec.visual.global_.offwidth = max(int(width), 640)
    spec.visual.global_.offheight = max(int(height), 480)
    spec.visual.headlight.ambient = [0.35, 0.35, 0.35]
    texture = spec.add_texture(
        name='grid', type=mujoco.mjtTexture.mjTEXTURE_2D,
        builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER, rgb1=[0.82, 0.82, 0.8],
        rgb2=[0.7, 0.7, 0.68], width=256, height=256)
    # no mirror image in a world: its walls and pillars would stand on their reflections
    material = spec.add_material(name='ground', texrepeat=[32, 32],
                                 reflectance=0.05 if world is None else 0.0)
    material.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = texture.name
    spec.worldbody.add_body(name=GROUND_BODY).add_geom(
        name='ground_plane', type=mujoco.mjtGeom.mjGEOM_PLANE, size=[20.0, 20.0, 0.05],
        material='ground', contype=0, conaffinity=0)
    if world is not None:
        add_world(spec, world)  # what it cannot build is left out, as the simulator does
    points = list(path)
    for index, (other_pose, other_path) in enumerate(others, start=1):
        robot = urdf_to_spec(urdf_xml, name=f'render{index}', pose=other_pose, free=False)
        spec.attach(robot, prefix=f'robot{index}/', frame=spec.worldbody.add_frame())
        points += list(other_path)
    for x, y in points:
        spec.worldbody.add_geom(
            type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.012, 0, 0], pos=[x, y, 0.012],
            rgba=[0.1, 0.7, 0.2, 1.0], contype=0, conaffinity=0)
    if world is None:
        spec.worldbody.add_light(name='sun', pos=[1.0, 1.0, 3.0], dir=[-0.3, -0.3, -1.0],
                                 diffuse=[0.8, 0.8, 0.8], castshadow=True)
    else:  # a hall: light it all, as the simulator's sun
        spec.worldbody.add_light(name='sun', pos=[0.0, 0.0, 10.0], dir=[0.3, 0.2, -1.0],
                                 type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL,
                                 diffuse=[0.8, 0.8, 0.8], castshadow=False)
    try:
        model = spec.compile()
    except ValueError as exc:
        raise ValueError(f'MuJoCo cannot build the scene: {mujoco_error(exc)}') from None
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


def frame_camera(model, data, azimuth=135.0, elevation=-25.0, scale=2.2):
    """
    Return a free ``mujoco.MjvCamera`` that frames every robot geom.

    :param model: ``mujoco.MjModel``.
    :param data: ``mujoco.MjData`` after ``mj_forward``.
    :param azimuth: deg, 0 = looking along +x.
    :param elevation: deg, negative = looking down.
    :param scale: distance in half-diagonals of that box.
    :returns: the camera: ``lookat`` = centre of the geoms' bounding spheres' box,
        ``distance`` = ``scale`` x its half-diagonal (at least 0.5 m).
    """
    import mujoco

    points = []
    for geom in range(model.ngeom):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        radius = model.geom_rbound[geom]
        centre = data.geom_xpos[geom]
        points.extend([centre - radius, centre + radius])
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    if points:
        points = np.array(points)
        low, high = points.min(axis=0), points.max(axis=0)
        camera.lookat[:] = (low + high) / 2.0
        camera.distance = max(scale * np.linalg.norm(high - low) / 2.0, 0.5)
    else:
        camera.lookat[:] = [0.0, 0.0, 0.0]
        camera.distance = 2.0
    camera.azimuth = azimuth
    camera.elevation = elevation
    return camera


def render_urdf(urdf_xml, width=640, height=480, frames=False, world=None):
    """
    Render a URDF robot to an RGB image, alone or in a world.

    :param urdf_xml: URDF text.
    :param width: pixels (> 0).
    :param height: pixels (> 0).
    :param frames: draw every body frame's axes (x red, y green, z blue).
    :param world: None (the robot on a plain ground), or a
        :class:`~amr_description.core.gazebo.sdf_elements.World` (``load_world``): the robot
        spawned at the origin of that world (as the sim stack spawns it), the whole world in view.
    :returns: numpy array of shape (height, width, 3), dtype uint8.
    :raises ValueError: when the URDF cannot be converted or the size is not positive.
    """
    if int(width) <= 0 or int(height) <= 0:
        raise ValueError(f'image size must be positive, found {width}x{height}')
    if world is not None:
        return _render_in_world(urdf_xml, world, int(width), int(height), frames)
    model, data = build_scene(urdf_xml, width, height)
    return _render(model, data, width, height, frames)


def _render_in_world(urdf_xml, world, width, height, frames):
    """Spawn the robot at the origin of ``world`` (an engine, no ROS) and render it all."""
    import mujoco
    from amr_description.sim.simulation import Simulation
    sim = Simulation(real_time_factor=0.0, world=world,
                     sensor_settings={'publish_ground_truth': False})
    try:
        sim.spawn(urdf_xml, name='robot', pose=[0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 1.0])
        model, data = sim.world.model, sim.world.data
        model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), width)
        model.vis.global_.offheight = max(int(model.vis.global_.offheight), height)
        mujoco.mj_forward(model, data)
        return _render(model, data, width, height, frames, elevation=-50.0, scale=1.1)
    finally:
        sim.close()


def _render(model, data, width, height, frames, elevation=-25.0, scale=2.2):
    """Return the RGB image of ``model``/``data`` seen by :func:`frame_camera`."""
    import mujoco

    option = mujoco.MjvOption()
    if frames:
        option.frame = mujoco.mjtFrame.mjFRAME_BODY
        model.vis.scale.framelength = 1.2
        model.vis.scale.framewidth = 0.06
    renderer = mujoco.Renderer(model, height=int(height), width=int(width))
    try:
        camera = frame_camera(model, data, elevation=elevation, scale=scale)
        renderer.update_scene(data, camera=camera, scene_option=option)
        return renderer.render().copy()
    finally:
        renderer.close()


def render_scene(urdf_xml, pose, path=(), width=800, height=600, markers=150, others=(),
                 world=None):
    """
    Render the robot at a planar pose on the ground, with the path it drove, in its world.

    :param urdf_xml: URDF text.
    :param pose: ``(x, y, yaw)`` of the root link (``base_footprint``) in the world, m and rad.
    :param path: ``(x, y)`` points in the world frame, m; at most ``markers`` evenly spaced
        ones are drawn.
    :param width: pixels (> 0).
    :param height: pixels (> 0).
    :param markers: largest number of path markers per robot, int > 0.
    :param others: ``(pose, path)`` of more robots (a fleet), as ``pose`` and ``path``.
    :param world: None (a plain ground) or the
        :class:`~amr_description.core.gazebo.sdf_elements.World` the robots drove in
        (``load_world``).
    :returns: numpy array of shape (height, width, 3), dtype uint8, seen from above at 55 deg
        so that the whole path, the robots and the world's models are in view.
    :raises ValueError: when the URDF cannot be converted.
    """
    def thin(path):
        points = list(path)
        if len(points) > markers:
            step = len(points) / float(markers)
            points = [points[int(i * step)] for i in range(markers)] + [points[-1]]
        return points

    def pose6(pose):
        return (pose[0], pose[1], 0.0, 0.0, 0.0, pose[2])

    model, data = build_scene(urdf_xml, width, height, pose=pose6(pose), path=thin(path),
                              others=[(pose6(p), thin(q)) for p, q in others], world=world)
    import mujoco

    renderer = mujoco.Renderer(model, height=int(height), width=int(width))
    try:
        camera = frame_camera(model, data, azimuth=-120.0, elevation=-55.0,
                              scale=2.2 if world is None else 1.35)
        camera.distance *= 1.2
        renderer.update_scene(data, camera=camera)
        return renderer.render().copy()
    finally:
        renderer.close()


def save_png(image, path):
    """
    Write an (H, W, 3) uint8 image to ``path`` as PNG (matplotlib).

    :raises ValueError: one line when the file cannot be written.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.image

    try:
        matplotlib.image.imsave(path, image)
    except OSError as exc:
        raise ValueError(f'{path}: cannot write: {exc.strerror}') from None
