/* -----------------------------------------------------------------------------
 * Lignum teaching example: the heavy top with error control.
 *
 * Shows: a constrained rigid body written with the body and joint helpers
 * (lignum_bodies.h, lignum_joints.h), installed as a model object
 * (lignum_model.h), and adaptive steps (LGN_STEP_ADAPTIVE
 * with LGNSStolerances).
 *
 * Model (Brüls and Cardona's heavy top): one body on R^3 x SO(3),
 * q = (x, p), v = (u inertial, Omega body), mass 15, principal inertia
 * diag(0.234375, 0.46875, 0.234375) about the centre of mass, which sits at
 * X = (0, 1, 0) in the body frame; a spherical joint holds the body point
 * -X at the inertial origin (3 constraints, index 3). Gravity (0, 0, -9.81).
 * Initially R = I, Omega = (0, 150, -4.61538), u = R (Omega x X).
 *
 *   M = diag(m I, J),  g = (-m gvec, Omega x J Omega),  Phi = x - R X
 *
 * all from the helpers: LGNModel_Attach gives Lignum every callback.
 * Output: t, the centre of mass x, the energy and |Phi|_2 every 0.1 s, then
 * the step statistics. With error control LGNSolve (LGN_NORMAL) returns the
 * dense output at tout, interpolated inside a step, projected onto the
 * constraints (LGNSetProjectOutputs): |Phi| is at round-off there too (the
 * interpolant itself is off by about the tolerances, 1e-6).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  sunrealtype kin, pot;
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  printf("%5.2f %12.6f %12.6f %12.6f %14.6f %10.1e\n", t, NV_Ith_S(q, 0), NV_Ith_S(q, 1),
         NV_Ith_S(q, 2), kin + pot, sqrt(N_VDotProd(phi, phi)));
}

int main(void)
{
  const sunrealtype X[3] = {0.0, 1.0, 0.0}, mX[3] = {0.0, -1.0, 0.0};
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, gvec[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype omega0[3] = {0.0, 150.0, -4.61538};
  const sunrealtype rtol = 1e-6, atol = 1e-6, dtout = 0.1, tend = 1.0;
  SUNContext ctx = NULL;
  LGNGroup G = NULL;
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, *qd, *vd;
  sunindextype m;
  long int nst = 0, nni = 0, netf = 0;
  int flag = 0;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  G = LGNGroup_R3xSO3(); /* q = (x, p): nq = 7, v = (u, Omega): nv = 6 */

  /* the model: one body, gravity, a spherical joint to the ground */
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  flag = LGNBodies_SetPrincipalInertia(bodies, 0, 15.0, J);
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);
  if (!flag) flag = LGNJoints_AddSpherical(joints, LGN_GROUND, origin, 0, mX);
  m = LGNJoints_NumConstraints(joints); /* 3 */

  /* initial state: x = R X = X, p = identity, u = R (Omega x X) */
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  phi = N_VNew_Serial(m, ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);
  N_VConst(0.0, q);
  qd[0] = X[0]; qd[1] = X[1]; qd[2] = X[2];
  qd[3] = 1.0;
  vd[0] = omega0[1] * X[2] - omega0[2] * X[1];
  vd[1] = omega0[2] * X[0] - omega0[0] * X[2];
  vd[2] = omega0[0] * X[1] - omega0[1] * X[0];
  vd[3] = omega0[0]; vd[4] = omega0[1]; vd[5] = omega0[2];

  /* the integrator */
  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);

  /* dense linear solver on the (nv + m) x (nv + m) iteration matrix */
  y = N_VNew_Serial(G->nv + m, ctx);
  A = SUNDenseMatrix(G->nv + m, G->nv + m, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);

  /* generalized-alpha with error control: LGNSetStepSize is the first
   * step tried, the tolerances steer the rest */
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, rtol, atol);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSetMaxNumSteps(mem, 100000);

  printf("Heavy top on R^3 x SO(3), spherical joint, generalized-alpha(0.9),\n");
  printf("error control with rtol = atol = %.0e\n\n", rtol);
  printf("%5s %12s %12s %12s %14s %10s\n", "t", "x", "y", "z", "energy", "|Phi|");
  if (!flag) Print(md, t, q, v, phi);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(md, t, q, v, phi);
  }
  if (flag) fprintf(stderr, "heavy_top: %s\n", LGNGetReturnFlagName(flag));

  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  LGNGetNumErrTestFails(mem, &netf);
  printf("\nsteps = %ld   Newton iterations = %ld   error test failures = %ld\n", nst, nni, netf);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(phi);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNModel_Destroy(&md); /* after LGNFree */
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
