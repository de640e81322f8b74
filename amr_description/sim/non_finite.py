# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
Where a MuJoCo state went non-finite: the body to name in the one-line report.

``mj_step`` checks qpos, qvel and qacc; on a non-finite (or huge) value it counts a warning
(``mjWARN_BADQPOS/BADQVEL/BADQACC``) and resets the data. The simulation watches those
counters (:data:`BAD_STATE_WARNINGS`) and, on a new one, names the body with
:func:`first_bad_body`.
"""

import math

import mujoco
import numpy as np

_BAD_QPOS = int(mujoco.mjtWarning.mjWARN_BADQPOS)
_BAD_QVEL = int(mujoco.mjtWarning.mjWARN_BADQVEL)
_BAD_QACC = int(mujoco.mjtWarning.mjWARN_BADQACC)

BAD_STATE_WARNINGS = (_BAD_QPOS, _BAD_QVEL, _BAD_QACC)
"""The indices of ``data.warning`` that count bad qpos, qvel and qacc."""


def first_bad_body(model, data):
    """
    Return the name of the first body with a non-finite state (``'?'`` if none).

    Looks at body positions and velocities, then ``qpos``, then the joint or degree of
    freedom MuJoCo's last bad-state warning names.

    :param model: the ``mujoco.MjModel``.
    :param data: its ``mujoco.MjData``.
    """
    for i in range(1, model.nbody):
        if not (np.isfinite(data.xpos[i]).all() and np.isfinite(data.cvel[i]).all()):
            return model.body(i).name
    for i in range(model.nq):
        if not math.isfinite(data.qpos[i]):
            joint = max(j for j in range(model.njnt) if model.jnt_qposadr[j] <= i)
            return model.body(int(model.jnt_bodyid[joint])).name
    for kind in (_BAD_QPOS, _BAD_QVEL, _BAD_QACC):
        if data.warning[kind].number:
            index = int(data.warning[kind].lastinfo)
            if kind == _BAD_QPOS and 0 <= index < model.nq:
                joint = max(j for j in range(model.njnt) if model.jnt_qposadr[j] <= index)
                return model.body(int(model.jnt_bodyid[joint])).name
            if 0 <= index < model.nv:
                return model.body(int(model.dof_bodyid[index])).name
    return '?'
