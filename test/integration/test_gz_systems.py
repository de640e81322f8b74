# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
gz-sim systems in a robot description run here: DiffDrive, JointStatePublisher, OdometryPublisher.

test/data/gz_diff_drive/robot.urdf.xacro is a two-wheeled robot with two casters as a Jazzy +
Harmonic course writes it (xacro including ``$(find amr_description)/urdf/...``, arguments,
``<gazebo reference>`` friction tags, gz-sim system plugins, one of them under its old
``ignition::gazebo`` name). Spawned with ``create -file``, it answers ``Twist`` on
``/cmd_vel`` with wheel odometry on ``/odom`` and TF on ``/tf``, as the user's
ros_gz_bridge would deliver them.
"""

import math
import os

import pytest
from test_sim import Peer  # noqa: I100 - the simulator tests' DDS peer

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
XACRO = os.path.join(ROOT, 'test', 'data', 'gz_diff_drive', 'robot.urdf.xacro')
CHUNK = 20  # physics steps (ms) between two looks at the robot


def _yaw(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class GzPeer(Peer):
    """Peer plus /cmd_vel (Twist) and the DiffDrive and JointStatePublisher topics."""

    def __init__(self, domain_id, cmd_topic='/cmd_vel', odom_topic='/odom', stamped=False):
        from geometry_msgs.msg import Twist
        from geometry_msgs.msg import TwistStamped
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState
        from tf2_msgs.msg import TFMessage
        super().__init__(domain_id)
        self.Twist = TwistStamped if stamped else Twist
        self.cmd = self.node.create_publisher(self.Twist, cmd_topic, 10)
        self.wheel_odom = []
        self.joint_states = []
        self.tf = []
        self.node.create_subscription(Odometry, odom_topic, self.wheel_odom.append, 100)
        self.node.create_subscription(JointState, '/joint_states', self.joint_states.append,
                                      100)
        self.node.create_subscription(TFMessage, '/tf', self.tf.append, 100)

    def step(self, steps):
        start = self.now
        request = self.srv.StepSimulation.Request()
        request.steps = steps
        assert self.call('step', request).result.result == self.msg.Result.RESULT_OK
        assert self.spin_until(lambda: self.now >= start + steps * 1e-3 - 1e-9, 30)

    def command_until(self, linear, angular, done, limit_steps=20000):
        """Publish a Twist, then step until ``done(wheel odometry twist)`` (paused sim)."""
        assert self.spin_until(lambda: self.cmd.get_subscription_count() > 0, 30)
        msg = self.Twist()
        twist = msg.twist if hasattr(msg, 'twist') else msg
        twist.linear.x, twist.angular.z = float(linear), float(angular)
        self.cmd.publish(msg)
        for _ in range(limit_steps // CHUNK):
            self.step(CHUNK)
            if self.spin_until(lambda: bool(self.wheel_odom), 1.0) and \
                    done(self.wheel_odom[-1].twist.twist):
                return
        raise AssertionError(f'the robot did not follow Twist({linear}, {angular})')

    def poses(self):
        """Return (ground truth x, y, yaw, wheel odometry x, y, yaw) of the latest messages."""
        count = len(self.odom), len(self.wheel_odom)
        self.spin_until(lambda: len(self.odom) > count[0] and len(self.wheel_odom) > count[1],
                        5)
        gt, od = self.odom[-1].pose.pose, self.wheel_odom[-1].pose.pose
        return (gt.position.x, gt.position.y, _yaw(gt.orientation),
                od.position.x, od.position.y, _yaw(od.orientation))


@pytest.fixture
def gz_peer(ros_env):
    pytest.importorskip('simulation_interfaces.srv')
    p = GzPeer(int(ros_env['ROS_DOMAIN_ID']))
    yield p
    p.close()


def _spawn(procs, exe, ros_env, peer, *parameters):
    sim = procs.start([exe('mujoco_sim'), '--ros-args', '-p', 'real_time_factor:=0.0',
                       *parameters], ros_env)
    assert peer.spin_until(lambda: peer.now is not None, 30), sim.output
    create = procs.start([exe('create'), '-file', XACRO], ros_env)
    assert create.wait(60) == 0, create.output + sim.output
    assert peer.set_state(peer.msg.SimulationState.STATE_PAUSED).result == \
        peer.msg.Result.RESULT_OK
    return sim


def test_diff_drive_robot_with_casters_drives_on_cmd_vel(procs, exe, ros_env, gz_peer):
    peer = gz_peer
    sim = _spawn(procs, exe, ros_env, peer)
    assert "gz-sim system plugin 'gz::sim::systems::PosePublisher' is not simulated" in \
        sim.output
    peer.step(500)  # rest on the casters
    assert peer.wheel_odom and peer.joint_states and peer.tf, sim.output
    odom = peer.wheel_odom[-1]
    assert (odom.header.frame_id, odom.child_frame_id) == ('odom', 'base_footprint')
    transform = peer.tf[-1].transforms[0]
    assert (transform.header.frame_id, transform.child_frame_id) == ('odom', 'base_footprint')
    assert peer.joint_states[-1].name == ['left_wheel_joint', 'right_wheel_joint']
    gx0, gy0, gyaw0, ox0, oy0, oyaw0 = peer.poses()
    assert abs(ox0) < 1e-6 and abs(oy0) < 1e-6

    peer.command_until(0.5, 0.0, lambda twist: twist.linear.x > 0.45)
    peer.step(1500)
    assert peer.joint_states[-1].velocity[0] == pytest.approx(5.0, rel=0.05)  # 0.5 / 0.1
    peer.command_until(0.0, 0.0, lambda twist: abs(twist.linear.x) < 1e-3)
    peer.step(500)
    gx, gy, gyaw, ox, oy, oyaw = peer.poses()
    ground, odometry = math.hypot(gx - gx0, gy - gy0), math.hypot(ox - ox0, oy - oy0)
    print(f'gz DiffDrive straight: ground truth {ground:.4f} m, odometry {odometry:.4f} m')
    assert ground > 0.8, sim.output[-2000:]
    assert odometry == pytest.approx(ground, rel=0.01)

    peer.command_until(0.0, 1.0, lambda twist: twist.angular.z > 0.9)
    peer.step(1000)
    peer.command_until(0.0, 0.0, lambda twist: abs(twist.angular.z) < 1e-3)
    peer.step(500)
    gx1, gy1, gyaw1, ox1, oy1, oyaw1 = peer.poses()
    turned = math.atan2(math.sin(gyaw1 - gyaw), math.cos(gyaw1 - gyaw))
    odometry_turn = math.atan2(math.sin(oyaw1 - oyaw), math.cos(oyaw1 - oyaw))
    print(f'gz DiffDrive turn: ground truth {math.degrees(turned):.1f} deg, odometry '
          f'{math.degrees(odometry_turn):.1f} deg')
    assert turned > 1.0
    assert odometry_turn == pytest.approx(turned, rel=0.02)
    assert sim.popen.poll() is None


BRIDGE = """
- ros_topic_name: /robot/cmd_vel
  gz_topic_name: /cmd_vel
  ros_type_name: geometry_msgs/msg/TwistStamped
  gz_type_name: gz.msgs.Twist
  direction: ROS_TO_GZ
- ros_topic_name: wheel_odom
  gz_topic_name: odom
  ros_type_name: nav_msgs/msg/Odometry
  gz_type_name: gz.msgs.Odometry
  direction: GZ_TO_ROS
- topic_name: /tf
  ros_type_name: tf2_msgs/msg/TFMessage
  gz_type_name: gz.msgs.Pose_V
  direction: GZ_TO_ROS
"""


def test_bridge_config_renames_the_topics_as_the_users_bridge(procs, exe, ros_env, tmp_path):
    pytest.importorskip('simulation_interfaces.srv')
    config = tmp_path / 'bridge.yaml'
    config.write_text(BRIDGE)
    peer = GzPeer(int(ros_env['ROS_DOMAIN_ID']), cmd_topic='/robot/cmd_vel',
                  odom_topic='/wheel_odom', stamped=True)
    try:
        sim = _spawn(procs, exe, ros_env, peer, '-p', f'bridge_config:={config}')
        peer.command_until(0.3, 0.0, lambda twist: twist.linear.x > 0.25)
        assert peer.wheel_odom[-1].child_frame_id == 'base_footprint'
        assert peer.tf, sim.output
        node = peer.node
        assert node.count_publishers('/wheel_odom') == 1
        # not in the bridge configuration: they do not reach ROS, as with ros_gz_bridge
        assert node.count_publishers('/odom') == 0
        assert node.count_publishers('/joint_states') == 0  # the peer only subscribes it
        assert node.count_subscribers('/cmd_vel') == 0
    finally:
        peer.close()
