# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The navigation job: map a world with SLAM, save the map, localize in it and go to goals.

``./scripts/main --navigate`` (``ros2 run amr_description navigate_job``) runs what a Nav2
user does after the tutorials, through the same interfaces
(nav2_simple_commander's ``BasicNavigator`` in this process):

1. **Mapping.** The ``navigation`` stack with ``slam:=True`` (simulator, slam_toolbox's
   ``online_sync``, the navigation servers, viewer) in ``--world`` (warehouse.sdf); the robot
   follows the world's waypoint route (:data:`.main.ROUTES`, ``follow_waypoints``) through
   every aisle while the map grows; ``map_saver_cli`` saves it to ``out/map.yaml``.
2. **Navigation.** The stack restarted with ``map:=out/map.yaml`` (map_server + AMCL, the
   robot back at its spawn pose, where AMCL starts); ``--goals`` (10) seeded random goals
   (``--seed``), each reachable and 0.45 m clear of every obstacle of both the true map and
   the saved one (:func:`amr_description.nav.trials.sample_goals`), sent one after the other
   with ``goToPose``; the planned path of each comes from ``getPath`` just before.

It prints one row per goal (result, sim time and its bound, planned and driven length,
ground-truth distance and heading error at the end, closest approach to the world) and
writes ``out/map.png`` (the SLAM map over the world's true map, the route driven) and
``out/navigation.png`` (planned and driven paths). The closest approach is the ground truth's
footprint (``config/nav2_params.yaml``) against the world's collision shapes
(:func:`amr_description.nav.trials.footprint_clearance`); overlapping is a collision.

Exit 0 when every goal SUCCEEDED with no collision in either phase; 1 otherwise, or when the
route is not finished, a stack does not come up or the map is not saved (one line on stderr).
Each stack's output goes to ``out/slam_stack.log`` and ``out/navigation_stack.log``.

``--rtf`` sets the simulator's real-time factor (1.0); ``--rtf 0`` runs it as fast as the
navigation stack keeps up, advanced in lock-step with the stack's commands and localizer
(:mod:`.lockstep`). Each phase's real-time factor is printed.

Modules: :mod:`.main` (command line, phases), :mod:`.report` (table and pictures),
:mod:`.lockstep` (``--rtf 0``).
"""
