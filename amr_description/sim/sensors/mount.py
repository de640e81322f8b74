# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Where a ``<gazebo><sensor>`` sits in the MuJoCo model: a site on its link's body.

Every sensor block the simulator simulates gets a site ``sensor/<name>`` on the body of its
URDF link (bodies keep their URDF link names; fixed joints are not lumped), at the block's
``<pose>`` in the link frame. An IMU also gets MuJoCo's own sensors on that site
(``accelerometer``, which includes gravity, ``gyro`` and ``framequat`` in the world frame;
MuJoCo ``doc/XMLreference.rst``), named ``sensor/<name>/accel``, ``/gyro`` and ``/quat``.
A camera gets a MuJoCo camera ``camera/<name>`` at the site: MuJoCo's camera looks along its
-Z with +Y up and +X right, SDF's along the sensor's +X with +Z up, so the camera's axes in
the sensor frame are x = -y_s, y = z_s, z = -x_s (:data:`CAMERA_IN_SENSOR`); its vertical
field of view is ``2 atan(height / (2 fy))`` (``fy`` from the SDF intrinsics or the
horizontal field of view, :meth:`~amr_description.core.gazebo.sensors.CameraSpec.k`).
The world's attach prefix (``<entity>/``) is put in front of every name.
"""

import math

import mujoco
import numpy as np

SITE_GROUP = 5
"""MuJoCo group of sensor sites (not drawn by default)."""


CAMERA_IN_SENSOR = ((0.0, 0.0, -1.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
"""Rotation matrix (rows) of a MuJoCo camera's axes in an SDF sensor frame (module doc)."""


def camera_name(block):
    """Return the MuJoCo camera name of a camera sensor block."""
    return f'camera/{block.name}'


def camera_quat(rpy):
    """Return the MuJoCo quaternion (w, x, y, z) of a camera at sensor pose ``rpy`` (rad)."""
    sensor = np.zeros(4)
    sensor[:] = quat_wxyz_from_rpy(*rpy)
    local = np.zeros(4)
    mujoco.mju_mat2Quat(local, np.array(CAMERA_IN_SENSOR).ravel())
    result = np.zeros(4)
    mujoco.mju_mulQuat(result, sensor, local)
    return result.tolist()


def site_name(block):
    """Return the site name of a :class:`~amr_description.core.gazebo.sensors.SensorBlock`."""
    return f'sensor/{block.name}'


def imu_sensor_names(block):
    """Return the MuJoCo sensor names (accelerometer, gyro, framequat) of an IMU block."""
    base = site_name(block)
    return f'{base}/accel', f'{base}/gyro', f'{base}/quat'


def quat_wxyz_from_rpy(roll, pitch, yaw):
    """Return the MuJoCo quaternion (w, x, y, z) of fixed-axis roll, pitch, yaw (rad)."""
    cr, sr = math.cos(0.5 * roll), math.sin(0.5 * roll)
    cp, sp = math.cos(0.5 * pitch), math.sin(0.5 * pitch)
    cy, sy = math.cos(0.5 * yaw), math.sin(0.5 * yaw)
    return [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy]


def add_mounts(spec, blocks):
    """
    Add the site (and an IMU's MuJoCo sensors) of every sensor block to a robot spec.

    :param spec: the robot's ``mujoco.MjSpec`` (bodies named after the URDF links).
    :param blocks: list of :class:`~amr_description.core.gazebo.sensors.SensorBlock`.
    """
    for block in blocks:
        body = spec.body(block.link)
        if body is None:
            continue
        site = body.add_site(name=site_name(block), pos=list(block.xyz),
                             quat=quat_wxyz_from_rpy(*block.rpy), group=SITE_GROUP,
                             size=[0.01, 0.01, 0.01])
        if block.camera is not None:
            camera = block.camera
            fy = camera.k()[1]
            body.add_camera(name=camera_name(block), pos=list(block.xyz),
                            quat=camera_quat(block.rpy),
                            fovy=math.degrees(2.0 * math.atan(0.5 * camera.height / fy)))
        if block.kind == 'imu':
            accel, gyro, quat = imu_sensor_names(block)
            spec.add_sensor(name=accel, type=mujoco.mjtSensor.mjSENS_ACCELEROMETER,
                            objtype=mujoco.mjtObj.mjOBJ_SITE, objname=site.name)
            spec.add_sensor(name=gyro, type=mujoco.mjtSensor.mjSENS_GYRO,
                            objtype=mujoco.mjtObj.mjOBJ_SITE, objname=site.name)
            spec.add_sensor(name=quat, type=mujoco.mjtSensor.mjSENS_FRAMEQUAT,
                            objtype=mujoco.mjtObj.mjOBJ_SITE, objname=site.name)
