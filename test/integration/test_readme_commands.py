# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
r"""
Every command block of README.md's tutorial sections runs as printed.

The command lines are read from README.md ("The tutorial path" up to "Nodes and topics"), their
``\`` continuations joined and ``#`` comments dropped; :data:`PLAYBOOK` says for each how a user
runs it: ``once`` (runs to its end), ``serve`` (keeps running until Ctrl-C; started, its
expected line awaited, stopped with SIGINT at the end of its scene), ``stop`` (the same, but
stopped before the next command, as ``bag record`` before ``bag info``) or ``skip`` (with
why).
Commands run in scenes, each in its own ROS domain and in a scratch directory that sees the
repository's urdf/ and config/: a command of README.md that the playbook does not know fails
the test, so README.md cannot drift from what is tested. A command fails on a non-zero exit
code, a missing expected line or a Python traceback.
"""

import os
import re
import subprocess

from conftest import next_domain_id  # noqa: I100 - the suite's fixtures and helpers
from conftest import release_domain_id
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
TELEOP = ('ros2 run amr_description teleop_twist_keyboard --ros-args -p stamped:=true '
          '-p use_sim_time:=true -r /cmd_vel:=/diff_drive_controller/cmd_vel')
ACTIVE = 'Configured and activated diff_drive_controller'
STOP_STACK = 'Ctrl-C in every terminal'  # kind 'stop-serving': not a README command

# scene -> [(command as in README.md, kind, expected text or None)], run in this order
PLAYBOOK = {
    'environment': [('source scripts/env.sh', 'once', None)],
    'talker': [
        ('ros2 run amr_description talker', 'serve', 'Publishing: "Hello World: '),
        ('ros2 run amr_description listener', 'serve', 'I heard: "Hello World: '),
        ('ros2 topic echo /topic', 'serve', "data: 'Hello World: "),
    ],
    'checks': [
        ('check_urdf urdf/amr.urdf', 'once', 'robot name is: amr'),
        ('ros2 run amr_description check_model --controllers config/controllers.yaml '
         'urdf/amr.urdf', 'once', None),
    ],
    'display': [
        ('ros2 launch amr_description display', 'serve', 'viewer: open http://'),
        ('ros2 run amr_description render -o robot.png', 'once', None),
        ('ros2 run amr_description render --urdf urdf/amr.urdf --frames -o robot.png', 'once',
         None),
        ('ros2 run amr_description render --urdf urdf/amr.urdf --world warehouse -o world.png',
         'once', 'wrote world.png'),
    ],
    'display without sliders': [
        ('ros2 launch amr_description display gui:=false', 'serve', 'viewer: open http://'),
    ],
    'remote pages': [
        ('ssh -L 8080:127.0.0.1:8080 -L 8081:127.0.0.1:8081 you@robot-host', 'skip',
         'needs another machine'),
    ],
    'sim': [
        ('ros2 launch amr_description sim', 'serve', ACTIVE),
        ('ros2 run amr_description screenshot http://127.0.0.1:8080/ -o viewer.png '
         '--size 1280x800', 'once', 'screenshot: wrote viewer.png (1280x800)'),
        ('ros2 control list_controllers', 'once', 'diff_drive_controller'),
        ('ros2 control list_hardware_interfaces', 'once', 'command interfaces'),
        ('ros2 topic pub --once /diff_drive_controller/cmd_vel geometry_msgs/msg/TwistStamped '
         '"{header: {frame_id: base_link}, twist: {linear: {x: 0.5}, angular: {z: 0.0}}}"',
         'once', None),
        ('ros2 topic echo /odom', 'serve', 'child_frame_id: base_footprint'),
        (TELEOP, 'serve', 'currently:'),
        ('ros2 param get /diff_drive_controller wheel_separation', 'once',
         'Double value is: 0.3'),
        ('ros2 param dump /diff_drive_controller > ddc.yaml', 'once', None),
        ('ros2 node info /diff_drive_controller', 'once', 'Subscribers:'),
        ('ros2 topic bw /tf', 'serve', 'B/s from'),
        ('ros2 bag record -a -o run1', 'stop', 'Recording...'),
        ('ros2 bag info run1', 'once', 'Storage id:'),
        ('ros2 bag play run1', 'once', None),
        ('ros2 doctor', 'once', None),
        ('ros2 daemon status', 'once', 'The daemon is'),
        (STOP_STACK, 'stop-serving', None),
        ('ros2 run amr_description viewer --ros-args -p use_sim_time:=true', 'serve',
         'viewer: open http://'),
        # (whether the short bag holds /clock depends on the recorder's discovery: the
        # round trip of test_cli_bag.py checks what the player does with it)
        ('ros2 bag play run1 --clock', 'once', None),
    ],
    'sim fast': [
        ('ros2 launch amr_description sim rtf:=0', 'serve', ACTIVE),
    ],
    'sim by hand': [
        ('ros2 run amr_description mujoco_sim --ros-args -r '
         '/diff_drive_controller/odom:=/odom', 'serve', 'spawn with'),
        ('ros2 run amr_description robot_state_publisher --ros-args -p use_sim_time:=true '
         '-p robot_description:="$(cat urdf/amr.urdf)"', 'serve', None),
        ('ros2 run amr_description create -topic robot_description -name amr -z 0.2', 'once',
         None),
        ('ros2 run amr_description spawner joint_state_broadcaster', 'once', None),
        ('ros2 run amr_description spawner diff_drive_controller', 'once', None),
    ],
}


def readme_commands():
    """Return the command lines of README.md's tutorial sections (continuations joined)."""
    with open(os.path.join(ROOT, 'README.md')) as f:
        text = f.read()
    tutorial = text[text.index('## The tutorial path'):text.index('## Nodes and topics')]
    commands = []
    for block in re.findall(r'```bash\n(.*?)```', tutorial, re.S):
        joined = re.sub(r'\\\n\s*', '', block)
        for line in joined.splitlines():
            line = re.sub(r'\s+#.*$', '', line).strip()
            if line and not line.startswith('#'):
                commands.append(line)
    return commands


def test_the_playbook_knows_every_command_of_the_readme():
    known = [command for scene in PLAYBOOK.values() for command, kind, _ in scene
             if kind != 'stop-serving']
    unknown = [c for c in readme_commands() if c not in known]
    assert not unknown, f'README.md commands missing from the playbook: {unknown}'
    missing = [c for c in known if c not in readme_commands()]
    assert not missing, f'playbook commands no longer in README.md: {missing}'


def _scratch(tmp_path):
    for name in ('urdf', 'config', 'scripts'):
        os.symlink(os.path.join(ROOT, name), tmp_path / name)
    return str(tmp_path)


def _check(proc, command, expected, code):
    output = proc.output
    assert 'Traceback' not in output, f'{command}:\n{output[-3000:]}'
    assert code == 0, f'{command}: exit code {code}\n{output[-3000:]}'
    if expected is not None:
        assert expected in output, f'{command}: no "{expected}"\n{output[-3000:]}'


@pytest.mark.parametrize('scene', [s for s in PLAYBOOK if s != 'environment'])
def test_a_scene_of_the_readme_runs_as_printed(scene, procs, ros_env, tmp_path):
    cwd = _scratch(tmp_path)
    domain = next_domain_id()  # a scene of its own: stacks of two scenes never meet
    env = dict(ros_env, ROS_DOMAIN_ID=str(domain))
    serving = []
    try:
        for command, kind, expected in PLAYBOOK[scene]:
            if kind == 'skip':
                continue
            if kind == 'stop-serving':  # the user stops what runs (Ctrl-C in each terminal)
                for proc, served, master in reversed(serving):
                    _check(proc, served, None, proc.interrupt(timeout=60.0))
                    if master is not None:
                        os.close(master)
                serving = []
                continue
            stdin = subprocess.DEVNULL
            master = None
            if command == TELEOP:
                master, stdin = os.openpty()  # a keyboard, as in a terminal
            proc = procs.start(['bash', '-c', command], env, cwd=cwd, stdin=stdin)
            if master is not None:
                os.close(stdin)
            if kind == 'once':
                _check(proc, command, expected, proc.wait(timeout=180.0))
                continue
            assert proc.wait_for_output(expected, 180.0) if expected else \
                proc.popen.poll() is None, f'{command}:\n{proc.output[-3000:]}'
            if kind == 'stop':  # the user presses Ctrl-C before the next command
                _check(proc, command, None, proc.interrupt(timeout=60.0))
                continue
            serving.append((proc, command, master))
        for proc, command, master in reversed(serving):
            _check(proc, command, None, proc.interrupt(timeout=60.0))
            if master is not None:
                os.close(master)
    finally:
        for proc, _, _ in serving:
            proc.interrupt(timeout=10.0)
        release_domain_id(domain)
