# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``behavior_server``: nav2_behaviors' behaviour server (Jazzy), a managed (lifecycle) node.

Parameters, with Nav2's code defaults: ``behavior_plugins`` ([spin, backup, drive_on_heading,
wait]) and ``<id>.plugin`` (``nav2_behaviors::Spin``, ``BackUp``, ``DriveOnHeading``,
``Wait``; another, e.g. ``AssistedTeleop``, is said in one line and not offered),
``cycle_frequency`` (10.0 Hz), ``local_costmap_topic`` (local_costmap/costmap_raw),
``local_footprint_topic`` (local_costmap/published_footprint), ``local_frame`` (odom),
``global_frame`` (map), ``robot_base_frame`` (base_link), ``transform_tolerance`` (0.1),
``simulate_ahead_time`` (2.0 s), ``max_rotational_vel`` (1.0), ``min_rotational_vel`` (0.4),
``rotational_acc_lim`` (3.2), ``enable_stamped_cmd_vel`` (false).

Each behaviour is an action named by its plugin id (``spin``: nav2_msgs/action/Spin, ...),
one goal at a time, a new goal aborting the running one. Spin turns ``target_yaw`` (sign =
direction) at ``clamp(sqrt(2 a remaining), min, max)``; BackUp drives ``|target.x|`` back at
``|speed|``; DriveOnHeading drives ``target.x`` at ``speed`` (same sign); Wait waits ``time``.
Before each command the poses of the next ``simulate_ahead_time`` are checked against the
local costmap's raw costs under the published footprint: a lethal cost is COLLISION_AHEAD. A
``time_allowance`` above 0 that runs out is TIMEOUT, a missing transform TF_ERROR, a bad
BackUp / DriveOnHeading target INVALID_INPUT; every end publishes a zero command on
``cmd_vel``. Arithmetic: :mod:`amr_description.nav.behaviors`. Sources:
``nav2_behaviors/src/behavior_server.cpp``, ``include/nav2_behaviors/timed_behavior.hpp``,
``plugins/*.cpp``.
"""

import math

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav import behaviors as bh
from amr_description.nav.costmap import footprint_cost
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.grid_message import costmap_from_message
from amr_description.ros import shutdown
from amr_description.ros.goal_server import SingleGoalServer
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.stamps import msg_to_time
from amr_description.ros.transforms import planar_pose
from amr_description.ros.transforms import TransformListener
from amr_description.ros.twist_io import TwistPublisher
from geometry_msgs.msg import PolygonStamped
from nav2_msgs.action import BackUp
from nav2_msgs.action import DriveOnHeading
from nav2_msgs.action import Spin
from nav2_msgs.action import Wait
from nav2_msgs.msg import Costmap as CostmapMsg
import numpy as np
from rclpy.duration import Duration
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy

KINDS = {'Spin': Spin, 'BackUp': BackUp, 'DriveOnHeading': DriveOnHeading, 'Wait': Wait}
DEFAULT_PLUGINS = {'spin': 'Spin', 'backup': 'BackUp', 'drive_on_heading': 'DriveOnHeading',
                   'wait': 'Wait'}
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)


class BehaviorServer(ManagedNode):
    """Node ``behavior_server``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters (``kwargs``: rclpy's node options)."""
        super().__init__('behavior_server', **kwargs)
        d = self.declare_parameter
        self.p = {k: d(k, v).value for k, v in {
            'local_costmap_topic': 'local_costmap/costmap_raw',
            'global_costmap_topic': 'global_costmap/costmap_raw',
            'local_footprint_topic': 'local_costmap/published_footprint',
            'global_footprint_topic': 'global_costmap/published_footprint',
            'cycle_frequency': 10.0, 'local_frame': 'odom', 'global_frame': 'map',
            'robot_base_frame': 'base_link', 'transform_tolerance': 0.1,
            'simulate_ahead_time': 2.0, 'max_rotational_vel': 1.0, 'min_rotational_vel': 0.4,
            'rotational_acc_lim': 3.2, 'enable_stamped_cmd_vel': False,
            'action_server_result_timeout': 10.0}.items()}
        self.plugins = {}
        for bid in d('behavior_plugins', list(DEFAULT_PLUGINS)).value:
            default = f'nav2_behaviors::{DEFAULT_PLUGINS.get(bid, "Wait")}'
            self.plugins[bid] = str(d(f'{bid}.plugin', default).value)
        self.tf_buffer = TransformBuffer()
        self._listener = self._cmd = None
        self._entities = []
        self.servers = {}
        self.runs = {}
        self.costmap = None
        self.footprint = None

    def configure(self):
        """Say which behaviours are offered; listen to TF."""
        self.get_logger().info('Configuring')
        for bid, plugin in self.plugins.items():
            kind = plugin.replace('/', '::').split('::')[-1]
            if kind in KINDS:
                self.get_logger().info(f'Creating behavior plugin {bid} of type {plugin}')
            else:
                self.get_logger().warning(f"{bid}: plugin '{plugin}' is not available here; "
                                          'its action is not offered')
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)

    def activate(self):
        """Create the action servers, the command publisher and the cycle timer."""
        self.get_logger().info('Activating')
        self._cmd = TwistPublisher(self, 'cmd_vel', self.p['enable_stamped_cmd_vel'],
                                   self.p['robot_base_frame'])
        # cycles only while a behaviour runs, as upstream's loop inside its action's execution
        self._timer = self.create_timer(1.0 / max(self.p['cycle_frequency'], 1e-3),
                                        self._cycle)
        self._timer.cancel()
        self._entities = [
            self._cmd.pub,
            self.create_subscription(CostmapMsg, self.p['local_costmap_topic'],
                                     self._on_costmap, LATCHED),
            self.create_subscription(PolygonStamped, self.p['local_footprint_topic'],
                                     self._on_footprint, 1),
            self._timer]
        for bid, plugin in self.plugins.items():
            kind = plugin.replace('/', '::').split('::')[-1]
            if kind in KINDS:
                self.servers[bid] = (kind, SingleGoalServer(
                    self, KINDS[kind], bid, lambda h, b=bid: self._on_goal(b, h)))

    def deactivate(self):
        """Stop any behaviour and destroy what :meth:`activate` made."""
        self.get_logger().info('Deactivating')
        if self.runs and self._cmd is not None:
            self._cmd.publish(0.0, 0.0)
        for _, server in self.servers.values():
            server.destroy()
        self.servers, self.runs = {}, {}
        self.destroy_entities(self._entities)
        self._entities = []
        self._cmd = None

    def cleanup(self):
        """Stop listening to TF."""
        self.get_logger().info('Cleaning up')
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    # inputs
    def _on_costmap(self, msg):
        try:
            self.costmap = costmap_from_message(msg)
        except ValueError as exc:
            self.get_logger().error(f'{self.p["local_costmap_topic"]}: {exc}; ignored')

    def _on_footprint(self, msg):
        pts = np.array([(p.x, p.y) for p in msg.polygon.points], float)
        if len(pts) and np.isfinite(pts).all():
            self.footprint = pts  # in the costmap's frame, at the robot's pose then

    def _pose(self):
        T, _ = self.tf_buffer.lookup(self.p['local_frame'], self.p['robot_base_frame'])
        return planar_pose(T)

    def _on_goal(self, bid, handle):
        kind, server = self.servers[bid]
        goal = handle.request
        result = KINDS[kind].Result()
        if kind in ('BackUp', 'DriveOnHeading'):
            reason = bh.drive_goal_error(goal.target.x, goal.target.y, goal.target.z,
                                         goal.speed, kind == 'BackUp')
            if reason:
                self.get_logger().error(f'{bid}: {reason}')
                result.error_code = KINDS[kind].Result.INVALID_INPUT
                result.error_msg = reason
                server.finish_current('abort', result)
                return
        try:
            start = self._pose()
        except TransformException as exc:
            return self._end(bid, 'abort', 'TF_ERROR', f'Initial robot pose is not available: '
                             f'{str(exc).strip()}')
        self.get_logger().info(f'Running {bid}')
        allowance = 0.0 if kind == 'Wait' else msg_to_time(goal.time_allowance)
        self.runs[bid] = {'start': start, 't0': self._now(), 'allowance': allowance,
                          'last_yaw': start[2], 'turned': 0.0}
        self._timer.reset()

    def _now(self):
        return self.get_clock().now().nanoseconds * 1e-9

    def _end(self, bid, outcome, code, message=''):
        kind, server = self.servers[bid]
        run = self.runs.pop(bid, None)
        result = KINDS[kind].Result()
        if run is not None:
            result.total_elapsed_time = Duration(
                nanoseconds=int((self._now() - run['t0']) * 1e9)).to_msg()
        if code:
            result.error_code = getattr(KINDS[kind].Result, code)
            result.error_msg = message
            self.get_logger().warning(f'{bid}: {message}')
        if kind != 'Wait' and self._cmd is not None:
            self._cmd.publish(0.0, 0.0)
        server.finish_current(outcome, result)

    def _cycle(self):
        if not self.runs:
            self._timer.cancel()
            return
        for bid in list(self.runs):
            kind, server = self.servers[bid]
            if not server.active:
                self.runs.pop(bid, None)
                continue
            run = self.runs[bid]
            if server.cancel_requested:
                self._end(bid, 'canceled', None)
                continue
            elapsed = self._now() - run['t0']
            if run['allowance'] > 0.0 and elapsed > run['allowance']:
                self._end(bid, 'abort', 'TIMEOUT',
                          f'{bid} has exceeded its time allowance of {run["allowance"]:g} s')
                continue
            if kind == 'Wait':
                left = msg_to_time(server.goal.time) - elapsed
                if left <= 0.0:
                    self._end(bid, 'succeed', None)
                else:
                    fb = Wait.Feedback()
                    fb.time_left = Duration(nanoseconds=int(left * 1e9)).to_msg()
                    server.feedback(fb)
                continue
            try:
                pose = self._pose()
            except TransformException as exc:
                self._end(bid, 'abort', 'TF_ERROR', f'Current robot pose is not available: '
                                                    f'{str(exc).strip()}')
                continue
            if kind == 'Spin':
                self._spin(bid, server, run, pose)
            else:
                self._drive(bid, kind, server, run, pose)

    def _spin(self, bid, server, run, pose):
        target = float(server.goal.target_yaw)
        run['turned'] += abs(bh.angle_diff(pose[2], run['last_yaw']))
        run['last_yaw'] = pose[2]
        fb = Spin.Feedback()
        fb.angular_distance_traveled = float(run['turned'])
        server.feedback(fb)
        remaining = abs(target) - run['turned']
        if remaining <= 0.0 or not math.isfinite(target):
            self._end(bid, 'succeed', None)
            return
        w = math.copysign(bh.spin_velocity(remaining, self.p['rotational_acc_lim'],
                                           self.p['min_rotational_vel'],
                                           self.p['max_rotational_vel']), target)
        poses = bh.spin_poses(pose, w, remaining, self.p['simulate_ahead_time'],
                              self.p['cycle_frequency'])
        if self._collides(pose, poses):
            self._end(bid, 'abort', 'COLLISION_AHEAD', 'Collision Ahead - Exiting Spin')
            return
        self._cmd.publish(0.0, w)

    def _drive(self, bid, kind, server, run, pose):
        goal = server.goal
        distance, speed = float(goal.target.x), float(goal.speed)
        if kind == 'BackUp':
            distance, speed = -abs(distance), -abs(speed)
        start = run['start']
        travelled = math.hypot(pose[0] - start[0], pose[1] - start[1])
        fb = KINDS[kind].Feedback()
        fb.distance_traveled = float(travelled)
        server.feedback(fb)
        remaining = abs(distance) - travelled
        if remaining <= 0.0:
            self._end(bid, 'succeed', None)
            return
        poses = bh.drive_poses(pose, speed, remaining, self.p['simulate_ahead_time'],
                               self.p['cycle_frequency'])
        if self._collides(pose, poses):
            self._end(bid, 'abort', 'COLLISION_AHEAD', f'Collision Ahead - Exiting {kind}')
            return
        self._cmd.publish(speed, 0.0)

    def _collides(self, pose, poses):
        if self.costmap is None:
            return False  # no costmap yet: Nav2 waits for one; we do not block the behaviour
        if self.footprint is None:
            outline = np.zeros((1, 2))
        else:  # the published footprint back into the robot frame
            c, s = math.cos(pose[2]), math.sin(pose[2])
            outline = (self.footprint - pose[:2]) @ np.array([[c, -s], [s, c]])
        return any(footprint_cost(self.costmap, outline, p) >= LETHAL_OBSTACLE for p in poses)


def main(args=None):
    """
    Run the behaviour server until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(BehaviorServer, args)


if __name__ == '__main__':
    main()
