# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""What the navigation job reports: the goal table, the route line and two pictures."""

import math
import sys

from amr_description.core.course import wrap_angle
import numpy as np

PROGRAM = 'navigate_job'


def fail(message):
    """Print ``[navigate_job] error: message`` on stderr; return exit code 1."""
    print(f'[{PROGRAM}] error: {message}', file=sys.stderr, flush=True)
    return 1


def robot_params(path):
    """
    Read the robot's footprint and controller speeds from a Nav2 params file.

    :param path: a params file (``config/nav2_params.yaml``).
    :returns: dict ``footprint`` (list of (x, y), m; the local costmap's ``footprint``, or a
        16-gon of its ``robot_radius``), ``speed`` (FollowPath's ``desired_linear_vel``, m/s,
        default 0.5) and ``turn_rate`` (``rotate_to_heading_angular_vel``, rad/s, default 1.8;
        Regulated Pure Pursuit's defaults), ``accel`` and ``angular_accel`` (velocity_smoother's
        ``max_accel`` in x, m/s^2, and theta, rad/s^2; Nav2's defaults 2.5 and 3.2).
    :raises OSError: an unreadable file.
    :raises ValueError: a footprint that is not a list of points, or a ``max_accel`` that is
        not a list of three.
    """
    import yaml
    with open(path) as stream:
        document = yaml.safe_load(stream) or {}
    local = document.get('local_costmap', {}).get('local_costmap', {})
    local = local.get('ros__parameters', {})
    follow = document.get('controller_server', {}).get('ros__parameters', {}).get(
        'FollowPath', {})
    smoother = document.get('velocity_smoother', {}).get('ros__parameters', {})
    accel = smoother.get('max_accel', [2.5, 0.0, 3.2])
    if not (isinstance(accel, list) and len(accel) == 3):
        raise ValueError(f"{path}: velocity_smoother max_accel '{accel}': expected [x, y, theta]")
    footprint = local.get('footprint', '[]')
    points = yaml.safe_load(footprint) if isinstance(footprint, str) else footprint
    if not points:
        r = float(local.get('robot_radius', 0.1))
        points = [(r * math.cos(a), r * math.sin(a)) for a in np.linspace(0, 2 * math.pi, 17)[:-1]]
    if not all(isinstance(p, (list, tuple)) and len(p) == 2 for p in points):
        raise ValueError(f"{path}: local_costmap footprint '{footprint}': expected [[x, y], ...]")
    return {'footprint': [tuple(map(float, p)) for p in points],
            'speed': float(follow.get('desired_linear_vel', 0.5)),
            'turn_rate': float(follow.get('rotate_to_heading_angular_vel', 1.8)),
            'accel': float(accel[0]), 'angular_accel': float(accel[2])}


def goal_figures(row, sections, robot):
    """
    Return one goal's figures from its ground truth and plan.

    :param row: dict ``goal`` (x, y, yaw), ``start`` (x, y, yaw), ``planned`` [(x, y)],
        ``truth`` [(t, x, y, yaw)] (sim s, world m, rad), ``result``; optionally ``span``
        (sim s when the goal was sent and when its result came; else the ground truth's
        first and last stamps). The ground truth may go on after the result (the robot
        settling): its last sample is the end pose.
    :param sections: the world's shapes (:func:`amr_description.core.scan_map.world_sections`).
    :param robot: :func:`robot_params`.
    :returns: dict ``time``, ``bound`` and ``fastest`` (s; the last two from the plan, or
        None without one: :func:`amr_description.nav.trials.time_bound` and
        :func:`amr_description.nav.trials.fastest_time`),
        ``planned`` and ``driven`` (m), ``error`` (m) and ``yaw_error`` (rad) of the last
        ground truth from the goal, ``clearance`` (m, the closest approach; negative: touched),
        ``budget`` (:func:`amr_description.nav.trials.time_budget` between the goal's sending
        and its result).
    """
    from amr_description.nav.trials import fastest_time
    from amr_description.nav.trials import footprint_clearance
    from amr_description.nav.trials import path_length
    from amr_description.nav.trials import time_bound
    from amr_description.nav.trials import time_budget
    truth = np.asarray(row['truth'], dtype=float).reshape(-1, 4)
    x, y, yaw = row['goal']
    end = truth[-1] if len(truth) else (0.0,) + tuple(row['start'])
    bound = fastest = None
    if len(row['planned']) > 1:
        bound = time_bound(row['planned'], row['start'][2], yaw, robot['speed'],
                           robot['turn_rate'])
        fastest = fastest_time(row['planned'], row['start'][2], yaw, robot['speed'],
                               robot['turn_rate'], robot['accel'], robot['angular_accel'])
    span = row.get('span') or ((truth[0, 0], truth[-1, 0]) if len(truth) > 1 else (0.0, 0.0))
    return {'time': float(span[1] - span[0]),
            'bound': bound, 'fastest': fastest, 'planned': path_length(row['planned']),
            'driven': path_length(truth[:, 1:3]),
            'error': math.hypot(end[1] - x, end[2] - y),
            'yaw_error': abs(wrap_angle(end[3] - yaw)),
            'clearance': float(footprint_clearance(truth[::5, 1:], robot['footprint'],
                                                   sections).min()) if len(truth) else math.inf,
            'budget': time_budget(truth, robot['speed'], span)}


def format_table(rows, route, sections, robot):
    """
    Return ``(text, ok)``: the route line and one row per goal; ok when all succeeded untouched.

    The last lines count the goals reached, those whose ground truth ended within Nav2's
    default tolerances, and those reached within their time bound
    (:func:`amr_description.nav.trials.time_bound`), with the times' sum against the bounds',
    the least time a base within the params file's limits could have taken for the same goals
    (:func:`amr_description.nav.trials.fastest_time`), and say where the goals' time went
    (:func:`amr_description.nav.trials.time_budget`).

    :param rows: :func:`goal_figures`' rows.
    :param route: the mapping route's ground truth [(t, x, y, yaw)].
    :param sections: the world's shapes.
    :param robot: :func:`robot_params`.
    """
    from amr_description.nav.trials import footprint_clearance
    from amr_description.nav.trials import path_length
    truth = np.asarray(route, dtype=float).reshape(-1, 4)
    route_gap = float(footprint_clearance(truth[::5, 1:], robot['footprint'], sections).min())
    lines = [f'mapping route: {path_length(truth[:, 1:3]):.2f} m driven in '
             f'{truth[-1, 0] - truth[0, 0]:.1f} s of sim time, closest approach to the world '
             f'{route_gap:.3f} m', '',
             '  #  goal x     y   yaw  result      time   bound  planned  driven   error  '
             'yaw err  closest',
             '        m     m   rad               s       s        m       m       m      '
             'deg        m']
    ok = route_gap > 0.0
    reached = within = timely = 0
    times = bounds = fastest = 0.0
    budget = dict.fromkeys(('turning', 'at_speed', 'slower', 'standing'), 0.0)
    for i, row in enumerate(rows, 1):
        f = goal_figures(row, sections, robot)
        budget = {key: budget[key] + f['budget'][key] for key in budget}
        x, y, yaw = row['goal']
        bound = '-' if f['bound'] is None else f"{f['bound']:.1f}"
        lines.append(f"{i:3d} {x:6.2f} {y:5.2f} {yaw:5.2f}  {row['result']:<10} "
                     f"{f['time']:6.1f} {bound:>7} {f['planned']:8.2f} {f['driven']:7.2f} "
                     f"{f['error']:7.3f} {math.degrees(f['yaw_error']):8.1f} "
                     f"{f['clearance']:8.3f}")
        succeeded = row['result'] == 'SUCCEEDED'
        reached += succeeded
        within += succeeded and f['error'] <= 0.25 and f['yaw_error'] <= 0.25
        if succeeded and f['bound'] is not None:
            timely += f['time'] <= f['bound']
            times, bounds = times + f['time'], bounds + f['bound']
            fastest += f['fastest']
        ok = ok and succeeded and f['clearance'] > 0.0
    lines += ['', f'{reached} of {len(rows)} goals SUCCEEDED; the ground truth ended within '
              f"Nav2's default tolerances (0.25 m, 0.25 rad) at {within}"]
    if bounds > 0.0:
        lines.append(f'time to goal within its bound (1.5 x (planned length / '
                     f'desired_linear_vel + in-place turns / rotate_to_heading_angular_vel)) '
                     f"at {timely}; {times:.1f} s against the bounds' {bounds:.1f} s "
                     f'({times / bounds:.2f})')
        lines.append(f'the fastest a base within these limits could reach them (in-place turns '
                     f'and planned length, each from rest to rest within desired_linear_vel, '
                     f"rotate_to_heading_angular_vel and velocity_smoother's max_accel): "
                     f'{fastest:.1f} s; the goals took {times / fastest:.2f} x that, the bounds '
                     f'allow {bounds / fastest:.2f} x')
    if rows:
        lines.append(f"where the goals' time went (ground truth): {budget['turning']:.1f} s "
                     f"turning in place, {budget['at_speed']:.1f} s at "
                     f"{0.8 * robot['speed']:.2f} m/s or more (80 % of desired_linear_vel), "
                     f"{budget['slower']:.1f} s slower, {budget['standing']:.1f} s standing")
    return '\n'.join(lines), ok


def _map_image(ax, grid, cmap='gray_r', alpha=1.0):
    """Draw an occupancy grid (unknown grey, free white, occupied black) in map coordinates."""
    data = grid.data.astype(float)
    shown = np.where(data < 0, 0.35, data / 100.0)
    ox, oy, _ = grid.origin
    extent = (ox, ox + grid.width * grid.resolution, oy, oy + grid.height * grid.resolution)
    ax.imshow(shown, origin='lower', extent=extent, cmap=cmap, vmin=0.0, vmax=1.0,
              alpha=alpha, interpolation='nearest')


def write_map_png(path, saved, true_map, route, waypoints):
    """
    Draw the SLAM map with the world's true obstacles over it and the route driven.

    :param path: output PNG.
    :param saved: the saved map (GridMap).
    :param true_map: the world's true map (GridMap, :func:`amr_description.nav.world_map`).
    :param route: the route's ground truth [(t, x, y, yaw)].
    :param waypoints: the route's waypoints [(x, y, yaw)].
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(9, 8), dpi=100)
    _map_image(ax, saved)
    truth = np.ma.masked_where(true_map.data < 50, np.ones(true_map.data.shape))
    ox, oy, _ = true_map.origin
    ax.imshow(truth, origin='lower', cmap='autumn', alpha=0.35, interpolation='nearest',
              extent=(ox, ox + true_map.width * true_map.resolution, oy,
                      oy + true_map.height * true_map.resolution))
    xy = np.asarray(route, dtype=float).reshape(-1, 4)[:, 1:3]
    ax.plot(xy[:, 0], xy[:, 1], color='tab:blue', linewidth=1.2, label='route driven')
    w = np.asarray(waypoints, dtype=float)
    ax.plot(w[:, 0], w[:, 1], 'o', color='tab:blue', markersize=5, label='waypoints')
    ax.plot([], [], 's', color='red', alpha=0.5, label='true obstacles (world shapes)')
    ax.set_title('SLAM map (black: occupied, grey: unknown) over the true world')
    ax.set_xlabel('x [m] (map = world)')
    ax.set_ylabel('y [m]')
    ax.legend(loc='upper left', bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def write_navigation_png(path, saved, rows):
    """
    Draw each goal's planned (dashed) and driven (ground truth) paths on the saved map.

    :param path: output PNG.
    :param saved: the saved map (GridMap).
    :param rows: the goal rows (``goal``, ``planned``, ``truth``, ``result``).
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(9, 8), dpi=100)
    _map_image(ax, saved)
    colours = plt.get_cmap('tab10')
    for i, row in enumerate(rows, 1):
        colour = colours((i - 1) % 10)
        plan = np.asarray(row['planned'], dtype=float).reshape(-1, 2)
        truth = np.asarray(row['truth'], dtype=float).reshape(-1, 4)
        if len(plan):
            ax.plot(plan[:, 0], plan[:, 1], '--', color=colour, linewidth=1.0)
        if len(truth):
            ax.plot(truth[:, 1], truth[:, 2], '-', color=colour, linewidth=1.5)
        x, y, yaw = row['goal']
        ax.annotate('', (x + 0.35 * math.cos(yaw), y + 0.35 * math.sin(yaw)), (x, y),
                    arrowprops={'arrowstyle': '->', 'color': colour})
        marker = 'o' if row['result'] == 'SUCCEEDED' else 'x'
        ax.plot([x], [y], marker, color=colour, markersize=7)
        ax.annotate(str(i), (x, y), textcoords='offset points', xytext=(5, 5), fontsize=9,
                    color=colour)
    ax.plot([], [], '--', color='0.3', label='planned (getPath)')
    ax.plot([], [], '-', color='0.3', label='driven (ground truth)')
    ax.set_title(f'{len(rows)} goals: planned and driven paths on the saved map')
    ax.set_xlabel('x [m] (map)')
    ax.set_ylabel('y [m]')
    ax.legend(loc='upper left', bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
