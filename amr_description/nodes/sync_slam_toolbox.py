# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``sync_slam_toolbox_node``: slam_toolbox's online synchronous mapper, node ``slam_toolbox``.

As ``async_slam_toolbox_node`` (:mod:`.slam_toolbox`: lifecycle, parameters, topics, TF,
services), except in what happens to a scan. The asynchronous node matches each usable scan
as it arrives, so scans that come while it is busy are lost; this one loses none the mapper
would keep:

- the scan callback places the scan with TF and queues it when it passes slam_toolbox's
  ``shouldProcessScan`` (``throttle_scans``, ``minimum_time_interval`` since the last queued
  scan, and ``minimum_travel_distance`` or ``minimum_travel_heading`` moved in odometry since
  it);
- a processing thread gives the queued scans to the mapper in order, publishing ``pose`` for
  each, and warns "Queue size has grown to: N. ..." while more than 10 wait (the mapper is
  slower than the robot);
- ``slam_toolbox/clear_queue`` (slam_toolbox/srv/ClearQueue) empties the queue and answers
  ``status: true``.

Source: slam_toolbox 2.8.3 ``src/slam_toolbox_sync.cpp`` (``laserCallback``, ``run``,
``clearQueueCallback``), ``src/slam_toolbox_common.cpp`` (``shouldProcessScan``).
"""

import collections
import threading

from amr_description.nav import slam
from amr_description.nodes.slam_toolbox import SlamToolbox
from amr_description.ros import shutdown
from amr_description.ros.transforms import stamp_seconds
from slam_toolbox import srv

QUEUE_WARNING = 10
"""More queued scans than this give slam_toolbox's warning at each one processed."""


class SyncSlamToolbox(SlamToolbox):
    """Node ``slam_toolbox`` of ``sync_slam_toolbox_node``; see the module docstring."""

    def __init__(self):
        """Hold the params file's parameters; the node starts unconfigured."""
        super().__init__()
        self._queue = collections.deque()
        self._wake = threading.Condition()
        self._worker = None
        self._running = False
        self._last_queued = None  # odometry pose of the last queued scan

    def activate(self):
        """Create the asynchronous node's entities, ``clear_queue`` and the processing thread."""
        super().activate()
        self._active.append(self.create_service(srv.ClearQueue, 'slam_toolbox/clear_queue',
                                                self._on_clear_queue))
        self._running = True
        self._worker = threading.Thread(target=self._process_queue, name='slam_processing',
                                        daemon=True)
        self._worker.start()

    def deactivate(self):
        """Stop the processing thread, then destroy what :meth:`activate` created."""
        self._stop_worker()
        super().deactivate()

    def destroy_node(self):
        """Stop the processing thread before the node's publishers go (Ctrl-C)."""
        self._stop_worker()
        return super().destroy_node()

    def _stop_worker(self):
        """Stop the processing thread; a scan being matched is finished first."""
        with self._wake:
            self._running = False
            self._wake.notify()
        if self._worker is not None:
            self._worker.join()
            self._worker = None

    def cleanup(self):
        """Forget the queue and the map."""
        with self._wake:
            self._queue.clear()
        self._last_queued = None
        super().cleanup()

    def _use(self, odom, scan, header_stamp):
        """Queue the scan if slam_toolbox's ``shouldProcessScan`` passes it."""
        if self._last_queued is not None and not slam.moved_enough(self._last_queued, odom,
                                                                   self.params):
            return
        self._last_queued = odom
        self._last_processed = stamp_seconds(header_stamp)
        with self._wake:
            self._queue.append((odom, scan, header_stamp))
            self._wake.notify()

    def _process_queue(self):
        """Give the queued scans to the mapper in order until deactivated."""
        while True:
            with self._wake:
                while self._running and (not self._queue or self._interactive):
                    self._wake.wait()
                if not self._running:
                    return
                odom, scan, header_stamp = self._queue.popleft()
                waiting = len(self._queue)
            if waiting > QUEUE_WARNING:
                self.get_logger().warning(f'Queue size has grown to: {waiting}. Recommend '
                                          'stopping until message is gone if online mapping.')
            self._match(odom, scan, header_stamp)

    def _interactive_changed(self):
        """Wake the processing thread: it holds the queue while interactive mode is on."""
        with self._wake:
            self._wake.notify()

    def _on_reset(self, request, response):
        self._last_queued = None  # the new map starts with the next scan
        return super()._on_reset(request, response)

    def _on_clear_queue(self, request, response):
        self.get_logger().info('SynchronousSlamToolbox: Clearing all queued scans to add to '
                               'map.')
        with self._wake:
            self._queue.clear()
        response.status = True
        return response


def main(args=None):
    """
    Run the synchronous SLAM node until Ctrl-C (executor, TF and processing threads).

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(SyncSlamToolbox, args)


if __name__ == '__main__':
    main()
