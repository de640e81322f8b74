# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``nav2_simple_commander.robot_navigator``: Nav2's Python API for scripts (Jazzy), on rclpy.

:class:`BasicNavigator` is an rclpy node with the action clients, topics and service clients
of upstream's (relative names, so ``namespace`` applies) and every public method with its
signature and behaviour: a task method sends a goal and returns whether it was accepted;
:meth:`BasicNavigator.isTaskComplete` spins up to 0.1 s on the result; :meth:`getResult`
maps the final status to :class:`TaskResult`. Waiting spins the node with
``spin_once`` (upstream's ``spin_until_future_complete`` with a time-out busy-waits in
Jazzy's rclpy). Docking and GPS waypoints are refused with one error line (their servers
are not built here). The later Jazzy's ``clearCostmapExceptRegion``, ``clearCostmapAroundRobot``
and ``clearCostmapAroundPose`` call the local costmap's ``clear_except_local_costmap``,
``clear_around_local_costmap`` and ``clear_around_pose_local_costmap``: upstream's call
``local_costmap/clear_costmap_except_region`` and the like, names no costmap offers, and wait
for ever. Source: ``nav2_simple_commander/robot_navigator.py`` (Jazzy).
"""

from enum import Enum
import time

from action_msgs.msg import GoalStatus
from builtin_interfaces.msg import Duration
from geometry_msgs.msg import PoseStamped
from geometry_msgs.msg import PoseWithCovarianceStamped
from lifecycle_msgs.srv import GetState
from nav2_msgs.action import AssistedTeleop
from nav2_msgs.action import BackUp
from nav2_msgs.action import ComputePathThroughPoses
from nav2_msgs.action import ComputePathToPose
from nav2_msgs.action import DriveOnHeading
from nav2_msgs.action import FollowPath
from nav2_msgs.action import FollowWaypoints
from nav2_msgs.action import NavigateThroughPoses
from nav2_msgs.action import NavigateToPose
from nav2_msgs.action import SmoothPath
from nav2_msgs.action import Spin
from nav2_msgs.srv import ClearCostmapAroundPose
from nav2_msgs.srv import ClearCostmapAroundRobot
from nav2_msgs.srv import ClearCostmapExceptRegion
from nav2_msgs.srv import ClearEntireCostmap
from nav2_msgs.srv import GetCostmap
from nav2_msgs.srv import LoadMap
from nav2_msgs.srv import ManageLifecycleNodes
import rclpy
from rclpy.action import ActionClient
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy
from rclpy.qos import HistoryPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy


class TaskResult(Enum):
    """The outcome of the last task."""

    UNKNOWN = 0
    SUCCEEDED = 1
    CANCELED = 2
    FAILED = 3


class BasicNavigator(Node):
    """
    Nav2's BasicNavigator; see the module docstring.

    :param node_name: the node's name (default ``basic_navigator``).
    :param namespace: the robot's namespace ('' at the root).
    """

    def __init__(self, node_name='basic_navigator', namespace=''):
        """Create the clients, ``amcl_pose`` subscription and ``initialpose`` publisher."""
        super().__init__(node_name=node_name, namespace=namespace)
        self.initial_pose = PoseStamped()
        self.initial_pose.header.frame_id = 'map'
        self.goal_handle = None
        self.result_future = None
        self.feedback = None
        self.status = None
        self.initial_pose_received = False
        amcl_pose_qos = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL,
                                   reliability=ReliabilityPolicy.RELIABLE,
                                   history=HistoryPolicy.KEEP_LAST, depth=1)
        self.nav_through_poses_client = ActionClient(self, NavigateThroughPoses,
                                                     'navigate_through_poses')
        self.nav_to_pose_client = ActionClient(self, NavigateToPose, 'navigate_to_pose')
        self.follow_waypoints_client = ActionClient(self, FollowWaypoints, 'follow_waypoints')
        self.follow_path_client = ActionClient(self, FollowPath, 'follow_path')
        self.compute_path_to_pose_client = ActionClient(self, ComputePathToPose,
                                                        'compute_path_to_pose')
        self.compute_path_through_poses_client = ActionClient(
            self, ComputePathThroughPoses, 'compute_path_through_poses')
        self.smoother_client = ActionClient(self, SmoothPath, 'smooth_path')
        self.spin_client = ActionClient(self, Spin, 'spin')
        self.backup_client = ActionClient(self, BackUp, 'backup')
        self.drive_on_heading_client = ActionClient(self, DriveOnHeading, 'drive_on_heading')
        self.assisted_teleop_client = ActionClient(self, AssistedTeleop, 'assisted_teleop')
        self.localization_pose_sub = self.create_subscription(
            PoseWithCovarianceStamped, 'amcl_pose', self._amclPoseCallback, amcl_pose_qos)
        self.initial_pose_pub = self.create_publisher(PoseWithCovarianceStamped,
                                                      'initialpose', 10)
        self.change_maps_srv = self.create_client(LoadMap, 'map_server/load_map')
        self.clear_costmap_global_srv = self.create_client(
            ClearEntireCostmap, 'global_costmap/clear_entirely_global_costmap')
        self.clear_costmap_local_srv = self.create_client(
            ClearEntireCostmap, 'local_costmap/clear_entirely_local_costmap')
        self.get_costmap_global_srv = self.create_client(GetCostmap,
                                                         'global_costmap/get_costmap')
        self.get_costmap_local_srv = self.create_client(GetCostmap, 'local_costmap/get_costmap')
        self.clear_costmap_except_region_srv = self.create_client(
            ClearCostmapExceptRegion, 'local_costmap/clear_except_local_costmap')
        self.clear_costmap_around_robot_srv = self.create_client(
            ClearCostmapAroundRobot, 'local_costmap/clear_around_local_costmap')
        self.clear_costmap_around_pose_srv = self.create_client(
            ClearCostmapAroundPose, 'local_costmap/clear_around_pose_local_costmap')

    # helpers
    def _spin_until(self, future, timeout_sec=None):
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while not future.done():
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0.0:
                return
            rclpy.spin_once(self, timeout_sec=0.05 if left is None else min(left, 0.05))

    def _wait_server(self, client, label):
        self.debug(f"Waiting for '{label}' action server")
        while not client.wait_for_server(timeout_sec=1.0):
            self.info(f"'{label}' action server not available, waiting...")

    def _send(self, client, goal, what):
        future = client.send_goal_async(goal, self._feedbackCallback)
        self._spin_until(future)
        self.goal_handle = future.result()
        if not self.goal_handle.accepted:
            self.error(f'{what} was rejected!')
            return False
        self.result_future = self.goal_handle.get_result_async()
        return True

    def _blocking(self, client, goal, label):
        """Send, wait for the result; return the result message or None."""
        self._wait_server(client, label)
        future = client.send_goal_async(goal)
        self._spin_until(future)
        self.goal_handle = future.result()
        if not self.goal_handle.accepted:
            self.error(f'{label} goal was rejected!')
            return None
        self.result_future = self.goal_handle.get_result_async()
        self._spin_until(self.result_future)
        self.status = self.result_future.result().status
        if self.status != GoalStatus.STATUS_SUCCEEDED:
            self.warn(f'Getting path failed with status code: {self.status}')
            return None
        return self.result_future.result().result

    @staticmethod
    def _duration(seconds):
        return Duration(sec=int(seconds), nanosec=int((seconds - int(seconds)) * 1e9))

    # the API
    def destroyNode(self):
        """Destroy the node (``destroy_node``)."""
        self.destroy_node()

    def destroy_node(self):
        """Destroy the action clients, then the node."""
        for client in (self.nav_through_poses_client, self.nav_to_pose_client,
                       self.follow_waypoints_client, self.follow_path_client,
                       self.compute_path_to_pose_client, self.compute_path_through_poses_client,
                       self.smoother_client, self.spin_client, self.backup_client,
                       self.drive_on_heading_client, self.assisted_teleop_client):
            client.destroy()
        super().destroy_node()

    def setInitialPose(self, initial_pose):
        """Publish ``initial_pose`` (PoseStamped) on ``initialpose`` with zero covariance."""
        self.initial_pose_received = False
        self.initial_pose = initial_pose
        self._setInitialPose()

    def goThroughPoses(self, poses, behavior_tree=''):
        """Send a NavigateThroughPoses goal; return True when accepted."""
        self._wait_server(self.nav_through_poses_client, 'NavigateThroughPoses')
        goal = NavigateThroughPoses.Goal()
        goal.poses = list(poses)
        goal.behavior_tree = behavior_tree
        self.info(f'Navigating with {len(goal.poses)} goals....')
        return self._send(self.nav_through_poses_client, goal,
                          f'Goal with {len(goal.poses)} poses')

    def goToPose(self, pose, behavior_tree=''):
        """Send a NavigateToPose goal; return True when accepted."""
        self._wait_server(self.nav_to_pose_client, 'NavigateToPose')
        goal = NavigateToPose.Goal()
        goal.pose = pose
        goal.behavior_tree = behavior_tree
        where = f'{pose.pose.position.x} {pose.pose.position.y}'
        self.info(f'Navigating to goal: {where}...')
        return self._send(self.nav_to_pose_client, goal, f'Goal to {where}')

    def followWaypoints(self, poses):
        """Send a FollowWaypoints goal; return True when accepted."""
        self._wait_server(self.follow_waypoints_client, 'FollowWaypoints')
        goal = FollowWaypoints.Goal()
        goal.poses = list(poses)
        self.info(f'Following {len(goal.poses)} goals....')
        return self._send(self.follow_waypoints_client, goal,
                          f'Following {len(goal.poses)} waypoints request')

    def followGpsWaypoints(self, gps_poses):
        """Refuse: the GPS waypoint follower is not built here."""
        self.error('followGpsWaypoints: follow_gps_waypoints is not available here')
        return False

    def spin(self, spin_dist=1.57, time_allowance=10):
        """Send a Spin goal; return True when accepted."""
        self._wait_server(self.spin_client, 'Spin')
        goal = Spin.Goal()
        goal.target_yaw = float(spin_dist)
        goal.time_allowance = Duration(sec=int(time_allowance))
        self.info(f'Spinning to angle {goal.target_yaw}....')
        return self._send(self.spin_client, goal, 'Spin request')

    def backup(self, backup_dist=0.15, backup_speed=0.025, time_allowance=10):
        """Send a BackUp goal; return True when accepted."""
        self._wait_server(self.backup_client, 'Backup')
        goal = BackUp.Goal()
        goal.target.x = float(backup_dist)
        goal.speed = float(backup_speed)
        goal.time_allowance = Duration(sec=int(time_allowance))
        self.info(f'Backing up {goal.target.x} m at {goal.speed} m/s....')
        return self._send(self.backup_client, goal, 'Backup request')

    def driveOnHeading(self, dist=0.15, speed=0.025, time_allowance=10):
        """Send a DriveOnHeading goal; return True when accepted."""
        self._wait_server(self.drive_on_heading_client, 'DriveOnHeading')
        goal = DriveOnHeading.Goal()
        goal.target.x = float(dist)
        goal.speed = float(speed)
        goal.time_allowance = Duration(sec=int(time_allowance))
        self.info(f'Drive {goal.target.x} m on heading at {goal.speed} m/s....')
        return self._send(self.drive_on_heading_client, goal, 'Drive On Heading request')

    def assistedTeleop(self, time_allowance=30):
        """Send an AssistedTeleop goal; return True when accepted."""
        self._wait_server(self.assisted_teleop_client, 'assisted_teleop')
        goal = AssistedTeleop.Goal()
        goal.time_allowance = Duration(sec=int(time_allowance))
        self.info("Running 'assisted_teleop'....")
        return self._send(self.assisted_teleop_client, goal, 'Assisted Teleop request')

    def followPath(self, path, controller_id='', goal_checker_id=''):
        """Send a FollowPath goal; return True when accepted."""
        self._wait_server(self.follow_path_client, 'FollowPath')
        goal = FollowPath.Goal()
        goal.path = path
        goal.controller_id = controller_id
        goal.goal_checker_id = goal_checker_id
        self.info('Executing path...')
        return self._send(self.follow_path_client, goal, 'Follow path')

    def dockRobotByPose(self, dock_pose, dock_type='', nav_to_dock=True):
        """Refuse: the docking server is not built here."""
        self.error('dockRobotByPose: dock_robot is not available here')
        return False

    def dockRobotByID(self, dock_id, nav_to_dock=True):
        """Refuse: the docking server is not built here."""
        self.error('dockRobotByID: dock_robot is not available here')
        return False

    def undockRobot(self, dock_type=''):
        """Refuse: the docking server is not built here."""
        self.error('undockRobot: undock_robot is not available here')
        return False

    def cancelTask(self):
        """Cancel the running task, if any."""
        self.info('Canceling current task.')
        if self.result_future:
            future = self.goal_handle.cancel_goal_async()
            self._spin_until(future)

    def isTaskComplete(self):
        """Spin up to 0.1 s; return True when the task ended (or there is none)."""
        if not self.result_future:
            return True
        self._spin_until(self.result_future, timeout_sec=0.10)
        if self.result_future.result():
            self.status = self.result_future.result().status
            if self.status != GoalStatus.STATUS_SUCCEEDED:
                self.debug(f'Task with failed with status code: {self.status}')
                return True
        else:
            return False
        self.debug('Task succeeded!')
        return True

    def getFeedback(self):
        """Return the last feedback message of the task."""
        return self.feedback

    def getResult(self):
        """Return the :class:`TaskResult` of the last task."""
        if self.status == GoalStatus.STATUS_SUCCEEDED:
            return TaskResult.SUCCEEDED
        if self.status == GoalStatus.STATUS_ABORTED:
            return TaskResult.FAILED
        if self.status == GoalStatus.STATUS_CANCELED:
            return TaskResult.CANCELED
        return TaskResult.UNKNOWN

    def waitUntilNav2Active(self, navigator='bt_navigator', localizer='amcl'):
        """Wait for the localizer (and AMCL's pose) and the navigator to be active."""
        if localizer != 'robot_localization':
            self._waitForNodeToActivate(localizer)
        if localizer == 'amcl':
            self._waitForInitialPose()
        self._waitForNodeToActivate(navigator)
        self.info('Nav2 is ready for use!')

    def _getPathImpl(self, start, goal, planner_id='', use_start=False):
        goal_msg = ComputePathToPose.Goal()
        goal_msg.start, goal_msg.goal = start, goal
        goal_msg.planner_id, goal_msg.use_start = planner_id, use_start
        self.info('Getting path...')
        return self._blocking(self.compute_path_to_pose_client, goal_msg, 'ComputePathToPose')

    def getPath(self, start, goal, planner_id='', use_start=False):
        """Return a path (nav_msgs/Path) from ComputePathToPose, or None."""
        result = self._getPathImpl(start, goal, planner_id, use_start)
        return None if result is None else result.path

    def getPathThroughPoses(self, start, goals, planner_id='', use_start=False):
        """Return a path through ``goals`` from ComputePathThroughPoses, or None."""
        goal_msg = ComputePathThroughPoses.Goal()
        goal_msg.start, goal_msg.goals = start, list(goals)
        goal_msg.planner_id, goal_msg.use_start = planner_id, use_start
        self.info('Getting path...')
        result = self._blocking(self.compute_path_through_poses_client, goal_msg,
                                'ComputePathThroughPoses')
        return None if result is None else result.path

    def smoothPath(self, path, smoother_id='', max_duration=2.0, check_for_collision=False):
        """Return a smoothed path from SmoothPath, or None (no smoother server here)."""
        goal_msg = SmoothPath.Goal()
        goal_msg.path = path
        goal_msg.max_smoothing_duration = self._duration(max_duration)
        goal_msg.smoother_id = smoother_id
        goal_msg.check_for_collisions = check_for_collision
        self.info('Smoothing path...')
        result = self._blocking(self.smoother_client, goal_msg, 'SmoothPath')
        return None if result is None else result.path

    def changeMap(self, map_filepath):
        """Ask map_server to load ``map_filepath`` (LoadMap) and log the outcome."""
        while not self.change_maps_srv.wait_for_service(timeout_sec=1.0):
            self.info('change map service not available, waiting...')
        req = LoadMap.Request()
        req.map_url = map_filepath
        future = self.change_maps_srv.call_async(req)
        self._spin_until(future)
        status = future.result().result
        if status != LoadMap.Response().RESULT_SUCCESS:
            self.error('Change map request failed!')
        else:
            self.info('Change map request was successful!')

    def _call(self, client, request, label):
        while not client.wait_for_service(timeout_sec=1.0):
            self.info(f'{label} service not available, waiting...')
        future = client.call_async(request)
        self._spin_until(future)
        return future.result()

    def clearAllCostmaps(self):
        """Clear the local and the global costmaps."""
        self.clearLocalCostmap()
        self.clearGlobalCostmap()

    def clearLocalCostmap(self):
        """Clear the local costmap (ClearEntireCostmap)."""
        self._call(self.clear_costmap_local_srv, ClearEntireCostmap.Request(),
                   'Clear local costmaps')

    def clearGlobalCostmap(self):
        """Clear the global costmap (ClearEntireCostmap)."""
        self._call(self.clear_costmap_global_srv, ClearEntireCostmap.Request(),
                   'Clear global costmaps')

    def clearCostmapExceptRegion(self, reset_distance):
        """Clear the local costmap outside a square of ``reset_distance`` m on the robot."""
        request = ClearCostmapExceptRegion.Request(reset_distance=float(reset_distance))
        self._call(self.clear_costmap_except_region_srv, request,
                   'ClearCostmapExceptRegion')

    def clearCostmapAroundRobot(self, reset_distance):
        """Clear the local costmap inside a square of ``reset_distance`` m on the robot."""
        request = ClearCostmapAroundRobot.Request(reset_distance=float(reset_distance))
        self._call(self.clear_costmap_around_robot_srv, request, 'ClearCostmapAroundRobot')

    def clearCostmapAroundPose(self, pose, reset_distance):
        """Clear the local costmap inside a square of ``reset_distance`` m on ``pose``."""
        request = ClearCostmapAroundPose.Request(pose=pose, reset_distance=float(reset_distance))
        self._call(self.clear_costmap_around_pose_srv, request, 'ClearCostmapAroundPose')

    def getGlobalCostmap(self):
        """Return the global costmap (nav2_msgs/Costmap)."""
        return self._call(self.get_costmap_global_srv, GetCostmap.Request(),
                          'Get global costmaps').map

    def getLocalCostmap(self):
        """Return the local costmap (nav2_msgs/Costmap)."""
        return self._call(self.get_costmap_local_srv, GetCostmap.Request(),
                          'Get local costmaps').map

    def _manage_all(self, command, word):
        self.info(f'{word} up lifecycle nodes based on lifecycle_manager.')
        for srv_name, srv_type in self.get_service_names_and_types():
            if srv_type[0] != 'nav2_msgs/srv/ManageLifecycleNodes':
                continue
            self.info(f'{word} {srv_name}')
            client = self.create_client(ManageLifecycleNodes, srv_name)
            req = ManageLifecycleNodes.Request()
            req.command = command
            while True:
                future = client.call_async(req) if client.wait_for_service(1.0) else None
                if future is None:
                    self.info(f'{srv_name} service not available, waiting...')
                    continue
                self._spin_until(future)
                if future.result() is not None:
                    break
            self.destroy_client(client)

    def lifecycleStartup(self):
        """Send STARTUP to every lifecycle manager (ManageLifecycleNodes)."""
        self._manage_all(ManageLifecycleNodes.Request().STARTUP, 'Starting')
        self.info('Nav2 is ready for use!')

    def lifecycleShutdown(self):
        """Send SHUTDOWN to every lifecycle manager (ManageLifecycleNodes)."""
        self._manage_all(ManageLifecycleNodes.Request().SHUTDOWN, 'Shutting')

    def _waitForNodeToActivate(self, node_name):
        self.debug(f'Waiting for {node_name} to become active..')
        node_service = f'{node_name}/get_state'
        state_client = self.create_client(GetState, node_service)
        while not state_client.wait_for_service(timeout_sec=1.0):
            self.info(f'{node_service} service not available, waiting...')
        state = 'unknown'
        while state != 'active':
            self.debug(f'Getting {node_name} state...')
            future = state_client.call_async(GetState.Request())
            # a request sent as the server is discovered can lose its response (the server
            # has not matched our reply reader yet): ask again rather than wait forever
            self._spin_until(future, timeout_sec=5.0)
            if not future.done():
                state_client.remove_pending_request(future)
                continue
            if future.result() is not None:
                state = future.result().current_state.label
                self.debug(f'Result of get_state: {state}')
            if state != 'active':
                time.sleep(2)
        self.destroy_client(state_client)

    def _waitForInitialPose(self):
        while not self.initial_pose_received:
            self.info('Setting initial pose')
            self._setInitialPose()
            self.info('Waiting for amcl_pose to be received')
            rclpy.spin_once(self, timeout_sec=1.0)

    def _amclPoseCallback(self, msg):
        self.debug('Received amcl pose')
        self.initial_pose_received = True

    def _feedbackCallback(self, msg):
        self.debug('Received action feedback message')
        self.feedback = msg.feedback

    def _setInitialPose(self):
        msg = PoseWithCovarianceStamped()
        msg.pose.pose = self.initial_pose.pose
        msg.header.frame_id = self.initial_pose.header.frame_id
        msg.header.stamp = self.initial_pose.header.stamp
        self.info('Publishing Initial Pose')
        self.initial_pose_pub.publish(msg)

    def info(self, msg):
        """Log at INFO."""
        self.get_logger().info(msg)

    def warn(self, msg):
        """Log at WARN."""
        self.get_logger().warning(msg)

    def error(self, msg):
        """Log at ERROR."""
        self.get_logger().error(msg)

    def debug(self, msg):
        """Log at DEBUG."""
        self.get_logger().debug(msg)
