# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
The ``mujoco_sim`` node: ROS plumbing around the simulation engine (gz sim's role).

The engine (:class:`amr_description.sim.simulation.Simulation`, no rclpy) owns the MuJoCo
world, the robots and one controller manager per robot with ``<ros2_control>``, and runs the
physics / ``read -> update -> write`` cycle in its own thread. This node adds parameters,
services, the /clock and sensor publishers (called by the simulation thread through hooks,
nothing else is woken per update) and the in-process sim time of the controller nodes.

Modules: :mod:`.node` (parameters, wiring, sensor publishers, ``main``), :mod:`.services`
(the simulation_interfaces services), :mod:`.clock` (the one-clock guard and the external
clock follower), :mod:`.bridge` (the ROS names of gz-sim systems' topics),
:mod:`.passive_viewer` (MuJoCo's own window, ``headless:=false``).

Parameters (read at start):
  ``physics_step`` (double, 0.001 s), ``real_time_factor`` (double, 1.0; 0 = as fast as
  possible), ``headless`` (bool, true; false opens the MuJoCo viewer when a display exists),
  ``parameters_file`` (string, '' = the URDF's ``<mujoco><ros2_control parameters=...>``),
  ``paused`` (bool, false), ``publish_ground_truth`` (bool, true), ``ground_truth_rate``
  (double, 50.0 Hz of sim time), ``clock_source`` (string, ``internal``: this node publishes
  /clock and refuses to start, exit code 1, when it finds another node publishing /clock
  in its first 10 s, publishing none of its own in the first 1.5 s; ``external``: follow the
  /clock of another simulator, never running ahead of it, and publish none),
  ``bridge_config`` (string, '': a ros_gz_bridge YAML file; the topics of the robots' gz-sim
  systems and sensor blocks then reach ROS as that bridge would bridge them, docs/gazebo.md),
  ``seed`` (integer, 0: seeds the sensors' noise; one seed gives the same messages in
  lock-step runs, docs/sensors.md).

Topics: ``/clock`` (rosgraph_msgs/Clock, reliable, depth 10) after every cycle, at least 100 Hz
of sim time, and at 10 Hz (wall) with an unchanged time while paused (an empty world runs in
real time even with ``real_time_factor`` 0: fast-forward starts with the first spawned
entity); one topic per sensor of every spawned robot (:mod:`amr_description.sim.sensors`), e.g.
``<namespace>/ground_truth/odom`` (nav_msgs/Odometry): pose of its root link in frame
``world``, twist in the root link frame (REP 105 / Odometry convention); child frame
``base_footprint`` (``r1/base_footprint`` in namespace ``/r1``); the topics of the gz-sim
systems a robot's description names (:mod:`amr_description.sim.systems`: e.g. DiffDrive's
Twist subscription and Odometry and TF publishers) and of its ``<gazebo><sensor>`` blocks
(lidar: LaserScan on ``<topic>``, PointCloud2 on ``<topic>/points``; IMU: Imu; cameras:
Image, CameraInfo, CompressedImage, depth Image and PointCloud2, docs/sensors.md), reliable,
volatile, depth 10 as ros_gz_bridge's.

Services (simulation_interfaces): ``~/spawn_entity`` (SpawnEntity; ``entity_namespace``
gives the robot's controller manager ``<namespace>/controller_manager``, its controllers
``<namespace>/<controller>``; each robot needs its own name and namespace),
``~/reset_simulation`` (ResetSimulation: resets poses, velocities and time to the spawn
state; removing spawned entities is unsupported), ``~/set_simulation_state``
(SetSimulationState: playing, paused, stopped = paused + reset, quitting),
``~/step_simulation`` (StepSimulation: N physics steps while paused; answers when done).

Threads: the rclpy executor runs in the main thread and is the only thread that creates or
destroys rclpy entities (spawn builds the controller manager in the service callback, a
coroutine that awaits the simulation thread's world change, so that the executor serves the
other robots' controller-manager services meanwhile). The
simulation thread publishes /clock and the sensors and sets the controller nodes' clocks;
their /clock subscriptions are removed before the executor ever sees them
(:class:`amr_description.ros.sim_time.SimTimeExecutor`). Cameras render and publish on their
own thread (``camera_render``, :mod:`amr_description.sim.sensors.camera`), through EGL unless
``MUJOCO_GL`` says otherwise (chosen by the package, :mod:`amr_description`).
"""
