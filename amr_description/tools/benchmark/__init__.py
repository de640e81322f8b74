# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Scaling benchmark of the simulator: N robots, each driven, real time and fast-forward.

For every N in ``--robots`` (default 1, 2, 4, 8, 16, 32), each against a fresh stack brought
up by the orchestrator on one ROS domain (localhost only): the ``sim`` stack for N = 1 (the
robot without a namespace, as the tutorial runs it) and the ``fleet`` stack (``robots:=N``,
namespaces ``r1`` ... ``rN`` on a 2 m grid) for N > 1:

start-up
    wall time from starting the stack (mujoco_sim, robot_state_publishers, ``create`` and
    spawners, as a launch file does) until every spawner has exited 0, i.e. every robot's
    ``joint_state_broadcaster`` and ``diff_drive_controller`` are active. Measured in both
    runs below; the smaller is reported.
real time (``rtf:=1``)
    every robot driven in a circle (``TURN_TWIST`` on its ``diff_drive_controller/cmd_vel``);
    real-time factor held (sim seconds from /clock per wall second) over ``--duration``, CPU
    of the ``mujoco_sim`` process and of the whole stack (``/proc/PID/stat``) per robot, in %
    of one core.
fast-forward (``rtf:=0``)
    the same drive; x real time over ``--duration``, and the cost per robot-second (wall
    seconds per simulated robot-second, ``1 / (x real time * N)``) relative to N = 1 (1.00 =
    linear scaling).
raw ``mj_step``
    the same N-robot world (:func:`~amr_description.launch.stacks.fleet_grid` positions)
    stepped by ``mujoco.mj_step`` in this process with the wheel speeds diff_drive_controller
    commands for ``TURN_TWIST``; the simulator's fast-forward speed as a fraction of it.

Commands are stamped an hour of sim time ahead of the /clock time seen when driving starts,
so ``cmd_vel_timeout`` never stops a robot whatever the speed of the simulation (a load
generator, not a user's behaviour); robots 2 m apart driving 0.6 m circles never touch.

viewer (part d, unless ``--no-viewer``)
    one robot in real time with robot_state_publisher, the ``viewer`` node and one headless
    browser on its page: real-time factor held and the viewer's CPU
    (:func:`amr_description.tools.benchmark_viewer.viewer_cost`).

A run whose stack does not come up (a process exits with an error, or the controllers are
not active in time) or whose measurement gets no /clock stops the benchmark: it prints the
stage that failed and the captured output of the failing process, exits 1 and writes no
report; nothing is retried. Usage: ``scripts/benchmark_sim [--robots 1,2,4] [--duration S]
[--output docs/benchmark.md]`` (``--output ''`` prints only).
"""
