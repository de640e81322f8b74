# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Physics fidelity report of a skid-steer robot in the MuJoCo world (no rclpy, sim time only).

``ros2 run amr_description physics_report [--urdf FILE] [--png FILE]`` spawns the robot into
:class:`~amr_description.sim.world.World` exactly as ``mujoco_sim`` does (URDF ->
:func:`~amr_description.sim.urdf_to_mjcf.urdf_to_spec`, 1 ms step), drives its wheels through
:class:`~amr_description.sim.mujoco_system.MujocoSystem` at 100 Hz (the controller manager's
rate) and measures, in simulated time (so the figures do not depend on the machine's load):

- every drive ramps the wheel commands up at :data:`RAMP` (what diff_drive_controller's
  acceleration limits do), then holds them;
- wheels in contact: a wheel is in contact at a step when one of its contacts with the ground
  carries a positive normal force (``mujoco.mj_contactForce``); the share of steps with all
  four in contact, over a 2 s window after 1 s of settling at constant wheel speeds;
- base jitter: peak-to-peak height of the root link over that window, mm;
- turn ratio: measured yaw rate over the Coulomb skid-steer yaw rate for the measured wheel
  speeds (:mod:`amr_description.core.skid_steer`: ``v b / (a^2 + b^2)`` turning in place, the
  integrated rigid-body model on arcs);
- sideways slip on arcs: the root link's mean sideways velocity (its y) against the
  integrated Coulomb model's for the measured wheel speeds, cm/s;
- velocity tracking: worst wheel's relative error of its mean speed against the command;
- straight-line odometry: distance from the wheel angles (``r * mean angle change``) against
  ground truth, %;
- rest: dropped from z 0.2 m, the time after which the base stays within 1 mm of its rest
  height and below 1 cm/s, and its creep over the following 60 s.
"""

import argparse
from dataclasses import dataclass
import math
import os
import sys

from amr_description.core.description.ros2_control_info import parse_ros2_control
from amr_description.core.skid_steer import steady_twist
from amr_description.core.skid_steer import turn_in_place_rate
from amr_description.sim.mujoco_system import MujocoSystem
from amr_description.sim.urdf_to_mjcf import urdf_to_spec
from amr_description.sim.world import World
import mujoco
import numpy as np

#: wheel link name suffixes of the tutorial robot, left side first
WHEELS = ('front_left', 'back_left', 'front_right', 'back_right')
CONTROL_PERIOD = 0.01  # s, the controller manager's 100 Hz
#: what the physics must meet: all four wheels in contact, jitter, turn-rate error, tracking,
#: odometry error, sideways slip on arcs beyond the Coulomb model's (m/s: unseen by the
#: odometry, it carries the base off its path), time to rest and creep (figures in
#: docs/simulation.md)
TARGETS = {'all4': 0.95, 'jitter_mm': 1.0, 'turn_ratio': 0.10, 'tracking': 0.02,
           'odometry': 0.005, 'sideways': 0.01, 'rest_s': 1.0, 'creep_mm': 1.0}
TURN_SPEEDS = (0.1, 0.5, 1.0, 2.0, 5.0, 10.0)  # rad/s, wheel speeds turning in place
#: wheel acceleration of the command ramps, rad/s^2: diff_drive_controller's 2 m/s^2 limit
#: (config/controllers.yaml) on 0.1 m wheels
RAMP = 20.0
STRAIGHT_SPEEDS = (1.0, 5.0, 10.0)  # rad/s
ARCS = ((2.0, 6.0), (5.0, 10.0), (-2.0, 6.0))  # (left, right) rad/s


@dataclass
class Drive:
    """
    What one constant-wheel-speed run measured.

    :param left: commanded left wheel speed, rad/s.
    :param right: commanded right wheel speed, rad/s.
    :param all4: share of steps with all four wheels in contact (0..1).
    :param mean_contacts: mean number of wheels in contact.
    :param jitter_mm: peak-to-peak base height, mm.
    :param yaw_rate: mean yaw rate, rad/s.
    :param model_yaw_rate: Coulomb model yaw rate for the measured wheel speeds, rad/s.
    :param wheel_speeds: mean speed of each wheel (front_left, back_left, front_right,
        back_right), rad/s.
    :param tracking: worst relative wheel speed error against the command (0..).
    :param distance: ground-truth distance travelled over the window, m.
    :param odometry_distance: ``r`` times the mean wheel angle change, m.
    :param sideways: mean sideways velocity of the root link (its y, REP 103: left positive),
        m/s; the wheel odometry does not see it.
    :param model_sideways: the Coulomb model's sideways velocity for the measured wheel
        speeds, m/s (0 turning in place and driving straight).
    """

    left: float
    right: float
    all4: float
    mean_contacts: float
    jitter_mm: float
    yaw_rate: float
    model_yaw_rate: float
    wheel_speeds: tuple
    tracking: float
    distance: float
    odometry_distance: float
    sideways: float
    model_sideways: float

    @property
    def turn_ratio(self):
        """Return measured / model yaw rate (nan when the model rate is ~0)."""
        if abs(self.model_yaw_rate) < 1e-9:
            return math.nan
        return self.yaw_rate / self.model_yaw_rate


class Bench:
    """
    One robot in a fresh :class:`World`, its wheels driven through :class:`MujocoSystem`.

    :param urdf_xml: the URDF (with ``<ros2_control>`` and ``<mujoco>`` blocks), str.
    :param z: spawn height of the root link, m.
    :param physics_step: s.
    :raises ValueError: when the URDF is not a four-wheeled robot with the link names of
        :data:`WHEELS` (``wheel_<name>``) and ``joint_wheel_<name>`` velocity joints.
    """

    def __init__(self, urdf_xml, z=0.0, physics_step=0.001):
        """Spawn the robot and bind its hardware interface."""
        self.world = World(physics_step)
        self.world.spawn(urdf_to_spec(urdf_xml, name='amr', pose=(0, 0, z, 0, 0, 0)), 'amr')
        self.system = MujocoSystem(self.world.model, self.world.data, prefix='amr/')
        self.system.on_init(parse_ros2_control(urdf_xml)[0])
        model = self.world.model
        try:
            self.wheel_bodies = [model.body(f'amr/wheel_{n}').id for n in WHEELS]
            joints = [model.joint(f'amr/joint_wheel_{n}') for n in WHEELS]
        except KeyError as exc:
            raise ValueError(f'the robot needs wheels {", ".join(WHEELS)}: {exc}') from None
        self.wheel_qpos = [int(j.qposadr[0]) for j in joints]
        self.wheel_dofs = [int(j.dofadr[0]) for j in joints]
        self.commands = [self.system.command_handles[f'joint_wheel_{n}/velocity']
                         for n in WHEELS]
        self.ground = model.geom('ground_plane').id
        mujoco.mj_forward(model, self.world.data)
        base = self.world.data.xpos[model.body('amr/base_link').id]
        offsets = np.array([self.world.data.xpos[b] - base for b in self.wheel_bodies])
        self.half_track = float(offsets[:2, 1].mean() - offsets[2:, 1].mean()) / 2.0
        self.half_wheelbase = float(np.mean(np.abs(offsets[:, 0] - offsets[:, 0].mean())))
        geom = [g for g in range(model.ngeom) if model.geom_bodyid[g] == self.wheel_bodies[0]
                and model.geom_contype[g] | model.geom_conaffinity[g]]
        self.wheel_radius = float(model.geom_size[geom[0], 0]) if geom else 0.1
        root = model.body('amr/' + self.world.robots['amr'].root).id
        self.mass = float(model.body_subtreemass[root])
        self.yaw_inertia = self._yaw_inertia(root)

    def _yaw_inertia(self, root):
        """Return the robot's moment of inertia about the vertical through its centre, kg m^2."""
        model, data = self.world.model, self.world.data
        bodies = [b for b in range(model.nbody) if model.body_rootid[b] == root]
        mass = model.body_mass[bodies]
        centre = (data.xipos[bodies] * mass[:, None]).sum(axis=0) / mass.sum()
        total = 0.0
        for b in bodies:
            rot = data.ximat[b].reshape(3, 3)
            total += (rot @ np.diag(model.body_inertia[b]) @ rot.T)[2, 2]
            total += model.body_mass[b] * float(np.sum((data.xipos[b, :2] - centre[:2]) ** 2))
        return float(total)

    def command(self, left, right):
        """Set the velocity command of the left and right wheels, rad/s."""
        for handle, value in zip(self.commands, (left, left, right, right)):
            handle.value = float(value)

    def run(self, seconds, sample=None):
        """
        Advance ``seconds`` of sim time: hardware write every 10 ms, ``sample()`` every step.

        :param seconds: sim time, s.
        :param sample: callable run after every physics step, or None.
        """
        steps_per_update = max(1, int(round(CONTROL_PERIOD / self.world.physics_step)))
        for _ in range(int(round(seconds / CONTROL_PERIOD))):
            self.system.write(self.world.time, CONTROL_PERIOD)
            if sample is None:
                self.world.step(steps_per_update)
            else:
                for _ in range(steps_per_update):
                    self.world.step(1)
                    sample()
            self.system.read(self.world.time, CONTROL_PERIOD)

    def wheels_in_contact(self):
        """Return how many wheels touch the ground with a positive normal force (0..4)."""
        model, data = self.world.model, self.world.data
        force = np.zeros(6)
        touching = set()
        for i in range(data.ncon):
            contact = data.contact[i]
            g1, g2 = int(contact.geom[0]), int(contact.geom[1])
            other = g2 if g1 == self.ground else g1 if g2 == self.ground else -1
            if other < 0:
                continue
            body = int(model.geom_bodyid[other])
            if body in self.wheel_bodies and body not in touching:
                mujoco.mj_contactForce(model, data, i, force)
                if force[0] > 0.0:
                    touching.add(body)
        return len(touching)

    def drive(self, left, right, settle=1.0, window=2.0, ramp=RAMP):
        """
        Reset, ramp the wheel speeds up, settle, then measure over a window.

        :param left: left wheel speed command, rad/s.
        :param right: right wheel speed command, rad/s.
        :param settle: s of driving at the commanded speeds before the window.
        :param ramp: wheel acceleration of the command ramp, rad/s^2.
        :param window: s measured.
        :returns: a :class:`Drive`.
        """
        world = self.world
        world.reset()
        self.command(0.0, 0.0)
        self.run(0.5)
        ramp_time = max(abs(left), abs(right)) / ramp
        for k in range(1, int(math.ceil(ramp_time / CONTROL_PERIOD)) + 1):
            scale = min(1.0, k * CONTROL_PERIOD / ramp_time)
            self.command(scale * left, scale * right)
            self.run(CONTROL_PERIOD)
        self.command(left, right)
        self.run(settle)
        data = world.data
        qadr, vadr = world.free_joint_address('amr')
        start_xy = data.qpos[qadr:qadr + 2].copy()
        start_angles = data.qpos[self.wheel_qpos].copy()
        contacts, heights, yaw_rates, speeds, sideways = [], [], [], [], []

        def sample():
            contacts.append(self.wheels_in_contact())
            heights.append(float(data.qpos[qadr + 2]))
            _, _, linear, angular = world.ground_truth('amr')
            yaw_rates.append(angular[2])
            sideways.append(linear[1])
            speeds.append(data.qvel[self.wheel_dofs].copy())

        self.run(window, sample)
        distance = float(np.linalg.norm(data.qpos[qadr:qadr + 2] - start_xy))
        turned = data.qpos[self.wheel_qpos] - start_angles
        wheel_speeds = np.mean(speeds, axis=0)
        rim = wheel_speeds * self.wheel_radius
        v_left, v_right = rim[:2].mean(), rim[2:].mean()
        model_sideways = 0.0
        if abs(v_left + v_right) < 1e-9 * max(1.0, abs(v_right)):
            model_rate = turn_in_place_rate((v_right - v_left) / 2.0, self.half_wheelbase,
                                            self.half_track)
        else:
            _, model_sideways, model_rate = (float(x) for x in steady_twist(
                v_left, v_right, self.half_wheelbase, self.half_track, self.mass,
                self.yaw_inertia))
        commands = np.array([left, left, right, right], dtype=float)
        errors = [abs(s - c) / abs(c) for s, c in zip(wheel_speeds, commands) if c != 0.0]
        return Drive(left=left, right=right, all4=float(np.mean(np.array(contacts) == 4)),
                     mean_contacts=float(np.mean(contacts)),
                     jitter_mm=1000.0 * float(np.ptp(heights)),
                     yaw_rate=float(np.mean(yaw_rates)), model_yaw_rate=model_rate,
                     wheel_speeds=tuple(float(v) for v in wheel_speeds),
                     tracking=max(errors) if errors else 0.0, distance=distance,
                     odometry_distance=float(abs(np.mean(turned)) * self.wheel_radius),
                     sideways=float(np.mean(sideways)), model_sideways=model_sideways)


def rest_and_creep(urdf_xml, z=0.2, creep_seconds=60.0):
    """
    Drop the robot from ``z`` with zero wheel commands; measure settling and creep.

    :param urdf_xml: the URDF, str.
    :param z: spawn height of the root link, m.
    :param creep_seconds: s of rest over which the creep is measured.
    :returns: ``(rest time s, creep mm)``: the time after which the base stays within 1 mm
        of its final height and below 1 cm/s (within the first 2 s), and the horizontal plus
        vertical displacement of the root over the following ``creep_seconds``.
    """
    bench = Bench(urdf_xml, z=z)
    world, data = bench.world, bench.world.data
    qadr, vadr = world.free_joint_address('amr')
    bench.command(0.0, 0.0)
    heights, speeds = [], []

    def sample():
        heights.append(float(data.qpos[qadr + 2]))
        speeds.append(float(np.linalg.norm(data.qvel[vadr:vadr + 3])))

    bench.run(2.0, sample)
    final = heights[-1]
    settled = [abs(h - final) < 1e-3 and v < 0.01 for h, v in zip(heights, speeds)]
    last_bad = max((i for i, ok in enumerate(settled) if not ok), default=-1)
    rest_time = (last_bad + 1) * world.physics_step
    start = data.qpos[qadr:qadr + 3].copy()
    bench.run(creep_seconds)
    creep = float(np.linalg.norm(data.qpos[qadr:qadr + 3] - start))
    return rest_time, 1000.0 * creep


def measure(urdf_xml):
    """
    Run every measurement of the report.

    :param urdf_xml: the URDF, str.
    :returns: dict with ``turns``, ``straights``, ``arcs`` (lists of :class:`Drive`),
        ``rest_s``, ``creep_mm`` and ``geometry`` (dict a, b, r, mass, yaw inertia).
    """
    bench = Bench(urdf_xml)
    result = {
        'turns': [bench.drive(-s, s) for s in TURN_SPEEDS],
        'straights': [bench.drive(s, s) for s in STRAIGHT_SPEEDS],
        'arcs': [bench.drive(left, right) for left, right in ARCS],
        'geometry': {'a': bench.half_wheelbase, 'b': bench.half_track,
                     'r': bench.wheel_radius, 'mass': bench.mass,
                     'yaw_inertia': bench.yaw_inertia},
    }
    result['rest_s'], result['creep_mm'] = rest_and_creep(urdf_xml)
    return result


def table_rows(result):
    """
    Return the report rows ``(case, quantity, value text, target text, ok)``.

    :param result: the dict of :func:`measure`.
    :returns: list of 5-tuples.
    """
    rows = []

    def drive_rows(case, drive, ratio=True, odometry=False, sideways=False):
        rows.append((case, 'all 4 wheels in contact', f'{100 * drive.all4:.1f} %',
                     '>= 95 %', drive.all4 >= TARGETS['all4']))
        rows.append((case, 'base height jitter', f'{drive.jitter_mm:.3f} mm', '< 1 mm',
                     drive.jitter_mm < TARGETS['jitter_mm']))
        if ratio:
            rows.append((case, 'yaw rate / Coulomb model', f'{drive.turn_ratio:.3f}',
                         '1 +- 0.10', abs(drive.turn_ratio - 1.0) <= TARGETS['turn_ratio']))
        rows.append((case, 'wheel speed error', f'{100 * drive.tracking:.2f} %', '< 2 %',
                     drive.tracking < TARGETS['tracking']))
        if sideways:
            slip = drive.sideways - drive.model_sideways
            rows.append((case, 'sideways slip - Coulomb model',
                         f'{100 * slip:+.2f} cm/s ({100 * drive.sideways:+.2f} vs '
                         f'{100 * drive.model_sideways:+.2f})', '+- 1 cm/s',
                         abs(slip) <= TARGETS['sideways']))
        if odometry:
            error = abs(drive.odometry_distance - drive.distance) / drive.distance
            rows.append((case, 'wheel odometry vs truth', f'{100 * error:.3f} %', '< 0.5 %',
                         error < TARGETS['odometry']))

    for drive in result['turns']:
        drive_rows(f'turn in place {drive.right:g} rad/s', drive)
    for drive in result['straights']:
        drive_rows(f'straight {drive.right:g} rad/s', drive, ratio=False, odometry=True)
    for drive in result['arcs']:
        drive_rows(f'arc {drive.left:g}/{drive.right:g} rad/s', drive, sideways=True)
    rows.append(('rest, dropped from z 0.2 m', 'time to rest', f'{result["rest_s"]:.3f} s',
                 '< 1 s', result['rest_s'] < TARGETS['rest_s']))
    rows.append(('rest, 60 s', 'creep', f'{result["creep_mm"]:.4f} mm', '< 1 mm',
                 result['creep_mm'] < TARGETS['creep_mm']))
    return rows


def format_table(rows):
    """Return the rows as an aligned text table (str)."""
    header = ('case', 'quantity', 'value', 'target', 'ok')
    lines = [header] + [(c, q, v, t, 'yes' if ok else 'NO') for c, q, v, t, ok in rows]
    widths = [max(len(line[i]) for line in lines) for i in range(5)]
    text = ['  '.join(cell.ljust(w) for cell, w in zip(line, widths)).rstrip()
            for line in lines]
    text.insert(1, '  '.join('-' * w for w in widths))
    return '\n'.join(text)


def plot_turn_ratio(result, path):
    """
    Draw the turn-in-place ratio (measured / Coulomb) against wheel speed as a PNG.

    :param result: the dict of :func:`measure`.
    :param path: output file.
    """
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    speeds = [d.right for d in result['turns']]
    ratios = [d.turn_ratio for d in result['turns']]
    geometry = result['geometry']
    fig, ax = plt.subplots(figsize=(7, 4), dpi=100)
    ax.axhspan(0.9, 1.1, color='tab:green', alpha=0.15, label='target: within 10 %')
    ax.axhline(1.0, color='tab:green', lw=1)
    ax.plot(speeds, ratios, 'o-', color='tab:blue', label='MuJoCo world, turning in place')
    arc_x = [max(abs(d.left), abs(d.right)) for d in result['arcs']]
    ax.plot(arc_x, [d.turn_ratio for d in result['arcs']], 's', color='tab:orange',
            label='arcs (vs integrated Coulomb model)')
    ax.set_xscale('log')
    ax.set_ylim(0.0, 1.5)
    ax.set_xlabel('wheel speed, rad/s (arcs: faster side)')
    ax.set_ylabel('yaw rate / Coulomb skid-steer model')
    ax.set_title(f'turn ratio vs speed (a = {geometry["a"]:.3g} m, b = {geometry["b"]:.3g} m:'
                 f' omega = v b / (a^2 + b^2))', fontsize=9)
    ax.grid(True, which='both', alpha=0.3)
    ax.legend(loc='lower left', fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def _default_urdf():
    """Return the path of urdf/amr.urdf: installed share first, else the source tree."""
    try:
        from ament_index_python.packages import get_package_share_directory
        return os.path.join(get_package_share_directory('amr_description'), 'urdf', 'amr.urdf')
    except Exception:  # noqa: B902 - no ament index: fall back to the source tree
        here = os.path.dirname(os.path.abspath(__file__))
        return os.path.join(here, '..', '..', 'urdf', 'amr.urdf')


def main(argv=None):
    """
    Entry point of ``physics_report``: print the table, write the PNG.

    :param argv: command-line arguments (default ``sys.argv[1:]``).
    :returns: 0 when every row meets its target, 1 otherwise or on bad input.
    """
    parser = argparse.ArgumentParser(
        prog='physics_report',
        description='Measure contact, skid-steer turning, wheel speed tracking, odometry and '
                    'rest of a robot in the MuJoCo world (sim time, no ROS).')
    parser.add_argument('--urdf', default=None, help='URDF file (default: urdf/amr.urdf)')
    parser.add_argument('--png', default='turn_ratio.png',
                        help='turn ratio plot to write (default: %(default)s)')
    args = parser.parse_args(argv)
    path = args.urdf or _default_urdf()
    try:
        with open(path) as f:
            urdf_xml = f.read()
        result = measure(urdf_xml)
    except (OSError, ValueError) as exc:
        print(f'physics_report: {path}: {exc}'.splitlines()[0], file=sys.stderr)
        return 1
    geometry = result['geometry']
    print(f'{path}: a = {geometry["a"]:.4g} m (half wheelbase), b = {geometry["b"]:.4g} m '
          f'(half track), r = {geometry["r"]:.4g} m, mass {geometry["mass"]:.4g} kg, '
          f'yaw inertia {geometry["yaw_inertia"]:.4g} kg m^2; 1 ms step, sim time')
    rows = table_rows(result)
    print(format_table(rows))
    plot_turn_ratio(result, args.png)
    failed = sum(not row[4] for row in rows)
    print(f'wrote {args.png}; {len(rows) - failed}/{len(rows)} rows within target')
    return 0 if failed == 0 else 1


if __name__ == '__main__':
    sys.exit(main())
