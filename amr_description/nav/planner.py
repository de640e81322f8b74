# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``GridBased`` global planner: NavFn's costs and goal rules over scikit-image's search.

Each cell's travel cost is NavFn's (``nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp``,
``NavFn::setCostmap``): ``50 + 0.8 * cost`` for costs below 253, 253 for unknown cells when
``allow_unknown``, impassable for inscribed, lethal (and unknown otherwise) cells. The
minimum-cost 8-connected path is found by ``skimage.graph.MCP_Geometric`` (Dijkstra, diagonal
steps cost sqrt(2) times the mean of the two cells) instead of NavFn's interpolated potential
field: paths run through the same corridors, their poses are the cells' centres. The goal rules
are ``NavfnPlanner::makePlan``'s (``nav2_navfn_planner/src/navfn_planner.cpp``): a goal
outside the map or a start outside it fail with their codes; a goal cell that is lethal with
``tolerance`` 0 fails as occupied; an unreachable goal is replaced by the reachable cell
closest to it within ``tolerance`` (a square, as NavFn's); the last pose carries the goal's
orientation (the approach direction with ``use_final_approach_orientation``).
"""

import math

from amr_description.nav.costmap import INSCRIBED_INFLATED_OBSTACLE
from amr_description.nav.costmap import LETHAL_OBSTACLE
from amr_description.nav.costmap import NO_INFORMATION
import numpy as np
# imported here, not in plan(): composed servers plan on threads of their own (nav/costmap.py)
from skimage.graph import MCP_Geometric

COST_NEUTRAL = 50.0
COST_FACTOR = 0.8
UNKNOWN_TRAVEL = 253.0
"""NavFn's travel costs: open space, per unit of Nav2 cost, unknown space when allowed."""


class PlanError(Exception):
    """
    A plan that cannot be made; ``code`` names ComputePathToPose's error constant.

    :param code: ``'START_OUTSIDE_MAP'``, ``'GOAL_OUTSIDE_MAP'``, ``'START_OCCUPIED'``,
        ``'GOAL_OCCUPIED'`` or ``'NO_VALID_PATH'``.
    :param message: one line for the log and the result's ``error_msg``.
    """

    def __init__(self, code, message):
        """Keep the code."""
        super().__init__(message)
        self.code = code


def travel_costs(costs, allow_unknown=True):
    """
    Return NavFn's per-cell travel costs (float, -1 = impassable) for Nav2 costs.

    :param costs: ``(h, w)`` uint8 Nav2 costs.
    :param allow_unknown: unknown cells are passable at 253.
    """
    c = np.asarray(costs)
    travel = COST_NEUTRAL + COST_FACTOR * c.astype(np.float64)
    travel[c >= INSCRIBED_INFLATED_OBSTACLE] = -1.0
    if allow_unknown:
        travel[c == NO_INFORMATION] = UNKNOWN_TRAVEL
    return travel


def make_plan(costmap, start, goal, tolerance=0.5, allow_unknown=True,
              use_final_approach_orientation=False):
    """
    Return a path from ``start`` to ``goal`` on ``costmap``.

    :param costmap: a :class:`amr_description.nav.costmap.Costmap`.
    :param start: ``(x, y)`` in the costmap's frame, m.
    :param goal: ``(x, y, yaw)`` in the costmap's frame, m and rad.
    :param tolerance: m; see the module docstring.
    :param allow_unknown: plan through unknown cells.
    :param use_final_approach_orientation: the last pose faces along the last step.
    :returns: ``(n, 3)`` array of ``x, y, yaw`` poses; the poses before the last have yaw NaN
        (NavFn leaves their orientation unset, w = 1).
    :raises PlanError: see its codes.
    """
    s_cell = costmap.world_to_map(start[0], start[1])
    if s_cell is None:
        raise PlanError('START_OUTSIDE_MAP', f'Start Coordinates of({start[0]:.2f}, '
                        f'{start[1]:.2f}) was outside bounds')
    g_cell = costmap.world_to_map(goal[0], goal[1])
    if g_cell is None:
        raise PlanError('GOAL_OUTSIDE_MAP', f'Goal Coordinates of({goal[0]:.2f}, '
                        f'{goal[1]:.2f}) was outside bounds')
    costs = costmap.costs
    if tolerance == 0.0 and costs[g_cell[1], g_cell[0]] == LETHAL_OBSTACLE:
        raise PlanError('GOAL_OCCUPIED', f'Goal Coordinates of({goal[0]:.2f}, '
                        f'{goal[1]:.2f}) was in lethal cost')
    if s_cell == g_cell:
        x, y = costmap.map_to_world(*s_cell)
        return np.array([[float(x), float(y), goal[2]]])
    travel = travel_costs(costs, allow_unknown)
    # the robot's own cell is passable even when inflated or lethal (NavFn's clearRobotCell)
    travel[s_cell[1], s_cell[0]] = max(travel[s_cell[1], s_cell[0]], COST_NEUTRAL)
    mcp = MCP_Geometric(travel, fully_connected=True)
    start_rc, goal_rc = (s_cell[1], s_cell[0]), (g_cell[1], g_cell[0])
    if travel[goal_rc] >= 0:
        cumulative, _ = mcp.find_costs([start_rc], [goal_rc])
    else:
        cumulative, _ = mcp.find_costs([start_rc])
    target = goal_rc
    if not np.isfinite(cumulative[goal_rc]):
        target = _closest_reachable(cumulative, goal_rc, tolerance / costmap.resolution)
        if target is None:
            raise PlanError('NO_VALID_PATH', 'Failed to create plan with tolerance of: '
                            f'{tolerance:.6f}')
    cells = np.array(mcp.traceback(target))  # (row, col) from start to target
    x, y = costmap.map_to_world(cells[:, 1], cells[:, 0])
    yaw = np.full(len(cells), np.nan)
    yaw[-1] = goal[2]
    if use_final_approach_orientation and len(cells) > 1:
        yaw[-1] = math.atan2(y[-1] - y[-2], x[-1] - x[-2])
    return np.column_stack((x, y, yaw))


def _closest_reachable(cumulative, goal_rc, half_cells):
    """Return the reachable cell within the square closest to the goal (Euclidean), or None."""
    h, w = cumulative.shape
    r = int(math.floor(half_cells))
    r0, r1 = max(goal_rc[0] - r, 0), min(goal_rc[0] + r + 1, h)
    c0, c1 = max(goal_rc[1] - r, 0), min(goal_rc[1] + r + 1, w)
    window = np.isfinite(cumulative[r0:r1, c0:c1])
    if not window.any():
        return None
    rows, cols = np.nonzero(window)
    d = np.hypot(rows + r0 - goal_rc[0], cols + c0 - goal_rc[1])
    k = int(np.argmin(d))
    return int(rows[k] + r0), int(cols[k] + c0)


def path_length(path):
    """Return the length (m) of an ``(n, >=2)`` path."""
    p = np.asarray(path, float)[:, :2]
    return float(np.hypot(*np.diff(p, axis=0).T).sum()) if len(p) > 1 else 0.0
