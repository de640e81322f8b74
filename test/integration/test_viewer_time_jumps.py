# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 bag play --clock`` beside a running sim stack and its viewer (a real browser).

The bag's /clock is older than the simulator's: /clock then jumps back and forth while the bag
plays. The viewer clears its dynamic transforms on each jump back, as tf2's listener does,
keeps the static ones (/tf_static is published once), says so in its status, and once the
bag has ended draws the robot again: no "No transform to" stays on the page.
"""

import re
import time

from amr_description.nodes.mujoco_sim.clock import CLOCK_WATCH_TIME
from browser import ensure_chromium  # noqa: I100 - helpers next to this file
from browser import free_port
from browser import open_page

TOPICS = ('/clock', '/tf', '/tf_static', '/joint_states')


def _sim_time(text):
    """Return the sim time the viewer's status shows (s), or None."""
    found = re.search(r'Sim time ([0-9.]+) s', text)
    return float(found.group(1)) if found else None


def test_bag_play_clock_beside_the_viewer_leaves_it_with_its_transforms(
        procs, exe, ros_env, tmp_path):
    assert ensure_chromium(), 'Debian chromium is missing: run scripts/setup'
    port = free_port()
    stack = procs.start([exe('bringup'), 'sim', f'viewer_port:={port}'], ros_env)
    assert stack.wait_for_output(f'viewer: open http://127.0.0.1:{port}/ in a browser', 180.0), \
        stack.output[-3000:]
    bag = tmp_path / 'run1'
    record = procs.start([exe('ros2'), 'bag', 'record', '-o', str(bag), '--use-sim-time',
                          '--max-duration', '3', *TOPICS], ros_env)
    assert record.wait(240.0) == 0, record.output + stack.output[-2000:]
    with open_page(f'http://127.0.0.1:{port}/') as page:
        assert page.wait_for_text('Fixed Frame', 120.0), page.page.inner_text('body')

        def posed():
            text = page.page.inner_text('body')
            return 'Sim time' in text and 'No transform to' not in text and \
                'Waiting for' not in text

        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and not posed():
            page.page.wait_for_timeout(500)
        assert posed(), page.page.inner_text('body')
        # a second /clock publisher in the simulator's first CLOCK_WATCH_TIME s (wall) makes it
        # refuse to run on (one clock per domain): play once its sim time, which at rtf 1
        # never runs ahead of the wall time since it started, is past that (a fast machine
        # records the 3 s bag well within it)
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and \
                (_sim_time(page.page.inner_text('body')) or 0.0) < CLOCK_WATCH_TIME + 1.0:
            page.page.wait_for_timeout(250)
        assert (_sim_time(page.page.inner_text('body')) or 0.0) >= CLOCK_WATCH_TIME + 1.0
        # looped until the viewer has said so: on a loaded machine the player's /clock may be
        # discovered only after a 3 s bag has ended
        play = procs.start([exe('ros2'), 'bag', 'play', str(bag), '--clock', '--loop'],
                           ros_env)
        assert stack.wait_for_output('/clock jumped back in time', 120.0), \
            stack.output[-3000:] + play.output
        said = False
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline and not said:
            said = 'jumped back in time' in page.page.inner_text('body')
            if not said:
                page.page.wait_for_timeout(250)
        assert said, page.page.inner_text('body')
        assert play.interrupt(timeout=30.0) == 0, play.output
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline and not posed():
            page.page.wait_for_timeout(500)
        assert posed(), page.page.inner_text('body')
        # it stays so while the simulator's /clock and /tf alone move on (2 s of sim time)
        first = _sim_time(page.page.inner_text('body'))
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            text = page.page.inner_text('body')
            assert posed(), text
            if first is not None and (_sim_time(text) or 0.0) > first + 2.0:
                break
            page.page.wait_for_timeout(250)
        else:
            raise AssertionError(f'sim time did not advance 2 s: {text}')
    assert stack.interrupt(timeout=30.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]
