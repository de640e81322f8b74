# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Nav2's lifecycle plans, map_saver_cli's arguments, OccupancyGrid conversions (no processes)."""

import math

from amr_description.cli.lifecycle import lifecycle_node_names
from amr_description.core import lifecycle_plan as lp
from amr_description.nav.grid_message import grid_from_message
from amr_description.nav.grid_message import occupancy_grid
from amr_description.nav.map_io import GridMap
from amr_description.nodes.map_saver import parse_cli
from builtin_interfaces.msg import Time
import numpy as np
import pytest


def test_startup_configures_all_then_activates_all_in_order():
    steps = lp.plan(lp.STARTUP, ['map_server', 'amcl'])
    assert [(s.node, s.transition, s.goal) for s in steps] == [
        ('map_server', lp.CONFIGURE, lp.INACTIVE), ('amcl', lp.CONFIGURE, lp.INACTIVE),
        ('map_server', lp.ACTIVATE, lp.ACTIVE), ('amcl', lp.ACTIVATE, lp.ACTIVE)]
    assert steps[0].line == 'Configuring map_server'


def test_shutdown_runs_backwards_to_finalized():
    steps = lp.plan(lp.SHUTDOWN, ['a', 'b'])
    assert [(s.node, s.transition) for s in steps] == [
        ('b', lp.DEACTIVATE), ('a', lp.DEACTIVATE), ('b', lp.CLEANUP), ('a', lp.CLEANUP),
        ('b', lp.UNCONFIGURED_SHUTDOWN), ('a', lp.UNCONFIGURED_SHUTDOWN)]
    assert steps[-1].goal == lp.FINALIZED


@pytest.mark.parametrize('command,transitions', [
    (lp.PAUSE, [lp.DEACTIVATE]), (lp.RESUME, [lp.ACTIVATE]),
    (lp.RESET, [lp.DEACTIVATE, lp.CLEANUP]), (lp.CONFIGURE_COMMAND, [lp.CONFIGURE]),
    (lp.CLEANUP_COMMAND, [lp.CLEANUP])])
def test_other_commands(command, transitions):
    assert [s.transition for s in lp.plan(command, ['n'])] == transitions


def test_unknown_command_is_refused():
    with pytest.raises(ValueError, match='unknown ManageLifecycleNodes command 9'):
        lp.plan(9, ['n'])


def test_map_saver_cli_arguments():
    options = parse_cli(['-f', '/tmp/m', '--occ', '0.7', '--free', '0.2', '--fmt', 'png',
                         '--mode', 'scale', '-t', 'slam_map', '--ros-args', '-p', 'x:=1'])
    assert options == {'topic': 'slam_map', 'path': '/tmp/m', 'occupied': 0.7, 'free': 0.2,
                       'fmt': 'png', 'mode': 'scale', 'help': False}
    assert parse_cli(['-h'])['help']
    with pytest.raises(ValueError, match='Value expected after -f'):
        parse_cli(['-f'])
    with pytest.raises(ValueError, match='--occ: expected a number'):
        parse_cli(['--occ', 'high'])
    with pytest.raises(ValueError, match='Wrong argument: --size'):
        parse_cli(['--size', '3'])


def test_occupancy_grid_round_trip_with_yaw():
    data = np.arange(-1, 11, dtype=np.int8).reshape(3, 4)
    msg = occupancy_grid(GridMap(data, 0.05, (1.5, -2.0, math.pi / 2)), 'map', Time(sec=3))
    assert (msg.info.width, msg.info.height) == (4, 3)
    assert msg.data[1 * 4 + 2] == data[1, 2]  # cell (x=2, y=1) at y * width + x
    assert msg.info.origin.orientation.z == pytest.approx(math.sqrt(0.5))
    assert msg.info.map_load_time.sec == 3 and msg.header.frame_id == 'map'
    grid = grid_from_message(msg)
    assert np.array_equal(grid.data, data)
    assert grid.origin == pytest.approx((1.5, -2.0, math.pi / 2))


def test_a_grid_message_of_the_wrong_size_is_one_line():
    msg = occupancy_grid(GridMap(np.zeros((2, 2), np.int8), 0.1), 'map', Time())
    msg.info.width = 3
    with pytest.raises(ValueError, match='data has 4 cells, expected width 3 x height 2 = 6'):
        grid_from_message(msg)


def test_lifecycle_nodes_are_those_with_get_state():
    services = [('/amcl/get_state', ['lifecycle_msgs/srv/GetState']),
                ('/talker/get_state', ['example/srv/Other']),
                ('/map_server/get_state', ['lifecycle_msgs/srv/GetState'])]
    assert lifecycle_node_names(['/talker', '/map_server', '/amcl'], services) == \
        ['/amcl', '/map_server']


def test_a_transition_without_an_answer_is_settled_by_the_nodes_state():
    # lifecycle_msgs/msg/State: 1-4 primary, 10-15 transition states
    assert lp.settled(lp.INACTIVE, lp.INACTIVE) is True
    assert lp.settled(lp.UNCONFIGURED, lp.INACTIVE) is False
    assert lp.settled(10, lp.INACTIVE) is None  # configuring
    assert lp.settled(None, lp.ACTIVE) is None  # no answer
    assert lp.settled(0, lp.ACTIVE) is None  # unknown


class _Future:
    """A future that is done when it has a result."""

    def __init__(self, result=None):
        self._result = result

    def done(self):
        return self._result is not None

    def result(self):
        return self._result


class _Client:
    """A service client whose answers are scripted (the last repeats); None never comes."""

    def __init__(self, answers):
        self.answers = list(answers)
        self.requests = []
        self.dropped = 0

    def call_async(self, request):
        self.requests.append(request)
        return _Future(self.answers.pop(0) if len(self.answers) > 1 else self.answers[0])

    def remove_pending_request(self, future):
        self.dropped += 1


def _autostart(monkeypatch, wait):
    from amr_description.nodes import lifecycle_autostart as autostart
    monkeypatch.setattr(autostart, 'SERVICE_WAIT', wait)
    return autostart


def _no_wait(future, timeout):
    """Answers are there at once or never (the scripted clients)."""


def _state(state_id):
    from lifecycle_msgs.srv import GetState
    answer = GetState.Response()
    answer.current_state.id = state_id
    return answer


def test_autostart_goes_on_when_the_change_state_answer_is_dropped(monkeypatch):
    autostart = _autostart(monkeypatch, 60.0)
    change = _Client([None])  # configured, but its answer was dropped
    get = _Client([_state(lp.UNCONFIGURED), None, _state(10), _state(lp.INACTIVE)])
    assert autostart._transition(_no_wait, change, get, lp.CONFIGURE) is True
    assert len(change.requests) == 1 and change.requests[0].transition.id == lp.CONFIGURE
    assert len(get.requests) == 4 and change.dropped == 1


def test_autostart_fails_only_at_the_deadline_when_the_node_stays_put(monkeypatch):
    from lifecycle_msgs.srv import ChangeState
    autostart = _autostart(monkeypatch, 0.05)
    change = _Client([None])
    get = _Client([_state(lp.UNCONFIGURED)])
    assert autostart._transition(_no_wait, change, get, lp.CONFIGURE) is False
    assert change.dropped == 1
    # an answer that comes is taken as it is
    refused = ChangeState.Response(success=False)
    get = _Client([_state(lp.UNCONFIGURED)])
    assert autostart._transition(_no_wait, _Client([refused]), get, lp.CONFIGURE) is False
