# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The main job: bring up the simulated robot(s), drive a square on odometry, report and draw it.

``ros2 run amr_description drive_square [--side 1.0] [--rtf 1.0] [--robots N]
[--output-dir out]`` starts the ``sim`` stack (``--robots 1``, today's names: ``/odom``,
``/diff_drive_controller/cmd_vel``, ``/ground_truth/odom``) or the ``fleet`` stack
(``--robots N`` > 1: robots ``r1`` ... ``rN`` with ``/rI/odom``,
``/rI/diff_drive_controller/cmd_vel``, ``/rI/ground_truth/odom``), unless ``--no-bringup``.
It waits until every robot's ``joint_state_broadcaster`` and ``diff_drive_controller`` are
active, then every robot drives its own square at once, closed-loop on its odometry, by
publishing ``geometry_msgs/TwistStamped`` exactly as a user's node would: one command per
odometry message, stamped with that message's stamp (sim time).

Fast-forward (``--rtf 0``) runs in lock-step: the job pauses the simulator
(``/mujoco_sim/set_simulation_state``) and advances it ``--lockstep-period`` (0.02 s, one
odometry period) at a time with ``/mujoco_sim/step_simulation``, answering every odometry
message before the next step. The course starts from odometry stamped at or after the time
at which the paused simulator stands (two equal values in a row on ``/clock``): messages it
published while it still ran ahead, maybe queued in this process, are not answered. The
simulation can therefore never run ahead of the driver, a command is at most one period old
in sim time when the controller takes it (far below ``cmd_vel_timeout``), and the result does
not depend on how loaded the machine is. In real-time mode (``--rtf`` > 0) the simulator
runs free.

The job fails (exit 1, one line on stderr) when a command was dropped as stale (a command
published when the sim time it observes on ``/clock`` is already ``cmd_vel_timeout`` past its
stamp, or an "Ignoring the received message" line of diff_drive_controller in the stack's own
log), when a course does not finish within ``--timeout``, or when a robot's ground-truth
closure misses ``--tolerance`` (m) or ``--tolerance-deg``, or when fewer than 95 % of the
lidar's scan points placed with ground truth lie on a true surface. Otherwise it prints a
table per leg (one robot) or one row per robot and a per-leg summary (several robots), writes
``path.png`` (odometry vs ground truth of every robot), ``scene.png`` (a render of the
final scene in its world) and, in a world with obstacles (``--world``: ``arena`` for one
robot, ``empty`` for a fleet), ``scans.png`` (:mod:`.scans`), stops the stack and exits 0.

Modules: :mod:`.driver` (the node, one driver per robot, lock-step), :mod:`.report`
(tables, plots, closure checks), :mod:`.scans` (the lidar map), :mod:`.main` (command line,
bring-up, ``main``).
"""
