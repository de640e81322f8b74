# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
Graph and tool verbs against live nodes, in the formats of ros2cli (jazzy).

``ros2 node info``, ``topic list -v/find/bw/delay``, ``service find``, ``interface
package(s)``, ``pkg xml`` and ``doctor``.

Formats from ros2cli's sources: node info sections ``  Subscribers:`` ... each followed by
``    /name: type`` lines or one empty line; ``list -v`` sections `` * /t [type] N
publisher(s)``; bw ``<bw>/s from N messages`` + ``\tMessage size mean: ...``; delay
``average delay: ...`` + ``\tmin: ...s max: ...s std dev: ...s window: N``; doctor's
``All N checks passed`` / ``N/M check(s) failed`` + ``Failed modules: ...`` and reports
``\n   NAME`` + ``item<pad>: value``.
"""

import re
import subprocess
import time


def _ros2(exe, env, *argv, timeout=60):
    return subprocess.run([exe('ros2'), *argv], env=env, capture_output=True, text=True,
                          timeout=timeout)


def test_node_info_of_talker(ros_env, procs, exe):
    from conftest import run_until
    procs.start([exe('talker')], ros_env)
    # a fresh process's discovery may miss endpoints on a loaded machine: ask until complete
    result = run_until([exe('ros2'), 'node', 'info', '/minimal_publisher'], ros_env, lambda r: (
        '    /topic: std_msgs/msg/String\n' in r.stdout
        and '/minimal_publisher/list_parameters:' in r.stdout))
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert out.startswith('/minimal_publisher\n  Subscribers:\n\n  Publishers:\n'), out
    publishers = out.split('  Publishers:\n')[1].split('  Service Servers:\n')[0]
    assert '    /topic: std_msgs/msg/String\n' in publishers
    assert '    /rosout: rcl_interfaces/msg/Log\n' in publishers
    servers = out.split('  Service Servers:\n')[1].split('  Service Clients:\n')[0]
    assert ('    /minimal_publisher/list_parameters: rcl_interfaces/srv/ListParameters\n'
            in servers)
    assert out.endswith('  Service Clients:\n\n  Action Servers:\n\n  Action Clients:\n\n')
    result = _ros2(exe, ros_env, 'node', 'info', '/nobody', '-s', '1')
    assert (result.returncode, result.stderr) == (1, "Unable to find node '/nobody'\n")


def test_topic_list_verbose_find_and_service_find(ros_env, procs, exe):
    from conftest import run_until
    procs.start([exe('talker')], ros_env)
    listener = procs.start([exe('listener')], ros_env)
    # both nodes are up and matched once the listener hears the talker (a loaded machine
    # takes seconds to start two Python processes)
    assert listener.wait_for_output('I heard', timeout=90.0), listener.output
    # each query is a fresh process whose discovery may still be incomplete after its spin
    # time: ask again until the answer holds what the graph has (or the deadline passes)
    result = run_until([exe('ros2'), 'topic', 'list', '-v'], ros_env, lambda r: (
        ' * /topic [std_msgs/msg/String] 1 publisher' in r.stdout.splitlines()
        and ' * /topic [std_msgs/msg/String] 1 subscriber' in r.stdout.splitlines()))
    assert result.returncode == 0, result.stderr
    published, subscribed = result.stdout.split('\n\n')[:2]
    assert published.startswith('Published topics:\n')
    assert ' * /topic [std_msgs/msg/String] 1 publisher' in published.splitlines()
    assert subscribed.startswith('Subscribed topics:\n')
    assert ' * /topic [std_msgs/msg/String] 1 subscriber' in subscribed.splitlines()

    result = run_until([exe('ros2'), 'topic', 'find', 'std_msgs/msg/String'], ros_env,
                       lambda r: r.stdout == '/topic\n')
    assert result.stdout == '/topic\n', result.stdout
    result = run_until([exe('ros2'), 'topic', 'find', '-c', 'std_msgs/msg/String'], ros_env,
                       lambda r: r.stdout == '1\n')
    assert result.stdout == '1\n'

    expected = {'/minimal_publisher/list_parameters', '/minimal_subscriber/list_parameters'}
    result = run_until([exe('ros2'), 'service', 'find', 'rcl_interfaces/srv/ListParameters'],
                       ros_env, lambda r: expected <= set(r.stdout.splitlines()))
    lines = result.stdout.splitlines()
    assert expected <= set(lines), result.stdout
    assert all(line.endswith('/list_parameters') for line in lines)


def test_topic_bw_and_delay(ros_env, procs, exe):
    procs.start([exe('ros2'), 'topic', 'pub', '-r', '10', '/stamped',
                 'geometry_msgs/msg/TwistStamped', '{header: auto}'], ros_env)
    bw = procs.start([exe('ros2'), 'topic', 'bw', '/stamped'], ros_env)
    delay = procs.start([exe('ros2'), 'topic', 'delay', '/stamped'], ros_env)
    assert bw.wait_for_output('Message size mean', timeout=30.0), bw.output
    assert delay.wait_for_output('window:', timeout=30.0), delay.output
    assert bw.output.startswith('Subscribed to [/stamped]\n'), bw.output
    # at 10 Hz the rate stays under 1000 B/s, so sizes are in B. CDR of a TwistStamped with
    # an empty frame id: 4 (encapsulation) + 8 (stamp) + 5 (empty
    # string: length + NUL) + 3 (alignment of the doubles) + 48 (six doubles) = 68 bytes
    assert re.search(r'^\d+ B/s from \d+ messages\n\tMessage size mean: 68 B min: 68 B '
                     r'max: 68 B$', bw.output, re.M), bw.output
    match = re.search(r'^average delay: (-?\d+\.\d{3})\n\tmin: -?\d+\.\d{3}s max: -?\d+\.\d{3}s '
                      r'std dev: \d+\.\d{5}s window: \d+$', delay.output, re.M)
    assert match, delay.output
    assert 0.0 <= float(match.group(1)) < 1.0


def test_interface_packages_and_pkg_xml(ros_env, exe):
    result = _ros2(exe, ros_env, 'interface', 'packages')
    packages = result.stdout.splitlines()
    assert {'std_msgs', 'tf2_msgs', 'geometry_msgs'} <= set(packages)
    assert packages == sorted(packages)
    result = _ros2(exe, ros_env, 'interface', 'package', 'tf2_msgs')
    assert 'tf2_msgs/msg/TFMessage' in result.stdout.splitlines()
    assert 'tf2_msgs/srv/FrameGraph' in result.stdout.splitlines()
    result = _ros2(exe, ros_env, 'interface', 'package', 'nope_msgs')
    assert (result.returncode, result.stderr) == (1, "Unknown package 'nope_msgs'\n")
    result = _ros2(exe, ros_env, 'pkg', 'xml', 'amr_description', '-t', 'name')
    assert result.stdout == 'amr_description\n'
    result = _ros2(exe, ros_env, 'pkg', 'xml', 'amr_description')
    assert result.stdout.startswith('<?xml') and '<name>amr_description</name>' in result.stdout
    result = _ros2(exe, ros_env, 'pkg', 'xml', 'nope')
    assert (result.returncode, result.stderr) == (1, 'Package not found\n')


def test_doctor_checks_and_report(ros_env, exe):
    env = dict(ros_env, ROS_DISTRO='jazzy')
    result = _ros2(exe, env, 'doctor')
    assert result.returncode == 0
    assert result.stdout == '\nAll 6 checks passed\n\n', (result.stdout, result.stderr)
    env.pop('ROS_DISTRO')
    result = _ros2(exe, env, 'doctor')
    assert result.stdout == '\n1/6 check(s) failed\n\nFailed modules: platform\n', result.stdout
    assert re.search(r'^.+: \d+: UserWarning: ROS_DISTRO is not set\.$', result.stderr, re.M)
    result = _ros2(exe, ros_env, 'doctor', '--report')
    assert '\n   RMW MIDDLEWARE\nmiddleware name    : rmw_fastrtps_cpp\n' in result.stdout
    assert f'\nROS_DOMAIN_ID                    : {ros_env["ROS_DOMAIN_ID"]}\n' in result.stdout


ACTION_SERVER = """
import rclpy
from rclpy.action import ActionServer
from tf2_msgs.action import LookupTransform
rclpy.init()
node = rclpy.create_node('lookup_server')
server = ActionServer(node, LookupTransform, 'lookup', lambda goal: LookupTransform.Result())
print('serving', flush=True)
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
"""


def test_action_list_shows_an_action_server(ros_env, procs, exe):
    import sys
    from conftest import run_until
    server = procs.start([sys.executable, '-c', ACTION_SERVER], ros_env)
    assert server.wait_for_output('serving', 60.0), server.output
    result = run_until([exe('ros2'), 'action', 'list', '-t'], ros_env,
                       lambda r: '/lookup [tf2_msgs/action/LookupTransform]' in r.stdout)
    assert result.stdout == '/lookup [tf2_msgs/action/LookupTransform]\n', result.stdout
    assert _ros2(exe, ros_env, 'action', 'list').stdout == '/lookup\n'
    assert _ros2(exe, ros_env, 'action', 'list', '-c').stdout == '1\n'


def test_topic_info_counts_are_the_graphs_every_time(ros_env, procs, exe):
    """Issue 33: ``topic info`` said ``Publisher count: 0`` in one call of three."""
    import xmlrpc.client
    procs.start([exe('talker')], ros_env)
    procs.start([exe('listener')], ros_env)
    assert _ros2(exe, ros_env, 'daemon', 'start').returncode == 0
    proxy = xmlrpc.client.ServerProxy(f'http://127.0.0.1:{11511 + int(ros_env["ROS_DOMAIN_ID"])}/')
    deadline = time.monotonic() + 90.0
    # warm: both seen, and older than the verbs' spin time (3 s), so the verbs ask it
    while (proxy.count_publishers('/topic'), proxy.count_subscribers('/topic')) != (1, 1) or \
            proxy.uptime() < 4.0:
        assert time.monotonic() < deadline, 'the daemon never saw the talker and the listener'
        time.sleep(0.2)
    # the daemon is warm: each call answers from the graph it follows (and the type is known
    # from the listener alone, which made the old answer race the talker's discovery)
    for _ in range(3):
        info = _ros2(exe, ros_env, 'topic', 'info', '/topic')
        assert info.stdout == ('Type: std_msgs/msg/String\nPublisher count: 1\n'
                               'Subscription count: 1\n'), info.stdout + info.stderr
    verbose = _ros2(exe, ros_env, 'topic', 'info', '-v', '/topic')
    assert 'Node name: minimal_publisher\n' in verbose.stdout, verbose.stdout + verbose.stderr
    assert 'Endpoint type: PUBLISHER\n' in verbose.stdout
    assert 'Endpoint type: SUBSCRIPTION\n' in verbose.stdout
    # its own node listens to discovery for the whole spin time before it counts
    direct = _ros2(exe, ros_env, 'topic', 'info', '/topic', '--no-daemon', '-s', '8')
    assert 'Publisher count: 1\nSubscription count: 1\n' in direct.stdout, \
        direct.stdout + direct.stderr
    assert _ros2(exe, ros_env, 'daemon', 'stop').returncode == 0
