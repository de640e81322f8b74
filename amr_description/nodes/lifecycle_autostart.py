# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What a launch file's lifecycle events do: configure, then activate, a lifecycle node.

slam_toolbox's ``online_async_launch.py`` (with ``autostart`` and no lifecycle manager)
emits ``ChangeState(TRANSITION_CONFIGURE)`` and, on the node reaching *inactive*,
``TRANSITION_ACTIVATE``; launch_ros does it through a node of its own named
``launch_ros_<pid>``. This program is that node for our stacks: ``lifecycle_autostart NODE
[TRANSITION ...]`` (default ``configure activate``) waits up to 60 s for
``NODE/change_state``, requests each transition in turn and exits 0, or 1 with one line
naming the node and the transition that failed.
"""

import os
import sys

from amr_description.ros import shutdown
from amr_description.ros.node import Node
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
import rclpy

SERVICE_WAIT = 60.0
TRANSITIONS = {'configure': Transition.TRANSITION_CONFIGURE,
               'activate': Transition.TRANSITION_ACTIVATE}


def main(args=None):
    """Run the transitions (see the module docstring); return the exit code."""
    argv = shutdown.remove_ros_args(args if args is not None else sys.argv)[1:]
    if not argv or any(t not in TRANSITIONS for t in argv[1:]):
        print('usage: lifecycle_autostart NODE [configure|activate ...]', file=sys.stderr)
        return 2
    target, steps = argv[0], argv[1:] or ['configure', 'activate']
    shutdown.init(args)
    node = Node(f'launch_ros_{os.getpid()}')
    code = 0
    try:
        client = node.create_client(ChangeState, f'{target}/change_state')
        if not client.wait_for_service(timeout_sec=SERVICE_WAIT):
            shutdown.fail('lifecycle_autostart',
                          f'{target}/change_state not offered after {SERVICE_WAIT:g} s')
        for step in steps:
            future = client.call_async(ChangeState.Request(
                transition=Transition(id=TRANSITIONS[step])))
            rclpy.spin_until_future_complete(node, future, timeout_sec=SERVICE_WAIT)
            if not future.done() or not future.result().success:
                shutdown.fail('lifecycle_autostart', f"{target}: transition '{step}' failed")
    except KeyboardInterrupt:
        code = 130
    finally:
        shutdown.shutdown(node)
    return code


if __name__ == '__main__':
    sys.exit(main())
