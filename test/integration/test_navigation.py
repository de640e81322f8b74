# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Navigation as nav2_bringup starts it, over real DDS, on the simulated robot in arena.sdf.

One stack: ``sim.launch.py world:=arena`` and ``bringup_launch.py map:=<arena map>`` (map_server,
amcl, controller_server, planner_server, behavior_server, velocity_smoother, bt_navigator,
waypoint_follower and both lifecycle managers, config/nav2_params.yaml), composed in one
``nav2_container`` process as nav2_bringup's default. The navigation servers' manager waits,
as upstream's, on the global costmap's activation ("Timed out waiting for transform from
base_footprint to map") until AMCL is given the initial pose. Then:
goals outside the map and with NaN end at once with GOAL_OUTSIDE_MAP (204) and the stack keeps
running; a NavigateToPose goal past the centre pillar succeeds with the robot's ground truth within
Nav2's goal tolerances (plus AMCL's error) and feedback filled (distance remaining falling,
navigation time rising, an estimated time); a goal on ``/goal_pose`` starts a navigation; a cancel
stops the robot with status CANCELED. ``ros2 action info`` names bt_navigator as the server and
``ros2 action send_goal`` prints ros2action's lines and the navigator's error code; a
nav2_simple_commander script in upstream's example pattern drives the robot to a goal;
waypoint_follower goes through two waypoints, the one outside the map listed as missed.
"""

import math
import subprocess
import sys
import time

import pytest
from test_sim import Peer  # noqa: I100 - the simulator tests' DDS peer

pytest.importorskip('nav2_msgs.action')


class NavPeer(Peer):
    """Peer plus /initialpose, /amcl_pose, /goal_pose and the navigate_to_pose action."""

    def __init__(self, domain_id):
        from geometry_msgs.msg import PolygonStamped
        from geometry_msgs.msg import PoseStamped
        from geometry_msgs.msg import PoseWithCovarianceStamped
        from nav2_msgs.action import NavigateToPose
        from rclpy.action import ActionClient
        from rclpy.qos import DurabilityPolicy
        from rclpy.qos import QoSProfile
        super().__init__(domain_id)
        self.PoseStamped, self.PoseCov, self.Action = (PoseStamped, PoseWithCovarianceStamped,
                                                       NavigateToPose)
        self.amcl = []
        self.node.create_subscription(PoseWithCovarianceStamped, '/amcl_pose', self.amcl.append,
                                      QoSProfile(depth=1,
                                                 durability=DurabilityPolicy.TRANSIENT_LOCAL))
        self.initial = self.node.create_publisher(PoseWithCovarianceStamped, '/initialpose', 10)
        self.goal_pose = self.node.create_publisher(PoseStamped, '/goal_pose', 10)
        self.action = ActionClient(self.node, NavigateToPose, '/navigate_to_pose')
        self.feedback = []
        self.footprints = []
        self.node.create_subscription(PolygonStamped, '/global_costmap/published_footprint',
                                      self.footprints.append, 10)

    def truth(self):
        p = self.odom[-1].pose.pose
        return (p.position.x, p.position.y,
                2.0 * math.atan2(p.orientation.z, p.orientation.w))

    def set_initial_pose(self):
        msg = self.PoseCov()
        msg.header.frame_id = 'map'
        msg.pose.pose = self.odom[-1].pose.pose
        msg.pose.covariance[0] = msg.pose.covariance[7] = msg.pose.covariance[35] = 0.01
        self.initial.publish(msg)

    def pose(self, x, y, yaw=0.0, cls=None):
        msg = (cls or self.PoseStamped)()
        msg.header.frame_id = 'map'
        msg.pose.position.x, msg.pose.position.y = float(x), float(y)
        msg.pose.orientation.z = math.sin(yaw / 2.0) if math.isfinite(yaw) else yaw
        msg.pose.orientation.w = math.cos(yaw / 2.0) if math.isfinite(yaw) else 1.0
        return msg

    def send(self, x, y, yaw=0.0):
        """Send a NavigateToPose goal; return its goal handle."""
        goal = self.Action.Goal()
        goal.pose = self.pose(x, y, yaw)
        self.feedback = []
        assert self.action.wait_for_server(timeout_sec=60.0)
        sent = self.action.send_goal_async(goal, feedback_callback=lambda m: self.feedback
                                           .append(m.feedback))
        assert self.spin_until(sent.done, 60.0)
        assert sent.result().accepted
        return sent.result()

    def follow_waypoints(self, points):
        """Send a FollowWaypoints goal through ``points`` [(x, y), ...]; return its handle."""
        from nav2_msgs.action import FollowWaypoints
        from rclpy.action import ActionClient
        client = ActionClient(self.node, FollowWaypoints, '/follow_waypoints')
        assert client.wait_for_server(timeout_sec=60.0)
        self.waypoint_feedback = []
        sent = client.send_goal_async(
            FollowWaypoints.Goal(poses=[self.pose(x, y) for x, y in points]),
            feedback_callback=lambda m: self.waypoint_feedback.append(
                m.feedback.current_waypoint))
        assert self.spin_until(sent.done, 60.0) and sent.result().accepted
        return sent.result()

    def result(self, handle, timeout):
        future = handle.get_result_async()
        assert self.spin_until(future.done, timeout), 'no result in time'
        return future.result().status, future.result().result


COMMANDER_SCRIPT = """
import math
import sys

from geometry_msgs.msg import PoseStamped
from nav2_simple_commander.robot_navigator import BasicNavigator, TaskResult
import rclpy

rclpy.init()
navigator = BasicNavigator()
x, y, yaw = map(float, sys.argv[1:4])
initial_pose = PoseStamped()
initial_pose.header.frame_id = 'map'
initial_pose.header.stamp = navigator.get_clock().now().to_msg()
initial_pose.pose.position.x, initial_pose.pose.position.y = x, y
initial_pose.pose.orientation.z, initial_pose.pose.orientation.w = (math.sin(yaw / 2),
                                                                    math.cos(yaw / 2))
navigator.setInitialPose(initial_pose)
navigator.waitUntilNav2Active()
# You may use the navigator to clear or obtain costmaps
navigator.clearAllCostmaps()  # also have clearLocalCostmap() and clearGlobalCostmap()
navigator.clearCostmapAroundRobot(1.0)
navigator.clearCostmapExceptRegion(2.0)
global_costmap = navigator.getGlobalCostmap()
local_costmap = navigator.getLocalCostmap()
print('costmaps: {} x {}, {} x {}'.format(
    global_costmap.metadata.size_x, global_costmap.metadata.size_y,
    local_costmap.metadata.size_x, local_costmap.metadata.size_y), flush=True)
goal_pose = PoseStamped()
goal_pose.header.frame_id = 'map'
goal_pose.header.stamp = navigator.get_clock().now().to_msg()
goal_pose.pose.position.x, goal_pose.pose.position.y = 1.5, -0.5
goal_pose.pose.orientation.w = 1.0
navigator.goToPose(goal_pose)
i = 0
while not navigator.isTaskComplete():
    i += 1
    feedback = navigator.getFeedback()
    if feedback and i % 5 == 0:
        print('distance remaining: ' + '{:.2f}'.format(feedback.distance_remaining), flush=True)
result = navigator.getResult()
if result == TaskResult.SUCCEEDED:
    print('Goal succeeded!')
elif result == TaskResult.CANCELED:
    print('Goal was canceled!')
elif result == TaskResult.FAILED:
    print('Goal failed!')
navigator.destroy_node()
rclpy.shutdown()
sys.exit(0 if result == TaskResult.SUCCEEDED else 1)
"""
"""A script as nav2_simple_commander's examples write them (example_nav_to_pose.py, its
costmap lines uncommented and the local costmap's clear-region calls added)."""


GOAL_YAW = 0.5
"""The first goal's heading (rad)."""


def _seconds(duration):
    return duration.sec + duration.nanosec * 1e-9


def test_navigate_to_pose_on_the_simulated_robot(procs, exe, ros_env, tmp_path):
    from action_msgs.msg import GoalStatus
    from amr_description.nav import map_io
    from amr_description.tools.benchmark.amcl_accuracy import arena_map
    from nav2_msgs.action import ComputePathToPose
    map_io.save_map(str(tmp_path / 'arena'), arena_map())
    sim = procs.start([exe('ros2'), 'launch', 'amr_description', 'sim.launch.py',
                       'world:=arena', 'viewer:=false'], ros_env)
    nav = procs.start([exe('ros2'), 'launch', 'amr_description', 'bringup_launch.py',
                       f'map:={tmp_path}/arena.yaml', 'use_sim_time:=true'], ros_env)
    peer = NavPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert nav.wait_for_output('[lifecycle_manager_localization]: Managed nodes are '
                                   'active', 240.0), nav.output[-3000:]
        # as upstream's: the global costmap's activation waits for map -> base_footprint,
        # which AMCL publishes once given a pose (RViz's "2D Pose Estimate")
        assert nav.wait_for_output('[global_costmap.global_costmap]: Timed out waiting for '
                                   'transform from base_footprint to map to become available',
                                   120.0), nav.output[-3000:]
        assert '[lifecycle_manager_navigation]: Managed nodes are active' not in nav.output
        assert peer.spin_until(lambda: peer.odom, 120.0), sim.output[-2000:]
        assert peer.spin_until(lambda: peer.set_initial_pose() or peer.amcl, 120.0)
        assert nav.wait_for_output('[lifecycle_manager_navigation]: Managed nodes are active',
                                   120.0), nav.output[-3000:]
        # composed, as nav2_bringup's default: every node loaded into one container process
        for plugin, name in (('nav2_amcl::AmclNode', 'amcl'),
                             ('nav2_controller::ControllerServer', 'controller_server'),
                             ('nav2_lifecycle_manager::LifecycleManager',
                              'lifecycle_manager_navigation')):
            assert f"[nav2_container]: Loaded component '{plugin}' as '/{name}'" in nav.output
        assert nav.output.count('[component_container_isolated-1]') > 10, nav.output[-3000:]
        # the planner knows the robot's pose in map once the global costmap shows its footprint
        assert peer.spin_until(lambda: peer.footprints, 120.0), nav.output[-3000:]

        # bad goals end at once with the planner's code; nothing stops
        codes = ComputePathToPose.Result
        for x, y in ((50.0, 0.0), (float('nan'), 0.0)):
            handle = peer.send(x, y)
            status, result = peer.result(handle, 60.0)
            assert status == GoalStatus.STATUS_ABORTED, (x, y, status)
            assert result.error_code == codes.GOAL_OUTSIDE_MAP, (x, y, result.error_code)
        # a goal on the centre pillar (a lethal cell: the test's map draws the surfaces):
        # GOAL_OCCUPIED at once with this robot's NavFn tolerance 0, no recovery runs
        sent = time.monotonic()
        handle = peer.send(1.12, 0.0)
        status, result = peer.result(handle, 60.0)
        print(f'goal in the pillar: {result.error_code} after {time.monotonic() - sent:.2f} s')
        assert status == GoalStatus.STATUS_ABORTED, status
        assert result.error_code == codes.GOAL_OCCUPIED, result.error_code
        assert 'Running recovery' not in nav.output, nav.output[-3000:]

        # the CLI: ros2 action info and send_goal with ros2action's output
        server = 'Action servers: 1\n    /bt_navigator [nav2_msgs/action/NavigateToPose]'
        deadline = time.monotonic() + 120.0
        while True:  # a new CLI process discovers the graph's endpoints over some seconds
            out = subprocess.run([exe('ros2'), 'action', 'info', '/navigate_to_pose', '-t'],
                                 env=ros_env, capture_output=True, text=True, timeout=120)
            assert out.returncode == 0 and 'Action: /navigate_to_pose' in out.stdout, out
            if server in out.stdout or time.monotonic() > deadline:
                break
        assert server in out.stdout, out.stdout
        out = subprocess.run([exe('ros2'), 'action', 'send_goal', '-f', '/navigate_to_pose',
                              'nav2_msgs/action/NavigateToPose',
                              '{pose: {header: {frame_id: map}, pose: {position: {x: 50.0}}}}'],
                             env=ros_env, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out
        assert 'Sending goal:\n     pose:' in out.stdout and 'Goal accepted with ID: ' in \
            out.stdout, out.stdout
        assert 'error_code: 204' in out.stdout, out.stdout
        assert out.stdout.rstrip().endswith('Goal finished with status: ABORTED'), out.stdout
        out = subprocess.run([exe('ros2'), 'action', 'send_goal', '/navigate_to_pose',
                              'nav2_msgs/action/Nope', '{}'],
                             env=ros_env, capture_output=True, text=True, timeout=120)
        assert out.returncode == 1 and out.stderr.strip() == 'The passed action type is invalid'

        # past the centre pillar at (1, 0) to (2.5, 0.5), facing 30 deg left of the approach:
        # a long in-place turn is where the skid-steer odometry slips most and AMCL lags
        start = peer.now
        handle = peer.send(2.5, 0.5, GOAL_YAW)
        status, result = peer.result(handle, 300.0)
        x, y, yaw = peer.truth()
        print(f'reached ({x:.3f}, {y:.3f}, {yaw:.3f}) in {peer.now - start:.1f} s of sim time')
        assert status == GoalStatus.STATUS_SUCCEEDED, (result.error_code, nav.output[-3000:])
        # Nav2's default tolerances, 0.25 m and 0.25 rad, plus AMCL's error (under 0.1 m)
        assert math.hypot(x - 2.5, y - 0.5) < 0.35
        assert abs(math.remainder(yaw - GOAL_YAW, math.tau)) < 0.45  # AMCL: up to 0.2 rad
        remaining = [f.distance_remaining for f in peer.feedback if f.distance_remaining > 0]
        assert len(remaining) > 5 and remaining[0] > 2.0 and remaining[-1] < 1.0
        times = [_seconds(f.navigation_time) for f in peer.feedback]
        assert times == sorted(times) and times[-1] > 3.0
        assert any(_seconds(f.estimated_time_remaining) > 0.0 for f in peer.feedback)
        assert peer.feedback[-1].current_pose.header.frame_id == 'map'

        # RViz's 2D Goal Pose: a PoseStamped on /goal_pose starts a navigation
        peer.goal_pose.publish(peer.pose(1.5, 0.6, math.pi))
        assert nav.wait_for_output('Received goal pose on goal_pose', 60.0)
        assert peer.spin_until(lambda: math.hypot(peer.truth()[0] - 2.5,
                                                  peer.truth()[1] - 0.5) > 0.3, 120.0)

        # a new goal pre-empts it; a cancel stops the robot
        handle = peer.send(-0.5, -0.5)
        assert peer.spin_until(lambda: len(peer.feedback) > 20 and
                               peer.feedback[-1].distance_remaining > 0.5, 120.0)
        cancel = handle.cancel_goal_async()
        assert peer.spin_until(cancel.done, 60.0)
        status, _ = peer.result(handle, 60.0)
        assert status == GoalStatus.STATUS_CANCELED
        settled = peer.now
        assert peer.spin_until(lambda: peer.now > settled + 2.0, 60.0)
        twist = peer.odom[-1].twist.twist
        assert math.hypot(twist.linear.x, twist.linear.y) < 0.02 and abs(twist.angular.z) < 0.05

        # upstream's nav2_simple_commander example pattern, unchanged, as a user's script
        x, y, yaw = peer.truth()
        before = peer.now
        script = tmp_path / 'go.py'
        script.write_text(COMMANDER_SCRIPT)
        out = subprocess.run([sys.executable, str(script), str(x), str(y), str(yaw)],
                             env=ros_env, capture_output=True, text=True, timeout=400)
        assert out.returncode == 0, out.stdout + out.stderr + nav.output[-3000:]
        assert 'Nav2 is ready for use!' in out.stderr and 'Goal succeeded!' in out.stdout
        assert 'distance remaining:' in out.stdout
        # the arena's map (100 x 110 cells at 5 cm) and the 3 m local window at 5 cm
        assert 'costmaps: 100 x 110, 60 x 60' in out.stdout, out.stdout

        def fresh():  # the peer did not spin while the script ran: read up to now
            last = peer.odom[-1].header.stamp
            return peer.now > before + 1.0 and last.sec + last.nanosec * 1e-9 > peer.now - 0.2

        assert peer.spin_until(fresh, 60.0)
        assert math.hypot(peer.truth()[0] - 1.5, peer.truth()[1] + 0.5) < 0.35

        # follow_waypoints (stop_on_failure false in config/nav2_params.yaml): the second
        # waypoint is outside the map, missed with the navigator's code, and the goal succeeds
        waypoints = peer.follow_waypoints([(2.0, -0.5), (50.0, 0.0)])
        status, result = peer.result(waypoints, 300.0)
        assert status == GoalStatus.STATUS_SUCCEEDED, nav.output[-3000:]
        assert [(m.index, m.error_code, m.goal.pose.position.x)
                for m in result.missed_waypoints] == [(1, codes.GOAL_OUTSIDE_MAP, 50.0)]
        # the feedback topic and the result's service answer are separate DDS writers: the
        # second waypoint's one feedback message may arrive after the result
        assert peer.spin_until(lambda: sorted(set(peer.waypoint_feedback)) == [0, 1], 30.0), \
            peer.waypoint_feedback
        assert math.hypot(peer.truth()[0] - 2.0, peer.truth()[1] + 0.5) < 0.35
        assert sim.popen.poll() is None and nav.popen.poll() is None
    finally:
        peer.close()
