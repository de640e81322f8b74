# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Talker -> listener across two processes over DDS, and a clean Ctrl-C."""

import re
import time


def _heard(listener):
    return [int(n) for n in re.findall(r'I heard: "Hello World: (\d+)"\n', listener.output)]


def test_listener_hears_talker(ros_env, procs, exe):
    listener = procs.start([exe('listener')], ros_env)
    talker = procs.start([exe('talker')], ros_env)
    assert talker.wait_for_output('Publishing: "Hello World: 0"', timeout=60.0), talker.output
    assert listener.wait_for_output('I heard: "Hello World: ', timeout=60.0), listener.output
    deadline = time.monotonic() + 5.0  # the talker publishes every 0.5 s
    while len(_heard(listener)) < 3 and time.monotonic() < deadline:
        time.sleep(0.05)
    heard = _heard(listener)
    # reliable QoS: once matched, every message arrives, in order
    assert len(heard) >= 3 and heard == list(range(heard[0], heard[0] + len(heard))), heard
    assert listener.interrupt() == 0
    assert 'Traceback' not in listener.output


def test_talker_ctrl_c_exits_zero_without_traceback(ros_env, procs, exe):
    talker = procs.start([exe('talker')], ros_env)
    assert talker.wait_for_output('Publishing: "Hello World: 1"', timeout=60.0), talker.output
    assert talker.interrupt() == 0
    assert 'Traceback' not in talker.output
