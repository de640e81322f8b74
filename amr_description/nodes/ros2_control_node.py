# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2_control_node``: a controller manager on its own, with a wall-clock control loop.

As upstream's ``controller_manager/ros2_control_node``: the
:class:`~amr_description.control.controller_manager.ControllerManager` of a robot description,
a thread running ``read -> update -> write`` at the manager's ``update_rate``, the executor
serving its services. In the simulator, ``mujoco_sim`` drives the same class from its
simulation thread instead. Run::

    ros2_control_node --urdf urdf/amr.urdf --params config/controllers.yaml --mock-hardware
"""

import argparse
import os
import sys
import threading
import time as _time

from amr_description.control.controller_manager import ControllerManager
import rclpy
from rclpy.executors import ExternalShutdownException


def _mock_factory(info):
    from amr_description.control.generic_system import GenericSystem
    return GenericSystem()


def main(args=None):
    """
    Run a controller manager standalone (ros2_control_node), wall-clock loop.

    Options: ``--urdf FILE`` (required), ``--params FILE`` (controllers YAML),
    ``--mock-hardware`` (every component is ``mock_components/GenericSystem``),
    ``--use-sim-time``; ROS arguments after ``--ros-args``.

    :returns: exit code: 0 after Ctrl-C, 1 on a configuration error (one line).
    """
    argv = sys.argv[1:] if args is None else list(args)
    ros_args = argv[argv.index('--ros-args'):] if '--ros-args' in argv else []
    own = argv[:len(argv) - len(ros_args)]
    parser = argparse.ArgumentParser(prog='controller_manager')
    parser.add_argument('--urdf', required=True, help='robot description (URDF file)')
    parser.add_argument('--params', default=None, help='controllers YAML file')
    parser.add_argument('--mock-hardware', action='store_true',
                        help='replace every hardware plugin by mock_components/GenericSystem')
    parser.add_argument('--use-sim-time', action='store_true')
    parser.add_argument('-n', '--namespace', default='')
    opts = parser.parse_args(own)
    try:
        with open(opts.urdf, 'r') as f:
            urdf = f.read()
    except OSError as exc:
        print(f'controller_manager: cannot read {opts.urdf}: {exc.strerror}', file=sys.stderr)
        return 1
    from amr_description.core.description.robot_description import RobotDescription
    try:  # parsed once: the resource manager and the controllers read this one parse
        urdf = RobotDescription(urdf, source=opts.urdf)
    except ValueError as exc:
        print(f'controller_manager: {str(exc).splitlines()[0]}', file=sys.stderr)
        return 1
    rclpy.init(args=['controller_manager'] + ros_args)
    executor = rclpy.executors.MultiThreadedExecutor(num_threads=2)
    cm = None
    thread = None
    stop = threading.Event()
    try:
        try:
            cm = ControllerManager(
                urdf, executor, _mock_factory if opts.mock_hardware else None,
                opts.params, opts.namespace, use_sim_time=opts.use_sim_time)
        except ValueError as exc:
            print(f'controller_manager: {exc}', file=sys.stderr)
            return 1

        def loop():
            period = 1.0 / cm.update_rate
            start = _time.monotonic()
            previous = 0.0
            k = 0
            while not stop.is_set() and cm.context.ok():
                k += 1
                target = start + k * period
                delay = target - _time.monotonic()
                if delay > 0:
                    stop.wait(delay)
                now = _time.monotonic() - start
                t = cm.get_clock().now().nanoseconds * 1e-9 if opts.use_sim_time else \
                    _time.time()
                cm.read(t, now - previous)
                cm.update(t, now - previous)
                cm.write(t, now - previous)
                previous = now

        thread = threading.Thread(target=loop, daemon=True)
        thread.start()
        cm.get_logger().info(f'update rate is {cm.update_rate} Hz')
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        stop.set()
        if thread is not None:
            thread.join(timeout=2.0)
        if cm is not None:
            cm.destroy()
        executor.shutdown()
        if rclpy.ok():
            rclpy.try_shutdown()
    return 0


if __name__ == '__main__':
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    sys.exit(main())
