/* -----------------------------------------------------------------------------
 * Planar mechanisms (planar_mechanisms.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "models/planar_mechanisms.h"

/* ---------------------------------------------------------------------------
 * The glue: every callback from the body and joint sets
 * ------------------------------------------------------------------------ */

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((PlanarMechanism *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const PlanarMechanism *pm = (const PlanarMechanism *)ud;
  int flag = LGNBodies_ForceFn(t, q, v, g, pm->bodies);
  if (flag == 0 && pm->torque_body >= 0) /* g holds minus the applied torque */
    N_VGetArrayPointer(g)[3 * pm->torque_body + 2] -= pm->torque;
  return flag;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((PlanarMechanism *)ud)->joints, t, q, phi);
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((PlanarMechanism *)ud)->joints, t, q, B);
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((PlanarMechanism *)ud)->joints, t, q, v, z);
}

static int PhiT(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  return LGNJoints_TimeDerivative(((PlanarMechanism *)ud)->joints, t, q, phit);
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  const PlanarMechanism *pm = (const PlanarMechanism *)ud;
  int flag = LGNBodies_Stiffness(pm->bodies, q, v, K);
  (void)vdot;
  if (flag == 0) flag = LGNJoints_Stiffness(pm->joints, t, q, lambda, K);
  return flag;
}

static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((PlanarMechanism *)ud)->bodies);
}

int planar_set_model(void *mem, PlanarMechanism *pm)
{
  int flag = LGNSetGroup(mem, pm->G);
  if (!flag) flag = LGNSetUserData(mem, pm);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, pm->m, Constr, ConstrJac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag && LGNJoints_NumDrivers(pm->joints) > 0) flag = LGNSetConstraintTimeFn(mem, PhiT);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  return flag;
}

static int NewMechanism(LGNGroup body, int nb, PlanarMechanism *pm)
{
  LGNGroup f[8];
  int k;
  memset(pm, 0, sizeof *pm);
  for (k = 0; k < nb; k++) f[k] = body;
  pm->nb          = nb;
  pm->torque_body = -1;
  pm->G           = LGNGroup_Product(nb, f);
  pm->bodies      = pm->G != NULL ? LGNBodies_Create(pm->G) : NULL;
  pm->joints      = pm->G != NULL ? LGNJoints_Create(pm->G) : NULL;
  return pm->bodies != NULL && pm->joints != NULL ? 0 : -1;
}

void planar_free(PlanarMechanism *pm)
{
  LGNJoints_Destroy(&pm->joints);
  LGNBodies_Destroy(&pm->bodies);
  LGNGroup_Destroy(pm->G);
  pm->G = NULL;
}

/* Body k's start: centre of mass c, angle th, inertial velocity u of the
 * centre of mass and rate w (v = (R^T u, w) on SE(2)). */
static void SetBody(LGNGroup body, sunrealtype *q, sunrealtype *v, int k, const double c[2],
                    double th, const double u[2], double w)
{
  const double cs = cos(th), sn = sin(th);
  q[3 * k]     = c[0];
  q[3 * k + 1] = c[1];
  q[3 * k + 2] = th;
  if (body->kind == LGN_GROUP_SE2) {
    v[3 * k]     = cs * u[0] + sn * u[1];
    v[3 * k + 1] = -sn * u[0] + cs * u[1];
  } else {
    v[3 * k]     = u[0];
    v[3 * k + 1] = u[1];
  }
  v[3 * k + 2] = w;
}

/* ---------------------------------------------------------------------------
 * Andrews' squeezing mechanism (andrews.f, common /andcom/)
 * ------------------------------------------------------------------------ */

static const double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050,
                    m6 = .00706, m7 = .05498;
static const double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014,
                    yc = .072, c0 = 4530.0;
static const double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                    i6 = 5.667e-7, i7 = 1.912e-5;
static const double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5,
                    l0 = 7785e-5;
static const double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2,
                    ta = 2308e-5, tb = 916e-5;
static const double u = 4e-2, ua = 1228e-5, ub = 449e-5, zf = 2e-2, zt = 4e-2, fa = 1421e-5,
                    mom = 33e-3;

/* the Test Set's start (init) and reference at t = 0.03 (solut) */
static const double ANDREWS_Q0[7] = {
  -0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
  0.222668390165885884674473185609, 0.487364979543842550225598953530,
  -0.222668390165885884674473185609, 1.23054744454982119249735015568};
const double PLANAR_ANDREWS_Q_REF[7] = {
  0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1,
  -0.5347301163226948e+0, 0.5244099658805304e+0, 0.5347301163226948e+0,
  0.1048080741042263e+1};
const double PLANAR_ANDREWS_V_REF[7] = {
  0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
  0.1929337464421385e+2, 0.5735699284790808e+0, -0.1929337464421385e+2,
  0.3231791658026955e+0};

/* A body pinned to the ground needs only the inertia about its pin
 * (bodies 1, 3, 5, 7 of andrews.f): its centre of mass is put on a line
 * through the pin at the distance of the Test Set's offsets. */
int planar_andrews(LGNGroup body, PlanarMechanism *pm, sunrealtype *q0, sunrealtype *v0)
{
  const double rho3 = hypot(sa, sb), rho5 = hypot(ta, tb), rho7 = hypot(ua, ub);
  const double ee = e - ea, zz = zf - fa;
  /* the points of the bodies (centre-of-mass frames) */
  const sunrealtype O[2] = {0, 0}, A[2] = {xa, ya}, B[2] = {xb, yb}, C[2] = {xc, yc};
  const sunrealtype p1O[2] = {-ra, 0}, p1F[2] = {rr - ra, 0};
  const sunrealtype p2F[2] = {da, 0}, p2E[2] = {da - d, 0};
  const sunrealtype p3B[2] = {0, rho3}, p3E[2] = {0, rho3 - ss}, p3D[2] = {sd, rho3 - sc};
  const sunrealtype p4H[2] = {0, ee}, p4E[2] = {0, -ea};
  const sunrealtype p5A[2] = {-rho5, 0}, p5H[2] = {zt - rho5, 0};
  const sunrealtype p6G[2] = {-zz, 0}, p6E[2] = {fa, 0};
  const sunrealtype p7A[2] = {0, rho7}, p7G[2] = {0, rho7 - u};
  const double mass[7] = {m1, m2, m3, m4, m5, m6, m7}, in[7] = {i1, i2, i3, i4, i5, i6, i7};
  const double *a = ANDREWS_Q0, zero[2] = {0, 0};
  double th[7], c[7][2];
  int k, flag;
  if (NewMechanism(body, 7, pm) != 0) return -1;
  flag = 0;
  for (k = 0; k < 7 && !flag; k++) flag = LGNBodies_SetPlanarMass(pm->bodies, k, mass[k], in[k]);
  if (!flag) flag = LGNBodies_AddPlanarSpringDamper(pm->bodies, 2, p3D, LGN_GROUND, C, c0, 0, l0);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, LGN_GROUND, O, 0, p1O);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 0, p1F, 1, p2F);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 1, p2E, 2, p3E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, LGN_GROUND, B, 2, p3B);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 1, p2E, 3, p4E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 3, p4H, 4, p5H);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, LGN_GROUND, A, 4, p5A);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 1, p2E, 5, p6E);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 5, p6G, 6, p7G);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, LGN_GROUND, A, 6, p7A);
  if (flag) return -1;
  pm->torque_body = 0;
  pm->torque      = mom;
  pm->m           = LGNJoints_NumConstraints(pm->joints);
  /* the start: body angles from the joint angles, centres of mass */
  th[0] = a[0];
  th[1] = a[0] + a[1];
  th[2] = a[2];
  th[3] = a[3] + a[4];
  th[4] = a[4];
  th[5] = a[5] + a[6];
  th[6] = a[6];
  c[0][0] = ra * cos(th[0]);
  c[0][1] = ra * sin(th[0]);
  c[1][0] = rr * cos(th[0]) - da * cos(th[1]);
  c[1][1] = rr * sin(th[0]) - da * sin(th[1]);
  c[2][0] = xb + rho3 * sin(th[2]); /* B + R(gamma) (0, -rho3) */
  c[2][1] = yb - rho3 * cos(th[2]);
  c[3][0] = xa + zt * cos(th[4]) + ee * sin(th[3]); /* H + ee R (0, -1) */
  c[3][1] = ya + zt * sin(th[4]) - ee * cos(th[3]);
  c[4][0] = xa + rho5 * cos(th[4]);
  c[4][1] = ya + rho5 * sin(th[4]);
  c[5][0] = xa + u * sin(th[6]) + zz * cos(th[5]); /* G + zz e(theta) */
  c[5][1] = ya - u * cos(th[6]) + zz * sin(th[5]);
  c[6][0] = xa + rho7 * sin(th[6]);
  c[6][1] = ya - rho7 * cos(th[6]);
  for (k = 0; k < 7; k++) SetBody(body, q0, v0, k, c[k], th[k], zero, 0);
  return 0;
}

void planar_andrews_angles(const PlanarMechanism *pm, const sunrealtype *q,
                           const sunrealtype *v, double ang[7], double rate[7])
{
  (void)pm;
  ang[0]  = q[2];
  ang[1]  = q[5] - q[2];
  ang[2]  = q[8];
  ang[3]  = q[11] - q[14];
  ang[4]  = q[14];
  ang[5]  = q[17] - q[20];
  ang[6]  = q[20];
  rate[0] = v[2];
  rate[1] = v[5] - v[2];
  rate[2] = v[8];
  rate[3] = v[11] - v[14];
  rate[4] = v[14];
  rate[5] = v[17] - v[20];
  rate[6] = v[20];
}

/* ---------------------------------------------------------------------------
 * The slider-crank: crank r, rod l (centres of mass at their middles), a
 * slider on the x axis; gravity -9.81 y; a rotational spring-damper
 * (kr, cr) between the ground and the crank, a spring-damper (k, c, L0)
 * between the slider and the point (XP, 0).
 * ------------------------------------------------------------------------ */

#define SC_R  0.2
#define SC_L  0.6
#define SC_M1 1.0
#define SC_M2 1.5
#define SC_M3 2.0
#define SC_J1 (SC_M1 * SC_R * SC_R / 12)
#define SC_J2 (SC_M2 * SC_L * SC_L / 12)
#define SC_J3 0.01
#define SC_G  9.81
#define SC_KR 2.0
#define SC_CR 0.05
#define SC_K  50.0
#define SC_C  0.5
#define SC_L0 0.5
#define SC_XP 1.5
#define SC_PHI0 0.3
#define SC_W0   6.0

void rn_slider_crank_start(sunrealtype q0[3], sunrealtype v0[3])
{
  const double psi = asin(-SC_R * sin(SC_PHI0) / SC_L);
  const double psid = -SC_R * cos(SC_PHI0) * SC_W0 / (SC_L * cos(psi));
  q0[0] = SC_PHI0;
  q0[1] = psi;
  q0[2] = SC_R * cos(SC_PHI0) + SC_L * cos(psi);
  v0[0] = SC_W0;
  v0[1] = psid;
  v0[2] = -SC_R * sin(SC_PHI0) * SC_W0 - SC_L * sin(psi) * psid;
}

int planar_slider_crank(LGNGroup body, PlanarMechanism *pm, sunrealtype *q0, sunrealtype *v0)
{
  const sunrealtype O[2] = {0, 0}, P[2] = {SC_XP, 0}, xaxis[2] = {1, 0};
  const sunrealtype cl[2] = {-SC_R / 2, 0}, cr[2] = {SC_R / 2, 0};
  const sunrealtype rl[2] = {-SC_L / 2, 0}, rrt[2] = {SC_L / 2, 0};
  const sunrealtype grav[3] = {0, -SC_G, 0};
  sunrealtype x[3], xd[3];
  double c[2], w[2], ph, ps;
  int flag;
  if (NewMechanism(body, 3, pm) != 0) return -1;
  flag = LGNBodies_SetPlanarMass(pm->bodies, 0, SC_M1, SC_J1);
  if (!flag) flag = LGNBodies_SetPlanarMass(pm->bodies, 1, SC_M2, SC_J2);
  if (!flag) flag = LGNBodies_SetPlanarMass(pm->bodies, 2, SC_M3, SC_J3);
  if (!flag) flag = LGNBodies_SetGravity(pm->bodies, grav);
  if (!flag) flag = LGNBodies_AddPlanarRotationalSpringDamper(pm->bodies, LGN_GROUND, 0, SC_KR, SC_CR, 0);
  if (!flag) flag = LGNBodies_AddPlanarSpringDamper(pm->bodies, 2, O, LGN_GROUND, P, SC_K, SC_C, SC_L0);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, LGN_GROUND, O, 0, cl);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 0, cr, 1, rl);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(pm->joints, 1, rrt, 2, O);
  if (!flag) flag = LGNJoints_AddPlanarPrismatic(pm->joints, LGN_GROUND, O, xaxis, 2, O, 0);
  if (flag) return -1;
  pm->m = LGNJoints_NumConstraints(pm->joints);
  rn_slider_crank_start(x, xd);
  ph = x[0];
  ps = x[1];
  c[0] = SC_R / 2 * cos(ph); /* crank */
  c[1] = SC_R / 2 * sin(ph);
  w[0] = -SC_R / 2 * sin(ph) * xd[0];
  w[1] = SC_R / 2 * cos(ph) * xd[0];
  SetBody(body, q0, v0, 0, c, ph, w, xd[0]);
  c[0] = SC_R * cos(ph) + SC_L / 2 * cos(ps); /* rod */
  c[1] = SC_R * sin(ph) + SC_L / 2 * sin(ps);
  w[0] = -SC_R * sin(ph) * xd[0] - SC_L / 2 * sin(ps) * xd[1];
  w[1] = SC_R * cos(ph) * xd[0] + SC_L / 2 * cos(ps) * xd[1];
  SetBody(body, q0, v0, 1, c, ps, w, xd[1]);
  c[0] = x[2]; /* slider */
  c[1] = 0;
  w[0] = xd[2];
  w[1] = 0;
  SetBody(body, q0, v0, 2, c, 0, w, 0);
  return 0;
}

void planar_slider_crank_coords(const sunrealtype *q, double x[3])
{
  x[0] = q[2];
  x[1] = q[5];
  x[2] = q[6];
}

/* ---- the same slider-crank on R^3, q = (phi, psi, s) --------------------- */

static int RnMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q);
  const double c = SC_M2 * SC_R * SC_L / 2 * cos(x[0] - x[1]);
  (void)t;
  (void)ud;
  SM_ELEMENT_D(M, 0, 0) = SC_M1 * SC_R * SC_R / 4 + SC_J1 + SC_M2 * SC_R * SC_R;
  SM_ELEMENT_D(M, 0, 1) = SM_ELEMENT_D(M, 1, 0) = c;
  SM_ELEMENT_D(M, 1, 1) = SC_M2 * SC_L * SC_L / 4 + SC_J2;
  SM_ELEMENT_D(M, 2, 2) = SC_M3;
  return 0;
}

/* Lagrange's equations: the velocity terms, gravity, the springs */
static int RnForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q), *xd = N_VGetArrayPointer(v);
  sunrealtype *gd = N_VGetArrayPointer(g);
  const double c = SC_M2 * SC_R * SC_L / 2, sn = sin(x[0] - x[1]);
  const double L = SC_XP - x[2]; /* the slider spring's length (XP > s) */
  (void)t;
  (void)ud;
  gd[0] = c * sn * xd[1] * xd[1] + (SC_M1 / 2 + SC_M2) * SC_G * SC_R * cos(x[0]) +
          SC_KR * x[0] + SC_CR * xd[0];
  gd[1] = -c * sn * xd[0] * xd[0] + SC_M2 * SC_G * SC_L / 2 * cos(x[1]);
  gd[2] = -(SC_K * (L - SC_L0) - SC_C * xd[2]);
  return 0;
}

static int RnConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q);
  sunrealtype *p = N_VGetArrayPointer(phi);
  (void)t;
  (void)ud;
  p[0] = SC_R * cos(x[0]) + SC_L * cos(x[1]) - x[2];
  p[1] = SC_R * sin(x[0]) + SC_L * sin(x[1]);
  return 0;
}

static int RnJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const sunrealtype *x = N_VGetArrayPointer(q);
  (void)t;
  (void)ud;
  SM_ELEMENT_D(B, 0, 0) = -SC_R * sin(x[0]);
  SM_ELEMENT_D(B, 0, 1) = -SC_L * sin(x[1]);
  SM_ELEMENT_D(B, 0, 2) = -1;
  SM_ELEMENT_D(B, 1, 0) = SC_R * cos(x[0]);
  SM_ELEMENT_D(B, 1, 1) = SC_L * cos(x[1]);
  SM_ELEMENT_D(B, 1, 2) = 0;
  return 0;
}

int rn_slider_crank_set_model(void *mem)
{
  int flag = LGNSetMassFn(mem, RnMass);
  if (!flag) flag = LGNSetForceFn(mem, RnForce);
  if (!flag) flag = LGNSetConstraints(mem, 2, RnConstr, RnJac);
  return flag;
}

/* ---------------------------------------------------------------------------
 * One integration
 * ------------------------------------------------------------------------ */

int planar_set_model_fn(void *mem, void *model)
{
  return planar_set_model(mem, (PlanarMechanism *)model);
}

int rn_slider_crank_set_model_fn(void *mem, void *model)
{
  (void)model;
  return rn_slider_crank_set_model(mem);
}

int planar_integrate(SUNContext ctx, LGNGroup G, sunindextype m, PlanarSetModelFn set_model,
                     void *model, const sunrealtype *q0, const sunrealtype *v0,
                     const PlanarRun *run, sunrealtype *q, sunrealtype *v, long *nsteps,
                     long *nniters)
{
  const sunindextype nv = G->nv, n = nv + m;
  N_Vector qv = N_VNew_Serial(G->nq, ctx), vv = N_VNew_Serial(nv, ctx);
  N_Vector tmpl = N_VNew_Serial(n, ctx);
  SUNMatrix A = SUNDenseMatrix(n, n, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(tmpl, A, ctx);
  void *mem = LGNCreate(ctx);
  sunrealtype t = 0;
  int flag = (qv && vv && tmpl && A && LS && mem) ? 0 : -1;
  if (!flag) {
    memcpy(N_VGetArrayPointer(qv), q0, (size_t)G->nq * sizeof *q0);
    memcpy(N_VGetArrayPointer(vv), v0, (size_t)nv * sizeof *v0);
    flag = LGNSetGroup(mem, G);
  }
  if (!flag) flag = set_model(mem, model);
  if (!flag) flag = LGNInit(mem, 0.0, qv, vv);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag && run->bdf_order > 0) flag = LGNSetBDF(mem, run->bdf_order);
  if (!flag && run->bdf_order == 0) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag && run->bdf_order == 0) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetMaxNumSteps(mem, 10000000L);
  if (!flag && run->adaptive) {
    flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, run->tol, run->tol);
  } else if (!flag && run->bdf_order > 0) { /* the history under error control */
    flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, 1e-12, 1e-12);
    if (!flag) flag = LGNSetStopTime(mem, run->t_start);
    if (!flag) flag = LGNSolve(mem, run->t_start, &t, qv, vv, LGN_NORMAL);
    if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
    if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_FIXED);
    if (!flag) flag = LGNSetStepSize(mem, run->h);
  } else if (!flag) {
    flag = LGNSetStepControl(mem, LGN_STEP_FIXED);
    if (!flag) flag = LGNSetStepSize(mem, run->h);
  }
  if (!flag) flag = LGNSetStopTime(mem, run->t_end);
  if (!flag) flag = LGNSolve(mem, run->t_end, &t, qv, vv, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  if (!flag && fabs(t - run->t_end) > 1e-12 * (1 + run->t_end)) flag = -99;
  if (!flag) {
    memcpy(q, N_VGetArrayPointer(qv), (size_t)G->nq * sizeof *q);
    memcpy(v, N_VGetArrayPointer(vv), (size_t)nv * sizeof *v);
  }
  if (nsteps != NULL) LGNGetNumSteps(mem, nsteps);
  if (nniters != NULL) LGNGetNumNewtonIters(mem, nniters);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(tmpl);
  N_VDestroy(qv);
  N_VDestroy(vv);
  return flag;
}
