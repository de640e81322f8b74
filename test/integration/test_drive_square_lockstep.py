# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The main job's lock-step never answers odometry the simulator published before it paused.

A stand-in simulator in this process offers ``mujoco_sim``'s lock-step services and a robot
that moves exactly as commanded (a unicycle, no physics). When asked to pause it stands one
second of sim time further on; the clock of that second reaches ``drive_square`` only after
the pause is answered, its odometry and ground truth only with the first advance: what
happens when the real simulator runs ahead at tens of times real time and its messages are
still in flight (or queued) while the service answer overtakes them (DDS orders messages per
topic, not across topics and services). Commands that answer them are older than
``cmd_vel_timeout`` when the stand-in takes them (a controller drops them), so the test
asserts that the first command the job sends is stamped at or after the paused time, that no
command is stale on arrival, and that the job drives the whole square (exit 0: the ground
truth closes within 0.01 m).
"""

import math
import os

import pytest
from stand_in import StandIn  # noqa: I100 - helpers next to this file

pytest.importorskip('rclpy')

PERIOD = 0.02  # s of sim time per tick (the odometry period)
RUN_AHEAD = 50  # ticks published between the pause request and its answer (1 s)
CMD_VEL_TIMEOUT = 0.5  # s, as config/controllers.yaml


class StandInSimulator(StandIn):
    """mujoco_sim's clock, pause and step services, one ideal robot and its controllers."""

    def __init__(self, domain_id):
        from controller_manager_msgs.srv import ListControllers
        from geometry_msgs.msg import TwistStamped
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from simulation_interfaces.srv import SetSimulationState
        from simulation_interfaces.srv import StepSimulation

        super().__init__('mujoco_sim', domain_id)
        self.Clock, self.Odometry = Clock, Odometry
        node = self.node
        node.declare_parameter('physics_step', 0.001)
        self.t = 0.0
        self.pose = [0.0, 0.0, 0.0]
        self.cmd = None  # (stamp s, linear m/s, angular rad/s)
        self.paused = False
        self.paused_at = None
        self.stale = []  # ages (s) of commands older than CMD_VEL_TIMEOUT on arrival
        self.first_stamp = None
        self.commands = 0
        self._late = []  # (publisher, message) of the run-ahead's clock, not yet published
        self._held = []  # (publisher, message) of its odometry and ground truth, held longer
        self._clock = node.create_publisher(Clock, '/clock', 10)
        self._odom = node.create_publisher(Odometry, '/odom', 10)
        self._truth = node.create_publisher(Odometry, '/ground_truth/odom', 10)
        node.create_subscription(TwistStamped, '/diff_drive_controller/cmd_vel', self._on_cmd,
                                 10)
        node.create_service(SetSimulationState, '/mujoco_sim/set_simulation_state',
                            self._on_state)
        node.create_service(StepSimulation, '/mujoco_sim/step_simulation', self._on_step)
        node.create_service(ListControllers, '/controller_manager/list_controllers',
                            self._on_list)
        node.create_timer(0.01, self._on_timer)
        node.create_timer(0.1, self._on_paused_tick)
        self.start()

    def _tick(self, dt, publish=True):
        linear = angular = 0.0
        if self.cmd is not None and self.t - self.cmd[0] <= CMD_VEL_TIMEOUT:
            linear, angular = self.cmd[1], self.cmd[2]
        x, y, yaw = self.pose
        self.pose = [x + linear * math.cos(yaw) * dt, y + linear * math.sin(yaw) * dt,
                     yaw + angular * dt]
        self.t += dt
        clock = self._clock_now()
        odom = self.Odometry()
        odom.header.stamp = clock.clock
        odom.pose.pose.position.x, odom.pose.pose.position.y = self.pose[0], self.pose[1]
        odom.pose.pose.orientation.z = math.sin(self.pose[2] / 2.0)
        odom.pose.pose.orientation.w = math.cos(self.pose[2] / 2.0)
        messages = [(self._clock, clock), (self._odom, odom), (self._truth, odom)]
        if publish:
            for publisher, msg in messages:
                publisher.publish(msg)
        return messages

    def _clock_now(self):
        clock = self.Clock()
        clock.clock.sec, clock.clock.nanosec = divmod(int(round(self.t * 1e9)), 1_000_000_000)
        return clock

    def _on_timer(self):
        if self._late:  # the run-ahead, delivered after the pause was answered
            for publisher, msg in self._late:
                publisher.publish(msg)
            self._late = []
        elif not self.paused:
            self._tick(PERIOD)  # free running at twice real time

    def _on_paused_tick(self):
        if self.paused and not self._late:  # as mujoco_sim: the unchanged time, at 10 Hz
            self._clock.publish(self._clock_now())

    def _on_cmd(self, msg):
        stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        if self.first_stamp is None:
            self.first_stamp = stamp
        self.commands += 1
        if self.t - stamp >= CMD_VEL_TIMEOUT:
            self.stale.append(round(self.t - stamp, 3))
            return
        self.cmd = (stamp, msg.twist.linear.x, msg.twist.angular.z)

    def _on_state(self, request, response):
        paused = request.state.state != request.state.STATE_PLAYING
        if paused and not self.paused:
            for _ in range(RUN_AHEAD):
                for publisher, msg in self._tick(PERIOD, publish=False):
                    if publisher is self._clock:
                        self._late.append((publisher, msg))
                    else:
                        self._held.append((publisher, msg))
            self.paused_at = self.t
        self.paused = paused
        response.result.result = response.result.RESULT_OK
        return response

    def _on_step(self, request, response):
        if not self.paused:
            response.result.result = response.result.OPERATION_FAILED
            return response
        for publisher, msg in self._held:  # the run-ahead's odometry, after the first advance
            publisher.publish(msg)
        self._held = []
        self._tick(request.steps * 0.001)
        response.result.result = response.result.RESULT_OK
        return response

    def _on_list(self, request, response):
        from controller_manager_msgs.msg import ControllerState
        for name in ('joint_state_broadcaster', 'diff_drive_controller'):
            response.controller.append(ControllerState(name=name, state='active'))
        return response


def test_lockstep_skips_odometry_from_before_the_pause(procs, exe, ros_env, tmp_path):
    pytest.importorskip('simulation_interfaces.srv')
    pytest.importorskip('controller_manager_msgs.srv')
    sim = StandInSimulator(int(ros_env['ROS_DOMAIN_ID']))
    try:
        proc = procs.start([exe('drive_square'), '--no-bringup', '--rtf', '0', '--viewer-port',
                            '0', '--output-dir', str(tmp_path / 'out'), '--timeout', '300'],
                           ros_env)
        assert proc.wait(400) == 0, proc.output
        assert sim.paused_at is not None and sim.first_stamp is not None, proc.output
        # the first command answers odometry of the paused simulator, not of its run-ahead
        assert sim.first_stamp >= sim.paused_at - 1e-6, (sim.first_stamp, sim.paused_at)
        assert sim.stale == [], sim.stale
        assert sim.commands > 500, sim.commands
        assert os.path.exists(tmp_path / 'out' / 'path.png')
        # --no-bringup: the user's simulator is left playing
        assert not sim.paused
    finally:
        sim.close()
