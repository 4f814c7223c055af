/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Consistent initial values (doc/user-guide.md, "Consistent initial values").
 *
 * Accelerations and multipliers, the index-1 form of the DAE at (q0, v0):
 *
 *   [ M   B^T ] [ vdot_0   ]   [ -g(q0, v0, t0)    ]
 *   [ B   0   ] [ lambda_0 ] = [ -z(q0, v0, t0)    ]
 *
 * then a_0 = vdot_0 unless the user gave a_0 (lgnComputeIC).
 *
 * The check at the first LGNSolve (lgnInitialConditions), of the constraint
 * the step enforces, within 100 times the tolerance scale:
 *   index 3: |Phi_i(q0)| <= 100 (atol + rtol max(1, |q0|_inf)),
 *   index 2: |(B(q0) v0 + Phi_t)_i| <= 100 (atol + rtol |v0|_inf)
 * (not when the user gave vdot_0, lambda_0: LGNSetInitialAcceleration),
 * else LGN_INCONSISTENT_IC with the size of the violation.
 *
 * The projections of LGNCalcIC (lgnProjectIC), both with the minimum-norm
 * correction in the metric of M:
 *   q: Newton on the group, q <- q o exp(dq) with
 *        [[M, B^T], [B, 0]] (dq, mu) = (0, -Phi(q)),
 *      until |Phi|_inf is at roundoff level (or stalls at a hundredth of
 *      the check's tolerance); LGN_IC_FAIL after LGN_IC_MAXIT iterations;
 *   v: [[M, B^T], [B, 0]] (dv, mu) = (0, -B(q) v - Phi_t), v <- v + dv (linear:
 *      one solve, repeated while roundoff leaves more than 100 eps |v|).
 *
 * The perturbed start (Arnold-Brüls-Cardona; lgnPerturbedStart), at the
 * first step attempt of size h: with vdot_+- the accelerations of the
 * index-1 system at q_+- = q0 o exp(h (+-v0 + h vdot0 / 2)),
 * v_+- = v0 +- h vdot0, t0 +- h,
 *   h vddot_0 = (vdot_+ - vdot_-) / 2,   a_0 = vdot_0 + (alpha_m - alpha_f) h vddot_0,
 * and at index 3 the velocity offset of the smooth numerical solution,
 *   l = h^2 [ c0 vddot_0 + [v0, vdot0] / 12 ],  c0 = 1/6 - (alpha_m - alpha_f)/2 - beta,
 *   [[M, B^T], [B, 0]] (dv, dlambda) = (0, B(q0) l),  v0 += dv,
 * with [v, w] = ad(v) w = -2 Tdot(0, v) w. lambda_0 stays the consistent
 * multiplier: dlambda has the units of a momentum (l is a velocity), and
 * adding it changed the heavy top's max_t |lambda error| in none of six
 * digits at h = 2e-3 ... 2.5e-4 (lambda_0 enters only the predictor).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lgn_impl.h"

#define LGN_IC_MAXIT      20               /* Newton iterations of the q projection */
#define LGN_IC_CHECK_FAC  SUN_RCONST(100.0) /* the check: 100 x the tolerance scale */

/* =============================================================================
 * The saddle-point system [[M, B^T], [B, 0]] at (q1, v1)
 * ===========================================================================*/

/* M, g, B at (t, q, v) through the iterate slots q1, v1 (q, v may be them). */
int lgnEvalAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  if (q != mem->q1) N_VScale(SUN_RCONST(1.0), q, mem->q1);
  if (v != mem->v1) N_VScale(SUN_RCONST(1.0), v, mem->v1);
  N_VConst(SUN_RCONST(0.0), mem->vdot1);
  if (mem->m > 0) N_VConst(SUN_RCONST(0.0), mem->lambda1);
  return lgnAgree(mem, lgnEvalModel(mem, t, SUNTRUE));
}

/* Assemble and factorise [[M, B^T], [B, 0]] from the M, B just evaluated
 * (EvalAt). */
int lgnSaddlePointFactor(LGNMem mem, sunrealtype t)
{
  LGNMatrixTerms terms;
  int flag;
  lgnInvalidate(mem, LGN_CHANGE_MATRIX); /* A now holds the saddle-point matrix */
  lgnSaddlePointTerms(&terms);
  flag = lgnAssembleIterationMatrix(mem, t, &terms);
  if (flag == LGN_SUCCESS) flag = lgnLsSetup(mem);
  return lgnAgree(mem, flag); /* across ranks: before a (collective) solve */
}

/* Solve with the factorised saddle-point matrix for the right-hand side in
 * mem->rhs (solution in mem->sol). */
int lgnSaddlePointBackSolve(LGNMem mem)
{
  sunindextype i;
  int flag;
  /* GGL: mu's rows are mu = 0 (identity, lgn_matrix.c) */
  for (i = mem->nv + mem->m; i < mem->nv + mem->nalg; i++) lgnData(mem->rhs)[i] = SUN_RCONST(0.0);
  flag = lgnLsSolve(mem, mem->sol, mem->rhs);
  if (flag == LGN_SUCCESS && !lgnAllFinite(lgnData(mem->sol), mem->nv + mem->m))
    flag = LGN_IC_FAIL;
  return lgnAgree(mem, flag);
}

/* Both: factorise and solve for mem->rhs. */
static int SaddlePointSolve(LGNMem mem, sunrealtype t)
{
  int flag = lgnSaddlePointFactor(mem, t);
  if (flag == LGN_SUCCESS) flag = lgnSaddlePointBackSolve(mem);
  return flag;
}

/* The index-1 right-hand side (-g, -z) at the (t, q1, v1) of EvalAt into
 * mem->rhs: LGN_SUCCESS, a callback's flag or LGN_NONFINITE (reported). */
int lgnIndex1Rhs(LGNMem mem, sunrealtype t)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype *rhs = lgnData(mem->rhs);
  const sunrealtype *g = lgnData(mem->g);
  int ret = LGN_SUCCESS, flag;

  for (i = 0; i < nv; i++) rhs[i] = -g[i];
  if (m > 0) {
    if (mem->curvature != NULL) {
      N_VConst(SUN_RCONST(0.0), mem->phi);
      ret = lgnUserCurvature(mem, t, mem->q1, mem->v1, mem->phi);
      ret = lgnCallbackVector(mem, LGN_CB_CURVATURE, ret, mem->phi, "LGNSolve");
    } else {
      ret = lgnCurvatureDQ(mem, t, mem->q1, mem->v1, mem->phi);
    }
    for (i = 0; i < m; i++) rhs[nv + i] = -lgnData(mem->phi)[i];
  }
  flag = ret;
  if (flag == LGN_SUCCESS && !lgnAllFinite(rhs, nv + m)) {
    LGN_ERROR(mem, LGN_NONFINITE,
              MSG_TIME "NaN or Inf in the forces or constraint curvature.", (double)t);
    flag = LGN_NONFINITE;
  }
  return lgnAgree(mem, flag);
}

/* The index-1 system at (t, q, v): (vdot, lambda) into mem->sol. */
static int SolveIndex1At(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  int flag = lgnEvalAt(mem, t, q, v); /* B: the matrix below */
  if (flag == LGN_SUCCESS) flag = lgnIndex1Rhs(mem, t);
  if (flag != LGN_SUCCESS) return flag;
  flag = SaddlePointSolve(mem, t);
  if (flag == LGN_IC_FAIL) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the consistent initial accelerations are not finite.",
              (double)t);
    return LGN_IC_FAIL;
  }
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the consistent initial accelerations could not be "
              "computed: [[M, B^T], [B, 0]] is singular or the solve failed "
              "(check M and B at q0).%s", (double)t,
              flag == LGN_LSETUP_FAIL || (mem->krylov && flag == LGN_RECOVERABLE)
                  ? mem->diag_text
                  : "");
    return LGN_IC_FAIL;
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * Accelerations and multipliers; the check of the first LGNSolve
 * ===========================================================================*/

int lgnComputeIC(LGNMem mem)
{
  int flag;
  if (!mem->user_vdot0) {
    flag = SolveIndex1At(mem, mem->tn, mem->q, mem->v);
    if (flag != LGN_SUCCESS) return flag;
    memcpy(lgnData(mem->vdot), lgnData(mem->sol), (size_t)mem->nv * sizeof(sunrealtype));
    if (mem->m > 0)
      memcpy(lgnData(mem->lambda), lgnData(mem->sol) + mem->nv,
             (size_t)mem->m * sizeof(sunrealtype));
  }
  if (!mem->user_a0) N_VScale(SUN_RCONST(1.0), mem->vdot, mem->a);
  mem->ic_done     = SUNTRUE;
  mem->lambda_valid = SUNTRUE;
  mem->pstart_done = SUNFALSE; /* the perturbed start (if on) at the first step */
  return LGN_SUCCESS;
}

/* max_i |x_i| and its index. */
static sunrealtype MaxAbs(const sunrealtype *x, sunindextype n, sunindextype *imax)
{
  sunrealtype r = SUN_RCONST(0.0);
  sunindextype i;
  *imax = 0;
  for (i = 0; i < n; i++)
    if (!(fabs(x[i]) <= r)) { /* NaN counts as the largest */
      r     = fabs(x[i]);
      *imax = i;
    }
  return r;
}

/* Phi(q, t) into mem->phi. */
static int EvalPhi(LGNMem mem, sunrealtype t, N_Vector q)
{
  int ret;
  N_VConst(SUN_RCONST(0.0), mem->phi);
  ret = lgnUserConstr(mem, t, q, mem->phi);
  return lgnAgree(mem, lgnCallbackVector(mem, LGN_CB_CONSTR, ret, mem->phi, __func__));
}

/* B(q) v + Phi_t(q) into mem->work_m (B evaluated into Bmat at t = tn). */
static int EvalBv(LGNMem mem, N_Vector q, N_Vector v)
{
  int ret;
  lgnMatClear(mem->Bmat);
  ret = lgnUserConstrJac(mem, mem->tn, q, mem->Bmat);
  if (ret != 0) return lgnAgree(mem, lgnCallbackFlag(mem, LGN_CB_CONSTR_JAC, ret, __func__));
  return lgnAgree(mem, lgnConstraintVelocity(mem, mem->tn, q, mem->Bmat, lgnData(v),
                                             mem->work_m));
}

/* max(1, |q|_inf) over the ranks. */
static sunrealtype QScaleOf(LGNMem mem, N_Vector qv)
{
  sunindextype i;
  sunrealtype s = SUN_RCONST(1.0);
  const sunrealtype *q = lgnData(qv);
  for (i = 0; i < mem->nq; i++) s = SUNMAX(s, fabs(q[i]));
  return lgnMaxAll(mem, s);
}

static sunrealtype QScale(LGNMem mem)
{
  return QScaleOf(mem, mem->q);
}

/* The check's tolerances (header comment). */
static sunrealtype TolPhi(LGNMem mem)
{
  return LGN_IC_CHECK_FAC * (mem->atol + mem->rtol * QScale(mem));
}

static sunrealtype TolBv(LGNMem mem)
{
  return LGN_IC_CHECK_FAC * (mem->atol + mem->rtol * N_VMaxNorm(mem->v));
}

/* The start at (q_n, v_n) against the constraint the step enforces (Phi
 * at index 3, B v at index 2, both under GGL), within 100 x the tolerance scale. At index 3
 * the hidden constraint B v = 0 is not checked: the method satisfies it
 * only to O(h^2) along its own solution, so a restart from a computed
 * state would fail any test tied to the tolerances. Not when the user gave
 * vdot_0 and lambda_0 (LGNSetInitialAcceleration): whoever continues a run
 * with its own initial values vouches for them. */
static int CheckConsistency(LGNMem mem)
{
  sunindextype i;
  sunrealtype viol, tol;
  int flag;
  if (mem->m == 0 || mem->user_vdot0) return LGN_SUCCESS;
  if (mem->constr_index != LGN_CONSTR_INDEX2) { /* index 3 and GGL: Phi */
    flag = EvalPhi(mem, mem->tn, mem->q);
    if (flag != LGN_SUCCESS) return flag;
    viol = lgnMaxAll(mem, MaxAbs(lgnData(mem->phi), mem->m, &i));
    tol  = TolPhi(mem);
    if (!(viol <= tol)) {
      LGN_ERROR(mem, LGN_INCONSISTENT_IC,
                MSG_TIME "inconsistent initial configuration: |Phi(q0)|_inf = "
                "%g (constraint %lld) exceeds the tolerance %g = 100 (atol + "
                "rtol max(1, |q0|_inf)); call LGNCalcIC to project q0 and v0 "
                "onto the constraints.", (double)mem->tn, (double)viol,
                (long long)i, (double)tol);
      return LGN_INCONSISTENT_IC;
    }
    if (mem->constr_index == LGN_CONSTR_INDEX3) return LGN_SUCCESS;
  }
  /* index 2 and GGL: B v + Phi_t */
  flag = EvalBv(mem, mem->q, mem->v);
  if (flag != LGN_SUCCESS) return flag;
  viol = lgnMaxAll(mem, MaxAbs(mem->work_m, mem->m, &i));
  tol  = TolBv(mem);
  if (!(viol <= tol)) {
    LGN_ERROR(mem, LGN_INCONSISTENT_IC,
              MSG_TIME "inconsistent initial velocity: |B(q0) v0%s|_inf = %g "
              "(constraint %lld) exceeds the tolerance %g = 100 (atol + rtol "
              "|v0|_inf); call LGNCalcIC to project v0 onto B(q0) v%s = 0.",
              (double)mem->tn, mem->constr_time != NULL ? " + Phi_t" : "",
              (double)viol, (long long)i, (double)tol,
              mem->constr_time != NULL ? " + Phi_t" : "");
    return LGN_INCONSISTENT_IC;
  }
  return LGN_SUCCESS;
}

int lgnInitialConditions(LGNMem mem)
{
  int flag = CheckConsistency(mem);
  if (flag != LGN_SUCCESS) return flag;
  return lgnComputeIC(mem);
}

/* =============================================================================
 * The projections of LGNCalcIC
 * ===========================================================================*/

/* q onto Phi(q, t) = 0 by Newton on the group, minimum-norm steps in M,
 *   [[M, B^T], [B, 0]] (dq, mu) = (0, -Phi(q, t)),  q <- q o exp(dq),
 * until |Phi|_inf <= 100 eps max(1, |q|_inf), or it stalls (stops
 * contracting) below tol_stall, after at least min_it iterations unless
 * Phi = 0 (so that the number of iterations does not hang on roundoff
 * near the threshold, e.g. on the number of ranks); v only for the
 * model's evaluation. what names the projection in messages. */
int lgnProjectQAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                  sunrealtype tol_stall, int min_it, const char *what)
{
  const sunindextype nv = mem->nv, m = mem->m;
  const sunrealtype tol_round = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * QScaleOf(mem, q);
  sunrealtype *rhs = lgnData(mem->rhs), nrm, prev = SUN_RCONST(0.0);
  sunindextype i, imax;
  int it, flag, ret;

  for (it = 0;; it++) {
    flag = EvalPhi(mem, t, q);
    if (flag != LGN_SUCCESS) return flag;
    nrm = lgnMaxAll(mem, MaxAbs(lgnData(mem->phi), m, &imax));
    if (nrm <= tol_round && (it >= min_it || nrm == SUN_RCONST(0.0))) return LGN_SUCCESS;
    /* no longer contracting: roundoff level of this model's Phi */
    if (it >= 2 && nrm > SUN_RCONST(0.5) * prev && nrm <= tol_stall) return LGN_SUCCESS;
    if (it == LGN_IC_MAXIT || !isfinite(nrm)) {
      LGN_ERROR(mem, LGN_IC_FAIL,
                MSG_TIME "%s onto Phi(q) = 0 did not converge in %d Newton "
                "iterations: |Phi|_inf = %g (constraint %lld), wanted <= %g.",
                (double)t, what, it, (double)nrm, (long long)imax, (double)tol_stall);
      return LGN_IC_FAIL;
    }
    prev = nrm;
    flag = lgnEvalAt(mem, t, q, v);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < nv; i++) rhs[i] = SUN_RCONST(0.0);
    for (i = 0; i < m; i++) rhs[nv + i] = -lgnData(mem->phi)[i];
    flag = SaddlePointSolve(mem, t);
    if (flag != LGN_SUCCESS) {
      LGN_ERROR(mem, LGN_IC_FAIL,
                MSG_TIME "%s failed: [[M, B^T], [B, 0]] is singular or the "
                "solve failed (check M and B near q).", (double)t, what);
      return LGN_IC_FAIL;
    }
    /* q <- q o exp(dq) (through q1: compose_exp may not alias) */
    ret = mem->G->ops.compose_exp(mem->G, lgnData(q), lgnData(mem->sol),
                                  lgnData(mem->q1));
    ret = lgnAgree(mem, ret != 0 ? lgnCallbackFlag(mem, LGN_CB_GROUP, ret, __func__)
                                  : LGN_SUCCESS);
    if (ret != LGN_SUCCESS) return ret;
    N_VScale(SUN_RCONST(1.0), mem->q1, q);
  }
}

/* q0 onto Phi(q) = 0 (LGNCalcIC): down to roundoff, or to a stall below a
 * hundredth of the check's tolerance. */
static int ProjectQ(LGNMem mem)
{
  return lgnProjectQAt(mem, mem->tn, mem->q, mem->v, SUN_RCONST(0.01) * TolPhi(mem), 0,
                       "LGNCalcIC: the projection of q0");
}

/* v onto B(q) v + Phi_t = 0, the M-orthogonal projection. */
static int ProjectV(LGNMem mem)
{
  const sunindextype nv = mem->nv, m = mem->m;
  sunrealtype *rhs = lgnData(mem->rhs), *v = lgnData(mem->v), nrm;
  const sunrealtype *sol = lgnData(mem->sol);
  sunindextype i, imax;
  int it, flag;

  for (it = 0; it < 3; it++) {
    flag = EvalBv(mem, mem->q, mem->v);
    if (flag != LGN_SUCCESS) return flag;
    nrm = lgnMaxAll(mem, MaxAbs(mem->work_m, m, &imax));
    if (nrm <= SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * N_VMaxNorm(mem->v)) break;
    for (i = 0; i < m; i++) rhs[nv + i] = -mem->work_m[i];
    flag = lgnEvalAt(mem, mem->tn, mem->q, mem->v);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < nv; i++) rhs[i] = SUN_RCONST(0.0);
    flag = SaddlePointSolve(mem, mem->tn);
    if (flag != LGN_SUCCESS) {
      LGN_ERROR(mem, LGN_IC_FAIL,
                MSG_TIME "LGNCalcIC: the projection of v0 failed: [[M, B^T], "
                "[B, 0]] is singular or the solve failed (check M and B at "
                "q0).", (double)mem->tn);
      return LGN_IC_FAIL;
    }
    for (i = 0; i < nv; i++) v[i] += sol[i];
  }
  return LGN_SUCCESS;
}

/* Both as icopt says; on failure q and v are restored. */
int lgnProjectIC(LGNMem mem, int icopt)
{
  const size_t nq = (size_t)mem->nq, nv = (size_t)mem->nv;
  sunrealtype *save;
  int flag = LGN_SUCCESS;
  if (mem->m == 0) return LGN_SUCCESS;
  save = (sunrealtype *)malloc((nq + nv) * sizeof(sunrealtype));
  if (save == NULL) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
  flag = lgnAgree(mem, save == NULL ? LGN_MEM_FAIL : LGN_SUCCESS);
  if (flag != LGN_SUCCESS) {
    free(save);
    return flag;
  }
  memcpy(save, lgnData(mem->q), nq * sizeof(sunrealtype));
  memcpy(save + nq, lgnData(mem->v), nv * sizeof(sunrealtype));
  if (icopt != LGN_IC_PROJECT_V) flag = ProjectQ(mem); /* Q or QV */
  if (flag == LGN_SUCCESS && icopt != LGN_IC_PROJECT_Q) flag = ProjectV(mem);
  if (flag != LGN_SUCCESS) {
    memcpy(lgnData(mem->q), save, nq * sizeof(sunrealtype));
    memcpy(lgnData(mem->v), save + nq, nv * sizeof(sunrealtype));
  }
  free(save);
  return flag;
}

/* =============================================================================
 * The perturbed start, at the first step attempt of size h
 * ===========================================================================*/

int lgnPerturbedStart(LGNMem mem, sunrealtype h)
{
  const sunindextype nv = mem->nv, m = mem->m;
  const sunrealtype dalpha = mem->alpha_m - mem->alpha_f;
  const sunrealtype c0 = SUN_RCONST(1.0) / SUN_RCONST(6.0) - dalpha / SUN_RCONST(2.0) -
                         mem->beta;
  const sunrealtype *v0 = lgnData(mem->v), *vd0 = lgnData(mem->vdot);
  sunrealtype *work, *vdp, *hvdd, *w, *rhs = lgnData(mem->rhs);
  sunrealtype *sol = lgnData(mem->sol), *v1 = lgnData(mem->v1);
  sunindextype i;
  int sign, flag = LGN_SUCCESS, ret;
  const sunbooleantype correct_v = mem->constr_index == LGN_CONSTR_INDEX3 && m > 0;

  if (correct_v && mem->G->ops.tangent_dot_apply == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The perturbed start (LGNSetPerturbedStart) needs the Lie "
              "group's tangent_dot_apply (the bracket [v0, vdot0]).");
    work = NULL;
    flag = LGN_ILL_INPUT;
  } else {
    work = (sunrealtype *)malloc(3 * (size_t)nv * sizeof(sunrealtype));
    if (work == NULL) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    flag = work == NULL ? LGN_MEM_FAIL : LGN_SUCCESS;
  }
  flag = lgnAgree(mem, flag); /* every rank goes on, or none */
  if (flag != LGN_SUCCESS) {
    free(work);
    return flag;
  }
  vdp = work; hvdd = work + nv; w = work + 2 * nv;

  /* vdot at t0 +- h: vdp = vdot_+, then hvdd = (vdot_+ - vdot_-) / 2 */
  for (sign = 1; sign >= -1 && flag == LGN_SUCCESS; sign -= 2) {
    for (i = 0; i < nv; i++) {
      w[i]  = h * (sign * v0[i] + SUN_RCONST(0.5) * h * vd0[i]);
      v1[i] = v0[i] + sign * h * vd0[i];
    }
    ret = mem->G->ops.compose_exp(mem->G, lgnData(mem->q), w, lgnData(mem->q1));
    flag = lgnAgree(mem, ret != 0 ? lgnCallbackFlag(mem, LGN_CB_GROUP, ret, __func__)
                                   : LGN_SUCCESS);
    if (flag != LGN_SUCCESS) break;
    flag = SolveIndex1At(mem, mem->tn + sign * h, mem->q1, mem->v1);
    if (flag != LGN_SUCCESS) break;
    if (sign > 0)
      memcpy(vdp, sol, (size_t)nv * sizeof(sunrealtype));
    else
      for (i = 0; i < nv; i++) hvdd[i] = SUN_RCONST(0.5) * (vdp[i] - sol[i]);
  }
  if (flag == LGN_SUCCESS && !mem->user_a0) {
    sunrealtype *a = lgnData(mem->a);
    for (i = 0; i < nv; i++) a[i] = vd0[i] + dalpha * hvdd[i];
  }
  if (flag == LGN_SUCCESS && correct_v) {
    /* l = h c0 (h vddot) + h^2 [v0, vdot0] / 12, [v, w] = -2 Tdot(0, v) w */
    ret = mem->G->ops.tangent_dot_apply(mem->G, mem->zero_nv, v0, vd0, w);
    if (ret != 0) flag = lgnCallbackFlag(mem, LGN_CB_GROUP, ret, __func__);
    flag = lgnAgree(mem, flag);
    if (flag == LGN_SUCCESS) {
      for (i = 0; i < nv; i++)
        vdp[i] = h * c0 * hvdd[i] - h * h * SUN_RCONST(2.0) * w[i] / SUN_RCONST(12.0);
      flag = lgnEvalAt(mem, mem->tn, mem->q, mem->v); /* B(q0) */
    }
    if (flag == LGN_SUCCESS) {
      for (i = 0; i < nv; i++) rhs[i] = SUN_RCONST(0.0);
      lgnMatvec(mem->Bmat, vdp, rhs + nv, SUNFALSE);
      flag = SaddlePointSolve(mem, mem->tn);
      if (flag != LGN_SUCCESS) {
        LGN_ERROR(mem, LGN_IC_FAIL,
                  MSG_TIME "the perturbed start failed: [[M, B^T], [B, 0]] is "
                  "singular or the solve failed.", (double)mem->tn);
        flag = LGN_IC_FAIL;
      }
    }
    if (flag == LGN_SUCCESS) {
      /* v0 += dv; lambda_0 is kept (see the header comment) */
      sunrealtype *v = lgnData(mem->v);
      for (i = 0; i < nv; i++) v[i] += sol[i];
    }
  }
  free(work);
  return flag;
}
