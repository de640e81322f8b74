# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
What Nav2's lifecycle manager does for each ``nav2_msgs/srv/ManageLifecycleNodes`` command.

Pure logic (no rclpy). Source: ``nav2_lifecycle_manager/src/lifecycle_manager.cpp`` (Jazzy):
STARTUP configures every node, then activates every node, in ``node_names`` order; PAUSE
deactivates, RESUME activates, RESET deactivates then cleans up, SHUTDOWN deactivates, cleans
up and shuts down, CONFIGURE configures and CLEANUP cleans up. Deactivate, cleanup and shutdown
run in reverse ``node_names`` order, configure and activate in order. Each step is a
``lifecycle_msgs/msg/Transition`` id, the state the node must then be in, and the log line's
verb ("Configuring map_server").
"""

from dataclasses import dataclass

# lifecycle_msgs/msg/Transition ids and lifecycle_msgs/msg/State ids
CONFIGURE, CLEANUP, ACTIVATE, DEACTIVATE, UNCONFIGURED_SHUTDOWN = 1, 2, 3, 4, 5
INACTIVE_SHUTDOWN, ACTIVE_SHUTDOWN = 6, 7
UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED = 1, 2, 3, 4

# nav2_msgs/srv/ManageLifecycleNodes commands
STARTUP, PAUSE, RESUME, RESET, SHUTDOWN, CONFIGURE_COMMAND, CLEANUP_COMMAND = range(7)

GOAL_STATE = {CONFIGURE: INACTIVE, CLEANUP: UNCONFIGURED, ACTIVATE: ACTIVE,
              DEACTIVATE: INACTIVE, UNCONFIGURED_SHUTDOWN: FINALIZED}
"""The primary state a node must reach after each transition."""

VERB = {CONFIGURE: 'Configuring', CLEANUP: 'Cleaning up', ACTIVATE: 'Activating',
        DEACTIVATE: 'Deactivating', UNCONFIGURED_SHUTDOWN: 'Shutting down'}
"""The word Nav2's manager logs before a node's name for each transition."""

_IN_ORDER = (CONFIGURE, ACTIVATE)

_COMMANDS = {
    STARTUP: (CONFIGURE, ACTIVATE),
    PAUSE: (DEACTIVATE,),
    RESUME: (ACTIVATE,),
    RESET: (DEACTIVATE, CLEANUP),
    SHUTDOWN: (DEACTIVATE, CLEANUP, UNCONFIGURED_SHUTDOWN),
    CONFIGURE_COMMAND: (CONFIGURE,),
    CLEANUP_COMMAND: (CLEANUP,),
}

MESSAGES = {
    STARTUP: ('Starting managed nodes bringup...', 'Managed nodes are active'),
    PAUSE: ('Pausing managed nodes...', 'Managed nodes have been paused'),
    RESUME: ('Resuming managed nodes...', 'Managed nodes are active'),
    RESET: ('Resetting managed nodes...', 'Managed nodes have been reset'),
    SHUTDOWN: ('Shutting down managed nodes...', 'Managed nodes have been shut down'),
    CONFIGURE_COMMAND: ('Configuring managed nodes...', 'Managed nodes are now configured'),
    CLEANUP_COMMAND: ('Cleaning up managed nodes...', 'Managed nodes have been cleaned up'),
}
"""The lines Nav2's manager logs before and after each command."""

ACTIVE_AFTER = {STARTUP: True, RESUME: True, PAUSE: False, RESET: False, SHUTDOWN: False,
                CONFIGURE_COMMAND: False, CLEANUP_COMMAND: False}
"""Whether the managed system counts as active (``~/is_active``) after each command."""

TRANSITION_STATES = 10
"""lifecycle_msgs/msg/State ids from this one up are transition states (configuring, ...)."""


def settled(state_id, goal):
    """
    Tell from a node's ``get_state`` answer whether a transition without an answer has ended.

    rmw_fastrtps drops a service response whose client reader the server has not matched
    within 100 ms ("failed to send response ... (timeout)", ros2/rmw_fastrtps#706), so a
    ``change_state`` may never be answered although the node made the transition. A node in a
    primary state has finished its transition.

    :param state_id: ``current_state.id`` from ``get_state``, or None (no answer).
    :param goal: the primary state the transition leads to (:data:`GOAL_STATE`).
    :returns: None while the node is in a transition state or did not answer; otherwise
        whether the node is in ``goal``.
    """
    if state_id is None or not 0 < state_id < TRANSITION_STATES:
        return None
    return state_id == goal


@dataclass(frozen=True)
class Step:
    """One transition of one node: its name, the transition id and the state it must reach."""

    node: str
    transition: int
    goal: int

    @property
    def line(self):
        """Return the log line, e.g. ``Configuring map_server``."""
        return f'{VERB[self.transition]} {self.node}'


def plan(command, node_names):
    """
    Return the steps of ``command`` for ``node_names``.

    :param command: a ``ManageLifecycleNodes`` command (0..6).
    :param node_names: the managed nodes, in ``node_names`` order.
    :returns: a list of :class:`Step`.
    :raises ValueError: for an unknown command.
    """
    if command not in _COMMANDS:
        raise ValueError(f'unknown ManageLifecycleNodes command {command} (expected 0..6)')
    steps = []
    for transition in _COMMANDS[command]:
        names = node_names if transition in _IN_ORDER else list(reversed(node_names))
        steps.extend(Step(name, transition, GOAL_STATE[transition]) for name in names)
    return steps
