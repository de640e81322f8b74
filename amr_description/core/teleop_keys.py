# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Keyboard -> velocity command mapping of ``teleop_twist_keyboard`` (pure, no rclpy).

Reproduces the key map and speed scaling of the upstream ROS 2 ``teleop_twist_keyboard``
(jazzy): a movement key sets direction factors ``(x, y, z, th)`` in {-1, 0, 1}; the command is
``linear = (x, y, z) * speed`` (m/s) and ``angular.z = th * turn`` (rad/s) in the robot's base
frame (REP 103: x forward, y left, z up, positive yaw counter-clockwise). Speed keys scale
``speed`` and/or ``turn`` and keep the current direction; any other key stops.
"""

from dataclasses import dataclass

#: key -> (x, y, z, th) direction factors; upper case = holonomic (strafing) variants.
MOVE_BINDINGS = {
    'i': (1, 0, 0, 0),
    'o': (1, 0, 0, -1),
    'j': (0, 0, 0, 1),
    'l': (0, 0, 0, -1),
    'u': (1, 0, 0, 1),
    ',': (-1, 0, 0, 0),
    '.': (-1, 0, 0, 1),
    'm': (-1, 0, 0, -1),
    'O': (1, -1, 0, 0),
    'I': (1, 0, 0, 0),
    'J': (0, 1, 0, 0),
    'L': (0, -1, 0, 0),
    'U': (1, 1, 0, 0),
    '<': (-1, 0, 0, 0),
    '>': (-1, -1, 0, 0),
    'M': (-1, 1, 0, 0),
    't': (0, 0, 1, 0),
    'b': (0, 0, -1, 0),
}

#: key -> (speed factor, turn factor).
SPEED_BINDINGS = {
    'q': (1.1, 1.1),
    'z': (0.9, 0.9),
    'w': (1.1, 1.0),
    'x': (0.9, 1.0),
    'e': (1.0, 1.1),
    'c': (1.0, 0.9),
}

#: Ctrl-C as read from a terminal in raw mode.
CTRL_C = '\x03'

#: how many speed changes are printed before the banner is shown again.
BANNER_EVERY = 15

BANNER = """
Reading from the keyboard and publishing to cmd_vel (Twist or TwistStamped).
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""


def format_speeds(speed, turn):
    """
    Return the status line printed after each speed change.

    :param speed: linear speed scale (m/s).
    :param turn: angular speed scale (rad/s).
    :returns: ``currently:``, ``speed <speed>``, ``turn <turn> `` separated by tabs (Python's
        str of the floats).
    """
    return 'currently:\tspeed %s\tturn %s ' % (speed, turn)


@dataclass
class TeleopState:
    """
    What the keyboard teleop remembers between key presses.

    :ivar speed: linear speed scale (m/s).
    :ivar turn: angular speed scale (rad/s).
    :ivar x: forward direction factor (-1, 0, 1).
    :ivar y: left direction factor.
    :ivar z: up direction factor.
    :ivar th: counter-clockwise yaw direction factor.
    :ivar status: speed changes since the banner was last printed (0..BANNER_EVERY-1).
    """

    speed: float = 0.5
    turn: float = 1.0
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    th: float = 0.0
    status: int = 0

    def twist(self):
        """
        Return the command for the current state.

        :returns: ``(linear_x, linear_y, linear_z, angular_z)`` in m/s and rad/s (angular x
            and y are always 0).
        """
        return (self.x * self.speed, self.y * self.speed, self.z * self.speed,
                self.th * self.turn)


@dataclass
class KeyResult:
    """
    What to do after a key press.

    :ivar finished: True for Ctrl-C (stop reading keys; the caller publishes zero and exits).
    :ivar publish: True when a twist must be published (every key except Ctrl-C).
    :ivar messages: lines to print, in order (speed status, sometimes the banner).
    """

    finished: bool = False
    publish: bool = True
    messages: tuple = ()


def apply_key(state, key):
    """
    Update ``state`` for one key press, as upstream teleop_twist_keyboard does.

    :param state: a :class:`TeleopState`, modified in place.
    :param key: the key read (a one-character str; ``''`` counts as "any other key").
    :returns: a :class:`KeyResult`.
    """
    if key in MOVE_BINDINGS:
        state.x, state.y, state.z, state.th = (float(v) for v in MOVE_BINDINGS[key])
        return KeyResult()
    if key in SPEED_BINDINGS:
        speed_factor, turn_factor = SPEED_BINDINGS[key]
        state.speed = state.speed * speed_factor
        state.turn = state.turn * turn_factor
        messages = [format_speeds(state.speed, state.turn)]
        if state.status == BANNER_EVERY - 1:
            messages.append(BANNER)
        state.status = (state.status + 1) % BANNER_EVERY
        return KeyResult(messages=tuple(messages))
    state.x = state.y = state.z = state.th = 0.0
    if key == CTRL_C:
        return KeyResult(finished=True, publish=False)
    return KeyResult()


def stop(state):
    """
    Zero the direction of ``state`` (key timeout or exit); speeds are kept.

    :param state: a :class:`TeleopState`, modified in place.
    """
    state.x = state.y = state.z = state.th = 0.0


def check_parameters(stamped, frame_id, speed, turn, key_timeout):
    """
    Validate the node parameters.

    :param stamped: publish TwistStamped (True) or Twist (False).
    :param frame_id: header frame of TwistStamped; must be empty when not stamped.
    :param speed: initial linear speed scale (m/s).
    :param turn: initial angular speed scale (rad/s).
    :param key_timeout: seconds without a key before a zero twist is sent (0 = off), >= 0.
    :raises ValueError: with a one-line message naming the parameter.
    """
    if frame_id and not stamped:
        raise ValueError("parameter 'frame_id' can only be set when 'stamped' is true")
    for name, value in (('speed', speed), ('turn', turn), ('key_timeout', key_timeout)):
        if not isinstance(value, (int, float)) or value != value:
            raise ValueError(f"parameter '{name}' must be a number, got {value!r}")
    if key_timeout < 0:
        raise ValueError(f"parameter 'key_timeout' must be >= 0 (0 = off), got {key_timeout}")
