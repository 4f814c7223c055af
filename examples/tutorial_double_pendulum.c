/* -----------------------------------------------------------------------------
 * Lignum tutorial: a double spherical pendulum (doc/tutorial.md explains
 * every step of this file).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Two equal rods (mass 1 kg, length 1 m, radius 0.05 m), each a rigid body
 * on R^3 x SO(3), hang under gravity g = 9.81 m/s^2 along -z: rod 0 from a
 * fixed point (the origin) by a spherical joint at its end, rod 1 from the
 * free end of rod 0 by a second spherical joint. Both rods spin about their
 * own axes, so the gyroscopic terms matter.
 *
 * Integrated with mod. LGGalpha (generalized-alpha, rho_inf = 0.9, exact
 * kinematics, index 3): first with a fixed step h = 1e-3 to t = 1 s, then
 * with error control (rtol = atol = 1e-7) to t = 2 s. Output every 0.1 s:
 * time, energy, its drift, |Phi|, the free end's position.
 *
 * Checks (exit status 1 on failure): the relative energy drift stays below
 * 1e-3 (the joints do no work, so only the method's numerical damping
 * changes the energy), and |Phi(q)|_inf below 1e-12 m at every output (the
 * index-3 method keeps the joints closed to round-off).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>        /* the integrator           */
#include <lignum/lignum_joints.h> /* spherical joints         */
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

/* ---- Step 1: the model's data ---------------------------------------------*/
#define NBODY 2
#define MASS  1.0  /* kg  */
#define LEN   1.0  /* m   */
#define RAD   0.05 /* m   */
#define GRAV  9.81 /* m/s^2, along -z */

typedef struct {
  double J[3];      /* principal moments of inertia (body frame, rod along x) */
  LGNJoints joints; /* the two spherical joints                              */
} Model;

/* ---- Step 3: the mass matrix, M = diag(m I, J) for each body --------------*/
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *user_data)
{
  const Model *md = (const Model *)user_data;
  int b, i;
  (void)t; (void)q;
  /* M arrives zeroed (dense): write the nonzero entries only */
  for (b = 0; b < NBODY; b++)
    for (i = 0; i < 3; i++) {
      SM_ELEMENT_D(M, 6 * b + i, 6 * b + i)         = MASS;     /* translation */
      SM_ELEMENT_D(M, 6 * b + 3 + i, 6 * b + 3 + i) = md->J[i]; /* rotation    */
    }
  return 0;
}

/* ---- Step 4: the forces, M vdot + g + B^T lambda = 0 -----------------------
 * g holds MINUS the applied forces: gravity (0, 0, -m GRAV) enters as
 * (0, 0, +m GRAV). The rotational rows hold the gyroscopic term
 * Omega x (J Omega) of Euler's equations J Omegadot + Omega x J Omega = 0. */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *user_data)
{
  const Model *md = (const Model *)user_data;
  const double *vd = N_VGetArrayPointer(v), *J = md->J;
  double *gd = N_VGetArrayPointer(g);
  int b;
  (void)t; (void)q;
  for (b = 0; b < NBODY; b++) {
    const double *W = vd + 6 * b + 3; /* body angular velocity Omega */
    double *gb = gd + 6 * b;
    gb[0] = 0.0;
    gb[1] = 0.0;
    gb[2] = MASS * GRAV;
    gb[3] = W[1] * J[2] * W[2] - W[2] * J[1] * W[1];
    gb[4] = W[2] * J[0] * W[0] - W[0] * J[2] * W[2];
    gb[5] = W[0] * J[1] * W[1] - W[1] * J[0] * W[0];
  }
  return 0;
}

/* ---- Step 5: the constraints, by the joint helpers ------------------------*/
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *user_data)
{
  return LGNJoints_Residual(((Model *)user_data)->joints, t, q, phi);
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *user_data)
{
  return LGNJoints_Jacobian(((Model *)user_data)->joints, t, q, B);
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *user_data)
{
  return LGNJoints_Curvature(((Model *)user_data)->joints, t, q, v, z);
}

/* ---- Step 10: outputs ------------------------------------------------------
 * Energy: kinetic (translation with the inertial u, rotation with the
 * body-fixed Omega) plus potential m GRAV z of each centre of mass. */
static double Energy(const Model *md, N_Vector q, N_Vector v)
{
  const double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  double E = 0.0;
  int b, i;
  for (b = 0; b < NBODY; b++) {
    for (i = 0; i < 3; i++) {
      E += 0.5 * MASS * vd[6 * b + i] * vd[6 * b + i];
      E += 0.5 * md->J[i] * vd[6 * b + 3 + i] * vd[6 * b + 3 + i];
    }
    E += MASS * GRAV * qd[7 * b + 2];
  }
  return E;
}

static double PhiNorm(const Model *md, N_Vector q, N_Vector phi)
{
  LGNJoints_Residual(md->joints, 0.0, q, phi);
  return N_VMaxNorm(phi);
}

/* R x for the row-major rotation matrix R */
static void Rotate(const double R[9], const double x[3], double y[3])
{
  int i;
  for (i = 0; i < 3; i++) y[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
}

static void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

int main(void)
{
  const double end_a[3] = {-0.5 * LEN, 0.0, 0.0}; /* joint end of a rod (body frame) */
  const double end_b[3] = {0.5 * LEN, 0.0, 0.0};  /* free end of a rod (body frame)  */
  const double origin[3] = {0.0, 0.0, 0.0};
  /* initial orientations (rotation vectors) and body angular velocities */
  const double psi[NBODY][3]   = {{0.0, 0.6, 0.3}, {0.0, -0.4, 1.2}};
  const double omega[NBODY][3] = {{20.0, 1.0, -2.0}, {-15.0, 0.0, 3.0}};
  const double t_fixed = 1.0, t_end = 2.0, dt_out = 0.1, h = 1e-3, tol = 1e-7;
  const double drift_bound = 1e-3, phi_bound = 1e-12;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[NBODY];
  N_Vector q = NULL, v = NULL, phi = NULL, tmpl = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  Model md;
  sunindextype nv, m;
  double *qd, *vd, E0, E, err, drift = 0.0, phimax = 0.0, t = 0.0, tout;
  double R[9], r[3], c[3], s[3], w[3], p_end[3];
  long int nst_fixed = 0, nst = 0, netf = 0, nni = 0;
  int b, i, k, flag;

  /* Step 1: principal moments of a solid cylinder along its x axis */
  md.J[0] = 0.5 * MASS * RAD * RAD;
  md.J[1] = md.J[2] = MASS * (3.0 * RAD * RAD + LEN * LEN) / 12.0;

  /* Step 2: the configuration group, R^3 x SO(3) for each rod */
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R3xSO3();
  for (b = 0; b < NBODY; b++) factors[b] = body; /* one factor may repeat */
  G  = LGNGroup_Product(NBODY, factors);          /* nq = 14, nv = 12     */
  nv = G->nv;

  /* Step 5: two spherical joints: ground - rod 0, rod 0 - rod 1 */
  md.joints = LGNJoints_Create(G);
  flag = LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, end_a);
  if (!flag) flag = LGNJoints_AddSpherical(md.joints, 0, end_b, 1, end_a);
  if (flag) return 1;
  m = LGNJoints_NumConstraints(md.joints); /* 6 */

  /* Step 6: a consistent initial state, (x_b, p_b) and (u_b, Omega_b).
   * Each joint end must coincide, and so must its velocity:
   *   x_b = x_{b-1} + R_{b-1} end_b - R_b end_a  (x_{-1} + R_{-1} end_b: the origin)
   *   u_b = u_{b-1} + R_{b-1} (Omega_{b-1} x end_b) - R_b (Omega_b x end_a) */
  q   = N_VNew_Serial(G->nq, ctx);
  v   = N_VNew_Serial(nv, ctx);
  phi = N_VNew_Serial(m, ctx);
  qd  = N_VGetArrayPointer(q);
  vd  = N_VGetArrayPointer(v);
  for (i = 0; i < 3; i++) p_end[i] = w[i] = 0.0; /* joint point and its velocity */
  for (b = 0; b < NBODY; b++) {
    double *x = qd + 7 * b, *p = qd + 7 * b + 3, *u = vd + 6 * b, *W = vd + 6 * b + 3;
    LGNQuaternionFromRotationVector(psi[b], p);
    LGNQuaternionToRotation(p, R);
    for (i = 0; i < 3; i++) W[i] = omega[b][i];
    Rotate(R, end_a, r);
    Cross(W, end_a, c);
    Rotate(R, c, u); /* R (Omega x end_a) */
    for (i = 0; i < 3; i++) {
      x[i] = p_end[i] - r[i];
      u[i] = w[i] - u[i];
    }
    /* this rod's free end and its velocity: the next joint */
    Rotate(R, end_b, r);
    Cross(W, end_b, c);
    Rotate(R, c, s);
    for (i = 0; i < 3; i++) {
      p_end[i] = x[i] + r[i];
      w[i]     = u[i] + s[i];
    }
  }

  /* Step 7: the integrator and the model */
  mem  = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE); /* M does not depend on q */
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);

  /* Step 8: the linear solver for the (nv + m) x (nv + m) iteration matrix */
  tmpl = N_VNew_Serial(nv + m, ctx);
  A    = SUNDenseMatrix(nv + m, nv + m, ctx);
  LS   = SUNLinSol_Dense(tmpl, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);

  /* Step 9: the method: mod. LGGalpha, index 3, fixed step h */
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_INDEX3);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNSStolerances(mem, 1e-10, 1e-10); /* Newton's tolerances */
  if (flag) {
    fprintf(stderr, "set-up failed: %s\n", LGNGetReturnFlagName(flag));
    return 1;
  }

  /* Step 10: the time loop, with outputs every dt_out */
  E0 = Energy(&md, q, v);
  printf("Double spherical pendulum, mod. LGGalpha(0.9), index 3\n");
  printf("%5s %12s %10s %10s %9s %9s %9s\n", "t", "energy", "drift", "|Phi|", "x_end",
         "y_end", "z_end");
  for (k = 1; t < t_end - 1e-12; k++) {
    tout = k * dt_out;
    if (t > t_fixed - 1e-12 && nst_fixed == 0) {
      /* Step 11: from t = 1 s on, error control */
      LGNGetNumSteps(mem, &nst_fixed);
      flag = LGNSStolerances(mem, tol, tol);
      if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
      if (flag) break;
      printf("-- %ld fixed steps; error control from here, rtol = atol = %g\n", nst_fixed, tol);
    }
    /* with error control, land exactly on tout (no interpolation) */
    if (nst_fixed > 0 && (flag = LGNSetStopTime(mem, tout)) != 0) break;
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (flag < 0) break;
    E   = Energy(&md, q, v);
    err = PhiNorm(&md, q, phi);
    drift  = fmax(drift, fabs(E - E0) / fabs(E0));
    phimax = fmax(phimax, err);
    LGNQuaternionToRotation(qd + 10, R); /* rod 1: x at qd[7..9], p at qd[10..13] */
    Rotate(R, end_b, r);
    printf("%5.2f %12.8f %10.2e %10.2e %9.5f %9.5f %9.5f\n", t, E, (E - E0) / fabs(E0), err,
           qd[7] + r[0], qd[8] + r[1], qd[9] + r[2]);
  }
  if (flag < 0) fprintf(stderr, "LGNSolve failed: %s at t = %g\n", LGNGetReturnFlagName(flag), t);
  LGNGetNumSteps(mem, &nst);
  LGNGetNumErrTestFails(mem, &netf);
  LGNGetNumNewtonIters(mem, &nni);
  printf("steps: %ld fixed, %ld with error control (%ld rejected); %.2f Newton iterations/step\n",
         nst_fixed, nst - nst_fixed, netf, nst > 0 ? (double)nni / (double)nst : 0.0);
  printf("max relative energy drift %.2e (bound %.0e), max |Phi| %.2e m (bound %.0e)\n", drift,
         drift_bound, phimax, phi_bound);

  /* Step 12: free what we created, in reverse order */
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(tmpl);
  N_VDestroy(phi);
  N_VDestroy(v);
  N_VDestroy(q);
  LGNJoints_Destroy(&md.joints);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);

  if (flag < 0 || !(t >= t_end - 1e-9) || !(drift < drift_bound) || !(phimax < phi_bound)) {
    printf("tutorial_double_pendulum: FAILED\n");
    return 1;
  }
  printf("tutorial_double_pendulum: OK\n");
  return 0;
}
