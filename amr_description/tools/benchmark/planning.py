# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Planner and controller cost on warehouse.sdf.

Run ``python -m amr_description.tools.benchmark.planning``.

The world's sections at 0.25 m are drawn into a 20 x 20 m map at 5 cm (400 x 400 cells), made
a global costmap as config/nav2_params.yaml's (static layer, inflation 0.70 m, scaling 3.0,
robot radius 0.22 m) and planned on between seeded random free cells reachable from the
world's origin, at least 12 m apart (the
warehouse's shelves leave no free pairs 15 m apart in a straight line everywhere; the length
planned is printed). Each cycle of Regulated Pure Pursuit is then timed on the path with the
collision check on. Targets (issue 31): planner <= 50 ms, controller <= 5 ms per cycle.
"""

import argparse
import math
import time

import numpy as np


def warehouse_costmap(resolution=0.05, size=20.0):
    """Return the global costmap of warehouse.sdf, centred on the world origin."""
    from amr_description.core.gazebo.sdf_world import load_world
    from amr_description.core.scan_map import surface_distance
    from amr_description.core.scan_map import world_sections
    from amr_description.nav import costmap as cm
    sections = world_sections(load_world('warehouse'), 0.25)
    n = int(round(size / resolution))
    lo = -size / 2.0
    cols, rows = np.meshgrid(np.arange(n), np.arange(n))
    centres = np.stack([lo + (cols + 0.5) * resolution, lo + (rows + 0.5) * resolution],
                       axis=-1).reshape(-1, 2)
    d = surface_distance(centres, sections).reshape(n, n)
    occupancy = np.where(d <= resolution * math.sqrt(0.5), 100, 0)
    inscribed = cm.footprint_radii(cm.pad_footprint(cm.footprint_from_radius(0.22), 0.01))[0]
    costs = cm.inflate(cm.static_costs(occupancy), resolution, 0.70, 3.0, inscribed)
    return cm.Costmap(costs, resolution, (lo, lo)), inscribed


def main(argv=None):
    """Print the planner's and the controller's times."""
    from amr_description.nav.planner import make_plan
    from amr_description.nav.planner import path_length
    from amr_description.nav.pure_pursuit import circle_collides
    from amr_description.nav.pure_pursuit import RegulatedPurePursuit
    parser = argparse.ArgumentParser(description='Planner and controller cost on warehouse.sdf.')
    parser.add_argument('--goals', type=int, default=20)
    parser.add_argument('--seed', type=int, default=1)
    args = parser.parse_args(argv)
    t = time.perf_counter()
    costmap, inscribed = warehouse_costmap()
    build = time.perf_counter() - t
    rng = np.random.default_rng(args.seed)
    from scipy import ndimage
    labels, _ = ndimage.label(costmap.costs < 253)
    inside = labels == labels[costmap.world_to_map(0.0, 0.0)[::-1]]  # the robot's start
    free = np.argwhere(inside & (costmap.costs < 128))
    plans, lengths, cycles = [], [], []
    rpp = RegulatedPurePursuit(inscribed_radius=inscribed)
    while len(plans) < args.goals:
        a, b = free[rng.integers(len(free), size=2)]
        (ax, ay), (bx, by) = (costmap.map_to_world(a[1], a[0]), costmap.map_to_world(b[1], b[0]))
        if math.hypot(bx - ax, by - ay) < 12.0:
            continue
        t = time.perf_counter()
        path = make_plan(costmap, (float(ax), float(ay)), (float(bx), float(by), 0.0))
        plans.append(time.perf_counter() - t)
        lengths.append(path_length(path))
        # one controller cycle at each of 20 places along the path, path in the robot frame
        for k in np.linspace(0, len(path) - 2, 20).astype(int):
            x, y = path[k, :2]
            yaw = math.atan2(path[k + 1, 1] - y, path[k + 1, 0] - x)
            c, s = math.cos(yaw), math.sin(yaw)
            rel = path[k:, :2] - (x, y)
            local = np.column_stack((rel @ [c, s], rel @ [-s, c], path[k:, 2]))

            def hit(px, py, pyaw, x=x, y=y, c=c, s=s):
                return circle_collides(costmap, x + c * px - s * py, y + s * px + c * py)
            t = time.perf_counter()
            try:
                rpp.compute(local, speed=(0.5, 0.0), cost=costmap.cost_at(x, y) or 0,
                            collision=hit)
            except Exception:  # noqa: B902 - a collision counts as a cycle too
                pass
            cycles.append(time.perf_counter() - t)
    ms = 1000.0
    print(f'warehouse.sdf global costmap 400 x 400 cells at 0.05 m: built in {build * ms:.0f} ms')
    print(f'planner GridBased, {len(plans)} goals >= 12 m apart (paths {min(lengths):.1f}-'
          f'{max(lengths):.1f} m): median {np.median(plans) * ms:.1f} ms, max '
          f'{max(plans) * ms:.1f} ms (target <= 50 ms)')
    print(f'controller RPP with collision check, {len(cycles)} cycles: median '
          f'{np.median(cycles) * ms:.2f} ms, max {max(cycles) * ms:.2f} ms (target <= 5 ms)')


if __name__ == '__main__':
    main()
