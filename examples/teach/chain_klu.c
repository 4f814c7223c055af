/* -----------------------------------------------------------------------------
 * Lignum teaching example: a chain of N bodies with the sparse solver KLU.
 *
 * Shows: a large model with sparse matrices. The iteration matrix is a
 * SUNSparseMatrix in CSC format solved by SUNLinSol_KLU (AMD ordering), and
 * every sparse callback comes from the model object (lignum_model.h): the
 * mass matrix and the damping from the body set, the constraints, their
 * Jacobian B, the curvature and the geometric stiffness from the joint
 * set; B^T lambda (LGNJoints_ConstraintForce) is added as one more
 * callback. Each helper adds its term, with its fixed pattern, to the
 * sparse matrix Lignum hands it, as it would to a dense one.
 *
 * Model: N = 10 slender bodies (length 1, mass 1, radius 0.02) on
 * (R^3 x SO(3))^N, initially in a horizontal line along x, released at
 * rest under gravity (0, 0, -9.81). A spherical joint holds the first body
 * at the origin, others join neighbours end to end (3N constraints).
 * Generalized-alpha (rho_inf = 0.9), index 3, fixed h = 1e-3, t in [0, 1].
 *
 * Output: t, the free end's position, the energy and |Phi|_2.
 * Needs Lignum built with KLU (LGN_HAVE_KLU).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#define NBODIES 10

/* B^T lambda without forming B (LGNSetConstraintForceFn): the model is the
 * user data of every callback set on the integrator */
static int ConstrForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  return LGNJoints_ConstraintForce(LGNModel_GetJoints((LGNModel)ud), t, q, lambda, f) ? -1 : 0;
}

static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  const sunrealtype *x = N_VGetArrayPointer(q) + 7 * (NBODIES - 1); /* last body */
  sunrealtype R[9], end[3], kin, pot;
  int i;
  LGNQuaternionToRotation(x + 3, R);
  for (i = 0; i < 3; i++) end[i] = x[i] + 0.5 * R[3 * i]; /* x + R (L/2, 0, 0) */
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  printf("%5.2f %12.6f %12.6f %12.6f %14.8f %10.1e\n", t, end[0], end[1], end[2], kin + pot,
         sqrt(N_VDotProd(phi, phi)));
}

int main(void)
{
  const sunrealtype L = 1.0, mass = 1.0, radius = 0.02, h = 1e-3, dtout = 0.2, tend = 1.0;
  const sunrealtype J[3] = {0.5 * mass * radius * radius, mass * L * L / 12.0, mass * L * L / 12.0};
  const sunrealtype gvec[3] = {0.0, 0.0, -9.81}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype left[3] = {-0.5 * L, 0.0, 0.0}, right[3] = {0.5 * L, 0.0, 0.0};
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[NBODIES];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, *qd;
  sunindextype m, n;
  long int nst = 0, nni = 0, nnz = 0;
  int flag = 0, k;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  /* (R^3 x SO(3))^N: one factor, referenced N times */
  body = LGNGroup_R3xSO3();
  for (k = 0; k < NBODIES; k++) factors[k] = body;
  G = LGNGroup_Product(NBODIES, factors);

  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  flag = LGNBodies_SetGravity(bodies, gvec);
  for (k = 0; k < NBODIES && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(bodies, k, mass, J);
    if (!flag) flag = k == 0 ? LGNJoints_AddSpherical(joints, LGN_GROUND, origin, 0, left)
                             : LGNJoints_AddSpherical(joints, k - 1, right, k, left);
  }
  m = LGNJoints_NumConstraints(joints); /* 3 N */
  n = G->nv + m;

  /* bodies along x, R = I, at rest */
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  phi = N_VNew_Serial(m, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < NBODIES; k++) {
    qd[7 * k] = (k + 0.5) * L;
    qd[7 * k + 3] = 1.0;
  }

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNSetConstraintForceFn(mem, ConstrForce);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);

  /* KLU on a CSC matrix of size nv + m; Lignum sizes its nnz */
  y = N_VNew_Serial(n, ctx);
  A = SUNSparseMatrix(n, n, 1, CSC_MAT, ctx);
  LS = SUNLinSol_KLU(y, A, ctx);
  if (LS == NULL || SUNLinSol_KLUSetOrdering(LS, 0) != 0) flag = -1; /* AMD */
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, h);

  printf("Chain of %d bodies, spherical joints, KLU (CSC, AMD), generalized-alpha(0.9), "
         "h = %.0e\n\n", NBODIES, h);
  printf("%5s %12s %12s %12s %14s %10s\n", "t", "x_end", "y_end", "z_end", "energy", "|Phi|");
  if (!flag) Print(md, t, q, v, phi);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(md, t, q, v, phi);
  }
  if (flag) fprintf(stderr, "chain_klu: %s\n", LGNGetReturnFlagName(flag));

  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  LGNGetIterationMatrixNnz(mem, &nnz);
  printf("\nsteps = %ld   Newton iterations = %ld   nnz(A) = %ld\n", nst, nni, nnz);

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
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
