# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""Talker -> listener across two processes over DDS, and a clean Ctrl-C."""

import re


def test_listener_hears_talker(ros_env, procs, exe):
    listener = procs.start([exe('listener')], ros_env)
    talker = procs.start([exe('talker')], ros_env)
    assert talker.wait_for_output('Publishing: "Hello World: 0"', timeout=10.0), talker.output
    assert listener.wait_for_output('I heard: "Hello World: ', timeout=10.0), listener.output
    heard = [int(n) for n in re.findall(r'I heard: "Hello World: (\d+)"', listener.output)]
    assert heard == sorted(heard)
    assert listener.interrupt() == 0
    assert 'Traceback' not in listener.output


def test_talker_ctrl_c_exits_zero_without_traceback(ros_env, procs, exe):
    talker = procs.start([exe('talker')], ros_env)
    assert talker.wait_for_output('Publishing: "Hello World: 1"', timeout=10.0), talker.output
    assert talker.interrupt() == 0
    assert 'Traceback' not in talker.output
