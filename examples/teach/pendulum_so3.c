/* -----------------------------------------------------------------------------
 * Lignum teaching example: a physical pendulum on SO(3).
 *
 * Shows: the smallest complete Lignum program. One rigid body turns about a
 * fixed pivot, so its configuration is a rotation alone: the group SO(3)
 * (q = unit quaternion, v = Omega, the body angular velocity). There are no
 * constraints: the pivot is built into the equations of motion,
 *
 *   J_O Omegadot + Omega x J_O Omega - s x (R^T m gvec) = 0,
 *
 * with J_O the inertia about the pivot (body axes), s the centre of mass
 * (body frame, the pivot at the origin) and gvec gravity. Lignum's force g
 * holds everything but the inertia term: g = Omega x J_O Omega - torque.
 * Generalized-alpha (rho_inf = 0.9), fixed step h = 1e-3, t in [0, 2].
 *
 * Output: t, the centre of mass R s (inertial), |Omega| and the energy
 *   E = Omega . J_O Omega / 2 - m gvec . (R s),
 * which the method conserves up to its small numerical dissipation.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* Model data: mass, centre of mass, inertia about the pivot, gravity. */
static const sunrealtype MASS = 1.0;
static const sunrealtype S[3] = {0.0, 0.0, -0.5};          /* body frame */
static const sunrealtype JO[3] = {0.35, 0.37, 0.02};       /* principal, about the pivot */
static const sunrealtype GVEC[3] = {0.0, 0.0, -9.81};

/* a x b */
static void Cross(const sunrealtype a[3], const sunrealtype b[3], sunrealtype c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* M = J_O (constant; Lignum zeroes M before the call). */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *user_data)
{
  int i;
  (void)t; (void)q; (void)user_data;
  for (i = 0; i < 3; i++) SM_ELEMENT_D(M, i, i) = JO[i];
  return 0;
}

/* g = Omega x J_O Omega - s x (R^T m gvec). */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *user_data)
{
  const sunrealtype *W = N_VGetArrayPointer(v);
  sunrealtype *gg = N_VGetArrayPointer(g);
  sunrealtype R[9], JW[3], gyro[3], wb[3], torque[3];
  int i;
  (void)t; (void)user_data;
  LGNQuaternionToRotation(N_VGetArrayPointer(q), R); /* row-major R[3i+j] */
  for (i = 0; i < 3; i++) JW[i] = JO[i] * W[i];
  for (i = 0; i < 3; i++) /* body components of the weight: R^T m gvec */
    wb[i] = MASS * (R[i] * GVEC[0] + R[3 + i] * GVEC[1] + R[6 + i] * GVEC[2]);
  Cross(W, JW, gyro);
  Cross(S, wb, torque);
  for (i = 0; i < 3; i++) gg[i] = gyro[i] - torque[i];
  return 0;
}

/* Centre of mass R s and the energy. */
static void Observe(N_Vector q, N_Vector v, sunrealtype x[3], sunrealtype *energy)
{
  const sunrealtype *W = N_VGetArrayPointer(v);
  sunrealtype R[9];
  int i;
  LGNQuaternionToRotation(N_VGetArrayPointer(q), R);
  *energy = 0.0;
  for (i = 0; i < 3; i++) {
    x[i] = R[3 * i] * S[0] + R[3 * i + 1] * S[1] + R[3 * i + 2] * S[2];
    *energy += 0.5 * JO[i] * W[i] * W[i] - MASS * GVEC[i] * x[i];
  }
}

int main(void)
{
  const sunrealtype psi0[3] = {0.6, 0.2, 0.0};   /* R0 = exp(psi0~) */
  const sunrealtype omega0[3] = {0.0, 1.0, 3.0}; /* body angular velocity */
  const sunrealtype h = 1e-3, dtout = 0.25, tend = 2.0;
  SUNContext ctx = NULL;
  LGNGroup G = NULL;
  N_Vector q = NULL, v = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, x[3], energy;
  long int nst = 0, nni = 0;
  int flag, i;

  /* 1. context and group */
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  G = LGNGroup_SO3(); /* nq = 4, nv = 3 */

  /* 2. initial state */
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  LGNQuaternionFromRotationVector(psi0, N_VGetArrayPointer(q));
  for (i = 0; i < 3; i++) NV_Ith_S(v, i) = omega0[i];

  /* 3. integrator memory, model, initial values */
  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);

  /* 4. linear solver: dense, (nv + m) x (nv + m) with m = 0 */
  A = SUNDenseMatrix(G->nv, G->nv, ctx);
  LS = LGNLinSol_Dense(v, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);

  /* 5. method: generalized-alpha, fixed step; stiffness and damping by
   *    difference quotients (no LGNSetStiffnessFn / LGNSetDampingFn) */
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, h);

  /* 6. time loop */
  printf("Physical pendulum on SO(3): generalized-alpha(0.9), h = %.0e\n\n", h);
  printf("%6s %12s %12s %12s %12s %14s\n", "t", "x_cm", "y_cm", "z_cm", "|Omega|", "energy");
  Observe(q, v, x, &energy);
  printf("%6.2f %12.6f %12.6f %12.6f %12.6f %14.8f\n", t, x[0], x[1], x[2],
         sqrt(N_VDotProd(v, v)), energy);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (flag) break;
    Observe(q, v, x, &energy);
    printf("%6.2f %12.6f %12.6f %12.6f %12.6f %14.8f\n", t, x[0], x[1], x[2],
           sqrt(N_VDotProd(v, v)), energy);
  }
  if (flag) fprintf(stderr, "pendulum_so3: %s\n", LGNGetReturnFlagName(flag));

  /* 7. statistics */
  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  printf("\nsteps = %ld   Newton iterations = %ld\n", nst, nni);

  /* 8. clean up: Lignum's memory, then what we created */
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
