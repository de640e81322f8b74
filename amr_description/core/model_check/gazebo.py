# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The Gazebo dialect of a description: what the simulator uses of each ``<gazebo>`` element.

gz_ros2_control's system plugin is used (it starts the controller manager, docs/gazebo.md);
every other ``<gazebo>`` element (gz-sim system plugins, ``<gazebo reference>`` tags, sensors)
is reported, by name, as not read by the simulator yet.
"""

from amr_description.core.gazebo_tags import is_control_plugin
from amr_description.core.gazebo_tags import parse_control_plugin
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING

NOT_YET = 'not read by the simulator yet (docs/gazebo.md)'


def check_gazebo(root):
    """
    Report every ``<gazebo>`` element: used, or not read.

    :param root: the ``<robot>`` element.
    :returns: list of :class:`~amr_description.core.model_check.findings.Finding`: an error
        for a malformed gz_ros2_control plugin, ok for a used one, a warning per element the
        simulator does not read.
    """
    findings = []
    for gazebo in root.findall('gazebo'):
        reference = gazebo.get('reference')
        where = f'<gazebo reference="{reference}">' if reference else '<gazebo>'
        for child in gazebo:
            if not isinstance(child.tag, str):
                continue
            if child.tag == 'plugin' and is_control_plugin(child):
                findings += _control_plugin(root, f"{where}<plugin {child.get('name', '')}>")
            elif child.tag == 'plugin':
                name = child.get('name') or child.get('filename') or '?'
                findings.append(Finding(WARNING, f'{where}<plugin {name}>',
                                        f'system plugin not simulated: {NOT_YET}'))
            else:
                findings.append(Finding(WARNING, f'{where}<{child.tag}>', NOT_YET))
    return findings


def _control_plugin(root, where):
    try:
        plugin = parse_control_plugin(root)
    except ValueError as exc:
        return [Finding(ERROR, where, str(exc).split(': ', 1)[-1])]
    findings = [Finding(INFO, where, 'gz_ros2_control: starts the controller manager '
                        f'{plugin.controller_manager_name!r} with '
                        + ', '.join(plugin.parameters))]
    if not plugin.hold_joints or plugin.position_proportional_gain != 0.1:
        findings.append(Finding(WARNING, where, '<hold_joints> and <position_proportional_gain> '
                                f'are {NOT_YET}'))
    return findings
