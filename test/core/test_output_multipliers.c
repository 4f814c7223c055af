/* -----------------------------------------------------------------------------
 * Multipliers and outputs on the constraints under error control, against
 * exact multipliers of two driven mechanisms:
 *
 *  - a rotor: one body (J_z = 2) on a revolute joint about z, turned by a
 *    rotation driver theta = 0.5 sin 3t: the driver's multiplier is
 *    -J_z theta'' = 9 sin 3t, the revolute joint's five are 0 (no gravity,
 *    the centre of mass on the axis), over t in [0, 1] ([0, 2] in --table);
 *  - a rotor on a driven base: the base (J = I) turned about z by
 *    a(t) = 0.5 sin 2t, the rotor (J = diag(0.5, 0.3, 0.3)) about the base's
 *    x by b(t) = 10 t + 0.5 sin 5t: the drivers' multipliers are minus
 *    d/dt of the angular momenta (both bodies' about z, the rotor's about
 *    its axis), by a five-point difference of their exact values, over
 *    t in [0, 1] ([0, 2] in --table);
 *  - a slider-crank (test_driven.c's) turned at theta = 2 pi t: the driver's
 *    multiplier is minus the motor torque, which the test computes from the
 *    power balance tau thetadot = dT/dt of the exact kinematics (crank,
 *    connecting rod and slider; a central difference of T(t) with step
 *    2e-4 and fourth order, good to 1e-12), over t in [0, 0.5] ([0, 1] in
 *    --table).
 *
 * Outputs every 0.1 s (rotor) / 0.125 s (slider-crank) in three ways: a
 * stop time at each output (LGN_NORMAL lands there), LGN_NORMAL
 * interpolated, and LGN_ONE_STEP (every step end). Asserted, for
 * generalized-alpha (rho_inf 0.9) and BDF (maxord 5) at index 3, 2 and GGL,
 * tol = rtol = atol = 1e-8, with the default outputs (consistent, all
 * projected: no setter called):
 *   (a) max |lambda - lambda_exact| <= 1e-5 max |lambda_exact| (and with
 *       fixed steps h = 1e-3, LGN_NORMAL, index 3 and 2);
 *   (b) LGNGetDky(tret, 2) equals LGNGetAcceleration after the output (to
 *       1e-12 relative), and B(q)^T lambda of the joint helpers
 *       (LGNJoints_ConstraintForce) balances M vdot + g at the output;
 *   (c) |Phi(q, t)| and |B v + Phi_t| at every output <= 1e-12 (roundoff);
 *   (d) the lambda error falls with the tolerance: at 1e-9 below a tenth of
 *       that at 1e-5 (slider-crank, each method, stop times, index 3, not
 *       projected: projected outputs of these driven mechanisms are on the
 *       exact motion, and their multipliers exact to roundoff);
 *   (e) without the projection the interpolated outputs leave the
 *       constraints by more than 1e-10 somewhere at tol 1e-6 (what (c) fixes),
 *       and the setters refuse bad input (LGNSetMultiplierErrorControl at
 *       index 3 in LGNSolve);
 *   (f) with the multipliers in the error test (LGNSetMultiplierErrorControl,
 *       atol_lambda 1e-6) the step's own multipliers (consistent outputs
 *       off) are within 1e-5 max |lambda_exact| at tol 1e-8, index 2 and GGL
 *       (the rotor).
 * `test_output_multipliers --table` prints the errors of the step's own
 * multipliers (LGNSetConsistentOutputs off) beside them: the table of
 * doc/user-guide.md §8.5.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

#define R_CRANK 0.2
#define L_ROD   0.6
#define PI      3.14159265358979323846

enum { ROTOR = 0, SLIDER_CRANK = 1, DRIVEN_BASE = 2, NMODEL = 3 };
static const char *model_name[NMODEL] = {"rotor", "slider-crank", "driven base"};
enum { MODE_TSTOP = 0, MODE_NORMAL = 1, MODE_ONE_STEP = 2 };
static int full_spans = 0; /* --table: [0, 2] and [0, 1] (the checks: half) */
static const char *mode_name[] = {"stop times", "LGN_NORMAL", "LGN_ONE_STEP"};

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
  int model;
} Model;

/* ---- the two mechanisms --------------------------------------------------- */

static int RotorLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 0.5 * sin(3.0 * t);
  f[1] = 1.5 * cos(3.0 * t);
  f[2] = -4.5 * sin(3.0 * t);
  return 0;
}

static int CrankLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 2.0 * PI * t;
  f[1] = 2.0 * PI;
  f[2] = 0.0;
  return 0;
}

/* The rotor on a driven base: the base (body 0, J = I) turns about the
 * ground's z by a(t) = 0.5 sin 2t, the rotor (body 1, J = diag(0.5, 0.3,
 * 0.3), spin axis its x) about the base's x by b(t) = 10 t + 0.5 sin 5t;
 * both centres at the origin. */
static int BaseLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 0.5 * sin(2.0 * t);
  f[1] = cos(2.0 * t);
  f[2] = -2.0 * sin(2.0 * t);
  return 0;
}

static int SpinLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 10.0 * t + 0.5 * sin(5.0 * t);
  f[1] = 10.0 + 2.5 * cos(5.0 * t);
  f[2] = -12.5 * sin(5.0 * t);
  return 0;
}

/* Angular momenta of the driven base's exact motion at t (inertial frame):
 * hr the rotor's, R I_r R^T (a' e_z + b' e1) with R = R_z(a) R_x(b) and
 * e1 = R_z(a) e_x its axis; hz the z component of the base's and the
 * rotor's together. */
static void DrivenMomenta(double t, double hr[3], double *hz, double e1[3])
{
  const double Jr[3] = {0.5, 0.3, 0.3};
  const double a = 0.5 * sin(2.0 * t), ad = cos(2.0 * t);
  const double b = 10.0 * t + 0.5 * sin(5.0 * t), bd = 10.0 + 2.5 * cos(5.0 * t);
  const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
  /* R = Rz(a) Rx(b), columns */
  const double R[3][3] = {{ca, -sa * cb, sa * sb}, {sa, ca * cb, -ca * sb}, {0.0, sb, cb}};
  double w[3], wb[3];
  int i, j;
  e1[0] = ca; e1[1] = sa; e1[2] = 0.0;
  for (i = 0; i < 3; i++) w[i] = bd * e1[i] + (i == 2 ? ad : 0.0);
  for (j = 0; j < 3; j++) { /* body frame: R^T w, times J */
    wb[j] = 0.0;
    for (i = 0; i < 3; i++) wb[j] += R[i][j] * w[i];
    wb[j] *= Jr[j];
  }
  for (i = 0; i < 3; i++) {
    hr[i] = 0.0;
    for (j = 0; j < 3; j++) hr[i] += R[i][j] * wb[j];
  }
  *hz = hr[2] + ad; /* the base: J = I, w = a' e_z */
}

/* The driven base's driver multipliers (minus the motor torques): the
 * base's -d/dt (H_base + H_rotor) . e_z, the rotor's -dH_rotor/dt . e1
 * (the joints carry the other components), by the five-point central
 * difference (step 1e-4). */
static void DrivenExact(double t, double *lam_base, double *lam_rotor)
{
  const double d = 1e-4, c[4] = {-1.0 / 12.0, 8.0 / 12.0, -8.0 / 12.0, 1.0 / 12.0};
  const double off[4] = {2.0, 1.0, -1.0, -2.0};
  double hr[3], hz, e1[3], dhr[3] = {0, 0, 0}, dhz = 0.0;
  int k, i;
  for (k = 0; k < 4; k++) {
    DrivenMomenta(t + off[k] * d, hr, &hz, e1);
    for (i = 0; i < 3; i++) dhr[i] += c[k] * hr[i] / d;
    dhz += c[k] * hz / d;
  }
  DrivenMomenta(t, hr, &hz, e1);
  *lam_base  = -dhz;
  *lam_rotor = -(dhr[0] * e1[0] + dhr[1] * e1[1] + dhr[2] * e1[2]);
}

/* Inertias of the slider-crank (test_driven.c). */
static const double Jc[3] = {0.01, 0.01, 0.01}, Jr[3] = {0.001, 0.03, 0.03};

/* The slider-crank's kinetic energy at t on its exact motion: crank about
 * its centre (the origin), rod (mass 1, J_z 0.03 about its centre) between
 * the pin and the slider, slider (mass 1) along x. */
static double CrankEnergy(double t)
{
  const double th = 2.0 * PI * t, w = 2.0 * PI;
  const double s = R_CRANK * sin(th), sq = sqrt(L_ROD * L_ROD - s * s);
  const double x = R_CRANK * cos(th) + sq;
  const double xd = -R_CRANK * sin(th) * w - s * R_CRANK * cos(th) * w / sq;
  /* rod: from the pin (r cos, r sin) to (x, 0); angle phi, sin phi = -s / L */
  const double pxd = -R_CRANK * sin(th) * w, pyd = R_CRANK * cos(th) * w;
  const double cxd = 0.5 * (pxd + xd), cyd = 0.5 * pyd;
  const double phid = -(R_CRANK * cos(th) * w) / (L_ROD * (sq / L_ROD));
  (void)x;
  return 0.5 * Jc[2] * w * w + 0.5 * (cxd * cxd + cyd * cyd) + 0.5 * Jr[2] * phid * phid +
         0.5 * xd * xd;
}

/* The exact driver multiplier (minus the motor torque) at t. */
static double ExactDriver(int model, double t)
{
  const double d = 2e-4;
  double dT;
  if (model == ROTOR) return 9.0 * sin(3.0 * t);
  /* tau thetadot = dT/dt, lambda = -tau; dT/dt by the five-point central
   * difference (error d^4 T^(5) / 30 ~ 1e-13, roundoff ~ eps T / d) */
  dT = (8.0 * (CrankEnergy(t + d) - CrankEnergy(t - d)) -
        (CrankEnergy(t + 2 * d) - CrankEnergy(t - 2 * d))) / (12.0 * d);
  return -dT / (2.0 * PI);
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}
static int ConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  return LGNJoints_TimeDerivative(((Model *)ud)->joints, t, q, phit) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}

/* The model's group, bodies, joints and start (q, v made here). */
static LGNGroup Build(SUNContext ctx, int model, Model *md, LGNGroup body, N_Vector *q,
                      N_Vector *v)
{
  const double ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0}, o[3] = {0, 0, 0};
  LGNGroup f3[3], G;
  double *qd;
  int b, nb = model == ROTOR ? 1 : model == DRIVEN_BASE ? 2 : 3;
  for (b = 0; b < nb; b++) f3[b] = body;
  G = nb == 1 ? body : LGNGroup_Product(nb, f3);
  md->model  = model;
  md->bodies = LGNBodies_Create(G);
  md->joints = LGNJoints_Create(G);
  if (model == ROTOR) {
    const double J[3] = {1.0, 1.0, 2.0};
    LGNBodies_SetPrincipalInertia(md->bodies, 0, 1.0, J);
    LGNJoints_AddRevolute(md->joints, LGN_GROUND, o, ez, 0, o, ez);
    LGNJoints_AddRotationDriver(md->joints, LGN_GROUND, ez, ex, 0, ex, RotorLaw, NULL);
  } else if (model == DRIVEN_BASE) {
    const double Jb[3] = {1.0, 1.0, 1.0}, Jr_[3] = {0.5, 0.3, 0.3}, ey[3] = {0, 1, 0};
    LGNBodies_SetPrincipalInertia(md->bodies, 0, 1.0, Jb);
    LGNBodies_SetPrincipalInertia(md->bodies, 1, 1.0, Jr_);
    LGNJoints_AddRevolute(md->joints, LGN_GROUND, o, ez, 0, o, ez);
    LGNJoints_AddRotationDriver(md->joints, LGN_GROUND, ez, ex, 0, ex, BaseLaw, NULL);
    LGNJoints_AddRevolute(md->joints, 0, o, ex, 1, o, ex);
    LGNJoints_AddRotationDriver(md->joints, 0, ex, ey, 1, ey, SpinLaw, NULL);
  } else {
    const double pin[3] = {R_CRANK, 0, 0}, rod_a[3] = {-L_ROD / 2, 0, 0};
    const double rod_b[3] = {L_ROD / 2, 0, 0};
    LGNBodies_SetPrincipalInertia(md->bodies, 0, 1.0, Jc);
    LGNBodies_SetPrincipalInertia(md->bodies, 1, 1.0, Jr);
    LGNBodies_SetPrincipalInertia(md->bodies, 2, 1.0, Jc);
    LGNJoints_AddRevolute(md->joints, LGN_GROUND, o, ez, 0, o, ez);
    LGNJoints_AddRotationDriver(md->joints, LGN_GROUND, ez, ex, 0, ex, CrankLaw, NULL);
    LGNJoints_AddSpherical(md->joints, 0, pin, 1, rod_a);
    LGNJoints_AddSpherical(md->joints, 1, rod_b, 2, o);
    LGNJoints_AddPrismatic(md->joints, LGN_GROUND, o, ex, 2, o, ex);
  }
  *q = N_VNew_Serial(G->nq, ctx);
  *v = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(*q);
  LGNGroup_Identity(G, qd);
  if (model == SLIDER_CRANK) {
    qd[7]  = R_CRANK + L_ROD / 2;
    qd[14] = R_CRANK + L_ROD;
  }
  N_VConst(0.0, *v);
  return G;
}

/* ---- one run --------------------------------------------------------------- */

typedef struct {
  int model, bdf, index, mode;
  double tol;
  sunbooleantype consistent;
  int project;        /* LGN_PROJECT_*, -1: the default */
  double lambda_atol; /* > 0: LGNSetMultiplierErrorControl on */
} Setup;

typedef struct {
  double lam_err;   /* max |lambda - exact| over the outputs            */
  double lam_max;   /* max |lambda_exact|                               */
  double phi, bv;   /* max |Phi|, |B v + Phi_t| at the outputs          */
  double dky_diff;  /* max |LGNGetDky(tret, 2) - LGNGetAcceleration|    */
  double balance;   /* max |M vdot + g + B^T lambda| (joint helpers)    */
  long int nst, nout;
  int flag;
} Result;

/* The checks at one output (t, q, v): the multipliers against the exact
 * ones, the constraints, LGNGetDky against the getters, the balance. */
static void AtOutput(void *mem, Model *md, const Setup *s, double t, N_Vector q, N_Vector v,
                     sunindextype m, Result *r)
{
  SUNContext ctx = q->sunctx;
  const sunindextype nv = N_VGetLength(v);
  N_Vector lam = N_VNew_Serial(m, ctx), phi = N_VNew_Serial(m, ctx);
  N_Vector phit = N_VNew_Serial(m, ctx), vd = N_VNew_Serial(nv, ctx);
  N_Vector vd2 = N_VNew_Serial(nv, ctx), g = N_VNew_Serial(nv, ctx);
  N_Vector f = N_VNew_Serial(nv, ctx);
  SUNMatrix B = SUNDenseMatrix(m, nv, ctx), M = SUNDenseMatrix(nv, nv, ctx);
  double *l = N_VGetArrayPointer(lam);
  sunindextype i, j, drv = 5; /* the driver's row: after the revolute's five */

  LGNGetMultipliers(mem, lam);
  if (s->model == DRIVEN_BASE) { /* rows 5 (base) and 11 (rotor) */
    double lb, lr;
    DrivenExact(t, &lb, &lr);
    r->lam_max = fmax(r->lam_max, fmax(fabs(lb), fabs(lr)));
    r->lam_err = fmax(r->lam_err, fmax(fabs(l[5] - lb), fabs(l[11] - lr)));
  } else {
    const double exact = ExactDriver(s->model, t);
    r->lam_max = fmax(r->lam_max, fabs(exact));
    r->lam_err = fmax(r->lam_err, fabs(l[drv] - exact));
  }
  if (s->model == ROTOR)
    for (i = 0; i < 5; i++) r->lam_err = fmax(r->lam_err, fabs(l[i]));

  LGNJoints_Residual(md->joints, t, q, phi);
  r->phi = fmax(r->phi, N_VMaxNorm(phi));
  SUNMatZero(B);
  LGNJoints_Jacobian(md->joints, t, q, B);
  LGNJoints_TimeDerivative(md->joints, t, q, phit);
  for (i = 0; i < m; i++) {
    double s_ = N_VGetArrayPointer(phit)[i];
    for (j = 0; j < nv; j++) s_ += SM_ELEMENT_D(B, i, j) * N_VGetArrayPointer(v)[j];
    r->bv = fmax(r->bv, fabs(s_));
  }

  LGNGetAcceleration(mem, vd);
  if (LGNGetDky(mem, t, 2, vd2) == LGN_SUCCESS) {
    N_VLinearSum(1.0, vd2, -1.0, vd, vd2);
    r->dky_diff = fmax(r->dky_diff, N_VMaxNorm(vd2) / fmax(1.0, N_VMaxNorm(vd)));
  } else {
    r->dky_diff = HUGE_VAL;
  }
  /* M vdot + g + B^T lambda = 0 with the joint helpers' B^T lambda */
  SUNMatZero(M);
  LGNBodies_MassFn(t, q, M, md->bodies);
  N_VConst(0.0, g);
  LGNBodies_ForceFn(t, q, v, g, md->bodies);
  LGNJoints_ConstraintForce(md->joints, t, q, lam, f);
  for (i = 0; i < nv; i++) {
    double s_ = N_VGetArrayPointer(g)[i] + N_VGetArrayPointer(f)[i];
    for (j = 0; j < nv; j++) s_ += SM_ELEMENT_D(M, i, j) * N_VGetArrayPointer(vd)[j];
    r->balance = fmax(r->balance, fabs(s_));
  }
  N_VDestroy(lam); N_VDestroy(phi); N_VDestroy(phit); N_VDestroy(vd); N_VDestroy(vd2);
  N_VDestroy(g); N_VDestroy(f);
  SUNMatDestroy(B); SUNMatDestroy(M);
}

static Result Run(SUNContext ctx, const Setup *s)
{
  /* the checks over half the spans of the table (cheaper) */
  const double tend = (s->model == SLIDER_CRANK ? 0.5 : 1.0) * (full_spans ? 2.0 : 1.0);
  const double dt   = s->model == SLIDER_CRANK ? 0.125 : 0.1;
  LGNGroup body = LGNGroup_R3xSO3(), G;
  Model md;
  N_Vector q, v, y;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunrealtype t = 0.0;
  sunindextype m, n;
  Result r;
  int flag, k;

  memset(&r, 0, sizeof r);
  G    = Build(ctx, s->model, &md, body, &q, &v);
  m    = LGNJoints_NumConstraints(md.joints);
  n    = G->nv + (s->index == LGN_CONSTR_GGL ? 2 * m : m); /* GGL: lambda and mu */
  y    = N_VNew_Serial(n, ctx);
  A    = SUNDenseMatrix(n, n, ctx);
  LS   = LGNLinSol_Dense(y, A, ctx);
  mem  = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, ConstrTime);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = s->bdf ? LGNSetBDF(mem, 5) : LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetConstraintIndex(mem, s->index);
  if (s->tol > 0.0) { /* error control; tol < 0: fixed steps h = -tol */
    if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, s->tol, s->tol);
  } else if (!flag) {
    flag = LGNSetStepSize(mem, -s->tol);
  }
  /* GGL: both mechanisms are driven in all but (slider-crank) the rod's
   * spin, and GGL's error estimate (projected onto the constraints'
   * tangent space, where Phi = 0 and B v + Phi_t = 0 both hold at the step
   * ends) is then about 0: its steps double up to 1 s and jump to the other
   * root of the driver's sin(theta - f(t)) (a defect of the error test, not
   * of the outputs: the step's end values are exact but on the wrong
   * branch). A step limit keeps the runs on the branch. */
  if (!flag && s->index == LGN_CONSTR_GGL) flag = LGNSetMaxStep(mem, 0.02);
  /* the defaults (consistent outputs, LGN_PROJECT_ALL) unless told */
  if (!flag && !s->consistent) flag = LGNSetConsistentOutputs(mem, SUNFALSE);
  if (!flag && s->project >= 0) flag = LGNSetProjectOutputs(mem, s->project);
  if (!flag && s->lambda_atol > 0.0)
    flag = LGNSetMultiplierErrorControl(mem, SUNTRUE, s->lambda_atol);
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  if (s->mode == MODE_ONE_STEP) {
    while (!flag && t < tend) {
      flag = LGNSolve(mem, tend, &t, q, v, LGN_ONE_STEP);
      if (flag >= 0) AtOutput(mem, &md, s, t, q, v, m, &r);
    }
  } else {
    for (k = 1; !flag && k * dt <= tend + 1e-12; k++) {
      const double tout = k * dt;
      if (s->mode == MODE_TSTOP) flag = LGNSetStopTime(mem, tout);
      if (!flag) flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
      if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
      if (!flag) AtOutput(mem, &md, s, t, q, v, m, &r);
    }
  }
  r.flag = flag < 0 ? flag : 0;
  LGNGetNumSteps(mem, &r.nst);
  LGNGetNumOutputSolves(mem, &r.nout);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  if (G != body) LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  return r;
}

static const char *IndexName(int index)
{
  return index == LGN_CONSTR_INDEX3 ? "index 3" : index == LGN_CONSTR_INDEX2 ? "index 2" : "GGL";
}

int main(int argc, char **argv)
{
  const int indices[3] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2, LGN_CONSTR_GGL};
  const int table = argc > 1 && strcmp(argv[1], "--table") == 0;
  SUNContext ctx;
  int model, bdf, ii, mode;
  SUNContext_Create(NULL, &ctx);

  /* (a)-(c): every method, form and output mode at tol 1e-8 */
  for (model = 0; model < NMODEL; model++)
    for (bdf = 0; bdf < 2; bdf++)
      for (ii = 0; ii < 3; ii++)
        for (mode = 0; mode < 3; mode++) {
          Setup s = {model, bdf, indices[ii], mode, 1e-8, SUNTRUE, -1, 0.0};
          Result r = Run(ctx, &s);
          const char *name = bdf ? "BDF5" : "gen-alpha";
          printf("%-12s %-9s %-7s %-12s: %4ld steps, %4ld output solves, max|lambda err| "
                 "%.2e of max %.2f; |Phi| %.1e, |Bv+Phi_t| %.1e, Dky %.1e, balance %.1e\n",
                 model_name[model], name, IndexName(indices[ii]), mode_name[mode], r.nst,
                 r.nout, r.lam_err, r.lam_max, r.phi, r.bv, r.dky_diff, r.balance);
          CHECK(r.flag == 0, "%s %s %s: flag %d", name, IndexName(indices[ii]),
                mode_name[mode], r.flag);
          CHECK(r.lam_err <= 1e-5 * r.lam_max, "(a) %s %s %s %s: lambda error %.2e > 1e-5 x %.2f",
                model_name[model], name, IndexName(indices[ii]),
                mode_name[mode], r.lam_err, r.lam_max);
          CHECK(r.dky_diff <= 1e-12, "(b) LGNGetDky(tret, 2) vs LGNGetAcceleration: %.2e",
                r.dky_diff);
          CHECK(r.balance <= 1e-10 * fmax(1.0, r.lam_max), "(b) M vdot + g + B^T lambda: %.2e",
                r.balance);
          CHECK(r.phi <= 1e-12 && r.bv <= 1e-12, "(c) %s %s %s: |Phi| %.2e, |B v + Phi_t| %.2e",
                name, IndexName(indices[ii]), mode_name[mode], r.phi, r.bv);
        }

  /* (a), (c) with fixed steps (h = 1e-3; LGN_NORMAL: the Newmark family
   * lands on tout, BDF steps past it and interpolates), at index 3 and 2 */
  for (model = 0; model < NMODEL; model++)
    for (bdf = 0; bdf < 2; bdf++)
      for (ii = 0; ii < 2; ii++) {
        Setup s = {model, bdf, indices[ii], MODE_NORMAL, -1e-3, SUNTRUE, -1, 0.0};
        Result r = Run(ctx, &s);
        printf("fixed h = 1e-3: %-12s %-9s %-7s: max|lambda err| %.2e of max %.2f; |Phi| %.1e, "
               "|Bv+Phi_t| %.1e\n", model_name[model], bdf ? "BDF5" : "gen-alpha",
               IndexName(indices[ii]), r.lam_err, r.lam_max, r.phi, r.bv);
        CHECK(r.flag == 0 && r.lam_err <= 1e-5 * r.lam_max && r.phi <= 1e-12 && r.bv <= 1e-12,
              "(a, c) fixed steps %s %s %s: flag %d, lambda error %.2e, |Phi| %.2e, |B v + "
              "Phi_t| %.2e", model_name[model], bdf ? "BDF5" : "gen-alpha",
              IndexName(indices[ii]), r.flag, r.lam_err, r.phi, r.bv);
      }

  /* (d) the lambda error falls with the tolerance (slider-crank, stop
   * times, index 3): without the projection, since with it these driven
   * outputs are on the exact motion and their multipliers exact to
   * roundoff (the rotor's are exact either way: its one coordinate is
   * fixed by Phi, its curvature does not depend on v) */
  for (model = SLIDER_CRANK; model < 2; model++)
    for (bdf = 0; bdf < 2; bdf++) {
      const double tols[3] = {1e-5, 1e-7, 1e-9};
      double err[3];
      int k;
      for (k = 0; k < 3; k++) {
        Setup s = {model, bdf, LGN_CONSTR_INDEX3, MODE_TSTOP, tols[k], SUNTRUE,
                   LGN_PROJECT_NONE, 0.0};
        Result r = Run(ctx, &s);
        err[k] = r.flag == 0 ? r.lam_err : HUGE_VAL;
      }
      printf("(d) %s %s, stop times, index 3: lambda error %.2e / %.2e / %.2e at tol "
             "1e-5 / 1e-7 / 1e-9\n", model_name[model],
             bdf ? "BDF5" : "gen-alpha", err[0], err[1], err[2]);
      CHECK(err[2] < 0.1 * err[0] && err[1] < err[0],
            "(d) the lambda error does not fall with the tolerance: %.2e %.2e %.2e", err[0],
            err[1], err[2]);
    }

  /* (f) the multipliers in the error test: the step's own multipliers
   * (consistent outputs off) within 1e-5 of max |lambda| at tol 1e-8 and
   * atol_lambda = 1e-6, stop times and LGN_ONE_STEP, index 2 and GGL (at
   * index 3 it is refused: the multipliers are determined only to Newton's
   * tolerance ~ atol / h there) */
  for (model = ROTOR; model <= ROTOR; model++)
    for (bdf = 0; bdf < 2; bdf++)
      for (ii = 1; ii < 3; ii++)
      for (mode = 0; mode < 3; mode += 2) {
        Setup s = {model, bdf, indices[ii], mode, 1e-8, SUNFALSE, LGN_PROJECT_ALL, 1e-6};
        Result r = Run(ctx, &s);
        printf("(f) %s %s %s %s: the step's own lambda error %.2e with the multipliers in "
               "the error test (%ld steps)\n", model_name[model], bdf ? "BDF5" : "gen-alpha",
               IndexName(indices[ii]), mode_name[mode], r.lam_err, r.nst);
        CHECK(r.flag == 0 && r.lam_err <= 1e-5 * r.lam_max,
              "(f) %s %s %s %s: the step's own lambda error %.2e > 1e-5 x %.2f (flag %d)",
              model_name[model], bdf ? "BDF5" : "gen-alpha",
              IndexName(indices[ii]), mode_name[mode], r.lam_err, r.lam_max, r.flag);
      }

  /* (e) without the projection, interpolated outputs leave the constraints */
  {
    Setup s = {ROTOR, 0, LGN_CONSTR_INDEX3, MODE_NORMAL, 1e-6, SUNTRUE, LGN_PROJECT_NONE, 0.0};
    Result r = Run(ctx, &s);
    printf("(e) rotor, gen-alpha, index 3, tol 1e-6, LGN_NORMAL, not projected: |Phi| %.2e, "
           "|B v + Phi_t| %.2e\n", r.phi, r.bv);
    CHECK(r.flag == 0 && fmax(r.phi, r.bv) > 1e-10,
          "(e) unprojected outputs on the constraints to %.2e: the test of (c) proves nothing",
          fmax(r.phi, r.bv));
  }
  {
    /* index 3: the multipliers in the error test refused by LGNSolve */
    Setup s = {ROTOR, 0, LGN_CONSTR_INDEX3, MODE_NORMAL, 1e-8, SUNFALSE, LGN_PROJECT_ALL, 1e-6};
    Result r = Run(ctx, &s);
    CHECK(r.flag == LGN_ILL_INPUT && r.nst == 0,
          "(e) LGNSetMultiplierErrorControl at index 3: flag %d after %ld steps, not refused",
          r.flag, r.nst);
  }
  {
    void *mem = LGNCreate(ctx);
    LGNSetErrFile(mem, NULL);
    CHECK(LGNSetConsistentOutputs(mem, 2) == LGN_ILL_INPUT &&
              LGNSetProjectOutputs(mem, -1) == LGN_ILL_INPUT &&
              LGNSetProjectOutputs(mem, 3) == LGN_ILL_INPUT &&
              LGNSetConsistentOutputs(NULL, SUNTRUE) == LGN_MEM_NULL &&
              LGNGetNumOutputSolves(mem, NULL) == LGN_ILL_INPUT &&
              LGNSetMultiplierErrorControl(mem, SUNTRUE, 0.0) == LGN_ILL_INPUT &&
              LGNSetMultiplierErrorControl(mem, SUNTRUE, NAN) == LGN_ILL_INPUT &&
              LGNSetMultiplierErrorControl(mem, 3, 1.0) == LGN_ILL_INPUT &&
              LGNSetMultiplierErrorControl(mem, SUNFALSE, 0.0) == LGN_SUCCESS,
          "(e) bad input accepted");
    LGNFree(&mem);
  }

  /* the table of the user guide (--table): before / after at three tolerances */
  full_spans = table;
  if (table)
    for (model = 0; model < NMODEL; model++)
      for (bdf = 0; bdf < 2; bdf++)
        for (mode = 0; mode < 3; mode += 2) {
          const double tols[3] = {1e-6, 1e-8, 1e-10};
          static const char *variant[3] = {"step's own", "consistent, not projected",
                                           "consistent, projected (default)"};
          int k, c;
          for (c = 0; c < 3; c++) {
            printf("| %s | %s | %s | %s |", model_name[model],
                   bdf ? "BDF5" : "gen-alpha", mode_name[mode], variant[c]);
            for (k = 0; k < 3; k++) {
              Setup s = {model, bdf, LGN_CONSTR_INDEX3, mode, tols[k], (sunbooleantype)(c > 0),
                         c == 2 ? LGN_PROJECT_ALL : LGN_PROJECT_NONE, 0.0};
              Result r = Run(ctx, &s);
              printf(" %.1e |", r.flag == 0 ? r.lam_err : HUGE_VAL);
            }
            printf("\n");
          }
        }
  SUNContext_Free(&ctx);
  return test_summary("test_output_multipliers");
}
