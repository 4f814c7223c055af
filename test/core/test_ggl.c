/* -----------------------------------------------------------------------------
 * The stabilised index-2 formulation (LGN_CONSTR_GGL) with the BDF family
 * (with the Newmark family: test_ggl_newmark).
 * The heavy top in R^3 x SO(3) of test_bdf (m = 3 constraints of a
 * spherical joint, mass 15, centre of mass at X = e_y, Omega0 = (0, 150,
 * -4.61538)) against the ARKODE reference (lgn_reference, Fehlberg 8):
 *  (a) fixed steps, orders 1 ... 5: the errors at t = 0.3 of the centre of
 *      mass, of the velocities (u, Omega) and of the multipliers lambda over
 *      four step sizes, fitted order k +- 0.2 each. As in test_bdf the
 *      history is started under error control at tolerance 1e-13 up to
 *      t = 0.02, then LGN_STEP_FIXED;
 *  (b) no drift: along a fixed-step run to t = 1 (order 4, h = 1e-3) both
 *      |Phi(q)| and |B(q) v| stay at the Newton tolerance's level (below
 *      1e-9 and 1e-7), where index 3 lets |B v| and index 2 lets |Phi|
 *      drift (printed for comparison, and checked to be larger);
 *  (c) on R^n the step is the textbook GGL BDF: a planar pendulum in
 *      Cartesian coordinates (R^2, Phi = (x^2 + y^2 - 1)/2) with fixed step
 *      and order k = 1 ... 5 agrees with the constant-coefficient BDF for
 *      x' = v + G^T mu, v' = vdot, M vdot = f - G^T lambda, Phi = 0, G v = 0
 *      written out here (solved by its own Newton iteration with a
 *      difference-quotient Jacobian) to 1e-10 after 50 steps;
 *  (d) error control, tol = 1e-6 ... 1e-9, maxord 4: the error at t = 1
 *      follows the tolerance (fitted exponent in (0.8, 1.2)). maxord 5 is
 *      run and printed, not checked: its controller has the two regimes of
 *      doc/theory.md section 8 (order 5 with steps too long after one
 *      start-up decision), which the GGL runs hit at tol 1e-8 and 1e-9
 *      (exponent 0.61 over these four tolerances; index 3 hits them at
 *      other tolerances, bench/bdf_ggl --half);
 *  (e) bad input: an unknown index, GGL with generalized-alpha's sigma
 *      variant (the Newmark family's GGL: test_ggl_newmark),
 *      GGL with a matrix of nv + m rows (LGN_LS_MISMATCH, not a crash),
 *      GGL with a Krylov solver or (with KLU) a sparse matrix (LGN_ILL_INPUT);
 *  (f) a start off the velocity constraint (v0 + 1e-3 along the joint's
 *      normal) is refused under GGL (LGN_INCONSISTENT_IC, though Phi(q0) =
 *      0) and LGNCalcIC (LGN_IC_PROJECT_QV) repairs it: |B v0| at roundoff
 *      afterwards and the run goes on;
 *  (g) modified Newton under GGL (maxord 4, tol 1e-8): the error within a
 *      factor 2 of full Newton's, with fewer matrix setups than iterations.
 *  (h) rheonomic constraints (LGNSetConstraintTimeFn): a bead on a rod
 *      turning at the rate w in the plane (the model of test_rheonomic,
 *      exact solution r(t) = r0 cosh(w t) + (rdot0/w) sinh(w t)), BDF
 *      maxord 4 under error control, tol 1e-6, 1e-8, 1e-10: at t = 1
 *      |Phi(q, t)| and |B v + Phi_t| are within the tolerance, and the error
 *      falls by more than 1e3 from tol 1e-6 to 1e-10 (measured 1.6e3: 1.0e-4,
 *      1.4e-6, 6.2e-8 in 36, 85, 191 steps; index 3 takes 59, 109, 258 steps
 *      to 1.8e-5, 3.8e-7, 3.6e-9 here, because its error test also weighs
 *      the drift of B v + Phi_t, which GGL does not have);
 * With --quick only (c), (e) and (f) (the valgrind test).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h> /* LGN_HAVE_KLU */
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "heavy_top_run.h"
#include "lgn_reference.h"
#include "test_util.h"

/* (a) fixed steps of order k after an error-controlled start; e: the
 * errors at t_end (HUGE_VAL on failure). */
static void FixedStepErrors(SUNContext ctx, int k, double h, double t_end,
                            const LGNRefHeavyTop *ref, double e[3])
{
  const double t_start = 0.02;
  Run r;
  sunrealtype t;
  int flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 12);
  e[0] = e[1] = e[2] = HUGE_VAL;
  if (!flag) flag = LGNSetBDF(r.mem, k);
  if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(r.mem, 1e-13, 1e-13);
  if (!flag) flag = LGNSetStopTime(r.mem, t_start);
  if (!flag) flag = LGNSolve(r.mem, t_start, &t, r.q, r.v, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_FIXED);
  if (!flag) flag = LGNSetStepSize(r.mem, h);
  if (!flag) flag = LGNSolve(r.mem, t_end, &t, r.q, r.v, LGN_NORMAL);
  if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
  if (!flag) Errors(&r, ref, e);
  else printf("order %d, h %g: flag %d\n", k, h, flag);
  RunFree(&r);
}

/* (b) the largest |Phi| and |B v| over a fixed-step run of order 4. */
static int Drift(SUNContext ctx, int index, double *phi, double *bv)
{
  Run r;
  sunrealtype t;
  double p, b;
  int flag = RunCreate(&r, ctx, index, index == LGN_CONSTR_GGL ? 12 : 9), n;
  *phi = *bv = 0;
  if (!flag) flag = LGNSetBDF(r.mem, 4);
  if (!flag) flag = LGNSStolerances(r.mem, 1e-10, 1e-10);
  if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
  for (n = 1; !flag && n <= 1000; n++) {
    flag = LGNSolve(r.mem, 1e-3 * n, &t, r.q, r.v, LGN_NORMAL);
    if (flag) break;
    Violations(&r, &p, &b);
    *phi = fmax(*phi, p);
    *bv  = fmax(*bv, b);
  }
  RunFree(&r);
  return flag;
}

/* (d) one error-controlled run to t = 1: the error of the centre of mass. */
static double AdaptiveRunNewton(SUNContext ctx, int maxord, double tol,
                                const LGNRefHeavyTop *ref, long int *nst, int newton,
                                long int *nsetups, long int *nni)
{
  Run r;
  sunrealtype t;
  double e[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  int flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 12);
  if (!flag) flag = LGNSetNewtonMode(r.mem, newton);
  if (!flag) flag = LGNSetBDF(r.mem, maxord);
  if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(r.mem, tol, tol);
  if (!flag) flag = LGNSetStopTime(r.mem, 1.0);
  if (!flag) flag = LGNSolve(r.mem, 1.0, &t, r.q, r.v, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
  if (!flag) Errors(&r, ref, e);
  else printf("adaptive run: flag %d\n", flag);
  LGNGetNumSteps(r.mem, nst);
  if (nsetups != NULL) LGNGetNumLinSolvSetups(r.mem, nsetups);
  if (nni != NULL) LGNGetNumNewtonIters(r.mem, nni);
  RunFree(&r);
  return e[0];
}

static double AdaptiveRun(SUNContext ctx, int maxord, double tol, const LGNRefHeavyTop *ref,
                          long int *nst)
{
  return AdaptiveRunNewton(ctx, maxord, tol, ref, nst, LGN_NEWTON_FULL, NULL, NULL);
}

/* ---- (c) the planar pendulum on R^2, written out ------------------------- */

#define PEND_M 2.0
#define PEND_G 9.81

/* g = -f: gravity along -y */
static int PMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = PEND_M;
  SM_ELEMENT_D(M, 1, 1) = PEND_M;
  return 0;
}

static int PForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 0.0;
  NV_Ith_S(g, 1) = PEND_M * PEND_G;
  return 0;
}

static int PConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double x = NV_Ith_S(q, 0), y = NV_Ith_S(q, 1);
  (void)t; (void)ud;
  NV_Ith_S(phi, 0) = 0.5 * (x * x + y * y - 1.0);
  return 0;
}

static int PConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)t; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = NV_Ith_S(q, 0);
  SM_ELEMENT_D(B, 0, 1) = NV_Ith_S(q, 1);
  return 0;
}

/* K_t = D_q(B^T lambda) = lambda I */
static int PStiff(sunrealtype t, N_Vector q, N_Vector v, N_Vector vd, N_Vector l,
                  SUNMatrix K, void *ud)
{
  (void)t; (void)q; (void)v; (void)vd; (void)ud;
  SM_ELEMENT_D(K, 0, 0) = NV_Ith_S(l, 0);
  SM_ELEMENT_D(K, 1, 1) = NV_Ith_S(l, 0);
  return 0;
}

static int PDamp(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  (void)t; (void)q; (void)v; (void)C; (void)ud;
  return 0;
}

/* The GGL BDF residual of one step in the unknowns z = (x, y, vx, vy,
 * lambda, mu): (sum_j a_j x_{n+1-j}) / h = v + G^T mu, (sum_j a_j
 * v_{n+1-j}) / h = vdot with M vdot = f - G^T lambda, Phi = 0, G v = 0. */
static void PendulumResidual(const double *z, const double *rx, const double *rv, double a0,
                             double h, double *F)
{
  const double x = z[0], y = z[1], vx = z[2], vy = z[3], l = z[4], mu = z[5];
  const double ax = -(l * x) / PEND_M, ay = -PEND_G - (l * y) / PEND_M;
  F[0] = (a0 * x + rx[0]) / h - (vx + x * mu);
  F[1] = (a0 * y + rx[1]) / h - (vy + y * mu);
  F[2] = (a0 * vx + rv[0]) / h - ax;
  F[3] = (a0 * vy + rv[1]) / h - ay;
  F[4] = 0.5 * (x * x + y * y - 1.0);
  F[5] = x * vx + y * vy;
}

/* 6 x 6 Gaussian elimination with partial pivoting: A d = b. */
static void Solve6(double A[6][6], double *b)
{
  int i, j, k, p;
  for (k = 0; k < 6; k++) {
    p = k;
    for (i = k + 1; i < 6; i++)
      if (fabs(A[i][k]) > fabs(A[p][k])) p = i;
    for (j = 0; j < 6; j++) {
      double s = A[k][j]; A[k][j] = A[p][j]; A[p][j] = s;
    }
    { double s = b[k]; b[k] = b[p]; b[p] = s; }
    for (i = k + 1; i < 6; i++) {
      const double f = A[i][k] / A[k][k];
      for (j = k; j < 6; j++) A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  for (k = 5; k >= 0; k--) {
    for (j = k + 1; j < 6; j++) b[k] -= A[k][j] * b[j];
    b[k] /= A[k][k];
  }
}

/* k-th order textbook GGL BDF (orders ramping 1, 2, ... as Lignum's fixed
 * steps do) against Lignum: max |difference| of (x, y, vx, vy) after
 * nsteps steps of h. */
static double PendulumTextbook(SUNContext ctx, int k, double h, int nsteps)
{
  static const double a[6][6] = {{0},
                                 {1, -1},
                                 {1.5, -2, 0.5},
                                 {11.0 / 6, -3, 1.5, -1.0 / 3},
                                 {25.0 / 12, -4, 3, -4.0 / 3, 0.25},
                                 {137.0 / 60, -5, 5, -10.0 / 3, 1.25, -0.2}};
  const double th = 0.3;
  double X[64][2], V[64][2], z[6], rx[2], rv[2], F[6], Fp[6], J[6][6], diff = 0;
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q = N_VNew_Serial(2, ctx), v = N_VNew_Serial(2, ctx), y = N_VNew_Serial(4, ctx);
  SUNMatrix A = SUNDenseMatrix(4, 4, ctx); /* nv + 2m = 4 */
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(mem, SUNFALSE);
  LGNSetProjectOutputs(mem, LGN_PROJECT_NONE);
  sunrealtype t;
  int n, j, kk, it, i, c, flag;

  /* consistent start: on the circle, velocity tangent to it */
  X[0][0] = sin(th);  X[0][1] = -cos(th);
  V[0][0] = 1.5 * cos(th); V[0][1] = 1.5 * sin(th);
  for (n = 0; n < nsteps; n++) {
    kk = n + 1 < k ? n + 1 : k;
    for (i = 0; i < 2; i++) {
      rx[i] = rv[i] = 0;
      for (j = 1; j <= kk; j++) {
        rx[i] += a[kk][j] * X[n + 1 - j][i];
        rv[i] += a[kk][j] * V[n + 1 - j][i];
      }
    }
    z[0] = X[n][0]; z[1] = X[n][1]; z[2] = V[n][0]; z[3] = V[n][1]; z[4] = 0; z[5] = 0;
    for (it = 0; it < 30; it++) { /* Newton, difference-quotient Jacobian */
      double nrm = 0;
      PendulumResidual(z, rx, rv, a[kk][0], h, F);
      for (c = 0; c < 6; c++) {
        const double dz = 1e-7 * fmax(1.0, fabs(z[c])), zc = z[c];
        z[c] = zc + dz;
        PendulumResidual(z, rx, rv, a[kk][0], h, Fp);
        z[c] = zc;
        for (i = 0; i < 6; i++) J[i][c] = (Fp[i] - F[i]) / dz;
      }
      for (i = 0; i < 6; i++) F[i] = -F[i];
      Solve6(J, F);
      for (i = 0; i < 6; i++) {
        z[i] += F[i];
        nrm = fmax(nrm, fabs(F[i]) / fmax(1.0, fabs(z[i])));
      }
      if (nrm < 1e-15) break;
    }
    X[n + 1][0] = z[0]; X[n + 1][1] = z[1];
    V[n + 1][0] = z[2]; V[n + 1][1] = z[3];
  }
  NV_Ith_S(q, 0) = X[0][0]; NV_Ith_S(q, 1) = X[0][1];
  NV_Ith_S(v, 0) = V[0][0]; NV_Ith_S(v, 1) = V[0][1];
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, PMass);
  if (!flag) flag = LGNSetForceFn(mem, PForce);
  if (!flag) flag = LGNSetStiffnessFn(mem, PStiff);
  if (!flag) flag = LGNSetDampingFn(mem, PDamp);
  if (!flag) flag = LGNSetConstraints(mem, 1, PConstr, PConstrJac);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSetBDF(mem, k);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNSStolerances(mem, 1e-13, 1e-13);
  for (n = 0; !flag && n < nsteps; n++) flag = LGNSolve(mem, 1e9, &t, q, v, LGN_ONE_STEP);
  if (flag) {
    printf("pendulum, order %d: flag %d\n", k, flag);
    diff = HUGE_VAL;
  }
  for (i = 0; !flag && i < 2; i++)
    diff = fmax(diff, fmax(fabs(NV_Ith_S(q, i) - X[nsteps][i]),
                           fabs(NV_Ith_S(v, i) - V[nsteps][i])));
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  LGNGroup_Destroy(G);
  return diff;
}

/* ---- (h) the bead on a turning rod (rheonomic) --------------------------- */

#define BEAD_M  2.0
#define BEAD_W  2.0
#define BEAD_R0 0.5
#define BEAD_RD 0.3

static int BMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = BEAD_M;
  SM_ELEMENT_D(M, 1, 1) = BEAD_M;
  return 0;
}

static int BForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)g; (void)ud; /* g = 0 */
  return 0;
}

static int BConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)ud;
  NV_Ith_S(phi, 0) = -NV_Ith_S(q, 0) * sin(BEAD_W * t) + NV_Ith_S(q, 1) * cos(BEAD_W * t);
  return 0;
}

static int BConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)q; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = -sin(BEAD_W * t);
  SM_ELEMENT_D(B, 0, 1) = cos(BEAD_W * t);
  return 0;
}

static int BConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  (void)ud;
  NV_Ith_S(phit, 0) =
      -BEAD_W * (NV_Ith_S(q, 0) * cos(BEAD_W * t) + NV_Ith_S(q, 1) * sin(BEAD_W * t));
  return 0;
}

/* The run to t = 1 at tolerance tol: the position error, |Phi| and
 * |B v + Phi_t| at t = 1 (flag != 0: failed). */
static int BeadRun(SUNContext ctx, double tol, double *err, double *phi, double *bv,
                   long int *nst)
{
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q = N_VNew_Serial(2, ctx), v = N_VNew_Serial(2, ctx), y = N_VNew_Serial(4, ctx);
  N_Vector p = N_VNew_Serial(1, ctx), pt = N_VNew_Serial(1, ctx);
  SUNMatrix A = SUNDenseMatrix(4, 4, ctx), B = SUNDenseMatrix(1, 2, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(mem, SUNFALSE);
  LGNSetProjectOutputs(mem, LGN_PROJECT_NONE);
  sunrealtype t;
  double r;
  int flag;
  NV_Ith_S(q, 0) = BEAD_R0;
  NV_Ith_S(q, 1) = 0.0;
  NV_Ith_S(v, 0) = BEAD_RD;
  NV_Ith_S(v, 1) = BEAD_R0 * BEAD_W; /* co-rotating: consistent */
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, BMass);
  if (!flag) flag = LGNSetForceFn(mem, BForce);
  if (!flag) flag = LGNSetConstraints(mem, 1, BConstr, BConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, BConstrTime);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSetBDF(mem, 4);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  if (!flag) flag = LGNSetStopTime(mem, 1.0);
  if (!flag) flag = LGNSolve(mem, 1.0, &t, q, v, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  LGNGetNumSteps(mem, nst);
  if (!flag) {
    r = BEAD_R0 * cosh(BEAD_W * t) + BEAD_RD / BEAD_W * sinh(BEAD_W * t);
    *err = hypot(NV_Ith_S(q, 0) - r * cos(BEAD_W * t), NV_Ith_S(q, 1) - r * sin(BEAD_W * t));
    BConstr(t, q, p, NULL);
    BConstrJac(t, q, B, NULL);
    BConstrTime(t, q, pt, NULL);
    *phi = fabs(NV_Ith_S(p, 0));
    *bv = fabs(SM_ELEMENT_D(B, 0, 0) * NV_Ith_S(v, 0) + SM_ELEMENT_D(B, 0, 1) * NV_Ith_S(v, 1) +
               NV_Ith_S(pt, 0));
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  SUNMatDestroy(B);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  N_VDestroy(p);
  N_VDestroy(pt);
  LGNGroup_Destroy(G);
  return flag;
}

int main(int argc, char **argv)
{
  /* --quick (the valgrind test): (c), (e) and (f) only */
  const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
  SUNContext ctx;
  LGNRefHeavyTop ref03, ref1;
  const double t03 = 0.3, t1 = 1.0;
  static const char *what[3] = {"positions", "velocities", "multipliers"};
  int k, i, c;

  SUNContext_Create(NULL, &ctx);
  CHECK(lgnref_heavy_top(&t03, 1, &ref03, LGNREF_FEHLBERG_8) == 0, "reference");
  CHECK(lgnref_heavy_top(&t1, 1, &ref1, LGNREF_FEHLBERG_8) == 0, "reference");

  /* (a) orders of the fixed-step formulas */
  if (!quick)
    printf("(a) GGL, fixed steps: errors at t = 0.3 (positions, velocities, multipliers)\n");
  for (k = 1; !quick && k <= 5; k++) {
    const double hs[4] = {2e-3, 1e-3, 5e-4, 2.5e-4};
    double err[3][4], e[3], p;
    for (i = 0; i < 4; i++) {
      FixedStepErrors(ctx, k, hs[i], t03, &ref03, e);
      for (c = 0; c < 3; c++) err[c][i] = e[c];
    }
    for (c = 0; c < 3; c++) {
      p = Fit(hs, err[c], 4);
      printf("  order %d, %-11s: %.3e %.3e %.3e %.3e, fitted order %.3f\n", k, what[c],
             err[c][0], err[c][1], err[c][2], err[c][3], p);
      CHECK(fabs(p - k) <= 0.2, "GGL fixed-step order %d, %s: fitted %.3f", k, what[c], p);
    }
  }

  /* (b) no drift of Phi or B v */
  if (!quick) {
    double phi[3], bv[3];
    const int idx[3] = {LGN_CONSTR_GGL, LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
    static const char *name[3] = {"GGL", "index 3", "index 2"};
    printf("(b) BDF4, h = 1e-3 to t = 1: max |Phi| and max |B v| along the solution\n");
    for (i = 0; i < 3; i++) {
      const int flag = Drift(ctx, idx[i], &phi[i], &bv[i]);
      printf("  %-8s: |Phi| %.3e, |B v| %.3e (flag %d)\n", name[i], phi[i], bv[i], flag);
      CHECK(flag == 0, "(b) %s: flag %d", name[i], flag);
    }
    CHECK(phi[0] <= 1e-9 && bv[0] <= 1e-7, "(b) GGL: |Phi| %.3e, |B v| %.3e", phi[0], bv[0]);
    CHECK(bv[1] > 100 * bv[0], "(b) index 3 |B v| %.3e against GGL's %.3e", bv[1], bv[0]);
    CHECK(phi[2] > 100 * phi[0], "(b) index 2 |Phi| %.3e against GGL's %.3e", phi[2], phi[0]);
  }

  /* (c) the textbook GGL BDF on R^2 */
  printf("(c) pendulum on R^2: Lignum's GGL BDF against the textbook one, 50 steps\n");
  for (k = 1; k <= 5; k++) {
    const double d = PendulumTextbook(ctx, k, 0.01, 50);
    printf("  order %d: max difference %.3e\n", k, d);
    CHECK(d <= 1e-10, "(c) textbook GGL BDF order %d: difference %.3e", k, d);
  }

  /* (d) error control */
  if (!quick) {
    const double tols[4] = {1e-6, 1e-7, 1e-8, 1e-9};
    int maxord;
    for (maxord = 4; maxord <= 5; maxord++) {
      double err[4], p;
      long int nst[4];
      printf("(d) GGL, error control, maxord %d\n", maxord);
      for (i = 0; i < 4; i++) {
        err[i] = AdaptiveRun(ctx, maxord, tols[i], &ref1, &nst[i]);
        printf("  tol %.0e: error %.3e, %5ld steps\n", tols[i], err[i], nst[i]);
      }
      p = Fit(tols, err, 4);
      printf("  error ~ tol^%.3f%s\n", p, maxord == 5 ? " (not checked: see the header)" : "");
      CHECK(err[0] < HUGE_VAL && err[1] < HUGE_VAL && err[2] < HUGE_VAL && err[3] < HUGE_VAL,
            "(d) maxord %d: the runs succeed", maxord);
      if (maxord == 4)
        CHECK(p > 0.8 && p < 1.2, "(d) maxord 4: tolerance proportionality: exponent %.3f", p);
    }
  }

  /* (e) bad input */
  {
    Run r;
    sunrealtype t;
    int flag;
    printf("(e) bad input\n");
    flag = RunCreate(&r, ctx, LGN_CONSTR_INDEX3, 12);
    CHECK(flag == 0, "(e) create: %d", flag);
    CHECK(LGNSetConstraintIndex(r.mem, 135) == LGN_ILL_INPUT, "(e) index 135 refused");
    CHECK(LGNSetConstraintIndex(NULL, LGN_CONSTR_GGL) == LGN_MEM_NULL, "(e) NULL memory");
    /* GGL with generalized-alpha's sigma variant: refused at the solve
     * (the simplified and exact variants: test_ggl_newmark) */
    flag = LGNSetConstraintIndex(r.mem, LGN_CONSTR_GGL);
    if (!flag) flag = LGNSetGenAlpha(r.mem, 0.9);
    if (!flag) flag = LGNSetKinematics(r.mem, LGN_KINEMATICS_SIGMA);
    if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_ILL_INPUT, "(e) GGL with generalized-alpha, sigma variant: %s",
          LGNGetReturnFlagName(flag));
    /* ... and then with BDF the same memory runs (the sigma variant, a
     * Newmark setting, back to its default: under BDF it is refused) */
    flag = LGNSetKinematics(r.mem, LGN_KINEMATICS_SIMPLIFIED);
    if (!flag) flag = LGNSetBDF(r.mem, 3);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "(e) GGL with BDF after the refusal: %s",
          LGNGetReturnFlagName(flag));
    RunFree(&r);
    /* a matrix of nv + m rows */
    flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 9);
    if (!flag) flag = LGNSetBDF(r.mem, 3);
    if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_LS_MISMATCH, "(e) GGL with a 9 x 9 matrix: %s",
          LGNGetReturnFlagName(flag));
    /* back to index 3, the 9 x 9 matrix fits again */
    flag = LGNSetConstraintIndex(r.mem, LGN_CONSTR_INDEX3);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "(e) index 3 with the 9 x 9 matrix: %s",
          LGNGetReturnFlagName(flag));
    RunFree(&r);
    /* a Krylov solver */
    flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 12);
    {
      SUNLinearSolver kry = SUNLinSol_SPGMR(r.y, SUN_PREC_NONE, 20, ctx);
      if (!flag) flag = LGNSetLinearSolver(r.mem, kry, NULL);
      if (!flag) flag = LGNSetBDF(r.mem, 3);
      if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
      if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
      CHECK(flag == LGN_ILL_INPUT, "(e) GGL with a Krylov solver: %s",
            LGNGetReturnFlagName(flag));
      LGNFree(&r.mem); /* before the solver it holds */
      SUNLinSolFree(kry);
    }
    RunFree(&r);
#if defined(LGN_HAVE_KLU)
    /* a sparse matrix with KLU, of the right size */
    flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 12);
    {
      SUNMatrix S = SUNSparseMatrix(12, 12, 1, CSC_MAT, ctx);
      SUNLinearSolver klu = SUNLinSol_KLU(r.y, S, ctx);
      if (!flag) flag = LGNSetLinearSolver(r.mem, klu, S);
      if (!flag) flag = LGNSetBDF(r.mem, 3);
      if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
      if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
      CHECK(flag == LGN_ILL_INPUT, "(e) GGL with a sparse matrix (KLU): %s",
            LGNGetReturnFlagName(flag));
      LGNFree(&r.mem);
      SUNLinSolFree(klu);
      SUNMatDestroy(S);
    }
    RunFree(&r);
#endif
  }

  /* (f) a start off B v = 0, refused and repaired */
  {
    Run r;
    sunrealtype t;
    double phi, bv;
    int flag = RunCreate(&r, ctx, LGN_CONSTR_GGL, 12);
    printf("(f) inconsistent velocity under GGL\n");
    /* the joint's x - R X = 0 with R = I: B v = u - Omega x X; u_z += 1e-3 */
    NV_Ith_S(r.v, 2) += 1e-3;
    if (!flag) flag = LGNReInit(r.mem, 0.0, r.q, r.v);
    if (!flag) flag = LGNSetBDF(r.mem, 3);
    if (!flag) flag = LGNSetStepSize(r.mem, 1e-3);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_INCONSISTENT_IC, "(f) |B v0| = 1e-3 under GGL: %s",
          LGNGetReturnFlagName(flag));
    flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_QV);
    CHECK(flag == LGN_SUCCESS, "(f) LGNCalcIC: %s", LGNGetReturnFlagName(flag));
    if (!flag) flag = LGNSolve(r.mem, 0.0, &t, r.q, r.v, LGN_NORMAL);
    Violations(&r, &phi, &bv);
    printf("  after LGNCalcIC: |Phi| %.3e, |B v| %.3e\n", phi, bv);
    CHECK(phi <= 1e-14 && bv <= 1e-12, "(f) projected start: |Phi| %.3e, |B v| %.3e", phi, bv);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "(f) the run after LGNCalcIC: %s", LGNGetReturnFlagName(flag));
    RunFree(&r);
  }

  /* (g) modified Newton */
  if (!quick) {
    long int nst[2], nset[2], nni[2];
    const double ef = AdaptiveRunNewton(ctx, 4, 1e-8, &ref1, &nst[0], LGN_NEWTON_FULL,
                                        &nset[0], &nni[0]);
    const double em = AdaptiveRunNewton(ctx, 4, 1e-8, &ref1, &nst[1], LGN_NEWTON_MODIFIED,
                                        &nset[1], &nni[1]);
    printf("(g) GGL, maxord 4, tol 1e-8: full Newton %.3e (%ld steps, %ld iterations, %ld "
           "setups), modified %.3e (%ld steps, %ld iterations, %ld setups)\n",
           ef, nst[0], nni[0], nset[0], em, nst[1], nni[1], nset[1]);
    CHECK(em <= 2 * ef && em >= 0.5 * ef, "(g) modified Newton %.3e against full %.3e", em, ef);
    CHECK(nset[1] < nni[1] / 2, "(g) modified Newton: %ld setups in %ld iterations", nset[1],
          nni[1]);
  }

  /* (h) rheonomic */
  if (!quick) {
    const double tols[3] = {1e-6, 1e-8, 1e-10};
    double err[3] = {0, 0, 0}, phi = HUGE_VAL, bv = HUGE_VAL;
    long int nst = 0;
    printf("(h) bead on a turning rod (Phi_t), GGL BDF maxord 4, error control\n");
    for (i = 0; i < 3; i++) {
      const int flag = BeadRun(ctx, tols[i], &err[i], &phi, &bv, &nst);
      printf("  tol %.0e: error %.3e in %ld steps, |Phi| %.3e, |B v + Phi_t| %.3e (flag %d)\n",
             tols[i], err[i], nst, phi, bv, flag);
      CHECK(flag == 0, "(h) tol %.0e: flag %d", tols[i], flag);
      CHECK(phi <= tols[i] && bv <= tols[i], "(h) tol %.0e: |Phi| %.3e, |B v + Phi_t| %.3e",
            tols[i], phi, bv);
    }
    CHECK(err[2] < 1e-3 * err[0], "(h) error %.3e at tol 1e-10 against %.3e at 1e-6", err[2],
          err[0]);
  }

  SUNContext_Free(&ctx);
  return test_summary("test_ggl");
}
