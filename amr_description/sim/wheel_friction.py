# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Coulomb friction between wheels and the ground at every physics step (no rclpy).

A wheel whose ``<mujoco><link>`` asks for ``ground_friction="coulomb"`` touches the ground
through a frictionless MuJoCo contact pair (``condim`` 1: the normal force only), and gets,
between ``mj_step1`` and ``mj_step2`` of every step, the force

    ``F = -mu N v / max(|v|, eps)``

at its contact point, added to ``qfrc_passive``: ``v`` the contact point's velocity in the
contact's tangent plane, ``N`` the pair's normal force in the step before, ``mu`` the pair's
sliding friction. Above ``eps`` this is Coulomb's law for a sliding contact (the force at
mu N, opposite the slip: Wong, *Theory of Ground Vehicles*, skid steering; the model of
:mod:`amr_description.core.skid_steer`), which MuJoCo's soft contact friction does not give
(docs/simulation.md, "Why the slide is not a matter of stiffness alone"); below ``eps`` it is
viscous, which keeps the explicit force stable at a 1 ms step.

The loop runs in C (amr_description/sim/wheel_friction.c, built by scripts/setup against the
installed mujoco wheel: about 4 % over ``mj_step`` for one robot); without the library the
same law runs here in numpy, one Python call per step, with one warning.
"""

import ctypes
import logging
import math
import os

import mujoco
import numpy as np

EPS = 0.02
"""m/s: slip speed below which the friction is viscous (``mu N / EPS`` N s/m). Stable while
``mu N dt / EPS`` stays below the contact's effective mass: 0.85 kg for a 17 N wheel load at
1 ms, against the 1.75 kg of a quarter of the 7 kg tutorial robot."""

LIBRARY = 'libamr_wheel_friction.so'
"""File name of the C loop that scripts/setup builds into build/wheel_friction/."""

_LOG = logging.getLogger(__name__)


def library_path():
    """Return where scripts/setup puts the C loop: build/wheel_friction/ of the repository."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
    return os.path.join(root, 'build', 'wheel_friction', LIBRARY)


def load_library(path=None):
    """
    Return the C loop ``amr_wheel_friction_step`` as a ctypes function, or None.

    :param path: the shared library; None: :func:`library_path`.
    """
    path = path or library_path()
    if not os.path.exists(path):
        return None
    try:
        function = ctypes.CDLL(path).amr_wheel_friction_step
    except (OSError, AttributeError) as exc:
        _LOG.warning('wheel friction: cannot load %s (%s); using numpy', path, exc)
        return None
    function.restype = ctypes.c_int
    function.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p,
                         ctypes.c_void_p, ctypes.c_double]
    return function


class CoulombWheels:
    """
    Step a model whose flagged wheel-ground pairs have Coulomb friction (module docstring).

    :param library: the C loop (:func:`load_library`), False for none (numpy), None to load
        it from :func:`library_path`.
    :param eps: m/s, :data:`EPS`.
    :ivar active: True while at least one pair is flagged (set by :meth:`configure`).
    """

    _warned = False

    def __init__(self, library=None, eps=EPS):
        """Load the C loop; nothing is flagged until :meth:`configure`."""
        self.function = load_library() if library is None else (library or None)
        self.eps = float(eps)
        self.flags = np.zeros(0, dtype=np.int32)
        self.normal = np.zeros(0)
        self.active = False  # at least one pair flagged (World.step's choice of loop)

    def configure(self, model, pair_names):
        """
        Flag the pairs of ``model`` named in ``pair_names``; forget the normal forces.

        The wheel must be each pair's ``geom2`` (the ground ``geom1``), as
        :meth:`~amr_description.sim.world.World.spawn` adds them.

        :param model: the compiled ``mujoco.MjModel``.
        :param pair_names: names of the pairs with Coulomb friction (a collection of str).
        """
        names = set(pair_names)
        self.flags = np.array([model.pair(p).name in names for p in range(model.npair)],
                              dtype=np.int32)
        self.normal = np.zeros(model.npair)
        self.active = bool(self.flags.any())
        if self.active and self.function is None and not CoulombWheels._warned:
            CoulombWheels._warned = True
            _LOG.warning('wheel friction: %s not built (scripts/setup builds it); the Coulomb '
                         'wheel friction runs in numpy, several times slower', library_path())

    def reset(self):
        """Forget the normal forces of the last step (after a reset of the data)."""
        self.normal[:] = 0.0

    def step(self, model, data, nstep):
        """
        Advance ``nstep`` physics steps with the friction forces.

        :param model: ``mujoco.MjModel`` (the one given to :meth:`configure`).
        :param data: its ``mujoco.MjData``.
        :param nstep: int >= 1.
        """
        if self.function is not None:
            self.function(model._address, data._address, int(nstep), self.flags.ctypes.data,
                          self.normal.ctypes.data, self.eps)
            return
        for _ in range(int(nstep)):
            mujoco.mj_step1(model, data)
            self._apply(model, data)
            mujoco.mj_step2(model, data)
            self._measure_normals(model, data)

    def _pair_of(self, model, contact):
        """Return the flagged pair index of a contact, or -1."""
        g1, g2 = int(contact.geom[0]), int(contact.geom[1])
        for p in np.flatnonzero(self.flags):
            a, b = int(model.pair_geom1[p]), int(model.pair_geom2[p])
            if (a, b) == (g1, g2) or (a, b) == (g2, g1):
                return int(p)
        return -1

    def _apply(self, model, data):
        """Add each flagged contact's friction force to ``qfrc_passive`` (numpy path)."""
        velocity = np.zeros(6)
        for i in range(data.ncon):
            contact = data.contact[i]
            pair = self._pair_of(model, contact)
            if pair < 0 or self.normal[pair] <= 0.0:
                continue
            geom = int(model.pair_geom2[pair])
            mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_GEOM, geom, velocity, 0)
            v = velocity[3:] + np.cross(velocity[:3], contact.pos - data.geom_xpos[geom])
            normal = contact.frame[:3]
            slip = v - np.dot(v, normal) * normal
            scale = -model.pair_friction[pair, 0] * self.normal[pair] / max(
                math.sqrt(float(np.dot(slip, slip))), self.eps)
            mujoco.mj_applyFT(model, data, slip * scale, np.zeros(3), contact.pos,
                              int(model.geom_bodyid[geom]), data.qfrc_passive)

    def _measure_normals(self, model, data):
        """Keep each flagged pair's normal force of the step just taken (numpy path)."""
        self.normal[:] = 0.0
        force = np.zeros(6)
        for i in range(data.ncon):
            pair = self._pair_of(model, data.contact[i])
            if pair >= 0:
                mujoco.mj_contactForce(model, data, i, force)
                self.normal[pair] += force[0]
