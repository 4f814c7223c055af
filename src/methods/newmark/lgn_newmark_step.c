/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * One step t_n -> t_n + h of the Newmark / generalized-alpha family on a Lie
 * group, for every kinematics variant (lgn_kinematics.c): IDA's IDAStep
 * shape, Predict -> Newton (lgn_newton.c) -> Complete. The state at t_n is
 * only overwritten in Complete, so a failed step leaves it intact.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_impl.h"

/* Per-step constants. */
LGNStepCoeffs lgnStepCoeffs(LGNMem mem, sunrealtype h)
{
  const sunrealtype *q = lgnData(mem->q);
  sunindextype i;
  LGNStepCoeffs c;
  c.h       = h;
  c.t1      = mem->tn + h;
  c.beta_p  = (SUN_RCONST(1.0) - mem->alpha_m) /
              (h * h * mem->beta * (SUN_RCONST(1.0) - mem->alpha_f));
  c.gamma_p = mem->gamma / (h * mem->beta);
  c.scale   = mem->beta * h * h;
  c.qscale  = SUN_RCONST(1.0);
  c.hmat    = h;
  for (i = 0; i < mem->nq; i++) c.qscale = SUNMAX(c.qscale, fabs(q[i]));
  c.qscale = lgnMaxAll(mem, c.qscale); /* the same Newton test on every rank */
  return c;
}

/* GGL (dense A only, lgn_ls.c): B(q_n, t_n), the normals of the step's
 * correction s = sigma + B(q_n)^T nu (doc/theory.md §7.1), once per step:
 * kept over the attempts from the same t_n (a committed step or a new
 * state drops it). */
static int GGLStartJacobian(LGNMem mem)
{
  const sunindextype len = mem->m * mem->nv;
  int ret;
  if (mem->ggl_Bn == NULL || mem->ggl_Bn_valid) return LGN_SUCCESS;
  ret = lgnEvalConstraintJacobian(mem, mem->tn, mem->q, mem->Bmat);
  if (ret != LGN_SUCCESS) return ret;
  memcpy(mem->ggl_Bn, SM_DATA_D(mem->Bmat), (size_t)len * sizeof(sunrealtype));
  mem->ggl_Bn_valid = SUNTRUE;
  return LGN_SUCCESS;
}

/* Predictor. LGN_PREDICTOR_ZERO: sigma_ddot = 0, lambda = lambda_n.
 * LGN_PREDICTOR_EXTRAPOLATE (for the variants that allow it) guesses
 * vdot_{n+1} and lambda_{n+1} by linear extrapolation; the variant maps the
 * guess into the chart of the step or scales the increment (its predict
 * operation). */
static int Predict(LGNMem mem, const LGNStepCoeffs *c)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  const sunrealtype am = mem->alpha_m, af = mem->alpha_f;
  const sunrealtype *vdot = lgnData(mem->vdot), *a = mem->a_step;
  const sunbooleantype extrapolate = mem->predictor == LGN_PREDICTOR_EXTRAPOLATE &&
                                     mem->kin->extrapolates;
  const sunrealtype r = mem->h_prev > SUN_RCONST(0.0) ? c->h / mem->h_prev
                                                      : SUN_RCONST(0.0);
  sunrealtype *acc = mem->work2_nv; /* guess of vdot_{n+1} */
  int flag = GGLStartJacobian(mem);

  if (flag != LGN_SUCCESS) return flag;
  mem->kin->bind(mem);
  for (i = 0; i < nv; i++) {
    mem->a_pred[i] = (af * vdot[i] - am * a[i]) / (SUN_RCONST(1.0) - am);
    acc[i] = extrapolate ? vdot[i] + r * (vdot[i] - mem->vdot_prev[i]) : SUN_RCONST(0.0);
    mem->sigma_ddot[i] = acc[i];
  }
  if (m > 0) {
    sunrealtype *l1 = lgnData(mem->lambda1);
    const sunrealtype *l0 = lgnData(mem->lambda);
    for (i = 0; i < m; i++)
      l1[i] = extrapolate ? l0[i] + r * (l0[i] - mem->lambda_prev[i]) : l0[i];
  }
  lgnFormIncrement(mem, c);
  return mem->kin->predict(mem, c, acc, extrapolate);
}

/* After convergence: a_{n+1} (with the chart shift of the exact variant,
 * doc/theory.md §4), then commit the new state. */
void lgnStepComplete(LGNMem mem, const LGNStepCoeffs *c)
{
  sunindextype i, nv = mem->nv;
  const sunrealtype ca = (SUN_RCONST(1.0) - mem->alpha_f) /
                         (SUN_RCONST(1.0) - mem->alpha_m);
  sunrealtype *a = lgnData(mem->a), *vdot1 = lgnData(mem->vdot1);

  for (i = 0; i < nv; i++)
    a[i] = mem->a_pred[i] + ca * mem->sigma_ddot[i] +
           (vdot1[i] - mem->sigma_ddot[i]);
  /* keep vdot_n, lambda_n for the extrapolating predictor */
  memcpy(mem->vdot_prev, lgnData(mem->vdot), (size_t)nv * sizeof(sunrealtype));
  if (mem->m > 0)
    memcpy(mem->lambda_prev, lgnData(mem->lambda), (size_t)mem->m * sizeof(sunrealtype));
  lgnCommitStep(mem, c);
}

/* The iterate becomes the state at t_{n+1} (every family): q, v, vdot,
 * lambda swap with the iterate, which keeps the step's start for the
 * dense output. */
void lgnCommitStep(LGNMem mem, const LGNStepCoeffs *c)
{
  N_Vector tmp;
  mem->h_prev = c->h;
  mem->ggl_Bn_valid = SUNFALSE; /* q_n moves on */
  tmp = mem->q;    mem->q = mem->q1;       mem->q1 = tmp;
  tmp = mem->v;    mem->v = mem->v1;       mem->v1 = tmp;
  tmp = mem->vdot; mem->vdot = mem->vdot1; mem->vdot1 = tmp;
  if (mem->m > 0) {
    tmp = mem->lambda; mem->lambda = mem->lambda1; mem->lambda1 = tmp;
  }
  mem->pstart_pending = SUNFALSE;
  mem->tprev = mem->tn;
  mem->tn    = c->t1;
  mem->hlast = c->h;
  mem->nst++;
  mem->dense_valid = SUNTRUE; /* q1, v1, vdot1 now hold the step's start */
  /* ghost bodies: the copies took the owners' corrections; now they take
   * the owners' values exactly (lgn_ghosts.c) */
  lgnGhostsRefreshState(mem);
}

/* Undo a perturbed start (v_0, a_0 from saved) after a failed attempt. */
static void RestoreStart(LGNMem mem, const sunrealtype *saved)
{
  memcpy(lgnData(mem->v), saved, (size_t)mem->nv * sizeof(sunrealtype));
  memcpy(lgnData(mem->a), saved + mem->nv, (size_t)mem->nv * sizeof(sunrealtype));
  mem->pstart_done    = SUNFALSE;
  mem->pstart_pending = SUNFALSE;
}

/* An attempt that converged was rejected (the error test): undo its
 * perturbed start, if it made one, so that the state is as before. */
void lgnStepRejected(LGNMem mem)
{
  if (mem->pstart_pending) RestoreStart(mem, mem->dense_work);
}

/* Predict and Newton, with one retry with a fresh matrix when modified
 * Newton failed with an old one. Writes only the iterate: the state at t_n
 * is untouched, whatever the outcome. No message: the caller decides what
 * a failure means (fixed step: an error; error control: a retry). */
int lgnStepAttempt(LGNMem mem, const LGNStepCoeffs *c)
{
  sunbooleantype used_old = SUNFALSE;
  int flag;

  sunbooleantype perturbed = SUNFALSE;
  sunrealtype *saved = mem->dense_work; /* free while dense_valid is false */

  mem->dense_valid = SUNFALSE; /* the iterate overwrites the last step's start */
  if (lgnPerturbedStartDue(mem)) {
    /* once, with the first step size tried (lgn_consistent_ic.c): v_0 and a_0 change
     * here; saved, so that a failed attempt leaves the state as it was and
     * the next attempt perturbs again with its own h */
    memcpy(saved, lgnData(mem->v), (size_t)mem->nv * sizeof(sunrealtype));
    memcpy(saved + mem->nv, lgnData(mem->a), (size_t)mem->nv * sizeof(sunrealtype));
    mem->pstart_done    = SUNTRUE;
    mem->pstart_pending = SUNTRUE; /* until the step is completed */
    perturbed = SUNTRUE;
    flag = lgnAgree(mem, lgnPerturbedStart(mem, c->h));
    if (flag != LGN_SUCCESS) {
      RestoreStart(mem, saved);
      return flag;
    }
  }
  flag = lgnAgree(mem, Predict(mem, c));
  if (flag == LGN_SUCCESS) flag = lgnNewton(mem, c, SUNFALSE, &used_old);
  if (flag == LGN_CONV_FAILURE && used_old) {
    /* modified Newton failed with an old matrix: once more with a fresh one */
    mem->nrestart++;
    flag = lgnAgree(mem, Predict(mem, c));
    if (flag == LGN_SUCCESS) flag = lgnNewton(mem, c, SUNTRUE, &used_old);
  }
  if (flag != LGN_SUCCESS) {
    mem->nfails++;
    if (perturbed) RestoreStart(mem, saved);
  }
  return flag;
}

/* Refuse a step that cannot advance t in floating point (t + h == t):
 * it would "succeed" without moving; and a step so small that the scaling
 * of the equations by h^2 (the index-3 rows, BDF's 1/c0^2) leaves the
 * floating-point range: below the cube root of the smallest normal number
 * (about 3e-103), where a step of 1e-150 returned velocities of 1e133 as
 * success (found by the fuzz target). */
int lgnCheckProgress(LGNMem mem, sunrealtype h)
{
  const sunrealtype hfloor = SUNRpowerR(SUN_SMALL_REAL, SUN_RCONST(1.0) / SUN_RCONST(3.0));
  if (fabs(h) < hfloor) {
    mem->hnext = SUN_RCONST(0.0); /* error control estimates anew next time */
    LGN_ERROR(mem, LGN_STEP_TOO_SMALL,
              MSG_TIME "the step size h = %g is below %g: the scaling of the "
              "equations by h^2 would leave the floating-point range.",
              (double)mem->tn, (double)h, (double)hfloor);
    return LGN_STEP_TOO_SMALL;
  }
  if (mem->tn + h != mem->tn) return LGN_SUCCESS;
  /* h collapsed (a callback failing recoverably from some t on): the next
   * LGNSolve starts error control anew (LGNSetInitStep, or the estimate) */
  mem->hnext = SUN_RCONST(0.0);
  LGN_ERROR(mem, LGN_STEP_TOO_SMALL,
            MSG_TIME "the step size h = %g cannot advance t in floating point "
            "(t + h == t).", (double)mem->tn, (double)h);
  return LGN_STEP_TOO_SMALL;
}

/* A step of the fixed size h (LGN_STEP_FIXED). */
int lgnStep(LGNMem mem, sunrealtype h)
{
  LGNStepCoeffs c = lgnStepCoeffs(mem, h);
  int flag = lgnCheckProgress(mem, h);
  if (flag != LGN_SUCCESS) return flag;

  mem->a_step    = lgnData(mem->a);
  lgnFixedNewtonTolerances(mem);
  flag = lgnStepAttempt(mem, &c);
  if (flag == LGN_CONV_FAILURE)
    LGN_ERROR(mem, LGN_CONV_FAILURE,
              MSG_TIME "the Newton iteration failed to converge (diverged or "
              "more than %d iterations) with h = %g (the state at t is kept).",
              (double)mem->tn, mem->maxcor, (double)h);
  if (flag != LGN_SUCCESS) return flag;
  lgnStepComplete(mem, &c);
  return LGN_SUCCESS;
}
