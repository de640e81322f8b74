# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""AMCL's pieces against closed forms: KLD limit, distance field, beams, motion, estimate."""

import math

from amr_description.nav import amcl
from amr_description.nav import laser_models
from amr_description.nav.map_io import GridMap
import numpy as np
import pytest


Z_99 = 2.3263478740408408
"""The standard normal quantile of Nav2's ``pf_z`` 0.99."""


def kld_limit(k, params):
    """Nav2 amcl's ``pf_resample_limit`` for ``k`` bins, one at a time (the reference)."""
    if k <= 1:
        return params.max_particles
    n = math.ceil((k - 1) / (2 * params.pf_err) * (1 - 2 / (9 * (k - 1))
                                                   + math.sqrt(2 / (9 * (k - 1))) * Z_99) ** 3)
    return min(max(n, params.min_particles), params.max_particles)


def _room():
    """Return a 4 x 3 m room (0.05 m cells), walls one cell thick, origin (-1, -1)."""
    data = np.zeros((60, 80), dtype=np.int8)
    data[0, :] = data[-1, :] = 100
    data[:, 0] = data[:, -1] = 100
    return GridMap(data, 0.05, (-1.0, -1.0, 0.0))


def test_kld_limit_closed_form():
    params = amcl.AmclParameters()
    limit = dict(zip((1, 2, 10, 10000), amcl.kld_limits([1, 2, 10, 10000], params).tolist()))
    assert limit[1] == params.max_particles
    # k = 10 bins: (k-1)/(2 err) (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z_0.99)^3
    z = Z_99
    k = 10
    expected = math.ceil((k - 1) / 0.1 * (1 - 2 / (9 * (k - 1))
                                          + math.sqrt(2 / (9 * (k - 1))) * z) ** 3)
    assert limit[k] == min(max(expected, 500), 2000)
    assert limit[2] == 500  # clamped to min_particles
    assert limit[10000] == 2000


def test_kld_limits_match_the_formula_one_at_a_time():
    for params in (amcl.AmclParameters(), amcl.AmclParameters(min_particles=100,
                                                              max_particles=50000)):
        ks = np.arange(1, 6001)
        assert amcl.kld_limits(ks, params).tolist() == [kld_limit(int(k), params)
                                                        for k in ks]


def test_resample_keeps_the_first_count_that_covers_its_bins():
    # KLD sampling: the kept count n is the smallest with n >= kld_limit(bins among the first
    # n draws), checked by brute force on the kept particles' own bins
    params = amcl.AmclParameters(min_particles=100, max_particles=5000)
    rng = np.random.default_rng(3)
    f = amcl.ParticleFilter(params, seed=3)
    # yaw 0 everywhere: the bins' yaw reference (the circular mean) is the same for any subset
    f.particles = np.column_stack([rng.normal(0, 0.6, 5000), rng.normal(0, 0.6, 5000),
                                   np.zeros(5000)])
    f.weights = np.full(5000, 1 / 5000)
    f.resample()
    n = len(f.particles)
    assert 100 < n < 5000
    bins = amcl._bins(f.particles, np.full(n, 1 / n))
    seen = [len({tuple(b) for b in bins[:m]}) for m in range(1, n + 1)]
    assert n >= kld_limit(seen[n - 1], params)
    assert all(m < kld_limit(seen[m - 1], params) for m in range(1, n))


def test_distance_field_and_free_space():
    field = amcl.LikelihoodMap(_room(), 2.0)
    # 1 m from the left wall's cell (x = -1 .. -0.95) and far from the others
    d = field.lookup(np.array([[0.025, 0.475], [50.0, 50.0]]))
    assert d[0] == pytest.approx(1.0, abs=0.03)
    assert d[1] == 2.0  # off the map: the cap
    poses = field.random_free_poses(500, np.random.default_rng(0))
    assert np.all(field.lookup(poses[:, :2]) > 0.0)


def test_parameters_taken_at_run_time():
    loc = amcl.Amcl(amcl.AmclParameters(), seed=0)
    loc.set_map(_room())
    field = loc.map
    loc.update_parameters({'z_hit': 0.9, 'laser_model_type': 'beam', 'scan_topic': 'x'})
    assert (loc.params.z_hit, loc.filter.params.laser_model_type) == (0.9, 'beam')
    assert loc.map is field  # the distance field did not change
    loc.update_parameters({'laser_likelihood_max_dist': 0.5})
    assert loc.map is not field and loc.map.distance.max() == 0.5


def test_freespace_downsampling_draws_from_every_other_free_cell():
    field = amcl.LikelihoodMap(_room(), 2.0, downsample=True)
    assert len(field.free) == 29 * 39  # rows 2..58 and columns 2..78, even ones only
    assert np.all(field.free % 2 == 0)
    assert len(amcl.LikelihoodMap(_room(), 2.0).free) == 58 * 78


def test_beams_follow_nav2_rules():
    filt = amcl.Amcl(amcl.AmclParameters(max_beams=5, laser_max_range=-1.0))
    ranges = [1.0, 0.05, 2.0, np.nan, 10.0, 3.0, 4.0, 5.0, 6.0]
    beams, rmax = filt.beams(ranges, 0.0, 0.1, 0.1, 10.0, (0.2, 0.0, 0.0))
    # step (9 - 1) // (5 - 1) = 2: readings 0, 2, 4, 6, 8 -> 1.0, 2.0, 10.0 (= max: skipped)
    assert rmax == 10.0
    assert beams[:, 3].tolist() == [1.0, 2.0, 4.0, 6.0]
    assert np.allclose(beams[:, 2], [0.0, 0.2, 0.6, 0.8])
    assert np.all(beams[:, 0] == 0.2)


def test_motion_model_mean_follows_odometry():
    filt = amcl.ParticleFilter(amcl.AmclParameters(), seed=3)
    filt.initialize((1.0, 2.0, math.pi / 2), np.zeros((3, 3)))
    filt.move((0.0, 0.0, 0.0), (0.5, 0.0, 0.2))  # 0.5 m forward then 0.2 rad left
    mean = filt.particles.mean(axis=0)
    assert mean[0] == pytest.approx(1.0, abs=0.02)
    assert mean[1] == pytest.approx(2.5, abs=0.02)
    assert mean[2] == pytest.approx(math.pi / 2 + 0.2, abs=0.02)
    # translation noise: alpha3 trans^2 + alpha4 (rot1^2 + rot2^2), rot1 = 0, rot2 = 0.2
    assert filt.particles[:, 1].std() == pytest.approx(
        math.sqrt(0.2 * 0.25 + 0.2 * 0.04), rel=0.1)


def test_omni_motion_model_moves_along_the_bearing_and_strafes_with_alpha5():
    params = amcl.AmclParameters(robot_model_type='nav2_amcl::OmniMotionModel', alpha1=0.0,
                                 alpha2=0.0, alpha3=0.0, alpha4=0.0, alpha5=0.0)
    filt = amcl.ParticleFilter(params, seed=3)
    filt.initialize((1.0, 2.0, math.pi / 2), np.zeros((3, 3)))
    # in odom: from (0, 0, 0) a step of 0.3 m at a bearing of 0.4 rad, turning 0.1 rad; a
    # particle facing +y moves 0.3 m at pi/2 + 0.4 and turns 0.1 rad, with no noise
    filt.move((0.0, 0.0, 0.0), (0.3 * math.cos(0.4), 0.3 * math.sin(0.4), 0.1))
    assert filt.particles[:, 0] == pytest.approx(1.0 + 0.3 * math.cos(math.pi / 2 + 0.4))
    assert filt.particles[:, 1] == pytest.approx(2.0 + 0.3 * math.sin(math.pi / 2 + 0.4))
    assert filt.particles[:, 2] == pytest.approx(math.pi / 2 + 0.1)
    # alpha5 alone: sideways spread only, sd sqrt(alpha5) x trans
    params.alpha5 = 0.25
    filt = amcl.ParticleFilter(params, seed=3)
    filt.initialize((0.0, 0.0, 0.0), np.zeros((3, 3)))
    filt.move((0.0, 0.0, 0.0), (0.4, 0.0, 0.0))
    assert filt.particles[:, 0] == pytest.approx(0.4)
    assert filt.particles[:, 1].std() == pytest.approx(0.5 * 0.4, rel=0.1)
    assert filt.particles[:, 1].mean() == pytest.approx(0.0, abs=0.01)


def test_estimate_is_the_heaviest_cluster_across_the_seam():
    filt = amcl.ParticleFilter(amcl.AmclParameters(), seed=1)
    rng = np.random.default_rng(2)
    heading_pi = np.column_stack([rng.normal(1.0, 0.05, 800), rng.normal(0.0, 0.05, 800),
                                  math.pi + rng.normal(0.0, 0.03, 800)])
    heading_pi[:, 2] = (heading_pi[:, 2] + math.pi) % (2 * math.pi) - math.pi
    other = np.column_stack([rng.normal(-3.0, 0.05, 200), rng.normal(0.0, 0.05, 200),
                             rng.normal(0.0, 0.03, 200)])
    filt.particles = np.vstack([heading_pi, other])
    filt.weights = np.full(1000, 1e-3)
    pose, cov = filt.estimate()
    assert pose[0] == pytest.approx(1.0, abs=0.01)
    assert abs(math.remainder(pose[2] - math.pi, math.tau)) < 0.01


def test_map_range_stops_at_the_first_cell_not_free():
    data = _room().data.copy()
    data[30, 60] = -1  # an unknown cell at x 2.0 .. 2.05, y 0.5 .. 0.55
    field = amcl.LikelihoodMap(GridMap(data, 0.05, (-1.0, -1.0, 0.0)), 2.0)
    # from cell (col 20, row 30), x 0.0 .. 0.05, y 0.5 .. 0.55: east to the unknown cell (40
    # cells), west to the wall's cell (col 0: 20 cells), north to row 59 (29 cells);
    # map_range.c's range is the distance between the two cells' centres
    origin = np.array([0.025, 0.525])
    ranges = field.cast(np.tile(origin, (3, 1)), [0.0, math.pi, math.pi / 2], 5.0)
    assert ranges[:3] == pytest.approx([40 * 0.05, 20 * 0.05, 29 * 0.05])
    assert field.cast(origin[None], [0.0], 1.0)[0] == 1.0  # nothing within 1 m: the limit
    # off the map counts as not free; a diagonal ray at 45 deg from cell (1, 1) to (59, 59)
    off = np.array([[0.025, 2.2]])  # above the map
    assert field.cast(off, [0.0], 5.0)[0] == 0.0
    diag = field.cast(np.array([[-0.925, -0.925]]), [math.pi / 4], 10.0)[0]
    assert diag == pytest.approx(58 * 0.05 * math.sqrt(2.0), abs=0.05)


def _factor(params, pose, field, beams, rmax, converged=False):
    """Return one particle's weight factor at ``pose``."""
    return laser_models.weight_factors(params, np.array([pose]), field, beams, rmax,
                                       converged)[0]


def test_beam_model_closed_form():
    field = amcl.LikelihoodMap(_room(), 2.0)
    p = amcl.AmclParameters(laser_model_type='beam')
    rmax = 5.0
    # the sensor 0.1 m ahead of the base (col 22), looking east: the map's range to the east
    # wall's cell (col 79) is 57 cells
    expected = 57 * 0.05
    beams = np.array([[0.1, 0.0, 0.0, expected],        # a hit where the map says
                      [0.1, 0.0, 0.0, expected - 0.5],  # short: an unexpected obstacle
                      [0.1, 0.0, 0.0, rmax]])           # at range_max: no return
    factor = _factor(p, (0.025, 0.525, 0.0), field, beams, rmax)

    def gauss(z):
        return p.z_hit * math.exp(-z * z / (2 * p.sigma_hit ** 2))
    pz = [gauss(0.0) + p.z_rand / rmax,
          gauss(-0.5) + p.z_rand / rmax
          + p.z_short * p.lambda_short * math.exp(-p.lambda_short * (expected - 0.5)),
          gauss(rmax - expected) + p.z_max]
    assert factor == pytest.approx(1.0 + sum(v ** 3 for v in pz))


def test_likelihood_field_prob_closed_form_and_beam_skipping():
    field = amcl.LikelihoodMap(_room(), 2.0)
    p = amcl.AmclParameters(laser_model_type='likelihood_field_prob')
    pose = (0.025, 0.525, 0.0)
    rmax = 5.0
    # end points 1.0 m and 0.6 m short of the east wall's cell (col 79: x 2.95 .. 3.0)
    beams = np.array([[0.0, 0.0, 0.0, 1.925], [0.0, 0.0, 0.0, 2.325]])
    d = field.lookup(np.array([[1.95, 0.525], [2.35, 0.525]]))
    pz = p.z_hit * np.exp(-d ** 2 / (2 * p.sigma_hit ** 2)) + p.z_rand / rmax
    assert _factor(p, pose, field, beams, rmax) == pytest.approx(np.prod(pz))
    # beam skipping, converged filter: beam 0 ends 1 m from any obstacle at every particle
    # (beyond beam_skip_distance 0.5): skipped; beam 1 ends 0.6 m off, skipped at 0.7
    p.do_beamskip, p.max_beams, p.beam_skip_distance = True, 2, 0.7
    assert _factor(p, pose, field, beams, rmax, True) == pytest.approx(pz[1])
    # both beams skipped: 2 of max_beams 2 >= 0.9 x 2, so every beam is used
    p.beam_skip_distance = 0.3
    assert _factor(p, pose, field, beams, rmax, True) == pytest.approx(np.prod(pz))
    # not converged: no skipping
    p.beam_skip_distance = 0.7
    assert _factor(p, pose, field, beams, rmax, False) == pytest.approx(np.prod(pz))


def test_converged_after_resampling_a_tight_cloud():
    filt = amcl.ParticleFilter(amcl.AmclParameters(), seed=0)
    filt.initialize((1.0, 1.0, 0.0), np.diag([0.01, 0.01, 0.01]))
    assert not filt.converged  # pf_init_converged
    filt.resample()
    assert filt.converged  # 0.1 m spread: every particle within 0.5 m of the mean
    # two equal clusters 1.2 m apart: the mean between them, every particle 0.6 m from it
    filt.particles = np.array([[0.0, 0.0, 0.0]] * 500 + [[1.2, 0.0, 0.0]] * 500)
    filt.weights = np.full(1000, 1e-3)
    filt.resample()
    assert not filt.converged


def test_beams_of_the_other_models():
    ranges = [1.0, 0.05, 2.0, np.nan, 10.0, 3.0, 4.0, 5.0, np.inf]
    beam = amcl.Amcl(amcl.AmclParameters(max_beams=5, laser_model_type='beam'))
    b, rmax = beam.beams(ranges, 0.0, 0.1, 0.1, 10.0, (0.0, 0.0, 0.0))
    # step 2: readings 0, 2, 4, 6, 8 -> 1.0, 2.0, 10.0 (= range_max: kept), 4.0, inf (left out)
    assert b[:, 3].tolist() == [1.0, 2.0, 10.0, 4.0]
    prob = amcl.Amcl(amcl.AmclParameters(max_beams=4, laser_model_type='likelihood_field_prob'))
    b, _ = prob.beams(ranges, 0.0, 0.1, 0.1, 10.0, (0.0, 0.0, 0.0))
    # step ceil(9 / 4) = 3: readings 0, 3, 6 -> 1.0, NaN (left out), 4.0
    assert b[:, 3].tolist() == [1.0, 4.0]
    assert np.allclose(b[:, 2], [0.0, 0.6])


@pytest.mark.parametrize('model', ['likelihood_field', 'beam', 'likelihood_field_prob',
                                   'beamskip'])
def test_filter_converges_in_a_room_with_scans(model):
    room = _room()
    params = amcl.AmclParameters(update_min_d=0.05, laser_model_type=model)
    if model == 'beamskip':
        params.laser_model_type, params.do_beamskip = 'likelihood_field_prob', True
    loc = amcl.Amcl(params, seed=0)
    loc.set_map(room)
    truth = np.array([0.5, 0.3, 0.3])
    loc.set_initial_pose(truth + (0.2, -0.15, 0.1), np.diag([0.05, 0.05, 0.02]))
    angles = np.linspace(-math.pi, math.pi, 181)[:-1]

    def scan(pose):
        walls = ((-0.975, None), (2.975, None), (None, -0.975), (None, 1.975))
        out = []
        for a in angles:
            d = (math.cos(pose[2] + a), math.sin(pose[2] + a))
            t = [((wx - pose[0]) / d[0]) if wx is not None and abs(d[0]) > 1e-9 else
                 ((wy - pose[1]) / d[1]) if wy is not None and abs(d[1]) > 1e-9 else -1
                 for wx, wy in walls]
            out.append(min(v for v in t if v > 0))
        return out
    odom = np.zeros(3)
    for k in range(12):
        beams, rmax = loc.beams(scan(truth), -math.pi, angles[1] - angles[0], 0.1, 10.0,
                                (0.0, 0.0, 0.0))
        loc.process(odom, beams, rmax)
        step = np.array([0.06 * math.cos(truth[2]), 0.06 * math.sin(truth[2]), 0.0])
        truth = truth + step
        odom = odom + [0.06, 0.0, 0.0]  # odometry frame at 0, heading 0: along its own x
    assert np.hypot(*(loc.pose[:2] - (truth - step)[:2])) < 0.05


def test_recovery_particles_as_pf_c():
    # pf.c (nav2_amcl/src/pf/pf.c): after each sensor update w_slow += alpha_slow (w_avg -
    # w_slow) and w_fast likewise (both start at the first w_avg, w_avg being the mean of the
    # weights before normalising); a resampling draws each particle from the map's free space
    # with probability max(0, 1 - w_fast / w_slow) and then sets both averages to 0
    room = _room()
    field = amcl.LikelihoodMap(room, 2.0)
    params = amcl.AmclParameters(recovery_alpha_slow=0.1, recovery_alpha_fast=0.5,
                                 min_particles=2000, max_particles=2000)
    here, elsewhere = (0.5, 0.3, 0.0), (2.5, 1.5, 2.0)
    angles = np.linspace(-math.pi, math.pi, 61)[:-1]
    select = amcl.Amcl(params)

    def beams_from(pose):
        ranges = field.cast(np.tile(pose[:2], (len(angles), 1)), pose[2] + angles, 10.0)
        return select.beams(list(ranges), -math.pi, angles[1] - angles[0], 0.1, 10.0,
                            (0.0, 0.0, 0.0))

    f_here = _factor(params, here, field, *beams_from(here))
    f_there = _factor(params, here, field, *beams_from(elsewhere))
    assert f_there < f_here  # the scan from elsewhere fits the particles' pose worse
    pf = amcl.ParticleFilter(params, seed=0)
    pf.initialize(here, np.zeros((3, 3)))  # every particle on one pose: one factor for all
    n = len(pf.particles)
    pf.weigh(field, *beams_from(here))
    assert pf.w_slow == pytest.approx(f_here / n) and pf.w_fast == pytest.approx(f_here / n)
    pf.weigh(field, *beams_from(elsewhere))
    slow = f_here / n + 0.1 * (f_there - f_here) / n
    fast = f_here / n + 0.5 * (f_there - f_here) / n
    assert (pf.w_slow, pf.w_fast) == pytest.approx((slow, fast))
    pf.resample(field)
    moved = np.any(pf.particles != here, axis=1)
    assert moved.mean() == pytest.approx(1.0 - fast / slow, abs=0.05)  # binomial sd 0.011
    assert np.all(field.lookup(pf.particles[moved, :2]) > 0.0)  # on free cells, not walls
    assert pf.w_slow == 0.0 and pf.w_fast == 0.0
    # the defaults (alphas 0) keep both averages at the first w_avg: none is drawn even when
    # the resampling is given the map
    pf = amcl.ParticleFilter(amcl.AmclParameters(min_particles=2000, max_particles=2000), 0)
    pf.initialize(here, np.zeros((3, 3)))
    pf.weigh(field, *beams_from(here))
    pf.weigh(field, *beams_from(elsewhere))
    assert pf.w_slow == pf.w_fast == pytest.approx(f_here / n)
    pf.resample(field)
    assert np.all(pf.particles == here)
