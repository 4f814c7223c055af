/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * What LGNSolve and LGNGetDky return (doc/user-guide.md §8.5): the output
 * (t, q, v) of a step end, a stop time, an event or an interpolated tout,
 * and the accelerations and multipliers that belong to it.
 *
 * Projected outputs (LGNSetProjectOutputs: by default all, the step ends
 * too; LGN_PROJECT_INTERPOLATED those between steps): q onto Phi(q, t) = 0
 * by Newton on the group with minimum-norm steps in the metric of M,
 *   [[M, B^T], [B, 0]] (dq, mu) = (0, -Phi(q, t)),  q <- q o exp(dq),
 * down to roundoff (lgnProjectQAt, lgn_consistent_ic.c), then v onto B(q, t) v + Phi_t
 * = 0 at the projected q,
 *   [[M, B^T], [B, 0]] (dv, mu) = (0, -(B v + Phi_t)),  v <- v + dv.
 * Only the returned q and v change: the integrator goes on from its own
 * state.
 *
 * Consistent outputs (LGNSetConsistentOutputs, default on): vdot and lambda
 * of the index-1 form of the DAE at the output's (t, q, v),
 *   [[M, B^T], [B, 0]] (vdot, lambda) = (-g(q, v, t), -z(q, v, t)),
 * z = d/dt (B v + Phi_t) - B vdot (the curvature with its time terms), the
 * system LGNCalcIC solves at the start. They are as accurate as q and v,
 * i.e. to the tolerance, in every method and constraint form; the step's
 * own multipliers are not (generalized-alpha's lambda_{n+1} carries O(h)
 * errors after a change of h, a landing step multiplies them, and no
 * method's error test measures them). With the projection on, both share
 * the factorisation at the projected q.
 *
 * The iterate slots q1, v1, vdot1 and lambda1, which hold the last step's
 * start for the dense output, are kept in out_save meanwhile; the
 * factorised matrix in A is the saddle-point matrix afterwards (a modified
 * Newton iteration sets up anew).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include "lgn_impl.h"

/* The iterate slots q1, v1, vdot1, lambda1 into out_save, or back. */
static void KeepSlots(LGNMem mem, sunbooleantype restore)
{
  const size_t nq = (size_t)mem->nq, nv = (size_t)mem->nv, m = (size_t)mem->m;
  sunrealtype *s = mem->out_save;
  sunrealtype *slot[4];
  size_t len[4], k;
  slot[0] = lgnData(mem->q1);    len[0] = nq;
  slot[1] = lgnData(mem->v1);    len[1] = nv;
  slot[2] = lgnData(mem->vdot1); len[2] = nv;
  slot[3] = m > 0 ? lgnData(mem->lambda1) : NULL; len[3] = m;
  for (k = 0; k < 4; k++) {
    if (len[k] == 0) continue;
    if (restore)
      memcpy(slot[k], s, len[k] * sizeof(sunrealtype));
    else
      memcpy(s, slot[k], len[k] * sizeof(sunrealtype));
    s += len[k];
  }
}

/* max_i |x_i| over the ranks (NaN counts as the largest). */
static sunrealtype MaxAbsAll(LGNMem mem, const sunrealtype *x, sunindextype n)
{
  sunrealtype r = SUN_RCONST(0.0);
  sunindextype i;
  for (i = 0; i < n; i++)
    if (!(fabs(x[i]) <= r)) r = fabs(x[i]);
  return lgnMaxAll(mem, r);
}

/* The saddle-point matrix at (t, q, v), factorised (message on failure). */
static int FactorAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  int flag = lgnEvalAt(mem, t, q, v);
  if (flag != LGN_SUCCESS) return flag;
  flag = lgnSaddlePointFactor(mem, t);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the output's accelerations and multipliers: [[M, B^T], "
              "[B, 0]] is singular or its factorisation failed (check M and B "
              "at the output).%s", (double)t,
              flag == LGN_LSETUP_FAIL ? mem->diag_text : "");
    return LGN_IC_FAIL;
  }
  return LGN_SUCCESS;
}

/* A solve with the factorised matrix (message on failure). */
static int BackSolve(LGNMem mem, sunrealtype t)
{
  int flag = lgnSaddlePointBackSolve(mem);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the output's saddle-point solve failed or gave NaN / "
              "Inf.", (double)t);
    return LGN_IC_FAIL;
  }
  return LGN_SUCCESS;
}

/* v onto B(q, t) v + Phi_t = 0 with the factorisation at (t, q) (header
 * comment); linear, so one correction, a second only when roundoff left
 * more than 100 eps max(1, |v|_inf). */
static int ProjectV(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  const sunindextype nv = mem->nv, m = mem->m;
  sunrealtype *rhs = lgnData(mem->rhs), *vd = lgnData(v), *r = mem->work_m;
  const sunrealtype *sol = lgnData(mem->sol);
  sunindextype i;
  int it, flag;
  for (it = 0; it < 2; it++) {
    /* Bmat holds B(q, t) (lgnEvalAt) */
    flag = lgnAgree(mem, lgnConstraintVelocity(mem, t, q, mem->Bmat, vd, r));
    if (flag != LGN_SUCCESS) return flag;
    if (MaxAbsAll(mem, r, m) <=
        SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * SUNMAX(SUN_RCONST(1.0), N_VMaxNorm(v)))
      break;
    for (i = 0; i < nv; i++) rhs[i] = SUN_RCONST(0.0);
    for (i = 0; i < m; i++) rhs[nv + i] = -r[i];
    flag = BackSolve(mem, t);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < nv; i++) vd[i] += sol[i];
  }
  return LGN_SUCCESS;
}

/* The projection (when on) and the consistent vdot and lambda (into vdot,
 * lambda when vdot is not NULL; lambda may be NULL), with the slots kept. */
static int Compute(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   sunbooleantype project, sunrealtype *vdot, sunrealtype *lambda)
{
  const sunindextype nv = mem->nv, m = mem->m;
  int flag = LGN_SUCCESS;

  if (project) {
    sunrealtype qs = SUN_RCONST(1.0);
    sunindextype i;
    for (i = 0; i < mem->nq; i++) qs = SUNMAX(qs, fabs(lgnData(q)[i]));
    qs   = lgnMaxAll(mem, qs);
    /* q: to roundoff, one Newton iteration at least (the same work on
     * any number of ranks); a stall is accepted only near it (1e4 eps |q|) */
    flag = lgnProjectQAt(mem, t, q, v, SUN_RCONST(1.0e4) * SUN_UNIT_ROUNDOFF * qs, 1,
                         "the projection of the output q");
  }
  if (flag == LGN_SUCCESS) flag = FactorAt(mem, t, q, v);
  if (flag == LGN_SUCCESS && project) {
    flag = ProjectV(mem, t, q, v);
    /* g at the projected v (M and B, and so the factorisation, are the same) */
    if (flag == LGN_SUCCESS && vdot != NULL) flag = lgnEvalAt(mem, t, q, v);
  }
  if (flag == LGN_SUCCESS && vdot != NULL) {
    flag = lgnIndex1Rhs(mem, t);
    if (flag == LGN_SUCCESS) flag = BackSolve(mem, t);
    if (flag == LGN_SUCCESS) {
      memcpy(vdot, lgnData(mem->sol), (size_t)nv * sizeof(sunrealtype));
      if (m > 0 && lambda != NULL)
        memcpy(lambda, lgnData(mem->sol) + nv, (size_t)m * sizeof(sunrealtype));
    }
  }
  return flag;
}

/* Compute with the slots kept, counted; a recoverable callback failure
 * becomes LGN_REPTD_CALLBACK_ERR: there is no step to retry. */
static int ComputeKept(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                       sunbooleantype project, sunrealtype *vdot, sunrealtype *lambda)
{
  int flag;
  KeepSlots(mem, SUNFALSE);
  flag = Compute(mem, t, q, v, project, vdot, lambda);
  KeepSlots(mem, SUNTRUE);
  mem->nout++;
  if (flag == LGN_RECOVERABLE) {
    LGN_ERROR(mem, LGN_REPTD_CALLBACK_ERR,
              MSG_TIME "a callback failed recoverably at the output.", (double)t);
    flag = LGN_REPTD_CALLBACK_ERR;
  }
  return flag;
}

/* Is the output at t projected: between the ends of the last step (or at
 * any t with LGN_PROJECT_ALL), with constraints. */
static sunbooleantype Projects(LGNMem mem, sunrealtype t)
{
  const sunbooleantype end = t == mem->tn || (mem->dense_valid && t == mem->tprev);
  return (sunbooleantype)(mem->m > 0 && (mem->out_project == LGN_PROJECT_ALL ||
                                         (mem->out_project == LGN_PROJECT_INTERPOLATED && !end)));
}

/* The work space and matrices an output needs (made by LGNSolve). */
static sunbooleantype Ready(LGNMem mem)
{
  return (sunbooleantype)(mem->work_done && mem->mat_done && mem->out_save != NULL);
}

/* The output (t, q, v) that LGNSolve returns: projected in place (when
 * due), and its vdot and lambda into out_vdot, out_lambda (when on;
 * out_valid). */
int lgnOutputAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  const sunbooleantype project = Projects(mem, t);
  int flag;
  if (!Ready(mem) || !(project || mem->out_consistent)) {
    mem->out_valid = mem->out_lvalid = SUNFALSE;
    return LGN_SUCCESS;
  }
  /* out_vdot, out_lambda are written only when all went well: on a
   * failure the getters keep the last output's values */
  flag = ComputeKept(mem, t, q, v, project, mem->out_consistent ? mem->out_vdot : NULL,
                     mem->out_lambda);
  if (flag != LGN_SUCCESS) return flag;
  mem->out_valid = mem->out_consistent;
  if (mem->out_consistent) mem->out_t = t;
  mem->out_lvalid = SUNFALSE;
  if (project) {
    /* kept: a failed LGNSolve that takes no step returns them again */
    if (mem->out_lq == NULL) mem->out_lq = N_VClone(q);
    if (mem->out_lv == NULL) mem->out_lv = N_VClone(v);
    if (mem->out_lq != NULL && mem->out_lv != NULL) {
      N_VScale(SUN_RCONST(1.0), q, mem->out_lq);
      N_VScale(SUN_RCONST(1.0), v, mem->out_lv);
      mem->out_lt     = t;
      mem->out_lvalid = SUNTRUE;
    }
  }
  return flag;
}

/* LGNGetDky's value at t of the last step: the dense output, projected
 * (k = 0, 1) and made consistent (k = 2) as LGNSolve's outputs are, so that
 * LGNGetDky at a returned time gives what LGNSolve and LGNGetAcceleration
 * gave. The last output's values (the getters') stay as they are. */
int lgnOutputDky(LGNMem mem, sunrealtype t, int k, N_Vector dky)
{
  const sunbooleantype project = Projects(mem, t);
  int flag;
  if (!Ready(mem) || !(k == 2 ? mem->out_consistent : project))
    return lgnDenseOutput(mem, t, k, lgnData(dky));
  if (mem->out_q == NULL) mem->out_q = N_VClone(mem->q);
  if (mem->out_v == NULL) mem->out_v = N_VClone(mem->v);
  flag = mem->out_q == NULL || mem->out_v == NULL ? LGN_MEM_FAIL : LGN_SUCCESS;
  if (flag != LGN_SUCCESS) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
  flag = lgnAgree(mem, flag);
  if (flag == LGN_SUCCESS) flag = lgnDenseOutput(mem, t, 0, lgnData(mem->out_q));
  if (flag == LGN_SUCCESS) flag = lgnDenseOutput(mem, t, 1, lgnData(mem->out_v));
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  {
    /* a getter: its evaluations and solves are not the steps' statistics
     * (LGNGetNum* and LGNGetDky in any order give the same numbers) */
    const long int nre = mem->nre, nje = mem->nje, ndq = mem->ndq, nlsetup = mem->nlsetup,
                   nlsolve = mem->nlsolve, nout = mem->nout;
    flag = ComputeKept(mem, t, mem->out_q, mem->out_v, project, k == 2 ? lgnData(dky) : NULL,
                       NULL);
    mem->nre     = nre;
    mem->nje     = nje;
    mem->ndq     = ndq;
    mem->nlsetup = nlsetup;
    mem->nlsolve = nlsolve;
    mem->nout    = nout;
  }
  if (flag == LGN_SUCCESS && k < 2)
    N_VScale(SUN_RCONST(1.0), k == 0 ? mem->out_q : mem->out_v, dky);
  return flag;
}

/* =============================================================================
 * The multipliers in the error test (LGNSetMultiplierErrorControl)
 * ===========================================================================*/

/* The step's multipliers lambda1 against the consistent ones lambda_c of
 * the index-1 system at its own (t1, q1, v1) (not projected):
 *   e_i = lambda1_i - lambda_c_i,  w_i = 1 / (atol_lambda + rtol |lambda_c_i|),
 *   |e_lambda| = sqrt( (1/m) sum_i (e_i w_i)^2 ),
 * the part of the step's multipliers its configuration does not account
 * for (generalized-alpha's O(1) error after a change of h, BDF's of its
 * order), as IDA's error test takes algebraic variables with
 * IDASetSuppressAlg(FALSE). */
int lgnMultiplierError(LGNMem mem, sunrealtype t1, sunrealtype *norm)
{
  const sunindextype m = mem->m;
  const sunrealtype *l1;
  sunrealtype sum[2] = {SUN_RCONST(0.0), SUN_RCONST(0.0)};
  sunindextype i;
  int flag;
  *norm = SUN_RCONST(0.0);
  mem->lambda_err = SUN_RCONST(0.0);
  if (!mem->lambda_errcon || m == 0 || mem->out_save == NULL) return LGN_SUCCESS;
  KeepSlots(mem, SUNFALSE); /* the iterate itself, not projected */
  flag = Compute(mem, t1, mem->q1, mem->v1, SUNFALSE, mem->dense_work, mem->out_lwork);
  KeepSlots(mem, SUNTRUE);
  if (flag != LGN_SUCCESS) return flag;
  l1 = lgnData(mem->lambda1);
  for (i = 0; i < m; i++) {
    const sunrealtype e = (l1[i] - mem->out_lwork[i]) /
                          (mem->lambda_atol + mem->rtol * fabs(mem->out_lwork[i]));
    sum[0] += e * e;
  }
  sum[1] = (sunrealtype)m;
  lgnSumAll(mem, sum, 2);
  *norm = sqrt(sum[0] / SUNMAX(sum[1], SUN_RCONST(1.0)));
  mem->lambda_err = *norm;
  return LGN_SUCCESS;
}

/* =============================================================================
 * The settings
 * ===========================================================================*/

/* A switch: on must be SUNTRUE or SUNFALSE (else LGN_ILL_INPUT). */
static int SetSwitch(LGNMem mem, sunbooleantype on, const char *func,
                     sunbooleantype *field)
{
  if (on != SUNTRUE && on != SUNFALSE) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "on = %d illegal: use SUNTRUE or SUNFALSE.", (int)on);
    return LGN_ILL_INPUT;
  }
  *field = on;
  return LGN_SUCCESS;
}

int LGNSetConsistentOutputs(void *lgn_mem, sunbooleantype on)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  flag = SetSwitch(mem, on, __func__, &mem->out_consistent);
  /* the last output's values belong to the old setting */
  if (flag == LGN_SUCCESS) mem->out_valid = SUNFALSE;
  return flag;
}

int LGNSetProjectOutputs(void *lgn_mem, int which)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (which != LGN_PROJECT_NONE && which != LGN_PROJECT_INTERPOLATED &&
      which != LGN_PROJECT_ALL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "which = %d illegal: use LGN_PROJECT_NONE, LGN_PROJECT_INTERPOLATED or "
              "LGN_PROJECT_ALL.", which);
    return LGN_ILL_INPUT;
  }
  mem->out_project = which;
  return LGN_SUCCESS;
}

int LGNSetMultiplierErrorControl(void *lgn_mem, sunbooleantype on, sunrealtype atol_lambda)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (on != SUNTRUE && on != SUNFALSE) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "on = %d illegal: use SUNTRUE or SUNFALSE.", (int)on);
    return LGN_ILL_INPUT;
  }
  if (on && !(atol_lambda > SUN_RCONST(0.0) && isfinite(atol_lambda))) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "atol_lambda = %g illegal: the multipliers' absolute tolerance must "
              "be > 0 and finite (in their units: forces, torques).", (double)atol_lambda);
    return LGN_ILL_INPUT;
  }
  mem->lambda_errcon = on;
  if (on) mem->lambda_atol = atol_lambda;
  return LGN_SUCCESS;
}

int LGNGetNumOutputSolves(void *lgn_mem, long int *nout)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (nout == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "nout = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *nout = mem->nout;
  return LGN_SUCCESS;
}
