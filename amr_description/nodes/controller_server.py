# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``controller_server``: nav2_controller's controller server (Jazzy), a managed (lifecycle) node.

It runs the local costmap beside itself (:class:`amr_description.nodes.costmap_2d.CostmapNode`
``local_costmap`` in ``local_costmap``, usually a rolling window in ``odom``) and follows paths
with Regulated Pure Pursuit (:mod:`amr_description.nav.pure_pursuit`). Parameters, with Nav2's
code defaults: ``controller_frequency`` (20.0 Hz), ``controller_plugins`` ([FollowPath]) and
``<id>.plugin``; ``nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController``
reads all of RPP's parameters under ``<id>.``; a DWB or MPPI section is said in one line and
runs as RPP with its desired speed (DWB ``max_vel_x``, MPPI ``vx_max``);
``goal_checker_plugins`` ([goal_checker]; SimpleGoalChecker with ``xy_goal_tolerance`` 0.25,
``yaw_goal_tolerance`` 0.25, ``stateful`` true, or StoppedGoalChecker with
``rot_stopped_velocity`` and ``trans_stopped_velocity`` 0.25 too, against the odometry's twist),
``progress_checker_plugins`` ([progress_checker]; SimpleProgressChecker with
``required_movement_radius`` 0.5, ``movement_time_allowance`` 10.0, or PoseProgressChecker with
``required_movement_angle`` 0.5 too), ``min_x_velocity_threshold``,
``min_theta_velocity_threshold`` (0.0001), ``failure_tolerance`` (0.0 s; -1 forever),
``odom_topic`` (odom), ``speed_limit_topic`` (speed_limit, nav2_msgs/SpeedLimit),
``enable_stamped_cmd_vel`` (false: geometry_msgs/Twist; true: TwistStamped in the robot base
frame) and ``publish_zero_velocity`` (true).

Action ``follow_path`` (nav2_msgs/action/FollowPath), one goal at a time, a new one replacing
the path (:class:`amr_description.ros.goal_server.SingleGoalServer`). Each cycle: the robot's
pose from TF, the progress check (FAILED_TO_MAKE_PROGRESS), the path pruned to the pose
nearest the robot and put in the robot's frame, RPP's command with the collision check on the
local costmap's footprint cost (NO_VALID_CONTROL after ``failure_tolerance``), feedback
(``distance_to_goal`` along the path, ``speed``), ``cmd_vel`` (reliable, depth 1), then the
goal check against the path's last pose; a reached goal, a failure or a cancel publishes a zero
command (a cancel once the controller says it may end: RPP with ``use_cancel_deceleration``
slows down first, logging "Waiting for the controller to finish cancellation"). An empty or
NaN path is INVALID_PATH, an unknown ``controller_id`` INVALID_CONTROLLER, a missing transform
TF_ERROR. RPP's ``max_robot_pose_search_dist`` defaults to half the local costmap's width, as
upstream's; ``ros2 param set`` changes the parameters listed in
:meth:`ControllerServer._on_set_parameters`. Source: ``nav2_controller/src/controller_server.cpp``.
"""

import math

from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav import checkers
from amr_description.nav import pure_pursuit as rpp
from amr_description.nav.costmap import footprint_cost
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.costmap import NO_INFORMATION
from amr_description.nav.cycle_clock import CycleClock
from amr_description.nav.planner import path_length
from amr_description.nodes.costmap_2d import CostmapNode
from amr_description.ros import shutdown
from amr_description.ros.goal_server import SingleGoalServer
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.odometry_twist import TwistListener
from amr_description.ros.transforms import planar_pose
from amr_description.ros.transforms import TransformListener
from amr_description.ros.transforms import yaw_of
from amr_description.ros.twist_io import TwistPublisher
from nav2_msgs.action import FollowPath
from nav2_msgs.msg import SpeedLimit
import numpy as np
from rcl_interfaces.msg import SetParametersResult

RPP = 'RegulatedPurePursuitController'
GOAL_CHECKER_KEYS = {'xy_goal_tolerance': 'xy', 'yaw_goal_tolerance': 'yaw',
                     'stateful': 'stateful', 'rot_stopped_velocity': 'rot_stopped',
                     'trans_stopped_velocity': 'trans_stopped'}
"""A goal checker's parameters that ``ros2 param set`` changes, and their keys here."""
PROGRESS_CHECKER_KEYS = {'required_movement_radius': ('radius', 'radius'),
                         'movement_time_allowance': ('time', 'allowance'),
                         'required_movement_angle': ('angle', 'angle')}
"""A progress checker's parameters that ``ros2 param set`` changes: (key here, attribute)."""
OTHER_SPEEDS = {'DWBLocalPlanner': 'max_vel_x', 'MPPIController': 'vx_max'}
"""Controllers run as RPP here, and the parameter giving their desired speed."""


def plugin_kind(name):
    """Return the class part of a plugin name (``pkg::Class`` or ``pkg/Class``)."""
    return name.replace('/', '::').split('::')[-1]


def path_array(path_msg):
    """
    Return ``(n, 3)`` poses ``x, y, yaw`` of a nav_msgs/Path.

    :raises ValueError: when the path is empty or holds a NaN or infinite value.
    """
    poses = [(p.pose.position.x, p.pose.position.y, yaw_of(p.pose.orientation))
             for p in path_msg.poses]
    if not poses:
        raise ValueError('Path is empty.')
    out = np.array(poses, float)
    if not np.isfinite(out).all():
        raise ValueError('Path has a NaN or infinite value.')
    return out


class ControllerServer(ManagedNode):
    """Node ``controller_server``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters and make the local costmap node (``kwargs``: rclpy's)."""
        super().__init__('controller_server', **kwargs)
        d = self.declare_parameter
        self.frequency = float(d('controller_frequency', 20.0).value)
        self.min_v = float(d('min_x_velocity_threshold', 0.0001).value)
        d('min_y_velocity_threshold', 0.0001)
        self.min_w = float(d('min_theta_velocity_threshold', 0.0001).value)
        self.failure_tolerance = float(d('failure_tolerance', 0.0).value)
        self.odom_topic = str(d('odom_topic', 'odom').value)
        self.speed_limit_topic = str(d('speed_limit_topic', 'speed_limit').value)
        self.stamped = bool(d('enable_stamped_cmd_vel', False).value)
        self.zero_on_stop = bool(d('publish_zero_velocity', True).value)
        d('use_realtime_priority', False)
        d('costmap_update_timeout', 0.30)
        self.tf_buffer = TransformBuffer()
        ns = self.get_namespace()
        self.costmap = CostmapNode(
            'local_costmap', self.tf_buffer, ns if ns != '/' else '',
            use_sim_time=self.get_parameter('use_sim_time').value, **kwargs)
        self.controllers = {cid: self._controller_params(cid) for cid in
                            d('controller_plugins', ['FollowPath']).value}
        self.goal_checkers = {gid: self._goal_params(gid) for gid in
                              d('goal_checker_plugins', ['goal_checker']).value}
        self.progress_checkers = {pid: self._progress_params(pid) for pid in
                                  d('progress_checker_plugins', ['progress_checker']).value}
        self.companion_nodes = [self.costmap]
        self._listener = self._server = self._cmd_pub = self._timer = None
        self._entities = []
        self.speed = (0.0, 0.0)
        self._odom = None
        self._cycles = CycleClock(1.0 / max(self.frequency, 1e-3))
        self.speed_limit = None
        self.run = None

    def _goal_params(self, gid):
        d = self.declare_parameter
        params = {
            'plugin': str(d(f'{gid}.plugin', 'nav2_controller::SimpleGoalChecker').value),
            'xy': float(d(f'{gid}.xy_goal_tolerance', 0.25).value),
            'yaw': float(d(f'{gid}.yaw_goal_tolerance', 0.25).value),
            'stateful': bool(d(f'{gid}.stateful', True).value)}
        if params['plugin'].endswith('StoppedGoalChecker'):
            params['rot_stopped'] = float(d(f'{gid}.rot_stopped_velocity', 0.25).value)
            params['trans_stopped'] = float(d(f'{gid}.trans_stopped_velocity', 0.25).value)
        return params

    def _progress_params(self, pid):
        d = self.declare_parameter
        params = {
            'plugin': str(d(f'{pid}.plugin', 'nav2_controller::SimpleProgressChecker').value),
            'radius': float(d(f'{pid}.required_movement_radius', 0.5).value),
            'time': float(d(f'{pid}.movement_time_allowance', 10.0).value)}
        if params['plugin'].endswith('PoseProgressChecker'):
            params['angle'] = float(d(f'{pid}.required_movement_angle', 0.5).value)
        return params

    def _controller_params(self, cid):
        d = self.declare_parameter
        kind = str(d(f'{cid}.plugin', 'dwb_core::DWBLocalPlanner').value)
        params = {}
        if plugin_kind(kind) == RPP:
            defaults = dict(rpp.RPP_DEFAULTS)
            # upstream: half the local costmap's getSizeInMetersX(), (cells - 0.5) x resolution
            res = float(self.costmap.p['resolution'])
            cells = int(float(self.costmap.p['width']) / res) if res > 0.0 else 0
            defaults['max_robot_pose_search_dist'] = max(cells - 0.5, 0.0) * res / 2.0
            for name, default in defaults.items():
                params[name] = d(f'{cid}.{name}', default).value
        elif plugin_kind(kind) in OTHER_SPEEDS:
            speed = float(d(f'{cid}.{OTHER_SPEEDS[plugin_kind(kind)]}', 0.0).value)
            if speed > 0.0:
                params['desired_linear_vel'] = speed
        return {'plugin': kind, 'params': params}

    def configure(self):
        """Say which controller runs for each id; listen to TF."""
        self.get_logger().info('Configuring controller interface')
        for cid, c in self.controllers.items():
            if plugin_kind(c['plugin']) == RPP:
                self.get_logger().info(f"Created controller : {cid} of type {c['plugin']}")
                # as RPP's ParameterHandler: contradicting settings turned off, with a line
                c['params'], warnings = rpp.checked_params(c['params'])
                for line in warnings:
                    self.get_logger().warn(line)
            else:
                speed = c['params'].get('desired_linear_vel', rpp.RPP_DEFAULTS[
                    'desired_linear_vel'])
                self.get_logger().info(
                    f"{cid}: plugin '{c['plugin']}' runs as Regulated Pure Pursuit here, with "
                    f"desired_linear_vel {speed:g} and the goal checker's tolerances")
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)

    def activate(self):
        """Start the costmap, the action server, the command publisher and the loop."""
        self.get_logger().info('Activating')
        self.costmap.start()
        self._cmd_pub = TwistPublisher(self, 'cmd_vel', self.stamped,
                                       self.costmap.p['robot_base_frame'])
        self._odom = TwistListener(self, self.odom_topic, self._on_odom)
        self._timer = self.create_timer(1.0 / max(self.frequency, 1e-3), self._cycle)
        self._entities = [
            self._cmd_pub.pub,
            self.create_subscription(SpeedLimit, self.speed_limit_topic, self._on_speed_limit,
                                     10),
            self._timer]
        self._cycles.reset()
        self._server = SingleGoalServer(self, FollowPath, 'follow_path', self._on_goal)
        self.watch_parameters(self._on_set_parameters)

    def deactivate(self):
        """Stop the robot, the action server and the costmap."""
        self.get_logger().info('Deactivating')
        self.unwatch_parameters()
        if self._server is not None:
            self._stop_robot()
            self._server.destroy()
            self._server = None
        self.destroy_entities(self._entities)
        self._entities = []
        self._timer = None
        if self._odom is not None:
            self._odom.destroy()
            self._odom = None
        self._cmd_pub = None
        self.costmap.stop()

    def cleanup(self):
        """Stop listening to TF."""
        self.get_logger().info('Cleaning up')
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    # ros2 param set
    def _on_set_parameters(self, parameters):
        """
        Take ``ros2 param set`` values while active, as upstream's dynamic parameter callbacks.

        The controller server's ``controller_frequency``, ``min_x_velocity_threshold``,
        ``min_theta_velocity_threshold`` and ``failure_tolerance``; every RPP parameter; the goal
        and progress checkers' tolerances. Refused with upstream's line, nothing changed:
        ``allow_reversing`` true while ``use_rotate_to_heading`` is, and an
        ``inflation_cost_scaling_factor`` of 0 or less. Sources: ``dynamicParametersCallback``
        of ``controller_server.cpp`` and the checkers, RPP's ``parameter_handler.cpp``.
        """
        for parameter in parameters:
            cid, _, name = parameter.name.partition('.')
            c = self.controllers.get(cid)
            if c is None or plugin_kind(c['plugin']) != RPP:
                continue
            line = None
            if name == 'allow_reversing' and parameter.value and \
                    c['params']['use_rotate_to_heading']:
                line = ('Both use_rotate_to_heading and allow_reversing parameter cannot be set '
                        'to true. Rejecting parameter update.')
            elif name == 'inflation_cost_scaling_factor' and parameter.value <= 0.0:
                line = ('The value inflation_cost_scaling_factor is incorrectly set, it should '
                        'be >0. Ignoring parameter update.')
            if line is not None:
                self.get_logger().warn(line)
                return SetParametersResult(successful=False, reason=line)
        for parameter in parameters:
            self._apply_parameter(parameter.name, parameter.value)
        return SetParametersResult(successful=True)

    def _apply_parameter(self, full_name, value):
        run = self.run
        if full_name == 'controller_frequency' and value > 0.0:
            self.frequency = float(value)
            self._cycles.period = 1.0 / self.frequency
            if self._timer is not None:
                self._timer.timer_period_ns = int(1e9 / self.frequency)
        elif full_name == 'min_x_velocity_threshold':
            self.min_v = float(value)
        elif full_name == 'min_theta_velocity_threshold':
            self.min_w = float(value)
        elif full_name == 'failure_tolerance':
            self.failure_tolerance = float(value)
        owner, _, name = full_name.partition('.')
        if owner in self.controllers and name in rpp.RPP_DEFAULTS:
            self.controllers[owner]['params'][name] = value
            if run is not None and run['cid'] == owner:
                run['rpp'].p[name] = value
        elif owner in self.goal_checkers and name in GOAL_CHECKER_KEYS:
            key = GOAL_CHECKER_KEYS[name]
            self.goal_checkers[owner][key] = value
            if run is not None and run['gid'] == owner:
                setattr(run['goal'], key, value)
                if key == 'xy':  # RPP reads the goal checker's tolerance each cycle
                    run['rpp'].goal_xy_tolerance = float(value)
        elif owner in self.progress_checkers and name in PROGRESS_CHECKER_KEYS:
            key, attribute = PROGRESS_CHECKER_KEYS[name]
            self.progress_checkers[owner][key] = value
            if run is not None and run['pid'] == owner:
                setattr(run['progress'], attribute, value)

    # inputs
    def _on_odom(self, twist):
        # on the odometry's thread: one assignment
        v = twist[0] if abs(twist[0]) >= self.min_v else 0.0
        w = twist[5] if abs(twist[5]) >= self.min_w else 0.0
        self.speed = (v, w) if math.isfinite(v) and math.isfinite(w) else (0.0, 0.0)

    def _on_speed_limit(self, msg):
        limit = float(msg.speed_limit)
        if not math.isfinite(limit) or limit <= 0.0:
            self.speed_limit = None  # NO_SPEED_LIMIT
        else:
            self.speed_limit = (limit, bool(msg.percentage))

    def _pick(self, table, wanted, what):
        if wanted in table:
            return wanted
        if not wanted and len(table) == 1:
            return next(iter(table))
        raise LookupError(f'FollowPath called with {what} name {wanted!r}, which does not '
                          f'exist. Available: {list(table)}')

    def _on_goal(self, handle):
        goal = handle.request
        codes = FollowPath.Result
        try:
            cid = self._pick(self.controllers, goal.controller_id, 'controller')
            gid = self._pick(self.goal_checkers, goal.goal_checker_id, 'goal checker')
            pid = self._pick(self.progress_checkers, goal.progress_checker_id,
                             'progress checker')
        except LookupError as exc:
            return self._fail(codes.INVALID_CONTROLLER, str(exc))
        try:
            path = path_array(goal.path)
        except ValueError as exc:
            return self._fail(codes.INVALID_PATH, str(exc))
        same = self.run is not None and self.run['cid'] == cid
        if not same:
            gc, pc = self.goal_checkers[gid], self.progress_checkers[pid]
            controller = rpp.RegulatedPurePursuit(
                self.controllers[cid]['params'], gc['xy'], self.costmap.inscribed,
                self.costmap.circumscribed, self.costmap.p['resolution'])
            self.run = {'cid': cid, 'gid': gid, 'pid': pid, 'rpp': controller,
                        'failing_since': None,
                        'goal': _goal_checker(gc), 'progress': _progress_checker(pc)}
            self.get_logger().info('Received a goal, begin computing control effort.')
        else:
            self.get_logger().info('Passing new path to controller.')
            # as Nav2's setPlannerPath: the goal checker's and RPP's latches start over
            # (RegulatedPurePursuitController::setPlan clears has_reached_xy_tolerance_)
            self.run['goal'].reset()
            self.run['rpp'].reset()
        self.run['path'] = path
        self.run['frame'] = goal.path.header.frame_id or self.costmap.p['global_frame']

    # the loop
    def _now(self):
        return self.get_clock().now().nanoseconds * 1e-9

    def _cycle(self):
        server = self._server
        if server is None or not server.active:
            return
        run = self.run
        if server.cancel_requested:
            # the controller may first slow the robot down (RPP's use_cancel_deceleration)
            if run is None or run['rpp'].cancel():
                self.get_logger().info('Cancellation was successful. Stopping the robot.')
                self._stop_robot()
                server.finish_current('canceled', FollowPath.Result())
                self.run = None
                return
            self.get_logger().info('Waiting for the controller to finish cancellation',
                                   throttle_duration_sec=1.0)
        codes = FollowPath.Result
        step = self._cycles.tick(self._now())
        base = self.costmap.p['robot_base_frame']
        try:
            T_path, _ = self.tf_buffer.lookup(run['frame'], base)
            T_cost, _ = self.tf_buffer.lookup(self.costmap.p['global_frame'], base)
        except TransformException as exc:
            return self._fail(codes.TF_ERROR, f'Unable to transform the robot pose: '
                                              f'{str(exc).strip()}')
        robot, robot_cost = planar_pose(T_path), planar_pose(T_cost)
        if not run['progress'].check(robot_cost, self._now()):
            return self._fail(codes.FAILED_TO_MAKE_PROGRESS, 'Failed to make progress')
        path = run['path']
        k = rpp.closest_pose(path, robot, run['rpp'].p['max_robot_pose_search_dist'])
        run['path'] = path = path[k:]
        local = rpp.to_robot_frame(path, robot)
        remaining = path_length(local)
        try:
            v, w = self._command(run['rpp'], local, robot_cost, remaining, step)
            run['failing_since'] = None
        except rpp.NoValidControl as exc:
            now = self._now()
            if run['failing_since'] is None:
                run['failing_since'] = now
            tolerance = self.failure_tolerance
            if tolerance == 0.0 or (tolerance > 0.0 and now - run['failing_since'] > tolerance):
                return self._fail(codes.NO_VALID_CONTROL, str(exc))
            v = w = 0.0
        feedback = FollowPath.Feedback()
        feedback.speed = float(abs(v))
        feedback.distance_to_goal = float(remaining + math.hypot(*local[0, :2]))
        self._server.feedback(feedback)
        self._publish(v, w)
        if run['goal'].is_goal_reached(robot, path[-1], self.speed):
            self.get_logger().info('Reached the goal!')
            self._stop_robot()
            self._server.finish_current('succeed', FollowPath.Result())
            self.run = None

    def _command(self, controller, local, robot_cost, remaining, step):
        grid = self.costmap.grid
        cost = grid.cost_at(robot_cost[0], robot_cost[1]) or 0
        if self.speed_limit is not None:
            base = self.controllers[self.run['cid']]['params'].get(
                'desired_linear_vel', rpp.RPP_DEFAULTS['desired_linear_vel'])
            limit, percent = self.speed_limit
            controller.p['desired_linear_vel'] = min(base, base * limit / 100.0
                                                     if percent else limit)
        c, s = math.cos(robot_cost[2]), math.sin(robot_cost[2])
        circular = self.costmap.p['footprint'] in ('', '[]')
        footprint = self.costmap.footprint
        track_unknown = self.costmap.p['track_unknown_space']

        def collides(x, y, yaw):
            pose = (robot_cost[0] + c * x - s * y, robot_cost[1] + s * x + c * y,
                    robot_cost[2] + yaw)
            if circular:
                return rpp.circle_collides(grid, pose[0], pose[1])
            value = footprint_cost(grid, footprint, pose)
            if value == NO_INFORMATION and track_unknown:
                return False
            return value >= LETHAL_OBSTACLE

        dt, lateness = step  # the loop's step and lateness (CycleClock)
        return controller.compute(local, self.speed, dt, cost, remaining, collides, lateness)

    # outputs
    def _publish(self, v, w):
        if self._cmd_pub is not None:
            self._cmd_pub.publish(v, w)

    def _stop_robot(self):
        if self.zero_on_stop:
            self._publish(0.0, 0.0)

    def _fail(self, code, message):
        self.get_logger().error(message)
        self._stop_robot()
        result = FollowPath.Result()
        result.error_code = code
        result.error_msg = message
        if self._server is not None:
            self._server.finish_current('abort', result)
        self.run = None


def _goal_checker(params):
    """Return the goal checker of a :meth:`ControllerServer._goal_params` dict."""
    if 'rot_stopped' in params:  # declared for StoppedGoalChecker only
        return checkers.StoppedGoalChecker(params['xy'], params['yaw'], params['stateful'],
                                           params['rot_stopped'], params['trans_stopped'])
    return checkers.SimpleGoalChecker(params['xy'], params['yaw'], params['stateful'])


def _progress_checker(params):
    """Return the progress checker of a :meth:`ControllerServer._progress_params` dict."""
    if 'angle' in params:  # declared for PoseProgressChecker only
        return checkers.PoseProgressChecker(params['radius'], params['time'], params['angle'])
    return checkers.SimpleProgressChecker(params['radius'], params['time'])


def main(args=None):
    """
    Run the controller server and its local costmap until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(ControllerServer, args)


if __name__ == '__main__':
    main()
