/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The local error of a step and its weighted norm (error control).
 *
 * The step's increment s = log(q_n^{-1} q_{n+1}) (the chart coordinate of
 * the new configuration, from the variant) is compared with the third-order
 * Magnus-Taylor increment of the exact flow through (q_n, v_n):
 *
 *   e = s - ( h v_n + (h^2/2) vdot_n + (h^2/6)(vdot_{n+1} - vdot_n)
 *             + (h^3/12) [v_n, vdot_n] )
 *
 * For every Newmark / generalized-alpha method the leading local error is
 * -h^3 (c0 vddot + [v, vdot]/12) with c0 = 1/6 - (alpha_m - alpha_f)/2 -
 * beta; the Magnus increment is exact to O(h^4), so e estimates it to
 * O(h^4) for every kinematics variant. The bracket [v, w] = ad(v) w =
 * -2 Tdot(0, v) w is the Lie group part of the error (on a spinning body as
 * large as the vector-space part). Lambda and a are left out, as IDA leaves
 * algebraic variables out with IDASetSuppressAlg.
 *
 * Error per unit step: the test reads e / h, the velocity error the
 * step's configuration error makes over it, in the weights of a velocity,
 * 1 / (atol_i + rtol |s_i / h|) (|s / h| ~ |v|), the meaning IDA gives
 * atol and rtol on its velocity components; that is e itself in the
 * weights w_i = 1 / (h atol_i + rtol |s_i|) (mem->ele keeps e, mem->ewt
 * these w). The norm is the RMS of e_i w_i over the nv components; a step
 * passes when it is <= 1.
 * Since |e| / h ~ h^2, the global error of these second-order methods then
 * follows the tolerance (tol^1; the error per step |e| ~ h^3 made it follow
 * tol^(2/3), 10^4 - 10^5 times the tolerance at tol 1e-10 on the heavy top,
 * bench/tolerance_band). At index 3 with rheonomic constraints the norm is
 * also at least that of B v + Phi_t at the new state
 * (VelocityConstraintNorm).
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_impl.h"

/* w_i = 1 / (unit atol_i + rtol |incr_i|): unit 1 for an error per step,
 * h for an error per unit step (then |e_i| w_i = |e_i / h| / (atol_i +
 * rtol |incr_i / h|), a velocity in a velocity's weights) */
void lgnErrorWeights(LGNMem mem, const sunrealtype *incr, sunrealtype unit, sunrealtype *w)
{
  const sunindextype nv = mem->nv;
  const sunrealtype *atol = mem->atol_vec;
  sunindextype i;
  for (i = 0; i < nv; i++)
    w[i] = SUN_RCONST(1.0) /
           (unit * (atol != NULL ? atol[i] : mem->atol) + mem->rtol * fabs(incr[i]));
}

/* sqrt( (1/nv) sum_i (x_i w_i)^2 ), over all ranks (owned entries: no ghosts) */
sunrealtype lgnWrmsNorm(LGNMem mem, const sunrealtype *x, const sunrealtype *w)
{
  sunrealtype s = SUN_RCONST(0.0);
  sunindextype i;
  for (i = 0; i < mem->nv_own; i++) s += (x[i] * w[i]) * (x[i] * w[i]);
  lgnSumAll(mem, &s, 1);
  return sqrt(s / mem->nv_all);
}

/* Index 3: e's part normal to the constraints, e <- e - M^{-1} B^T mu with
 * B e = 0 (the M-orthogonal projection onto the tangent space), with the
 * factorised iteration matrix A = [[cM M + O(h), B T], [B T, 0]] of the step:
 * solving A (x, mu) = (cM M e, 0) gives that projection up to O(h) e. The
 * normal part is removed by Phi(q) = 0 anyway; it is where the multipliers'
 * oscillations of generalized-alpha at index 3 enter vdot, which would make
 * the estimate noisy. One solve per step. */
static int ProjectOnConstraints(LGNMem mem, const LGNStepCoeffs *c)
{
  const sunindextype nv = mem->nv;
  sunrealtype *rhs = lgnData(mem->rhs), *sol = lgnData(mem->sol);
  const sunrealtype cM = c->scale * c->beta_p;
  sunindextype i;
  int flag;
  lgnMatvec(mem->Mmat, mem->ele, rhs, SUNFALSE);
  for (i = 0; i < nv; i++) rhs[i] *= cM;
  /* the constraint rows: 0 (under GGL the velocity rows too: then B B^T nu
   * = O(h) x, nu ~ 0, and x is the same projection) */
  for (i = 0; i < mem->nalg; i++) rhs[nv + i] = SUN_RCONST(0.0);
  flag = lgnAgree(mem, lgnLsSolve(mem, mem->sol, mem->rhs));
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < nv; i++) mem->ele[i] = sol[i];
  return LGN_SUCCESS;
}

/* The norm given to a step outside the estimate's range (OutOfRange): an
 * error-test failure, cut as one (lgn_newmark_adapt.c). */
#define OUT_OF_RANGE_NORM SUN_RCONST(100.0)
/* |e| / |s| above this: the step is outside the estimate's range, about
 * h w > 1 (the pendulum's h = 0.5: 0.23 = 0.09 (h w)^2); never reached in
 * the accepted or rejected steps of test_tolerance, test_ggl,
 * test_ggl_newmark, test_error_control, test_output_multipliers (all
 * below 0.05) */
#define TAYLOR_RATIO SUN_RCONST(0.1)

/* The estimate e = s - (Taylor increment) holds in the asymptotic range,
 * |e| = O(h^3) against the increment |s| = O(h): |e| / |s| ~ (h w)^2 for
 * a motion of frequency w. Before its projection (which removes what the
 * constraints determine), e above a tenth of the step's own increment
 * (2-norms over the nv components) means a step far beyond the time scale
 * of the motion, where the h^3 term no longer leads and the projected
 * estimate may vanish by coincidence. Seen: a pendulum started at rest
 * (lambda_0 = 0: the projected change of vdot is zero for every h) took
 * h = 0.5 (a quarter period) with a projected |e| of roundoff and q off by
 * 0.28. Called with mem->ele unprojected; only when e is also above the
 * tolerance (a step at rest: s and e both at roundoff). */
static sunbooleantype OutOfRange(LGNMem mem, const sunrealtype *s, sunrealtype h)
{
  sunrealtype sum[2] = {SUN_RCONST(0.0), SUN_RCONST(0.0)}; /* |e|^2, |s|^2 */
  sunindextype i;
  /* index 3 after the first step: generalized-alpha's multiplier
   * oscillations put a normal part into e of 5-7 % of |s| at h = 1e-4 on
   * the pendulum (what the projection removes): only the first step, from
   * a consistent start, is tested there */
  if (mem->m > 0 && mem->constr_index == LGN_CONSTR_INDEX3 && mem->nst > 0) return SUNFALSE;
  for (i = 0; i < mem->nv_own; i++) {
    sum[0] += mem->ele[i] * mem->ele[i];
    sum[1] += s[i] * s[i];
  }
  lgnSumAll(mem, sum, 2);
  if (!(sum[0] > TAYLOR_RATIO * TAYLOR_RATIO * sum[1])) return SUNFALSE;
  lgnErrorWeights(mem, s, h, mem->ewt);
  return lgnWrmsNorm(mem, mem->ele, mem->ewt) > SUN_RCONST(1.0);
}

/* After Newton has converged (the iterate holds t_{n+1}, the state t_n):
 * the estimate into mem->ele, the weights into mem->ewt, and its norm into
 * *norm. */
int lgnLocalError(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *norm)
{
  LGNGroup G = mem->G;
  const sunindextype nv = mem->nv;
  const sunrealtype h = c->h, h2 = h * h;
  const sunrealtype *s = mem->kin->increment(mem);
  const sunrealtype *v0 = lgnData(mem->v), *a0 = lgnData(mem->vdot);
  const sunrealtype *a1 = lgnData(mem->vdot1);
  sunrealtype *td = mem->work_nv; /* Tdot(0, v_n) vdot_n = -ad(v_n) vdot_n / 2 */
  sunindextype i;
  sunbooleantype out_of_range;
  int ret = G->ops.tangent_dot_apply(G, mem->zero_nv, v0, a0, td);
  ret = lgnAgree(mem, ret != 0 ? lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve")
                                : LGN_SUCCESS);
  if (ret != LGN_SUCCESS) return ret;
  for (i = 0; i < nv; i++)
    mem->ele[i] = s[i] - (h * v0[i] + h2 * (SUN_RCONST(0.5) * a0[i] +
                                            (a1[i] - a0[i]) / SUN_RCONST(6.0)) -
                          h2 * h * td[i] / SUN_RCONST(6.0));
  out_of_range = OutOfRange(mem, s, h);
  /* per unit step: |e / h| in the weights 1 / (atol + rtol |s / h|) */
  ret = lgnErrorNorm(mem, c, s, h, norm);
  if (ret == LGN_SUCCESS && out_of_range) *norm = SUNMAX(*norm, OUT_OF_RANGE_NORM);
  return ret;
}

/* The norm of the estimate in mem->ele (projected at index 3), with the
 * weights of the step's increment incr and the unit of lgnErrorWeights
 * into mem->ewt. */
/* Index 3 with constraints that depend on time: the hidden constraint of
 * the new state, u = B(q1) v1 + Phi_t(q1, t1) (zero on the exact solution),
 * in the units of the test: for the Newmark family (error per unit step) a
 * velocity, u / (atol + rtol |Phi_t|); for BDF (a configuration increment)
 * the displacement over the step, h u / (atol + rtol h |Phi_t|) (the
 * prescribed rates set the scale:
 * relative to them where they move, atol where they rest). The
 * estimate e keeps only its part in the
 * constraints' tangent space; in a driven mechanism (the motion prescribed:
 * no tangent space but a free spin) that part is nothing, and without this
 * term the velocities and the output between steps went uncontrolled (a
 * motor-driven slider-crank at tol 1e-8 took 14 steps per revolution and
 * returned positions 0.19 m off as success). */
static int VelocityConstraintNorm(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *norm)
{
  const sunindextype m = mem->m;
  const sunrealtype hs = mem->family == LGN_FAMILY_BDF ? c->h : SUN_RCONST(1.0);
  sunrealtype s[2] = {SUN_RCONST(0.0), SUN_RCONST(0.0)}, w; /* sum, rows */
  sunindextype i;
  int ret = LGN_SUCCESS;
  /* across ranks, a rank without Phi_t adds nothing but takes part */
  if (mem->constr_time != NULL) {
    ret = lgnEvalConstraintJacobian(mem, c->t1, mem->q1, mem->Bmat);
    if (ret == LGN_SUCCESS)
      ret = lgnConstraintVelocity(mem, c->t1, mem->q1, mem->Bmat, lgnData(mem->v1),
                                  mem->work_m);
  }
  ret = lgnAgree(mem, ret);
  if (ret != LGN_SUCCESS) return ret;
  if (mem->constr_time != NULL) {
    for (i = 0; i < m; i++) {
      w = hs * mem->work_m[i] / (mem->atol + mem->rtol * hs * fabs(lgnData(mem->phit)[i]));
      s[0] += w * w;
    }
    s[1] = (sunrealtype)m;
  }
  lgnSumAll(mem, s, 2);
  *norm = sqrt(s[0] / s[1]);
  return LGN_SUCCESS;
}

/* mem->ele projected on the constraints' tangent space (index 3, GGL), as
 * the error test projects it; unchanged at index 2 and without constraints. */
int lgnProjectEstimate(LGNMem mem, const LGNStepCoeffs *c)
{
  if (mem->m > 0 && mem->constr_index != LGN_CONSTR_INDEX2) return ProjectOnConstraints(mem, c);
  return LGN_SUCCESS;
}

int lgnErrorNorm(LGNMem mem, const LGNStepCoeffs *c, const sunrealtype *incr,
                 sunrealtype unit, sunrealtype *norm)
{
  if (mem->m > 0 && mem->constr_index != LGN_CONSTR_INDEX2) { /* index 3, GGL */
    int flag = ProjectOnConstraints(mem, c);
    if (flag != LGN_SUCCESS) return flag;
  }
  lgnErrorWeights(mem, incr, unit, mem->ewt);
  *norm = lgnWrmsNorm(mem, mem->ele, mem->ewt);
  if (mem->m > 0 && mem->constr_index == LGN_CONSTR_INDEX3 && mem->any_constr_time) {
    sunrealtype vnorm;
    int flag = VelocityConstraintNorm(mem, c, &vnorm);
    if (flag != LGN_SUCCESS) return flag;
    *norm = SUNMAX(*norm, vnorm);
  }
  return LGN_SUCCESS;
}
