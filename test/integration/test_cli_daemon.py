# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 daemon`` and the graph verbs that use it, as ros2cli's (real processes, real DDS).

A graph verb starts the daemon on first use and answers from it afterwards; ``--no-daemon``
neither starts nor asks it; ``ros2 daemon start|status|stop`` print upstream's lines; a daemon
started with other discovery settings is replaced by the next verb; no daemon outlives its
test (conftest's ``release_domain_id``).
"""

import subprocess
import time
import xmlrpc.client

from amr_description.cli.daemon import process_alive
from conftest import run_until  # noqa: I100 - the suite's helpers


def _ros2(exe, env, *argv, timeout=60):
    return subprocess.run([exe('ros2'), *argv], env=env, capture_output=True, text=True,
                          timeout=timeout)


def _daemon_pid(env):
    proxy = xmlrpc.client.ServerProxy(f'http://127.0.0.1:{11511 + int(env["ROS_DOMAIN_ID"])}/')
    try:
        return int(proxy.pid())
    except (OSError, xmlrpc.client.Error):
        return None


def _wait_status(exe, env, text, timeout=30.0):
    result = run_until([exe('ros2'), 'daemon', 'status'], env,
                       lambda r: r.stdout.strip() == text, timeout=timeout)
    return result.stdout.strip()


def test_a_graph_verb_starts_the_daemon_and_then_answers_from_it(procs, exe, ros_env):
    assert _ros2(exe, ros_env, 'daemon', 'status').stdout == 'The daemon is not running\n'
    # --no-daemon: its own node, no daemon started
    listed = _ros2(exe, ros_env, 'topic', 'list', '--no-daemon', '-s', '0.5')
    assert listed.returncode == 0 and '/rosout' in listed.stdout, listed.stderr
    assert _ros2(exe, ros_env, 'daemon', 'status').stdout == 'The daemon is not running\n'
    # first use: answered by its own node, and the daemon is started in the background
    first = _ros2(exe, ros_env, 'topic', 'list')
    assert first.returncode == 0 and '/rosout' in first.stdout, first.stderr
    assert _wait_status(exe, ros_env, 'The daemon is running') == 'The daemon is running'
    pid = _daemon_pid(ros_env)
    # a talker appears in the daemon's graph; the verbs answer from it
    procs.start([exe('talker')], ros_env)
    found = run_until([exe('ros2'), 'topic', 'list', '-t'], ros_env,
                      lambda r: '/topic [std_msgs/msg/String]' in r.stdout)
    assert '/topic [std_msgs/msg/String]' in found.stdout, found.stdout + found.stderr
    typed = _ros2(exe, ros_env, 'topic', 'type', '/topic')
    assert typed.stdout == 'std_msgs/msg/String\n', typed.stdout + typed.stderr
    # hz takes the topic's type from the warm daemon (unit test: without asking its node)
    hz = procs.start([exe('ros2'), 'topic', 'hz', '/topic'], ros_env)
    assert hz.wait_for_output('average rate: ', timeout=90.0), hz.output
    assert hz.interrupt() is not None, 'ros2 topic hz ignored Ctrl-C'
    nodes = run_until([exe('ros2'), 'node', 'list', '-a'], ros_env,
                      lambda r: '/minimal_publisher' in r.stdout)
    lines = nodes.stdout.split()
    assert '/minimal_publisher' in lines, nodes.stdout
    # the daemon's own node is hidden: listed with --all only, as upstream's
    assert any(n.startswith('/_ros2cli_daemon_') for n in lines), nodes.stdout
    assert not any(n.startswith('/_ros2cli_daemon_')
                   for n in _ros2(exe, ros_env, 'node', 'list').stdout.split())
    # node info from the warm daemon: its node_endpoints, printed in upstream's sections
    proxy = xmlrpc.client.ServerProxy(f'http://127.0.0.1:{11511 + int(ros_env["ROS_DOMAIN_ID"])}/')
    sections = dict(proxy.node_endpoints('minimal_publisher', '/'))
    assert ['/topic', ['std_msgs/msg/String']] in sections['Publishers'], sections
    info = run_until([exe('ros2'), 'node', 'info', '/minimal_publisher', '-s', '0.5'], ros_env,
                     lambda r: '    /topic: std_msgs/msg/String\n' in r.stdout)
    assert info.stdout.startswith('/minimal_publisher\n  Subscribers:\n'), info.stdout
    assert '    /topic: std_msgs/msg/String\n' in info.stdout, info.stdout + info.stderr
    # param list: the warm daemon's node lists the nodes and calls list_parameters
    listed = run_until([exe('ros2'), 'param', 'list', '/minimal_publisher'], ros_env,
                       lambda r: '  use_sim_time' in r.stdout.splitlines())
    assert '  use_sim_time' in listed.stdout.splitlines(), listed.stdout + listed.stderr
    daemon_name, daemon_namespace = proxy.get_name_and_namespace()
    clients = dict(proxy.node_endpoints(daemon_name, daemon_namespace))['Service Clients']
    assert ['/minimal_publisher/list_parameters', ['rcl_interfaces/srv/ListParameters']] in \
        clients, clients
    assert _daemon_pid(ros_env) == pid  # the same daemon answered every verb
    # echo takes the type from the warm daemon, then waits until its own node sees the
    # publisher, so that a transient-local (latched) message reaches it
    procs.start([exe('static_transform_publisher'), '--x', '1', '--frame-id', 'world',
                 '--child-frame-id', 'probe'], ros_env)
    run_until([exe('ros2'), 'topic', 'list'], ros_env, lambda r: '/tf_static' in r.stdout)
    for _ in range(3):
        latched = _ros2(exe, ros_env, 'topic', 'echo', '--once', '/tf_static', timeout=90)
        assert 'child_frame_id: probe' in latched.stdout, latched.stdout + latched.stderr
    # start when running, stop, stop when stopped: upstream's lines
    assert _ros2(exe, ros_env, 'daemon', 'start').stdout == 'The daemon is already running\n'
    stopped = _ros2(exe, ros_env, 'daemon', 'stop')
    assert stopped.stdout == 'The daemon has been stopped\n', stopped.stdout + stopped.stderr
    assert not process_alive(pid), 'the daemon process is still there after "has been stopped"'
    assert _ros2(exe, ros_env, 'daemon', 'stop').stdout == 'The daemon is not running\n'
    started = _ros2(exe, ros_env, 'daemon', 'start')
    assert started.stdout == 'The daemon has been started\n', started.stdout + started.stderr


def test_a_daemon_with_other_discovery_settings_is_replaced(exe, ros_env):
    subnet = dict(ros_env, ROS_AUTOMATIC_DISCOVERY_RANGE='SUBNET')
    assert _ros2(exe, subnet, 'daemon', 'start').stdout == 'The daemon has been started\n'
    stale = _daemon_pid(ros_env)
    assert stale is not None
    listed = _ros2(exe, ros_env, 'topic', 'list')  # LOCALHOST: the SUBNET daemon is stale
    assert listed.returncode == 0 and '/rosout' in listed.stdout, listed.stderr
    deadline = time.monotonic() + 30.0
    while time.monotonic() < deadline and _daemon_pid(ros_env) in (None, stale):
        time.sleep(0.1)
    fresh = _daemon_pid(ros_env)
    assert fresh is not None and fresh != stale
    proxy = xmlrpc.client.ServerProxy(f'http://127.0.0.1:{11511 + int(ros_env["ROS_DOMAIN_ID"])}/')
    assert proxy.settings()['ROS_AUTOMATIC_DISCOVERY_RANGE'] == 'LOCALHOST'
