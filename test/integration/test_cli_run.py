# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 run`` resolves executables through the ament index; ``ros2 pkg`` lists them."""

import subprocess


def test_run_talker_through_ament_index(ros_env, procs, exe):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker'], ros_env)
    assert run.wait_for_output('Publishing: "Hello World: 0"', timeout=10.0), run.output
    assert run.interrupt() == 0
    assert 'Traceback' not in run.output


def test_run_passes_arguments_and_ros_args(ros_env, procs, exe):
    run = procs.start([exe('ros2'), 'run', 'amr_description', 'talker', '--ros-args',
                       '-r', '__node:=renamed'], ros_env)
    assert run.wait_for_output('[renamed]: Publishing', timeout=10.0), run.output
    assert run.interrupt() == 0


def test_run_errors_in_upstream_wording(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'run', 'no_such_pkg', 'x'], env=ros_env,
                            capture_output=True, text=True, timeout=10)
    assert (result.returncode, result.stderr) == (1, "Package 'no_such_pkg' not found\n")
    result = subprocess.run([exe('ros2'), 'run', 'amr_description', 'nope'], env=ros_env,
                            capture_output=True, text=True, timeout=10)
    assert (result.returncode, result.stderr) == (1, 'No executable found\n')


def test_pkg_executables_lists_talker(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'pkg', 'executables', 'amr_description'],
                            env=ros_env, capture_output=True, text=True, timeout=10)
    lines = result.stdout.splitlines()
    assert 'amr_description talker' in lines and lines == sorted(lines)
