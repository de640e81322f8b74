# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``render``: draw the robot headless to a PNG, from a URDF file or ``/robot_description``.

``ros2 run amr_description render [--urdf PATH] [-o out.png] [--width W] [--height H]
[--frames] [--world WORLD] [--timeout S]``; ``--world`` draws the robot at the origin of an
SDF world (as the sim stack spawns it) with the whole world in view. Without ``--urdf`` a
short-lived node ``render`` takes the model from the ``/robot_description`` topic
(std_msgs/String, transient local, as published by robot_state_publisher). The picture
itself: :mod:`amr_description.sim.render`.
"""

import argparse
import os
import sys
import time


def _parse(argv):
    """Parse the non-ROS arguments."""
    parser = argparse.ArgumentParser(prog='render', description='Render the robot to a PNG '
                                     '(MuJoCo, headless).')
    parser.add_argument('--urdf', metavar='PATH', help='URDF file (default: the '
                        '/robot_description topic)')
    parser.add_argument('-o', '--output', default='robot.png', help='PNG file (robot.png)')
    parser.add_argument('--width', type=int, default=640, help='pixels (640)')
    parser.add_argument('--height', type=int, default=480, help='pixels (480)')
    parser.add_argument('--frames', action='store_true', help='draw the link frame axes')
    parser.add_argument('--world', metavar='WORLD', default=None,
                        help='draw the robot at the origin of an SDF world: a shipped world '
                        '(empty, arena, warehouse), a file or a package:// URI')
    parser.add_argument('--timeout', type=float, default=10.0,
                        help='seconds to wait for /robot_description (10)')
    return parser.parse_args(argv)


def _description_from_topic(args, timeout):
    """
    Return the first /robot_description message's data, or None after ``timeout`` s.

    A short-lived node ``render`` in the clean-shutdown pattern of
    :mod:`amr_description.ros.shutdown` (bad ROS arguments: one line, exit code 1).
    """
    from amr_description.ros import shutdown
    from amr_description.ros.node import Node
    from rclpy.qos import DurabilityPolicy
    from rclpy.qos import QoSProfile
    from std_msgs.msg import String

    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    node = None
    received = []
    try:
        shutdown.init(args)
        node = shutdown.create(Node, 'render')
        node.create_subscription(
            String, 'robot_description', lambda msg: received.append(msg.data),
            QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        deadline = time.monotonic() + timeout
        shutdown.spin(node, until=lambda: received or time.monotonic() > deadline)
    finally:
        shutdown.shutdown(node)
    return received[0] if received else None


def main(args=None):
    """
    Render the robot and write the PNG.

    :param args: full argument list including ROS arguments (default ``sys.argv``).
    :returns: 0 on success, 1 on a bad URDF, a missing description or an unwritable file
        (one-line error on stderr).
    """
    from amr_description.ros import shutdown

    argv = sys.argv if args is None else args
    options = _parse(shutdown.remove_ros_args(argv)[1:])
    try:
        if options.urdf:
            from amr_description.core.description.files import read_description
            urdf_xml = read_description(options.urdf)  # a URDF, or a xacro expanded
        else:
            urdf_xml = _description_from_topic(argv, options.timeout)
            if urdf_xml is None:
                raise ValueError(f'no message on /robot_description within {options.timeout:g} s '
                                 '(it reads a running stack, e.g. ros2 launch amr_description '
                                 'display; or give a file with --urdf PATH)')
        from amr_description.core.description.urdf_model import parse_urdf
        from amr_description.sim.render import render_urdf
        from amr_description.sim.render import save_png
        # the package's one loader: what robot_state_publisher and the simulator refuse is
        # refused here too, before any pixel is drawn or file written
        parse_urdf(urdf_xml, source=options.urdf or '/robot_description')
        world = None
        if options.world:
            from amr_description.core.gazebo.sdf_world import collapse_repeats
            from amr_description.core.gazebo.sdf_world import load_world
            world = load_world(options.world)  # WorldError (a ValueError): one line
            for line in collapse_repeats(world.messages):
                print(f'render: {line}', file=sys.stderr)
        image = render_urdf(urdf_xml, options.width, options.height, options.frames, world)
        save_png(image, options.output)
    except KeyboardInterrupt:
        return 1
    except ValueError as exc:
        print(f'render: {" ".join(str(exc).split())}', file=sys.stderr)
        return 1
    print(f'wrote {options.output} ({options.width}x{options.height})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
