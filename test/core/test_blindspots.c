/* -----------------------------------------------------------------------------
 * Lignum test: wrong answers once reported as success by the error control.
 *
 * (b) A planar pendulum in Cartesian coordinates (R^2, unit mass and length,
 *     gravity 9.81, start (1, 0) at rest, index 3, generalized-alpha
 *     rho_inf 0.9, error control rtol = atol = 1e-6) with
 *     LGNSetInitStep(1e6): LGNSolve to t = 0.5 accepted a first step of
 *     h = 61 s (the estimate, the step's increment minus a third-order
 *     Taylor increment, is meaningless that far beyond the period) and
 *     returned q off by 0.94 with success. Now the first step is at most
 *     |tout - t0| and the run agrees with a fixed-step run (h = 1e-4) to
 *     1e-3; the first step used is asserted to be at most 0.5.
 * (a) A fully driven mechanism under GGL: a rotor (R^1, J = 2, no force)
 *     turned by the driver Phi = sin(theta - f(t)), f = 0.5 sin 3t, error
 *     control tol 1e-8, generalized-alpha (rho_inf 0.9), to t = 2. The
 *     projected estimate keeps nothing (the constraint determines every
 *     coordinate; reported on the SO(3) rotor of test_output_multipliers:
 *     steps doubling to about 1 s, Newton on the other root). Asserted:
 *     success and |theta(2) - f(2)| <= 1e-6 with no step limit. This R^1
 *     rotor passed before the range test of lgn_newmark_errtest.c too: a guard,
 *     not a reproduction.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

#define PEND_G 9.81

static int PMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  SM_ELEMENT_D(M, 1, 1) = 1.0;
  return 0;
}

static int PForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 0.0;
  NV_Ith_S(g, 1) = PEND_G;
  return 0;
}

/* Phi = (|q|^2 - 1) / 2, B = q^T */
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

/* ---- (a) the driven rotor ------------------------------------------------ */

#define ROTOR_J 2.0

static double Drive(double t) { return 0.5 * sin(3.0 * t); }
static double DriveRate(double t) { return 1.5 * cos(3.0 * t); }

static int RMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = ROTOR_J;
  return 0;
}

static int RForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 0.0;
  return 0;
}

static int RConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)ud;
  NV_Ith_S(phi, 0) = sin(NV_Ith_S(q, 0) - Drive(t));
  return 0;
}

static int RConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)ud;
  SM_ELEMENT_D(B, 0, 0) = cos(NV_Ith_S(q, 0) - Drive(t));
  return 0;
}

static int RConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  (void)ud;
  NV_Ith_S(phit, 0) = -cos(NV_Ith_S(q, 0) - Drive(t)) * DriveRate(t);
  return 0;
}

static void DrivenRotorGGL(SUNContext ctx)
{
  const double tend = 2.0;
  LGNGroup G = LGNGroup_Rn(1);
  N_Vector q = N_VNew_Serial(1, ctx), v = N_VNew_Serial(1, ctx), y = N_VNew_Serial(3, ctx);
  SUNMatrix A = SUNDenseMatrix(3, 3, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  sunrealtype t = 0.0;
  long int nst = 0;
  double err;
  int flag;
  NV_Ith_S(q, 0) = Drive(0.0);
  NV_Ith_S(v, 0) = DriveRate(0.0);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, RMass);
  if (!flag) flag = LGNSetForceFn(mem, RForce);
  if (!flag) flag = LGNSetConstraints(mem, 1, RConstr, RConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, RConstrTime);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, 1e-8, 1e-8);
  if (!flag) flag = LGNSolve(mem, tend, &t, q, v, LGN_NORMAL);
  LGNGetNumSteps(mem, &nst);
  err = fabs(NV_Ith_S(q, 0) - Drive(t));
  printf("(a) driven rotor, GGL, tol 1e-8: %s at t = %g, %ld steps, |theta - f| = %.3g\n",
         LGNGetReturnFlagName(flag), t, nst, err);
  CHECK(flag == LGN_SUCCESS && t == tend && err < 1e-6,
        "(a) driven rotor under GGL: %s at t = %g, |theta - f| = %g", LGNGetReturnFlagName(flag),
        t, err);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  LGNGroup_Destroy(G);
}

/* ---- (b) the pendulum ---------------------------------------------------- */

/* The pendulum at index 3, generalized-alpha (rho_inf 0.9), solved to tend:
 * fixed steps h > 0, or error control (tol) with the first step h0 (h <= 0).
 * q at tend and the first step used; the flag. */
static int PendulumRun(SUNContext ctx, double h, double tol, double h0, double tend,
                       double qend[2], double *h0_used)
{
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q = N_VNew_Serial(2, ctx), v = N_VNew_Serial(2, ctx), y = N_VNew_Serial(3, ctx);
  SUNMatrix A = SUNDenseMatrix(3, 3, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  sunrealtype t = 0.0, hin = 0.0;
  int flag;
  NV_Ith_S(q, 0) = 1.0; NV_Ith_S(q, 1) = 0.0;
  NV_Ith_S(v, 0) = 0.0; NV_Ith_S(v, 1) = 0.0;
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, PMass);
  if (!flag) flag = LGNSetForceFn(mem, PForce);
  if (!flag) flag = LGNSetConstraints(mem, 1, PConstr, PConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, PStiff);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  if (h > 0.0) {
    if (!flag) flag = LGNSetStepSize(mem, h);
  } else {
    if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSetInitStep(mem, h0);
  }
  if (!flag) flag = LGNSolve(mem, tend, &t, q, v, LGN_NORMAL);
  if (!flag && t != tend) flag = -999;
  if (!flag) flag = LGNGetActualInitStep(mem, &hin);
  qend[0] = NV_Ith_S(q, 0);
  qend[1] = NV_Ith_S(q, 1);
  *h0_used = hin;
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  LGNGroup_Destroy(G);
  return flag;
}

/* (b) a user's first step of 1e6 on the pendulum */
static void HugeFirstStep(SUNContext ctx)
{
  const double tend = 0.5;
  double qref[2], q[2], h0 = 0.0, hdummy, err;
  int flag = PendulumRun(ctx, 1e-4, 1e-12, 0.0, tend, qref, &hdummy);
  CHECK(flag == LGN_SUCCESS, "(b) the fixed-step reference: %s", LGNGetReturnFlagName(flag));
  flag = PendulumRun(ctx, 0.0, 1e-6, 1e6, tend, q, &h0);
  err  = hypot(q[0] - qref[0], q[1] - qref[1]);
  printf("(b) LGNSetInitStep(1e6), tol 1e-6: %s, first step %g, |q - qref| = %.3g\n",
         LGNGetReturnFlagName(flag), h0, err);
  CHECK(flag == LGN_SUCCESS && err < 1e-3,
        "(b) LGNSetInitStep(1e6): %s, |q - qref| = %g (q = %g %g, qref = %g %g)",
        LGNGetReturnFlagName(flag), err, q[0], q[1], qref[0], qref[1]);
  CHECK(h0 <= tend, "(b) the first step used %g exceeds |tout - t0| = %g", h0, tend);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx)) return 1;
  DrivenRotorGGL(ctx);
  HugeFirstStep(ctx);
  SUNContext_Free(&ctx);
  return test_summary("test_blindspots");
}
