/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * One step t_n -> t_n + h of the Newmark / generalized-alpha family on a Lie
 * group, for every kinematics variant (spec numerics.md §2, §3 and
 * modified-kinematics.md §1-2). The step works in the local coordinate sigma
 * of the step, q_{n+1} = q_n o exp(sigma), with Newmark formulas on sigma:
 *
 *   sigma      = h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
 *   sigma_dot  = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
 *   a_{n+1}    = a+ + (1-af)/(1-am) sigma_ddot,   a+ = (af vdot_n - am a_n)/(1-am)
 *
 * The variants differ only in the map (sigma, sigma_dot, sigma_ddot) -> (v, vdot):
 *   simplified: v = sigma_dot,            vdot = sigma_ddot          (LGNM, LGGalpha)
 *   exact:      v = T(sigma) sigma_dot,   vdot = T sigma_ddot + Tdot(sigma, sigma_dot) sigma_dot
 *   sigma:      as simplified, but the predicted increment is scaled by Xi and
 *               Newton corrections are composed on the right of q1
 *               (modified-kinematics.md §3); no T in the iteration matrix.
 * (sigma = h Delta q_n of the Brüls-Cardona form). On R^n both coincide with
 * the conventional Newmark / generalized-alpha method.
 *
 * Step structure (IDA's IDAStep): Predict -> Newton -> Complete. The state at
 * t_n is only overwritten in Complete, so a failed step leaves it intact.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include "lgn_impl.h"

/* Per-step constants. */
typedef struct {
  sunrealtype h, t1;
  sunrealtype beta_p;  /* beta'  = (1-am)/(h^2 beta (1-af)): d sigma_ddot / d sigma */
  sunrealtype gamma_p; /* gamma' = gamma/(h beta):           d sigma_dot  / d sigma */
  sunrealtype scale;   /* beta h^2: scaling of the dynamic rows (spec §2)         */
  sunrealtype qscale;  /* max(1, |q_n|_max): size of the configuration         */
} StepCoeffs;

static StepCoeffs SetCoeffs(LGNMem mem, sunrealtype h)
{
  const sunrealtype *q = lgnData(mem->q);
  sunindextype i;
  StepCoeffs c;
  c.h       = h;
  c.t1      = mem->tn + h;
  c.beta_p  = (SUN_RCONST(1.0) - mem->alpha_m) /
              (h * h * mem->beta * (SUN_RCONST(1.0) - mem->alpha_f));
  c.gamma_p = mem->gamma / (h * mem->beta);
  c.scale   = mem->beta * h * h;
  c.qscale  = SUN_RCONST(1.0);
  for (i = 0; i < mem->nq; i++) c.qscale = SUNMAX(c.qscale, fabs(q[i]));
  return c;
}

/* sigma and sigma_dot from the current sigma_ddot (Newmark on sigma):
 * a_{n+1} = a+ + (1-af)/(1-am) sigma_ddot. */
static void FormIncrement(LGNMem mem, const StepCoeffs *c)
{
  sunindextype i, nv = mem->nv;
  const sunrealtype h = c->h, beta = mem->beta, gamma = mem->gamma;
  const sunrealtype ca = (SUN_RCONST(1.0) - mem->alpha_f) /
                         (SUN_RCONST(1.0) - mem->alpha_m);
  const sunrealtype *v = lgnData(mem->v), *a = lgnData(mem->a);
  sunrealtype a1;

  for (i = 0; i < nv; i++) {
    a1                = mem->a_pred[i] + ca * mem->sigma_ddot[i];
    mem->sigma[i]     = h * v[i] + h * h * ((SUN_RCONST(0.5) - beta) * a[i] + beta * a1);
    mem->sigma_dot[i] = v[i] + h * ((SUN_RCONST(1.0) - gamma) * a[i] + gamma * a1);
  }
}

/* Where sigma_dot and sigma_ddot live. In the simplified and sigma variants
 * v1 = sigma_dot and vdot1 = sigma_ddot, so the increments are kept in v1
 * and vdot1 themselves (nothing to copy per iteration); the exact variant
 * has its own arrays (lgnAllocWork). Bound at the start of every step
 * attempt, since Complete swaps v with v1 and vdot with vdot1. */
static void BindIncrement(LGNMem mem)
{
  if (mem->kinematics == LGN_KINEMATICS_EXACT) {
    mem->sigma_dot  = mem->sigma + mem->nv;
    mem->sigma_ddot = mem->sigma + 2 * mem->nv;
  } else {
    mem->sigma_dot  = lgnData(mem->v1);
    mem->sigma_ddot = lgnData(mem->vdot1);
  }
}

/* Predictor. LGN_PREDICTOR_ZERO is the spec's (numerics.md §2 step 1,
 * modified-kinematics.md §2 step 1): sigma_ddot = 0, lambda = lambda_n.
 * LGN_PREDICTOR_EXTRAPOLATE guesses vdot_{n+1} and lambda_{n+1} by linear
 * extrapolation and, for exact kinematics, maps the guess into the chart of
 * the step: sigma_ddot = T(sigma)^{-1} (vdot - Tdot(sigma, sigma_dot) sigma_dot)
 * (one fixed-point pass). The sigma variant always uses the spec's predictor
 * followed by the scaling Xi = I - (h beta/(2 gamma)) ad(sigma_dot) of the
 * increment (modified-kinematics.md §3): its result depends on the path of
 * the Newton iterates, so the predictor is part of the method. */
static int Predict(LGNMem mem, const StepCoeffs *c)
{
  LGNGroup G = mem->G;
  sunindextype i, nv = mem->nv, m = mem->m;
  const sunrealtype am = mem->alpha_m, af = mem->alpha_f;
  const sunrealtype *vdot = lgnData(mem->vdot), *a = lgnData(mem->a);
  const sunbooleantype extrapolate = mem->predictor == LGN_PREDICTOR_EXTRAPOLATE &&
                                     mem->kinematics != LGN_KINEMATICS_SIGMA;
  const sunrealtype r = mem->h_prev > SUN_RCONST(0.0) ? c->h / mem->h_prev
                                                      : SUN_RCONST(0.0);
  sunrealtype *acc = mem->work2_nv; /* guess of vdot_{n+1} */
  int ret = 0;

  BindIncrement(mem);
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
  FormIncrement(mem, c);

  if (extrapolate && mem->kinematics == LGN_KINEMATICS_EXACT) {
    ret = G->ops.tangent_dot_apply(G, mem->sigma, mem->sigma_dot,
                                   mem->sigma_dot, mem->work_nv);
    for (i = 0; i < nv && ret == 0; i++) mem->work_nv[i] = acc[i] - mem->work_nv[i];
    if (ret == 0)
      ret = G->ops.tangent_inverse_apply(G, mem->sigma, mem->work_nv, mem->sigma_ddot);
    if (ret == 0) FormIncrement(mem, c);
  }

  if (mem->kinematics == LGN_KINEMATICS_SIGMA) {
    /* Xi sigma = sigma - (h beta/(2 gamma)) ad(sigma_dot) sigma, with
     * ad(w) y = -2 Tdot(0, w) y in any Lie group (numerics.md §4.1) */
    sunrealtype *zero = acc;
    for (i = 0; i < nv; i++) zero[i] = SUN_RCONST(0.0);
    ret = G->ops.tangent_dot_apply(G, zero, mem->sigma_dot, mem->sigma, mem->work_nv);
    for (i = 0; i < nv && ret == 0; i++)
      mem->sigma[i] += (c->h * mem->beta / mem->gamma) * mem->work_nv[i];
    if (ret == 0)
      ret = G->ops.compose_exp(G, lgnData(mem->q), mem->sigma, lgnData(mem->q1));
  }
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
  return LGN_SUCCESS;
}

/* The iterate (q1, v1, vdot1) from (sigma, sigma_dot, sigma_ddot) by the
 * kinematics variant (table above); with_tangent: also Tm = T(sigma) for the
 * iteration matrix. The sigma variant carries q1 itself (corrections
 * composed on the right). */
static int Kinematics(LGNMem mem, sunbooleantype with_tangent)
{
  LGNGroup G = mem->G;
  sunindextype nv = mem->nv;
  sunrealtype *v1 = lgnData(mem->v1), *vdot1 = lgnData(mem->vdot1);
  sunindextype i;
  int ret = 0;

  if (mem->kinematics != LGN_KINEMATICS_SIGMA) {
    ret = G->ops.compose_exp(G, lgnData(mem->q), mem->sigma, lgnData(mem->q1));
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
    if (with_tangent) {
      ret = lgnTangentMatrices(mem);
      if (ret != LGN_SUCCESS) return ret;
    }
  }
  if (mem->kinematics == LGN_KINEMATICS_EXACT) {
    /* v = T sigma_dot, vdot = T sigma_ddot + Tdot(sigma, sigma_dot) sigma_dot */
    ret = G->ops.tangent_apply(G, mem->sigma, mem->sigma_dot, v1);
    if (ret == 0) ret = G->ops.tangent_apply(G, mem->sigma, mem->sigma_ddot, vdot1);
    if (ret == 0)
      ret = G->ops.tangent_dot_apply(G, mem->sigma, mem->sigma_dot,
                                     mem->sigma_dot, mem->work_nv);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
    for (i = 0; i < nv; i++) vdot1[i] += mem->work_nv[i];
  }
  /* otherwise v1 and vdot1 are sigma_dot and sigma_ddot (BindIncrement) */
  return LGN_SUCCESS;
}

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

/* Weighted RMS norm of the Newton correction in the variables of the spec's
 * stop test (numerics.md §2): xi = (sigma/h, h lambda), weights
 * 1/(atol + rtol |xi_i| + floor_i). The multiplier part of the correction
 * arrives scaled, dmu = beta h^2 dlambda. The configuration and multiplier
 * parts (same normalisation, norm^2 = sigma part^2 + lambda part^2) go to
 * *norm_sigma and *norm_lambda.
 * The floors are the roundoff level of the iteration: the configuration is
 * known to ~eps |q|, so sigma to eps |q| and, through the scaling of the
 * index-3 equations, lambda only to ~eps |q| / (beta h^2). Without them a
 * tight tolerance at small h asks Newton to resolve noise (it stalls at a
 * constant correction). |q| is taken at t_n (c->qscale), once per step. */
static sunrealtype CorrectionNorm(LGNMem mem, const StepCoeffs *c,
                                  const sunrealtype *delta,
                                  const sunrealtype *dmu,
                                  sunrealtype *norm_sigma,
                                  sunrealtype *norm_lambda)
{
  const sunindextype nv = mem->nv, m = mem->m;
  const sunrealtype h = c->h, rtol = mem->rtol, atol = mem->atol;
  const sunrealtype *lambda1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  const sunrealtype roundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * c->qscale;
  /* w_i = (delta_i / h) / (atol + rtol |sigma_i / h| + roundoff / h) and
   * w_i = (h dmu_i / scale) / (atol + rtol |h lambda_i| + roundoff / (beta h)),
   * each with one division */
  const sunrealtype sigma_atol  = atol * h + roundoff;
  const sunrealtype lambda_unit = c->scale / h;
  const sunrealtype lambda_atol = atol + roundoff / (mem->beta * h);
  sunrealtype sum, sum_lambda;

  sum = SumOfSquaresRatio(nv, delta, mem->sigma, SUN_RCONST(1.0), sigma_atol, rtol);
  *norm_sigma = sqrt(sum / (sunrealtype)(nv + m));
  sum_lambda = SumOfSquaresRatio(m, dmu, lambda1, h, lambda_unit * lambda_atol,
                                 lambda_unit * rtol);
  *norm_lambda = sqrt(sum_lambda / (sunrealtype)(nv + m));
  return sqrt((sum + sum_lambda) / (sunrealtype)(nv + m));
}

/* Apply a Newton correction: sigma += delta, sigma_dot += gamma' delta,
 * sigma_ddot += beta' delta, lambda += dmu/(beta h^2) (the multiplier unknown
 * is scaled, spec §2 D_R). */
static int ApplyCorrection(LGNMem mem, const StepCoeffs *c,
                           const sunrealtype *delta, const sunrealtype *dmu)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype *lambda1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  int ret;
  for (i = 0; i < nv; i++) {
    mem->sigma[i] += delta[i];
    mem->sigma_dot[i] += c->gamma_p * delta[i];
    mem->sigma_ddot[i] += c->beta_p * delta[i];
  }
  for (i = 0; i < m; i++) lambda1[i] += dmu[i] / c->scale;
  if (mem->kinematics == LGN_KINEMATICS_SIGMA) {
    /* sigma variant: q1 <- q1 o exp(delta) */
    ret = mem->G->ops.compose_exp(mem->G, lgnData(mem->q1), delta, lgnData(mem->q1));
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
  }
  return LGN_SUCCESS;
}

/* Modified Newton (LGN_NEWTON_MODIFIED), after IDA's idaNls. */
#define NEWTON_RATE_MAX  SUN_RCONST(0.9) /* slower contraction: rebuild A    */
#define NEWTON_RATE_FAST SUN_RCONST(0.5) /* faster: a correction <= 1 stops  */
#define REUSE_H_TOL      SUN_RCONST(0.1) /* reuse A while |h - h_A| <= 0.1 h_A */

/* Can the step start with the factorised matrix already in A? */
static sunbooleantype MatrixReusable(LGNMem mem, const StepCoeffs *c)
{
  return mem->lu_valid && fabs(c->h - mem->lu_h) <= REUSE_H_TOL * mem->lu_h &&
         (mem->msbp < 0 || mem->nst - mem->lu_nst < mem->msbp);
}

/* Can a linear contraction at this rate bring the correction below 1 in the
 * iterations left (|d| rate^k <= 1)? */
static sunbooleantype WithinBudget(LGNMem mem, int iter, sunrealtype norm,
                                   sunrealtype rate)
{
  const int left = mem->maxcor - iter - 1;
  if (norm <= SUN_RCONST(1.0)) return SUNTRUE;
  if (rate <= SUN_RCONST(0.0)) return SUNTRUE;
  if (rate >= SUN_RCONST(1.0)) return SUNFALSE;
  return (sunrealtype)left * log(SUN_RCONST(1.0) / rate) >= log(norm);
}

/* Newton iteration on (sigma, lambda) with the scaled iteration matrix
 * (spec §2; modified-kinematics.md §2 for the exact variant).
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
 * With either matrix, from the third iteration on, the iteration also stops
 * when the configuration part is <= 1 and the multiplier corrections have
 * stopped contracting (stalled multipliers, counted by LGNGetNumNewtonStalls);
 * the multiplier part of that correction is kept as the noise level of the
 * step size, and from the second iteration on a correction whose
 * configuration part is <= 1 and whose multiplier error left (its
 * multiplier part; with a reused matrix r/(1-r) times it) is within that
 * level stops the iteration too.
 * *used_old tells whether a matrix of an earlier step was used: the caller
 * may then retry a failure with a fresh one.
 * Returns LGN_CONV_FAILURE without a message (the caller reports it). */
static int Newton(LGNMem mem, const StepCoeffs *c, sunbooleantype force_setup,
                  sunbooleantype *used_old)
{
  const sunbooleantype modified = mem->newton_mode == LGN_NEWTON_MODIFIED;
  const sunbooleantype use_tangent = mem->kinematics != LGN_KINEMATICS_SIGMA;
  sunindextype nv = mem->nv;
  sunrealtype *sol, norm, norm_sigma, norm_lambda, rate, norm_prev = SUN_RCONST(0.0);
  sunbooleantype setup = !modified || force_setup || !MatrixReusable(mem, c);
  sunbooleantype fresh = SUNFALSE, fresh_prev, stalled, converged;
  int iter, flag;
  /* index 2: the row B v is scaled by 1/gamma' so that its block is B T */
  const sunrealtype cv = c->gamma_p;

  *used_old = !setup;
  for (iter = 0; iter < mem->maxcor; iter++) {
    flag = Kinematics(mem, setup);
    if (flag == LGN_SUCCESS && setup && mem->kinematics == LGN_KINEMATICS_EXACT)
      flag = lgnExactKinematicsDerivatives(mem, c->gamma_p, c->beta_p);
    if (flag == LGN_SUCCESS) flag = lgnNewtonResidual(mem, c->t1, c->scale, cv, setup);
    if (flag == LGN_SUCCESS && setup) {
      lgnInvalidateMatrix(mem); /* A is overwritten */
      flag = lgnAssembleAndFactor(mem, c->t1, c->scale * c->beta_p,
                                  c->scale * c->gamma_p, c->scale, use_tangent);
      if (flag == LGN_SUCCESS) {
        mem->lu_valid = SUNTRUE;
        mem->lu_h     = c->h;
        mem->lu_nst   = mem->nst;
      }
    }
    if (flag == LGN_SUCCESS) flag = lgnLsSolve(mem, mem->sol, mem->rhs);
    if (flag != LGN_SUCCESS) return flag;
    mem->nni++;
    fresh_prev = fresh;
    fresh      = setup;
    if (!fresh) mem->nreuse++;
    setup = !modified;

    sol  = lgnData(mem->sol); /* (delta, dmu) */
    norm = CorrectionNorm(mem, c, sol, sol + nv, &norm_sigma, &norm_lambda);
    if (!isfinite(norm)) break;
    /* stalled multipliers: the configuration has converged but the
     * multiplier corrections have stopped contracting. At index 3 the
     * multipliers of a long chain are determined only to about
     * cond(A) eps |q| / (beta h^2), with cond(A) growing like the square
     * of the number of links, so they may sit above the tolerance at
     * roundoff level; further iterations (or a new matrix, which sees the
     * same noise) would only stir it. */
    stalled = iter >= 2 && norm_sigma <= SUN_RCONST(1.0) &&
              norm > SUN_RCONST(1.0) && norm > SUN_RCONST(0.5) * norm_prev;
    /* ... or, from the second iteration on, the multiplier error left is
     * already down to the noise level of the last stall at this step size.
     * After a Newton correction (fresh matrix) that error is taken as the
     * correction's multiplier part; with a reused matrix contracting at
     * the rate r of this step, it is at most r/(1-r) times that part. */
    if (stalled) {
      mem->lambda_noise   = norm_lambda;
      mem->lambda_noise_h = c->h;
    } else if (iter >= 1) {
      const sunrealtype r = norm / norm_prev;
      const sunrealtype left = fresh ? norm_lambda
                             : (r < SUN_RCONST(1.0) ? r / (SUN_RCONST(1.0) - r) * norm_lambda
                                                    : SUN_BIG_REAL);
      stalled = norm_sigma <= SUN_RCONST(1.0) && norm > SUN_RCONST(1.0) &&
                fabs(c->h - mem->lambda_noise_h) <= REUSE_H_TOL * c->h &&
                left <= mem->lambda_noise;
    }
    if (fresh) {
      /* divergence: from the third iteration on, a Newton correction ten
       * times larger than the previous one means Newton is not contracting */
      if (!stalled && iter >= 2 && fresh_prev && norm > 10 * norm_prev &&
          norm > SUN_RCONST(1.0))
        break;
      converged = norm <= SUN_RCONST(1.0) || stalled;
    } else {
      rate = iter > 0 ? norm / norm_prev : mem->newton_rate;
      if (iter > 0) mem->newton_rate = rate;
      if (!stalled && iter > 0 &&
          (rate > NEWTON_RATE_MAX || !WithinBudget(mem, iter, norm, rate))) {
        setup = SUNTRUE;
        if (norm > norm_prev) continue; /* drop it, rebuild at this iterate */
      }
      converged = stalled ||
                  (norm <= SUN_RCONST(1.0) &&
                   (rate <= NEWTON_RATE_FAST ||
                    rate / (SUN_RCONST(1.0) - rate) * norm <= SUN_RCONST(1.0)));
    }
    norm_prev = norm;
    flag = ApplyCorrection(mem, c, sol, sol + nv);
    if (flag != LGN_SUCCESS) return flag;
    if (stalled) mem->nstall++;
    if (converged) return Kinematics(mem, SUNFALSE);
  }
  mem->nncf++;
  return LGN_CONV_FAILURE;
}

/* After convergence: a_{n+1} (with the chart shift of the exact variant,
 * modified-kinematics.md §2 step 3), then commit the new state. */
static void Complete(LGNMem mem, const StepCoeffs *c)
{
  sunindextype i, nv = mem->nv;
  const sunrealtype ca = (SUN_RCONST(1.0) - mem->alpha_f) /
                         (SUN_RCONST(1.0) - mem->alpha_m);
  sunrealtype *a = lgnData(mem->a), *vdot1 = lgnData(mem->vdot1);
  N_Vector tmp;

  for (i = 0; i < nv; i++)
    a[i] = mem->a_pred[i] + ca * mem->sigma_ddot[i] +
           (vdot1[i] - mem->sigma_ddot[i]);
  /* keep vdot_n, lambda_n for the extrapolating predictor */
  memcpy(mem->vdot_prev, lgnData(mem->vdot), (size_t)nv * sizeof(sunrealtype));
  if (mem->m > 0)
    memcpy(mem->lambda_prev, lgnData(mem->lambda), (size_t)mem->m * sizeof(sunrealtype));
  mem->h_prev = c->h;

  tmp = mem->q;    mem->q = mem->q1;       mem->q1 = tmp;
  tmp = mem->v;    mem->v = mem->v1;       mem->v1 = tmp;
  tmp = mem->vdot; mem->vdot = mem->vdot1; mem->vdot1 = tmp;
  if (mem->m > 0) {
    tmp = mem->lambda; mem->lambda = mem->lambda1; mem->lambda1 = tmp;
  }
  mem->tn    = c->t1;
  mem->hlast = c->h;
  mem->nst++;
}

int lgnStep(LGNMem mem, sunrealtype h)
{
  StepCoeffs c = SetCoeffs(mem, h);
  sunbooleantype used_old = SUNFALSE;
  int flag;

  flag = Predict(mem, &c);
  if (flag == LGN_SUCCESS) flag = Newton(mem, &c, SUNFALSE, &used_old);
  if (flag == LGN_CONV_FAILURE && used_old) {
    /* modified Newton failed with an old matrix: once more with a fresh one */
    mem->nrestart++;
    flag = Predict(mem, &c);
    if (flag == LGN_SUCCESS) flag = Newton(mem, &c, SUNTRUE, &used_old);
  }
  if (flag == LGN_CONV_FAILURE)
    LGN_ERROR(mem, LGN_CONV_FAILURE,
              MSG_TIME "the Newton iteration failed to converge (diverged or "
              "more than %d iterations) with h = %g (the state at t is kept).",
              (double)mem->tn, mem->maxcor, (double)h);
  if (flag != LGN_SUCCESS) {
    mem->nfails++;
    return flag;
  }
  Complete(mem, &c);
  return LGN_SUCCESS;
}
