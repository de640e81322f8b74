# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The Gazebo dialect of a URDF that the simulator reads: gz_ros2_control's names and plugin.

As gz_ros2_control (jazzy): the ``<ros2_control>`` hardware plugins
``gz_ros2_control/GazeboSimSystem`` and ``ign_ros2_control/IgnitionSystem`` are the
simulator's own hardware component (:data:`SIMULATOR_SYSTEMS`), and a ``<gazebo><plugin>``
whose ``filename`` is one of :data:`CONTROL_PLUGIN_FILES` (or whose ``name`` is one of
:data:`CONTROL_PLUGIN_NAMES`) starts the robot's controller manager with its children
(``GazeboSimROS2ControlPlugin::Configure``): every ``<parameters>`` file in document order
(a later file overrides an earlier one), ``<controller_manager_name>`` (default
``controller_manager``), ``<ros><namespace>`` and every ``<ros><remapping>``,
``<hold_joints>`` (default true) and ``<position_proportional_gain>`` (default 0.1). Both the
text form and a ``value="..."`` attribute are read.
"""

from dataclasses import dataclass
from dataclasses import field

SIMULATOR_SYSTEMS = ('amr_description/MujocoSystem', 'gz_ros2_control/GazeboSimSystem',
                     'ign_ros2_control/IgnitionSystem')
"""``<hardware><plugin>`` names that select the simulator's hardware component."""

GAZEBO_SYSTEMS = SIMULATOR_SYSTEMS[1:]
"""gz_ros2_control's hardware plugin names: the component then commands its joints as
gz_ros2_control does (:mod:`amr_description.sim.mujoco_system`)."""

CONTROL_PLUGIN_FILES = ('gz_ros2_control-system', 'libgz_ros2_control-system.so',
                        'libign_ros2_control-system.so', 'ign_ros2_control-system')
"""``<gazebo><plugin filename>`` values of gz_ros2_control's system plugin."""

CONTROL_PLUGIN_NAMES = ('gz_ros2_control::GazeboSimROS2ControlPlugin',
                        'ign_ros2_control::IgnitionROS2ControlPlugin')
"""``<gazebo><plugin name>`` values of gz_ros2_control's system plugin."""


@dataclass
class ControlPlugin:
    """
    The gz_ros2_control ``<gazebo><plugin>`` of a robot description.

    :param parameters: the ``<parameters>`` files, document order (URIs as written).
    :param controller_manager_name: the controller manager's node name.
    :param namespace: ``<ros><namespace>``, '' for none (a leading ``/`` is added).
    :param remappings: ``<ros><remapping>`` rules, e.g. ``['/tf:=tf']``.
    :param hold_joints: hold joints no controller commands (velocity 0).
    :param position_proportional_gain: the gain of position commands.
    """

    parameters: list = field(default_factory=list)
    controller_manager_name: str = 'controller_manager'
    namespace: str = ''
    remappings: list = field(default_factory=list)
    hold_joints: bool = True
    position_proportional_gain: float = 0.1


def tag_text(element):
    """
    Return the value of a Gazebo tag: its ``value`` attribute or its text, stripped.

    As sdformat 14's URDF reader: the attribute wins over the text (``<mu1 value="0.5"/>``).
    """
    value = element.get('value')
    return (value if value is not None else element.text or '').strip()


def tag_bool(element, where):
    """
    Return the boolean value of a Gazebo tag (``true``/``1``/``yes``, ``false``/``0``/``no``).

    :raises ValueError: one line naming ``where`` for any other value.
    """
    return text_bool(tag_text(element), where)


def text_bool(text, where):
    """
    Return the boolean a tag's value means, as sdformat reads it (``true``/``1``/``yes``).

    :raises ValueError: one line naming ``where`` for anything but those and ``false``/``0``/
        ``no``.
    """
    value = text.strip().lower()
    if value in ('true', '1', 'yes'):
        return True
    if value in ('false', '0', 'no'):
        return False
    raise ValueError(f'{where}: expected true or false, found {text!r}')


def is_control_plugin(plugin):
    """Return True when a ``<plugin>`` element is gz_ros2_control's system plugin."""
    return (plugin.get('filename') or '').strip() in CONTROL_PLUGIN_FILES or \
        (plugin.get('name') or '').strip() in CONTROL_PLUGIN_NAMES


def parse_control_plugin(root):
    """
    Return the :class:`ControlPlugin` of a URDF ``<robot>`` element, or None without one.

    :param root: the ``<robot>`` element (standard library or lxml).
    :raises ValueError: one line naming the element: no (or an empty) ``<parameters>``, a
        ``<hold_joints>`` that is not a boolean, a gain that is not a number.
    """
    for gazebo in root.findall('gazebo'):
        for plugin in gazebo.findall('plugin'):
            if is_control_plugin(plugin):
                return _read_plugin(plugin)
    return None


def _read_plugin(plugin):
    where = f"<gazebo><plugin name=\"{plugin.get('name', '')}\">"
    result = ControlPlugin()
    result.parameters = [tag_text(p) for p in plugin.findall('parameters')]
    if not result.parameters or not all(result.parameters):
        raise ValueError(f'{where}: <parameters> (the controllers YAML) is required and must '
                         'not be empty, as gz_ros2_control needs it')
    element = plugin.find('controller_manager_name')
    if element is not None and tag_text(element):
        result.controller_manager_name = tag_text(element)
    ros = plugin.find('ros')
    if ros is not None:
        namespace = ros.find('namespace')
        if namespace is not None and tag_text(namespace).strip('/'):
            result.namespace = '/' + tag_text(namespace).strip('/')
        result.remappings = [tag_text(r) for r in ros.findall('remapping') if tag_text(r)]
    element = plugin.find('hold_joints')
    if element is not None:
        result.hold_joints = tag_bool(element, f'{where}<hold_joints>')
    element = plugin.find('position_proportional_gain')
    if element is not None:
        try:
            result.position_proportional_gain = float(tag_text(element))
        except ValueError:
            raise ValueError(f'{where}<position_proportional_gain>: expected a number, found '
                             f'{tag_text(element)!r}') from None
    return result


KEPT_JOINT_TAGS = ('preserveFixedJoint', 'disableFixedJointLumping')
"""``<gazebo reference="joint">`` tags that are what the simulator does anyway: every link
keeps its own body and frame (no fixed-joint lumping), so a sensor or a TF frame on a link
merged away in Gazebo is still there."""

VISUAL_TAGS = ('visual',)
"""``<gazebo reference>`` blobs of Gazebo's renderer that the simulator does not read."""

GAZEBO_MATERIALS = {
    'Gazebo/Grey': (0.7, 0.7, 0.7, 1.0), 'Gazebo/Gray': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/DarkGrey': (0.175, 0.175, 0.175, 1.0), 'Gazebo/DarkGray': (0.175, 0.175, 0.175, 1.0),
    'Gazebo/White': (1.0, 1.0, 1.0, 1.0), 'Gazebo/WhiteGlow': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/FlatBlack': (0.1, 0.1, 0.1, 1.0), 'Gazebo/Black': (0.0, 0.0, 0.0, 1.0),
    'Gazebo/Red': (1.0, 0.0, 0.0, 1.0), 'Gazebo/RedGlow': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/RedBright': (0.87, 0.26, 0.07, 1.0),
    'Gazebo/Green': (0.0, 1.0, 0.0, 1.0), 'Gazebo/GreenGlow': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/Blue': (0.0, 0.0, 1.0, 1.0), 'Gazebo/BlueGlow': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/SkyBlue': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/Yellow': (1.0, 1.0, 0.0, 1.0), 'Gazebo/YellowGlow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/ZincYellow': (0.9725, 0.9529, 0.2078, 1.0), 'Gazebo/DarkYellow': (0.7, 0.7, 0.0, 1.0),
    'Gazebo/Purple': (1.0, 0.0, 1.0, 1.0), 'Gazebo/PurpleGlow': (1.0, 0.0, 1.0, 1.0),
    'Gazebo/Turquoise': (0.0, 1.0, 1.0, 1.0), 'Gazebo/TurquoiseGlow': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/Orange': (1.0, 0.5088, 0.0468, 1.0), 'Gazebo/Indigo': (0.33, 0.0, 0.5, 1.0),
    'Gazebo/Gold': (0.8, 0.64869, 0.120759, 1.0),
    'Gazebo/RedTransparent': (1.0, 0.0, 0.0, 0.5), 'Gazebo/GreenTransparent': (0.0, 1.0, 0.0, 0.5),
    'Gazebo/BlueTransparent': (0.0, 0.0, 1.0, 0.5), 'Gazebo/GreyTransparent': (0.5, 0.5, 0.5, 0.5),
    'Gazebo/BlackTransparent': (0.0, 0.0, 0.0, 0.5),
    'Gazebo/YellowTransparent': (1.0, 1.0, 0.0, 0.5),
    'Gazebo/DarkMagentaTransparent': (0.6, 0.0, 0.6, 0.5),
    'Gazebo/OrangeTransparent': (1.0, 0.44, 0.0, 0.6),
}
"""Diffuse colours (rgba) of the solid ``Gazebo/*`` script materials, as gz-sim 8 gives a
visual from its built-in ``gazebo.material`` (``src/rendering/MaterialParser``; glow variants
take their base colour; a transparent one its overlay alpha). Textured ones (``Gazebo/Wood``,
...) are not listed."""


def gazebo_material(tags, where):
    """
    Return the colour a link's ``<gazebo reference><material>`` gives its visuals, or None.

    As sdformat 14 (the tag becomes each visual's ``material/script/name``, overriding the
    URDF ``<material>``) and gz-sim 8 (:data:`GAZEBO_MATERIALS`).

    :param tags: dict tag -> value of one ``<gazebo reference>`` link.
    :param where: what messages name (``<gazebo reference="base_link">``).
    :returns: ``(rgba, None)``, ``(None, None)`` without the tag, or ``(None, line)`` for a
        material the simulator does not know (the URDF colour stays; the line says so).
    """
    name = tags.get('material')
    if not name:
        return None, None
    if name in GAZEBO_MATERIALS:
        return GAZEBO_MATERIALS[name], None
    return None, f'{where}<material>: {name!r} is not a solid Gazebo material: the URDF ' \
        'colour is used'


GRAVITY_TAGS = ('gravity', 'turnGravityOff')
"""``<gazebo reference="link">`` tags that switch gravity off for the link."""


def link_gravity(tags, where):
    """
    Return False when a link's ``<gazebo reference>`` turns gravity off, else True.

    sdformat 14: ``<turnGravityOff>true`` becomes the link's ``<gravity>false``; a
    ``<gravity>`` tag is copied as is. The simulator cancels gravity on such a link's body
    (MuJoCo ``gravcomp`` 1).

    :raises ValueError: one line naming the tag when its value is not a boolean.
    """
    gravity = True
    for tag, off_when in zip(GRAVITY_TAGS, (False, True)):
        if tag in tags and text_bool(tags[tag], f'{where}<{tag}>') == off_when:
            gravity = False
    return gravity


FRICTION_TAGS = ('mu1', 'mu2')
"""``<gazebo reference>`` tags the simulator maps to contact friction."""

IGNORED_AS_HARMONIC = ('fdir1', 'kp', 'kd', 'minDepth', 'maxVel', 'maxContacts', 'laserRetro',
                       'stopCfm', 'stopErp', 'provideFeedback', 'implicitSpringDamper',
                       'cfmDamping', 'fudgeFactor', 'dampingFactor')
"""``<gazebo reference>`` tags read and ignored: Harmonic's default engine (DART) ignores them
too (gz-physics 7 ``dartsim/src/SDFFeatures.cc``; ``dampingFactor``, sdformat's link
``velocity_decay``: gz-physics#635, open); ``fdir1`` is ignored as MuJoCo's contact
friction is isotropic."""


def parse_reference_tags(root):
    """
    Return the ``<gazebo reference="...">`` tags of a URDF, per reference.

    As sdformat 14's URDF reader: blocks are merged per reference in document order (a later
    tag overrides an earlier one), a value is the ``value`` attribute or the text. Tags with
    children (``<sensor>``, ``<plugin>``, ``<visual>``) are left out.

    :param root: the ``<robot>`` element.
    :returns: dict reference (link or joint name) -> dict tag -> value (str).
    """
    tags = {}
    for gazebo in root.findall('gazebo'):
        reference = gazebo.get('reference')
        if not reference:
            continue
        for child in gazebo:
            if isinstance(child.tag, str) and len(child) == 0:
                tags.setdefault(reference, {})[child.tag] = tag_text(child)
    return tags


def surface_friction(tags, where):
    """
    Return the MuJoCo sliding friction of one link's Gazebo tags, or None without mu1/mu2.

    Gazebo's friction pyramid has ``mu1`` along ``fdir1`` and ``mu2`` across; MuJoCo's
    contact friction is isotropic, so the smaller one is taken (the direction that slips
    first); one given alone stands for both. With the ground, Gazebo (ODE and DART) combines
    the two surfaces' coefficients by their minimum, and the Gazebo ground is rougher (mu
    100 in gz-sim's ``empty.sdf``), so the link's value is the contact's: the converter gives
    such a geom MuJoCo's contact priority.

    :param tags: dict tag -> value of one ``<gazebo reference>`` link.
    :param where: what errors name (``<gazebo reference="caster">``).
    :raises ValueError: one line when mu1 or mu2 is not a number >= 0.
    """
    values = []
    for tag in FRICTION_TAGS:
        if tag in tags:
            try:
                value = float(tags[tag])
            except ValueError:
                value = -1.0
            if not value >= 0.0 or value == float('inf'):
                raise ValueError(f'{where}<{tag}>: expected a number >= 0, found '
                                 f'{tags[tag]!r}')
            values.append(value)
    return min(values) if values else None


def apply_surface_tags(config, tags, model):
    """
    Give every link with ``mu1``/``mu2`` tags its friction, unless ``<mujoco>`` sets one.

    :param config: the :class:`~amr_description.core.description.mujoco_block.MujocoConfig`
        (changed in place: ``link_contact[link]`` gets ``friction`` and ``priority`` 1).
    :param tags: :func:`parse_reference_tags`.
    :param model: the :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :raises ValueError: as :func:`surface_friction`.
    """
    for reference, link_tags in tags.items():
        if reference not in model.links:
            continue
        mu = surface_friction(link_tags, f'<gazebo reference="{reference}">')
        contact = config.link_contact.get(reference, {})
        if mu is None or 'friction' in contact:
            continue
        contact = dict(contact, friction=(mu,) + tuple(config.contact['friction'][1:]),
                       priority=1)
        config.link_contact[reference] = contact
