# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Helper of the stand-in tests: a node in its own rclpy context, spun by a daemon thread.

A stand-in plays a server (a simulator's services, a spawn service) inside the test process,
so that a test can make it misbehave on purpose, while the program under test runs as a real
process on the same ROS domain.
"""

import threading


class StandIn:
    """
    A node ``name`` on ``domain_id`` in a context of its own.

    Subclasses create their publishers, services and timers on :attr:`node`, then call
    :meth:`start`. Callbacks run on the spinning thread, one at a time.
    """

    def __init__(self, name, domain_id):
        """Initialise the context and create the node and its executor (not yet spinning)."""
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.rclpy = rclpy
        self.context = rclpy.Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node(name, context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.thread = threading.Thread(target=self._spin, daemon=True)

    def start(self):
        """Start spinning the node on a daemon thread."""
        self.thread.start()

    def _spin(self):
        while self.context.ok():
            try:
                self.executor.spin_once(timeout_sec=0.1)
            except Exception:  # noqa: B902 - the context shut down
                break

    def close(self):
        """Stop spinning, destroy the node and shut the context down."""
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)
