# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Adaptive Monte Carlo localization as Nav2's ``amcl`` (Jazzy) does it, in numpy (no rclpy).

Poses are planar ``(x, y, yaw)`` (m, m, rad): particles in the map frame, odometry in the odom
frame, both of the base frame. The pieces, each after ``nav2_amcl``'s sources:

- **map**: :class:`~amr_description.nav.laser_models.LikelihoodMap`.
- **motion** (``src/motion_model/differential_motion_model.cpp``): the odometry step as rot1,
  trans, rot2; each particle moves by them with zero-mean noise of variance
  ``alpha1 rot^2 + alpha2 trans^2`` (rotations) and ``alpha3 trans^2 + alpha4 (rot1^2 +
  rot2^2)`` (translation); rot1 is 0 below 1 cm of translation, and the rotations are folded
  so that driving backwards is not a half turn (Thrun et al., Probabilistic Robotics, table
  5.6). With ``robot_model_type`` ``nav2_amcl::OmniMotionModel``
  (``src/motion_model/omni_motion_model.cpp``): the step as a translation along its bearing
  in the odom frame, a rotation and a sideways (strafe) part, each particle moving by them
  with noise of standard deviations ``sqrt(alpha3 trans^2 + alpha4 rot^2)`` (translation),
  ``sqrt(alpha1 rot^2 + alpha2 trans^2)`` (rotation) and ``sqrt(alpha4 rot^2 + alpha5
  trans^2)`` (strafe, zero-mean); a base that slides sideways is covered by ``alpha5``.
- **sensor**: ``laser_model_type``'s model, :mod:`~amr_description.nav.laser_models`.
- **resampling** (``src/pf/pf.c``, ``pf_update_resample``): KLD sampling (Fox, "Adapting
  the sample size in particle filters through KLD-sampling", IJRR 2003): particles are drawn
  until their number reaches ``(k - 1) / (2 pf_err) (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1)))
  z)^3`` for the k histogram bins (0.5 m, 0.5 m, 10 deg) they occupy, between
  ``min_particles`` and ``max_particles``; with ``recovery_alpha_slow/fast`` above 0, random
  free-space particles are mixed in with probability ``max(0, 1 - w_fast / w_slow)``.
- **estimate** (``pf_cluster_stats``): particles grouped by connected histogram bins; the
  cluster with the largest total weight gives the pose (weighted mean, circular for yaw); the
  covariance is the whole filter's.
"""

from dataclasses import dataclass
from dataclasses import fields
import math

from amr_description.nav.laser_models import LikelihoodMap
from amr_description.nav.laser_models import select_beams
from amr_description.nav.laser_models import weight_factors
from amr_description.nav.pose_graph import between
from amr_description.nav.pose_graph import compose
from amr_description.nav.pose_graph import inverse
from amr_description.nav.pose_graph import wrap
import numpy as np
from scipy import ndimage
from scipy.special import ndtri

BIN = (0.5, 0.5, math.radians(10.0))
"""Histogram bin size of KLD sampling and clustering (m, m, rad), ``pf_kdtree`` of nav2_amcl."""


DIFFERENTIAL = ('nav2_amcl::DifferentialMotionModel', 'differential')
OMNI = ('nav2_amcl::OmniMotionModel', 'omnidirectional')
"""``robot_model_type`` values: Jazzy's plugin names and the older short names."""

CONVERGED_DISTANCE = 0.5
"""m, ``pf.c``'s ``dist_threshold``: the filter has converged when every particle is this close
to the particles' mean in x and in y."""


@dataclass
class AmclParameters:
    """Nav2 ``amcl``'s filter parameters with ``nav2_amcl/src/amcl_node.cpp``'s defaults."""

    alpha1: float = 0.2
    alpha2: float = 0.2
    alpha3: float = 0.2
    alpha4: float = 0.2
    alpha5: float = 0.2
    laser_likelihood_max_dist: float = 2.0
    laser_max_range: float = 100.0
    laser_min_range: float = -1.0
    max_beams: int = 60
    max_particles: int = 2000
    min_particles: int = 500
    pf_err: float = 0.05
    pf_z: float = 0.99
    recovery_alpha_fast: float = 0.0
    recovery_alpha_slow: float = 0.0
    resample_interval: int = 1
    sigma_hit: float = 0.2
    z_hit: float = 0.5
    z_rand: float = 0.5
    update_min_a: float = 0.2
    update_min_d: float = 0.25
    robot_model_type: str = 'nav2_amcl::DifferentialMotionModel'
    laser_model_type: str = 'likelihood_field'
    z_short: float = 0.05
    z_max: float = 0.05
    lambda_short: float = 0.1
    do_beamskip: bool = False
    beam_skip_distance: float = 0.5
    beam_skip_threshold: float = 0.3
    beam_skip_error_threshold: float = 0.9
    freespace_downsampling: bool = False

    @classmethod
    def names(cls):
        """Return the parameter names, in declaration order."""
        return [f.name for f in fields(cls)]


def kld_limits(bins, params):
    """
    Return the KLD-sampling particle count for each count of occupied histogram bins.

    ``pf_resample_limit`` of nav2_amcl, for every count in ``bins`` at once: with ``k`` bins
    (``k > 1``), ``ceil((k - 1) / (2 pf_err) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1)))
    z)^3)`` with ``z`` the standard normal quantile of ``pf_z``; ``max_particles`` for
    ``k <= 1``; clamped to ``[min_particles, max_particles]``.

    :param bins: (K,) int, counts of occupied bins.
    :returns: (K,) int64 particle counts.
    """
    k = np.asarray(bins, dtype=float)
    with np.errstate(divide='ignore', invalid='ignore'):
        b = 2.0 / (9.0 * (k - 1))
        c = np.sqrt(2.0 / (9.0 * (k - 1))) * float(ndtri(params.pf_z))
        n = np.ceil((k - 1) / (2.0 * params.pf_err) * (1.0 - b + c) ** 3)
    n = np.where(k <= 1, params.max_particles, n)
    return np.clip(n, params.min_particles, params.max_particles).astype(np.int64)


def _bins(particles, weights):
    """
    Return each particle's histogram bin (N, 3), yaw measured from the circular mean.

    Yaw is unwrapped round the weighted circular mean so that a cloud heading along +-pi is
    one cluster, not two halves either side of the seam.
    """
    mean = math.atan2(weights @ np.sin(particles[:, 2]), weights @ np.cos(particles[:, 2]))
    unwrapped = np.column_stack([particles[:, :2], wrap(particles[:, 2] - mean)])
    return np.floor(unwrapped / BIN).astype(np.int64)


class ParticleFilter:
    """
    Particles and weights; the motion, sensor and resampling steps (module docstring).

    :param params: :class:`AmclParameters`.
    :param seed: seed of the filter's numpy ``Generator``.
    :ivar particles: (N, 3) poses in the map frame.
    :ivar weights: (N,) summing to 1.
    :ivar converged: True after a resampling left every particle within
        :data:`CONVERGED_DISTANCE` of the mean in x and y; False after an initialisation.
    """

    def __init__(self, params=None, seed=None):
        """Start empty (no pose known)."""
        self.params = params or AmclParameters()
        self.rng = np.random.default_rng(seed)
        self.particles = np.zeros((0, 3))
        self.weights = np.zeros(0)
        self.w_slow = self.w_fast = 0.0
        self.converged = False

    def initialize(self, mean, covariance):
        """
        Draw ``max_particles`` particles from a Gaussian (``pf_init``).

        :param mean: ``(x, y, yaw)``.
        :param covariance: 3x3 (x, y, yaw); a zero one puts every particle on the mean.
        """
        n = self.params.max_particles
        cov = np.asarray(covariance, dtype=float).reshape(3, 3)
        noise = self.rng.multivariate_normal(np.zeros(3), cov, n, method='eigh') \
            if np.any(cov) else np.zeros((n, 3))
        self.particles = np.asarray(mean, dtype=float) + noise
        self.particles[:, 2] = wrap(self.particles[:, 2])
        self.weights = np.full(n, 1.0 / n)
        self.w_slow = self.w_fast = 0.0
        self.converged = False

    def initialize_uniform(self, likelihood_map):
        """Spread ``max_particles`` particles over the map's free space (``pf_init_model``)."""
        n = self.params.max_particles
        self.particles = likelihood_map.random_free_poses(n, self.rng)
        self.weights = np.full(n, 1.0 / n)
        self.w_slow = self.w_fast = 0.0
        self.converged = False

    def move(self, old, new):
        """Apply the odometry step from ``old`` to ``new`` (odom frame) with sampled noise."""
        p = self.params
        if p.robot_model_type in OMNI:
            return self._move_omni(old, new)
        d = between(old, new)
        trans = math.hypot(d[0], d[1])
        heading = math.atan2(new[1] - old[1], new[0] - old[0])
        rot1 = 0.0 if trans < 0.01 else float(wrap(heading - old[2]))
        rot2 = float(wrap(new[2] - old[2] - rot1))
        # fold: driving backwards is rot1 - pi, not a half turn
        r1 = min(abs(rot1), abs(wrap(rot1 - math.pi)))
        r2 = min(abs(rot2), abs(wrap(rot2 - math.pi)))
        n = len(self.particles)
        normal = self.rng.standard_normal((n, 3))
        rot1_hat = rot1 - normal[:, 0] * math.sqrt(p.alpha1 * r1 ** 2 + p.alpha2 * trans ** 2)
        trans_hat = trans - normal[:, 1] * math.sqrt(p.alpha3 * trans ** 2
                                                     + p.alpha4 * (r1 ** 2 + r2 ** 2))
        rot2_hat = rot2 - normal[:, 2] * math.sqrt(p.alpha1 * r2 ** 2 + p.alpha2 * trans ** 2)
        heading = self.particles[:, 2] + rot1_hat
        self.particles[:, 0] += trans_hat * np.cos(heading)
        self.particles[:, 1] += trans_hat * np.sin(heading)
        self.particles[:, 2] = wrap(heading + rot2_hat)

    def _move_omni(self, old, new):
        """Apply the odometry step with the omnidirectional motion model (module docstring)."""
        p = self.params
        dx, dy = new[0] - old[0], new[1] - old[1]
        trans = math.hypot(dx, dy)
        rot = float(wrap(new[2] - old[2]))
        normal = self.rng.standard_normal((len(self.particles), 3))
        trans_hat = trans + normal[:, 0] * math.sqrt(p.alpha3 * trans ** 2 + p.alpha4 * rot ** 2)
        rot_hat = rot + normal[:, 1] * math.sqrt(p.alpha1 * rot ** 2 + p.alpha2 * trans ** 2)
        strafe_hat = normal[:, 2] * math.sqrt(p.alpha4 * rot ** 2 + p.alpha5 * trans ** 2)
        bearing = float(wrap(math.atan2(dy, dx) - old[2])) + self.particles[:, 2]
        c, s = np.cos(bearing), np.sin(bearing)
        self.particles[:, 0] += trans_hat * c + strafe_hat * s
        self.particles[:, 1] += trans_hat * s - strafe_hat * c
        self.particles[:, 2] = wrap(self.particles[:, 2] + rot_hat)

    def weigh(self, likelihood_map, beams, range_max):
        """
        Multiply the weights by the ``laser_model_type`` model of a scan; normalise.

        :param beams: (M, 4) of the used beams (:meth:`Amcl.beams`): sensor x, y, yaw in the
            base frame, range (m).
        :param range_max: m, the scan's (or ``laser_max_range``).
        :returns: the total weight before normalising (for the recovery averages).
        """
        if len(beams) == 0 or len(self.particles) == 0:
            return 0.0
        w = self.weights * weight_factors(self.params, self.particles, likelihood_map, beams,
                                          range_max, self.converged)
        total = float(w.sum())
        if total > 0.0:
            self.weights = w / total
            self._update_recovery(total / len(w))  # pf.c: the average weight
        else:
            self.weights = np.full(len(w), 1.0 / len(w))
        return total

    def _update_converged(self):
        """Set :attr:`converged` as ``pf.c``'s ``pf_update_converged`` (unweighted mean)."""
        xy = self.particles[:, :2]
        self.converged = bool(len(xy)) and bool(
            np.all(np.abs(xy - xy.mean(axis=0)) <= CONVERGED_DISTANCE))

    def _update_recovery(self, w_avg):
        p = self.params
        if self.w_slow == 0.0:
            self.w_slow = w_avg
        else:
            self.w_slow += p.recovery_alpha_slow * (w_avg - self.w_slow)
        if self.w_fast == 0.0:
            self.w_fast = w_avg
        else:
            self.w_fast += p.recovery_alpha_fast * (w_avg - self.w_fast)

    def resample(self, likelihood_map=None):
        """Draw a new set by KLD sampling (module docstring); weights become uniform."""
        p = self.params
        n_max = p.max_particles
        random_p = 0.0
        if likelihood_map is not None and self.w_slow > 0.0:
            random_p = max(0.0, 1.0 - self.w_fast / self.w_slow)
        positions = (self.rng.random() + np.arange(n_max)) / n_max  # systematic
        picks = np.searchsorted(np.cumsum(self.weights), positions)
        picks = self.rng.permutation(np.minimum(picks, len(self.weights) - 1))
        drawn = self.particles[picks]
        if random_p > 0.0:
            swap = self.rng.random(n_max) < random_p
            if swap.any():
                drawn[swap] = likelihood_map.random_free_poses(int(swap.sum()), self.rng)
        # the smallest n with n >= kld_limits(bins among the first n): the k-th new bin
        # appears at draw first[k - 1]; n = limit(k) qualifies when no new bin comes before it
        bins = _bins(drawn, np.full(n_max, 1.0 / n_max))
        lo = bins.min(axis=0)
        keys = np.ravel_multi_index((bins - lo).T, bins.max(axis=0) - lo + 1)
        _, first = np.unique(keys, return_index=True)  # one key per bin: 8x faster than rows
        first = np.sort(first)
        limits = kld_limits(np.arange(1, len(first) + 1), p)
        ends = np.append(first[1:], n_max)
        hit = np.flatnonzero(limits <= ends)
        count = int(max(limits[hit[0]], first[hit[0]] + 1)) if len(hit) else n_max
        count = max(count, p.min_particles)
        self.particles = drawn[:count].copy()
        self.weights = np.full(count, 1.0 / count)
        if random_p > 0.0:
            self.w_slow = self.w_fast = 0.0
        self._update_converged()

    def estimate(self):
        """
        Return ``(pose, covariance)``: the heaviest cluster's mean and the filter's covariance.

        :returns: pose (3,); covariance 3x3 (x, y from every particle, yaw from the circular
            spread), as ``pf_get_cluster_stats`` and amcl_node's ``getMaxWeightHyp``.
        """
        bins = _bins(self.particles, self.weights)
        lo = bins.min(axis=0)
        shape = bins.max(axis=0) - lo + 1
        grid = np.zeros(shape, dtype=bool)
        grid[tuple((bins - lo).T)] = True
        labels, _ = ndimage.label(grid, structure=np.ones((3, 3, 3)))
        cluster = labels[tuple((bins - lo).T)]
        totals = np.bincount(cluster, weights=self.weights)
        members = cluster == int(np.argmax(totals))
        w = self.weights[members] / self.weights[members].sum()
        pts = self.particles[members]
        yaw = math.atan2(np.sum(w * np.sin(pts[:, 2])), np.sum(w * np.cos(pts[:, 2])))
        pose = np.array([np.sum(w * pts[:, 0]), np.sum(w * pts[:, 1]), yaw])
        wa = self.weights
        mean_xy = wa @ self.particles[:, :2]
        dxy = self.particles[:, :2] - mean_xy
        cov = np.zeros((3, 3))
        cov[:2, :2] = (wa[:, None] * dxy).T @ dxy
        r = math.hypot(wa @ np.cos(self.particles[:, 2]), wa @ np.sin(self.particles[:, 2]))
        cov[2, 2] = -2.0 * math.log(max(r, 1e-12))
        return pose, cov


class Amcl:
    """
    The filter with Nav2 amcl's update rules: when to update, resample and publish.

    :param params: :class:`AmclParameters`.
    :param seed: the filter's random seed.
    :ivar map: the :class:`LikelihoodMap`, or None before a map arrives.
    :ivar initialized: True once a pose (or global localization) started the filter.
    """

    def __init__(self, params=None, seed=None):
        """Start with no map and no pose."""
        self.params = params or AmclParameters()
        self.filter = ParticleFilter(self.params, seed)
        self.map = None
        self._grid = None
        self.initialized = False
        self._odom = None  # odometry pose at the last filter update
        self._force = False
        self._resample_count = 0
        self.map_to_odom = None
        self.pose = None
        self.covariance = None

    def set_map(self, grid):
        """Use ``grid`` (:class:`~amr_description.nav.map_io.GridMap`) from now on."""
        self._grid = grid
        self.map = LikelihoodMap(grid, self.params.laser_likelihood_max_dist,
                                 self.params.freespace_downsampling)

    def update_parameters(self, values):
        """
        Take new parameter values at run time (upstream's ``dynamicParametersCallback``).

        Every field of :class:`AmclParameters` in ``values`` is used from the next scan on;
        the distance field is rebuilt when ``laser_likelihood_max_dist`` or
        ``freespace_downsampling`` changed. The particles are kept (upstream re-initialises
        its filter round the last pose of configure for a particle-count change); new
        particle limits apply at the next resampling.

        :param values: ``{name: value}``; other names are ignored.
        """
        names = set(AmclParameters.names())
        rebuild = any(values.get(n, getattr(self.params, n)) != getattr(self.params, n)
                      for n in ('laser_likelihood_max_dist', 'freespace_downsampling'))
        for name, value in values.items():
            if name in names:
                setattr(self.params, name, value)
        if rebuild and self.map is not None:
            self.set_map(self._grid)

    def set_initial_pose(self, pose, covariance):
        """Start the filter round ``pose`` (map frame) with a 3x3 ``covariance``."""
        self.filter.initialize(pose, covariance)
        self.initialized = True
        self._force = True
        self._odom = None

    def global_localization(self):
        """
        Spread the particles over the map's free space (``reinitialize_global_localization``).

        :raises ValueError: without a map, or with no free cell.
        """
        if self.map is None:
            raise ValueError('no map received yet')
        self.filter.initialize_uniform(self.map)
        self.initialized = True
        self._force = True

    def request_nomotion_update(self):
        """Make the next scan update the filter even without motion."""
        self._force = True

    def beams(self, ranges, angle_min, angle_increment, range_min, range_max, sensor_pose):
        """Return the model's beams and range limit (:func:`.laser_models.select_beams`)."""
        return select_beams(self.params, ranges, angle_min, angle_increment, range_min,
                            range_max, sensor_pose)

    def process(self, odom_pose, beams, range_max):
        """
        Run the filter for one scan taken at ``odom_pose``; return True when it updated.

        Motion is applied and the scan weighed when the odometry moved more than
        ``update_min_d`` along x or y, or turned more than ``update_min_a``, since the last
        update, or when an update is forced (a new pose, ``request_nomotion_update``);
        resampling follows every ``resample_interval`` updates. The pose and the map -> odom
        transform are recomputed after every update.
        """
        if not self.initialized or self.map is None:
            return False
        odom_pose = np.asarray(odom_pose, dtype=float)
        if self._odom is None:
            self._odom = odom_pose
            self._force = True
        d = odom_pose - self._odom
        d[2] = float(wrap(d[2]))
        p = self.params
        moved = abs(d[0]) > p.update_min_d or abs(d[1]) > p.update_min_d \
            or abs(d[2]) > p.update_min_a
        if not (moved or self._force):
            return False
        self.filter.move(self._odom, odom_pose)
        self._odom = odom_pose
        self._force = False
        self.filter.weigh(self.map, beams, range_max)
        self._resample_count += 1
        if self._resample_count % max(1, p.resample_interval) == 0:
            self.filter.resample(self.map if p.recovery_alpha_slow > 0 else None)
        self.pose, self.covariance = self.filter.estimate()
        self.map_to_odom = compose(self.pose, inverse(odom_pose))
        return True
