# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Command line of ``static_transform_publisher`` (pure, no rclpy).

Reproduces the argument rules of tf2_ros' ``static_transform_publisher`` program (ROS 2
Jazzy): flags ``--x --y --z`` (translation, m), ``--qx --qy --qz --qw`` (rotation as a
quaternion, taken as given) or ``--roll --pitch --yaw`` (rad, fixed axes: ``Rz(yaw) Ry(pitch)
Rx(roll)``, tf2's ``Quaternion::setRPY``), ``--frame-id`` and ``--child-frame-id``; the
deprecated positional forms ``x y z yaw pitch roll frame child`` (8 values) and ``x y z qx
qy qz qw frame child`` (9 values) with a warning; ``-h``/``--help``. Without a translation or
rotation the identity is published. The error texts are upstream's.
"""

from dataclasses import dataclass
from dataclasses import field
import math

USAGE = (
    'usage: static_transform_publisher [--x X] [--y Y] [--z Z] [--qx QX] [--qy QY] '
    '[--qz QZ] [--qw QW] [--roll ROLL] [--pitch PITCH] [--yaw YAW] --frame-id FRAME_ID '
    '--child-frame-id CHILD_FRAME_ID\n\n'
    'A command line utility for manually sending a static transform.\n\n'
    'If no translation or orientation is provided, the identity transform will be '
    'published.\n\n'
    'The translation offsets are in meters.\n\n'
    'The rotation may be provided with roll, pitch, yaw euler angles in radians, or as a '
    'quaternion.\n\n'
    'required arguments:\n'
    '  --frame-id FRAME_ID parent frame\n'
    '  --child-frame-id CHILD_FRAME_ID child frame id\n\n'
    'optional arguments:\n'
    '  --x X                 x component of translation\n'
    '  --y Y                 y component of translation\n'
    '  --z Z                 z component of translation\n'
    '  --qx QX               x component of quaternion rotation\n'
    '  --qy QY               y component of quaternion rotation\n'
    '  --qz QZ               z component of quaternion rotation\n'
    '  --qw QW               w component of quaternion rotation\n'
    '  --roll ROLL           roll component Euler rotation\n'
    '  --pitch PITCH         pitch component Euler rotation\n'
    '  --yaw YAW             yaw component Euler rotation')

OLD_STYLE_WARNING = 'Old-style arguments are deprecated; see --help for new-style arguments'

_TRANSLATION = {'--x': 0, '--y': 1, '--z': 2}
_QUATERNION = {'--qx': 0, '--qy': 1, '--qz': 2, '--qw': 3}
_RPY = {'--roll': 0, '--pitch': 1, '--yaw': 2}
_FRAMES = ('--frame-id', '--child-frame-id')


@dataclass
class StaticTransform:
    """
    A parsed command line.

    :ivar translation: ``[x, y, z]`` in m, parent frame.
    :ivar rotation: quaternion ``[x, y, z, w]`` of the child frame in the parent frame.
    :ivar frame_id: parent frame.
    :ivar child_frame_id: child frame.
    :ivar help: ``-h``/``--help`` was given (nothing else is checked then).
    :ivar warnings: lines to log as warnings (the deprecated positional form).
    """

    translation: list = field(default_factory=lambda: [0.0, 0.0, 0.0])
    rotation: list = field(default_factory=lambda: [0.0, 0.0, 0.0, 1.0])
    frame_id: str = ''
    child_frame_id: str = ''
    help: bool = False  # noqa: A003 - the flag's own name
    warnings: list = field(default_factory=list)


def quaternion_from_rpy(roll, pitch, yaw):
    """
    Return the quaternion ``[x, y, z, w]`` of fixed-axis roll, pitch, yaw (rad).

    The rotation is ``Rz(yaw) @ Ry(pitch) @ Rx(roll)`` (REP 103; tf2 ``Quaternion::setRPY``,
    URDF ``rpy``), written with half angles.
    """
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return [sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy]


def _number(name, text):
    try:
        return float(text)
    except ValueError:
        raise ValueError(f'Failed to parse {name} argument as float') from None


def parse(args):
    """
    Parse the program's arguments (ROS arguments already removed, program name excluded).

    :param args: list of str.
    :returns: :class:`StaticTransform`.
    :raises ValueError: upstream's one-line reason, e.g. ``Frame id must not be empty``.
    """
    result = StaticTransform()
    rpy = [0.0, 0.0, 0.0]
    seen = set()  # 'frame', 'translation', 'quaternion', 'rpy'
    positional = []
    i = 0
    while i < len(args):
        name = args[i]
        if name in ('-h', '--help'):
            result.help = True
            i += 1
            continue
        if name not in _TRANSLATION and name not in _QUATERNION and name not in _RPY and \
                name not in _FRAMES:
            positional.append(name)
            i += 1
            continue
        if i == len(args) - 1:
            raise ValueError(f'Not enough arguments for {name}')
        value = args[i + 1]
        if name in _TRANSLATION:
            result.translation[_TRANSLATION[name]] = _number(name, value)
            seen.add('translation')
        elif name in _QUATERNION:
            result.rotation[_QUATERNION[name]] = _number(name, value)
            seen.add('quaternion')
        elif name in _RPY:
            rpy[_RPY[name]] = _number(name, value)
            seen.add('rpy')
        else:
            setattr(result, 'frame_id' if name == '--frame-id' else 'child_frame_id', value)
            seen.add('frame')
        i += 2
    if result.help:
        return result
    if 'rpy' in seen and 'quaternion' in seen:
        raise ValueError('Cannot specify both quaternion and Euler rotations')
    if 'rpy' in seen:
        result.rotation = quaternion_from_rpy(*rpy)
    if len(positional) in (8, 9):
        result.warnings.append(OLD_STYLE_WARNING)
        if seen & {'frame', 'translation', 'quaternion'}:
            raise ValueError('Cannot specify both new-style (flags) and old-style (arguments)')
        result.translation = [_number(n, v) for n, v in zip('xyz', positional[:3])]
        if len(positional) == 8:
            yaw, pitch, roll = (_number(n, v)
                                for n, v in zip(('yaw', 'pitch', 'roll'), positional[3:6]))
            result.rotation = quaternion_from_rpy(roll, pitch, yaw)
        else:
            result.rotation = [_number(n, v)
                               for n, v in zip(('qx', 'qy', 'qz', 'qw'), positional[3:7])]
        result.frame_id, result.child_frame_id = positional[-2], positional[-1]
    elif positional:
        raise ValueError('Extra unparsed arguments on command-line')
    if not result.frame_id:
        raise ValueError('Frame id must not be empty')
    if not result.child_frame_id:
        raise ValueError('Child frame id must not be empty')
    return result
