# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""A node's work on threads of its own: periodic, on request; errors one line, stop joins."""

import threading

from amr_description.ros.worker_threads import OnRequest
from amr_description.ros.worker_threads import Periodic


class _Log:

    def __init__(self):
        self.lines = []

    def error(self, text, throttle_duration_sec=None):
        self.lines.append(text)


def test_periodic_work_goes_on_after_an_error_and_stops_with_its_thread():
    log, calls, third = _Log(), [], threading.Event()

    def work():
        calls.append(len(calls))
        if len(calls) == 1:
            raise ValueError('bad stamp')
        if len(calls) == 3:
            third.set()

    worker = Periodic('test_periodic', 0.01, work, log, 'map -> odom not published')
    worker.start()
    assert third.wait(30.0)
    worker.stop()
    done = len(calls)
    assert log.lines == ['map -> odom not published: bad stamp']
    assert not worker._thread.is_alive() and len(calls) == done  # no call after stop()


def test_on_request_runs_once_per_burst_of_requests():
    log, calls = _Log(), []
    inside, release, finished = threading.Event(), threading.Event(), threading.Event()

    def work():
        calls.append(1)
        if len(calls) == 1:
            inside.set()
            release.wait(30.0)
        else:
            finished.set()

    worker = OnRequest('test_on_request', work, log, 'map not published')
    worker.start()
    worker.request()
    assert inside.wait(30.0)
    for _ in range(5):  # asked five times while the first run works: one more run
        worker.request()
    release.set()
    assert finished.wait(30.0)
    worker.stop()
    assert len(calls) == 2 and log.lines == [] and not worker._thread.is_alive()


def test_an_error_after_stop_ends_the_thread_without_a_line():
    log, started = _Log(), threading.Event()
    holder = {}

    def work():
        started.set()
        holder['worker']._stop.set()  # what stop() does first, as the node goes away
        raise RuntimeError('publisher destroyed')

    holder['worker'] = worker = OnRequest('test_stopping', work, log, 'map not published')
    worker.start()
    worker.request()
    assert started.wait(30.0)
    worker._thread.join(30.0)
    assert not worker._thread.is_alive() and log.lines == []
