/* -----------------------------------------------------------------------------
 * Lignum test: a setting of one method family is refused under the other
 * (issue 32), whichever order the calls come in.
 *
 *  - at set time: LGNSetKinematics and LGNSetPredictor under the BDF family,
 *    LGNSetBDFForm under the Newmark family, with a value other than their
 *    default, return LGN_ILL_INPUT with a message naming the setter, and
 *    change nothing (the getter still gives the old value; the same call is
 *    accepted once its family is selected); their defaults are accepted;
 *  - at the start: a setting accepted under its family and left at a value
 *    other than its default when the other family is selected makes LGNSolve
 *    and LGNCalcIC return LGN_ILL_INPUT naming the setting; set back to the
 *    default (or with its family selected again) the run goes on.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

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

/* a free unit mass on R^2 */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  sunindextype i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < SM_ROWS_D(M); i++) SM_ELEMENT_D(M, i, i) = 1.0;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  N_VConst(SUN_RCONST(0.0), g);
  return 0;
}

/* flag is expected and the last message names name */
static int Refused(int flag, int expected, const char *name)
{
  return flag == expected && strstr(last_msg, name) != NULL;
}

typedef struct {
  void *mem;
  N_Vector q, v;
  SUNMatrix A;
  SUNLinearSolver LS;
} Run;

static int Setup(Run *r, SUNContext ctx, LGNGroup G)
{
  int flag;
  r->q   = N_VNew_Serial(2, ctx);
  r->v   = N_VNew_Serial(2, ctx);
  r->A   = SUNDenseMatrix(2, 2, ctx);
  r->LS  = SUNLinSol_Dense(r->q, r->A, ctx);
  r->mem = LGNCreate(ctx);
  N_VConst(SUN_RCONST(0.0), r->q);
  N_VConst(SUN_RCONST(1.0), r->v);
  flag = LGNSetErrHandlerFn(r->mem, Capture, NULL);
  if (!flag) flag = LGNSetGroup(r->mem, G);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, Force);
  if (!flag) flag = LGNSetStepSize(r->mem, SUN_RCONST(0.01));
  if (!flag) flag = LGNInit(r->mem, SUN_RCONST(0.0), r->q, r->v);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  return flag;
}

static void Teardown(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  N_VDestroy(r->q);
  N_VDestroy(r->v);
}

static int Solve(Run *r)
{
  sunrealtype t = SUN_RCONST(0.0);
  return LGNSolve(r->mem, SUN_RCONST(0.05), &t, r->q, r->v, LGN_NORMAL);
}

int main(void)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_Rn(2);
  Run r;
  int kin = -1;
  SUNContext_Create(NULL, &ctx);

  /* ---- at set time ---- */
  CHECK(Setup(&r, ctx, G) == LGN_SUCCESS, "setup");
  CHECK(Refused(LGNSetBDFForm(r.mem, LGN_BDF_FIXED_LEADING), LGN_ILL_INPUT, "LGNSetBDFForm"),
        "LGNSetBDFForm under the Newmark family refused: %s", last_msg);
  CHECK(strstr(last_msg, "BDF family") != NULL, "the message names the family: %s", last_msg);
  CHECK(LGNSetBDFForm(r.mem, LGN_BDF_VARIABLE_COEFF) == LGN_SUCCESS,
        "the BDF default is accepted under the Newmark family");
  CHECK(LGNSetBDF(r.mem, 3) == LGN_SUCCESS, "LGNSetBDF");
  CHECK(Refused(LGNSetKinematics(r.mem, LGN_KINEMATICS_EXACT), LGN_ILL_INPUT, "LGNSetKinematics"),
        "LGNSetKinematics under BDF refused: %s", last_msg);
  CHECK(LGNGetKinematics(r.mem, &kin) == LGN_SUCCESS && kin == LGN_KINEMATICS_SIMPLIFIED,
        "the refused kinematics changed nothing (%d)", kin);
  CHECK(Refused(LGNSetPredictor(r.mem, LGN_PREDICTOR_EXTRAPOLATE), LGN_ILL_INPUT,
                "LGNSetPredictor"), "LGNSetPredictor under BDF refused: %s", last_msg);
  CHECK(LGNSetKinematics(r.mem, LGN_KINEMATICS_SIMPLIFIED) == LGN_SUCCESS &&
        LGNSetPredictor(r.mem, LGN_PREDICTOR_ZERO) == LGN_SUCCESS,
        "the Newmark defaults are accepted under BDF");
  CHECK(Refused(LGNSetKinematics(r.mem, 12345), LGN_ILL_INPUT, "kinematics = 12345"),
        "an illegal value is named before the family: %s", last_msg);
  CHECK(LGNSetBDFForm(r.mem, LGN_BDF_FIXED_LEADING) == LGN_SUCCESS, "LGNSetBDFForm under BDF");
  CHECK(Solve(&r) == LGN_SUCCESS, "BDF with its own settings runs: %s", last_msg);
  Teardown(&r);

  /* ---- at the start: Newmark settings left, then BDF selected ---- */
  CHECK(Setup(&r, ctx, G) == LGN_SUCCESS, "setup");
  CHECK(LGNSetKinematics(r.mem, LGN_KINEMATICS_EXACT) == LGN_SUCCESS, "kinematics (Newmark)");
  CHECK(LGNSetBDF(r.mem, 2) == LGN_SUCCESS, "switching the family is accepted");
  last_msg[0] = '\0';
  CHECK(Refused(Solve(&r), LGN_ILL_INPUT, "LGNSetKinematics"),
        "LGNSolve refuses the Newmark kinematics under BDF: %s", last_msg);
  CHECK(Refused(LGNCalcIC(r.mem, LGN_IC_PROJECT_QV), LGN_ILL_INPUT, "LGNSetKinematics"),
        "LGNCalcIC refuses it too: %s", last_msg);
  CHECK(LGNSetGenAlpha(r.mem, 0.9) == LGN_SUCCESS &&
        LGNSetKinematics(r.mem, LGN_KINEMATICS_SIMPLIFIED) == LGN_SUCCESS &&
        LGNSetPredictor(r.mem, LGN_PREDICTOR_EXTRAPOLATE) == LGN_SUCCESS &&
        LGNSetBDF(r.mem, 2) == LGN_SUCCESS, "settings back, a Newmark predictor, BDF again");
  last_msg[0] = '\0';
  CHECK(Refused(Solve(&r), LGN_ILL_INPUT, "LGNSetPredictor"),
        "LGNSolve refuses the Newmark predictor under BDF: %s", last_msg);
  CHECK(LGNSetGenAlpha(r.mem, 0.9) == LGN_SUCCESS &&
        LGNSetPredictor(r.mem, LGN_PREDICTOR_ZERO) == LGN_SUCCESS &&
        LGNSetBDF(r.mem, 2) == LGN_SUCCESS, "the predictor back to its default");
  CHECK(Solve(&r) == LGN_SUCCESS, "then the run goes on: %s", last_msg);
  Teardown(&r);

  /* ---- at the start: a BDF form left, then Newmark selected ---- */
  CHECK(Setup(&r, ctx, G) == LGN_SUCCESS, "setup");
  CHECK(LGNSetBDF(r.mem, 2) == LGN_SUCCESS &&
        LGNSetBDFForm(r.mem, LGN_BDF_FIXED_LEADING) == LGN_SUCCESS &&
        LGNSetGenAlpha(r.mem, 0.9) == LGN_SUCCESS, "a BDF form, then the Newmark family");
  last_msg[0] = '\0';
  CHECK(Refused(Solve(&r), LGN_ILL_INPUT, "LGNSetBDFForm"),
        "LGNSolve refuses the BDF form under Newmark: %s", last_msg);
  CHECK(LGNSetBDF(r.mem, 2) == LGN_SUCCESS && Solve(&r) == LGN_SUCCESS,
        "with BDF selected again the run goes on: %s", last_msg);
  Teardown(&r);

  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return test_summary("test_family_settings");
}
