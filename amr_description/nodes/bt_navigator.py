# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``bt_navigator``: nav2_bt_navigator's navigator (Jazzy), a managed (lifecycle) node.

The default behaviour tree's semantics are written as code
(:mod:`amr_description.nav.navigation_logic`): ``navigate_to_pose``
(nav2_msgs/action/NavigateToPose) and ``navigate_through_poses`` (NavigateThroughPoses) plan
with the planner server's ``compute_path_to_pose`` / ``compute_path_through_poses`` (planner
``GridBased``) at 1 Hz, follow with the controller server's ``follow_path`` (controller
``FollowPath``), on a failure clear the costmaps, and run the round robin of recoveries
(``spin``, ``wait``, ``backup`` of the behaviour server) up to 6 times. One navigation runs at
a time; a new goal on either action pre-empts it. Feedback as upstream's: ``current_pose``,
``navigation_time``, ``estimated_time_remaining``, ``number_of_recoveries``,
``distance_remaining`` (and ``number_of_poses_remaining``); passed poses (within 0.5 m) are
dropped as RemovePassedGoals does. A failed navigation's ``error_code`` is the smallest
non-zero of the planner's and the controller's. ``goal_pose`` (geometry_msgs/PoseStamped, RViz's
"2D Goal Pose") starts a NavigateToPose through the action, as upstream's navigator does.

Parameters, with Nav2's defaults: ``global_frame`` (map), ``robot_base_frame`` (base_link),
``transform_tolerance`` (0.1), ``odom_topic`` (odom), ``navigators``
([navigate_to_pose, navigate_through_poses]) with ``<id>.plugin``, ``bt_loop_duration``
(10 ms; ticks run at most at 20 Hz here, and only while a navigation runs: a goal's first
tick runs when it is accepted, and a step's goal goes to its server as soon as the step before
it ends, not at the next tick),
``error_code_names``, ``default_nav_to_pose_bt_xml`` and ``default_nav_through_poses_bt_xml``
(a tree other than the default, here or in a goal's ``behavior_tree``, is said in one line and
the default's semantics run). A server that stays
undiscovered for :data:`SERVER_WAIT` s fails its step as an UNKNOWN error.
Sources: ``nav2_bt_navigator/src/bt_navigator.cpp``, ``src/navigators/*.cpp``.
"""

import math
import os

from action_msgs.msg import GoalStatus
from amr_description.core.tf_buffer import TransformBuffer
from amr_description.core.tf_buffer import TransformException
from amr_description.nav import navigation_logic as logic
from amr_description.ros import shutdown
from amr_description.ros.goal_server import GoalClient
from amr_description.ros.goal_server import SingleGoalServer
from amr_description.ros.managed_node import ManagedNode
from amr_description.ros.odometry_twist import TwistListener
from amr_description.ros.transforms import planar_pose
from amr_description.ros.transforms import set_yaw
from amr_description.ros.transforms import transform_planar
from amr_description.ros.transforms import TransformListener
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import BackUp
from nav2_msgs.action import ComputePathThroughPoses
from nav2_msgs.action import ComputePathToPose
from nav2_msgs.action import FollowPath
from nav2_msgs.action import NavigateThroughPoses
from nav2_msgs.action import NavigateToPose
from nav2_msgs.action import Spin
from nav2_msgs.action import Wait
from nav2_msgs.srv import ClearEntireCostmap
import numpy as np
from rclpy.duration import Duration

DEFAULT_TREES = ('navigate_to_pose_w_replanning_and_recovery.xml',
                 'navigate_through_poses_w_replanning_and_recovery.xml')
SERVER_WAIT = 20.0
"""Seconds a server may stay undiscovered before its step fails."""
CLEAR = {'global': 'global_costmap/clear_entirely_global_costmap',
         'local': 'local_costmap/clear_entirely_local_costmap'}


def duration(seconds):
    """Return a builtin_interfaces/Duration of ``seconds``."""
    return Duration(nanoseconds=int(max(seconds, 0.0) * 1e9)).to_msg()


class BtNavigator(ManagedNode):
    """Node ``bt_navigator``; see the module docstring."""

    def __init__(self, **kwargs):
        """Declare the parameters (``kwargs``: rclpy's node options)."""
        super().__init__('bt_navigator', **kwargs)
        d = self.declare_parameter
        self.p = {k: d(k, v).value for k, v in {
            'global_frame': 'map', 'robot_base_frame': 'base_link',
            'transform_tolerance': 0.1, 'odom_topic': 'odom', 'bt_loop_duration': 10,
            'default_server_timeout': 20, 'wait_for_service_timeout': 1000,
            'action_server_result_timeout': 900.0, 'always_reload_bt_xml': False,
            'default_nav_to_pose_bt_xml': '', 'default_nav_through_poses_bt_xml': '',
            'goal_blackboard_id': 'goal', 'goals_blackboard_id': 'goals',
            'path_blackboard_id': 'path', 'plugin_lib_names': [''],
            'error_code_names': ['follow_path_error_code', 'compute_path_error_code'],
            'navigators': ['navigate_to_pose', 'navigate_through_poses']}.items()}
        self.plugins = {}
        for nid in self.p['navigators']:
            default = ('nav2_bt_navigator::NavigateThroughPosesNavigator' if 'through' in nid
                       else 'nav2_bt_navigator::NavigateToPoseNavigator')
            self.plugins[nid] = str(d(f'{nid}.plugin', default).value)
        self.tf_buffer = TransformBuffer()
        self._listener = None
        self._entities = []
        self.servers = {}
        self.goal_clients = {}
        self.nav = None
        self.speed = 0.0
        self._odom = self._timer = None

    def configure(self):
        """Create the clients of the servers the tree uses; listen to TF."""
        self.get_logger().info('Configuring')
        for key in ('default_nav_to_pose_bt_xml', 'default_nav_through_poses_bt_xml'):
            tree = str(self.p[key])
            if tree and os.path.basename(tree) not in DEFAULT_TREES:
                self.get_logger().info(f"{key} '{tree}': the default tree's behaviour "
                                       '(replanning at 1 Hz with recoveries) runs here')
        self.goal_clients = {
            'plan': GoalClient(self, ComputePathToPose, 'compute_path_to_pose'),
            'plan_through': GoalClient(self, ComputePathThroughPoses,
                                       'compute_path_through_poses'),
            'follow': GoalClient(self, FollowPath, 'follow_path'),
            'spin': GoalClient(self, Spin, 'spin'),
            'wait': GoalClient(self, Wait, 'wait'),
            'backup': GoalClient(self, BackUp, 'backup'),
            'goal_pose': GoalClient(self, NavigateToPose, 'navigate_to_pose')}
        self.clear_clients = {k: self.create_client(ClearEntireCostmap, v)
                              for k, v in CLEAR.items()}
        self._listener = TransformListener(self, self.tf_buffer, spin_thread=True)

    def activate(self):
        """Offer the navigators' actions; listen to ``goal_pose`` and odometry."""
        self.get_logger().info('Activating')
        kinds = {'NavigateToPoseNavigator': NavigateToPose,
                 'NavigateThroughPosesNavigator': NavigateThroughPoses}
        for nid, plugin in self.plugins.items():
            kind = plugin.replace('/', '::').split('::')[-1]
            if kind not in kinds:
                self.get_logger().warning(f"{nid}: navigator plugin '{plugin}' is not "
                                          'available here; not offered')
                continue
            self.servers[nid] = SingleGoalServer(
                self, kinds[kind], nid, lambda h, n=nid, t=kinds[kind]: self._on_goal(n, t, h))
        period = max(float(self.p['bt_loop_duration']) / 1000.0, 0.05)
        self._odom = TwistListener(self, self.p['odom_topic'], self._on_odom)
        # ticks only while a navigation runs, as upstream's tree (_tick cancels it when idle)
        self._timer = self.create_timer(period, self._tick)
        self._timer.cancel()
        self._entities = [
            self.create_subscription(PoseStamped, 'goal_pose', self._on_goal_pose, 10),
            self._timer]

    def deactivate(self):
        """Abort a running navigation and withdraw the actions."""
        self.get_logger().info('Deactivating')
        if self.nav is not None:
            self._end('abort', 'navigator deactivated')
        for server in self.servers.values():
            server.destroy()
        self.servers = {}
        self.destroy_entities(self._entities)
        self._entities = []
        self._timer = None
        if self._odom is not None:
            self._odom.destroy()
            self._odom = None

    def cleanup(self):
        """Destroy the clients; stop listening to TF."""
        self.get_logger().info('Cleaning up')
        for client in self.goal_clients.values():
            client.destroy()
        for client in getattr(self, 'clear_clients', {}).values():
            self.destroy_client(client)
        self.goal_clients, self.clear_clients = {}, {}
        if self._listener is not None:
            self._listener.destroy()
            self._listener = None

    # inputs
    def _on_odom(self, twist):
        # on the odometry's thread: one assignment
        v = twist[0]
        self.speed = v if math.isfinite(v) else 0.0

    def _on_goal_pose(self, msg):
        self.get_logger().info('Received goal pose on goal_pose; sending it to '
                               'navigate_to_pose')
        goal = NavigateToPose.Goal()
        goal.pose = msg
        self.goal_clients['goal_pose'].send(goal)

    def _now(self):
        return self.get_clock().now().nanoseconds * 1e-9

    def _in_global(self, pose):
        """Return ``pose`` (PoseStamped) in the global frame, or itself if TF cannot."""
        frame = self.p['global_frame']
        source = pose.header.frame_id or frame
        if source == frame:
            return pose
        try:
            T, _ = self.tf_buffer.lookup(frame, source)
        except TransformException as exc:
            self.get_logger().warning(f'goal in {source!r}: {str(exc).strip()}')
            return pose
        out = PoseStamped()
        out.header.frame_id = frame
        out.header.stamp = pose.header.stamp
        x, y, yaw = transform_planar(T, pose.pose)
        out.pose.position.x, out.pose.position.y = x, y
        set_yaw(out.pose.orientation, yaw)
        return out

    def _robot(self):
        try:
            T, _ = self.tf_buffer.lookup(self.p['global_frame'], self.p['robot_base_frame'])
        except TransformException:
            return None
        return planar_pose(T)

    # navigations
    def _on_goal(self, nid, action, handle):
        for other, server in self.servers.items():
            if other != nid and server.active:
                server.finish_current('abort', server.type.Result())
        if self.nav is not None:
            self._stop_clients()
        goal = handle.request
        if goal.behavior_tree and os.path.basename(goal.behavior_tree) not in DEFAULT_TREES:
            self.get_logger().info(f"behavior_tree '{goal.behavior_tree}': the default "
                                   "tree's behaviour runs here")
        poses = [goal.pose] if action is NavigateToPose else list(goal.poses)
        if not poses:
            self.nav = None
            result = action.Result()
            result.error_code = ComputePathThroughPoses.Result.NO_VIAPOINTS_GIVEN
            result.error_msg = 'No goals given'
            self.get_logger().error('Goal failed: No goals given')
            return self.servers[nid].finish_current('abort', result)
        goals = [self._in_global(p) for p in poses]
        g = goals[-1].pose.position
        self.get_logger().info(f'Begin navigating from the current location to '
                               f'({g.x:.2f}, {g.y:.2f})')
        self.nav = {'server': self.servers[nid], 'action': action, 'goals': goals,
                    't0': self._now(), 'recoveries': 0, 'retries': 0, 'compute': 0,
                    'follow': 0, 'path': None, 'last_plan': -math.inf, 'plan_retry': False,
                    'follow_retry': False, 'state': 'run', 'rr': 0, 'rr_failed': 0,
                    'to_send': {}, 'clearing': 0}
        self._timer.reset()
        self._tick()  # the first plan now, not a loop period later

    def _stop_clients(self):
        for name, client in self.goal_clients.items():
            if name == 'goal_pose':
                continue  # the goal being run may be the one it sent on behalf of /goal_pose
            if client.busy or client.handle is not None:
                client.cancel()

    def _end(self, outcome, message=''):
        nav, self.nav = self.nav, None
        self._stop_clients()
        result = nav['action'].Result()
        names = {'follow_path_error_code': nav['follow'],
                 'compute_path_error_code': nav['compute']}
        result.error_code = logic.error_code(names.get(n, 0) for n in self.p['error_code_names'])
        result.error_msg = message
        if outcome == 'succeed':
            self.get_logger().info('Goal succeeded')
        elif outcome == 'abort':
            self.get_logger().error(f'Goal failed: {message or "error code"} '
                                    f'(error_code {result.error_code})')
        else:
            self.get_logger().info('Goal canceled')
        nav['server'].finish_current(outcome, result)

    def _send(self, nav, name, goal, on_done):
        """Send now if the server is discovered, else at the first tick that finds it."""
        client = self.goal_clients[name]
        if client.ready():
            client.send(goal, lambda s, r, n=nav, k=name, f=on_done: self._done(n, k, s, r, f))
        else:
            nav['to_send'][name] = (goal, on_done, self._now())

    def _tick(self):
        nav = self.nav
        if nav is None:
            self._timer.cancel()
            return
        if not nav['server'].active:
            self.nav = None
            self._stop_clients()
            return
        if nav['server'].cancel_requested:
            return self._end('canceled')
        now = self._now()
        for name, (goal, on_done, since) in list(nav['to_send'].items()):
            client = self.goal_clients[name]
            if client.ready():
                del nav['to_send'][name]
                self._send(nav, name, goal, on_done)
            elif now - since > SERVER_WAIT:
                del nav['to_send'][name]
                self._done(nav, name, GoalStatus.STATUS_ABORTED, None, on_done)
        robot = self._robot()
        if nav['state'] == 'run':
            self._drop_passed(nav, robot)
            planner = 'plan' if nav['action'] is NavigateToPose else 'plan_through'
            if not self.goal_clients[planner].busy and planner not in nav['to_send'] and \
                    not nav['clearing'] and now - nav['last_plan'] >= logic.REPLAN_PERIOD:
                nav['last_plan'] = now
                self._send(nav, planner, self._plan_goal(nav), self._plan_done)
        if self.nav is nav and robot is not None:
            self._feedback(nav, robot, now)

    def _done(self, nav, name, status, result, on_done):
        if self.nav is nav:
            on_done(nav, status, result)

    def _plan_goal(self, nav):
        if nav['action'] is NavigateToPose:
            goal = ComputePathToPose.Goal()
            goal.goal = nav['goals'][-1]
        else:
            goal = ComputePathThroughPoses.Goal()
            goal.goals = nav['goals']
        goal.planner_id = 'GridBased'
        return goal

    def _drop_passed(self, nav, robot):
        if nav['action'] is NavigateToPose or robot is None:
            return
        xy = [(g.pose.position.x, g.pose.position.y) for g in nav['goals']]
        n = logic.passed_goals(xy, robot[:2])
        if n:
            del nav['goals'][:n]

    def _plan_done(self, nav, status, result):
        if status == GoalStatus.STATUS_SUCCEEDED:
            nav['compute'], nav['plan_retry'] = 0, False
            nav['path'] = result.path
            nav['path_xy'] = np.array([(p.pose.position.x, p.pose.position.y)
                                       for p in result.path.poses]).reshape(-1, 2)
            goal = FollowPath.Goal()
            goal.path = result.path
            goal.controller_id = 'FollowPath'
            self._send(nav, 'follow', goal, self._follow_done)
            return
        code = result.error_code if result is not None else 200
        nav['compute'] = code
        nav['message'] = result.error_msg if result is not None else 'planner not available'
        if code in logic.PLANNER_HELPS and not nav['plan_retry']:
            nav['plan_retry'] = True
            self._clear(nav, ['global'], lambda: nav.__setitem__('last_plan', -math.inf))
        else:
            self._pipeline_failed(nav)

    def _follow_done(self, nav, status, result):
        if status == GoalStatus.STATUS_SUCCEEDED:
            nav['follow'] = 0
            return self._end('succeed')
        code = result.error_code if result is not None else 100
        nav['follow'] = code
        nav['message'] = result.error_msg if result is not None else 'controller not available'
        if code in logic.CONTROLLER_HELPS and not nav['follow_retry'] and \
                nav['path'] is not None:
            nav['follow_retry'] = True
            goal = FollowPath.Goal()
            goal.path = nav['path']
            goal.controller_id = 'FollowPath'
            self._clear(nav, ['local'], lambda: self._send(nav, 'follow', goal,
                                                           self._follow_done))
        else:
            self._pipeline_failed(nav)

    def _clear(self, nav, which, then):
        nav['clearing'] += len(which)

        def one_done(_=None):
            nav['clearing'] -= 1
            if nav['clearing'] == 0 and self.nav is nav:
                then()

        for key in which:
            client = self.clear_clients[key]
            if client.service_is_ready():
                client.call_async(ClearEntireCostmap.Request()).add_done_callback(one_done)
            else:
                self.get_logger().warning(f'{CLEAR[key]} is not available; not cleared')
                one_done()

    def _pipeline_failed(self, nav):
        self._stop_clients()
        nav['to_send'].clear()
        if nav['retries'] < logic.NUMBER_OF_RETRIES and \
                logic.recovery_could_help(nav['compute'], nav['follow']):
            nav['state'] = 'recover'
            self._recover(nav)
        else:
            self._end('abort', nav.get('message') or 'navigation failed')

    def _recover(self, nav):
        kind, arg = logic.RECOVERIES[nav['rr'] % len(logic.RECOVERIES)]
        nav['rr'] += 1
        self.get_logger().info(f'Running recovery: {kind}')
        if kind == 'clear':
            self._clear(nav, ['local', 'global'], lambda: self._recovered(nav, True))
            return
        nav['recoveries'] += 1
        if kind == 'spin':
            goal = Spin.Goal()
            goal.target_yaw = float(arg)
            goal.time_allowance = duration(10.0)
        elif kind == 'wait':
            goal = Wait.Goal()
            goal.time = duration(arg)
        else:
            goal = BackUp.Goal()
            goal.target.x, goal.speed = float(arg[0]), float(arg[1])
            goal.time_allowance = duration(10.0)
        self._send(nav, kind, goal, lambda n, s, r: self._recovered(
            n, s == GoalStatus.STATUS_SUCCEEDED))

    def _recovered(self, nav, ok):
        if self.nav is not nav:
            return
        if not ok:
            nav['rr_failed'] += 1
            if nav['rr_failed'] >= len(logic.RECOVERIES):
                return self._end('abort', 'every recovery failed')
            return self._recover(nav)
        nav.update(retries=nav['retries'] + 1, state='run', plan_retry=False,
                   follow_retry=False, last_plan=-math.inf, rr_failed=0, path=None)

    def _feedback(self, nav, robot, now):
        fb = nav['action'].Feedback()
        fb.current_pose.header.frame_id = self.p['global_frame']
        fb.current_pose.header.stamp = self.get_clock().now().to_msg()
        fb.current_pose.pose.position.x, fb.current_pose.pose.position.y = map(float, robot[:2])
        set_yaw(fb.current_pose.pose.orientation, float(robot[2]))
        fb.navigation_time = duration(now - nav['t0'])
        fb.number_of_recoveries = int(nav['recoveries'])
        distance = 0.0
        if nav['path'] is not None:  # its xy made once per plan, not per tick
            distance = logic.remaining_distance(nav['path_xy'], robot[:2])
        fb.distance_remaining = float(distance)
        fb.estimated_time_remaining = duration(logic.time_remaining(distance, self.speed))
        if nav['action'] is NavigateThroughPoses:
            fb.number_of_poses_remaining = len(nav['goals'])
        nav['server'].feedback(fb)


def main(args=None):
    """
    Run the navigator until Ctrl-C.

    :param args: command-line arguments for rclpy (default ``sys.argv``).
    """
    shutdown.run(BtNavigator, args)


if __name__ == '__main__':
    main()
