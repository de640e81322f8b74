# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The Gazebo dialect of a description: what the simulator does with each ``<gazebo>`` element.

Every ``<gazebo>`` child gets one finding (docs/gazebo.md has the table): gz_ros2_control's
plugin and the gz-sim systems the simulator runs (DiffDrive, JointStatePublisher,
OdometryPublisher) are used; lidar and IMU ``<sensor>`` blocks are simulated
(docs/sensors.md), other sensor types and bad fields are warnings; ``mu1``/``mu2`` are
mapped to contact friction; the tags Harmonic's default engine ignores are ignored here too;
everything else is reported as not read by the simulator (yet).
"""

from amr_description.core.gazebo.sensors import parse_sensors
from amr_description.core.gazebo.sensors import read_sensor
from amr_description.core.gazebo.sensors import SensorError
from amr_description.core.gazebo.systems import is_sensor_system
from amr_description.core.gazebo.systems import parse_gazebo_systems
from amr_description.core.gazebo.systems import system_class
from amr_description.core.gazebo.tags import FRICTION_TAGS
from amr_description.core.gazebo.tags import gazebo_material
from amr_description.core.gazebo.tags import GRAVITY_TAGS
from amr_description.core.gazebo.tags import IGNORED_AS_HARMONIC
from amr_description.core.gazebo.tags import is_control_plugin
from amr_description.core.gazebo.tags import KEPT_JOINT_TAGS
from amr_description.core.gazebo.tags import link_gravity
from amr_description.core.gazebo.tags import parse_control_plugin
from amr_description.core.gazebo.tags import surface_friction
from amr_description.core.gazebo.tags import tag_bool
from amr_description.core.gazebo.tags import tag_text
from amr_description.core.gazebo.tags import VISUAL_TAGS
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING

NOT_YET = 'not read by the simulator yet (docs/gazebo.md)'


def check_gazebo(root):
    """
    Report every ``<gazebo>`` element: used, mapped, ignored or not read.

    :param root: the ``<robot>`` element.
    :returns: list of :class:`~amr_description.core.model_check.findings.Finding`: an error
        for a malformed plugin or tag, ok for a used, mapped or ignored one, a warning per
        element the simulator does not read.
    """
    findings = []
    moving = [j.get('name') for j in root.findall('joint') if j.get('type') != 'fixed']
    try:
        systems = parse_gazebo_systems(root, moving)
    except ValueError as exc:
        element, _, message = str(exc).partition(': ')
        findings.append(Finding(ERROR, element, message))
        systems = None
    links = {link.get('name') for link in root.findall('link')}
    for gazebo in root.findall('gazebo'):
        reference = gazebo.get('reference')
        where = f'<gazebo reference="{reference}">' if reference else '<gazebo>'
        for child in gazebo:
            if not isinstance(child.tag, str):
                continue
            if child.tag == 'plugin' and is_control_plugin(child):
                findings += _control_plugin(root, f"{where}<plugin {child.get('name', '')}>")
            elif child.tag == 'plugin' and is_sensor_system(child):
                findings.append(Finding(INFO, f"{where}<plugin {child.get('name', '')}>",
                                        'not needed: every simulated <sensor> runs here '
                                        '(docs/sensors.md)'))
            elif child.tag == 'plugin':
                findings.append(_system(child, where, reference, systems))
            elif child.tag == 'sensor':
                findings.append(_sensor(child, where, reference, links))
            elif reference in links and child.tag in FRICTION_TAGS:
                findings.append(_friction(child, where))
            elif child.tag in KEPT_JOINT_TAGS:
                findings.append(Finding(INFO, f'{where}<{child.tag}>', 'every link keeps its '
                                        'own body and frame here (no fixed-joint lumping)'))
            elif reference in links and child.tag == 'material' and len(child) == 0:
                findings.append(_material(child, where))
            elif reference in links and child.tag in GRAVITY_TAGS:
                findings.append(_gravity(child, where))
            elif reference in links and child.tag == 'selfCollide':
                findings.append(_self_collide(child, where))
            elif child.tag in VISUAL_TAGS:
                findings.append(Finding(INFO, f'{where}<{child.tag}>', 'not used: visuals take '
                                        'the URDF <material> colour or a Gazebo/* material'))
            elif child.tag in IGNORED_AS_HARMONIC:
                findings.append(Finding(INFO, f'{where}<{child.tag}>', 'ignored, as Gazebo '
                                        "Harmonic's default physics engine (DART) does"))
            else:
                findings.append(Finding(WARNING, f'{where}<{child.tag}>', NOT_YET))
    for message in parse_sensors(root, links).messages:
        if '(one topic, one sensor)' in message:  # read one by one above, found here
            element, _, text = message.partition(': ')  # "sensor 'name'", the reason
            findings.append(Finding(WARNING, element, text))
    return findings


def _material(element, where):
    rgba, problem = gazebo_material({'material': tag_text(element)}, where)
    if rgba is None:
        return Finding(WARNING, f'{where}<material>', problem.split(': ', 1)[1])
    colour = ' '.join(f'{v:g}' for v in rgba)
    return Finding(INFO, f'{where}<material>', f"the link's visuals are drawn {colour} (rgba) "
                   'by the simulator and its cameras, as gz-sim; the viewer keeps the URDF '
                   'colour, as RViz')


def _gravity(element, where):
    try:
        on = link_gravity({element.tag: tag_text(element)}, where)
    except ValueError as exc:
        return Finding(ERROR, f'{where}<{element.tag}>', str(exc).split(': ', 1)[1])
    return Finding(INFO, f'{where}<{element.tag}>', 'gravity acts on this link' if on else
                   'no gravity on this link (its weight is cancelled)')


def _self_collide(element, where):
    try:
        on = tag_bool(element, f'{where}<selfCollide>')
    except ValueError as exc:
        return Finding(ERROR, f'{where}<selfCollide>', str(exc).split(': ', 1)[1])
    return Finding(INFO, f'{where}<selfCollide>', "collides with the robot's other links"
                   if on else "does not collide with the robot's other links (SDF default)")


def _system(plugin, where, reference, systems):
    name = system_class(plugin) or plugin.get('filename') or '?'
    element = f"{where}<plugin {plugin.get('name') or name}>"
    if systems is None:
        return Finding(INFO, element, 'not checked further (see the error above)')
    if reference or name in systems.unknown:
        return Finding(WARNING, element, f'system plugin not simulated: {NOT_YET}')
    return Finding(INFO, element, f'simulated as gz-sim\'s {name.rsplit("::", 1)[-1]}')


def _sensor(sensor, where, reference, links):
    element = f"{where}<sensor {sensor.get('name', '')}>"
    if reference not in links:
        return Finding(WARNING, element, 'not on a link of the description: skipped')
    try:
        block = read_sensor(sensor, reference)
    except SensorError as exc:
        text = str(exc).split(': ', 1)[-1] if ': ' in str(exc) else str(exc)
        return Finding(WARNING, element, text + ('' if 'not simulated' in text
                                                 else '; the sensor is skipped'))
    rate = f'{block.update_rate:g} Hz' if block.update_rate > 0 else 'every physics step'
    if block.kind == 'lidar':
        rays = block.lidar.horizontal.count * block.lidar.vertical.count
        what = f'a ray-cast lidar of {rays} rays'
    elif block.camera is not None:
        camera = block.camera
        kind = {'camera': 'a camera', 'depth': 'a depth camera', 'rgbd': 'an RGB-D camera'}
        what = f'{kind[block.kind]} of {camera.width}x{camera.height} pixels'
    elif block.kind == 'navsat':
        what = "a navsat (GPS) receiver, given the world's <spherical_coordinates>,"
    elif block.kind == 'contact':
        what = f'a contact sensor of collision {block.contact_collision!r}'
    elif block.kind == 'imu':
        what = 'an IMU'
    else:
        what = f'a {block.kind} sensor'
    return Finding(INFO, element, f'simulated as {what} at {rate} (docs/sensors.md)')


def _friction(tag, where):
    element = f'{where}<{tag.tag}>'
    try:
        mu = surface_friction({tag.tag: tag_text(tag)}, where)
    except ValueError as exc:
        return Finding(ERROR, element, str(exc).split(': ', 1)[-1])
    return Finding(INFO, element, f'contact friction {mu:g} (MuJoCo is isotropic: the smaller '
                   'of mu1 and mu2)')


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
