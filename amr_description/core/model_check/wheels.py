# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Drive wheels: positive wheel speed rolls the base forward; cylinders on their axles."""


from amr_description.core.model_check.controllers_yaml import diff_drive_params
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import origin_matrix
from amr_description.core.model_check.findings import vec
from amr_description.core.model_check.findings import WARNING
import numpy as np


def drive_direction(axle):
    """
    Return the base velocity direction of positive wheel speed for an axle direction.

    :param axle: wheel axle (joint axis) in the base frame, 3 floats, REP 103 (z up).
    :returns: ``a x z`` normalized (numpy, 3 floats): the direction the wheel centre moves
        when the wheel turns positively while rolling on the ground below it; zero when the
        axle is vertical (the wheel cannot roll).
    """
    a = np.asarray(axle, dtype=float)
    a = a / np.linalg.norm(a)
    d = np.cross(a, [0.0, 0.0, 1.0])
    n = np.linalg.norm(d)
    return d / n if n > 1e-9 else np.zeros(3)


def wheel_radius(model, link_name, axis=None):
    """
    Return the wheel radius (m) of a link from its collision (else visual) geometry.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param link_name: the wheel link.
    :param axis: unused; kept for symmetry with the joint axis checks.
    :returns: the radius of the first cylinder or sphere, or None when there is none.
    """
    link = model.links[link_name]
    for element in list(link.collisions) + list(link.visuals):
        geometry = element.geometry
        if geometry is None:
            continue
        if geometry.cylinder is not None:
            return float(geometry.cylinder.radius)
        if geometry.sphere is not None:
            return float(geometry.sphere.radius)
    return None


def wheel_joints(model, controllers=None):
    """
    Return the names of the drive wheel joints.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param controllers: parsed controllers.yaml (dict) or None.
    :returns: the ``left_wheel_names + right_wheel_names`` of every diff_drive_controller in
        ``controllers`` that are URDF joints; without controllers, every continuous joint
        whose child link has a cylinder or sphere.
    """
    names = []
    for params in diff_drive_params(controllers or {}).values():
        for key in ('left_wheel_names', 'right_wheel_names'):
            names.extend(n for n in params.get(key) or [] if n in model.joints)
    if names or controllers:
        return list(dict.fromkeys(names))
    return [j.name for j in model.joints.values()
            if j.type == 'continuous' and wheel_radius(model, j.child) is not None]


def axle_in_frame(model, joint_name, frame):
    """
    Return a joint's axis expressed in link ``frame`` at zero joint positions.

    :returns: unit vector (numpy, 3 floats): ``R_frame^T R_parent R_origin axis``.
    """
    joint = model.joints[joint_name]
    T_parent = np.linalg.inv(model.link_pose(frame)) @ model.link_pose(joint.parent)
    R = (T_parent @ origin_matrix(joint.origin))[:3, :3]
    a = R @ np.asarray(joint.axis, dtype=float)
    return a / np.linalg.norm(a)


def joint_position_in_frame(model, joint_name, frame):
    """Return the position (m, numpy 3) of a joint's frame in link ``frame`` at zero."""
    joint = model.joints[joint_name]
    T = np.linalg.inv(model.link_pose(frame)) @ model.link_pose(joint.parent)
    return (T @ origin_matrix(joint.origin))[:3, 3]


def check_wheels(model, joints, base_frame):
    """
    Check that positive speed of each drive wheel rolls the base forward.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param joints: wheel joint names.
    :param base_frame: the base link (REP 105 ``base_link``; the root when absent).
    :returns: list of :class:`Finding`.
    """
    if base_frame not in model.links:
        base_frame = model.root
    findings = []
    for name in joints:
        joint = model.joints[name]
        element = f'joint {name!r}'
        if joint.type not in ('continuous', 'revolute'):
            findings.append(Finding(ERROR, element, 'a drive wheel joint must rotate',
                                    'continuous', joint.type))
            continue
        axle = axle_in_frame(model, name, base_frame)
        direction = drive_direction(axle)
        expected = f'axle along +y in {base_frame} (drives +x)'
        found = f'axle {vec(axle)} drives {vec(direction)}'
        if direction[0] > 0.7:
            findings.append(Finding(INFO, element, 'positive wheel speed drives forward'))
        elif direction[0] < -0.7:
            findings.append(Finding(
                ERROR, element, 'positive wheel speed drives the base BACKWARDS '
                '(reversed axle, e.g. rpy="1.5708 0 0" with axis "0 0 1")', expected, found))
        elif not direction.any():
            findings.append(Finding(ERROR, element, 'vertical axle: the wheel cannot roll',
                                    expected, found))
        else:
            findings.append(Finding(ERROR, element, 'positive wheel speed drives the base '
                                    'sideways', expected, found))
        radius = wheel_radius(model, joint.child)
        if radius is None:
            findings.append(Finding(ERROR, f'link {joint.child!r}',
                                    'wheel has no cylinder or sphere geometry', 'radius',
                                    'none'))
        else:
            findings.extend(_check_cylinder_axis(model, joint))
    return findings


def _check_cylinder_axis(model, joint):
    """Warn when a wheel cylinder's axis is not along the joint axis (it would not roll)."""
    link = model.links[joint.child]
    for collision in link.collisions:
        if collision.geometry is not None and collision.geometry.cylinder is not None:
            cyl_axis = origin_matrix(collision.origin)[:3, :3] @ [0.0, 0.0, 1.0]
            axis = np.asarray(joint.axis, dtype=float)
            cosine = abs(cyl_axis @ axis) / np.linalg.norm(axis)
            if cosine < 0.99:
                return [Finding(WARNING, f'link {joint.child!r}',
                                'wheel cylinder axis is not along the joint axis',
                                vec(axis), vec(cyl_axis))]
    return []
