/* -----------------------------------------------------------------------------
 * Lignum teaching example: a chain of N bodies with the sparse solver KLU.
 *
 * Shows: a large model with sparse matrices. The iteration matrix is a
 * SUNSparseMatrix in CSC format solved by SUNLinSol_KLU (AMD ordering), and
 * every sparse callback comes from the helpers: the mass matrix and the
 * damping from the body set (lignum_bodies.h), the constraints, their
 * Jacobian B, B^T lambda, the curvature and the geometric stiffness from
 * the joint set (lignum_joints.h). Each writes its own fixed pattern into
 * the sparse matrix Lignum hands it.
 *
 * Model: N = 10 slender bodies (length 1, mass 1, radius 0.02) on
 * (R^3 x SO(3))^N, initially in a horizontal line along x, released at
 * rest under gravity (0, 0, -9.81). A spherical joint holds the first body
 * at the origin, others join neighbours end to end (3N constraints).
 * On R^3 x SO(3) without springs g depends on q not at all, so K_t is the
 * joints' part alone (with force elements one would add LGNBodies_Stiffness
 * into a second sparse matrix and SUNMatScaleAdd them).
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
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#define NBODIES 10

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

/* sparse M, overwritten with the pattern of LGNBodies_MassNnz */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}

/* sparse C = dg/dv (the gyroscopic terms) */
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Model *)ud)->bodies);
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}

/* sparse B, overwritten with the pattern of LGNJoints_JacobianNnz */
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}

/* B^T lambda without forming B: the residual needs no Jacobian */
static int ConstrForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  return LGNJoints_ConstraintForce(((Model *)ud)->joints, t, q, lambda, f) ? -1 : 0;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}

/* sparse K_t = d/dq (B^T lambda) (the bodies add nothing here, see above) */
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K, void *ud)
{
  (void)v; (void)vdot;
  return LGNJoints_Stiffness(((Model *)ud)->joints, t, q, lambda, K) ? -1 : 0;
}

static void Print(Model *md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  const sunrealtype *x = N_VGetArrayPointer(q) + 7 * (NBODIES - 1); /* last body */
  sunrealtype R[9], end[3], kin, pot;
  int i;
  LGNQuaternionToRotation(x + 3, R);
  for (i = 0; i < 3; i++) end[i] = x[i] + 0.5 * R[3 * i]; /* x + R (L/2, 0, 0) */
  LGNBodies_Energy(md->bodies, q, v, &kin, &pot);
  LGNJoints_Residual(md->joints, t, q, phi);
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
  Model md = {NULL, NULL};
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

  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  flag = LGNBodies_SetGravity(md.bodies, gvec);
  for (k = 0; k < NBODIES && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, mass, J);
    if (!flag) flag = k == 0 ? LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, left)
                             : LGNJoints_AddSpherical(md.joints, k - 1, right, k, left);
  }
  m = LGNJoints_NumConstraints(md.joints); /* 3 N */
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
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetConstraintForceFn(mem, ConstrForce);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
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
  if (!flag) Print(&md, t, q, v, phi);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(&md, t, q, v, phi);
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
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
