# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The keyboard teleop driven through a pseudo-terminal, received over real DDS."""

import os
import subprocess
import threading
import time

import pytest

TOPIC = '/diff_drive_controller/cmd_vel'


class _Receiver:
    """A TwistStamped subscriber in this test process, on the test's ROS domain."""

    def __init__(self, domain_id, topic=TOPIC):
        import rclpy
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from geometry_msgs.msg import TwistStamped
        os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
        self.rclpy = rclpy
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = rclpy.create_node('teleop_test_receiver', context=self.context)
        self.messages = []
        self._lock = threading.Lock()
        self.node.create_subscription(TwistStamped, topic, self._on_msg, 10)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._thread = threading.Thread(target=self.executor.spin, daemon=True)
        self._thread.start()

    def _on_msg(self, msg):
        with self._lock:
            self.messages.append(msg)

    def wait_count(self, count, timeout=60.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                if len(self.messages) >= count:
                    return list(self.messages)
            time.sleep(0.02)
        with self._lock:
            return list(self.messages)

    def matched(self):
        return self.node.count_publishers(TOPIC) > 0

    def close(self):
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self.rclpy.try_shutdown(context=self.context)


def _values(msg):
    t = msg.twist
    return (t.linear.x, t.linear.y, t.linear.z, t.angular.z)


@pytest.fixture
def receiver(ros_env):
    rx = _Receiver(int(ros_env['ROS_DOMAIN_ID']))
    yield rx
    rx.close()


def _start_teleop(procs, exe, ros_env, extra=()):
    master, slave = os.openpty()
    argv = [exe('teleop_twist_keyboard'), '--ros-args', '-p', 'stamped:=true',
            '-p', 'frame_id:=base_link', '-r', f'/cmd_vel:={TOPIC}', *extra]
    proc = procs.start(argv, ros_env, stdin=slave)
    os.close(slave)
    return proc, master


def _wait_matched(receiver, proc, master, timeout=60.0):
    """
    Wait until the teleop's messages reach ``receiver``, then forget what was received.

    Discovery is not symmetric in time: the receiver may see the publisher before the
    publisher sees the receiver, and a message sent then is lost (volatile QoS). So type
    ``k`` (a zero twist, the teleop's initial state) until one arrives, wait out any
    ``key_timeout`` zero it triggers, and clear the received list.
    """
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not receiver.messages:
        assert proc.popen.poll() is None, proc.output
        if receiver.matched():
            os.write(master, b'k')
        time.sleep(0.2)
    assert receiver.messages, proc.output
    time.sleep(0.8)
    with receiver._lock:
        receiver.messages.clear()


def test_keys_to_twist_stamped_and_zero_on_exit(procs, exe, ros_env, receiver):
    proc, master = _start_teleop(procs, exe, ros_env)
    try:
        assert proc.wait_for_output('currently:\tspeed 0.5\tturn 1.0', timeout=60), proc.output
        _wait_matched(receiver, proc, master)
        os.write(master, b'i')
        msgs = receiver.wait_count(1)
        assert [_values(m) for m in msgs] == [(0.5, 0.0, 0.0, 0.0)]
        assert msgs[0].header.frame_id == 'base_link'
        os.write(master, b'q')   # speeds x1.1, direction kept
        os.write(master, b'J')   # holonomic left
        os.write(master, b'u')
        msgs = receiver.wait_count(4)
        got = [v for m in msgs[1:] for v in _values(m)]
        assert got == pytest.approx([0.55, 0.0, 0.0, 0.0, 0.0, 0.55, 0.0, 0.0,
                                     0.55, 0.0, 0.0, 1.1])
        assert proc.wait_for_output('currently:\tspeed 0.55', timeout=60), proc.output
        os.write(master, b'\x03')  # Ctrl-C in raw mode
        assert proc.wait(60) == 0, proc.output
        msgs = receiver.wait_count(5)
        assert len(msgs) == 5
        assert _values(msgs[-1]) == (0.0, 0.0, 0.0, 0.0)
        assert 'Traceback' not in proc.output
    finally:
        os.close(master)


def test_key_timeout_publishes_zero(procs, exe, ros_env, receiver):
    proc, master = _start_teleop(procs, exe, ros_env, ('-p', 'key_timeout:=0.3'))
    try:
        assert proc.wait_for_output('currently:', timeout=60), proc.output
        _wait_matched(receiver, proc, master)
        os.write(master, b'l')
        msgs = receiver.wait_count(2, timeout=60)
        assert [_values(m) for m in msgs] == [(0.0, 0.0, 0.0, -1.0), (0.0, 0.0, 0.0, 0.0)]
        stamps = [m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in msgs]
        assert 0.25 <= stamps[1] - stamps[0] < 1.5
        time.sleep(0.8)  # only one zero per idle period
        assert len(receiver.wait_count(3, timeout=0.1)) == 2
        proc.interrupt()   # SIGINT also ends it cleanly
        assert proc.wait(60) == 0, proc.output
        assert 'Traceback' not in proc.output
    finally:
        os.close(master)


def test_stdin_not_a_terminal(exe, ros_env):
    result = subprocess.run([exe('teleop_twist_keyboard')], env=ros_env, stdin=subprocess.PIPE,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and 'stdin is not a terminal' in lines[0]
    assert 'Traceback' not in result.stderr + result.stdout


def test_frame_id_needs_stamped(procs, exe, ros_env):
    master, slave = os.openpty()
    try:
        proc = procs.start([exe('teleop_twist_keyboard'), '--ros-args', '-p',
                            'frame_id:=base_link'], ros_env, stdin=slave)
        assert proc.wait(60) == 1
        assert "'frame_id' can only be set when 'stamped' is true" in proc.output
        assert 'Traceback' not in proc.output
    finally:
        os.close(slave)
        os.close(master)
