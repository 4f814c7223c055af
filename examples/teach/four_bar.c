/* -----------------------------------------------------------------------------
 * Lignum teaching example: a spatial four-bar linkage built from joints.
 *
 * Shows: a closed loop made with the joint helpers and consistent initial
 * velocities from LGNCalcIC. Planar four-bars made of four revolute joints
 * are overconstrained in space (20 rows of rank 17: Lignum leaves three out,
 * with a warning, as bricard.c shows); the RSUR linkage below has the same
 * planar motion with exactly as many rows as needed:
 *
 *   ground - crank    revolute about z at A = (0, 0, 0)       5 rows
 *   crank  - coupler  spherical at B                           3 rows
 *   coupler - rocker  universal at C: the coupler's z axis
 *                     perpendicular to the rocker's long axis  4 rows
 *   rocker - ground   revolute about z at D = (3, 0, 0)        5 rows
 *
 * 17 rows for 3 bodies (18 velocities): one degree of freedom. The bodies
 * are slender rods on (R^3 x SO(3))^3 along their body x axes (mass = length,
 * radius 0.05): crank A -> B = (0, 1, 0), coupler B -> C = (3, 2, 0), rocker
 * D -> C; gravity (0, -9.81, 0) in the plane. The crank starts with angular
 * velocity 2 about z, the other bodies at rest: LGNCalcIC (LGN_IC_PROJECT_V)
 * makes the velocities consistent (M-orthogonal projection onto B v = 0).
 * Generalized-alpha (rho_inf = 0.9), index 3, fixed h = 1e-3, t in [0, 2].
 *
 * Output: t, the crank tip B and the rocker tip C (x, y), the energy, |Phi|.
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

/* Rod k of length len: centre c, turned by angle a about z; inertia set. */
static int PlaceRod(LGNModel md, sunrealtype *q, int k, const sunrealtype c[3], sunrealtype a,
                    sunrealtype len)
{
  const sunrealtype r = 0.05, m = len;
  const sunrealtype J[3] = {0.5 * m * r * r, m * len * len / 12.0, m * len * len / 12.0};
  sunrealtype *qk = q + 7 * k;
  qk[0] = c[0]; qk[1] = c[1]; qk[2] = c[2];
  qk[3] = cos(0.5 * a); qk[4] = 0.0; qk[5] = 0.0; qk[6] = sin(0.5 * a);
  return LGNBodies_SetPrincipalInertia(LGNModel_GetBodies(md), k, m, J);
}

/* Tip x + R (len/2, 0, 0) of rod k. */
static void Tip(N_Vector q, int k, sunrealtype len, sunrealtype tip[3])
{
  const sunrealtype *qk = N_VGetArrayPointer(q) + 7 * k;
  sunrealtype R[9];
  int i;
  LGNQuaternionToRotation(qk + 3, R);
  for (i = 0; i < 3; i++) tip[i] = qk[i] + 0.5 * len * R[3 * i];
}

static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi,
                  const sunrealtype len[3])
{
  sunrealtype b[3], c[3], kin, pot;
  Tip(q, 0, len[0], b);
  Tip(q, 2, len[2], c);
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  printf("%5.2f %10.6f %10.6f %10.6f %10.6f %14.8f %10.1e\n", t, b[0], b[1], c[0], c[1],
         kin + pot, sqrt(N_VDotProd(phi, phi)));
}

int main(void)
{
  const sunrealtype A[3] = {0.0, 0.0, 0.0}, D[3] = {3.0, 0.0, 0.0};
  const sunrealtype ez[3] = {0.0, 0.0, 1.0}, ex[3] = {1.0, 0.0, 0.0};
  const sunrealtype gvec[3] = {0.0, -9.81, 0.0}, omega = 2.0;
  const sunrealtype len[3] = {1.0, sqrt(10.0), 2.0}, pi = acos(-1.0);
  const sunrealtype h = 1e-3, dtout = 0.25, tend = 2.0;
  const sunrealtype c0[3] = {0.0, 0.5, 0.0}, c1[3] = {1.5, 1.5, 0.0}, c2[3] = {3.0, 1.0, 0.0};
  sunrealtype lo[3][3], hi[3][3]; /* rod ends (-len/2, 0, 0), (len/2, 0, 0) */
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[3];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL;
  SUNMatrix Amat = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, *qd, *vd;
  sunindextype m, n;
  long int nst = 0, nni = 0;
  int flag = 0, k;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R3xSO3();
  factors[0] = factors[1] = factors[2] = body;
  G = LGNGroup_Product(3, factors);
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);
  for (k = 0; k < 3; k++) {
    lo[k][0] = -0.5 * len[k]; hi[k][0] = 0.5 * len[k];
    lo[k][1] = lo[k][2] = hi[k][1] = hi[k][2] = 0.0;
  }

  /* bodies: crank, coupler, rocker */
  flag = PlaceRod(md, qd, 0, c0, 0.5 * pi, len[0]);
  if (!flag) flag = PlaceRod(md, qd, 1, c1, atan2(1.0, 3.0), len[1]);
  if (!flag) flag = PlaceRod(md, qd, 2, c2, 0.5 * pi, len[2]);
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);

  /* joints: R, S, U, R (17 rows) */
  if (!flag) flag = LGNJoints_AddRevolute(joints, LGN_GROUND, A, ez, 0, lo[0], ez);
  if (!flag) flag = LGNJoints_AddSpherical(joints, 0, hi[0], 1, lo[1]);
  if (!flag) flag = LGNJoints_AddUniversal(joints, 1, hi[1], ez, 2, hi[2], ex);
  if (!flag) flag = LGNJoints_AddRevolute(joints, 2, lo[2], ez, LGN_GROUND, D, ez);
  m = LGNJoints_NumConstraints(joints);
  n = G->nv + m;
  phi = N_VNew_Serial(m, ctx);

  /* velocities: the crank turns about A, the rest at rest (projected below) */
  N_VConst(0.0, v);
  vd[0] = -omega * c0[1]; /* u = omega ez x (c0 - A) */
  vd[1] = omega * c0[0];
  vd[5] = omega;          /* Omega = (0, 0, omega) in body axes */

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y = N_VNew_Serial(n, ctx);
  Amat = SUNDenseMatrix(n, n, ctx);
  LS = LGNLinSol_Dense(y, Amat, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, Amat);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, h);

  /* consistent initial velocities, read back as the start of the table */
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  if (!flag) flag = LGNGetConsistentIC(mem, q, v);

  printf("Spatial four-bar (revolute, spherical, universal, revolute), %ld constraints,\n",
         (long)m);
  printf("generalized-alpha(0.9), h = %.0e\n\n", h);
  printf("%5s %10s %10s %10s %10s %14s %10s\n", "t", "B_x", "B_y", "C_x", "C_y", "energy",
         "|Phi|");
  if (!flag) Print(md, t, q, v, phi, len);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(md, t, q, v, phi, len);
  }
  if (flag) fprintf(stderr, "four_bar: %s\n", LGNGetReturnFlagName(flag));

  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  printf("\nsteps = %ld   Newton iterations = %ld\n", nst, nni);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(Amat);
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
