# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``<ros2_control>`` blocks and controllers.yaml against the URDF geometry."""


from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.model_check.controllers_yaml import diff_drive_params
from amr_description.core.model_check.controllers_yaml import node_parameters
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import GEOMETRY_TOLERANCE
from amr_description.core.model_check.findings import HARDWARE_GROUP
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING
from amr_description.core.model_check.wheels import joint_position_in_frame
from amr_description.core.model_check.wheels import wheel_radius
import numpy as np


def hardware_plugins():
    """
    Return the hardware plugin names the installed package registers (a set).

    :returns: the entry-point names of group ``amr_description.hardware`` (e.g.
        ``'amr_description/MujocoSystem'``); empty when the package is not installed.
    """
    from importlib.metadata import entry_points
    return {entry.name for entry in entry_points(group=HARDWARE_GROUP)}


def check_ros2_control(model, urdf_xml, controllers=None):
    """
    Check the ``<ros2_control>`` blocks, and the diff_drive_controller against them.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param urdf_xml: the URDF text or its parsed ``<robot>`` element (for the
        ``<ros2_control>`` blocks).
    :param controllers: parsed controllers.yaml (dict) or None to skip the YAML checks.
    :returns: list of :class:`Finding`.
    """
    try:
        infos = parse_ros2_control(urdf_xml)
    except ValueError as exc:
        return [Finding(ERROR, '<ros2_control>', str(exc))]
    findings = []
    components = {}
    plugins = hardware_plugins()
    for info in infos:
        if plugins and info.plugin not in plugins:
            findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                    'unknown hardware plugin: mujoco_sim cannot load it',
                                    'one of ' + ', '.join(sorted(plugins)), info.plugin))
        for joint in info.joints:
            components[joint.name] = joint
            if joint.name not in model.joints:
                findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                        f'joint {joint.name!r} is not a URDF joint'))
            elif model.joints[joint.name].type == 'fixed':
                findings.append(Finding(ERROR, f'ros2_control {info.name!r}',
                                        f'joint {joint.name!r} is fixed'))
    if controllers is None:
        return findings
    cm = node_parameters(controllers, 'controller_manager')
    if not isinstance(cm, dict):
        return findings + [Finding(ERROR, 'controllers.yaml',
                                   'no controller_manager.ros__parameters section')]
    for name, params in diff_drive_params(controllers).items():
        findings.extend(_check_diff_drive(model, components, name, params))
    return findings


def _check_diff_drive(model, components, name, params):
    """Check one diff_drive_controller's wheels and geometry against the URDF."""
    element = f'controllers.yaml {name}'
    findings = []
    sides = {}
    for side in ('left', 'right'):
        key = f'{side}_wheel_names'
        wheels = params.get(key) or []
        if not wheels:
            findings.append(Finding(ERROR, element, f'{key} is empty', 'joint names', '[]'))
        sides[side] = [w for w in wheels if w in model.joints]
        for wheel in wheels:
            findings.extend(_check_wheel_interfaces(
                element, wheel, components.get(wheel), model,
                params.get('position_feedback', True)))
    base = params.get('base_frame_id', 'base_link')
    if base not in model.links:
        findings.append(Finding(ERROR, element, 'base_frame_id is not a URDF link',
                                'a link name', repr(base)))
        base = model.root
    elif params.get('enable_odom_tf', True):
        parents = [j.parent for j in model.joints.values() if j.child == base]
        if parents:
            findings.append(Finding(
                WARNING, element,
                f'base_frame_id has a parent in the URDF ({parents[0]}): the odometry TF '
                f"odom -> {base} and robot_state_publisher's {parents[0]} -> {base} give it "
                'two parents (REP 105: odom -> the URDF root)', f'{model.root!r}', repr(base)))
    if sides['left'] and sides['right']:
        left_y = np.mean([joint_position_in_frame(model, w, base)[1] for w in sides['left']])
        right_y = np.mean([joint_position_in_frame(model, w, base)[1] for w in sides['right']])
        separation = left_y - right_y
        if separation <= 0.0:
            findings.append(Finding(ERROR, element, 'left wheels are not left of right wheels',
                                    'left y > right y', f'{left_y:g} <= {right_y:g}'))
        value = params.get('wheel_separation')
        if not isinstance(value, (int, float)) or abs(value - separation) > GEOMETRY_TOLERANCE:
            findings.append(Finding(ERROR, element, 'wheel_separation does not match the URDF',
                                    f'{separation:g} m (+-1 mm)', f'{value}'))
        else:
            findings.append(Finding(INFO, element, f'wheel_separation {value:g} m matches'))
        findings.extend(check_separation_multiplier(model, element, params, base, sides))
    value = params.get('wheel_radius')
    for wheel in sides['left'] + sides['right']:
        radius = wheel_radius(model, model.joints[wheel].child)
        if radius is None:
            continue
        if not isinstance(value, (int, float)) or abs(value - radius) > GEOMETRY_TOLERANCE:
            findings.append(Finding(ERROR, element,
                                    f'wheel_radius does not match the URDF wheel of {wheel}',
                                    f'{radius:g} m (+-1 mm)', f'{value}'))
            break
    else:
        if sides['left'] + sides['right']:
            findings.append(Finding(INFO, element, f'wheel_radius {value:g} m matches'))
    return findings


def check_separation_multiplier(model, element, params, base, sides):
    """
    Compare a skid-steer base's ``wheel_separation_multiplier`` with the Coulomb value.

    A base with wheels at different x on one side (skid steer) turning in place slips its
    wheels sideways; with equal wheel loads and Coulomb friction it turns at
    ``omega = v b / (a^2 + b^2)`` (:mod:`amr_description.core.skid_steer`), so odometry needs
    ``wheel_separation_multiplier = (a^2 + b^2) / b^2`` with ``b`` half the track and ``a``
    the mean distance of the wheels from their centre along x (half the wheelbase).

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param element: the controller's name in findings (str).
    :param params: its ``ros__parameters`` (dict).
    :param base: the base frame the wheel positions are expressed in.
    :param sides: dict ``'left'``/``'right'`` -> wheel joint names (URDF joints).
    :returns: list of :class:`Finding`: nothing for a two-wheeled base, else a warning when
        the multiplier is more than 10 % from the geometric value, an ``ok`` otherwise.
    """
    wheels = sides['left'] + sides['right']
    if not sides['left'] or not sides['right']:
        return []
    positions = np.array([joint_position_in_frame(model, w, base) for w in wheels])
    left_y = positions[:len(sides['left']), 1].mean()
    right_y = positions[len(sides['left']):, 1].mean()
    b = (left_y - right_y) / 2.0
    a = float(np.mean(np.abs(positions[:, 0] - positions[:, 0].mean())))
    if not b > 0.0 or a < GEOMETRY_TOLERANCE:
        return []  # not a skid-steer base (or already reported as broken)
    geometric = (a * a + b * b) / (b * b)
    value = params.get('wheel_separation_multiplier', 1.0)
    formula = (f'skid steer: (a^2 + b^2) / b^2 with half wheelbase a = {a:g} m, half track '
               f'b = {b:g} m')
    if not isinstance(value, (int, float)) or abs(value - geometric) > 0.1 * geometric:
        return [Finding(WARNING, element, 'wheel_separation_multiplier is far from the '
                        f'Coulomb-friction value, {formula}', f'{geometric:.3g} (+-10 %)',
                        f'{value}')]
    return [Finding(INFO, element,
                    f'wheel_separation_multiplier {value:g} matches {formula} = {geometric:.3g}')]


def _check_wheel_interfaces(element, wheel, component, model, position_feedback):
    """Check the ros2_control interfaces one diff_drive wheel needs."""
    if wheel not in model.joints:
        return [Finding(ERROR, element, f'wheel {wheel!r} is not a URDF joint')]
    if component is None:
        return [Finding(ERROR, element, f'wheel {wheel!r} is not in a <ros2_control> block')]
    findings = []
    commands = component.command_interface_names()
    states = component.state_interface_names()
    if 'velocity' not in commands:
        findings.append(Finding(ERROR, f'ros2_control joint {wheel!r}',
                                'diff_drive_controller needs a velocity command interface',
                                'velocity', ', '.join(commands) or 'none'))
    for state in ('position', 'velocity'):
        if state not in states:
            needed = (state == 'position') == bool(position_feedback)
            findings.append(Finding(
                ERROR if needed else WARNING, f'ros2_control joint {wheel!r}',
                f'missing {state} state interface', state, ', '.join(states) or 'none'))
    return findings
