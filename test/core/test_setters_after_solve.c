/* -----------------------------------------------------------------------------
 * Lignum test: a setting changed between two LGNSolve calls takes effect
 * completely, with nothing left over from before (no stale cache).
 *
 * (a) LGNSetGroup after a first solve with another group of the same sizes
 *     (R^3 x SO(3) -> SE(3)), the old group destroyed: the continuation must
 *     equal, bit for bit, a fresh integrator started with SE(3) at the same
 *     state (both compute consistent accelerations there), and read no freed
 *     memory (run under valgrind and ASan). Before the fix the block table
 *     of the old group was kept: the iteration matrix was built with the old
 *     group's T, and freed memory was read.
 * (b) Each method or model setter after a solve with modified Newton (which
 *     reuses the factorised matrix across steps): the continuation must equal,
 *     bit for bit, a fresh integrator configured with the new setting and
 *     started from the same state, accelerations, multipliers and auxiliary
 *     variable. A cache the setter failed to drop (the factorised matrix, a
 *     constant mass matrix, the Newton rate) would make them differ.
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

/* A heavy body: mass m, principal moments J (body axes), gravity along -z,
 * optionally pinned to the ground at the body point Xp (a heavy top). */
typedef struct {
  double m, J[3], Xp[3];
} Body;

static const Body body_a = {2.0, {0.3, 0.5, 0.7}, {0.0, 0.0, 0.4}};
static const Body body_b = {2.5, {0.35, 0.45, 0.8}, {0.0, 0.0, 0.4}};

#define GRAV 9.81

static void Rotation(N_Vector q, double R[9])
{
  LGNQuaternionToRotation(N_VGetArrayPointer(q) + 3, R);
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const Body *b = (const Body *)ud;
  int i;
  (void)t;
  (void)q;
  for (i = 0; i < 3; i++) {
    SM_ELEMENT_D(M, i, i)     = b->m;
    SM_ELEMENT_D(M, i + 3, i + 3) = b->J[i];
  }
  return 0;
}

/* the same body, 10 % heavier: another mass function */
static int MassHeavier(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  int i, flag = Mass(t, q, M, ud);
  for (i = 0; i < 6; i++) SM_ELEMENT_D(M, i, i) *= 1.1;
  return flag;
}

static void Gyroscopic(const Body *b, const double *W, double *g)
{
  g[0] = W[1] * b->J[2] * W[2] - W[2] * b->J[1] * W[1];
  g[1] = W[2] * b->J[0] * W[0] - W[0] * b->J[2] * W[2];
  g[2] = W[0] * b->J[1] * W[1] - W[1] * b->J[0] * W[0];
}

/* R^3 x SO(3), v = (u inertial, W body): g = (m g e3, W x J W) */
static int ForceR3xSO3(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const Body *b = (const Body *)ud;
  double *gg = N_VGetArrayPointer(g);
  (void)t;
  (void)q;
  gg[0] = gg[1] = 0.0;
  gg[2] = b->m * GRAV;
  Gyroscopic(b, N_VGetArrayPointer(v) + 3, gg + 3);
  return 0;
}

/* ... with a linear damping of the velocity: another force function */
static int ForceDamped(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  int i, flag = ForceR3xSO3(t, q, v, g, ud);
  for (i = 0; i < 6; i++) N_VGetArrayPointer(g)[i] += 0.2 * N_VGetArrayPointer(v)[i];
  return flag;
}

/* SE(3), v = (U, W) body-fixed: g = (m W x U + m g R^T e3, W x J W) */
static int ForceSE3(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const Body *b = (const Body *)ud;
  const double *U = N_VGetArrayPointer(v), *W = U + 3;
  double *gg = N_VGetArrayPointer(g), R[9];
  (void)t;
  Rotation(q, R);
  gg[0] = b->m * (W[1] * U[2] - W[2] * U[1]) + b->m * GRAV * R[6];
  gg[1] = b->m * (W[2] * U[0] - W[0] * U[2]) + b->m * GRAV * R[7];
  gg[2] = b->m * (W[0] * U[1] - W[1] * U[0]) + b->m * GRAV * R[8];
  Gyroscopic(b, W, gg + 3);
  return 0;
}

/* the pivot: Phi = x + R Xp, B = [I, -R Xp~] (R^3 x SO(3)) */
static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const Body *b = (const Body *)ud;
  const double *x = N_VGetArrayPointer(q);
  double R[9];
  int i;
  (void)t;
  Rotation(q, R);
  for (i = 0; i < 3; i++)
    N_VGetArrayPointer(phi)[i] =
        x[i] + R[3 * i] * b->Xp[0] + R[3 * i + 1] * b->Xp[1] + R[3 * i + 2] * b->Xp[2];
  return 0;
}

static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const Body *b = (const Body *)ud;
  const double *s = b->Xp;
  const double S[9] = {0.0, -s[2], s[1], s[2], 0.0, -s[0], -s[1], s[0], 0.0};
  double R[9];
  int i, j, k;
  (void)t;
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

/* A consistent initial state: W0, the rotation exp(psi0), the pivot fixed
 * (pinned) or a free body thrown with velocity u0. */
static void InitialState(const Body *b, int pinned, N_Vector q, N_Vector v)
{
  const double psi0[3] = {0.3, -0.2, 0.5}, W0[3] = {1.0, -2.0, 8.0};
  double *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v), R[9], c[3];
  int i;
  LGNQuaternionFromRotationVector(psi0, x + 3);
  Rotation(q, R);
  c[0] = W0[1] * b->Xp[2] - W0[2] * b->Xp[1];
  c[1] = W0[2] * b->Xp[0] - W0[0] * b->Xp[2];
  c[2] = W0[0] * b->Xp[1] - W0[1] * b->Xp[0];
  for (i = 0; i < 3; i++) {
    x[i] = -(R[3 * i] * b->Xp[0] + R[3 * i + 1] * b->Xp[1] + R[3 * i + 2] * b->Xp[2]);
    u[i] = pinned ? -(R[3 * i] * c[0] + R[3 * i + 1] * c[1] + R[3 * i + 2] * c[2])
                  : 1.5 - 0.5 * i;
    u[3 + i] = W0[i];
  }
}

typedef struct {
  SUNContext ctx;
  void *mem;
  SUNMatrix A;
  SUNLinearSolver LS;
  N_Vector q, v;
} Run;

/* An integrator on G for the body: modified Newton, exact kinematics,
 * generalized-alpha 0.8, h = 1e-3, tight Newton tolerances. */
static int RunCreate(Run *r, SUNContext ctx, LGNGroup G, int pinned, const Body *b,
                     LGNForceFn force)
{
  const sunindextype n = 6 + (pinned ? 3 : 0);
  int flag;
  memset(r, 0, sizeof *r);
  r->ctx = ctx;
  r->q   = N_VNew_Serial(7, ctx);
  r->v   = N_VNew_Serial(6, ctx);
  r->A   = SUNDenseMatrix(n, n, ctx);
  {
    N_Vector y = N_VNew_Serial(n, ctx); /* a template: not kept by the solver */
    r->LS = SUNLinSol_Dense(y, r->A, ctx);
    N_VDestroy(y);
  }
  r->mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(r->mem, SUNFALSE);
  LGNSetProjectOutputs(r->mem, LGN_PROJECT_NONE);
  InitialState(b, pinned, r->q, r->v);
  flag = LGNSetGroup(r->mem, G);
  if (!flag) flag = LGNSetUserData(r->mem, (void *)b);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, force);
  if (!flag && pinned) flag = LGNSetConstraints(r->mem, 3, Phi, Jac);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = LGNSetGenAlpha(r->mem, 0.8);
  if (!flag) flag = LGNSetKinematics(r->mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetNewtonMode(r->mem, LGN_NEWTON_MODIFIED);
  if (!flag) flag = LGNSetStepSize(r->mem, 1e-3);
  if (!flag) flag = LGNSStolerances(r->mem, 1e-10, 1e-10);
  return flag;
}

static void RunFree(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  N_VDestroy(r->q);
  N_VDestroy(r->v);
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

/* The group of a fresh reference integrator started from a state reached by
 * another one: LGNInit would normalise the quaternion again, which may move
 * its last bit, so the reference's group takes q as it is (the user may set
 * a group's operations, lignum_group.h). */
static LGNGroup FreshGroup(LGNGroup G)
{
  if (G != NULL) G->ops.normalize = NULL;
  return G;
}

/* (a) R^3 x SO(3) -> SE(3) after a first solve. */
static void GroupSwitch(SUNContext ctx)
{
  const double t1 = 0.05, t2 = 0.1;
  LGNGroup G1 = LGNGroup_R3xSO3(), G2 = LGNGroup_SE3(), G2z = FreshGroup(LGNGroup_SE3());
  Run x, z;
  double t = 0.0;
  long int nst = 0;
  int flag;

  flag = RunCreate(&x, ctx, G1, 0, &body_a, ForceR3xSO3);
  if (!flag) flag = LGNInit(x.mem, 0.0, x.q, x.v);
  if (!flag) flag = LGNSolve(x.mem, t1, &t, x.q, x.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "first solve on R^3 x SO(3): %s", LGNGetReturnFlagName(flag));
  /* the same (q, v), read on SE(3) from now on, with SE(3)'s forces */
  flag = LGNSetGroup(x.mem, G2);
  if (!flag) flag = LGNSetForceFn(x.mem, ForceSE3);
  CHECK(flag == LGN_SUCCESS, "LGNSetGroup to SE(3) after a solve: %s",
        LGNGetReturnFlagName(flag));
  LGNGroup_Destroy(G1); /* the integrator must not hold on to it */

  flag = RunCreate(&z, ctx, G2z, 0, &body_a, ForceSE3);
  N_VScale(1.0, x.q, z.q);
  N_VScale(1.0, x.v, z.v);
  if (!flag) flag = LGNInit(z.mem, t1, z.q, z.v);
  if (!flag) flag = LGNSolve(z.mem, t2, &t, z.q, z.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "fresh SE(3) integrator: %s", LGNGetReturnFlagName(flag));

  flag = LGNSolve(x.mem, t2, &t, x.q, x.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "continued on SE(3): %s", LGNGetReturnFlagName(flag));
  LGNGetNumSteps(x.mem, &nst);
  CHECK(nst == 100, "steps after the switch: %ld, expected 100", nst);
  CHECK(SameBits(x.q, z.q) && SameBits(x.v, z.v),
        "after LGNSetGroup the run equals a fresh SE(3) run bit for bit "
        "(max |dq| = %.3g, |dv| = %.3g)", MaxDiff(x.q, z.q), MaxDiff(x.v, z.v));
  RunFree(&x);
  RunFree(&z);
  LGNGroup_Destroy(G2);
  LGNGroup_Destroy(G2z);
}

/* (b) one setter after a solve, against a fresh integrator with it. */
typedef int (*Change)(void *mem);

static int ChangeGenAlpha(void *mem) { return LGNSetGenAlpha(mem, 0.5); }
static int ChangeNewmark(void *mem) { return LGNSetNewmark(mem, 0.3025, 0.6); }
static int ChangeSimplified(void *mem) { return LGNSetKinematics(mem, LGN_KINEMATICS_SIMPLIFIED); }
static int ChangeSigma(void *mem) { return LGNSetKinematics(mem, LGN_KINEMATICS_SIGMA); }
static int ChangeIndex2(void *mem) { return LGNSetConstraintIndex(mem, LGN_CONSTR_INDEX2); }
static int ChangeMassFn(void *mem) { return LGNSetMassFn(mem, MassHeavier); }
static int ChangeForceFn(void *mem) { return LGNSetForceFn(mem, ForceDamped); }
static int ChangeUserData(void *mem) { return LGNSetUserData(mem, (void *)&body_b); }
static int ChangeMassConstant(void *mem) { return LGNSetMassConstant(mem, SUNTRUE); }
static int ChangeConstraints(void *mem) { return LGNSetConstraints(mem, 3, Phi, Jac); }

static void SetterAfterSolve(SUNContext ctx, const char *name, Change change,
                             sunbooleantype mass_constant_first)
{
  const double t1 = 0.02, t2 = 0.04;
  LGNGroup G = LGNGroup_R3xSO3(), Gz = FreshGroup(LGNGroup_R3xSO3());
  N_Vector vdot = N_VNew_Serial(6, ctx), lambda = N_VNew_Serial(3, ctx);
  N_Vector a = N_VNew_Serial(6, ctx);
  Run x, z;
  double t = 0.0;
  long int setups_before = 0, setups_after = 0;
  int flag;

  flag = RunCreate(&x, ctx, G, 1, &body_a, ForceR3xSO3);
  if (!flag && mass_constant_first) flag = LGNSetMassConstant(x.mem, SUNTRUE);
  if (!flag) flag = LGNInit(x.mem, 0.0, x.q, x.v);
  if (!flag) flag = LGNSolve(x.mem, t1, &t, x.q, x.v, LGN_NORMAL);
  if (!flag) flag = LGNGetAcceleration(x.mem, vdot);
  if (!flag) flag = LGNGetMultipliers(x.mem, lambda);
  if (!flag) flag = LGNGetAuxAcceleration(x.mem, a);
  if (!flag) flag = change(x.mem);
  if (!flag) flag = LGNGetNumLinSolvSetups(x.mem, &setups_before);
  CHECK(flag == LGN_SUCCESS, "%s: first solve and the change: %s", name,
        LGNGetReturnFlagName(flag));

  flag = RunCreate(&z, ctx, Gz, 1, &body_a, ForceR3xSO3);
  if (!flag && mass_constant_first) flag = LGNSetMassConstant(z.mem, SUNTRUE);
  if (!flag) flag = change(z.mem);
  N_VScale(1.0, x.q, z.q);
  N_VScale(1.0, x.v, z.v);
  if (!flag) flag = LGNInit(z.mem, t1, z.q, z.v);
  if (!flag) flag = LGNSetInitialAcceleration(z.mem, vdot, lambda);
  if (!flag) flag = LGNSetInitialAux(z.mem, a);
  if (!flag) flag = LGNSolve(z.mem, t2, &t, z.q, z.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "%s: fresh integrator: %s", name, LGNGetReturnFlagName(flag));

  flag = LGNSolve(x.mem, t2, &t, x.q, x.v, LGN_ONE_STEP);
  if (!flag) flag = LGNGetNumLinSolvSetups(x.mem, &setups_after);
  CHECK(flag == LGN_SUCCESS && setups_after > setups_before,
        "%s: the first step after the change sets a new matrix up (%ld -> %ld)",
        name, setups_before, setups_after);
  if (!flag) flag = LGNSolve(x.mem, t2, &t, x.q, x.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "%s: continued: %s", name, LGNGetReturnFlagName(flag));
  CHECK(SameBits(x.q, z.q) && SameBits(x.v, z.v),
        "%s: the continuation equals a fresh integrator bit for bit "
        "(max |dq| = %.3g, |dv| = %.3g)", name, MaxDiff(x.q, z.q), MaxDiff(x.v, z.v));
  RunFree(&x);
  RunFree(&z);
  N_VDestroy(vdot);
  N_VDestroy(lambda);
  N_VDestroy(a);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(Gz);
}

int main(void)
{
  SUNContext ctx = NULL;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  GroupSwitch(ctx);
  SetterAfterSolve(ctx, "LGNSetGenAlpha", ChangeGenAlpha, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetNewmark", ChangeNewmark, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetKinematics(simplified)", ChangeSimplified, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetKinematics(sigma)", ChangeSigma, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetConstraintIndex(2)", ChangeIndex2, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetMassFn", ChangeMassFn, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetMassFn with a constant mass", ChangeMassFn, SUNTRUE);
  SetterAfterSolve(ctx, "LGNSetForceFn", ChangeForceFn, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetUserData", ChangeUserData, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetUserData with a constant mass", ChangeUserData, SUNTRUE);
  SetterAfterSolve(ctx, "LGNSetMassConstant", ChangeMassConstant, SUNFALSE);
  SetterAfterSolve(ctx, "LGNSetConstraints (same m)", ChangeConstraints, SUNFALSE);
  SUNContext_Free(&ctx);
  return test_summary("test_setters_after_solve");
}
