# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
End to end: ``./scripts/main --navigate``'s job maps warehouse.sdf, saves the map, navigates.

Runs ``navigate_job --goals 2 --rtf 0`` (the job's default world, route and seed; two goals
instead of ten, in lock-step, to keep the suite's time) without the viewer and checks what a
user sees: the lock-step's report for both phases (the simulator paused and advanced in
ticks), the mapping route's seven waypoints reached, the map saved in Nav2's format (a YAML
beside a trinary PGM, its free and occupied cells where the warehouse's true map has them), a
table row per goal with SUCCEEDED and a closest approach above 0 (no contact), both PNGs, exit
code 0, and every process of both stacks gone afterwards.
"""

import os
import re

from conftest import launched_pids
from conftest import left_running
import numpy as np
import pytest

pytest.importorskip('nav2_msgs.action')

ROUTE = re.compile(r'route SUCCEEDED: (\d+) of (\d+) waypoints')
LOCKSTEP = re.compile(r'real-time factor ([\d.]+)\); lock-step: (\d+) ticks')
ROW = re.compile(r'^\s+(\d+)\s+(-?[\d.]+)\s+(-?[\d.]+)\s+(-?[\d.]+)\s+(\w+)\s+([\d.]+)\s+'
                 r'([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+(-?[\d.]+)$', re.M)


def _occupied_near_truth(saved, truth, reach):
    """Share of ``saved``'s occupied cells within ``reach`` (>= 1) cells of one of ``truth``'s."""
    from scipy import ndimage
    near = ndimage.binary_dilation(np.asarray(truth.data) == 100, iterations=reach)
    cells = np.argwhere(np.asarray(saved.data) == 100)  # (row, col) = (y, x)
    xy = np.asarray(saved.origin[:2]) + (cells[:, ::-1] + 0.5) * saved.resolution
    ij = np.floor((xy - np.asarray(truth.origin[:2])) / truth.resolution).astype(int)[:, ::-1]
    inside = ((ij >= 0) & (ij < near.shape)).all(axis=1)
    hits = near[ij[inside, 0], ij[inside, 1]]
    return float(np.count_nonzero(hits)) / max(len(cells), 1), len(cells)


def test_navigate_job_maps_saves_and_reaches_its_goals(ros_env, procs, exe, tmp_path):
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.nav import map_io
    from amr_description.nav.world_map import world_map
    out = tmp_path / 'out'
    proc = procs.start([exe('navigate_job'), '--goals', '2', '--rtf', '0', '--output-dir',
                        str(out), '--viewer-port', '0'], ros_env)
    assert proc.wait(timeout=1500) == 0, proc.output[-4000:]
    text = proc.output
    # both phases ran in lock-step: over 500 ticks of 0.05 s each (the route alone takes ~90 s)
    phases = LOCKSTEP.findall(text)
    assert len(phases) == 2 and all(int(ticks) > 500 for _, ticks in phases), text[-4000:]

    match = ROUTE.search(text)
    assert match and match.group(1) == match.group(2) == '7', text[-4000:]
    # the map in Nav2's format; its walls where the world's shapes are (within 10 cm: the
    # first run's map 100 %, the same map shifted 0.3 m 82 %)
    saved, meta = map_io.load_map(str(out / 'map.yaml'))
    assert os.path.basename(meta.image) == 'map.pgm' and meta.mode == 'trinary', meta
    assert meta.resolution == pytest.approx(0.05), meta
    assert np.count_nonzero(np.asarray(saved.data) == 0) > 10000
    share, occupied = _occupied_near_truth(saved, world_map(load_world('warehouse')), 2)
    assert occupied > 500 and share > 0.95, (occupied, share)

    rows = ROW.findall(text)
    assert len(rows) == 2, text[-4000:]
    for row in rows:
        assert row[4] == 'SUCCEEDED', row
        assert float(row[11]) > 0.0, row  # closest approach of the footprint to the world
    assert '2 of 2 goals SUCCEEDED' in text, text[-2000:]
    summary = re.search(r'time to goal within its bound .* at (\d); ([\d.]+) s against the '
                        r"bounds' ([\d.]+) s", text)
    assert summary and int(summary[1]) <= 2, text[-2000:]
    assert float(summary[2]) == pytest.approx(sum(float(row[5]) for row in rows), abs=0.15)
    # the ground truth's account of those seconds covers them (a sample interval lost at
    # each end of a goal at most)
    budget = re.search(r"where the goals' time went \(ground truth\): ([\d.]+) s turning in "
                       r'place, ([\d.]+) s at [\d.]+ m/s or more .*, ([\d.]+) s slower, '
                       r'([\d.]+) s standing', text)
    assert budget and sum(map(float, budget.groups())) == pytest.approx(
        float(summary[2]), abs=0.5), text[-2000:]
    # no base within the params file's limits is faster than the yardstick, the real one included
    fastest = re.search(r'could reach them .*: ([\d.]+) s; the goals took ([\d.]+) x that, '
                        r'the bounds allow ([\d.]+) x', text)
    assert fastest and 1.0 <= float(fastest[2]) and 1.0 < float(fastest[3]) < 1.5, \
        text[-2000:]

    for name in ('map.png', 'navigation.png'):
        data = (out / name).read_bytes()
        assert data[:8] == b'\x89PNG\r\n\x1a\n' and len(data) > 10000, name

    pids = [p for name in ('slam_stack.log', 'navigation_stack.log')
            for p in launched_pids((out / name).read_text())]
    assert len(pids) >= 8, pids
    assert not left_running(pids), 'stack processes left behind'
