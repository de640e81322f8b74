# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The shipped URDF works with the tutorial's ``-p robot_description:="$(cat amr.urdf)"``."""

import os

import yaml

URDF = os.path.join(os.path.dirname(__file__), '..', '..', 'urdf', 'amr.urdf')


def test_urdf_is_one_yaml_scalar():
    # rcl parses a -p value as YAML: a ': ' or a line ending in ':' (in a comment, say) turns
    # the document into a mapping and `ros2 run ... --ros-args -p robot_description:=...`
    # fails with "Couldn't parse parameter override rule"
    with open(URDF) as f:
        text = f.read()
    assert isinstance(yaml.safe_load(text), str)
