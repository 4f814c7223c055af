/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The BDF family on the Lie group (LGNSetBDF), variable order 1 ... 5 and
 * variable step, in the local chart of the last point (Wieloch and Arnold,
 * "BDF integrators for constrained mechanical systems on Lie groups", 2021):
 * with q = q_n o exp(x) the equations of motion read
 *
 *   xdot = T(x)^{-1} v,   M(q) vdot + g(q, v, t) + B(q)^T lambda = 0,   Phi(q) = 0
 *
 * and the history becomes x_{n-j} = log(q_n^{-1} q_{n-j}) (x_n = 0) and
 * v_{n-j} (body velocities: no transport). A step of order k and size h
 * solves the BDF equations with the variable coefficients of the nodes
 * tau_0 = t_{n+1}, tau_j = t_{n+1-j} (the derivative at tau_0 of the
 * interpolating polynomial, d_j = l_j'(tau_0), c0 = d_0 = sum 1/(tau_0 - tau_j)):
 *
 *   xdot_{n+1} = c0 x + r_x,  r_x = sum_{j>=1} d_j x_{n+1-j},   v_{n+1} = T(x) xdot_{n+1},
 *   vdot_{n+1} = c0 v_{n+1} + r_v,  r_v = sum_{j>=1} d_j v_{n+1-j},
 *
 * for (x, lambda) by the Newton iteration of the Newmark family (the BDF
 * table of lgn_kinematics.c). The predictor is the polynomial through the
 * last k + 1 points (at the start, the Taylor step x = h v_n, v = v_n + h vdot_n).
 *
 * That is the variable-coefficient form (LGN_BDF_VARIABLE_COEFF, the
 * default). The fixed-leading-coefficient form (LGN_BDF_FIXED_LEADING,
 * IDA's) keeps c0 = alpha_s / h, alpha_s = sum_{j<=k} 1/j, and takes the
 * rest from the predictor P (degree k through the last k + 1 points):
 *
 *   xdot_{n+1} = P_x'(t_{n+1}) + c0 (x - P_x(t_{n+1})),  the same for v, vdot,
 *
 * i.e. r_x = sum_j (p_j' - c0 p_j) x_{n-j} with p_j the predictor's weights
 * (the derivative of the polynomial through x_{n+1} and P at the equally
 * spaced t_{n+1} - j h). Its error test is IDA's ck |y - y_pred| and its
 * order estimates E_j = j! h^{j+1} |[y_{n+1}, ..., y_{n-j}]| (LocalError,
 * OrderEstimatesOf), its order rules IDA's on terr_j = (j + 1) E_j
 * (LowerOrderFLC, SelectOrderFLC), and its step grows from 1.5 h on. A step
 * whose predictor nodes' spacings differ by more than a factor 4 (a switch
 * to fixed steps) takes the variable coefficients.
 *
 * Local error of the variable coefficients (positions, and velocities times
 * h; the multipliers are left out, as IDA leaves algebraic variables out
 * with IDASetSuppressAlg):
 *   LTE_k = (x_{n+1} - x_pred) / (c0 psi_{k+1}),  psi_j = t_{n+1} - t_{n+1-j},
 * and the same with v, times h (the norm is the larger of the two, both
 * projected on the constraints' tangent space; doc/theory.md section 8 for
 * why the velocities must enter at order 5; the velocities' part less a
 * bound of what the positions' roundoff noise makes of it, PositionNoise),
 * from y_{n+1} - y_pred = [y_{n+1}, ..., y_{n-k}] prod_{j<=k+1} psi_j and
 * LTE_k = y^(k+1)/(k+1)! prod_{j<=k} psi_j / c0 (for constant steps
 * h^{k+1} y^(k+1) / ((k+1) sum_{j<=k} 1/j): 1/2, 2/9, ... as it should be).
 * The same with the divided differences of orders k and k + 2 (of x and of
 * h v; at index 3, maxord 5 and k >= 4 projected like the error test's
 * estimate) estimates the error at orders k - 1 and k + 1; order and step
 * follow IDA's rules except that E_{k-1} <= E_k alone lowers the order,
 * that h is kept only for factors in (1, 1.1), and that order 5 takes no
 * longer steps than order 4 would:
 * lower the order when E_{k-1} <= E_k, raise it after k + 1 steps at order
 * k when E_{k+1} < E_k; h_new = h (2 E + 1e-4)^{-1/(k+1)}, at most 2 h, kept
 * when the factor lies in (1, 1.1), cut to [0.5, 0.9] h when below 1; at
 * order 5 at most the factor of E_4. At the start the order rises by one
 * every step (while the estimates allow).
 * Under error control a step that would leave less than a tenth of itself
 * before the stop time stretches to land on it, and one that would leave
 * less than one more step takes half the rest (no short landing step).
 * Error test failures: the first lowers the order if E_{k-1} <= E_k and cuts
 * h by 0.9 (2 E)^{-1/(k+1)} in [0.25, 0.9], the second by 0.25, the third
 * also drops to order 1; Newton failures cut h by 0.25.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include "lgn_impl.h"
#include "lgn_methods.h"

#define BDF_HMAX_RATIO SUN_RCONST(2.0)
#define BDF_CUT_FAIL   SUN_RCONST(0.25)
#define BDF_NEWTON_SHARE SUN_RCONST(0.1) /* of epcon times the error test's tolerances */
#define BDF_LAND_STRETCH SUN_RCONST(1.1) /* a step lands on tstop within 10 % */
/* the fixed-leading-coefficient form grows h once the estimate allows 1.5 h
 * (IDA: 2, IDASetEtaFixedStepBounds): measured on the heavy top, doc/theory.md
 * section 8 */
#define BDF_FLC_GROW SUN_RCONST(1.5)
/* the variable coefficients keep h only while the estimate allows less
 * than 1.1 h (IDA's 2 let the step settle anywhere in a factor 2^(k+2) of
 * the estimate: half-decade tolerances 6.9 times off their neighbours;
 * doc/theory.md section 8) */
#define BDF_VC_GROW SUN_RCONST(1.1)

/* =============================================================================
 * Coefficients
 * ===========================================================================*/

/* d_j = l_j'(tau_0): d_0 = sum_{i>0} 1/(tau_0 - tau_i), and for j > 0
 * d_j = prod_{i != 0, j} (tau_0 - tau_i) / prod_{i != j} (tau_j - tau_i). */
static void LagrangeDerivativeAtFirst(const sunrealtype *tau, int n, sunrealtype *d)
{
  int i, j;
  d[0] = SUN_RCONST(0.0);
  for (i = 1; i <= n; i++) d[0] += SUN_RCONST(1.0) / (tau[0] - tau[i]);
  for (j = 1; j <= n; j++) {
    sunrealtype num = SUN_RCONST(1.0), den = SUN_RCONST(1.0);
    for (i = 0; i <= n; i++) {
      if (i == j) continue;
      den *= tau[j] - tau[i];
      if (i != 0) num *= tau[0] - tau[i];
    }
    d[j] = num / den;
  }
}

/* =============================================================================
 * The history
 * ===========================================================================*/

/* Start anew from the state at t_n (one point). */
static void StartHistory(LGNMem mem)
{
  mem->bdf_t[0] = mem->tn;
  memcpy(mem->bdf_q, lgnData(mem->q), (size_t)mem->nq * sizeof(sunrealtype));
  memcpy(mem->bdf_v, lgnData(mem->v), (size_t)mem->nv * sizeof(sunrealtype));
  if (mem->m > 0) memcpy(mem->bdf_l, lgnData(mem->lambda), (size_t)mem->m * sizeof(sunrealtype));
  mem->bdf_vgain[0]     = SUN_RCONST(0.0); /* v_0 is given */
  mem->bdf_nhist        = 1;
  mem->bdf_order        = 1;
  mem->bdf_nsteps_order = 0;
  mem->bdf_phase0       = SUNTRUE;
  mem->bdf_chart_t      = NAN;
  mem->bdf_ns           = 0;
  mem->bdf_hused        = SUN_RCONST(0.0);
}

/* The accepted state at t_n becomes the newest point. */
static void PushHistory(LGNMem mem)
{
  const size_t nq = (size_t)mem->nq, nv = (size_t)mem->nv, m = (size_t)mem->m;
  const int n = SUNMIN(mem->bdf_nhist, LGN_BDF_MAXHIST - 1);
  memmove(mem->bdf_t + 1, mem->bdf_t, (size_t)n * sizeof(sunrealtype));
  memmove(mem->bdf_vgain + 1, mem->bdf_vgain, (size_t)n * sizeof(sunrealtype));
  memmove(mem->bdf_q + nq, mem->bdf_q, (size_t)n * nq * sizeof(sunrealtype));
  memmove(mem->bdf_v + nv, mem->bdf_v, (size_t)n * nv * sizeof(sunrealtype));
  mem->bdf_t[0] = mem->tn;
  mem->bdf_vgain[0] = mem->bdf_vgain1;
  memcpy(mem->bdf_q, lgnData(mem->q), nq * sizeof(sunrealtype));
  memcpy(mem->bdf_v, lgnData(mem->v), nv * sizeof(sunrealtype));
  if (m > 0) {
    memmove(mem->bdf_l + m, mem->bdf_l, (size_t)n * m * sizeof(sunrealtype));
    memcpy(mem->bdf_l, lgnData(mem->lambda), m * sizeof(sunrealtype));
  }
  mem->bdf_nhist   = n + 1;
  mem->bdf_chart_t = NAN;
}

/* x_{n-j} = log(q_n^{-1} q_{n-j}), once per t_n (x_n = 0). The logarithm
 * is the principal one (rotation angles up to pi): once the history turns
 * further, x jumps by about 2 pi and the BDF derivative would be wrong. So
 * the history is cut at the first point whose difference from its
 * neighbour, d_j = x_{n-j} - x_{n-j+1}, jumps against the previous one
 * scaled by the step sizes: |d_j| > 2 r_j |d_{j-1}| + 1/2 (inf-norms,
 * r_j = (t_{n-j+1} - t_{n-j}) / (t_{n-j+2} - t_{n-j+1})). A wrap adds about
 * 2 pi, which this sees up to about 1.9 rad per step; no extra logarithm
 * is needed. */
static int ChartCoordinates(LGNMem mem)
{
  LGNGroup G = mem->G;
  const sunindextype nq = mem->nq, nv = mem->nv;
  sunindextype i;
  int j, ret;
  if (mem->bdf_chart_t == mem->tn) return LGN_SUCCESS;
  mem->dense_valid = SUNFALSE; /* the dense output reads the old chart */
  memset(mem->bdf_x, 0, (size_t)nv * sizeof(sunrealtype));
  for (j = 1; j < mem->bdf_nhist; j++) {
    sunrealtype *x = mem->bdf_x + j * nv;
    sunrealtype dmax = SUN_RCONST(0.0), dprev = SUN_RCONST(0.0);
    ret = G->ops.compose_log(G, mem->bdf_q, mem->bdf_q + j * nq, x);
    ret = lgnAgree(mem, ret != 0 ? lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve")
                                  : LGN_SUCCESS);
    if (ret != LGN_SUCCESS) return ret;
    if (j == 1) continue;
    for (i = 0; i < nv; i++) {
      dmax  = SUNMAX(dmax, fabs(x[i] - x[i - nv]));
      dprev = SUNMAX(dprev, fabs(x[i - nv] - x[i - 2 * nv]));
    }
    /* the history is cut on every rank where it leaves one rank's chart */
    if (lgnMaxAll(mem, dmax > SUN_RCONST(2.0) * dprev * (mem->bdf_t[j - 1] - mem->bdf_t[j]) /
                                  (mem->bdf_t[j - 2] - mem->bdf_t[j - 1]) +
                              SUN_RCONST(0.5)
                          ? SUN_RCONST(1.0)
                          : SUN_RCONST(0.0)) > SUN_RCONST(0.0)) { /* beyond the chart */
      mem->bdf_nhist = j;
      break;
    }
  }
  mem->bdf_chart_t = mem->tn;
  return LGN_SUCCESS;
}

/* Error control: the highest order up to k whose nodes t_{n+1}, t_n, ...,
 * t_{n+1-k} have neighbouring spacings within a factor 4 of each other. The
 * controller changes h by at most 2 from step to step, except when it
 * lands on a stop time with a short step and then goes on from the step it
 * wanted; a short step inside the nodes makes the variable coefficients of
 * the higher orders amplify the history's errors. (Fixed steps keep their
 * grid: LGNSolve steps past tout and interpolates.) */
static int SpacingOrder(const LGNMem mem, sunrealtype h, int k)
{
  sunrealtype prev = h, d;
  int j;
  for (j = 1; j < k; j++) {
    d = mem->bdf_t[j - 1] - mem->bdf_t[j];
    if (d > SUN_RCONST(4.0) * prev || prev > SUN_RCONST(4.0) * d) return j;
    prev = d;
  }
  return k;
}

/* =============================================================================
 * One attempt
 * ===========================================================================*/

/* lambda1 = the polynomial of degree kp through the last kp + 1
 * multipliers at t_{n+1} (weights p from the predictor), or lambda_n. */
static void PredictMultipliers(LGNMem mem, int kp, const sunrealtype *p)
{
  const sunindextype m = mem->m;
  sunrealtype *l1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  sunindextype i;
  int j;
  if (m == 0) return;
  if (kp == 0) {
    memcpy(l1, lgnData(mem->lambda), (size_t)m * sizeof(sunrealtype));
    return;
  }
  for (i = 0; i < m; i++) {
    sunrealtype l = SUN_RCONST(0.0);
    for (j = 0; j <= kp; j++) l += p[j] * mem->bdf_l[j * m + i];
    l1[i] = l;
  }
}

/* The fixed-leading-coefficient constant of order k: alpha_s = sum_{j<=k}
 * 1/j (IDA's -alphas; c0 = alpha_s / h). */
static sunrealtype AlphaS(int k)
{
  sunrealtype a = SUN_RCONST(0.0);
  int j;
  for (j = 1; j <= k; j++) a += SUN_RCONST(1.0) / (sunrealtype)j;
  return a;
}

/* The coefficients of order k and size h, the predictor, and Newton. The
 * state at t_n is not touched. */
static int Attempt(LGNMem mem, sunrealtype h, int k, LGNStepCoeffs *c)
{
  const sunindextype nv = mem->nv;
  const int nh = mem->bdf_nhist;
  const sunrealtype t1 = mem->tn + h;
  const sunrealtype *X = mem->bdf_x, *V = mem->bdf_v;
  sunbooleantype flc = mem->bdf_form == LGN_BDF_FIXED_LEADING && nh > 1;
  sunrealtype tau[LGN_BDF_MAXHIST + 1], d[LGN_BDF_MAXHIST + 1], dp[LGN_BDF_MAXHIST + 1];
  sunrealtype *xp = mem->bdf_xpred, *vp = mem->bdf_vpred;
  sunbooleantype used_old = SUNFALSE;
  sunindextype i;
  int j, kp = 0, flag;

  /* the predictor: the polynomial P of degree kp through the last kp + 1
   * points at t_{n+1} (weights d_j), and for the fixed leading coefficient
   * its derivative (weights dp_j) */
  if (nh == 1) {
    const sunrealtype *v0 = lgnData(mem->v), *a0 = lgnData(mem->vdot);
    for (i = 0; i < nv; i++) {
      xp[i] = h * v0[i];
      vp[i] = v0[i] + h * a0[i];
    }
    mem->bdf_vpgain = mem->bdf_vgain[0];
  } else {
    kp = SUNMIN(k, nh - 1);
    /* the derivative weights only for the fixed leading coefficient (the
     * basis' derivative costs (kp + 1)^3 divisions) */
    lgnLagrangeBasis(mem->bdf_t, kp, t1, d, flc ? dp : NULL);
    for (i = 0; i < nv; i++) {
      sunrealtype x = SUN_RCONST(0.0), v = SUN_RCONST(0.0);
      for (j = 0; j <= kp; j++) {
        x += d[j] * X[j * nv + i];
        v += d[j] * V[j * nv + i];
      }
      xp[i] = x;
      vp[i] = v;
    }
    mem->bdf_vpgain = SUN_RCONST(0.0);
    for (j = 0; j <= kp; j++) mem->bdf_vpgain += fabs(d[j]) * mem->bdf_vgain[j];
  }

  /* the fixed leading coefficient extrapolates P' from the predictor's
   * nodes: with spacings more than a factor 4 apart (a switch from error
   * control to a fixed step 40 times longer was seen to diverge at order 4)
   * the step takes the variable coefficients */
  if (flc && SpacingOrder(mem, h, kp + 1) < kp + 1) flc = SUNFALSE;
  mem->bdf_step_flc = flc;
  if (flc) {
    /* fixed leading coefficient (IDA): xdot = P'(t_{n+1}) + c0 (x - P(t_{n+1}))
     * with c0 = alpha_s / h, so r_x = sum_j (dp_j - c0 d_j) x_{n-j} (the same
     * for v); the noise gain of v_{n+1} is c0 + sum_j |dp_j - c0 d_j| */
    const sunrealtype c0 = AlphaS(k) / h;
    mem->bdf_c0     = c0;
    mem->bdf_vgain1 = c0;
    for (j = 0; j <= kp; j++) mem->bdf_vgain1 += fabs(dp[j] - c0 * d[j]);
    for (i = 0; i < nv; i++) {
      sunrealtype rx = SUN_RCONST(0.0), rv = SUN_RCONST(0.0);
      for (j = 0; j <= kp; j++) {
        rx += (dp[j] - c0 * d[j]) * X[j * nv + i];
        rv += (dp[j] - c0 * d[j]) * V[j * nv + i];
      }
      mem->bdf_rx[i] = rx;
      mem->bdf_rv[i] = rv;
    }
  } else {
    /* variable coefficients: nodes t_{n+1}, t_n, ..., t_{n+1-k} */
    sunrealtype dc[LGN_BDF_MAXHIST + 1];
    tau[0] = t1;
    for (j = 1; j <= k; j++) tau[j] = mem->bdf_t[j - 1];
    LagrangeDerivativeAtFirst(tau, k, dc);
    mem->bdf_c0 = dc[0];
    /* v_{n+1} = T(x)(sum_j d_j x_{n+1-j}): a noise e in each x_j reaches it
     * as at most sum_j |d_j| e (PositionNoise) */
    mem->bdf_vgain1 = SUN_RCONST(0.0);
    for (j = 0; j <= k; j++) mem->bdf_vgain1 += fabs(dc[j]);
    for (i = 0; i < nv; i++) {
      sunrealtype rx = SUN_RCONST(0.0), rv = SUN_RCONST(0.0);
      for (j = 1; j <= k; j++) {
        rx += dc[j] * X[(j - 1) * nv + i];
        rv += dc[j] * V[(j - 1) * nv + i];
      }
      mem->bdf_rx[i] = rx;
      mem->bdf_rv[i] = rv;
    }
  }
  memcpy(mem->sigma, xp, (size_t)nv * sizeof(sunrealtype));
  PredictMultipliers(mem, kp, d);

  /* Newton on (x, lambda): d xdot / dx = c0, d vdot / dx ~ c0^2 (T aside) */
  c->h       = h;
  c->t1      = t1;
  c->gamma_p = mem->bdf_c0;
  c->beta_p  = mem->bdf_c0 * mem->bdf_c0;
  c->scale   = SUN_RCONST(1.0) / c->beta_p;
  c->hmat    = SUN_RCONST(1.0) / mem->bdf_c0;
  c->qscale  = SUN_RCONST(1.0);
  for (i = 0; i < mem->nq; i++) c->qscale = SUNMAX(c->qscale, fabs(lgnData(mem->q)[i]));
  c->qscale = lgnMaxAll(mem, c->qscale);

  mem->dense_valid = SUNFALSE; /* the iterate overwrites the last step's start */
  mem->kin->bind(mem);
  flag = lgnNewton(mem, c, SUNFALSE, &used_old);
  if (flag == LGN_CONV_FAILURE && used_old) {
    mem->nrestart++;
    memcpy(mem->sigma, xp, (size_t)nv * sizeof(sunrealtype));
    PredictMultipliers(mem, kp, d);
    flag = lgnNewton(mem, c, SUNTRUE, &used_old);
  }
  if (flag != LGN_SUCCESS) mem->nfails++;
  return flag;
}

/* The noise of the positions x_j in the RMS of the error test's weights w:
 * Newton's roundoff floor 100 eps |q| (lgn_newton.c, CorrectionNorm), below
 * which the iteration does not resolve x. The velocities v = T(x)(sum_j d_j
 * x_j) carry it times their gain sum_j |d_j| (up to 1/h times 6.7, 10.7, 17
 * at orders 3, 4, 5), and their differences in the estimates more: at tol
 * 1e-13 on the heavy top that is the size of the velocities' estimates
 * (doc/theory.md section 8), which are therefore taken less this bound. */
static sunrealtype PositionNoise(const LGNMem mem, const LGNStepCoeffs *c, const sunrealtype *w)
{
  sunrealtype s = SUN_RCONST(0.0);
  sunindextype i;
  for (i = 0; i < mem->nv_own; i++) s += w[i] * w[i];
  lgnSumAll(mem, &s, 1); /* the weights' RMS over all ranks */
  return SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * c->qscale * sqrt(s / mem->nv_all);
}

/* The local error estimate of order k (into mem->ele: the positions) and
 * its norm: the larger of the positions' LTE_k and the velocities' h LTE_k,
 * both projected on the constraints' tangent space and in the weights of
 * the positions (the velocity error of the step, as the displacement it
 * makes over the step). The velocities must be in the test: in the chart
 * of q_n the positions of a spinning body are nearly odd in t - t_n, and
 * their LTE_5 (x^(6), centred on t_{n-2}) drops to O(h^7) while the
 * velocities' error O(h^6) still drives the global error (doc/theory.md
 * section 8). */
static int LocalError(LGNMem mem, const LGNStepCoeffs *c, int k, sunrealtype *err)
{
  const sunindextype nv = mem->nv;
  const sunrealtype *v1 = lgnData(mem->v1);
  sunrealtype f = SUN_RCONST(1.0), ev;
  sunindextype i;
  int flag;
  mem->bdf_sigck = SUN_RCONST(1.0);
  if (mem->bdf_nhist > 1 && mem->bdf_step_flc) {
    /* IDA's error test (IDASetCoeffs, IDATestError): ck |y - y_pred| with
     *   ck = max(|alpha_k + alpha_0 - alpha_s|, alpha_k),
     *   alpha_j = h / psi_{j+1}, alpha_0 = sum_{j<=k} h / psi_j,
     *   alpha_s = sum_{j<=k} 1/j,  psi_j = t_{n+1} - t_{n+1-j}
     * (1/(k+1) for constant steps; the term alpha_0 - alpha_s is the
     * difference of the variable leading coefficient from the fixed one,
     * times h), and the order/step estimate sigma_k |y - y_pred| with
     * sigma_k = k! prod_{j=1..k} h / psi_{j+1} (bdf_sigck = sigma_k / ck) */
    const sunrealtype h = c->h, ak = h / (c->t1 - mem->bdf_t[k]);
    sunrealtype a0 = SUN_RCONST(0.0), sig = SUN_RCONST(1.0);
    int j;
    for (j = 1; j <= k; j++) {
      a0 += h / (c->t1 - mem->bdf_t[j - 1]);
      sig *= (sunrealtype)j * h / (c->t1 - mem->bdf_t[j]);
    }
    f = SUNMAX(fabs(ak + a0 - AlphaS(k)), ak);
    mem->bdf_sigck = sig / f;
  } else if (mem->bdf_nhist > 1) /* else the Taylor predictor: LTE_1 = y - y_pred */
    f = SUN_RCONST(1.0) / (mem->bdf_c0 * (c->t1 - mem->bdf_t[k]));
  for (i = 0; i < nv; i++) mem->ele[i] = f * (mem->sigma[i] - mem->bdf_xpred[i]);
  flag = lgnErrorNorm(mem, c, mem->sigma, SUN_RCONST(1.0), err);
  if (flag != LGN_SUCCESS) return flag;
  /* the velocities, projected the same way (ele keeps the positions) */
  memcpy(mem->bdf_dd, mem->ele, (size_t)nv * sizeof(sunrealtype));
  for (i = 0; i < nv; i++) mem->ele[i] = c->h * f * (v1[i] - mem->bdf_vpred[i]);
  flag = lgnErrorNorm(mem, c, mem->sigma, SUN_RCONST(1.0), &ev);
  memcpy(mem->ele, mem->bdf_dd, (size_t)nv * sizeof(sunrealtype));
  /* less what the positions' noise can make of it: h f (v_{n+1} - sum_j
   * p_j v_{n-j}), each v with its gain */
  ev -= c->h * f * (mem->bdf_vgain1 + mem->bdf_vpgain) * PositionNoise(mem, c, mem->ewt);
  *err = SUNMAX(*err, ev);
  return flag;
}

/* =============================================================================
 * Order and step selection (after an accepted step)
 * ===========================================================================*/

/* The variable coefficients at index 3 and maxord 5 project the estimates
 * that the rules between orders 4 and 5 read (at orders k >= 4) on the
 * constraints' tangent space, as the error test projects its estimate: on
 * the heavy top the unprojected divided differences are some 200 times the
 * projected ones (their part normal to the constraints, not the error),
 * and with the order-5 limit (Order5Limit) E_4 <= E_5 of that kind lowered
 * the order to steps whose order-4 error was 5 times the tolerance: three
 * failed error tests in a row, then order 1. Each projection is a solve
 * with the step's factored matrix; projected at every order and maxord,
 * the heavy top took about 10 % more instructions per step, and maxord 4
 * was no more regular (doc/theory.md section 8). GGL keeps them unprojected
 * (projected, its maxord 4 lost tolerance proportionality: exponent 0.39),
 * and the fixed leading coefficient keeps IDA's unprojected estimates. */
static sunbooleantype ProjectsOrderEstimates(const LGNMem mem, int k)
{
  return mem->bdf_form == LGN_BDF_VARIABLE_COEFF && mem->m > 0 &&
         mem->constr_index == LGN_CONSTR_INDEX3 && mem->bdf_maxord == 5 && k >= 4;
}

/* mem->work_nv <- its projection (mem->ele is the projection's work space;
 * OrderEstimates restores it). A failed solve leaves it unprojected. */
static void ProjectOrderEstimate(LGNMem mem, const LGNStepCoeffs *c)
{
  const size_t bytes = (size_t)mem->nv * sizeof(sunrealtype);
  memcpy(mem->ele, mem->work_nv, bytes);
  if (lgnProjectEstimate(mem, c) == LGN_SUCCESS) memcpy(mem->work_nv, mem->ele, bytes);
}

/* Estimates E_j of the error of orders j = k - 2 ... k + 1 of the step just
 * taken (E[j - k + 2]; negative: not available) from the divided
 * differences of y over t_{n+1}, t_n, ... (y1 the new point, Y the
 * history), times s, in the weights of the error test; maximum with E.
 * noise > 0 (the velocities): each less the bound of what the positions'
 * noise (PositionNoise) makes of it, at least 0. */
static void OrderEstimatesOf(LGNMem mem, const LGNStepCoeffs *c, int k, const sunrealtype *y1,
                             const sunrealtype *Y, sunrealtype s, sunrealtype noise,
                             sunrealtype E[4])
{
  const sunindextype nv = mem->nv;
  const sunbooleantype project = ProjectsOrderEstimates(mem, k);
  const int npts = SUNMIN(mem->bdf_nhist + 1, k + 3);
  sunrealtype tt[LGN_BDF_MAXHIST + 1], *a = mem->bdf_dd;
  sunrealtype den[LGN_BDF_MAXHIST + 1][LGN_BDF_MAXHIST + 1];
  sunindextype i;
  int j, m, o;

  tt[0] = c->t1;
  memcpy(a, y1, (size_t)nv * sizeof(sunrealtype));
  for (j = 1; j < npts; j++) {
    tt[j] = mem->bdf_t[j - 1];
    memcpy(a + j * nv, Y + (j - 1) * nv, (size_t)nv * sizeof(sunrealtype));
  }
  /* in place: a_m <- [P_0 .. P_m] (one division per node pair, not per
   * component) */
  for (m = 1; m < npts; m++)
    for (j = npts - 1; j >= m; j--) {
      const sunrealtype r = SUN_RCONST(1.0) / (tt[j] - tt[j - m]);
      for (i = 0; i < nv; i++) a[j * nv + i] = (a[j * nv + i] - a[(j - 1) * nv + i]) * r;
    }
  /* the velocities' noise: den[m][j] = prod_{l <= m, l != j} (tt_j - tt_l),
   * the denominators of the divided difference over tt_0 .. tt_m, built
   * one node at a time (each product in the order l = 0, 1, ...) */
  if (noise > SUN_RCONST(0.0)) {
    den[0][0] = SUN_RCONST(1.0);
    for (m = 1; m < npts; m++) {
      den[m][m] = SUN_RCONST(1.0);
      for (j = 0; j < m; j++) {
        den[m][j] = den[m - 1][j] * (tt[j] - tt[m]);
        den[m][m] *= tt[m] - tt[j];
      }
    }
  }
  for (o = 0; o < 4; o++) {
    const int ord = k - 2 + o; /* E_ord uses [P_0 .. P_{ord+1}] */
    sunrealtype prod = s, c0 = SUN_RCONST(0.0), fac;
    /* projected: E_{k-2}, and E_{k+1} at maxord, are left out (no rule of
     * this form reads them) */
    if (ord < 1 || ord + 1 >= npts) continue;
    if (project && (o == 0 || (o == 3 && k >= mem->bdf_maxord))) continue;
    for (j = 1; j <= ord; j++) {
      prod *= c->t1 - tt[j];
      c0 += SUN_RCONST(1.0) / (c->t1 - tt[j]);
    }
    fac = prod / c0;
    if (mem->bdf_form == LGN_BDF_FIXED_LEADING) {
      /* IDA: E_ord = sigma_ord |phi_{ord+1}|, phi_m = [P_0 .. P_m] prod_{j<=m}
       * psi_j, sigma_ord = ord! prod_{j<=ord} h / psi_{j+1}: ord! h^{ord+1}
       * [P_0 .. P_{ord+1}] (for ord = k + 1 IDA takes the difference of two
       * successive y - y_pred, the same for constant steps) */
      fac = s;
      for (j = 1; j <= ord; j++) fac *= (sunrealtype)j * c->h;
      fac *= c->h;
    }
    for (i = 0; i < nv; i++) mem->work_nv[i] = a[(ord + 1) * nv + i] * fac;
    if (project) ProjectOrderEstimate(mem, c);
    if (noise > SUN_RCONST(0.0)) { /* the velocities: less their noise */
      /* [y_0 .. y_m] = sum_j y_j / prod_{i != j} (tt_j - tt_i), each y_j
       * (v_{n+1-j}) with the noise gain g_j times the positions' noise */
      sunrealtype nz = SUN_RCONST(0.0), e;
      for (j = 0; j <= ord + 1; j++)
        nz += (j == 0 ? mem->bdf_vgain1 : mem->bdf_vgain[j - 1]) / fabs(den[ord + 1][j]);
      e = lgnWrmsNorm(mem, mem->work_nv, mem->ewt) - nz * noise * fac;
      E[o] = SUNMAX(E[o], SUNMAX(SUN_RCONST(0.0), e));
    } else
      E[o] = SUNMAX(E[o], lgnWrmsNorm(mem, mem->work_nv, mem->ewt));
  }
}

/* E_{k-2} ... E_{k+1} of the error test's kind (projected or not,
 * ProjectsOrderEstimates): positions x in the chart of q_n and velocities
 * times h. The step's own estimate in mem->ele is kept. */
static void OrderEstimates(LGNMem mem, const LGNStepCoeffs *c, int k, sunrealtype E[4])
{
  const size_t bytes = (size_t)mem->nv * sizeof(sunrealtype);
  E[0] = E[1] = E[2] = E[3] = -SUN_RCONST(1.0);
  memcpy(mem->bdf_ele_keep, mem->ele, bytes);
  OrderEstimatesOf(mem, c, k, mem->sigma, mem->bdf_x, SUN_RCONST(1.0), SUN_RCONST(0.0), E);
  OrderEstimatesOf(mem, c, k, lgnData(mem->v1), mem->bdf_v, c->h,
                   PositionNoise(mem, c, mem->ewt), E);
  memcpy(mem->ele, mem->bdf_ele_keep, bytes);
}

/* The step factor for an error estimate E at order k: r = (2 E +
 * 1e-4)^{-1/(k+1)}, at most 2; kept at 1 for r in (1, grow) (IDA's
 * eta_max_fx, 2 by default; here 1.5 in the fixed-leading-coefficient form,
 * 1.1 in the variable-coefficient form), cut to [0.5, 0.9] below 1. */
static sunrealtype StepFactor(sunrealtype E, int k, sunrealtype grow)
{
  sunrealtype r = pow(SUN_RCONST(2.0) * E + SUN_RCONST(1.0e-4),
                      -SUN_RCONST(1.0) / (sunrealtype)(k + 1));
  if (r >= BDF_HMAX_RATIO) return BDF_HMAX_RATIO;
  if (r >= grow) return r;
  if (r <= SUN_RCONST(1.0)) return SUNMAX(SUN_RCONST(0.5), SUNMIN(SUN_RCONST(0.9), r));
  return SUN_RCONST(1.0);
}

/* A lower order when E_{k-1} <= E_k. (IDA also asks E_{k-2} <= E_k at
 * k > 2 (IDATestError): on the heavy top that keeps order 5 where its
 * error is 10 times maxord 4's, bench/bdf_lte --sweep.) */
static sunbooleantype LowerOrder(const sunrealtype E[4], int k)
{
  return k > 1 && E[1] >= SUN_RCONST(0.0) && E[2] >= SUN_RCONST(0.0) && E[1] <= E[2];
}

/* The fixed-leading-coefficient form: IDA's terms terr_j = (j + 1) E_j
 * (IDATestError). Lower at k = 2 when terr_1 <= terr_2 / 2 (IDA), at k > 2
 * when terr_{k-1} <= terr_k. IDA also asks terr_{k-2} <= terr_k at k > 2:
 * on the heavy top that keeps order 5 with steps too long (error ~ tol^0.6
 * ... tol^0.7 at maxord 5, bench/bdf_forms), as it did in the
 * variable-coefficient form (LowerOrder). */
static sunbooleantype LowerOrderFLC(const sunrealtype E[4], int k)
{
  const sunrealtype tk = (sunrealtype)(k + 1) * E[2], tkm1 = (sunrealtype)k * E[1];
  if (k < 2 || E[1] < SUN_RCONST(0.0) || E[2] < SUN_RCONST(0.0)) return SUNFALSE;
  if (k == 2) return tkm1 <= SUN_RCONST(0.5) * tk;
  return tkm1 <= tk;
}

/* The fixed-leading-coefficient form after an accepted step: IDA's
 * choice (IDACompleteStep) among k - 1, k, k + 1 once the step has been
 * taken k + 2 times at this order and size (bdf_ns): raise when
 * terr_{k+1} < terr_k (at k = 1 when below terr_k / 2), lower when
 * terr_{k-1} <= min(terr_k, terr_{k+1}). The start-up is Lignum's (the
 * order rises each step while E_{k+1} < E_k). err is the error test's
 * value (ck); the step follows sigma_k (bdf_sigck). */
static sunrealtype SelectOrderFLC(LGNMem mem, const LGNStepCoeffs *c, int k, sunrealtype err)
{
  sunrealtype E[4], Enew, scale;
  int knew = k;
  OrderEstimates(mem, c, k, E);
  /* from the unprojected estimates to the projected sigma measure */
  scale = E[2] > SUN_RCONST(0.0) ? err * mem->bdf_sigck / E[2] : mem->bdf_sigck;
  Enew  = err * mem->bdf_sigck;
  if (LowerOrderFLC(E, k)) {
    knew = k - 1;
    Enew = E[1] * scale;
  } else if (k < mem->bdf_maxord && mem->bdf_phase0) {
    if (E[3] < SUN_RCONST(0.0) || (E[2] >= SUN_RCONST(0.0) && E[3] < E[2])) {
      knew = k + 1; /* start-up */
      if (E[3] >= SUN_RCONST(0.0)) Enew = E[3] * scale;
    }
  } else if (k < mem->bdf_maxord && mem->bdf_ns >= k + 2 && E[3] >= SUN_RCONST(0.0) &&
             E[2] >= SUN_RCONST(0.0)) {
    const sunrealtype tk = (sunrealtype)(k + 1) * E[2], tkp1 = (sunrealtype)(k + 2) * E[3];
    if (k == 1) {
      if (tkp1 < SUN_RCONST(0.5) * tk) knew = 2;
    } else if (E[1] >= SUN_RCONST(0.0) && (sunrealtype)k * E[1] <= SUNMIN(tk, tkp1)) {
      knew = k - 1;
    } else if (tkp1 < tk) {
      knew = k + 1;
    }
    if (knew == k + 1) Enew = E[3] * scale;
    if (knew == k - 1) Enew = E[1] * scale;
  }
  if (knew < k || knew == mem->bdf_maxord) mem->bdf_phase0 = SUNFALSE;
  if (knew != k) mem->bdf_nsteps_order = -1; /* Accept counts this step */
  mem->bdf_order = knew;
  return StepFactor(Enew, knew, BDF_FLC_GROW);
}

/* The next step of order 5 is no longer than the one order 4 would take
 * (the factor for E_4 of the step just taken; else no limit, 2). On the heavy
 * top the order-5 estimate falls like h^7 while the global error of order 5
 * falls like h^5: steps from E_5 alone made the error follow tol^0.64 at
 * maxord 5. E_4 falls like h^5, so steps from it make the order-5 error
 * follow the tolerance (tol^1.0) with fewer steps for the same error than
 * before (doc/theory.md section 8). */
static sunrealtype Order5Limit(const sunrealtype E[4], int k, int knew, sunrealtype scale)
{
  /* E[j] is E_{k-2+j}: E_4 is E[1] at k = 5, E[2] at k = 4 */
  const sunrealtype E4 = knew != 5 ? -SUN_RCONST(1.0) : k == 5 ? E[1] : k == 4 ? E[2]
                                                                        : -SUN_RCONST(1.0);
  if (E4 < SUN_RCONST(0.0)) return BDF_HMAX_RATIO;
  return StepFactor(E4 * scale, 4, BDF_VC_GROW);
}

/* After an accepted step of order k with estimate err: the next order and
 * the factor of the next step. */
static sunrealtype SelectOrder(LGNMem mem, const LGNStepCoeffs *c, int k, sunrealtype err)
{
  sunrealtype E[4], Enew = err, scale;
  sunbooleantype may_raise;
  int knew = k;
  if (mem->bdf_form == LGN_BDF_FIXED_LEADING) return SelectOrderFLC(mem, c, k, err);
  OrderEstimates(mem, c, k, E);
  /* E[1], E[3] compared with E[2], their own kind (unprojected, or
   * projected at index 3 with maxord 5 from order 4 on: OrderEstimates),
   * and carried over to err's measure (projected, with the
   * velocity-constraint term) by err / E[2] */
  scale = E[2] > SUN_RCONST(0.0) ? err / E[2] : SUN_RCONST(1.0);
  may_raise = k < mem->bdf_maxord && E[3] >= SUN_RCONST(0.0) && E[2] >= SUN_RCONST(0.0) &&
              (mem->bdf_phase0 || mem->bdf_nsteps_order >= k + 1);
  if (LowerOrder(E, k)) {
    knew = k - 1;
    Enew = E[1] * scale;
  } else if (may_raise && E[3] < E[2]) {
    knew = k + 1;
    Enew = E[3] * scale;
  } else if (k < mem->bdf_maxord && mem->bdf_phase0 && E[3] < SUN_RCONST(0.0)) {
    knew = k + 1; /* start-up: not enough points for E_{k+1} yet */
  }
  /* the start-up ends as IDA's does: at a decrease, or at maxord */
  if (knew < k || knew == mem->bdf_maxord) mem->bdf_phase0 = SUNFALSE;
  if (knew != k) mem->bdf_nsteps_order = -1; /* Accept counts this step */
  mem->bdf_order = knew;
  return SUNMIN(StepFactor(Enew, knew, BDF_VC_GROW), Order5Limit(E, k, knew, scale));
}

/* =============================================================================
 * The steps
 * ===========================================================================*/

/* The history and work space, the chart of t_n; a group without log is
 * refused. */
static int Prepare(LGNMem mem)
{
  int flag;
  if (mem->G->ops.compose_log == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "BDF needs the Lie group's compose_log operation (log(q1^{-1} q2)), "
              "which this group does not set.");
    flag = LGN_ILL_INPUT;
  } else {
    flag = lgnAllocBDF(mem);
  }
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  /* a landing on a stop time or tout moves t_n to it by roundoff */
  if (mem->bdf_nhist > 0 &&
      fabs(mem->bdf_t[0] - mem->tn) <= SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF *
                                           SUNMAX(SUN_RCONST(1.0), fabs(mem->tn)))
    mem->bdf_t[0] = mem->tn;
  if (mem->bdf_nhist == 0 || mem->bdf_t[0] != mem->tn) StartHistory(mem);
  return ChartCoordinates(mem);
}

/* Commit the accepted step of order k. */
static void Accept(LGNMem mem, const LGNStepCoeffs *c, int k)
{
  lgnCommitStep(mem, c);
  PushHistory(mem);
  mem->bdf_last_order = k;
  mem->bdf_nsteps_order++;
  mem->bdf_nord[k]++;
}

/* A step of the fixed size h (LGN_STEP_FIXED): order min(maxord, points
 * in the history). */
int lgnBDFStep(LGNMem mem, sunrealtype h)
{
  LGNStepCoeffs c;
  int k, flag = lgnCheckProgress(mem, h);
  if (flag == LGN_SUCCESS) flag = Prepare(mem);
  if (flag != LGN_SUCCESS) return flag;
  k = SUNMIN(mem->bdf_maxord, mem->bdf_nhist);
  lgnFixedNewtonTolerances(mem);
  flag = Attempt(mem, h, k, &c);
  if (flag == LGN_CONV_FAILURE)
    LGN_ERROR(mem, LGN_CONV_FAILURE,
              MSG_TIME "the Newton iteration failed to converge (diverged or "
              "more than %d iterations) with h = %g (the state at t is kept).",
              (double)mem->tn, mem->maxcor, (double)h);
  if (flag != LGN_SUCCESS) return flag;
  Accept(mem, &c, k);
  mem->bdf_order = SUNMIN(mem->bdf_maxord, mem->bdf_nhist);
  return LGN_SUCCESS;
}

/* One accepted error-controlled step from t_n (LGN_SUCCESS), or the flag of
 * a failure with the state at t_n as it was. A stop time is landed on. */
int lgnBDFAdaptiveStep(LGNMem mem, sunrealtype tout)
{
  sunrealtype h, err = SUN_RCONST(0.0), factor, E[4], h_wanted;
  sunbooleantype landing;
  int nef = 0, ncf = 0, k, flag;
  LGNStepCoeffs c;

  flag = Prepare(mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!(mem->hnext > SUN_RCONST(0.0))) {
    mem->hnext     = lgnFirstStep(mem, tout);
    mem->h0_actual = mem->hnext;
  }
  h = lgnLimitStep(mem, mem->hnext);
  for (;;) {
    h_wanted = h;
    /* a step that would leave less than a tenth of itself before the stop
     * time stretches to land on it: a sliver step in the history (one of
     * 2e-9 after steps of 8e-5 was seen) forces the spacing guard's low
     * orders, and a fixed-step run continuing from the stop time takes it
     * into its coefficients */
    landing  = mem->tstop_set && mem->tn + h * BDF_LAND_STRETCH >= mem->tstop;
    if (landing) h = mem->tstop - mem->tn;
    /* and one that would leave less than a step (up to 1.1 h) takes half
     * the rest, so that the landing step is not short: a landing step
     * below a quarter of the one before forces order 1 (SpacingOrder),
     * whose error test then failed and cut h by 1e-3 (tol 1e-13 on the
     * heavy top) */
    else if (mem->tstop_set && mem->tn + SUN_RCONST(2.0) * h * BDF_LAND_STRETCH > mem->tstop)
      h = SUN_RCONST(0.5) * (mem->tstop - mem->tn);
    flag = lgnCheckProgress(mem, h);
    if (flag != LGN_SUCCESS) return flag;
    /* order k needs k + 1 points for its estimate (or the Taylor start) */
    k = SUNMAX(1, SpacingOrder(mem, h, SUNMIN(mem->bdf_order, mem->bdf_nhist - 1)));
    /* at index 3 a Newton error in x reaches v = T(x)(c0 x + r_x) times
     * c0 ~ k/h, and the history: a tenth of epcon times the error test's
     * tolerances (measured on the heavy top: with modified Newton the error
     * then follows tol^1.0 instead of tol^0.8) */
    lgnNewtonTolerancesPerStep(mem, h, BDF_NEWTON_SHARE);
    mem->lsetup_recoverable = SUNTRUE;
    flag = Attempt(mem, h, k, &c);
    mem->lsetup_recoverable = SUNFALSE;
    if (flag == LGN_SUCCESS) flag = LocalError(mem, &c, k, &err);
    if (flag == LGN_SUCCESS && mem->lambda_errcon) { /* the multipliers too (lgn_output.c) */
      sunrealtype err_l;
      flag = lgnMultiplierError(mem, c.t1, &err_l);
      err  = SUNMAX(err, err_l);
    }
    mem->err_norm = err;

    if (flag == LGN_SUCCESS && err <= SUN_RCONST(1.0)) {
      /* IDA's ns: consecutive steps of this size and order, up to k + 2 */
      mem->bdf_ns    = h == mem->bdf_hused && k == mem->bdf_last_order
                           ? SUNMIN(mem->bdf_ns + 1, k + 2) : 1;
      mem->bdf_hused = h;
      factor = SelectOrder(mem, &c, k, err);
      if (nef > 0 || ncf > 0) factor = SUNMIN(factor, SUN_RCONST(1.0));
      Accept(mem, &c, k);
      if (landing) mem->tn = mem->tstop;
      mem->err_prev = err;
      /* after a landing, go on from the step the controller wanted (the
       * spacing guard lowers the order while the short step is in the
       * history) */
      mem->hnext = lgnLimitStep(mem, landing ? SUNMAX(h * factor, h_wanted) : h * factor);
      return LGN_SUCCESS;
    }

    mem->bdf_phase0 = SUNFALSE;
    if (flag == LGN_SUCCESS) { /* error test failed */
      mem->netf++;
      nef++;
      if (nef >= mem->maxnef || h <= mem->hmin) {
        LGN_ERROR(mem, LGN_ERR_FAILURE,
                  MSG_TIME "the error test failed %d times, the last with "
                  "h = %g, order %d and |e| = %g%s (the state at t is kept).",
                  (double)mem->tn, nef, (double)h, k, (double)err,
                  h <= mem->hmin ? " at the minimum step size" : "");
        return LGN_ERR_FAILURE;
      }
      if (nef == 1) {
        const sunbooleantype flc = mem->bdf_form == LGN_BDF_FIXED_LEADING;
        OrderEstimates(mem, &c, k, E);
        if (flc) err *= mem->bdf_sigck; /* IDA: the step from sigma_k, not ck */
        if ((flc ? LowerOrderFLC(E, k) : LowerOrder(E, k)) && E[2] > SUN_RCONST(0.0)) {
          mem->bdf_order = k - 1;
          mem->bdf_nsteps_order = 0;
          err *= E[1] / E[2];
          k--;
        }
        factor = SUN_RCONST(0.9) * pow(SUN_RCONST(2.0) * err + SUN_RCONST(1.0e-4),
                                       -SUN_RCONST(1.0) / (sunrealtype)(k + 1));
        factor = SUNMAX(BDF_CUT_FAIL, SUNMIN(SUN_RCONST(0.9), factor));
      } else {
        if (nef >= 3) {
          mem->bdf_order = 1;
          mem->bdf_nsteps_order = 0;
        }
        factor = BDF_CUT_FAIL;
      }
    } else if (flag == LGN_CONV_FAILURE || flag == LGN_RECOVERABLE) {
      /* singular on any rank: the same flag on all */
      const sunbooleantype singular =
          lgnMaxAll(mem, flag == LGN_RECOVERABLE && mem->last_lin_flag != 0 ? SUN_RCONST(1.0)
                                                                             : SUN_RCONST(0.0)) >
          SUN_RCONST(0.0);
      ncf++;
      if (ncf >= mem->maxncf || h <= mem->hmin) {
        const int out = flag == LGN_CONV_FAILURE ? LGN_CONV_FAILURE
                      : singular                 ? LGN_LSETUP_FAIL
                                                 : LGN_REPTD_CALLBACK_ERR;
        LGN_ERROR(mem, out,
                  MSG_TIME "%s %d times, the last with h = %g%s (the state at t "
                  "is kept).%s", (double)mem->tn,
                  flag == LGN_CONV_FAILURE ? "the Newton iteration failed to converge"
                  : singular ? "the iteration matrix was singular"
                             : "a callback failed recoverably",
                  ncf, (double)h, h <= mem->hmin ? " at the minimum step size" : "",
                  singular ? mem->diag_text : "");
        return out;
      }
      factor = BDF_CUT_FAIL;
    } else {
      return flag; /* unrecoverable: reported where it happened */
    }
    h = lgnLimitStep(mem, h * factor);
    mem->hnext = h;
  }
}
