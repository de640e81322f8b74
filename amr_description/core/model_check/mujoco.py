# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The ``<mujoco>`` simulator block, read by the simulator's own reader."""


from amr_description.core.description.mujoco_block import parse_mujoco_block
from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.xml_document import parse_text


def check_mujoco_block(model, urdf_xml):
    """
    Check the ``<mujoco>`` extension block (format: docs/architecture.md).

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :param urdf_xml: the URDF text, or its parsed ``<robot>`` element.

    Values are read by :func:`amr_description.core.description.mujoco_block.parse_mujoco_block`,
    the reader the simulator's converter uses: what it refuses is reported here with its line.

    :returns: list of :class:`Finding`: a value the reader refuses, link/joint names that do
        not exist, actuators on joints without a velocity command interface.
    """
    root = parse_text(urdf_xml) if isinstance(urdf_xml, (str, bytes)) else urdf_xml
    blocks = root.findall('mujoco')
    if not blocks:
        return [Finding(INFO, '<mujoco>', 'no simulator block: the measured defaults of '
                        'docs/gazebo.md apply')]
    findings = []
    try:
        parse_mujoco_block(root)
    except ValueError as exc:
        findings.append(Finding(ERROR, '<mujoco>', str(exc).replace('<mujoco>: ', '', 1)))
    commands = set()
    try:
        for info in parse_ros2_control(root):
            commands.update(j.name for j in info.joints if 'velocity' in
                            j.command_interface_names())
    except ValueError:
        pass
    for block in blocks:
        for element in block:
            if not isinstance(element.tag, str):
                continue
            findings.extend(_check_mujoco_names(model, element, commands))
    return findings


def _check_mujoco_names(model, element, commands):
    """Check the names one child of ``<mujoco>`` refers to."""
    where = f'<mujoco><{element.tag}>'
    findings = []
    if element.tag == 'ros2_control':
        if not element.get('parameters'):
            findings.append(Finding(ERROR, where, 'missing parameters attribute'))
    if element.tag == 'link' and element.get('name') not in model.links:
        findings.append(Finding(ERROR, where, 'names no URDF link', 'a link',
                                repr(element.get('name'))))
    if element.tag == 'actuator':
        joint = element.get('joint')
        if joint is not None and joint not in commands:
            findings.append(Finding(ERROR, where,
                                    'joint has no velocity command interface in <ros2_control>',
                                    'a ros2_control velocity joint', repr(joint)))
    return findings
