# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""``ros2 interface show`` expands nested types with tabs, as upstream jazzy."""

import subprocess


def test_interface_show_twist_stamped(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'interface', 'show', 'geometry_msgs/msg/TwistStamped'],
                            env=ros_env, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.endswith(
        'std_msgs/Header header\n\tbuiltin_interfaces/Time stamp\n\t\tint32 sec\n'
        '\t\tuint32 nanosec\n\tstring frame_id\nTwist twist\n\tVector3  linear\n'
        '\t\tfloat64 x\n\t\tfloat64 y\n\t\tfloat64 z\n\tVector3  angular\n'
        '\t\tfloat64 x\n\t\tfloat64 y\n\t\tfloat64 z\n')


def test_interface_show_unknown_is_one_line_error(ros_env, exe):
    result = subprocess.run([exe('ros2'), 'interface', 'show', 'nope_msgs/msg/X'],
                            env=ros_env, capture_output=True, text=True, timeout=60)
    assert (result.returncode, result.stderr) == (1, "Unknown package 'nope_msgs'\n")
