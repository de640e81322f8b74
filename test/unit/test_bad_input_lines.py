# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Bad input to the readers and the CLI: one line naming what is wrong (no process, no DDS)."""

import subprocess
import sys

from amr_description.cli.daemon import domain_id
import pytest


@pytest.mark.parametrize('value, expected', [('', 0), ('0', 0), ('232', 232), (' 7', 7)])
def test_domain_id_accepts_what_rcl_and_fast_dds_accept(monkeypatch, value, expected):
    monkeypatch.setenv('ROS_DOMAIN_ID', value)
    assert domain_id() == expected


@pytest.mark.parametrize('value', ['abc', '233', '-1', '1.5', '0x10'])
def test_domain_id_refuses_with_one_line(monkeypatch, value):
    monkeypatch.setenv('ROS_DOMAIN_ID', value)
    with pytest.raises(ValueError, match=f"ROS_DOMAIN_ID '{value}': expected an integer from 0 "
                       'to 232'):
        domain_id()


def test_ros2_with_a_bad_domain_id_is_one_line_and_exit_1():
    env_script = ('import os, sys; os.environ["ROS_DOMAIN_ID"] = "abc"; '
                  'from amr_description.cli.main import main; sys.exit(main(sys.argv[1:]))')
    run = subprocess.run([sys.executable, '-c', env_script, 'topic', 'list'],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 1
    assert run.stderr.strip() == "ROS_DOMAIN_ID 'abc': expected an integer from 0 to 232"
    assert run.stdout == ''
