/* -----------------------------------------------------------------------------
 * Lignum test: arguments that used to be accepted and then failed later (or
 * silently) are refused where they are given, with a message naming them.
 *
 *  - a dense linear solver created for another size than A (SUNDIALS would
 *    write past its pivot array);
 *  - method parameters that are not finite (alpha = -Inf);
 *  - step sizes whose square or its inverse is not a finite number;
 *  - an initial configuration that is not on the group (zero quaternion, or
 *    one whose normalisation overflows: refused without touching the state)
 *    or has a NaN, and a NaN velocity;
 *  - initial accelerations set after the first step (as LGNSetInitialAux);
 *  - and LGNSetGroup with another size after LGNInit is refused with the
 *    state kept (the solve goes on); a new integrator takes the new size.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

static char last_msg[512];
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

/* A free symmetric top on SO(3) (or a free point on R^n: unit mass, no
 * force). */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  sunindextype i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < SM_ROWS_D(M); i++) SM_ELEMENT_D(M, i, i) = 1.0;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)g; (void)ud;
  return 0;
}

static int Refused(int flag, int expected, const char *name)
{
  return flag == expected && strstr(last_msg, name) != NULL;
}

int main(void)
{
  SUNContext ctx;
  LGNGroup so3 = LGNGroup_SO3(), r5 = LGNGroup_Rn(5);
  N_Vector q, v, q5, v5, y1, vd;
  SUNMatrix A3, A1, A5;
  SUNLinearSolver LS1, LS3, LS5;
  void *mem;
  double t;
  int flag;

  SUNContext_Create(NULL, &ctx);
  q  = N_VNew_Serial(4, ctx);
  v  = N_VNew_Serial(3, ctx);
  q5 = N_VNew_Serial(5, ctx);
  v5 = N_VNew_Serial(5, ctx);
  y1 = N_VNew_Serial(1, ctx);
  vd = N_VNew_Serial(3, ctx);
  A1 = SUNDenseMatrix(1, 1, ctx);
  A3 = SUNDenseMatrix(3, 3, ctx);
  A5 = SUNDenseMatrix(5, 5, ctx);
  LS1 = SUNLinSol_Dense(y1, A1, ctx); /* for 1 x 1 */
  LS3 = SUNLinSol_Dense(v, A3, ctx);
  LS5 = SUNLinSol_Dense(v5, A5, ctx);
  N_VConst(0.0, q);
  N_VGetArrayPointer(q)[0] = 1.0;
  N_VConst(1.0, v);
  N_VConst(0.0, q5);
  N_VConst(1.0, v5);

  mem = LGNCreate(ctx);
  LGNSetErrHandlerFn(mem, Capture, NULL);
  LGNSetGroup(mem, so3);
  LGNSetMassFn(mem, Mass);
  LGNSetForceFn(mem, Force);
  LGNSetStepSize(mem, 1e-3);
  CHECK(LGNInit(mem, 0.0, q, v) == LGN_SUCCESS, "LGNInit");

  /* m so large that sizes would overflow */
  CHECK(Refused(LGNSetConstraints(mem, (sunindextype)1 << 40, NULL, NULL), LGN_ILL_INPUT, "m = "),
        "m = 2^40: %s", last_msg);

  /* a tout behind t refused before anything is computed: vdot stays 0 */
  N_VConst(1.0, vd);
  flag = LGNSolve(mem, -1.0, &t, q, v, LGN_NORMAL);
  CHECK(Refused(flag, LGN_BAD_TOUT, "behind") && LGNGetAcceleration(mem, vd) == LGN_SUCCESS &&
            N_VMaxNorm(vd) == 0.0,
        "tout behind t before the first step: %s, |vdot| = %g", last_msg, N_VMaxNorm(vd));

  /* a dense solver made for 1 x 1, with a 3 x 3 A */
  CHECK(LGNSetLinearSolver(mem, LS1, A3) == LGN_SUCCESS, "attach");
  flag = LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL);
  CHECK(Refused(flag, LGN_LS_MISMATCH, "created for 1 x 1"), "dense solver of another size: %s (%s)",
        LGNGetReturnFlagName(flag), last_msg);
  CHECK(LGNSetLinearSolver(mem, LS3, A3) == LGN_SUCCESS, "attach the right one");

  /* method parameters */
  CHECK(Refused(LGNSetGenAlphaParams(mem, -INFINITY, 0.4, 0.3, 0.6), LGN_ILL_INPUT, "finite"),
        "alpha_m = -Inf: %s", last_msg);
  CHECK(Refused(LGNSetGenAlphaParams(mem, 0.2, NAN, 0.3, 0.6), LGN_ILL_INPUT, "finite"),
        "alpha_f = NaN: %s", last_msg);

  /* step sizes */
  CHECK(Refused(LGNSetStepSize(mem, 1e-300), LGN_ILL_INPUT, "h = 1e-300"), "h = 1e-300: %s", last_msg);
  CHECK(Refused(LGNSetStepSize(mem, 1e200), LGN_ILL_INPUT, "h = 1e+200"), "h = 1e200: %s", last_msg);
  CHECK(LGNSetStepSize(mem, 1e-100) == LGN_SUCCESS, "h = 1e-100 is fine");
  CHECK(LGNSetStepSize(mem, 1e-3) == LGN_SUCCESS, "h = 1e-3");

  /* the initial state */
  N_VConst(0.0, q);
  CHECK(Refused(LGNReInit(mem, 0.0, q, v), LGN_ILL_INPUT, "q0 is not an element"),
        "zero quaternion: %s", last_msg);
  N_VGetArrayPointer(q)[0] = NAN;
  CHECK(Refused(LGNReInit(mem, 0.0, q, v), LGN_ILL_INPUT, "q0 has a NaN"), "NaN in q0: %s", last_msg);
  N_VGetArrayPointer(q)[0] = 1.0;
  N_VGetArrayPointer(v)[1] = INFINITY;
  CHECK(Refused(LGNReInit(mem, 0.0, q, v), LGN_ILL_INPUT, "v0 has a NaN or Inf"), "Inf in v0: %s",
        last_msg);
  N_VGetArrayPointer(v)[1] = 1.0;
  CHECK(LGNReInit(mem, 0.0, q, v) == LGN_SUCCESS, "a good start again");

  /* initial accelerations after the first step */
  flag = LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "run: %s", LGNGetReturnFlagName(flag));

  /* a finite q0 whose normalisation overflows (|q| = 2e300), refused by
   * LGNReInit and by LGNInit: the state at t = 0.01 is kept (fuzzer finding:
   * the refused LGNReInit had overwritten q and v) */
  {
    N_Vector qbad = N_VClone(q), qk = N_VClone(q), vk = N_VClone(v);
    double tk = 0.0;
    N_VConst(1e300, qbad);
    CHECK(Refused(LGNReInit(mem, 5.0, qbad, v), LGN_ILL_INPUT, "q0 is not an element"),
          "|q0| = 2e300 to LGNReInit: %s", last_msg);
    CHECK(Refused(LGNInit(mem, 5.0, qbad, v), LGN_ILL_INPUT, "q0 is not an element"),
          "|q0| = 2e300 to LGNInit: %s", last_msg);
    CHECK(LGNGetCurrentTime(mem, &tk) == LGN_SUCCESS && tk == t, "t kept: %g", tk);
    CHECK(LGNGetDky(mem, t, 0, qk) == LGN_SUCCESS && LGNGetDky(mem, t, 1, vk) == LGN_SUCCESS,
          "q, v at t still there");
    N_VLinearSum(1.0, qk, -1.0, q, qk);
    N_VLinearSum(1.0, vk, -1.0, v, vk);
    CHECK(N_VMaxNorm(qk) == 0.0 && N_VMaxNorm(vk) == 0.0, "q, v kept: |dq| = %g, |dv| = %g",
          N_VMaxNorm(qk), N_VMaxNorm(vk));
    N_VDestroy(qbad);
    N_VDestroy(qk);
    N_VDestroy(vk);
  }
  N_VConst(0.0, vd);
  CHECK(Refused(LGNSetInitialAcceleration(mem, vd, NULL), LGN_ILL_INPUT, "before the first step"),
        "vdot0 after a step: %s", last_msg);

  /* a constant of another setter is refused, naming the right ones */
  CHECK(Refused(LGNSetKinematics(mem, LGN_NEWTON_MODIFIED), LGN_ILL_INPUT, "LGN_KINEMATICS_EXACT"),
        "LGNSetKinematics(LGN_NEWTON_MODIFIED): %s", last_msg);
  CHECK(Refused(LGNSetNewtonMode(mem, LGN_KINEMATICS_EXACT), LGN_ILL_INPUT, "LGN_NEWTON_FULL"),
        "LGNSetNewtonMode(LGN_KINEMATICS_EXACT): %s", last_msg);
  CHECK(Refused(LGNSetConstraintIndex(mem, LGN_ONE_STEP), LGN_ILL_INPUT, "LGN_CONSTR_INDEX3"),
        "LGNSetConstraintIndex(LGN_ONE_STEP): %s", last_msg);
  CHECK(Refused(LGNSetPredictor(mem, LGN_STEP_ADAPTIVE), LGN_ILL_INPUT, "LGN_PREDICTOR_ZERO"),
        "LGNSetPredictor(LGN_STEP_ADAPTIVE): %s", last_msg);

  /* the settings and the aggregate statistics read back */
  {
    int kin = 0, idx = 0, mode = 0, ctl = 0;
    sunrealtype h = 0, rt = 0, at = 0, hin, hl, hc, tc;
    long int nst, nre, nls, netf, nst1 = -1, nni, nncf, nni1 = -1;
    CHECK(LGNSetKinematics(mem, LGN_KINEMATICS_EXACT) == LGN_SUCCESS &&
              LGNGetKinematics(mem, &kin) == LGN_SUCCESS && kin == LGN_KINEMATICS_EXACT,
          "LGNGetKinematics");
    CHECK(LGNGetConstraintIndex(mem, &idx) == LGN_SUCCESS && idx == LGN_CONSTR_INDEX3,
          "LGNGetConstraintIndex");
    CHECK(LGNGetNewtonMode(mem, &mode) == LGN_SUCCESS && mode == LGN_NEWTON_FULL, "LGNGetNewtonMode");
    CHECK(LGNGetStepControl(mem, &ctl) == LGN_SUCCESS && ctl == LGN_STEP_FIXED, "LGNGetStepControl");
    CHECK(LGNGetStepSize(mem, &h) == LGN_SUCCESS && h == 1e-3, "LGNGetStepSize");
    CHECK(LGNSStolerances(mem, 1e-7, 1e-9) == LGN_SUCCESS &&
              LGNGetTolerances(mem, &rt, &at) == LGN_SUCCESS && rt == 1e-7 && at == 1e-9,
          "LGNGetTolerances");
    CHECK(LGNGetIntegratorStats(mem, &nst, &nre, &nls, &netf, &hin, &hl, &hc, &tc) == LGN_SUCCESS &&
              LGNGetNumSteps(mem, &nst1) == LGN_SUCCESS && nst == nst1 && nst == 10 &&
              fabs(hl - 1e-3) < 1e-15 && tc == t,
          "LGNGetIntegratorStats: %ld steps, h %g, t %g", nst, hl, tc);
    CHECK(LGNGetNewtonStats(mem, &nni, &nncf) == LGN_SUCCESS &&
              LGNGetNumNewtonIters(mem, &nni1) == LGN_SUCCESS && nni == nni1 && nncf == 0,
          "LGNGetNewtonStats");
    CHECK(Refused(LGNGetIntegratorStats(mem, &nst, &nre, &nls, &netf, &hin, &hl, NULL, &tc),
                  LGN_ILL_INPUT, "hcur"),
          "a NULL output named: %s", last_msg);
  }

  /* LGN_ONE_STEP with a tout behind t */
  flag = LGNSolve(mem, -1.0, &t, q, v, LGN_ONE_STEP);
  CHECK(Refused(flag, LGN_BAD_TOUT, "behind"), "LGN_ONE_STEP, tout behind t: %s", last_msg);

  /* a group of another size after LGNInit (SO(3) -> R^5): refused, the
   * state kept (issue 31; it used to drop the state, and the next solve
   * said "before LGNInit"); a new problem takes a new integrator */
  CHECK(Refused(LGNSetGroup(mem, r5), LGN_ILL_INPUT, "LGNCreate"),
        "LGNSetGroup with another size: %s", last_msg);
  {
    const double t0 = t;
    flag = LGNSolve(mem, t0 + 0.02, &t, q, v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS && t == t0 + 0.02, "the state kept: %s at t = %g",
          LGNGetReturnFlagName(flag), t);
  }
  {
    void *mem5 = LGNCreate(ctx);
    flag = LGNSetGroup(mem5, r5);
    if (!flag) flag = LGNSetMassFn(mem5, Mass);
    if (!flag) flag = LGNSetForceFn(mem5, Force);
    if (!flag) flag = LGNSetStepSize(mem5, 1e-3);
    if (!flag) flag = LGNInit(mem5, 0.0, q5, v5);
    if (!flag) flag = LGNSetLinearSolver(mem5, LS5, A5);
    if (!flag) flag = LGNSolve(mem5, 0.5, &t, q5, v5, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS && fabs(N_VGetArrayPointer(q5)[0] - 0.5) < 1e-12,
          "a new integrator on R^5 (free motion, x = t): %s, x = %.17g",
          LGNGetReturnFlagName(flag), N_VGetArrayPointer(q5)[0]);
    LGNFree(&mem5);
  }
  LGNFree(&mem);
  SUNLinSolFree(LS1);
  SUNLinSolFree(LS3);
  SUNLinSolFree(LS5);
  SUNMatDestroy(A1);
  SUNMatDestroy(A3);
  SUNMatDestroy(A5);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(q5);
  N_VDestroy(v5);
  N_VDestroy(y1);
  N_VDestroy(vd);
  LGNGroup_Destroy(so3);
  LGNGroup_Destroy(r5);
  SUNContext_Free(&ctx);
  return test_summary("test_validation");
}
