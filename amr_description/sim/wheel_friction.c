// Copyright 2026 The amr_description Authors
// Licensed under the Apache License, Version 2.0
//
// Coulomb friction between wheels and the ground, applied at every physics step.
//
// MuJoCo's soft contact friction on a sliding wheel is neither at mu N nor opposite the
// slip (docs/simulation.md, "Why the slide is not a matter of stiffness alone"), and a
// skid-steer base then slides outwards on arcs. Here the wheel-ground contact pairs are
// frictionless in MuJoCo (condim 1: the normal force only) and each wheel gets
//
//     F = -mu N v / max(|v|, eps)
//
// at its contact point: v the contact point's velocity in the ground plane, N the normal
// force of the wheel's contact in the previous step, mu the pair's friction coefficient.
// Above eps that is Coulomb's law (Wong, Theory of Ground Vehicles, skid steering; the model
// of amr_description/core/skid_steer.py); below eps a viscous regularisation, stable while
// mu N dt / eps stays below the contact's effective mass. The force is added to
// qfrc_passive between mj_step1 and mj_step2, so nothing persists in mjData.
//
// Built by scripts/setup against the headers and library of the installed mujoco wheel;
// amr_description/sim/wheel_friction.py loads it (and has the same law in numpy without it).

#include <math.h>
#include <mujoco/mujoco.h>

// Return the flagged pair whose two geoms a contact joins, or -1.
static int flagged_pair(const mjModel * m, const mjContact * con, const int * pair_flag)
{
  for (int p = 0; p < m->npair; p++) {
    if (pair_flag[p] &&
      ((m->pair_geom1[p] == con->geom[0] && m->pair_geom2[p] == con->geom[1]) ||
      (m->pair_geom1[p] == con->geom[1] && m->pair_geom2[p] == con->geom[0])))
    {
      return p;
    }
  }
  return -1;
}

// Step the model nstep times with Coulomb friction on the flagged contact pairs.
//
// pair_flag[p] != 0 for the wheel-ground pairs (index into m->pair_*); normal[p] holds each
// pair's normal force from the step before (N, updated here). Returns the number of steps.
int amr_wheel_friction_step(const mjModel * m, mjData * d, int nstep, const int * pair_flag,
  double * normal, double eps)
{
  for (int step = 0; step < nstep; step++) {
    mj_step1(m, d);
    for (int i = 0; i < d->ncon; i++) {
      const mjContact * con = d->contact + i;
      int pair = flagged_pair(m, con, pair_flag);
      if (pair < 0 || normal[pair] <= 0) {
        continue;
      }
      // the wheel is the pair's non-ground geom: geom2 (World adds the ground as geom1)
      int geom = m->pair_geom2[pair];
      int body = m->geom_bodyid[geom];
      mjtNum vel[6];
      mj_objectVelocity(m, d, mjOBJ_GEOM, geom, vel, 0);
      mjtNum arm[3], spin[3], v[3];
      mju_sub3(arm, con->pos, d->geom_xpos + 3 * geom);
      mju_cross(spin, vel, arm);
      mju_add3(v, vel + 3, spin);
      // the slip in the contact's tangent plane (normal along the contact frame's first row)
      mjtNum along = mju_dot3(v, con->frame);
      mjtNum slip[3];
      mju_addScl3(slip, v, con->frame, -along);
      mjtNum speed = mju_norm3(slip);
      mjtNum scale = -m->pair_friction[5 * pair] * normal[pair] / fmax(speed, eps);
      mjtNum force[3], torque[3] = {0, 0, 0};
      mju_scl3(force, slip, scale);
      mj_applyFT(m, d, force, torque, con->pos, body, d->qfrc_passive);
    }
    mj_step2(m, d);
    for (int p = 0; p < m->npair; p++) {
      normal[p] = 0;
    }
    for (int i = 0; i < d->ncon; i++) {
      int pair = flagged_pair(m, d->contact + i, pair_flag);
      if (pair >= 0) {
        mjtNum f[6];
        mj_contactForce(m, d, i, f);
        normal[pair] += f[0];
      }
    }
  }
  return nstep;
}
