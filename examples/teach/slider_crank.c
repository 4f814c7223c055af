/* -----------------------------------------------------------------------------
 * Lignum teaching example: a slider-crank with a prismatic joint and a spring.
 *
 * Shows: LGNJoints_AddPrismatic (a body sliding along a fixed line, its
 * rotation locked) and a force element (LGNBodies_AddSpringDamper), whose
 * stiffness joins the joints' in K_t.
 *
 * Model, three bodies on (R^3 x SO(3))^3 moving in the x-y plane:
 *   crank  (length 1, mass 1)  revolute about z at the origin    5 rows
 *   rod    (length 3, mass 3)  spherical to the crank tip        3 rows
 *          universal to the slider: rod z axis perpendicular
 *          to the slider's y axis (this keeps the rod from
 *          spinning about itself)                                4 rows
 *   slider (mass 2)            prismatic along x through the
 *                              origin, body frame = inertial     5 rows
 * 17 rows, 18 velocities: one degree of freedom. A spring (k = 50, rest
 * length 2, no damping) pulls the slider towards the point (6, 0, 0);
 * gravity (0, -9.81, 0). The crank starts at 45 degrees turning at 5 rad/s;
 * LGNCalcIC (LGN_IC_PROJECT_V) gives the other bodies consistent velocities.
 * Generalized-alpha (rho_inf = 0.9), index 3, fixed h = 1e-3, t in [0, 2].
 *
 * Output: t, the crank tip (x, y), the slider's position and velocity along
 * x, the energy (kinetic + gravity + spring) and |Phi|.
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

/* Body k at centre c, turned by angle a about z. */
static void Place(sunrealtype *q, int k, const sunrealtype c[3], sunrealtype a)
{
  sunrealtype *qk = q + 7 * k;
  qk[0] = c[0]; qk[1] = c[1]; qk[2] = c[2];
  qk[3] = cos(0.5 * a); qk[4] = 0.0; qk[5] = 0.0; qk[6] = sin(0.5 * a);
}

static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  const sunrealtype *qd = N_VGetArrayPointer(q);
  sunrealtype R[9], kin, pot;
  LGNQuaternionToRotation(qd + 3, R);
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  printf("%5.2f %10.6f %10.6f %10.6f %11.6f %14.8f %10.1e\n", t,
         qd[0] + 0.5 * R[0], qd[1] + 0.5 * R[3], /* crank tip x + R (1/2, 0, 0) */
         qd[14], NV_Ith_S(v, 12), kin + pot, sqrt(N_VDotProd(phi, phi)));
}

int main(void)
{
  const sunrealtype L1 = 1.0, L2 = 3.0, pi = acos(-1.0), omega = 5.0;
  const sunrealtype o[3] = {0.0, 0.0, 0.0}, ex[3] = {1.0, 0.0, 0.0};
  const sunrealtype ey[3] = {0.0, 1.0, 0.0}, ez[3] = {0.0, 0.0, 1.0};
  const sunrealtype crank_lo[3] = {-0.5 * L1, 0.0, 0.0}, crank_hi[3] = {0.5 * L1, 0.0, 0.0};
  const sunrealtype rod_lo[3] = {-0.5 * L2, 0.0, 0.0}, rod_hi[3] = {0.5 * L2, 0.0, 0.0};
  const sunrealtype anchor[3] = {6.0, 0.0, 0.0}, gvec[3] = {0.0, -9.81, 0.0};
  const sunrealtype Jc[3] = {1e-3, L1 * L1 / 12.0, L1 * L1 / 12.0};
  const sunrealtype Jr[3] = {3e-3, 3.0 * L2 * L2 / 12.0, 3.0 * L2 * L2 / 12.0};
  const sunrealtype Js[3] = {0.1, 0.1, 0.1};
  const sunrealtype h = 1e-3, dtout = 0.25, tend = 2.0;
  sunrealtype a = 0.25 * pi, B[3], C[3], c[3];
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[3];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, *qd, *vd;
  sunindextype m, n;
  long int nst = 0, nni = 0;
  int flag = 0;

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

  /* geometry: crank tip B at 45 degrees, slider C on the x axis */
  B[0] = L1 * cos(a); B[1] = L1 * sin(a); B[2] = 0.0;
  C[0] = B[0] + sqrt(L2 * L2 - B[1] * B[1]); C[1] = 0.0; C[2] = 0.0;
  c[0] = 0.5 * B[0]; c[1] = 0.5 * B[1]; c[2] = 0.0;
  Place(qd, 0, c, a);
  c[0] = 0.5 * (B[0] + C[0]); c[1] = 0.5 * B[1];
  Place(qd, 1, c, atan2(C[1] - B[1], C[0] - B[0]));
  Place(qd, 2, C, 0.0);

  flag = LGNBodies_SetPrincipalInertia(bodies, 0, 1.0, Jc);
  if (!flag) flag = LGNBodies_SetPrincipalInertia(bodies, 1, 3.0, Jr);
  if (!flag) flag = LGNBodies_SetPrincipalInertia(bodies, 2, 2.0, Js);
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);
  if (!flag) flag = LGNBodies_AddSpringDamper(bodies, LGN_GROUND, anchor, 2, o, 50.0, 0.0, 2.0);

  if (!flag) flag = LGNJoints_AddRevolute(joints, LGN_GROUND, o, ez, 0, crank_lo, ez);
  if (!flag) flag = LGNJoints_AddSpherical(joints, 0, crank_hi, 1, rod_lo);
  if (!flag) flag = LGNJoints_AddUniversal(joints, 1, rod_hi, ez, 2, o, ey);
  if (!flag) flag = LGNJoints_AddPrismatic(joints, LGN_GROUND, o, ex, 2, o, ex);
  m = LGNJoints_NumConstraints(joints);
  n = G->nv + m;
  phi = N_VNew_Serial(m, ctx);

  /* the crank turns about the origin; LGNCalcIC does the rest */
  N_VConst(0.0, v);
  vd[0] = -omega * qd[1];
  vd[1] = omega * qd[0];
  vd[5] = omega;

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y = N_VNew_Serial(n, ctx);
  A = SUNDenseMatrix(n, n, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  if (!flag) flag = LGNGetConsistentIC(mem, q, v);

  printf("Slider-crank (revolute, spherical, universal, prismatic), spring on the slider,\n");
  printf("generalized-alpha(0.9), h = %.0e\n\n", h);
  printf("%5s %10s %10s %10s %11s %14s %10s\n", "t", "B_x", "B_y", "x_slider", "u_slider",
         "energy", "|Phi|");
  if (!flag) Print(md, t, q, v, phi);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(md, t, q, v, phi);
  }
  if (flag) fprintf(stderr, "slider_crank: %s\n", LGNGetReturnFlagName(flag));

  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  printf("\nsteps = %ld   Newton iterations = %ld\n", nst, nni);

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
