# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""What the main job reports: leg and robot tables, closures, dropped commands, plots."""

import math
import os
import sys

from amr_description.core.course import closure_error
from amr_description.core.course import format_leg_table
from amr_description.core.course import leg_delta
from amr_description.nodes.drive_square.driver import CMD_VEL_TIMEOUT
from amr_description.nodes.drive_square.driver import STALE_LOG_LINE


def _relative_path(points, origin):
    """Express planar points in the frame of ``origin`` = ``(x, y, yaw)``."""
    c, s = math.cos(origin[2]), math.sin(origin[2])
    return [((x - origin[0]) * c + (y - origin[1]) * s,
             -(x - origin[0]) * s + (y - origin[1]) * c) for x, y in points]


def _to_world(points, origin):
    """Map planar points given in the frame of ``origin`` = ``(x, y, yaw)`` to its parent."""
    c, s = math.cos(origin[2]), math.sin(origin[2])
    return [(origin[0] + x * c - y * s, origin[1] + x * s + y * c) for x, y in points]


def write_fleet_plot(path, robots, side):
    """
    Plot every robot's odometry and ground-truth paths to a PNG.

    One robot is drawn in its start frame (the commanded square from the origin); several
    are drawn in the simulator's ``world`` frame, each odometry path placed at its robot's
    ground-truth start pose, with each robot's commanded square.

    :param path: output PNG path.
    :param robots: list of dicts with ``name``, ``odom_path``, ``truth_path`` (lists of
        ``(x, y)`` in m, odom and world frames), ``odom_origin`` and ``truth_origin``
        (``(x, y, yaw)`` of the course start in each frame).
    :param side: commanded side length in m.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    single = len(robots) == 1
    fig, ax = plt.subplots(figsize=(7, 7), dpi=100)
    square = [(0, 0), (side, 0), (side, side), (0, side), (0, 0)]
    for i, robot in enumerate(robots):
        first = i == 0
        start = (0.0, 0.0, 0.0) if single else robot['truth_origin']
        corners = _to_world(square, start)
        ax.plot([p[0] for p in corners], [p[1] for p in corners], color='0.7',
                linestyle='--', label='commanded square' if first else None)
        odom = _to_world(_relative_path(robot['odom_path'], robot['odom_origin']), start)
        truth = _to_world(_relative_path(robot['truth_path'], robot['truth_origin']), start)
        if truth:
            ax.plot([p[0] for p in truth], [p[1] for p in truth], color='tab:blue',
                    label='ground truth' if first else None)
        if odom:
            ax.plot([p[0] for p in odom], [p[1] for p in odom], color='tab:red',
                    linewidth=0.8, label='odometry' if first else None)
        if not single:
            ax.annotate(robot['name'], (start[0], start[1]), textcoords='offset points',
                        xytext=(-14, -14), fontsize=9)
    ax.set_aspect('equal')
    if single:
        ax.set_xlabel('x [m] (start frame)')
        ax.set_ylabel('y [m] (start frame)')
        ax.set_title(f'amr: {side:g} m square, odometry vs ground truth')
        ax.legend(loc='center')
    else:
        ax.set_xlabel('x [m] (world)')
        ax.set_ylabel('y [m] (world)')
        ax.set_title(f'{len(robots)} robots: {side:g} m squares, odometry vs ground truth')
        ax.legend(loc='upper left', bbox_to_anchor=(1.0, 1.0))
        fig.tight_layout()
    ax.grid(True, alpha=0.3)
    fig.savefig(path)
    plt.close(fig)


def format_robot_table(legs, robots):
    """
    Format one row per robot (closures) and a per-leg summary over the robots.

    :param legs: the :class:`~amr_description.core.course.Leg` list every robot drove.
    :param robots: list of ``(name, odom_marks, truth_marks, stale)``: the poses at the start
        and at the end of each leg (``len(legs) + 1`` each) and the dropped command count.
    :returns: the two tables as one str (m and deg).
    """
    header = (f"{'robot':<6}  {'odom closure':>12}  {'odom hdg':>8}  {'true closure':>12}  "
              f"{'true hdg':>8}  {'dropped':>7}")
    lines = [header, '-' * len(header)]
    for name, odom, truth, stale in robots:
        od, oh = closure_error(odom)
        td, th = closure_error(truth)
        lines.append(f'{name:<6}  {od:>10.3f} m  {math.degrees(oh):>6.2f} d  '
                     f'{td:>10.3f} m  {math.degrees(th):>6.2f} d  {stale:>7}')
    lines.append('')
    header = (f"{'leg':>3}  {'kind':<8}  {'cmd':>7}  {'true min':>8}  {'true mean':>9}  "
              f"{'true max':>8}  {'|odom - true| max':>17}")
    lines += [header, '-' * len(header)]
    for i, leg in enumerate(legs):
        straight = leg.kind == 'straight'
        values, gaps = [], []
        for _, odom, truth, _ in robots:
            o = leg_delta(odom[i], odom[i + 1])[0 if straight else 1]
            t = leg_delta(truth[i], truth[i + 1])[0 if straight else 1]
            values.append(t if straight else math.degrees(t))
            gaps.append(abs(o - t) if straight else abs(math.degrees(o - t)))
        unit = 'm' if straight else 'd'
        cmd = leg.target if straight else math.degrees(leg.target)
        fmt = '.3f' if straight else '.1f'
        lines.append(f'{i + 1:>3}  {leg.kind:<8}  {cmd:>5{fmt}} {unit}  '
                     f'{min(values):>6{fmt}} {unit}  {sum(values) / len(values):>7{fmt}} {unit}'
                     f'  {max(values):>6{fmt}} {unit}  {max(gaps):>15{fmt}} {unit}')
    return '\n'.join(lines)


def count_stale_lines(log_path):
    """Return how many commands diff_drive_controller logged as dropped in ``log_path``."""
    try:
        with open(log_path, 'r', errors='replace') as f:
            return sum(1 for line in f if STALE_LOG_LINE in line)
    except OSError:
        return 0


def fail(message):
    print(f'[drive_square] error: {message}', file=sys.stderr, flush=True)
    return 1


def scan_report(opts, robot, scans):
    """
    Write ``out/scans.png`` and return ``(line, ground-truth share)``, or None without scans.

    :param opts: the options (``world``, ``output_dir``).
    :param robot: the :class:`~amr_description.nodes.drive_square.driver.RobotDriver`.
    :param scans: the :class:`~amr_description.nodes.drive_square.scans.ScanRecorder`.
    """
    from amr_description.core.scan_map import compose
    from amr_description.core.scan_map import inverse
    from amr_description.core.scan_map import world_sections
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.launch.stacks import read_urdf
    from amr_description.nodes.drive_square.scans import lidar_mount
    from amr_description.nodes.drive_square.scans import MARGIN
    from amr_description.nodes.drive_square.scans import on_surface_share
    from amr_description.nodes.drive_square.scans import write_scan_map

    mount = lidar_mount(read_urdf())
    if mount is None or not scans.scans:
        return None
    block, offset, height = mount
    sections = world_sections(load_world(opts.world), height)
    if not sections:
        return None
    stddev = block.lidar.noise.stddev
    to_world = compose(robot.truth_marks[0], inverse(robot.odom_marks[0]))
    truth = scans.placed(scans.truth, offset)
    odom = scans.placed(scans.odom, offset, to_world)
    shares = on_surface_share(truth, sections, stddev), on_surface_share(odom, sections, stddev)
    path = os.path.join(opts.output_dir, 'scans.png')
    write_scan_map(path, sections, [('ground truth', truth, shares[0], 'tab:blue'),
                                    ('/odom', odom, shares[1], 'tab:red')],
                   f'{opts.world}: {len(scans.scans)} scans of the drive, lidar '
                   f'{height:.2f} m above the ground')
    line = (f'scan points within 3 stddev + {100 * MARGIN:g} cm of a true surface: ground '
            f'truth {100 * shares[0]:.1f} % ({len(truth)} points), /odom '
            f'{100 * shares[1]:.1f} % ({len(odom)} points); wrote {path}')
    return line, shares[0]


def report(opts, node, legs, log_path, scans=None):
    """Print the tables, check drops and closures, write the PNGs; return the exit code."""
    robots = node.robots
    print()
    if len(robots) == 1:
        robot = robots[0]
        print(format_leg_table(legs, robot.odom_marks, robot.truth_marks))
        odom_err = closure_error(robot.odom_marks)
        truth_err = closure_error(robot.truth_marks)
        print()
        print(f'closure (end vs start): /odom {odom_err[0]:.3f} m, '
              f'{math.degrees(odom_err[1]):.1f} deg; ground truth {truth_err[0]:.3f} m, '
              f'{math.degrees(truth_err[1]):.1f} deg')
    else:
        print(format_robot_table(legs, [(r.name, r.odom_marks, r.truth_marks, r.stale)
                                        for r in robots]))
    print()
    plot = os.path.join(opts.output_dir, 'path.png')
    write_fleet_plot(plot, [{'name': r.name, 'odom_path': r.odom_path,
                             'truth_path': r.truth_path, 'odom_origin': r.odom_marks[0],
                             'truth_origin': r.truth_marks[0]} for r in robots], opts.side)
    written = [plot]
    scene = os.path.join(opts.output_dir, 'scene.png')
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.launch.stacks import read_urdf
    from amr_description.sim.render import render_scene
    from amr_description.sim.render import save_png
    save_png(render_scene(read_urdf(), robots[0].truth_marks[-1], robots[0].truth_path,
                          others=[(r.truth_marks[-1], r.truth_path) for r in robots[1:]],
                          world=load_world(opts.world)), scene)
    written.append(scene)
    print(f'wrote {" and ".join(written)}')
    mapped = scan_report(opts, robots[0], scans) if scans is not None else None
    if mapped is not None:
        print(mapped[0])
        if mapped[1] < 0.95:
            return fail(f'only {100 * mapped[1]:.1f} % of the scan points placed with ground '
                        'truth lie on a true surface (95 % expected)')
    dropped = sum(r.stale for r in robots)
    logged = count_stale_lines(log_path) if log_path else 0
    if dropped or logged:
        return fail(f'{max(dropped, logged)} command(s) dropped as older than cmd_vel_timeout '
                    f'({CMD_VEL_TIMEOUT:g} s of sim time): the driver fell behind the '
                    'simulation (try --rtf 0, the lock-step mode)')
    missed = []
    for r in robots:
        distance, heading = closure_error(r.truth_marks)
        if distance > opts.tolerance or math.degrees(heading) > opts.tolerance_deg:
            missed.append(f'{r.name} {distance:.3f} m {math.degrees(heading):.2f} deg')
    if missed:
        return fail(f'ground-truth closure beyond {opts.tolerance:g} m / '
                    f'{opts.tolerance_deg:g} deg: {", ".join(missed)}')
    return 0
