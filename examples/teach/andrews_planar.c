/* -----------------------------------------------------------------------------
 * Lignum teaching example: Andrews' squeezing mechanism as a planar
 * mechanism (lignum_planar.h).
 *
 * Shows: bodies on a planar group (R^2 x SO(2): q = (x, y, theta), v = (u
 * inertial, omega)), planar revolute joints, a spring-damper, and a motor
 * torque that the body helpers lack, added in the force callback.
 *
 * The mechanism of the Test Set for IVP Solvers (andrews.f; Hairer and
 * Wanner II, VII.7): seven bodies in the plane joined by ten revolute
 * joints (three of them at the point E), a spring c0 from body 3 to the
 * fixed point C, and a motor torque mom on the crank; 21 velocities, 20
 * rows, one degree of freedom. Each body's frame sits at its centre of
 * mass; the bodies pinned to the ground (1, 3, 5, 7) need only their
 * inertia about the pin, so their centres of mass are put on a line
 * through the pin. BDF (maxord 5), index 3, rtol = atol = 1e-8, t in
 * [0, 0.03] s.
 *
 * Output: t and the Test Set's joint angles beta, Theta, gamma (from the
 * body angles: beta = theta_1, Theta = theta_2 - theta_1, gamma =
 * theta_3), |Phi|; at the end the largest error of the seven angles
 * against the Test Set's reference (max |x - x_ref| / (1 + |x_ref|)).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_planar.h> /* planar groups, bodies and joints */
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* ---- the data of andrews.f (SI units) ------------------------------------ */
static const double m[7] = {.04325, .00365, .02373, .00706, .07050, .00706, .05498};
static const double in[7] = {2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7,
                             1.912e-5};
static const double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014,
                    yc = .072, c0 = 4530.0, d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5,
                    rr = 7e-3, ra = 92e-5, l0 = 7785e-5, ss = 35e-3, sa = 1874e-5,
                    sb = 1043e-5, sc = 18e-3, sd = 2e-2, ta = 2308e-5, tb = 916e-5, u = 4e-2,
                    ua = 1228e-5, ub = 449e-5, zf = 2e-2, zt = 4e-2, fa = 1421e-5, mom = 33e-3;

/* the Test Set's start (joint angles, at rest) and its reference at 0.03 */
static const double X0[7] = {-0.0617138900142764496, 0.0, 0.455279819163070380,
                             0.222668390165885885, 0.487364979543842550,
                             -0.222668390165885885, 1.23054744454982119};
static const double XREF[7] = {15.81077119629904, -15.75637105984298, 0.04082224013073101,
                               -0.5347301163226948, 0.5244099658805304, 0.5347301163226948,
                               1.048080741042263};

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

/* ---- the model callbacks: the sets' functions, plus the motor ------------- */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  int flag = LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
  N_VGetArrayPointer(g)[2] -= mom; /* g holds minus the torque on body 1 */
  return flag;
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi);
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B);
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z);
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  int flag = LGNBodies_Stiffness(((Model *)ud)->bodies, q, v, K);
  (void)vdot;
  return flag ? flag : LGNJoints_Stiffness(((Model *)ud)->joints, t, q, lambda, K);
}

/* The Test Set's joint angles from the body angles q[3k + 2] */
static void Angles(const sunrealtype *q, double x[7])
{
  x[0] = q[2];
  x[1] = q[5] - q[2];
  x[2] = q[8];
  x[3] = q[11] - q[14];
  x[4] = q[14];
  x[5] = q[17] - q[20];
  x[6] = q[20];
}

int main(void)
{
  const double rho3 = hypot(sa, sb), rho5 = hypot(ta, tb), rho7 = hypot(ua, ub);
  const double ee = e - ea, zz = zf - fa;
  /* points: fixed (inertial) and of the bodies (body frames) */
  const sunrealtype O[2] = {0, 0}, A[2] = {xa, ya}, B[2] = {xb, yb}, C[2] = {xc, yc};
  const sunrealtype p1O[2] = {-ra, 0}, p1F[2] = {rr - ra, 0}, p2F[2] = {da, 0},
                    p2E[2] = {da - d, 0}, p3B[2] = {0, rho3}, p3E[2] = {0, rho3 - ss},
                    p3D[2] = {sd, rho3 - sc}, p4H[2] = {0, ee}, p4E[2] = {0, -ea},
                    p5A[2] = {-rho5, 0}, p5H[2] = {zt - rho5, 0}, p6G[2] = {-zz, 0},
                    p6E[2] = {fa, 0}, p7A[2] = {0, rho7}, p7G[2] = {0, rho7 - u};
  const double *a = X0;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, f[7];
  Model md = {NULL, NULL};
  N_Vector q = NULL, v = NULL, phi = NULL, tmpl = NULL;
  SUNMatrix Am = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunindextype m_rows = 0, nv;
  sunrealtype *qd, t = 0;
  double th[7], x[7], err = 0;
  int k, flag = 0;

  /* the group: seven R^2 x SO(2) bodies */
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R2xSO2();
  for (k = 0; k < 7; k++) f[k] = body;
  G  = LGNGroup_Product(7, f);
  nv = G->nv;

  /* the bodies, the spring, the joints */
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  for (k = 0; k < 7 && !flag; k++) flag = LGNBodies_SetPlanarMass(md.bodies, k, m[k], in[k]);
  if (!flag) flag = LGNBodies_AddPlanarSpringDamper(md.bodies, 2, p3D, LGN_GROUND, C, c0, 0, l0);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, LGN_GROUND, O, 0, p1O);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 0, p1F, 1, p2F);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 1, p2E, 2, p3E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, LGN_GROUND, B, 2, p3B);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 1, p2E, 3, p4E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 3, p4H, 4, p5H);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, LGN_GROUND, A, 4, p5A);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 1, p2E, 5, p6E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, 5, p6G, 6, p7G);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(md.joints, LGN_GROUND, A, 6, p7A);
  if (!flag) m_rows = LGNJoints_NumConstraints(md.joints); /* 20 */

  /* the start: body angles from the joint angles, the centres of mass */
  q   = N_VNew_Serial(G->nq, ctx);
  v   = N_VNew_Serial(nv, ctx);
  phi = N_VNew_Serial(m_rows, ctx);
  qd  = N_VGetArrayPointer(q);
  th[0] = a[0], th[1] = a[0] + a[1], th[2] = a[2], th[3] = a[3] + a[4];
  th[4] = a[4], th[5] = a[5] + a[6], th[6] = a[6];
  qd[0]  = ra * cos(th[0]), qd[1] = ra * sin(th[0]);
  qd[3]  = rr * cos(th[0]) - da * cos(th[1]), qd[4] = rr * sin(th[0]) - da * sin(th[1]);
  qd[6]  = xb + rho3 * sin(th[2]), qd[7] = yb - rho3 * cos(th[2]);
  qd[9]  = xa + zt * cos(th[4]) + ee * sin(th[3]);
  qd[10] = ya + zt * sin(th[4]) - ee * cos(th[3]);
  qd[12] = xa + rho5 * cos(th[4]), qd[13] = ya + rho5 * sin(th[4]);
  qd[15] = xa + u * sin(th[6]) + zz * cos(th[5]);
  qd[16] = ya - u * cos(th[6]) + zz * sin(th[5]);
  qd[18] = xa + rho7 * sin(th[6]), qd[19] = ya - rho7 * cos(th[6]);
  for (k = 0; k < 7; k++) qd[3 * k + 2] = th[k];
  N_VConst(0.0, v); /* at rest */

  /* the integrator: BDF, index 3, error control */
  mem = LGNCreate(ctx);
  if (mem == NULL) return 1;
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m_rows, Constr, ConstrJac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  tmpl = N_VNew_Serial(nv + m_rows, ctx);
  Am   = SUNDenseMatrix(nv + m_rows, nv + m_rows, ctx);
  LS   = LGNLinSol_Dense(tmpl, Am, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, Am);
  if (!flag) flag = LGNSetBDF(mem, 5);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, 1e-8, 1e-8);
  if (flag) {
    fprintf(stderr, "set-up failed: %s\n", LGNGetReturnFlagName(flag));
    return 1;
  }

  printf("Andrews' squeezing mechanism, 7 planar bodies: BDF5, index 3, tol 1e-8\n\n");
  printf("%7s %14s %14s %12s %9s\n", "t", "beta", "Theta", "gamma", "|Phi|");
  for (k = 1; k <= 6 && flag == 0; k++) {
    flag = LGNSolve(mem, 0.005 * k, &t, q, v, LGN_NORMAL);
    if (!flag) flag = LGNJoints_Residual(md.joints, t, q, phi);
    Angles(qd, x);
    if (!flag) printf("%7.3f %14.8f %14.8f %12.8f %9.1e\n", t, x[0], x[1], x[2], N_VMaxNorm(phi));
  }
  if (flag) fprintf(stderr, "failed at t = %g: %s\n", t, LGNGetReturnFlagName(flag));
  for (k = 0; k < 7; k++) err = fmax(err, fabs(x[k] - XREF[k]) / (1 + fabs(XREF[k])));
  printf("\nlargest error of the 7 angles against the Test Set at t = 0.03: %.1e\n", err);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(Am);
  N_VDestroy(tmpl);
  N_VDestroy(phi);
  N_VDestroy(v);
  N_VDestroy(q);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  if (flag || !(err < 1e-4)) {
    printf("andrews_planar: FAILED\n");
    return 1;
  }
  printf("andrews_planar: OK\n");
  return 0;
}
