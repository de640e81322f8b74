# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
The ``GridBased`` global planner: NavFn's costs and goal rules over scikit-image's search.

Each cell's travel cost is NavFn's (``nav2_navfn_planner/include/nav2_navfn_planner/navfn.hpp``,
``NavFn::setCostmap``): ``50 + 0.8 * cost`` for costs below 253, 253 for unknown cells when
``allow_unknown``, impassable for inscribed, lethal (and unknown otherwise) cells. The
potential (each cell's cheapest travel cost to the goal) comes from
``skimage.graph.MCP_Geometric`` (Dijkstra over 8-connected cells, a diagonal step costing sqrt(2)
times the mean of its two cells) instead of NavFn's interpolated wavefront; like NavFn's
propagation it stops once it has reached the robot (here: every passable cell within
:data:`DESCENT_WINDOW` cells of it), the cells not reached being ``inf``. The path is
NavFn's ``calcPath`` on it (:func:`descend`): from the robot's cell down the interpolated
gradient of the potential in steps of half a cell, following the grid to the lowest neighbour
where a neighbour is impassable or the path oscillates. Descending one potential of the goal,
a path replanned from a point on the last one is the rest of it (a path traced back cell by
cell is not: its equal-cost diagonal and straight steps came in another order after each
replan, and the robot weaved after the moving kink). The goal rules
are ``NavfnPlanner::makePlan``'s (``nav2_navfn_planner/src/navfn_planner.cpp``): a goal
outside the map or a start outside it fail with their codes; a goal cell that is lethal with
``tolerance`` 0 fails as occupied; an unreachable goal is replaced by the reachable cell
closest to it within ``tolerance`` (a square, as NavFn's); the last pose carries the goal's
orientation (the approach direction with ``use_final_approach_orientation``).
"""

import math

from amr_description.nav.costmap import footprint_cost
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

PATH_STEP = 0.5
"""Cells per step down the potential (NavFn's ``pathStep``)."""

DESCENT_WINDOW = 3
"""Cells on each side of the robot's cell whose potential is final before the search stops."""


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
    start_rc, goal_rc = (s_cell[1], s_cell[0]), (g_cell[1], g_cell[0])
    # NavFn's propagation stops once it reaches the robot (``propNavFnDijkstra``): here once
    # the cells around the robot that the first steps down the gradient read are final
    near = _passable_around(travel, start_rc, DESCENT_WINDOW)
    mcp = MCP_Geometric(travel, fully_connected=True)
    potential = None
    if travel[goal_rc] >= 0:
        potential, _ = mcp.find_costs([goal_rc], near, find_all_ends=True)
    target = goal_rc
    if potential is None or not np.isfinite(potential[start_rc]):
        # the goal's cell is impassable, or walled in: the reachable cell nearest to it
        reach, _ = MCP_Geometric(travel, fully_connected=True).find_costs([start_rc])
        target = _closest_reachable(reach, goal_rc, tolerance / costmap.resolution)
        if target is None:
            raise PlanError('NO_VALID_PATH', 'Failed to create plan with tolerance of: '
                            f'{tolerance:.6f}')
        mcp = MCP_Geometric(travel, fully_connected=True)
        potential, _ = mcp.find_costs([target], near, find_all_ends=True)
    cells = descend(potential, start_rc, target)
    if cells is None:  # NavFn would fail here; the cells' own path is still a path
        cells = np.array(mcp.traceback(start_rc), float)[::-1]
    x, y = costmap.map_to_world(cells[:, 1], cells[:, 0])
    yaw = np.full(len(cells), np.nan)
    yaw[-1] = goal[2]
    if use_final_approach_orientation and len(cells) > 1:
        yaw[-1] = math.atan2(y[-1] - y[-2], x[-1] - x[-2])
    return np.column_stack((x, y, yaw))


def cell_gradient(potential, r, c):
    """
    Return NavFn's unit descent direction ``(d row, d col)`` of cell ``(r, c)``.

    A reachable cell sums its one-sided differences to its reachable side neighbours along
    each axis (towards lower potential); an unreachable cell points at a reachable side
    neighbour; outside the map counts as unreachable. ``(0, 0)`` when nothing sets a
    direction. Source: ``NavFn::gradCell`` (``nav2_navfn_planner/src/navfn.cpp``).

    :param potential: ``(h, w)`` cost to the goal, ``inf`` where unreachable.
    """
    h, w = potential.shape
    centre = float(potential[r, c])
    grad = [0.0, 0.0]
    for axis, (before, after) in enumerate((((r - 1, c), (r + 1, c)),
                                            ((r, c - 1), (r, c + 1)))):
        sides = [float(potential[i, j]) if 0 <= i < h and 0 <= j < w else math.inf
                 for i, j in (before, after)]
        if math.isfinite(centre):
            grad[axis] = ((sides[0] - centre if math.isfinite(sides[0]) else 0.0) +
                          (centre - sides[1] if math.isfinite(sides[1]) else 0.0))
        elif math.isfinite(sides[0]):
            grad[axis] = -1.0
        elif math.isfinite(sides[1]):
            grad[axis] = 1.0
    norm = math.hypot(grad[0], grad[1])
    return (grad[0] / norm, grad[1] / norm) if norm > 0.0 else (0.0, 0.0)


def descend(potential, start_rc, target_rc, step=PATH_STEP):
    """
    Return the path down a potential: ``(n, 2)`` float (row, col) from start to target.

    NavFn's ``calcPath``: from the start cell, move ``step`` cells along the bilinear
    interpolation of the four surrounding cells' gradients (:func:`cell_gradient`); where a
    cell of the 3 x 3 around the position is unreachable, or the position came back to where it
    was two steps before, move to the neighbour of lowest potential instead. The path ends at
    the target once within one cell of it. Source: ``nav2_navfn_planner/src/navfn.cpp``.

    :param potential: ``(h, w)`` cost to ``target_rc`` (``inf``: unreachable).
    :returns: the points, or None where NavFn fails (no lower neighbour, a zero gradient, the
        map's edge, or more than ``4 (h + w) / step`` steps).
    """
    potential = np.asarray(potential, float)
    h, w = potential.shape
    pot = np.ascontiguousarray(potential).ravel().item  # a Python float per call: fast
    cache = {}

    def gradient(n):
        if n not in cache:
            cache[n] = cell_gradient(potential, *divmod(n, w))
        return cache[n]

    inf = math.inf
    tr, tc = int(target_rc[0]), int(target_rc[1])
    y, x = float(start_rc[0]), float(start_rc[1])
    points = [(y, x)]
    for _ in range(int(4 * (h + w) / step)):
        r, c = int(round(y)), int(round(x))
        if abs(r - tr) <= 1 and abs(c - tc) <= 1:
            points.append((float(tr), float(tc)))
            return np.array(points)
        if not (0 < r < h - 1 and 0 < c < w - 1):
            return None
        around = [pot(k * w + j) for k in (r - 1, r, r + 1) for j in (c - 1, c, c + 1)]
        if max(around) == inf or (len(points) > 2 and points[-1] == points[-3]):
            k = min(range(9), key=around.__getitem__)
            if around[k] >= around[4]:
                return None
            y, x = float(r - 1 + k // 3), float(c - 1 + k % 3)
        else:
            r0, c0 = int(y), int(x)
            fr, fc = y - r0, x - c0
            n = r0 * w + c0
            (a0, a1), (b0, b1) = gradient(n), gradient(n + 1)
            (c0_, c1), (d0, d1) = gradient(n + w), gradient(n + w + 1)
            g0 = (1 - fr) * ((1 - fc) * a0 + fc * b0) + fr * ((1 - fc) * c0_ + fc * d0)
            g1 = (1 - fr) * ((1 - fc) * a1 + fc * b1) + fr * ((1 - fc) * c1 + fc * d1)
            norm = math.hypot(g0, g1)
            if norm == 0.0:
                return None
            y, x = y + step * g0 / norm, x + step * g1 / norm
        points.append((y, x))
    return None


def _passable_around(travel, rc, half):
    """Return the passable cells ``(row, col)`` within ``half`` cells of ``rc`` on the map."""
    h, w = travel.shape
    r0, r1 = max(rc[0] - half, 0), min(rc[0] + half + 1, h)
    c0, c1 = max(rc[1] - half, 0), min(rc[1] + half + 1, w)
    rows, cols = np.nonzero(travel[r0:r1, c0:c1] >= 0)
    return [(int(r + r0), int(c + c0)) for r, c in zip(rows, cols)]


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


def invalid_poses(costmap, poses, robot, footprint=None):
    """
    Return the indices of a path's poses in collision, from the pose nearest the robot on.

    As planner_server's ``isPathValid`` (``nav2_planner/src/planner_server.cpp``): the check
    starts at the pose nearest ``robot`` (the poses behind it may have been passed and become
    occupied since); a pose is invalid when its cost is LETHAL_OBSTACLE or
    INSCRIBED_INFLATED_OBSTACLE: the cell's cost (a pose off the map: lethal) for a costmap
    whose footprint came from ``robot_radius``, else the highest cost under the footprint's
    outline at the pose's yaw (:func:`amr_description.nav.costmap.footprint_cost`).

    :param costmap: :class:`amr_description.nav.costmap.Costmap`.
    :param poses: ``(n, 3)`` ``(x, y, yaw)`` in the costmap's frame (m, rad).
    :param robot: ``(x, y)`` of the robot in that frame, or None (TF could not place it:
        nothing is checked, as upstream's).
    :param footprint: ``(m, 2)`` padded footprint, or None to check cells (``use_radius``).
    :returns: list of int indices, in order.
    """
    p = np.asarray(poses, float).reshape(-1, 3)
    if robot is None or not len(p):
        return []
    first = int(np.argmin(np.hypot(p[:, 0] - robot[0], p[:, 1] - robot[1])))
    bad = []
    for i in range(first, len(p)):
        if footprint is None:
            cost = costmap.cost_at(p[i, 0], p[i, 1])
            cost = LETHAL_OBSTACLE if cost is None else cost
        else:
            cost = footprint_cost(costmap, footprint, p[i])
        if cost in (LETHAL_OBSTACLE, INSCRIBED_INFLATED_OBSTACLE):
            bad.append(i)
    return bad
