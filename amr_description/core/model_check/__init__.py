# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Model checks beyond ``check_urdf``: physics, drive wheels, ros2_control and controllers.yaml.

``check_urdf`` (urdfdom) only proves the file parses into a tree. The checks here catch what
makes a robot fall through the floor, explode, or drive backwards in simulation:

- every non-root link has ``<collision>`` and ``<inertial>`` (a driven wheel without
  ``<collision>``, one whose joint has a velocity or effort command interface or that the
  controllers YAML names as a wheel, is an error: it cannot touch the ground); mass > 0;
  the inertia matrix is symmetric positive definite and its principal moments obey the
  triangle inequality (``I1 + I2 >= I3``, true of every real body); it is close to what the
  collision geometry and mass imply (solid box / cylinder / sphere formulas; warning only);
  a root link with inertia is flagged (KDL, hence robot_state_publisher, ignores it:
  warning);
- drive wheels: positive wheel speed must roll the base forward. With the axle ``a`` (the
  joint axis rotated into the base frame, ``R(rpy) @ axis``) and the wheel touching the ground
  below its centre, rolling without slipping moves the centre with ``v = w a x r`` where
  ``r = +z`` points from the contact to the centre, so the drive direction is ``a x z`` and
  forward needs ``(a x z) . x = a_y > 0``: the axle must point along base +y;
- the document itself goes through the package's one loader
  (:func:`amr_description.core.description.urdf_model.parse_urdf`): what it refuses (non-finite
  numbers, duplicate names, unknown joint types, broken trees, non-positive inertia on moving
  links) is an error naming the element that holds it, and no other check runs;
- every ``<ros2_control>`` ``<hardware><plugin>`` is a hardware plugin the package registers
  (entry-point group ``amr_description.hardware``, what mujoco_sim loads);
- the ``<ros2_control>`` block against controllers.yaml (ros2_control format): every wheel of
  ``diff_drive_controller`` is a joint of the block with a velocity command interface and
  position and velocity state interfaces; ``wheel_separation`` and ``wheel_radius`` match the
  URDF geometry within 1 mm;
- the ``<mujoco>`` simulator block (docs/architecture.md) names existing links and joints;
- the installed URDF (``share/amr_description/urdf``) is the source file or equal to it.

Pure logic except the optional ament index lookup of the installed copy; the ``check_model``
command is :mod:`amr_description.nodes.check_model`. One module per group of checks.
"""

from amr_description.core.description.ros2_control_info import driven_joints
from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.model_check.controllers import check_ros2_control
from amr_description.core.model_check.controllers_yaml import diff_drive_params
from amr_description.core.model_check.gazebo import check_gazebo
from amr_description.core.model_check.links import check_links
from amr_description.core.model_check.mujoco import check_mujoco_block
from amr_description.core.model_check.wheels import check_wheels
from amr_description.core.model_check.wheels import wheel_joints
from amr_description.core.xml_document import parse_text


def check_model(model, urdf_xml, controllers=None):
    """
    Run every model check that needs no file system.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`; its
        ``element`` (the parsed ``<robot>``) is read by every check, so the description is
        parsed once.
    :param urdf_xml: the URDF text (parsed only when the model holds no element).
    :param controllers: parsed controllers.yaml (dict) or None.
    :returns: list of :class:`Finding`.
    """
    base = 'base_link'
    for params in diff_drive_params(controllers or {}).values():
        base = params.get('base_frame_id', base)
    wheels = wheel_joints(model, controllers)
    root = model.element if model.element is not None else parse_text(urdf_xml)
    try:
        infos = parse_ros2_control(root)
    except ValueError:
        infos = []  # check_ros2_control reports it
    # the YAML's wheels are driven; without a YAML, wheel_joints guesses by shape: not them
    findings = check_links(model, driven_joints(model, infos, wheels if controllers else ()))
    findings += check_wheels(model, wheels, base)
    findings += check_ros2_control(model, root, controllers)
    findings += check_mujoco_block(model, root)
    findings += check_gazebo(root)
    return findings
