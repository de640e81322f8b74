# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
AMCL replayed from a bag against its ground truth: the same scans, other parameters.

Reads a rosbag2 (MCAP or SQLite, with rosbags) holding the lidar's ``sensor_msgs/LaserScan``,
the wheel odometry and the simulator's ground truth (both ``nav_msgs/Odometry``), and runs
:class:`~amr_description.nav.amcl.Amcl` over the scans in this process (no ROS): each scan at
the odometry pose interpolated at its stamp, the filter started at the ground truth of the
first scan (``--start offset``: an ``/initialpose`` ``--offset`` from it with RViz's
covariance, as test/integration/test_localization.py sends; ``--start global``:
``reinitialize_global_localization``). For each parameter set and seed it prints the position
and heading error of the filter's pose after every update, against the ground truth at the
scan's stamp (median, 90th percentile, maximum), and the distance driven from which every
later update was within 5 cm and 3 deg (issue 30's target); with ``/amcl_pose`` in the bag,
the live node's error too. A bag of
``navigate_job`` holds two runs of the clock (mapping, then the goals); only the last is used.

The parameters are those of the ``amcl`` section of a Nav2 params file (config/nav2_params.yaml
by default), each ``--set name=value`` replacing one; several ``--set`` groups are separated
by ``--vs``. The lidar must sit at the base frame's origin in the plane (urdf/amr.urdf.xacro),
or its offset given with ``--sensor x,y,yaw``.

Usage: ``python -m amr_description.tools.benchmark.amcl_replay BAG MAP_YAML [--set
sigma_hit=0.1 --vs --set alpha1=0.4]``.
"""

import argparse
import math
import sys

import numpy as np

RVIZ_COVARIANCE = (0.25, 0.25, 0.06853891945200942)
"""Variances (m^2, m^2, rad^2) of x, y and yaw in RViz's "2D Pose Estimate" message."""


def interpolate_pose(track, t):
    """
    Return the planar pose of a track at time ``t``, linear in x, y and the shorter yaw arc.

    :param track: ``(n, 4)`` rows ``t, x, y, yaw`` (s, m, m, rad), times increasing.
    :param t: s.
    :returns: ``(3,)`` array ``x, y, yaw``, or None outside the track's times.
    """
    i = int(np.searchsorted(track[:, 0], t))
    if i < len(track) and track[i, 0] == t:
        return track[i, 1:4].copy()
    if i <= 0 or i >= len(track):
        return None
    a, b = track[i - 1], track[i]
    f = (t - a[0]) / (b[0] - a[0])
    turn = math.atan2(math.sin(b[3] - a[3]), math.cos(b[3] - a[3]))
    return np.array([a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]),
                     math.atan2(math.sin(a[3] + f * turn), math.cos(a[3] + f * turn))])


def pose_error(estimate, truth):
    """Return ``(distance, |heading error|)`` (m, rad) between two ``x, y, yaw`` poses."""
    d = estimate[2] - truth[2]
    return (math.hypot(estimate[0] - truth[0], estimate[1] - truth[1]),
            abs(math.atan2(math.sin(d), math.cos(d))))


def last_clock_run(stamps):
    """Return the index where the last run of a clock starts (a step back of over 5 s)."""
    stamps = np.asarray(stamps, dtype=float)
    back = np.nonzero(np.diff(stamps) < -5.0)[0]
    return int(back[-1] + 1) if len(back) else 0


def summary(errors):
    """Return the one-line summary of ``(n, 2)`` errors (m, rad)."""
    e = np.asarray(errors, dtype=float).reshape(-1, 2)
    if not len(e):
        return 'no update'
    d, a = e[:, 0] * 100.0, np.degrees(e[:, 1])
    return (f'{len(e)} updates: {np.median(d):.1f} cm median, {np.percentile(d, 90):.1f} cm '
            f'90th percentile, {d.max():.1f} cm max; heading {np.median(a):.2f} deg median, '
            f'{a.max():.1f} deg max')


def read_bag(path, scan_topic, odom_topic, truth_topic, amcl_topic):
    """
    Return the scans, odometry, ground truth and AMCL poses of a bag's last clock run.

    :returns: ``(scans, odom, truth, amcl)``: scans a list of ``(t, ranges, angle_min,
        angle_increment, range_min, range_max)``; the others ``(n, 4)`` tracks
        ``t, x, y, yaw``.
    :raises ValueError: a topic missing from the bag.
    """
    from pathlib import Path
    from amr_description.ros.transforms import stamp_seconds
    from amr_description.ros.transforms import yaw_of
    from rosbags.highlevel import AnyReader
    topics = (scan_topic, odom_topic, truth_topic, amcl_topic)
    rows = {t: [] for t in topics}
    with AnyReader([Path(path)]) as reader:
        present = {c.topic for c in reader.connections}
        for topic in topics[:3]:
            if topic not in present:
                raise ValueError(f'{path}: no topic {topic} (topics: {sorted(present)})')
        connections = [c for c in reader.connections if c.topic in topics]
        for connection, _, raw in reader.messages(connections=connections):
            msg = reader.deserialize(raw, connection.msgtype)
            if connection.topic == scan_topic:
                rows[scan_topic].append((stamp_seconds(msg.header.stamp),
                                         np.asarray(msg.ranges, dtype=float), msg.angle_min,
                                         msg.angle_increment, msg.range_min, msg.range_max))
            else:
                pose = msg.pose.pose
                rows[connection.topic].append((stamp_seconds(msg.header.stamp), pose.position.x,
                                               pose.position.y, yaw_of(pose.orientation)))
    scans = rows[scan_topic][last_clock_run([s[0] for s in rows[scan_topic]]):]
    tracks = []
    for topic in topics[1:]:
        track = np.array(rows[topic], dtype=float).reshape(-1, 4)
        track = track[last_clock_run(track[:, 0]):]
        tracks.append(track[np.argsort(track[:, 0], kind='stable')])
    return (scans, *tracks)


def replay(scans, odom, truth, grid, params, sensor=(0.0, 0.0, 0.0), seed=1,
           initial_sigma=(0.1, 0.1, 0.05), start='truth', offset=(0.0, 0.0, 0.0)):
    """
    Run the filter over the scans; return the errors and the distance driven at each update.

    :param grid: the map (:class:`~amr_description.nav.map_io.GridMap`).
    :param params: :class:`~amr_description.nav.amcl.AmclParameters`.
    :param sensor: the lidar's ``x, y, yaw`` in the base frame.
    :param initial_sigma: standard deviations (m, m, rad) round the first ground truth
        (``start`` 'truth').
    :param start: 'truth' (round the first ground truth), 'offset' (an ``/initialpose``
        ``offset`` from it, in the map frame, with RViz's "2D Pose Estimate" covariance,
        :data:`RVIZ_COVARIANCE`) or 'global' (``reinitialize_global_localization``).
    :param offset: ``dx, dy, dyaw`` (m, m, rad) for ``start`` 'offset'.
    :returns: ``(errors, driven)``: ``(n, 2)`` m, rad after each update, and ``(n,)`` the
        ground truth's path length (m) from the first scan to that update.
    :raises ValueError: an unknown ``start``.
    """
    from amr_description.nav.amcl import Amcl
    if start not in ('truth', 'offset', 'global'):
        raise ValueError(f'start: expected truth, offset or global, found {start!r}')
    amcl = Amcl(params, seed=seed)
    amcl.set_map(grid)
    errors, driven = [], []
    path, previous = 0.0, None
    for t, ranges, angle_min, increment, range_min, range_max in scans:
        at_odom, at_truth = interpolate_pose(odom, t), interpolate_pose(truth, t)
        if at_odom is None or at_truth is None:
            continue
        if previous is not None:
            path += math.hypot(*(at_truth[:2] - previous[:2]))
        previous = at_truth
        if not amcl.initialized:
            if start == 'global':
                amcl.global_localization()
            elif start == 'offset':
                amcl.set_initial_pose(at_truth + np.asarray(offset, dtype=float),
                                      np.diag(RVIZ_COVARIANCE))
            else:
                amcl.set_initial_pose(at_truth, np.diag(np.square(initial_sigma)))
        beams, limit = amcl.beams(ranges, angle_min, increment, range_min, range_max, sensor)
        if amcl.process(at_odom, beams, limit):
            errors.append(pose_error(amcl.pose, at_truth))
            driven.append(path)
    return np.array(errors, dtype=float).reshape(-1, 2), np.array(driven, dtype=float)


def settled_after(errors, driven, distance=0.05, heading=math.radians(3.0)):
    """
    Return the distance driven from which every later update is within the bounds.

    :param errors: ``(n, 2)`` m, rad, as :func:`replay` returns.
    :param driven: ``(n,)`` m.
    :param distance: m.
    :param heading: rad.
    :returns: m, or None when the last update is outside the bounds (or there is none).
    """
    e = np.asarray(errors, dtype=float).reshape(-1, 2)
    outside = np.nonzero((e[:, 0] > distance) | (e[:, 1] > heading))[0]
    if not len(e) or (len(outside) and outside[-1] == len(e) - 1):
        return None
    return float(driven[outside[-1] + 1]) if len(outside) else float(driven[0])


def params_from_file(path, overrides):
    """
    Return AmclParameters from a Nav2 params file's ``amcl`` section and ``name=value`` texts.

    :raises ValueError: an override that is not ``name=value`` with a known name and, for a
        numeric parameter, a number.
    """
    import dataclasses
    import yaml
    from amr_description.nav.amcl import AmclParameters
    from amr_description.tools.benchmark.common import parameter_overrides
    with open(path, encoding='utf-8') as f:
        section = ((yaml.safe_load(f) or {}).get('amcl') or {}).get('ros__parameters') or {}
    kinds = {f.name: type(f.default) for f in dataclasses.fields(AmclParameters)}
    values = {k: v for k, v in section.items() if k in kinds}
    values.update(parameter_overrides(AmclParameters, overrides))
    return AmclParameters(**{k: kinds[k](v) for k, v in values.items()})


def main(argv=None):
    """Print the errors of each parameter set; return 0, or 1 with a one-line error."""
    parser = argparse.ArgumentParser(prog='amcl_replay', description=__doc__.split('\n\n')[0])
    parser.add_argument('bag')
    parser.add_argument('map', help='the map YAML AMCL ran on')
    parser.add_argument('--params-file', default='config/nav2_params.yaml')
    parser.add_argument('--scan', default='/scan')
    parser.add_argument('--odom', default='/odom')
    parser.add_argument('--truth', default='/ground_truth/odom')
    parser.add_argument('--amcl', default='/amcl_pose')
    parser.add_argument('--sensor', default='0,0,0', help='x,y,yaw of the lidar (m, rad)')
    parser.add_argument('--seeds', default='1,2')
    parser.add_argument('--set', action='append', default=[], dest='sets',
                        help='name=value over the params file (repeatable)')
    parser.add_argument('--vs', action='append_const', const='--vs', dest='sets',
                        help='start another parameter set')
    parser.add_argument('--start', default='truth', choices=('truth', 'offset', 'global'),
                        help='round the first ground truth, an /initialpose --offset from '
                        'it, or global localization')
    parser.add_argument('--offset', default='0.4,-0.3,0.349',
                        help='dx,dy,dyaw of the initial pose for --start offset (m, rad)')
    opts = parser.parse_args(argv)
    try:
        from amr_description.nav import map_io
        sensor = tuple(float(v) for v in opts.sensor.split(','))
        offset = tuple(float(v) for v in opts.offset.split(','))
        seeds = [int(v) for v in opts.seeds.split(',')]
        groups = [[]]
        for item in opts.sets:
            groups.append([]) if item == '--vs' else groups[-1].append(item)
        sets = [(g, params_from_file(opts.params_file, g)) for g in groups]
        grid, _ = map_io.load_map(opts.map)
        scans, odom, truth, live = read_bag(opts.bag, opts.scan, opts.odom, opts.truth,
                                            opts.amcl)
    except (OSError, ValueError) as exc:
        print(f'amcl_replay: {exc}', file=sys.stderr)
        return 1
    print(f'{len(scans)} scans, {scans[0][0]:.1f}-{scans[-1][0]:.1f} s of sim time'
          if scans else '0 scans')
    if len(live):
        errors = [pose_error(row[1:], g) for row in live
                  if (g := interpolate_pose(truth, row[0])) is not None]
        print(f'live {opts.amcl}: {summary(errors)}')
    for group, params in sets:
        for seed in seeds:
            errors, driven = replay(scans, odom, truth, grid, params, sensor, seed,
                                    start=opts.start, offset=offset)
            since = settled_after(errors, driven)
            settled = ('not within 5 cm and 3 deg at the end' if since is None else
                       f'within 5 cm and 3 deg from {since:.2f} m of driving on')
            print(f"{' '.join(group) or 'params file'} (seed {seed}): {summary(errors)}; "
                  f'{settled}', flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
