/* -----------------------------------------------------------------------------
 * Rheonomic constraints Phi(q, t) (LGNSetConstraintTimeFn) on a model with
 * an exact solution: a bead of mass m on a rod that turns about the origin
 * at the constant rate w, in the plane (group R^2, no gravity):
 *
 *   Phi(x, t) = -x sin(w t) + y cos(w t),     B = [-sin wt, cos wt],
 *   Phi_t = -w (x cos wt + y sin wt),
 *   z = d/dt(B v + Phi_t) - B vdot = -2 w (vx cos wt + vy sin wt) - w^2 Phi,
 *
 * r(t) = r0 cosh(w t) + (rdot0 / w) sinh(w t) along the rod, and the rod
 * pushes the bead with lambda = -2 m w rdot (B^T lambda + m vdot = 0).
 *  (a) index 3 and index 2, generalized-alpha, fixed steps h = 4e-3 ...
 *      5e-4: the position and lambda at t = 1 converge to the exact ones
 *      with fitted order 2 +- 0.2; the curvature by difference quotients
 *      (with its time terms) and the analytic callback give the same
 *      positions to 1e-10 and lambda errors within 1 % of each other;
 *  (b) error control (index 3 and 2, rtol = atol = 1e-5, 1e-6, 1e-7): the
 *      error at t = 1 follows tol^p with 0.85 < p < 1.15 (the error per
 *      unit step: measured 0.99 and 1.00; 0.65 with the error per step of
 *      earlier releases) and is below
 *      1e-4 |r| at 1e-7;
 *  (c) the start at index 2: v0 along the rod only is refused as
 *      inconsistent (|B v0 + Phi_t| named), and LGNCalcIC projects it to
 *      the co-rotating velocity r0 w e_theta (exactly, M = m I);
 *  (d) without Phi_t the co-rotating start is refused at index 2 (the
 *      check uses Phi_t), and a curvature callback that leaves out the time
 *      terms gives a lambda error at the first step 100 x larger: the
 *      checks above can fail.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

#define MASS  2.0
#define OMEGA 2.0
#define R0    0.5
#define RDOT0 0.3

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = MASS;
  SM_ELEMENT_D(M, 1, 1) = MASS;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)g; (void)ud; /* g = 0 */
  return 0;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q);
  (void)ud;
  NV_Ith_S(phi, 0) = -x[0] * sin(OMEGA * t) + x[1] * cos(OMEGA * t);
  return 0;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)q; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = -sin(OMEGA * t);
  SM_ELEMENT_D(B, 0, 1) = cos(OMEGA * t);
  return 0;
}

static int ConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q);
  (void)ud;
  NV_Ith_S(phit, 0) = -OMEGA * (x[0] * cos(OMEGA * t) + x[1] * sin(OMEGA * t));
  return 0;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v);
  const sunrealtype c = cos(OMEGA * t), s = sin(OMEGA * t);
  (void)ud;
  NV_Ith_S(z, 0) = -2.0 * OMEGA * (u[0] * c + u[1] * s) -
                   OMEGA * OMEGA * (-x[0] * s + x[1] * c);
  return 0;
}

/* The time terms left out: wrong for this model (negative control). */
static int CurvatureNoTime(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(z, 0) = 0.0;
  return 0;
}

static double ExactR(double t)
{
  return R0 * cosh(OMEGA * t) + RDOT0 / OMEGA * sinh(OMEGA * t);
}

static double ExactLambda(double t)
{
  const double rdot = R0 * OMEGA * sinh(OMEGA * t) + RDOT0 * cosh(OMEGA * t);
  return -2.0 * MASS * OMEGA * rdot;
}

typedef struct {
  int index;           /* LGN_CONSTR_INDEX3 or 2 */
  double h;            /* > 0: fixed step; 0: error control */
  double tol;          /* error control */
  LGNCurvatureFn curv; /* NULL: difference quotients */
  int with_phit;
  int corotating;      /* v0 = rdot0 e_r + r0 w e_theta, else rdot0 e_r only */
  int calcic;          /* LGNCalcIC(LGN_IC_PROJECT_V) before the run */
  double tend;
  int one_step;        /* stop after one step */
} Run;

typedef struct {
  int flag;
  double t, pos_err, lambda_err, v0[2];
} Result;

static Result Integrate(const Run *run)
{
  Result res = {0, 0.0, 0.0, 0.0, {0.0, 0.0}};
  SUNContext ctx = NULL;
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q, v, lambda, v0c, y3;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunrealtype t = 0.0;
  int flag;

  SUNContext_Create(NULL, &ctx);
  q      = N_VNew_Serial(2, ctx);
  v      = N_VNew_Serial(2, ctx);
  v0c    = N_VNew_Serial(2, ctx);
  lambda = N_VNew_Serial(1, ctx);
  NV_Ith_S(q, 0) = R0;
  NV_Ith_S(q, 1) = 0.0;
  NV_Ith_S(v, 0) = RDOT0;
  NV_Ith_S(v, 1) = run->corotating ? R0 * OMEGA : 0.0;
  A   = SUNDenseMatrix(3, 3, ctx);
  y3  = N_VNew_Serial(3, ctx);
  LS  = SUNLinSol_Dense(y3, A, ctx);
  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, 1, Constr, ConstrJac);
  if (!flag && run->with_phit) flag = LGNSetConstraintTimeFn(mem, ConstrTime);
  if (!flag) flag = LGNSetCurvatureFn(mem, run->curv);
  if (!flag) flag = LGNSetConstraintIndex(mem, run->index);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag && run->h > 0.0) flag = LGNSetStepSize(mem, run->h);
  if (!flag && run->h == 0.0) {
    flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, run->tol, run->tol);
  }
  if (!flag && run->calcic) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  if (!flag) flag = LGNGetConsistentIC(mem, NULL, v0c);
  res.v0[0] = NV_Ith_S(v0c, 0);
  res.v0[1] = NV_Ith_S(v0c, 1);
  if (!flag && run->one_step) flag = LGNSolve(mem, run->tend, &t, q, v, LGN_ONE_STEP);
  else if (!flag) flag = LGNSolve(mem, run->tend, &t, q, v, LGN_NORMAL);
  if (!flag) flag = LGNGetMultipliers(mem, lambda);
  res.flag = flag;
  res.t    = t;
  if (!flag) {
    const double r = ExactR(t);
    res.pos_err = hypot(NV_Ith_S(q, 0) - r * cos(OMEGA * t),
                        NV_Ith_S(q, 1) - r * sin(OMEGA * t));
    res.lambda_err = fabs(NV_Ith_S(lambda, 0) - ExactLambda(t));
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(v0c);
  N_VDestroy(lambda);
  N_VDestroy(y3);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return res;
}

/* Slope of log(err) against log(h), least squares. */
static double FitOrder(const double *h, const double *err, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double x = log(h[i]), y = log(err[i]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int main(void)
{
  const double hs[4] = {4e-3, 2e-3, 1e-3, 5e-4};
  const int indices[2] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
  int k, i;

  /* (a) orders; DQ curvature against the analytic one */
  for (k = 0; k < 2; k++) {
    double perr[4], lerr[4], p_order, l_order;
    for (i = 0; i < 4; i++) {
      Run run = {indices[k], hs[i], 0.0, Curvature, 1, 1, 0, 1.0, 0};
      Run dq  = run;
      Result r, rdq;
      dq.curv = NULL;
      r   = Integrate(&run);
      rdq = Integrate(&dq);
      CHECK(r.flag == LGN_SUCCESS && rdq.flag == LGN_SUCCESS,
            "index %d h %g: flags %d %d", indices[k], hs[i], r.flag, rdq.flag);
      perr[i] = r.pos_err;
      lerr[i] = r.lambda_err;
      /* the quotient's error in vdot_0 (about 1e-10) reaches lambda at
       * index 3 amplified by 1/h^2 */
      CHECK_CLOSE(rdq.pos_err, r.pos_err, 1e-10, "position error, DQ vs analytic curvature");
      CHECK_CLOSE(rdq.lambda_err, r.lambda_err, 0.01 * r.lambda_err,
                  "lambda error, DQ vs analytic curvature");
      printf("index %s h %.1e: |x - x_exact| = %.3e, |lambda - exact| = %.3e\n",
             k == 0 ? "3" : "2", hs[i], perr[i], lerr[i]);
    }
    p_order = FitOrder(hs, perr, 4);
    l_order = FitOrder(hs, lerr, 4);
    printf("index %s: fitted orders position %.3f, lambda %.3f\n", k == 0 ? "3" : "2",
           p_order, l_order);
    CHECK(fabs(p_order - 2.0) <= 0.2, "position order %.3f", p_order);
    CHECK(fabs(l_order - 2.0) <= 0.2, "lambda order %.3f", l_order);
    CHECK(perr[3] < 1e-5 * ExactR(1.0), "position error %.3e at h = 5e-4", perr[3]);
  }

  /* (b) error control: the error follows the tolerance */
  for (k = 0; k < 2; k++) {
    const double tols[3] = {1e-5, 1e-6, 1e-7};
    double err[3], expo;
    for (i = 0; i < 3; i++) {
      Run run = {indices[k], 0.0, tols[i], NULL, 1, 1, 0, 1.0, 0};
      Result r = Integrate(&run);
      err[i] = r.pos_err;
      printf("index %s, tol %.0e: |x - x_exact| = %.3e\n", k == 0 ? "3" : "2", tols[i],
             r.pos_err);
      CHECK(r.flag == LGN_SUCCESS && r.t == 1.0, "adaptive flag %d at t = %g", r.flag, r.t);
    }
    expo = FitOrder(tols, err, 3);
    printf("index %s: error ~ tol^%.3f\n", k == 0 ? "3" : "2", expo);
    CHECK(expo > 0.85 && expo < 1.15, "tolerance proportionality: exponent %.3f", expo);
    CHECK(err[2] < 1e-4 * ExactR(1.0), "error %.3e at tol 1e-7", err[2]);
  }

  /* (c) the start at index 2 */
  {
    Run bad = {LGN_CONSTR_INDEX2, 1e-3, 0.0, NULL, 1, 0, 0, 0.1, 0};
    Run fix = bad;
    Result r;
    printf("expected: an inconsistent start at index 2\n");
    r = Integrate(&bad);
    CHECK(r.flag == LGN_INCONSISTENT_IC, "v0 along the rod at index 2: flag %d", r.flag);
    fix.calcic = 1;
    r = Integrate(&fix);
    CHECK(r.flag == LGN_SUCCESS, "after LGNCalcIC: flag %d", r.flag);
    CHECK_CLOSE(r.v0[0], RDOT0, 1e-14, "projected v0_x");
    CHECK_CLOSE(r.v0[1], R0 * OMEGA, 1e-14, "projected v0_y");
  }

  /* (d) negative controls */
  {
    Run nophit = {LGN_CONSTR_INDEX2, 1e-3, 0.0, Curvature, 0, 1, 0, 0.1, 0};
    Run good   = {LGN_CONSTR_INDEX3, 1e-3, 0.0, Curvature, 1, 1, 0, 1e-3, 1};
    Run wrong  = good;
    Result r, rg, rw;
    printf("expected: an inconsistent start at index 2 without Phi_t\n");
    r = Integrate(&nophit);
    CHECK(r.flag == LGN_INCONSISTENT_IC, "co-rotating start without Phi_t: flag %d", r.flag);
    wrong.curv = CurvatureNoTime;
    rg = Integrate(&good);
    rw = Integrate(&wrong);
    printf("lambda error after one step: with the time terms %.3e, without %.3e\n",
           rg.lambda_err, rw.lambda_err);
    CHECK(rg.flag == LGN_SUCCESS && rw.flag == LGN_SUCCESS, "one step: flags %d %d",
          rg.flag, rw.flag);
    CHECK(rw.lambda_err > 100 * rg.lambda_err, "the time terms of the curvature matter");
  }
  return test_summary("test_rheonomic");
}
