# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
SLAM against ground truth when odometry is wrong: pose error, map accuracy, wall coverage.

In this process (no ROS): our robot (urdf/amr.urdf.xacro, its 2-D lidar with its noise) is
moved along a scripted closed route in a shipped world (``arena``: three laps of an 8.8 m
loop round the pillars, 26.4 m; ``warehouse``: out along the first aisle, a 15.8 m loop
through two aisles and back, 21.7 m; ``warehouse-aisles``: the route of ``./scripts/main
--navigate`` through the aisles between the rows of identical shelves, then back through two of
them, 37.3 m, where a loop match one aisle over fits as well as the right one) at 0.5 m/s,
turning in place at 0.8 rad/s at corners;
the lidar is cast by MuJoCo at 10 Hz at the true pose. The odometry is diff_drive_controller's
(``ros2_controllers/diff_drive_controller/src/odometry.cpp``) from the true wheel motion with
``wheel_radius`` 3 % too large and ``wheel_separation_multiplier`` 10 % low: it sees
``v' = 1.03 v`` and ``w' = (1.03 / 0.9) w``. Every scan goes to
:class:`~amr_description.nav.slam.Mapper` (slam_toolbox's defaults), and then:

pose
    RMS over every scan of the distance (m) and yaw difference (deg) between SLAM's pose of
    ``base_footprint`` in ``map`` and the truth (the map frame is the start pose, as the
    truth's reference); odometry's end error beside it. Target <= 0.05 m, <= 2 deg.
map accuracy
    the share of the final map's occupied cells whose centre lies within 1.5 cells of a true
    surface (the world's collision shapes cut at the lidar's height,
    :func:`~amr_description.core.scan_map.world_sections`). Target >= 95 %.
wall coverage
    the share of the true surface points the lidar saw (every return, placed at the true
    pose, noise-free) that have an occupied map cell within 1.5 cells. Target >= 90 %.

Usage: ``python -m amr_description.tools.benchmark.slam_accuracy [--world arena] [--set
name=value]`` (``--set`` replaces one of slam_toolbox's defaults); prints one line per route,
and returns 1 when a target is missed.
"""

import argparse
import math
import sys
import time

import numpy as np

RADIUS_ERROR = 1.03
SEPARATION_ERROR = 0.9
SPEED, TURN_RATE, SCAN_RATE = 0.5, 0.8, 10.0
LIDAR_HEIGHT = 0.25

ROUTES = {
    'arena': ([(-0.65, -0.55), (2.65, -0.55), (2.65, 0.55), (-0.65, 0.55)] * 3
              + [(-0.65, -0.55)]),
    'warehouse': [(-2.0, 0.0), (0.95, 0.0), (4.85, 0.0), (4.85, 4.0), (0.95, 4.0),
                  (0.95, 0.0), (-2.0, 0.0)],
    'warehouse-aisles': [(0.0, 0.0), (4.85, 0.0), (4.85, 2.0), (0.95, 2.0), (0.95, 4.0),
                         (4.85, 4.0), (4.85, 6.0), (0.95, 6.0), (0.95, 4.0), (4.85, 4.0),
                         (4.85, 0.0), (0.0, 0.0)],
}
"""Waypoints (x, y) in the world frame; the robot starts at the first facing the second."""


def world_of(route):
    """Return the shipped world a route of :data:`ROUTES` runs in (warehouse-aisles: warehouse)."""
    return route.split('-')[0]


def trajectory(waypoints):
    """
    Return the true poses (M, 3) and body twists (M, 2) at :data:`SCAN_RATE` along a route.

    Straight legs at :data:`SPEED` or just below, turns in place at :data:`TURN_RATE` or just
    below (the shorter way), each leg a whole number of scan periods.
    """
    dt = 1.0 / SCAN_RATE
    x, y = waypoints[0]
    yaw = math.atan2(waypoints[1][1] - y, waypoints[1][0] - x)
    poses, twists = [(x, y, yaw)], [(0.0, 0.0)]
    for (ax, ay), (bx, by) in zip(waypoints, waypoints[1:]):
        heading = math.atan2(by - ay, bx - ax)
        turn = math.atan2(math.sin(heading - yaw), math.cos(heading - yaw))
        steps = int(math.ceil(abs(turn) / (TURN_RATE * dt)))
        for _ in range(steps):
            yaw += turn / steps
            poses.append((x, y, yaw))
            twists.append((0.0, turn / steps / dt))
        yaw = heading
        length = math.hypot(bx - ax, by - ay)
        steps = int(length / (SPEED * dt))
        for k in range(1, steps + 1):
            f = k / steps
            poses.append((ax + f * (bx - ax), ay + f * (by - ay), yaw))
            twists.append((length / steps / dt, 0.0))
        x, y = bx, by
    return np.array(poses), np.array(twists)


def odometry(twists, radius_error=RADIUS_ERROR, separation_error=SEPARATION_ERROR):
    """Return the odometry poses (M, 3) integrated from the twists with the given geometry."""
    dt = 1.0 / SCAN_RATE
    pose = np.zeros(3)
    out = [pose.copy()]
    for v, w in twists[1:]:
        v, w = radius_error * v, radius_error / separation_error * w
        # diff_drive_controller's integrateRungeKutta2: heading at mid-step
        mid = pose[2] + 0.5 * w * dt
        pose = pose + (v * dt * math.cos(mid), v * dt * math.sin(mid), w * dt)
        out.append(pose.copy())
    return np.array(out)


def scans(world_name, poses):
    """Return the lidar's ranges at each true pose, the Scan template and the sensor pose."""
    import mujoco
    from amr_description.core.description.files import read_description
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.launch.stacks import urdf_path
    from amr_description.sim.simulation import Simulation
    sim = Simulation(real_time_factor=0.0, world=load_world(world_name),
                     sensor_settings={'publish_ground_truth': False})
    entity = sim.spawn(read_description(urdf_path(), {}), name='amr',
                       pose=[float(poses[0][0]), float(poses[0][1]), 0.0, 0, 0, 0, 1])
    lidar = next(s for s in entity.sensors if s.name == 'lidar')
    world = sim.world
    qadr, _ = world.free_joint_address('amr')
    site = world.model.site(lidar.cast.site).id
    ranges = []
    for k, (x, y, yaw) in enumerate(poses):
        world.data.qpos[qadr:qadr + 7] = (x, y, 0.0, math.cos(yaw / 2), 0, 0, math.sin(yaw / 2))
        mujoco.mj_kinematics(world.model, world.data)
        world._poses_current = True
        ranges.append(lidar.measure(world, 100.0 + k / SCAN_RATE).ranges.tolist())
        if k == 0:
            body = world.model.body('amr/base_footprint').id
            offset = world.data.site_xpos[site] - world.data.xpos[body]
            sensor = world.data.xmat[body].reshape(3, 3).T @ offset
    msg = lidar.measure(world, 0.0)
    sim.close()
    return np.array(ranges), msg, (float(sensor[0]), float(sensor[1]), 0.0)


def parameters(sets):
    """
    Return slam_toolbox's defaults with ``name=value`` texts applied (``--set``).

    :param sets: list of ``name=value`` texts, each name a field of
        :class:`~amr_description.nav.slam.SlamParameters`.
    :raises ValueError: one line, for an unknown name or a value that is not a number
        (``true``/``false`` for a bool).
    """
    from amr_description.nav.slam import SlamParameters
    from amr_description.tools.benchmark.common import parameter_overrides
    return SlamParameters(**parameter_overrides(SlamParameters, sets))


def run(route, params=None):
    """
    Return the figures of one route (see the module docstring) as a dict.

    :param params: :class:`~amr_description.nav.slam.SlamParameters` (None: the defaults).
    """
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.core.scan_map import surface_distance
    from amr_description.core.scan_map import world_sections
    from amr_description.nav.pose_graph import between
    from amr_description.nav.pose_graph import compose
    from amr_description.nav.slam import Mapper
    from amr_description.nav.slam import Scan
    from amr_description.nav.slam import scan_rays
    world_name = world_of(route)
    truth, twists = trajectory(ROUTES[route])
    odom = odometry(twists)
    ranges, msg, sensor_pose = scans(world_name, truth)
    mapper = Mapper(params)
    start = truth[0]
    errors, cpu = [], time.process_time()
    for k in range(len(truth)):
        scan = Scan(ranges[k], msg.angle_min, msg.angle_increment, msg.range_min,
                    msg.range_max, sensor_pose)
        mapper.process(odom[k], scan, k / SCAN_RATE)
        estimate = mapper.pose(odom[k])
        true_rel = between(start, truth[k])
        diff = between(true_rel, estimate)
        errors.append((math.hypot(diff[0], diff[1]), abs(diff[2])))
    cpu = time.process_time() - cpu
    grid = mapper.occupancy()
    errors = np.array(errors)
    sections = world_sections(load_world(world_name), LIDAR_HEIGHT)
    rows, cols = np.nonzero(grid.data == 100)
    centres = np.stack([grid.origin[0] + (cols + 0.5) * grid.resolution,
                        grid.origin[1] + (rows + 0.5) * grid.resolution], axis=1)
    world_centres = np.array([compose(start, c)[:2] for c in
                              np.hstack([centres, np.zeros((len(centres), 1))])])
    accurate = float(np.mean(surface_distance(world_centres, sections)
                             <= 1.5 * grid.resolution))
    seen = []
    for k in range(0, len(truth), 5):
        scan = Scan(ranges[k], msg.angle_min, msg.angle_increment, msg.range_min,
                    msg.range_max, sensor_pose)
        _, ends, hits = scan_rays(scan, 25.0)
        pts = np.array([compose(truth[k], (p[0], p[1], 0.0))[:2] for p in ends[hits]])
        if len(pts):
            seen.append(pts[surface_distance(pts, sections) < 0.05])
    seen = np.vstack(seen)
    occupied = set(zip(cols.tolist(), rows.tolist()))
    local = np.array([between(start, (p[0], p[1], 0.0))[:2] for p in seen])
    cells = np.floor((local - grid.origin[:2]) / grid.resolution).astype(int)
    covered = np.mean([any((cx + i, cy + j) in occupied for i in (-1, 0, 1) for j in (-1, 0, 1))
                       for cx, cy in cells])
    odom_end = between(between(start, truth[-1]), odom[-1])
    return {'distance': float(np.sum(np.hypot(*np.diff(truth[:, :2], axis=0).T))),
            'rms_m': float(np.sqrt(np.mean(errors[:, 0] ** 2))),
            'rms_deg': math.degrees(float(np.sqrt(np.mean(errors[:, 1] ** 2)))),
            'max_m': float(errors[:, 0].max()),
            'odom_end_m': float(math.hypot(odom_end[0], odom_end[1])),
            'accurate': accurate, 'coverage': float(covered),
            'keyframes': len(mapper.keyframes), 'loops': mapper.loop_closures,
            'cpu_s': cpu, 'scans': len(truth)}


def main(argv=None):
    """Print one line per route; return 1 when a target is missed, else 0."""
    parser = argparse.ArgumentParser(prog='slam_accuracy', description=__doc__.splitlines()[1])
    parser.add_argument('--world', action='append', choices=sorted(ROUTES),
                        help='route to map, named by its world (repeatable; default: all)')
    parser.add_argument('--set', action='append', default=[], dest='sets',
                        help="name=value over slam_toolbox's defaults (repeatable)")
    opts = parser.parse_args(argv)
    try:
        params = parameters(opts.sets)
    except ValueError as exc:
        parser.error(str(exc))
    missed = False
    for name in opts.world or sorted(ROUTES):
        r = run(name, params)
        ok = (r['rms_m'] <= 0.05 and r['rms_deg'] <= 2.0 and r['accurate'] >= 0.95
              and r['coverage'] >= 0.90)
        missed |= not ok
        print(f"{name}: {r['distance']:.1f} m driven, odometry ends {r['odom_end_m']:.2f} m "
              f"off; SLAM pose RMS {100 * r['rms_m']:.1f} cm (max {100 * r['max_m']:.1f} cm), "
              f"{r['rms_deg']:.2f} deg; map cells on a surface {100 * r['accurate']:.1f} %, "
              f"walls seen in the map {100 * r['coverage']:.1f} %; {r['keyframes']} "
              f"keyframes, {r['loops']} loop closures, {r['cpu_s']:.1f} CPU s for "
              f"{r['scans']} scans ({'met' if ok else 'MISSED'})")
    return 1 if missed else 0


if __name__ == '__main__':
    sys.exit(main())
