/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The Newton iteration of a step on (sigma, lambda) with the scaled
 * iteration matrix (lgn_matrix.c), full or modified (after IDA's idaNls):
 *
 *   - the iterate: the variant's state map, the residual, and, when a new
 *     matrix is due, its terms, assembly and factorisation (NewtonSolve);
 *   - the size of a correction: a weighted RMS norm (CorrectionNorm);
 *   - the convergence test, on an explicit state (NewtonTest): stop,
 *     continue, rebuild the matrix, or give up (TestCorrection);
 *   - the matrix-reuse policy of modified Newton (MatrixReusable, and the
 *     rebuild on slow contraction inside TestCorrection).
 *
 * A correction computed with a matrix evaluated at the current iterate (a
 * "fresh" one: every iteration of full Newton) is a Newton step: the
 * iteration stops when it is <= 1 in the norm of CorrectionNorm, since the
 * error left is then of the order of its square. Modified Newton solves with
 * the matrix of an earlier iterate or step while it contracts fast: with the
 * contraction rate r = |d_k|/|d_{k-1}| (at the first iterate of a step the
 * last rate seen), the error left after d_k is at most r/(1-r) |d_k|, so it
 * stops when |d_k| <= 1 and, if r > 1/2, r/(1-r) |d_k| <= 1. When r exceeds
 * 0.9, or is too slow to converge in the iterations left, the matrix is
 * rebuilt at the current iterate (a correction that grew is dropped first).
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_impl.h"

#define NEWTON_RATE_MAX  SUN_RCONST(0.9) /* slower contraction: rebuild A    */
#define NEWTON_RATE_FAST SUN_RCONST(0.5) /* faster: a correction <= 1 stops  */
#define REUSE_H_TOL      SUN_RCONST(0.1) /* reuse A while |h - h_A| <= 0.1 h_A */
#define DIVERGENCE_GROWTH 10             /* a Newton step 10x the last: diverging */

/* The state of the convergence test across the iterations of one attempt. */
typedef struct {
  int iter;                  /* index of the correction just computed      */
  sunbooleantype fresh;      /* it was solved with a matrix of its iterate */
  sunbooleantype fresh_prev; /* ... and the previous one                   */
  sunrealtype norm;          /* its weighted RMS norm                      */
  sunrealtype norm_sigma;    /* ... configuration part                     */
  sunrealtype norm_lambda;   /* ... multiplier part                        */
  sunrealtype norm_prev;     /* the norm of the last correction applied    */
  sunbooleantype stalled;    /* multipliers at roundoff: accept as it is   */
} NewtonTest;

/* What the test says after a correction. */
typedef enum {
  NEWTON_CONTINUE,  /* apply it and iterate                               */
  NEWTON_CONVERGED, /* apply it and stop                                  */
  NEWTON_DROP,      /* do not apply it: rebuild the matrix at this iterate */
  NEWTON_DIVERGED   /* give up                                            */
} NewtonVerdict;

/* =============================================================================
 * The size of a correction
 * ===========================================================================*/

/* sum_i (d_i / (a + r |c x_i|))^2, in four partial sums: one running sum
 * would make each addition wait for the previous one (the loop is bound by
 * the latency of the additions, not by the divisions). */
static sunrealtype SumOfSquaresRatio(sunindextype n, const sunrealtype *d,
                                     const sunrealtype *x, sunrealtype c,
                                     sunrealtype a, sunrealtype r)
{
  sunrealtype s[4] = {SUN_RCONST(0.0), SUN_RCONST(0.0), SUN_RCONST(0.0),
                      SUN_RCONST(0.0)};
  sunrealtype w;
  sunindextype i, j;
  for (i = 0; i + 4 <= n; i += 4)
    for (j = 0; j < 4; j++) {
      w = d[i + j] / (a + r * fabs(c * x[i + j]));
      s[j] += w * w;
    }
  for (; i < n; i++) {
    w = d[i] / (a + r * fabs(c * x[i]));
    s[0] += w * w;
  }
  return (s[0] + s[1]) + (s[2] + s[3]);
}

/* sum_i (d_i / (f a_i + a0 + r |x_i|))^2 for per-component a_i. */
static sunrealtype SumOfSquaresRatioV(sunindextype n, const sunrealtype *d,
                                      const sunrealtype *x, const sunrealtype *a,
                                      sunrealtype f, sunrealtype a0, sunrealtype r)
{
  sunrealtype s = SUN_RCONST(0.0), w;
  sunindextype i;
  for (i = 0; i < n; i++) {
    w = d[i] / (f * a[i] + a0 + r * fabs(x[i]));
    s += w * w;
  }
  return s;
}

/* Weighted RMS norm of the Newton correction in the variables
 * xi = (sigma/h, h lambda), weights 1/(atol + rtol |xi_i| + floor_i). The
 * multiplier part of the correction arrives scaled, dmu = beta h^2 dlambda.
 * The configuration and multiplier parts (same normalisation, norm^2 =
 * sigma part^2 + lambda part^2) go to t->norm_sigma and t->norm_lambda.
 * The tolerances are the step's (mem->nls_*): the user's in the fixed-step
 * mode, tied to the error test's with error control (below,
 * lgnNewtonTolerances; the multipliers' part has its own, nls_l*).
 * The floors are the roundoff level of the iteration: the configuration is
 * known to ~eps |q|, so sigma to eps |q| and, through the scaling of the
 * index-3 equations, lambda only to ~eps |q| / (beta h^2). Without them a
 * tight tolerance at small h asks Newton to resolve noise (it stalls at a
 * constant correction). |q| is taken at t_n (c->qscale), once per step. */
static void CorrectionNorm(LGNMem mem, const LGNStepCoeffs *c,
                           const sunrealtype *delta, const sunrealtype *dmu,
                           NewtonTest *t)
{
  const sunindextype nv = mem->nv_own, m = mem->m; /* owned: not the ghosts */
  const sunrealtype h = c->h, rtol = mem->nls_rtol, atol = mem->nls_atol;
  const sunrealtype *lambda1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  const sunrealtype roundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * c->qscale;
  /* w_i = (delta_i / h) / (atol + rtol |sigma_i / h| + roundoff / h) and
   * w_i = (h dmu_i / scale) / (atol + rtol |h lambda_i| + roundoff / (beta h)),
   * each with one division */
  const sunrealtype sigma_atol  = atol * h + roundoff;
  const sunrealtype lambda_unit = c->scale / h;
  /* beta h^2 = scale for the Newmark family; BDF's scale is 1/c0^2 */
  const sunrealtype beta = mem->family == LGN_FAMILY_BDF ? c->scale / (h * h) : mem->beta;
  const sunrealtype lambda_atol = mem->nls_latol + roundoff / (beta * h);
  const sunbooleantype ggl = m > 0 && mem->constr_index == LGN_CONSTR_GGL;
  const sunrealtype n = mem->nv_all + (ggl ? SUN_RCONST(2.0) : SUN_RCONST(1.0)) * mem->m_all;
  sunrealtype sum[2]; /* the configuration and multiplier parts */

  /* per-component tolerances (error control): the same weights with
   * atol_i h in place of atol h */
  sum[0] = mem->nls_atolv != NULL
               ? SumOfSquaresRatioV(nv, delta, mem->sigma, mem->nls_atolv,
                                    h * mem->nls_vfac, roundoff, rtol)
               : SumOfSquaresRatio(nv, delta, mem->sigma, SUN_RCONST(1.0), sigma_atol,
                                   rtol);
  /* GGL: the unknown nu = mu / gamma' moves the configuration by T^{-1} B^T
   * dnu, a displacement: weighted as one (mu is near 0, no relative part) */
  if (ggl) sum[0] += SumOfSquaresRatio(m, dmu + m, mem->ggl_mu, SUN_RCONST(0.0), sigma_atol,
                                       rtol);
  sum[1] = SumOfSquaresRatio(m, dmu, lambda1, h, lambda_unit * lambda_atol,
                             lambda_unit * mem->nls_lrtol);
  lgnSumAll(mem, sum, 2); /* over the ranks: every rank takes the same decision */
  t->norm_sigma  = sqrt(sum[0] / n);
  t->norm_lambda = sqrt(sum[1] / n);
  t->norm        = sqrt((sum[0] + sum[1]) / n);
}

/* =============================================================================
 * The tolerances of a step
 * ===========================================================================*/

/* Newton's tolerances in the fixed-step mode: the user's (LGNSStolerances). */
void lgnFixedNewtonTolerances(LGNMem mem)
{
  mem->nls_rtol  = mem->rtol;
  mem->nls_atol  = mem->atol;
  mem->nls_atolv = NULL;
  mem->nls_vfac  = SUN_RCONST(1.0);
  mem->nls_lrtol = mem->rtol;
  mem->nls_latol = mem->atol;
}

/* Newton's tolerances under the BDF family's error test (a configuration
 * increment, the velocities' error times h): share epcon times its
 * tolerances, on sigma / h, multipliers alike. */
void lgnNewtonTolerancesPerStep(LGNMem mem, sunrealtype h, sunrealtype share)
{
  mem->nls_rtol  = share * mem->epcon * mem->rtol;
  mem->nls_atol  = share * mem->epcon * mem->atol / h;
  mem->nls_atolv = mem->atol_vec;
  mem->nls_vfac  = share * mem->epcon / h;
  mem->nls_lrtol = mem->nls_rtol;
  mem->nls_latol = mem->nls_atol;
}

/* Newton's tolerances under the Newmark family's error test (error per
 * unit step, lgn_newmark_errtest.c), tied to it as IDA
 * ties them (idaNls: the correction in the error test's weights below
 * epcon): the velocity a correction d of the increment makes, gamma' d
 * (Newmark family: gamma / (beta h); BDF: c0), is at most epcon times the
 * error test's velocity tolerance atol + rtol |v|. Newton's unknown for the
 * configuration is sigma / h (lgn_newton.c), |sigma / h| ~ |v|, so its
 * tolerances are epcon / (gamma' h) times the user's. The multipliers,
 * outside the error test, keep epcon times the tolerances on h lambda
 * (their roundoff floor is in CorrectionNorm). */
void lgnNewtonTolerances(LGNMem mem, const LGNStepCoeffs *c)
{
  const sunrealtype f = mem->epcon / (c->gamma_p * c->h);
  mem->nls_rtol  = f * mem->rtol;
  mem->nls_atol  = f * mem->atol;
  mem->nls_vfac  = f;
  /* per component in the configuration part; the multipliers with the
   * mean (LGNSVtolerances keeps it in atol) */
  mem->nls_atolv = mem->atol_vec;
  mem->nls_lrtol = mem->epcon * mem->rtol;
  mem->nls_latol = mem->epcon * mem->atol / c->h;
}

/* =============================================================================
 * The convergence test
 * ===========================================================================*/

/* Can a linear contraction at this rate bring the correction below 1 in the
 * iterations left (|d| rate^k <= 1)? */
static sunbooleantype WithinBudget(LGNMem mem, int iter, sunrealtype norm,
                                   sunrealtype rate)
{
  int left = mem->maxcor - iter - 1;
  if (norm <= SUN_RCONST(1.0)) return SUNTRUE;
  if (rate <= SUN_RCONST(0.0)) return SUNTRUE;
  if (rate >= SUN_RCONST(1.0)) return SUNFALSE;
  /* norm rate^left <= 1 by products (left < maxcor): two logarithms cost
   * more than the rest of the test */
  for (; left > 0 && norm > SUN_RCONST(1.0); left--) norm *= rate;
  return norm <= SUN_RCONST(1.0);
}

/* Stalled multipliers: the configuration has converged but the multiplier
 * corrections have stopped contracting (from the third iteration on). At
 * index 3 the multipliers of a long chain are determined only to about
 * cond(A) eps |q| / (beta h^2), with cond(A) growing like the square of the
 * number of links, so they may sit above the tolerance at roundoff level;
 * further iterations (or a new matrix, which sees the same noise) would only
 * stir it. The multiplier part of that correction is kept as the noise level
 * of the step size. From the second iteration on, a correction whose
 * configuration part is <= 1 and whose multiplier error left is within that
 * level stops the iteration too: after a Newton correction (fresh matrix)
 * that error is taken as the correction's multiplier part; with a reused
 * matrix contracting at the rate r of this step, it is at most r/(1-r)
 * times that part. */
static sunbooleantype StalledMultipliers(LGNMem mem, const LGNStepCoeffs *c,
                                         const NewtonTest *t)
{
  if (!mem->accept_stalls) return SUNFALSE; /* LGNSetAcceptStalls */
  sunbooleantype stalled = t->iter >= 2 && t->norm_sigma <= SUN_RCONST(1.0) &&
                           t->norm > SUN_RCONST(1.0) &&
                           t->norm > SUN_RCONST(0.5) * t->norm_prev;
  if (stalled) {
    mem->lambda_noise   = t->norm_lambda;
    mem->lambda_noise_h = c->h;
  } else if (t->iter >= 1) {
    const sunrealtype r = t->norm / t->norm_prev;
    const sunrealtype left = t->fresh ? t->norm_lambda
                           : (r < SUN_RCONST(1.0) ? r / (SUN_RCONST(1.0) - r) * t->norm_lambda
                                                  : SUN_BIG_REAL);
    stalled = t->norm_sigma <= SUN_RCONST(1.0) && t->norm > SUN_RCONST(1.0) &&
              fabs(c->h - mem->lambda_noise_h) <= REUSE_H_TOL * c->h &&
              left <= mem->lambda_noise;
  }
  return stalled;
}

/* The verdict on the correction just computed (t->norm ...); *rebuild:
 * the next iteration needs a matrix evaluated at its iterate. */
static NewtonVerdict TestCorrection(LGNMem mem, const LGNStepCoeffs *c,
                                    NewtonTest *t, sunbooleantype *rebuild)
{
  sunrealtype rate;
  if (!isfinite(t->norm)) return NEWTON_DIVERGED;
  t->stalled = StalledMultipliers(mem, c, t);
  if (t->fresh) {
    /* divergence: from the third iteration on, a Newton correction ten
     * times larger than the previous one means Newton is not contracting */
    if (!t->stalled && t->iter >= 2 && t->fresh_prev &&
        t->norm > DIVERGENCE_GROWTH * t->norm_prev && t->norm > SUN_RCONST(1.0))
      return NEWTON_DIVERGED;
    return (t->norm <= SUN_RCONST(1.0) || t->stalled) ? NEWTON_CONVERGED
                                                      : NEWTON_CONTINUE;
  }
  /* a reused matrix: judged by its contraction rate */
  rate = t->iter > 0 ? t->norm / t->norm_prev : mem->newton_rate;
  if (t->iter > 0) mem->newton_rate = rate;
  if (!t->stalled && t->iter > 0 &&
      (rate > NEWTON_RATE_MAX || !WithinBudget(mem, t->iter, t->norm, rate))) {
    *rebuild = SUNTRUE;
    if (t->norm > t->norm_prev) return NEWTON_DROP; /* rebuild at this iterate */
  }
  return (t->stalled ||
          (t->norm <= SUN_RCONST(1.0) &&
           (rate <= NEWTON_RATE_FAST ||
            rate / (SUN_RCONST(1.0) - rate) * t->norm <= SUN_RCONST(1.0))))
             ? NEWTON_CONVERGED
             : NEWTON_CONTINUE;
}

/* =============================================================================
 * The iteration
 * ===========================================================================*/

/* Can the step start with the factorised matrix already in A? */
static sunbooleantype MatrixReusable(LGNMem mem, const LGNStepCoeffs *c)
{
  return mem->lu_valid && fabs(c->hmat - mem->lu_h) <= REUSE_H_TOL * mem->lu_h &&
         (mem->msbp < 0 || mem->nst - mem->lu_nst < mem->msbp);
}

/* The correction at the current iterate into mem->sol: the variant's state
 * map, the residual and (setup) a new factorised matrix there. */
static int NewtonSolve(LGNMem mem, const LGNStepCoeffs *c, sunbooleantype setup)
{
  LGNMatrixTerms terms;
  /* index 2: the row B v is scaled by 1/gamma' so that its block is B T */
  int flag = mem->kin->iterate(mem, setup);
  if (flag == LGN_SUCCESS)
    flag = lgnNewtonResidual(mem, c->t1, c->scale, c->gamma_p, setup);
  /* across ranks, each stage is agreed before the next, which may be
   * collective (a Krylov solve) */
  flag = lgnAgree(mem, flag);
  if (flag == LGN_SUCCESS && setup) {
    lgnInvalidate(mem, LGN_CHANGE_MATRIX); /* A is overwritten */
    flag = mem->kin->matrix(mem, c, &terms);
    if (flag == LGN_SUCCESS) flag = lgnAssembleIterationMatrix(mem, c->t1, &terms);
    if (flag == LGN_SUCCESS) flag = lgnLsSetup(mem);
    flag = lgnAgree(mem, flag);
    if (flag == LGN_SUCCESS) {
      mem->lu_valid = SUNTRUE;
      mem->lu_h     = c->hmat;
      mem->lu_nst   = mem->nst;
    }
  }
  if (flag == LGN_SUCCESS && mem->krylov) lgnKrylovNewtonWeights(mem, c);
  if (flag == LGN_SUCCESS) flag = lgnAgree(mem, lgnLsSolve(mem, mem->sol, mem->rhs));
  return flag;
}

/* GGL: the correction dnu of the kinematic multiplier's unknown
 * (doc/theory.md §7.1). BDF: nu = mu / gamma' (v = T(x) xdot - B^T mu,
 * evaluated by the iterate). Newmark family: nu = h eta moves the Newmark
 * increment s = sigma + B(q_n)^T nu and not the configuration, so
 * sigma_dot += gamma' B_n^T dnu, sigma_ddot += beta' B_n^T dnu. */
static void GGLCorrection(LGNMem mem, const LGNStepCoeffs *c, const sunrealtype *dnu)
{
  sunindextype i, k, nv = mem->nv, m = mem->m;
  const sunrealtype *Bn = mem->ggl_Bn;
  sunrealtype w;
  if (mem->family == LGN_FAMILY_BDF) {
    for (i = 0; i < m; i++) mem->ggl_mu[i] += c->gamma_p * dnu[i];
    return;
  }
  for (i = 0; i < m; i++) mem->ggl_mu[i] += dnu[i];
  for (k = 0; k < nv; k++) {
    w = SUN_RCONST(0.0);
    for (i = 0; i < m; i++) w += Bn[i + k * m] * dnu[i];
    mem->sigma_dot[k] += c->gamma_p * w;
    mem->sigma_ddot[k] += c->beta_p * w;
  }
}

/* Apply a Newton correction: sigma += delta, sigma_dot += gamma' delta,
 * sigma_ddot += beta' delta, lambda += dmu/(beta h^2) (the multiplier unknown
 * is scaled), and whatever the variant carries besides. */
static int ApplyCorrection(LGNMem mem, const LGNStepCoeffs *c,
                           const sunrealtype *delta, const sunrealtype *dmu)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype *lambda1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  for (i = 0; i < nv; i++) {
    mem->sigma[i] += delta[i];
    mem->sigma_dot[i] += c->gamma_p * delta[i];
    mem->sigma_ddot[i] += c->beta_p * delta[i];
  }
  for (i = 0; i < m; i++) lambda1[i] += dmu[i] / c->scale;
  if (m > 0 && mem->constr_index == LGN_CONSTR_GGL) GGLCorrection(mem, c, dmu + m);
  return mem->kin->correct != NULL ? mem->kin->correct(mem, delta) : LGN_SUCCESS;
}

/* Newton from the predicted iterate. force_setup: start with a new matrix.
 * *used_old tells whether a matrix of an earlier step was used: the caller
 * may then retry a failure with a fresh one. Returns LGN_CONV_FAILURE
 * without a message (the caller reports it). */
int lgnNewton(LGNMem mem, const LGNStepCoeffs *c, sunbooleantype force_setup,
              sunbooleantype *used_old)
{
  const sunbooleantype modified = mem->newton_mode == LGN_NEWTON_MODIFIED;
  const sunindextype nv = mem->nv;
  sunbooleantype setup = !modified || force_setup || !MatrixReusable(mem, c);
  NewtonTest test = {0, SUNFALSE, SUNFALSE, SUN_RCONST(0.0), SUN_RCONST(0.0),
                     SUN_RCONST(0.0), SUN_RCONST(0.0), SUNFALSE};
  NewtonVerdict verdict;
  sunrealtype *sol;
  int flag;

  *used_old = !setup;
  if (mem->m > 0 && mem->constr_index == LGN_CONSTR_GGL) { /* mu predicted 0 */
    sunindextype i;
    for (i = 0; i < mem->m; i++) mem->ggl_mu[i] = SUN_RCONST(0.0);
    mem->ggl_t1 = c->t1;
  }
  for (test.iter = 0; test.iter < mem->maxcor; test.iter++) {
    flag = NewtonSolve(mem, c, setup);
    if (flag != LGN_SUCCESS) return flag;
    mem->nni++;
    test.fresh_prev = test.fresh;
    test.fresh      = setup;
    if (!test.fresh) mem->nreuse++;
    setup = !modified;

    sol = lgnData(mem->sol); /* (delta, dmu) */
    CorrectionNorm(mem, c, sol, sol + nv, &test);
    verdict = TestCorrection(mem, c, &test, &setup);
    if (verdict == NEWTON_DIVERGED) break;
    if (verdict == NEWTON_DROP) continue;
    test.norm_prev = test.norm;
    flag = lgnAgree(mem, ApplyCorrection(mem, c, sol, sol + nv));
    if (flag != LGN_SUCCESS) return flag;
    if (test.stalled) mem->nstall++;
    if (verdict == NEWTON_CONVERGED) return lgnAgree(mem, mem->kin->iterate(mem, SUNFALSE));
  }
  mem->nncf++;
  return LGN_CONV_FAILURE;
}
