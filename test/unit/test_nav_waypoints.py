# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The waypoint follower's visiting order and missed list (nav2_waypoint_follower's rules)."""

from amr_description.nav.waypoints import TASK_EXECUTOR_FAILED
from amr_description.nav.waypoints import WaypointRun
import pytest


def visit(run, outcomes):
    """Feed ``outcomes`` (True: reached, int: failed with that code); return the indices."""
    seen, end = [], None
    for outcome in outcomes:
        seen.append(run.index)
        end = run.reached() if outcome is True else run.failed(outcome)
        if end != 'next':
            break
    return seen, end


def test_all_reached_in_order_from_goal_index():
    seen, end = visit(WaypointRun(4, goal_index=1), [True] * 10)
    assert seen == [1, 2, 3]
    assert end == 'succeeded'


def test_loops_start_again_from_zero():
    seen, end = visit(WaypointRun(3, goal_index=2, number_of_loops=2), [True] * 20)
    assert seen == [2, 0, 1, 2, 0, 1, 2]
    assert end == 'succeeded'


def test_stop_on_failure_aborts_at_the_first_miss():
    run = WaypointRun(3, stop_on_failure=True)
    seen, end = visit(run, [True, 104, True])
    assert (seen, end) == ([0, 1], 'aborted')
    assert run.missed == [(1, 104)]


def test_without_stop_on_failure_misses_are_listed_and_it_succeeds():
    run = WaypointRun(3, stop_on_failure=False)
    seen, end = visit(run, [201, True, 0])
    assert (seen, end) == ([0, 1, 2], 'succeeded')
    assert run.missed == [(0, 201), (2, 0)]


def test_failed_task_is_a_miss_with_task_executor_failed():
    run = WaypointRun(2, stop_on_failure=False)
    assert run.reached(task_succeeded=False) == 'next'
    assert run.missed == [(0, TASK_EXECUTOR_FAILED)]
    assert TASK_EXECUTOR_FAILED == 601


@pytest.mark.parametrize('count, index', [(0, 0), (2, 2), (3, -1)])
def test_bad_goal_raises(count, index):
    with pytest.raises(ValueError):
        WaypointRun(count, goal_index=index)


def test_unused_overrides_lists_the_params_file_entries_never_declared():
    from amr_description.ros.parameters import unused_overrides

    class FakeNode:
        _parameter_overrides = {'use_sim_time': True, 'controller_frequency': 20.0,
                                'FollowPath.critics': ['x'], 'progress_checker_plugins': []}

        def has_parameter(self, name):
            return name == 'controller_frequency'

    assert unused_overrides(FakeNode()) == ['FollowPath.critics', 'progress_checker_plugins']
