# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The ``display`` stack: robot_state_publisher + joint_state_publisher form one TF tree.

Starts ``bringup display`` (the tutorial's display.launch.py minus RViz) and checks, over
DDS, that ``/tf_static`` and ``/tf`` together connect all six frames of the robot to the root
``base_footprint``, then that Ctrl-C stops the stack cleanly.
"""

from test_robot_state_publisher import Peer  # noqa: I100 - the RSP tests' DDS peer
from test_robot_state_publisher import transforms

FRAMES = {'base_footprint', 'base_link', 'wheel_front_left', 'wheel_front_right',
          'wheel_back_left', 'wheel_back_right'}


def _root(frame, parents):
    seen = set()
    while frame in parents and frame not in seen:
        seen.add(frame)
        frame = parents[frame]
    return frame


def test_display_stack_forms_one_tf_tree(ros_env, procs, exe):
    stack = procs.start([exe('bringup'), 'display', 'gui:=false', 'viewer:=false'], ros_env)
    peer = Peer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        def tree():
            pairs = transforms(peer.static + peer.tf)
            return {child: parent for parent, child in pairs}

        assert peer.spin_until(lambda: FRAMES - {'base_footprint'} <= set(tree()), 20.0), \
            (tree(), stack.output[-3000:])
        parents = tree()
        assert parents['base_link'] == 'base_footprint'
        assert all(parents[w] == 'base_link' for w in FRAMES if w.startswith('wheel_'))
        assert {_root(f, parents) for f in FRAMES} == {'base_footprint'}
        # the wheels' transforms come from joint_state_publisher's zeros, on /tf
        assert {t.child_frame_id for m in peer.tf for t in m.transforms} >= \
            {f for f in FRAMES if f.startswith('wheel_')}
    finally:
        peer.close()
    assert stack.interrupt(timeout=60.0) == 0, stack.output[-3000:]
    assert 'Traceback' not in stack.output, stack.output[-3000:]
    assert 'process has died' not in stack.output, stack.output[-3000:]
