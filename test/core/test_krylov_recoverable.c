/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A recoverable failure (return > 0) of a user preconditioner's setup or
 * solve with a matrix-free Krylov solver (lgn_krylov.c). Regression test of
 * a finding of the fuzz target (test/fuzz): with a fixed step size LGNSolve
 * returned the internal code LGN_RECOVERABLE (100), a positive value with no
 * name, instead of a failure flag (error control retries such a step with a
 * smaller h, a fixed step cannot).
 *
 * On the 3-body spherical-pendulum chain with SPGMR (PREC_LEFT) and the
 * identity as the user preconditioner, after 5 good steps of h = 1e-3 the
 * preconditioner's setup (then, separately, its solve) returns +1 once.
 * Asserted:
 *   - fixed steps: LGNSolve returns LGN_LSETUP_FAIL (LGN_LSOLVE_FAIL for the
 *     solve), a named negative flag; the current time, the number of steps
 *     and the returned q, v are those before the call; with the fault gone
 *     the next LGNSolve goes on;
 *   - error control: the same single fault is absorbed (the step retried
 *     smaller): LGNSolve returns LGN_SUCCESS at tout.
 * Each of the four cases fails on the code before the fix with flag 100
 * (fixed steps).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "models/chain.h"
#include "test_util.h"

/* the fault: in the setup (0) or the solve (1), at call `at` from now */
static struct {
  int where;
  long at, calls;
} fault;

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

static int FaultNow(int where)
{
  if (fault.where != where || fault.at <= 0) return 0;
  return ++fault.calls == fault.at ? 1 : 0;
}

static int Setup(sunrealtype t, N_Vector q, N_Vector v, sunrealtype cM, sunrealtype cC,
                 sunrealtype cK, void *ud)
{
  (void)t; (void)q; (void)v; (void)cM; (void)cC; (void)cK; (void)ud;
  return FaultNow(0);
}

static int Solve(sunrealtype t, N_Vector q, N_Vector v, N_Vector r, N_Vector z,
                 sunrealtype cM, sunrealtype cC, sunrealtype cK, sunrealtype delta, void *ud)
{
  (void)t; (void)q; (void)v; (void)cM; (void)cC; (void)cK; (void)delta; (void)ud;
  N_VScale(1.0, r, z);
  return FaultNow(1);
}

static void Case(SUNContext ctx, int where, int adaptive)
{
  const char *what = where == 0 ? "setup" : "solve";
  const int expect = where == 0 ? LGN_LSETUP_FAIL : LGN_LSOLVE_FAIL;
  RigidSystem *sys = chain_create(3, RB_R3XSO3, ctx);
  const sunindextype n = sys->G->nv + LGNJoints_NumConstraints(sys->joints);
  N_Vector y = N_VNew_Serial(n, ctx), q = N_VClone(sys->q0), v = N_VClone(sys->v0);
  N_Vector q5 = N_VClone(sys->q0), v5 = N_VClone(sys->v0);
  SUNLinearSolver LS = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 40, ctx);
  RigidCallbacks cb;
  void *mem = LGNCreate(ctx);
  sunrealtype t = 0.0, t5 = 0.0, tcur = 0.0;
  long int nst5 = 0, nst = 0;
  int flag, k;
  rigid_get_callbacks(&cb);
  memset(&fault, 0, sizeof fault);
  LGNSetErrFile(mem, NULL);
  flag = LGNSetGroup(mem, sys->G);
  if (!flag) flag = LGNInit(mem, 0.0, sys->q0, sys->v0);
  if (!flag) flag = LGNSetUserData(mem, sys);
  if (!flag) flag = LGNSetMassFn(mem, cb.mass);
  if (!flag) flag = LGNSetForceFn(mem, cb.force);
  if (!flag) flag = LGNSetStiffnessFn(mem, cb.stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, cb.damping);
  if (!flag)
    flag = LGNSetConstraints(mem, LGNJoints_NumConstraints(sys->joints), Constr, ConstrJac);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, NULL);
  if (!flag) flag = LGNSetPreconditioner(mem, Setup, Solve);
  if (!flag && adaptive) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag && adaptive) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  CHECK(flag == LGN_SUCCESS, "set up (%d)", flag);
  for (k = 0; k < 5 && flag == LGN_SUCCESS; k++) flag = LGNSolve(mem, 1.0, &t, q, v, LGN_ONE_STEP);
  CHECK(flag == LGN_SUCCESS, "5 good steps (%d)", flag);
  LGNGetCurrentTime(mem, &t5);
  LGNGetNumSteps(mem, &nst5);
  N_VScale(1.0, q, q5);
  N_VScale(1.0, v, v5);

  /* the next call of the setup (solve) returns +1 */
  fault.where = where;
  fault.at    = 1;
  flag        = LGNSolve(mem, t5 + 0.01, &t, q, v, LGN_NORMAL);
  printf("%s, %s: the preconditioner %s returns +1 once -> %s (%d)\n",
         adaptive ? "error control" : "fixed steps", what, what, LGNGetReturnFlagName(flag),
         flag);
  if (adaptive) {
    CHECK(flag == LGN_SUCCESS && fabs(t - (t5 + 0.01)) <= 1e-12,
          "error control absorbs a recoverable %s failure: %s at %.17g", what,
          LGNGetReturnFlagName(flag), t);
  } else {
    CHECK(flag == expect, "fixed steps: a recoverable %s failure is %s, not %d", what,
          LGNGetReturnFlagName(expect), flag);
    LGNGetCurrentTime(mem, &tcur);
    LGNGetNumSteps(mem, &nst);
    CHECK(tcur == t5 && nst == nst5, "no step taken: t %.17g (was %.17g), %ld steps (%ld)",
          tcur, t5, nst, nst5);
    CHECK(t == t5, "tret is the current time");
    N_VLinearSum(1.0, q, -1.0, q5, q);
    N_VLinearSum(1.0, v, -1.0, v5, v);
    CHECK(N_VMaxNorm(q) == 0.0 && N_VMaxNorm(v) == 0.0, "q, v as before the call");
    fault.at = 0;
    flag     = LGNSolve(mem, t5 + 0.01, &t, q, v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "with the fault gone the solve goes on (%d)", flag);
  }
  CHECK(fault.calls >= 1, "the fault was reached");
  LGNFree(&mem);
  SUNLinSolFree(LS);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(q5);
  N_VDestroy(v5);
  rigid_free(&sys);
}

int main(void)
{
  SUNContext ctx;
  int where, adaptive;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  for (adaptive = 0; adaptive < 2; adaptive++)
    for (where = 0; where < 2; where++) Case(ctx, where, adaptive);
  SUNContext_Free(&ctx);
  return test_summary("test_krylov_recoverable");
}
