# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Links: collision, inertial, mass and an inertia that a real body can have."""


from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INERTIA_TOLERANCE
from amr_description.core.model_check.findings import origin_matrix
from amr_description.core.model_check.findings import vec
from amr_description.core.model_check.findings import WARNING
import numpy as np


def box_inertia(mass, size):
    """
    Return the 3x3 inertia (kg m^2) of a solid box about its centre, box axes.

    :param mass: kg.
    :param size: (x, y, z) edge lengths, m.
    :returns: ``diag(m (y^2+z^2), m (x^2+z^2), m (x^2+y^2)) / 12``.
    """
    x, y, z = (float(v) for v in size)
    return np.diag([y * y + z * z, x * x + z * z, x * x + y * y]) * mass / 12.0


def cylinder_inertia(mass, radius, length):
    """
    Return the 3x3 inertia (kg m^2) of a solid cylinder about its centre, axis along z.

    :returns: ``diag(m (3 r^2 + h^2) / 12, same, m r^2 / 2)``.
    """
    side = mass * (3.0 * radius * radius + length * length) / 12.0
    return np.diag([side, side, mass * radius * radius / 2.0])


def sphere_inertia(mass, radius):
    """Return the 3x3 inertia (kg m^2) of a solid sphere: ``2/5 m r^2`` on the diagonal."""
    return np.eye(3) * 0.4 * mass * radius * radius


def geometry_inertia(geometry, mass):
    """
    Return the inertia of a yourdfpy ``Geometry`` primitive about its own frame, or None.

    :param geometry: yourdfpy ``Geometry`` (box, cylinder or sphere; meshes give None).
    :param mass: kg.
    :returns: 3x3 numpy array (kg m^2) or None.
    """
    if geometry is None:
        return None
    if geometry.box is not None:
        return box_inertia(mass, geometry.box.size)
    if geometry.cylinder is not None:
        return cylinder_inertia(mass, geometry.cylinder.radius, geometry.cylinder.length)
    if geometry.sphere is not None:
        return sphere_inertia(mass, geometry.sphere.radius)
    return None


def inertia_problems(inertia):
    """
    Return why a 3x3 inertia matrix is not physical, or [] when it is.

    :param inertia: 3x3 array, kg m^2.
    :returns: list of (message, expected, found) tuples: not symmetric, not positive definite
        (eigenvalues), principal moments breaking the triangle inequality.
    """
    inertia = np.asarray(inertia, dtype=float)
    problems = []
    if not np.allclose(inertia, inertia.T):
        problems.append(('inertia matrix is not symmetric', 'I == I^T', 'asymmetric'))
        return problems
    moments = np.linalg.eigvalsh(inertia)
    if moments[0] <= 0.0:
        problems.append(('inertia is not positive definite', 'principal moments > 0',
                         vec(moments, 8)))
        return problems
    tolerance = 1e-9 * moments.sum()
    if moments[0] + moments[1] < moments[2] - tolerance:
        problems.append(('principal moments break the triangle inequality',
                         'I1 + I2 >= I3', vec(moments, 8)))
    return problems


HEAVY_SHARE = 0.1
"""Share of the robot's mass from which a link without ``<collision>`` is reported."""


def check_links(model, driven=None):
    """
    Check collision, inertial, mass and inertia of every link.

    A link on a fixed joint may have neither (a sensor frame, a weight: sdformat merges it
    into its parent) unless it carries :data:`HEAVY_SHARE` of the robot's mass (a chassis
    without ``<collision>`` falls through the floor: a warning); a link on a moving joint
    without ``<collision>`` is a warning, without ``<inertial>`` an error (Gazebo drops it).
    A driven wheel without ``<collision>`` is an error: it cannot touch the ground, so the
    robot sits on its base while the wheel spins in the air.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param driven: dict joint name -> why it is driven (text), from
        :func:`~amr_description.core.description.ros2_control_info.driven_joints`.
    :returns: list of :class:`Finding`.
    """
    driven = driven or {}
    driven_links = {model.joints[name].child: (name, why) for name, why in driven.items()
                    if name in model.joints}
    findings = []
    parent_types = {joint.child: joint.type for joint in model.joints.values()}
    total = sum(link.inertial.mass for link in model.links.values()
                if link.inertial is not None and link.inertial.mass and link.inertial.mass > 0)
    for name, link in model.links.items():
        element = f'link {name!r}'
        inertial = link.inertial
        if name == model.root:
            if inertial is not None and inertial.mass:
                findings.append(Finding(
                    WARNING, element,
                    'root link has an inertia, which KDL (robot_state_publisher) ignores; '
                    'add a dummy root link such as base_footprint', 'no <inertial>',
                    f'mass {inertial.mass:g} kg'))
            continue
        fixed = parent_types.get(name) == 'fixed'
        mass = inertial.mass if inertial is not None and inertial.mass else 0.0
        if not link.collisions and name in driven_links:
            joint, why = driven_links[name]
            findings.append(Finding(
                ERROR, element, f'no <collision> on the link driven by joint {joint!r} '
                f'({why}): it cannot touch the ground (a wheel spins in the air while the '
                'robot sits on its base)', '<collision>', 'none'))
        elif not link.collisions and (not fixed or mass >= HEAVY_SHARE * total):
            findings.append(Finding(WARNING, element, 'no <collision>: it cannot touch anything',
                                    '<collision>', 'none'))
        if inertial is None:
            if not fixed:  # a fixed child is merged into its parent (sdformat's lumping)
                findings.append(Finding(ERROR, element, 'no <inertial> on a moving joint: '
                                        'simulators drop the link', '<inertial>', 'none'))
            continue
        mass = inertial.mass if inertial.mass is not None else 0.0
        if mass <= 0.0:
            findings.append(Finding(ERROR, element, 'mass must be positive', 'mass > 0 kg',
                                    f'{mass:g} kg'))
            continue
        if inertial.inertia is None:
            findings.append(Finding(ERROR, element, 'no <inertia>', '<inertia>', 'none'))
            continue
        problems = inertia_problems(inertial.inertia)
        for message, expected, found in problems:
            findings.append(Finding(ERROR, element, message, expected, found))
        if not problems:
            findings.extend(_compare_geometry_inertia(element, link, mass))
    return findings


def _compare_geometry_inertia(element, link, mass):
    """Warn when a link's inertia is far from that of its single collision primitive."""
    if len(link.collisions) != 1:
        return []
    collision = link.collisions[0]
    body = geometry_inertia(collision.geometry, mass)
    if body is None:
        return []
    inertial = link.inertial
    T_inertial = origin_matrix(inertial.origin)
    T_geometry = origin_matrix(collision.origin)
    # Geometry inertia expressed in the inertial frame, about the inertial frame's origin
    # (parallel-axis theorem for an offset centre).
    T = np.linalg.inv(T_inertial) @ T_geometry
    R, d = T[:3, :3], T[:3, 3]
    expected = R @ body @ R.T + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))
    found = np.asarray(inertial.inertia, dtype=float)
    distance = np.linalg.norm(found - expected) / np.linalg.norm(expected)
    if distance > INERTIA_TOLERANCE:
        return [Finding(
            WARNING, element,
            f'inertia is {distance:.0%} away from that of its collision geometry and mass',
            'ixx iyy izz ~ ' + vec(np.diag(expected), 6),
            'ixx iyy izz = ' + vec(np.diag(found), 6))]
    return []
