# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
controller_server alone over real DDS: FollowPath's commands and ``ros2 param set`` on them.

One stack (controller_server with config/nav2_params.yaml, a static ``odom -> base_footprint``,
lifecycle_manager): a straight path ahead is followed at RPP's ``desired_linear_vel``; the
test's peer plays the base, its ``/odom`` twist the last command. ``ros2 param set`` changes the
speed of the goal being followed, refuses ``allow_reversing`` beside ``use_rotate_to_heading``
with upstream's line, and turns ``use_cancel_deceleration`` on: a cancel then slows the commands
by ``cancel_deceleration`` to 0 before the goal ends CANCELED.
"""

import pytest
from test_sim import Peer  # noqa: I100 - the simulator tests' DDS peer

pytest.importorskip('nav2_msgs.action')


class ControllerPeer(Peer):
    """Peer plus /cmd_vel (answered on /odom, as a base would) and the follow_path action."""

    def __init__(self, domain_id):
        from geometry_msgs.msg import TwistStamped
        from nav2_msgs.action import FollowPath
        from nav_msgs.msg import Odometry
        from rclpy.action import ActionClient
        super().__init__(domain_id)
        self.commands = []
        self.odom_pub = self.node.create_publisher(Odometry, '/odom', 10)
        self.node.create_subscription(TwistStamped, '/cmd_vel', self._on_command, 10)
        self.Action = FollowPath
        self.action = ActionClient(self.node, FollowPath, '/follow_path')

    def _on_command(self, msg):
        from nav_msgs.msg import Odometry
        self.commands.append((msg.twist.linear.x, msg.twist.angular.z))
        odom = Odometry()
        odom.header.frame_id, odom.child_frame_id = 'odom', 'base_footprint'
        odom.twist.twist = msg.twist
        self.odom_pub.publish(odom)

    def follow(self, length):
        """Send a straight path ``length`` m ahead in ``odom``; return the goal's handle."""
        from geometry_msgs.msg import PoseStamped
        goal = self.Action.Goal()
        goal.path.header.frame_id = 'odom'
        for i in range(int(length / 0.05) + 1):
            pose = PoseStamped()
            pose.header.frame_id = 'odom'
            pose.pose.position.x = i * 0.05
            pose.pose.orientation.w = 1.0
            goal.path.poses.append(pose)
        assert self.action.wait_for_server(timeout_sec=120.0)
        sent = self.action.send_goal_async(goal)
        assert self.spin_until(sent.done, 60.0) and sent.result().accepted
        return sent.result()

    def speeds_settle_at(self, v, timeout=60.0):
        """Spin until five new commands in a row are ``v`` m/s ahead, not turning."""
        start = len(self.commands)

        def settled():
            last = self.commands[start:][-5:]
            return len(last) == 5 and all(abs(c[0] - v) < 1e-6 and c[1] == 0.0 for c in last)

        return self.spin_until(settled, timeout)


def ros2_param(exe, ros_env, *args):
    """Run ``ros2 param ARGS``; return the CompletedProcess (text output)."""
    import subprocess
    return subprocess.run([exe('ros2'), 'param', *args], env=ros_env, capture_output=True,
                          text=True, timeout=120)


def test_follow_path_speed_parameters_and_cancel_deceleration(procs, exe, ros_env):
    from action_msgs.msg import GoalStatus
    from amr_description.launch.nav_stacks import share_file
    params = share_file('config', 'nav2_params.yaml')
    # the peer's base never moves in TF: no progress check within the test
    server = procs.start([exe('controller_server'), '--ros-args', '--params-file', params, '-p',
                          'progress_checker.movement_time_allowance:=3600.0'], ros_env)
    procs.start([exe('static_transform_publisher'), '--frame-id', 'odom', '--child-frame-id',
                 'base_footprint'], ros_env)
    manager = procs.start([exe('lifecycle_manager'), '--ros-args', '-p',
                           'node_names:=[controller_server]', '-p', 'autostart:=true'],
                          ros_env)
    peer = ControllerPeer(int(ros_env['ROS_DOMAIN_ID']))
    try:
        assert manager.wait_for_output('Managed nodes are active', 180.0), server.output
        handle = peer.follow(20.0)
        assert peer.speeds_settle_at(0.5), (peer.commands[-10:], server.output[-2000:])

        # the goal being followed takes the new speed
        out = ros2_param(exe, ros_env, 'set', '/controller_server',
                         'FollowPath.desired_linear_vel', '0.25')
        assert out.stdout.strip() == 'Set parameter successful', out
        assert peer.speeds_settle_at(0.25), (peer.commands[-10:], server.output[-2000:])

        # refused with upstream's line, nothing changes
        refusal = ('Both use_rotate_to_heading and allow_reversing parameter cannot be set to '
                   'true. Rejecting parameter update.')
        out = ros2_param(exe, ros_env, 'set', '/controller_server',
                         'FollowPath.allow_reversing', 'true')
        assert out.stderr.strip() == f'Setting parameter failed: {refusal}', out
        assert server.wait_for_output(refusal, 30.0)
        out = ros2_param(exe, ros_env, 'get', '/controller_server',
                         'FollowPath.allow_reversing')
        assert out.stdout.strip() == 'Boolean value is: False', out

        # a cancel with use_cancel_deceleration: the commands fall by 1.0 m/s^2 to 0 first
        for name, value in (('use_cancel_deceleration', 'true'),
                            ('cancel_deceleration', '1.0')):
            out = ros2_param(exe, ros_env, 'set', '/controller_server', f'FollowPath.{name}',
                             value)
            assert out.stdout.strip() == 'Set parameter successful', out
        assert peer.speeds_settle_at(0.25)
        before = len(peer.commands)
        cancel = handle.cancel_goal_async()
        result = handle.get_result_async()
        assert peer.spin_until(lambda: cancel.done() and result.done(), 60.0), server.output
        assert result.result().status == GoalStatus.STATUS_CANCELED
        assert peer.spin_until(lambda: 'Cancellation was successful. Stopping the robot.' in
                               server.output, 30.0), server.output[-2000:]
        assert 'Waiting for the controller to finish cancellation' in server.output
        slowing = [v for v, _ in peer.commands[before:] if 0.0 < v < 0.25 - 1e-6]
        print(f'commands after the cancel: {[round(v, 3) for v, _ in peer.commands[before:]]}')
        # about 0.05 m/s less each 0.05 s cycle: 0.20, 0.15, 0.10, 0.05 (a cycle may repeat
        # one when the answering odometry is late)
        assert len(slowing) >= 3 and slowing == sorted(slowing, reverse=True), peer.commands
        assert peer.commands[-1] == (0.0, 0.0)
        assert server.popen.poll() is None
    finally:
        peer.close()
