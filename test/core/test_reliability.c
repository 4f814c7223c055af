/* -----------------------------------------------------------------------------
 * Lignum test: reliability after failures and of settings (issue 31).
 *
 * A heavy top (R^3 x SO(3), pinned at Xp: 6 velocities, 3 constraints).
 * (a) After a failed LGNSolve every getter returns the last valid values or
 *     a flag, never made-up numbers with success: the multipliers after
 *     LGN_LS_MISMATCH (GGL with the index-3 solver still attached) are the
 *     last ones computed, bit for bit; before any are computed the getter
 *     says so (it returned zeros with success before).
 * (b) LGNRootInit(mem, INT_MAX, g) is refused naming nrtfn (3 nrtfn
 *     overflowed an int), and the root functions set before stay in force.
 * (c) Fixed steps honour a stop time: LGN_NORMAL and LGN_ONE_STEP land on
 *     it exactly (the step before it shortened) with LGN_TSTOP_RETURN, bit
 *     for bit the run to tout = tstop; BDF lands on it too; a stop time
 *     left behind t by LGNReInit is refused by LGNSolve, state unchanged.
 * (d) After h collapsed (a force callback failing recoverably past t* with
 *     error control, ending in LGN_STEP_TOO_SMALL), the next LGNSolve
 *     recovers once the callback works again, to the reference; and
 *     LGNSetInitStep after steps sets the size of the next step. At index
 *     2: at index 3 the steps of 1e-17 before the collapse leave v wrong
 *     by O(eps |q| / h), whatever comes after.
 * (e) Refused with a message, state unchanged: LGNSetGroup with a group of
 *     another size after LGNInit; LGNCalcIC after steps; principal moments
 *     of inertia violating the triangle inequality (equality accepted).
 * (f) Tolerances so small that the error weights overflow (4.9e-324) are
 *     refused by LGNSStolerances / LGNSVtolerances naming them; SPGMR made
 *     for a left preconditioner without one fails with a message saying so.
 * (g) An adaptive first step of 1e6 is cut and retried (at index 3 the
 *     Newton iteration fails, at index 2 the iteration matrix is singular:
 *     recoverable under error control in the Newmark family now, as under
 *     BDF) and gives the right answer; a fixed step of 1e6 fails cleanly.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

#define GRAV 9.81
static const double MASS = 2.0, JB[3] = {0.3, 0.5, 0.7}, XP[3] = {0.0, 0.0, 0.4};

/* (d): the force callback fails recoverably (+1) at t > t_fail while set */
static int force_broken = 0;
static const double t_fail = 0.02;

/* the last message of the error handler, and its code */
static char last_msg[1024];
static int last_code = 0;

static void Handler(int code, const char *module, const char *function, const char *msg,
                    void *data)
{
  (void)module; (void)function; (void)data;
  last_code = code;
  if (getenv("LGN_TEST_VERBOSE") != NULL) printf("  [%d] %s: %s\n", code, function, msg);
  snprintf(last_msg, sizeof last_msg, "%s", msg);
}

static void Rotation(N_Vector q, double R[9])
{
  LGNQuaternionToRotation(N_VGetArrayPointer(q) + 3, R);
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) {
    SM_ELEMENT_D(M, i, i)         = MASS;
    SM_ELEMENT_D(M, i + 3, i + 3) = JB[i];
  }
  return 0;
}

/* g = (m g e3, W x J W) */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *W = N_VGetArrayPointer(v) + 3;
  double *gg = N_VGetArrayPointer(g);
  (void)q; (void)ud;
  if (force_broken && t > t_fail) return 1;
  gg[0] = gg[1] = 0.0;
  gg[2] = MASS * GRAV;
  gg[3] = W[1] * JB[2] * W[2] - W[2] * JB[1] * W[1];
  gg[4] = W[2] * JB[0] * W[0] - W[0] * JB[2] * W[2];
  gg[5] = W[0] * JB[1] * W[1] - W[1] * JB[0] * W[0];
  return 0;
}

/* Phi = x + R Xp */
static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double *x = N_VGetArrayPointer(q);
  double R[9];
  int i;
  (void)t; (void)ud;
  Rotation(q, R);
  for (i = 0; i < 3; i++)
    N_VGetArrayPointer(phi)[i] = x[i] + R[3 * i] * XP[0] + R[3 * i + 1] * XP[1] + R[3 * i + 2] * XP[2];
  return 0;
}

/* B = [I, -R Xp~] */
static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const double S[9] = {0.0, -XP[2], XP[1], XP[2], 0.0, -XP[0], -XP[1], XP[0], 0.0};
  double R[9];
  int i, j, k;
  (void)t; (void)ud;
  Rotation(q, R);
  for (i = 0; i < 3; i++) {
    SM_ELEMENT_D(B, i, i) = 1.0;
    for (j = 0; j < 3; j++) {
      double rs = 0.0;
      for (k = 0; k < 3; k++) rs += R[3 * i + k] * S[3 * k + j];
      SM_ELEMENT_D(B, i, 3 + j) = -rs;
    }
  }
  return 0;
}

/* A consistent start: rotation exp(psi0), body rates W0, the pivot at rest. */
static void InitialState(N_Vector q, N_Vector v)
{
  const double psi0[3] = {0.3, -0.2, 0.5}, W0[3] = {1.0, -2.0, 8.0};
  double *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v), R[9], c[3];
  int i;
  LGNQuaternionFromRotationVector(psi0, x + 3);
  Rotation(q, R);
  c[0] = W0[1] * XP[2] - W0[2] * XP[1];
  c[1] = W0[2] * XP[0] - W0[0] * XP[2];
  c[2] = W0[0] * XP[1] - W0[1] * XP[0];
  for (i = 0; i < 3; i++) {
    x[i]     = -(R[3 * i] * XP[0] + R[3 * i + 1] * XP[1] + R[3 * i + 2] * XP[2]);
    u[i]     = -(R[3 * i] * c[0] + R[3 * i + 1] * c[1] + R[3 * i + 2] * c[2]);
    u[3 + i] = W0[i];
  }
}

typedef struct {
  SUNContext ctx;
  LGNGroup G;
  void *mem;
  SUNMatrix A;
  SUNLinearSolver LS;
  N_Vector q, v, lam;
} Top;

/* A heavy top at index 3, generalized-alpha 0.8, dense LU of size n (9 fits),
 * fixed h = 1e-3 unless adaptive (tolerances tol). */
static int TopCreate(Top *T, SUNContext ctx, sunindextype n, int adaptive, double tol)
{
  int flag;
  memset(T, 0, sizeof *T);
  T->ctx = ctx;
  T->G   = LGNGroup_R3xSO3();
  T->q   = N_VNew_Serial(7, ctx);
  T->v   = N_VNew_Serial(6, ctx);
  T->lam = N_VNew_Serial(3, ctx);
  T->A   = SUNDenseMatrix(n, n, ctx);
  {
    N_Vector y = N_VNew_Serial(n, ctx);
    T->LS = SUNLinSol_Dense(y, T->A, ctx);
    N_VDestroy(y);
  }
  T->mem = LGNCreate(ctx);
  InitialState(T->q, T->v);
  flag = LGNSetGroup(T->mem, T->G);
  if (!flag) flag = LGNSetErrHandlerFn(T->mem, Handler, NULL);
  if (!flag) flag = LGNSetMassFn(T->mem, Mass);
  if (!flag) flag = LGNSetForceFn(T->mem, Force);
  if (!flag) flag = LGNSetConstraints(T->mem, 3, Phi, Jac);
  if (!flag) flag = LGNInit(T->mem, 0.0, T->q, T->v);
  if (!flag) flag = LGNSetLinearSolver(T->mem, T->LS, T->A);
  if (!flag) flag = LGNSetGenAlpha(T->mem, 0.8);
  if (!flag) flag = LGNSetStepSize(T->mem, 1e-3);
  if (!flag) flag = LGNSStolerances(T->mem, tol, tol);
  if (!flag && adaptive) flag = LGNSetStepControl(T->mem, LGN_STEP_ADAPTIVE);
  return flag;
}

static void TopFree(Top *T)
{
  LGNFree(&T->mem);
  SUNLinSolFree(T->LS);
  SUNMatDestroy(T->A);
  N_VDestroy(T->q);
  N_VDestroy(T->v);
  N_VDestroy(T->lam);
  LGNGroup_Destroy(T->G);
}

static int SameBits(N_Vector x, N_Vector y)
{
  return N_VGetLength(x) == N_VGetLength(y) &&
         memcmp(N_VGetArrayPointer(x), N_VGetArrayPointer(y),
                (size_t)N_VGetLength(x) * sizeof(sunrealtype)) == 0;
}

static double MaxDiff(N_Vector x, N_Vector y)
{
  double d = 0.0;
  sunindextype i;
  for (i = 0; i < N_VGetLength(x); i++)
    d = fmax(d, fabs(N_VGetArrayPointer(x)[i] - N_VGetArrayPointer(y)[i]));
  return d;
}

/* The reference at t: the top with fixed steps of 1e-5 (second order: its
 * error is about 1e-8, far below the tolerances compared against). */
static void Reference(SUNContext ctx, double t, N_Vector q, N_Vector v)
{
  Top R;
  double tret = 0.0;
  int flag = TopCreate(&R, ctx, 9, 0, 1e-12);
  if (!flag) flag = LGNSetStepSize(R.mem, 1e-5);
  if (!flag) flag = LGNSolve(R.mem, t, &tret, R.q, R.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && tret == t, "reference run to %g: %s", t,
        LGNGetReturnFlagName(flag));
  N_VScale(1.0, R.q, q);
  N_VScale(1.0, R.v, v);
  TopFree(&R);
}

/* (a) The multipliers after a failed LGNSolve. */
static void GettersAfterFailure(SUNContext ctx)
{
  Top T;
  N_Vector lam0 = N_VNew_Serial(3, ctx), vd0 = N_VNew_Serial(6, ctx), vd = N_VNew_Serial(6, ctx);
  double t = 0.0;
  int flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  if (!flag) flag = LGNGetMultipliers(T.mem, lam0);
  if (!flag) flag = LGNGetAcceleration(T.mem, vd0);
  CHECK(flag == LGN_SUCCESS && N_VMaxNorm(lam0) > 1.0, "(a) a first solve: %s, |lambda| = %g",
        LGNGetReturnFlagName(flag), N_VMaxNorm(lam0));
  /* GGL needs a 12 x 12 solver: the next solve fails */
  flag = LGNSetConstraintIndex(T.mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSolve(T.mem, 0.1, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_LS_MISMATCH, "(a) GGL with a 9 x 9 solver: %s (LGN_LS_MISMATCH expected)",
        LGNGetReturnFlagName(flag));
  N_VConst(-7.0, T.lam);
  flag = LGNGetMultipliers(T.mem, T.lam);
  CHECK(flag != LGN_SUCCESS || SameBits(T.lam, lam0),
        "(a) LGNGetMultipliers after the failure: %s with lambda = (%g, %g, %g), the "
        "last valid ones are (%g, %g, %g)", LGNGetReturnFlagName(flag),
        NV_Ith_S(T.lam, 0), NV_Ith_S(T.lam, 1), NV_Ith_S(T.lam, 2), NV_Ith_S(lam0, 0),
        NV_Ith_S(lam0, 1), NV_Ith_S(lam0, 2));
  flag = LGNGetAcceleration(T.mem, vd);
  CHECK(flag != LGN_SUCCESS || SameBits(vd, vd0), "(a) LGNGetAcceleration after the failure");
  /* back to index 3: it goes on from the kept state */
  flag = LGNSetConstraintIndex(T.mem, LGN_CONSTR_INDEX3);
  if (!flag) flag = LGNSolve(T.mem, 0.1, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == 0.1, "(a) index 3 again: %s", LGNGetReturnFlagName(flag));
  TopFree(&T);

  /* a first solve that fails before any multipliers are computed (a 6 x 6
   * solver for 9 unknowns): no zeros reported as multipliers */
  flag = TopCreate(&T, ctx, 6, 0, 1e-10);
  if (!flag) flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_LS_MISMATCH, "(a) a 6 x 6 solver for 9 unknowns: %s",
        LGNGetReturnFlagName(flag));
  N_VConst(-7.0, T.lam);
  flag = LGNGetMultipliers(T.mem, T.lam);
  CHECK(flag != LGN_SUCCESS, "(a) LGNGetMultipliers before any were computed: %s with "
        "lambda = (%g, %g, %g)", LGNGetReturnFlagName(flag), NV_Ith_S(T.lam, 0),
        NV_Ith_S(T.lam, 1), NV_Ith_S(T.lam, 2));
  TopFree(&T);
  N_VDestroy(lam0);
  N_VDestroy(vd0);
  N_VDestroy(vd);
}

/* (b) a root at t = 0.02 */
static int Root(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *g, void *ud)
{
  (void)q; (void)v; (void)ud;
  g[0] = t - 0.02;
  return 0;
}

static void RootInitOverflow(SUNContext ctx)
{
  Top T;
  double t = 0.0;
  int flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNRootInit(T.mem, 1, Root);
  CHECK(flag == LGN_SUCCESS, "(b) LGNRootInit(1): %s", LGNGetReturnFlagName(flag));
  last_msg[0] = '\0';
  flag = LGNRootInit(T.mem, INT_MAX, Root);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "nrtfn") != NULL,
        "(b) LGNRootInit(INT_MAX): %s, \"%s\" (LGN_ILL_INPUT naming nrtfn expected)",
        LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNRootInit(T.mem, INT_MAX / 3 + 1, Root);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "nrtfn") != NULL,
        "(b) LGNRootInit(INT_MAX / 3 + 1): %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  /* the root function set before is still in force */
  flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_ROOT_RETURN && fabs(t - 0.02) < 1e-10,
        "(b) the earlier root function after the refused calls: %s at t = %.17g",
        LGNGetReturnFlagName(flag), t);
  TopFree(&T);
}

/* (c) Stop times with fixed steps. */
static void FixedStepStopTime(SUNContext ctx)
{
  const double tstop = 0.0105;
  Top T, R;
  N_Vector qref = N_VNew_Serial(7, ctx), vref = N_VNew_Serial(6, ctx);
  double t = 0.0, tr = 0.0, hlast = 0.0;
  int flag, k;

  /* LGN_NORMAL: land on tstop exactly, as the run to tout = tstop does */
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetStopTime(T.mem, tstop);
  if (!flag) flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_TSTOP_RETURN && t == tstop,
        "(c) fixed steps, tstop = %g, tout = 0.05: %s at t = %.17g (LGN_TSTOP_RETURN at "
        "tstop expected)", tstop, LGNGetReturnFlagName(flag), t);
  flag = TopCreate(&R, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSolve(R.mem, tstop, &tr, R.q, R.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && SameBits(T.q, R.q) && SameBits(T.v, R.v),
        "(c) the state at tstop is the run to tout = tstop (|dq| = %g)", MaxDiff(T.q, R.q));
  /* the stop time is cleared: on to tout */
  flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == 0.05, "(c) on from tstop: %s at %.17g",
        LGNGetReturnFlagName(flag), t);
  TopFree(&T);
  TopFree(&R);

  /* LGN_ONE_STEP: steps of h, the last one shortened to tstop */
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetStopTime(T.mem, 0.0025);
  for (k = 0; k < 3 && flag == LGN_SUCCESS; k++)
    flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_ONE_STEP);
  LGNGetLastStep(T.mem, &hlast);
  CHECK(k == 3 && flag == LGN_TSTOP_RETURN && t == 0.0025 && fabs(hlast - 5e-4) < 1e-15,
        "(c) LGN_ONE_STEP to tstop = 0.0025: step %d %s at t = %.17g, last h = %g", k,
        LGNGetReturnFlagName(flag), t, hlast);
  TopFree(&T);

  /* BDF with fixed steps lands on tstop too (the step before it shortened),
   * close to the reference there */
  Reference(ctx, tstop, qref, vref);
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetBDF(T.mem, 2);
  if (!flag) flag = LGNSetStopTime(T.mem, tstop);
  if (!flag) flag = LGNSolve(T.mem, 0.05, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_TSTOP_RETURN && t == tstop && MaxDiff(T.q, qref) < 1e-4 &&
            MaxDiff(T.v, vref) < 1e-3,
        "(c) BDF2, fixed steps, tstop = %g: %s at t = %.17g, |q - qref| = %g, |v - vref| = %g",
        tstop, LGNGetReturnFlagName(flag), t, MaxDiff(T.q, qref), MaxDiff(T.v, vref));
  TopFree(&T);

  /* a stop time left behind t by LGNReInit: refused by LGNSolve, state kept */
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetStopTime(T.mem, 0.03);
  if (!flag) flag = LGNReInit(T.mem, 0.5, T.q, T.v);
  if (!flag) flag = LGNGetConsistentIC(T.mem, qref, vref); /* the state at t */
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(T.mem, 0.6, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "stop time") != NULL && t == 0.5 &&
            SameBits(T.q, qref) && SameBits(T.v, vref),
        "(c) tstop = 0.03 behind t = 0.5 after LGNReInit: %s at t = %g, \"%s\"",
        LGNGetReturnFlagName(flag), t, last_msg);
  flag = LGNClearStopTime(T.mem);
  if (!flag) flag = LGNSolve(T.mem, 0.51, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == 0.51, "(c) on after LGNClearStopTime: %s",
        LGNGetReturnFlagName(flag));
  TopFree(&T);
  N_VDestroy(qref);
  N_VDestroy(vref);
}

/* (d) Recovery after a collapsed step under error control. */
static void RecoveryAfterCollapse(SUNContext ctx)
{
  const double tol = 1e-6, tend = 0.05;
  Top T;
  N_Vector qref = N_VNew_Serial(7, ctx), vref = N_VNew_Serial(6, ctx);
  double t = 0.0, h = 0.0;
  int flag, pass;

  Reference(ctx, tend, qref, vref);
  for (pass = 0; pass < 2; pass++) {
    flag = TopCreate(&T, ctx, 9, 1, tol);
    if (!flag) flag = LGNSetConstraintIndex(T.mem, LGN_CONSTR_INDEX2);
    if (!flag) flag = LGNSetMaxConvFails(T.mem, 200); /* h collapses in one call */
    force_broken = 1;
    if (!flag) flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_NORMAL);
    force_broken = 0;
    CHECK(flag == LGN_STEP_TOO_SMALL && t <= t_fail,
          "(d) the force failing past t* = %g: %s at t = %.17g (LGN_STEP_TOO_SMALL expected)",
          t_fail, LGNGetReturnFlagName(flag), t);
    if (pass == 0) {
      /* the callback works again: the next call goes on */
      flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_NORMAL);
      CHECK(flag == LGN_SUCCESS && t == tend && MaxDiff(T.q, qref) < 1e-4 &&
                MaxDiff(T.v, vref) < 1e-3,
            "(d) after the collapse, the callback healthy: %s at t = %g, |q - qref| = %g, "
            "|v - vref| = %g", LGNGetReturnFlagName(flag), t, MaxDiff(T.q, qref),
            MaxDiff(T.v, vref));
    } else {
      /* LGNSetInitStep after steps: the size of the next step (smaller
       * than the estimate, 4e-8 here, so that it is taken as it is) */
      flag = LGNSetInitStep(T.mem, 1e-9);
      if (!flag) flag = LGNGetCurrentStep(T.mem, &h);
      CHECK(flag == LGN_SUCCESS && h == 1e-9, "(d) LGNSetInitStep(1e-9) after steps: the "
            "next step is %g", h);
      if (!flag) flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_ONE_STEP);
      if (!flag) flag = LGNGetLastStep(T.mem, &h);
      CHECK(flag == LGN_SUCCESS && h == 1e-9, "(d) the step after LGNSetInitStep(1e-9): "
            "%s, h = %g", LGNGetReturnFlagName(flag), h);
      if (!flag) flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_NORMAL);
      CHECK(flag == LGN_SUCCESS && t == tend && MaxDiff(T.q, qref) < 1e-4 &&
                MaxDiff(T.v, vref) < 1e-3,
            "(d) on to %g: %s, |q - qref| = %g, |v - vref| = %g", tend,
            LGNGetReturnFlagName(flag), MaxDiff(T.q, qref), MaxDiff(T.v, vref));
    }
    TopFree(&T);
  }
  N_VDestroy(qref);
  N_VDestroy(vref);
}

/* (e) Settings refused after LGNInit or after steps, the state kept. */
static void RefusedSettings(SUNContext ctx)
{
  Top T;
  LGNGroup G2 = LGNGroup_SO3();
  LGNBodies B;
  N_Vector q0 = N_VNew_Serial(7, ctx), v0 = N_VNew_Serial(6, ctx);
  const double bad[3] = {1.0, 1.0, 5.0}, rod[3] = {1.0, 2.0, 3.0};
  double plate[3] = {0.1, 0.2, 0.0}, t = 0.0;
  int flag = TopCreate(&T, ctx, 9, 0, 1e-10);

  /* LGNSetGroup with a group of another size after LGNInit */
  last_msg[0] = '\0';
  flag = LGNSetGroup(T.mem, G2);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "LGNInit") != NULL,
        "(e) LGNSetGroup(SO(3)) after LGNInit on R^3 x SO(3): %s, \"%s\"",
        LGNGetReturnFlagName(flag), last_msg);
  flag = LGNSolve(T.mem, 0.01, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == 0.01, "(e) a solve after the refused LGNSetGroup: %s",
        LGNGetReturnFlagName(flag));

  /* LGNCalcIC after steps */
  N_VScale(1.0, T.q, q0);
  N_VScale(1.0, T.v, v0);
  last_msg[0] = '\0';
  flag = LGNCalcIC(T.mem, LGN_IC_PROJECT_QV);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "LGNReInit") != NULL,
        "(e) LGNCalcIC after steps: %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  flag = LGNSolve(T.mem, 0.01, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == 0.01 && SameBits(T.q, q0) && SameBits(T.v, v0),
        "(e) the state after the refused LGNCalcIC: %s, |dv| = %g", LGNGetReturnFlagName(flag),
        MaxDiff(T.v, v0));
  TopFree(&T);

  /* principal moments: the triangle inequality J_i <= J_j + J_k */
  TopCreate(&T, ctx, 9, 0, 1e-10); /* for its group: one rigid body */
  B = LGNBodies_Create(T.G);
  LGNBodies_SetErrHandlerFn(B, Handler, NULL);
  last_msg[0] = '\0';
  flag = LGNBodies_SetPrincipalInertia(B, 0, 2.0, bad);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "J") != NULL &&
            strstr(last_msg, "triangle") != NULL,
        "(e) J = (1, 1, 5): %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  flag = LGNBodies_SetPrincipalInertia(B, 0, 2.0, rod);
  CHECK(flag == LGN_SUCCESS, "(e) J = (1, 2, 3) (a plate: equality): %s",
        LGNGetReturnFlagName(flag));
  plate[2] = plate[0] + plate[1]; /* 0.30000000000000004 */
  flag = LGNBodies_SetPrincipalInertia(B, 0, 2.0, plate);
  CHECK(flag == LGN_SUCCESS, "(e) J = (0.1, 0.2, 0.1 + 0.2): %s", LGNGetReturnFlagName(flag));
  plate[2] = 0.3 * (1.0 + 1e-6);
  flag = LGNBodies_SetPrincipalInertia(B, 0, 2.0, plate);
  CHECK(flag == LGN_ILL_INPUT, "(e) J = (0.1, 0.2, 0.3 (1 + 1e-6)): %s",
        LGNGetReturnFlagName(flag));
  /* ... and of a full tensor: diag(1, 1, 5) refused; a plate (1, 2, 3)
   * rotated by 30 degrees about x accepted */
  {
    const double c = 0.5 * sqrt(3.0), s = 0.5; /* 30 degrees */
    const double D[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 5.0};
    const double P[9] = {1.0, 0.0, 0.0, 0.0, 2.0 * c * c + 3.0 * s * s, (3.0 - 2.0) * c * s,
                         0.0, (3.0 - 2.0) * c * s, 2.0 * s * s + 3.0 * c * c};
    last_msg[0] = '\0';
    flag = LGNBodies_SetMass(B, 0, 2.0, D);
    CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "triangle") != NULL,
          "(e) inertia diag(1, 1, 5): %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
    flag = LGNBodies_SetMass(B, 0, 2.0, P);
    CHECK(flag == LGN_SUCCESS, "(e) a rotated plate's inertia: %s", LGNGetReturnFlagName(flag));
  }
  LGNBodies_Destroy(&B);
  TopFree(&T);
  LGNGroup_Destroy(G2);
  N_VDestroy(q0);
  N_VDestroy(v0);
}

/* (f) Messages that point at the cause. */
static void HelpfulMessages(SUNContext ctx)
{
  Top T;
  N_Vector atol = N_VNew_Serial(6, ctx), y = N_VNew_Serial(9, ctx);
  SUNLinearSolver spgmr = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 20, ctx);
  double t = 0.0;
  int flag = TopCreate(&T, ctx, 9, 1, 1e-6);

  last_msg[0] = '\0';
  flag = LGNSStolerances(T.mem, 1e-6, 4.9e-324);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "atol") != NULL,
        "(f) atol = 4.9e-324: %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNSStolerances(T.mem, 4.9e-324, 1e-6);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "rtol") != NULL,
        "(f) rtol = 4.9e-324: %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  N_VConst(1e-6, atol);
  NV_Ith_S(atol, 4) = 4.9e-324;
  last_msg[0] = '\0';
  flag = LGNSVtolerances(T.mem, 1e-6, atol);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "atol[4]") != NULL,
        "(f) atol[4] = 4.9e-324: %s, \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  /* the tolerances set before are kept */
  flag = LGNSolve(T.mem, 0.01, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "(f) a solve after the refused tolerances: %s",
        LGNGetReturnFlagName(flag));
  TopFree(&T);

  /* SPGMR for a left preconditioner, none attached */
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetLinearSolver(T.mem, spgmr, NULL);
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(T.mem, 0.01, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag != LGN_SUCCESS && strstr(last_msg, "PREC_LEFT") != NULL &&
            strstr(last_msg, "preconditioner") != NULL,
        "(f) SPGMR(PREC_LEFT) without a preconditioner: %s, \"%s\"",
        LGNGetReturnFlagName(flag), last_msg);
  TopFree(&T);
  SUNLinSolFree(spgmr);
  N_VDestroy(y);
  N_VDestroy(atol);
}

/* (g) A first step of 1e6 under error control. */
static void HugeFirstStep(SUNContext ctx)
{
  const double tend = 0.05;
  Top T;
  N_Vector qref = N_VNew_Serial(7, ctx), vref = N_VNew_Serial(6, ctx);
  double t = 0.0, h0 = 0.0;
  int flag;

  Reference(ctx, tend, qref, vref);
  flag = TopCreate(&T, ctx, 9, 1, 1e-6);
  if (!flag) flag = LGNSetInitStep(T.mem, 1e6);
  if (!flag) flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_NORMAL);
  LGNGetActualInitStep(T.mem, &h0);
  CHECK(flag == LGN_SUCCESS && t == tend && MaxDiff(T.q, qref) < 1e-4 &&
            MaxDiff(T.v, vref) < 1e-3,
        "(g) LGNSetInitStep(1e6) with error control: %s at t = %g, |q - qref| = %g, "
        "|v - vref| = %g", LGNGetReturnFlagName(flag), t, MaxDiff(T.q, qref),
        MaxDiff(T.v, vref));
  CHECK(h0 == tend, "(g) the first step tried: %g (1e6 cut to |tout - t0|)", h0);
  TopFree(&T);

  /* at index 2 the iteration matrix is singular at h = 1e6 (a recoverable
   * failure now: cut and retried) */
  flag = TopCreate(&T, ctx, 9, 1, 1e-6);
  if (!flag) flag = LGNSetConstraintIndex(T.mem, LGN_CONSTR_INDEX2);
  if (!flag) flag = LGNSetInitStep(T.mem, 1e6);
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(T.mem, tend, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS && t == tend && MaxDiff(T.q, qref) < 1e-4 &&
            MaxDiff(T.v, vref) < 1e-3,
        "(g) index 2, LGNSetInitStep(1e6): %s at t = %g, |q - qref| = %g, |v - vref| = %g "
        "\"%s\"", LGNGetReturnFlagName(flag), t, MaxDiff(T.q, qref), MaxDiff(T.v, vref),
        last_msg);
  TopFree(&T);

  /* fixed steps of 1e6: a clean failure, the state kept */
  flag = TopCreate(&T, ctx, 9, 0, 1e-10);
  if (!flag) flag = LGNSetStepSize(T.mem, 1e6);
  if (!flag) flag = LGNGetConsistentIC(T.mem, qref, NULL); /* the state at t */
  if (!flag) flag = LGNSolve(T.mem, 1e6, &t, T.q, T.v, LGN_NORMAL);
  CHECK(flag < 0 && t == 0.0 && SameBits(T.q, qref),
        "(g) a fixed step of 1e6: %s at t = %g", LGNGetReturnFlagName(flag), t);
  TopFree(&T);
  N_VDestroy(qref);
  N_VDestroy(vref);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  GettersAfterFailure(ctx);
  RootInitOverflow(ctx);
  FixedStepStopTime(ctx);
  RecoveryAfterCollapse(ctx);
  RefusedSettings(ctx);
  HelpfulMessages(ctx);
  HugeFirstStep(ctx);
  SUNContext_Free(&ctx);
  return test_summary("test_reliability");
}
