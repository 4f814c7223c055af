/* -----------------------------------------------------------------------------
 * Lignum tutorial: a double spherical pendulum (doc/tutorial.md explains
 * every step of this file).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Two equal rods (mass 1 kg, length 1 m, radius 0.05 m), each a rigid body
 * on R^3 x SO(3), hang under gravity 9.81 m/s^2 along -z: rod 0 from the
 * origin by a spherical joint at its end, rod 1 from the free end of rod 0
 * by a second spherical joint. They start horizontal along x, spinning
 * about their own axes, so the gyroscopic terms matter.
 *
 * The bodies (lignum_bodies.h) and the joints (lignum_joints.h) make a
 * model (lignum_model.h), which gives Lignum M, g, K_t, C_t, Phi, B and the
 * curvature in one call; LGNCalcIC makes the start consistent. Integrated with
 * mod. LGGalpha (generalized-alpha, rho_inf = 0.9, exact kinematics, index
 * 3) with error control (rtol = atol = 1e-6) to t = 2 s. Output every
 * 0.2 s: time, the centre of rod 1, the energy, its relative drift and
 * |Phi|; then the statistics.
 *
 * Checks (exit status 1 on failure): the relative energy drift stays below
 * 1e-3 (the joints do no work, so only the method changes the energy) and
 * |Phi|_inf below 1e-6 m at every output (between the steps of error
 * control the output is interpolated, accurate to the tolerances).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>        /* the integrator                       */
#include <lignum/lignum_bodies.h> /* rigid bodies: M, g, K_t, C_t, energy */
#include <lignum/lignum_joints.h> /* joints: Phi, B, curvature, K_t       */
#include <lignum/lignum_model.h>  /* bodies + joints: every callback      */
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* ---- Step 11: one line of output -------------------------------------------
 * the centre x_1 of rod 1, the energy E, its drift since E0 and |Phi|_inf */
static int PrintOutput(LGNModel model, sunrealtype t, N_Vector q, N_Vector v, N_Vector phi,
                       sunrealtype E0, sunrealtype *drift, sunrealtype *phimax)
{
  const sunrealtype *qd = N_VGetArrayPointer(q);
  sunrealtype kin, pot, E, err;
  int flag = LGNBodies_Energy(LGNModel_GetBodies(model), q, v, &kin, &pot);
  if (!flag) flag = LGNJoints_Residual(LGNModel_GetJoints(model), t, q, phi);
  if (flag) return flag;
  E       = kin + pot;
  err     = N_VMaxNorm(phi);
  *drift  = fmax(*drift, fabs(E - E0) / fabs(E0));
  *phimax = fmax(*phimax, err);
  printf("%5.2f %10.6f %10.6f %10.6f %12.8f %10.2e %9.1e\n", t, qd[7], qd[8], qd[9], E,
         (E - E0) / fabs(E0), err);
  return 0;
}

int main(void)
{
  /* Step 1: the data: two solid cylinders along their body x axis (SI) */
  const sunrealtype mass = 1.0, len = 1.0, rad = 0.05;
  const sunrealtype J[3] = {0.5 * mass * rad * rad, mass * (3.0 * rad * rad + len * len) / 12.0,
                            mass * (3.0 * rad * rad + len * len) / 12.0};
  const sunrealtype gravity[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3]  = {0.0, 0.0, 0.0};
  const sunrealtype end_a[3]   = {-0.5 * len, 0.0, 0.0}; /* joint end (body frame) */
  const sunrealtype end_b[3]   = {0.5 * len, 0.0, 0.0};  /* free end (body frame)  */
  const sunrealtype omega0[3]  = {20.0, 0.0, 3.0};       /* rod 0: Omega (body)    */
  const sunrealtype omega1[3]  = {-15.0, 0.0, 6.0};      /* rod 1: Omega (body)    */
  const sunrealtype rtol = 1e-6, atol = 1e-6, dt_out = 0.2;
  const sunrealtype drift_bound = 1e-3, phi_bound = 1e-6;
  const int nout = 10;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[2];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel model   = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, tmpl = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunindextype nv, m = 0;
  sunrealtype *qd, *vd, kin, pot, E0, t = 0.0, drift = 0.0, phimax = 0.0;
  int i, k, flag;

  /* Step 2: the configuration group, R^3 x SO(3) for each rod */
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body       = LGNGroup_R3xSO3();
  factors[0] = factors[1] = body;
  G          = LGNGroup_Product(2, factors); /* nq = 14, nv = 12 */
  if (body == NULL || G == NULL) return 1;
  nv = G->nv;

  /* Step 3: the bodies: mass, inertia, gravity (M, g, K_t, C_t, energy) */
  bodies = LGNBodies_Create(G);
  flag = LGNBodies_SetPrincipalInertia(bodies, 0, mass, J);
  if (!flag) flag = LGNBodies_SetPrincipalInertia(bodies, 1, mass, J);
  if (!flag) flag = LGNBodies_SetGravity(bodies, gravity);

  /* Step 4: the joints: ground - rod 0 and rod 0 - rod 1 (Phi, B, Z) */
  joints = LGNJoints_Create(G);
  if (!flag) flag = LGNJoints_AddSpherical(joints, LGN_GROUND, origin, 0, end_a);
  if (!flag) flag = LGNJoints_AddSpherical(joints, 0, end_b, 1, end_a);
  if (!flag) m = LGNJoints_NumConstraints(joints); /* 3 + 3 = 6 */

  /* Step 5: the model: both sets, installed on the integrator in Step 7 */
  model = LGNModel_Create(bodies, joints);
  if (model == NULL) return 1;

  /* Step 6: the initial state: both rods along x (R = I), spinning */
  q   = N_VNew_Serial(G->nq, ctx);
  v   = N_VNew_Serial(nv, ctx);
  phi = N_VNew_Serial(m, ctx);
  qd  = N_VGetArrayPointer(q);
  vd  = N_VGetArrayPointer(v);
  LGNGroup_Identity(G, qd); /* x_b = 0, p_b = (1, 0, 0, 0) */
  qd[0] = 0.5 * len;        /* x_0 = (L/2, 0, 0)  */
  qd[7] = 1.5 * len;        /* x_1 = (3L/2, 0, 0) */
  N_VConst(0.0, v);         /* u_0 = u_1 = 0      */
  for (i = 0; i < 3; i++) {
    vd[3 + i] = omega0[i];
    vd[9 + i] = omega1[i];
  }

  /* Step 7: the integrator and the model */
  mem = LGNCreate(ctx);
  if (mem == NULL) return 1;
  if (!flag) flag = LGNModel_Attach(model, mem); /* group and every callback */
  if (!flag) flag = LGNInit(mem, 0.0, q, v);

  /* Step 8: the linear solver for the (nv + m) x (nv + m) iteration matrix */
  tmpl = N_VNew_Serial(nv + m, ctx);
  A    = SUNDenseMatrix(nv + m, nv + m, ctx);
  LS   = LGNLinSol_Dense(tmpl, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);

  /* Step 9: the method, mod. LGGalpha at index 3, with error control */
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, rtol, atol);

  /* Step 10: consistent initial values: project q_0, then v_0 */
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
  if (!flag) flag = LGNGetConsistentIC(mem, q, v);
  if (!flag) flag = LGNBodies_Energy(bodies, q, v, &kin, &pot);
  if (flag) {
    fprintf(stderr, "set-up failed: %s\n", LGNGetReturnFlagName(flag));
    return 1;
  }

  /* Step 11: the time loop, with outputs every dt_out */
  E0 = kin + pot;
  printf("Double spherical pendulum: mod. LGGalpha(0.9), index 3, rtol = atol = %.0e\n\n", rtol);
  printf("%5s %10s %10s %10s %12s %10s %9s\n", "t", "x_1", "y_1", "z_1", "energy", "drift",
         "|Phi|");
  flag = PrintOutput(model, t, q, v, phi, E0, &drift, &phimax);
  for (k = 1; k <= nout && flag == 0; k++) {
    flag = LGNSolve(mem, k * dt_out, &t, q, v, LGN_NORMAL);
    if (flag == 0) flag = PrintOutput(model, t, q, v, phi, E0, &drift, &phimax);
  }
  if (flag) fprintf(stderr, "failed at t = %g: %s\n", t, LGNGetReturnFlagName(flag));

  /* Step 12: the statistics */
  printf("\n");
  LGNPrintAllStats(mem, stdout, SUN_OUTPUTFORMAT_TABLE);
  printf("\nmax relative energy drift %.1e (bound %.0e), max |Phi| %.1e m (bound %.0e)\n", drift,
         drift_bound, phimax, phi_bound);

  /* Step 13: free what we created, in reverse order */
  LGNFree(&mem); /* first: it uses the model */
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(tmpl);
  N_VDestroy(phi);
  N_VDestroy(v);
  N_VDestroy(q);
  LGNModel_Destroy(&model);
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);

  if (flag || !(drift < drift_bound) || !(phimax < phi_bound)) {
    printf("tutorial_double_pendulum: FAILED\n");
    return 1;
  }
  printf("tutorial_double_pendulum: OK\n");
  return 0;
}
