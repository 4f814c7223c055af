/* -----------------------------------------------------------------------------
 * Lignum teaching example: Bricard's mechanism, an overconstrained linkage.
 *
 * Shows: a mechanism with redundant constraints runs as modelled. Five rods
 * (1 m, 1 kg, 0.1 m square section) and the ground form a closed loop of
 * six revolute joints along a skew hexagon of a unit cube's edges,
 *
 *   P0 = (0,0,0) -> P1 = (1,0,0) -> P2 = (1,1,0) -> P3 = (1,1,1)
 *      -> P4 = (0,1,1) -> P5 = (0,0,1) -> (ground) -> P0,
 *
 * each joint's axis normal to both rods it joins. Grübler's count gives
 * 6 x 5 - 6 x 5 = 0 degrees of freedom, yet the mechanism moves: of the
 * 30 constraint rows only 29 are independent (B has rank 29). Lignum
 * finds this at the start (a QR factorisation with column pivoting of B^T),
 * leaves one row out with a warning (LGNSetRedundantConstraints), checks
 * it after every step, and returns zero for its multiplier. The linear
 * solver is created for all 30 rows as usual.
 *
 * Released from rest under gravity (0, -9.81, 0); BDF with error control
 * (rtol = atol = 1e-10), t in [0, 10]. Output: t, the corner P3 (x, y, z),
 * the energy, the largest |Phi| of all 30 rows; then the row left out.
 * Option --quick: t in [0, 1] (for valgrind).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* The warning names the row left out: printed to stdout. */
static void Handler(int code, const char *module, const char *func, const char *msg, void *d)
{
  (void)module; (void)d;
  printf("%s %s: %s\n\n", code == LGN_WARNING ? "warning from" : "error in", func, msg);
}

/* P3: the end (0, 0, 1/2) of rod 2, which runs along z. */
static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  const sunrealtype *q2 = N_VGetArrayPointer(q) + 14;
  sunrealtype R[9], kin, pot;
  LGNQuaternionToRotation(q2 + 3, R);
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  printf("%5.1f %10.6f %10.6f %10.6f %14.8f %10.1e\n", t, q2[0] + 0.5 * R[2],
         q2[1] + 0.5 * R[5], q2[2] + 0.5 * R[8], kin + pot, N_VMaxNorm(phi));
}

int main(int argc, char **argv)
{
  static const sunrealtype P[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                      {1, 1, 1}, {0, 1, 1}, {0, 0, 1}};
  static const sunrealtype axis[6][3] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0},
                                         {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
  static const int along[5] = {0, 1, 2, 0, 1}; /* rod k runs along x, y or z */
  const int quick = (argc > 1 && !strcmp(argv[1], "--quick")); /* t in [0, 1] */
  const sunrealtype gvec[3] = {0.0, -9.81, 0.0}, tol = 1e-10, tend = quick ? 1.0 : 10.0;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[5];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, lambda = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, x[5][3], sa[3], sb[3], *qd;
  sunindextype m, n, nred = 0, rows[30];
  long int nst = 0;
  int flag = 0, k, i;
  char what[160];

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R3xSO3();
  for (k = 0; k < 5; k++) factors[k] = body;
  G = LGNGroup_Product(5, factors);
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  q  = N_VNew_Serial(G->nq, ctx);
  v  = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(q);
  N_VConst(0.0, v);

  /* rods at the edges' midpoints, body axes = inertial axes */
  for (k = 0; !flag && k < 5; k++) {
    sunrealtype J[3] = {(1.0 + 0.01) / 12.0, (1.0 + 0.01) / 12.0, (1.0 + 0.01) / 12.0};
    J[along[k]] = 0.02 / 12.0; /* about the rod's own axis */
    for (i = 0; i < 3; i++) x[k][i] = 0.5 * (P[k][i] + P[k + 1][i]);
    qd[7 * k] = x[k][0]; qd[7 * k + 1] = x[k][1]; qd[7 * k + 2] = x[k][2];
    qd[7 * k + 3] = 1.0; qd[7 * k + 4] = qd[7 * k + 5] = qd[7 * k + 6] = 0.0;
    flag = LGNBodies_SetPrincipalInertia(bodies, k, 1.0, J);
  }
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);

  /* six revolute joints: ground-rod 0 at P0, rod k-1 - rod k at Pk, rod 4 - ground at P5 */
  for (i = 0; i < 3; i++) sb[i] = P[0][i] - x[0][i];
  if (!flag) flag = LGNJoints_AddRevolute(joints, LGN_GROUND, P[0], axis[0], 0, sb, axis[0]);
  for (k = 1; !flag && k < 5; k++) {
    for (i = 0; i < 3; i++) { sa[i] = P[k][i] - x[k - 1][i]; sb[i] = P[k][i] - x[k][i]; }
    flag = LGNJoints_AddRevolute(joints, k - 1, sa, axis[k], k, sb, axis[k]);
  }
  for (i = 0; i < 3; i++) sa[i] = P[5][i] - x[4][i];
  if (!flag) flag = LGNJoints_AddRevolute(joints, 4, sa, axis[5], LGN_GROUND, P[5], axis[5]);
  m      = LGNJoints_NumConstraints(joints); /* 30 */
  n      = G->nv + m;                           /* the solver: all 30 rows */
  phi    = N_VNew_Serial(m, ctx);
  lambda = N_VNew_Serial(m, ctx);

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNSetErrHandlerFn(mem, Handler, NULL);
  /* the default, written out: leave dependent rows out (with a warning) */
  if (!flag) flag = LGNSetRedundantConstraints(mem, LGN_REDUNDANT_ELIMINATE);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y  = N_VNew_Serial(n, ctx);
  A  = SUNDenseMatrix(n, n, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetBDF(mem, 5);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);

  printf("Bricard's mechanism: 5 rods on 6 revolute joints, %ld constraint rows,\n", (long)m);
  printf("BDF with error control, rtol = atol = %.0e\n\n", tol);
  for (tout = 1.0; !flag && tout <= tend + 0.5; tout += 1.0) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag && tout == 1.0) /* after the warning */
      printf("%5s %10s %10s %10s %14s %10s\n", "t", "P3_x", "P3_y", "P3_z", "energy",
             "max|Phi|");
    if (!flag) Print(md, t, q, v, phi);
  }
  if (flag) fprintf(stderr, "bricard: %s\n", LGNGetReturnFlagName(flag));

  /* the row left out, by joint, and its multiplier */
  if (!flag) flag = LGNGetRedundantConstraints(mem, &nred, rows);
  if (!flag) flag = LGNGetMultipliers(mem, lambda);
  for (k = 0; !flag && k < (int)nred; k++) {
    LGNJoints_DescribeConstraint(joints, rows[k], what, sizeof what);
    printf("\nrow %ld left out (%s), multiplier %g\n", (long)rows[k], what,
           (double)N_VGetArrayPointer(lambda)[rows[k]]);
  }
  LGNGetNumSteps(mem, &nst);
  printf("steps: %ld\n", nst);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(phi);
  N_VDestroy(lambda);
  LGNModel_Destroy(&md); /* after LGNFree */
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
