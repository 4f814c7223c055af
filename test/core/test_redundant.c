/* -----------------------------------------------------------------------------
 * Lignum test: redundant but consistent constraints run (LGN_REDUNDANT_ELIMINATE,
 * the default), and inconsistent ones are flagged.
 *
 *  (a) the all-revolute planar four-bar built in space (3 rods on 4
 *      revolute joints: 20 rows of rank 17, one degree of freedom), released
 *      from rest under gravity, against a minimal-coordinate reference (the
 *      crank angle, Lagrange's equation integrated by RK4 with dt = 1e-4):
 *      the coupler-rocker joint's position over 2 s within 3e-5 at tol 1e-9
 *      (BDF) and 1e-7 (generalized-alpha, whose control is per unit step)
 *      (FB_ERR: the integrators' own error; a wrong elimination is O(0.1));
 *      dense and KLU, index 3, index 2 and GGL, generalized-alpha and BDF;
 *      one warning naming the 3 rows left out, LGNGetRedundantConstraints
 *      lists them, their multipliers are 0;
 *  (b) Bricard's mechanism (five 1 m, 1 kg rods with 0.1 m square
 *      section on six revolute joints along a skew hexagon of a unit cube's
 *      edges, consecutive axes perpendicular; gravity -y; 30 rows of rank
 *      29, one degree of freedom), released from rest, against the same
 *      mechanism with the last revolute replaced by a universal joint
 *      (29 rows, independent: nothing left out): the corner point P3 and the
 *      total energy over 10 s within 1e-6 at tol 1e-10 (BDF; at tol 1e-9
 *      they differ by 1.3e-6 and 6.5e-7), dense; KLU over 2 s;
 *  (c) inconsistent redundancy: a body pinned twice, the second pin moving
 *      away (rheonomic): the rows left out drift off and LGNSolve stops
 *      with LGN_REDUNDANT_INCONSISTENT soon after; two different pins from
 *      the start: flagged by LGNCalcIC / the first LGNSolve;
 *  (d) LGN_REDUNDANT_REFUSE restores the refusal (LGN_IC_FAIL naming the
 *      rows, test_singular); a bad mode is refused.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include "test_util.h"

#define GRAV 9.81
#define LGN_PI 3.14159265358979323846

/* ---- the handler: warnings counted, the last message kept ---------------- */

static char last_msg[2048];
static int nwarn;
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)module; (void)d;
  if (code == LGN_WARNING) nwarn++;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

/* ---- a model from the body and joint helpers ---------------------------- */

typedef struct {
  LGNBodies B;
  LGNJoints J;
  double drift; /* (c): the second pin's speed along x (0: none) */
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t;
  return LGNBodies_Mass(((Model *)ud)->B, q, M);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t;
  return LGNBodies_Force(((Model *)ud)->B, q, v, g);
}
static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const Model *md = (const Model *)ud;
  int flag = LGNJoints_Residual(md->J, t, q, phi);
  if (md->drift != 0.0) N_VGetArrayPointer(phi)[3] -= md->drift * t; /* (c) */
  return flag;
}
static int PhiT(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  const Model *md = (const Model *)ud;
  int flag = LGNJoints_TimeDerivative(md->J, t, q, phit);
  N_VGetArrayPointer(phit)[3] -= md->drift;
  return flag;
}
static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->J, t, q, B);
}
static int Curv(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->J, t, q, v, z);
}

/* A rod body with R = I at its midpoint: principal inertia of a rod of
 * length L along body axis `axis` with an a x a section. */
static void RodInertia(LGNBodies B, int k, double L, double a, int axis)
{
  double J[3];
  int i;
  for (i = 0; i < 3; i++) J[i] = (L * L + a * a) / 12.0;
  J[axis] = (a * a + a * a) / 12.0;
  LGNBodies_SetPrincipalInertia(B, k, 1.0, J);
}

static void SetPose(double *qd, int k, const double x[3])
{
  qd[7 * k] = x[0]; qd[7 * k + 1] = x[1]; qd[7 * k + 2] = x[2];
  qd[7 * k + 3] = 1.0; qd[7 * k + 4] = qd[7 * k + 5] = qd[7 * k + 6] = 0.0;
}

/* ---- one run: the options and its outputs ------------------------------- */

typedef struct {
  int sparse, index, bdf;
  int calcic;            /* LGNCalcIC(LGN_IC_PROJECT_QV) first */
  double tol, tf;
  int nout;              /* outputs at tf k / nout */
  void (*out)(int k, double t, N_Vector q, N_Vector v, void *ctx);
  void *ctx;
} RunOpts;

typedef struct {
  int flag;               /* of the last call */
  double t;               /* where it stopped */
  sunindextype nred, rows[32];
  double ic_phi, ic_bv;   /* calcic: |Phi|, |B v| of all rows at the projected start */
  double lambda[32];      /* LGNGetMultipliers at the end */
  int nwarn;
} RunResult;

static RunResult Run(Model *md, LGNGroup G, N_Vector q0, N_Vector v0, sunindextype m,
                     const RunOpts *o)
{
  RunResult res;
  SUNContext ctx = NULL;
  const sunindextype nv = N_VGetLength(v0);
  N_Vector qo, vo, lam;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem;
  double t = 0.0;
  int flag, k;

  memset(&res, 0, sizeof res);
  SUNContext_Create(NULL, &ctx);
  qo   = N_VClone(q0);
  vo   = N_VClone(v0);
  lam  = N_VNew_Serial(m, ctx);
  nwarn = 0;
  mem   = LGNCreate(ctx);
  flag  = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetErrHandlerFn(mem, Capture, NULL);
  if (!flag) flag = LGNSetUserData(mem, md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Phi, Jac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curv);
  if (!flag && md->drift != 0.0) flag = LGNSetConstraintTimeFn(mem, PhiT);
  if (!flag) flag = LGNInit(mem, 0.0, q0, v0);
  if (!flag) flag = LGNSetConstraintIndex(mem, o->index);
  if (!flag && o->bdf) flag = LGNSetBDF(mem, 5);
  {
    /* sized for the user's m rows: Lignum makes a solver of the same kind
     * for the rows it keeps */
    const sunindextype nk = nv + (o->index == LGN_CONSTR_GGL ? 2 : 1) * m;
    N_Vector y = N_VNew_Serial(nk, ctx);
    if (!o->sparse) {
      A  = SUNDenseMatrix(nk, nk, ctx);
      LS = SUNLinSol_Dense(y, A, ctx);
    } else {
#if defined(LGN_HAVE_KLU)
      A  = SUNSparseMatrix(nk, nk, nk * 20, CSC_MAT, ctx);
      LS = SUNLinSol_KLU(y, A, ctx);
#endif
    }
    N_VDestroy(y);
  }
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, o->tol, o->tol);
  if (!flag) flag = LGNSetMaxNumSteps(mem, 200000);
  if (!flag && o->calcic) {
    /* the projected start against all of the user's rows */
    SUNMatrix Bf = SUNDenseMatrix(m, nv, ctx);
    N_Vector phi = N_VNew_Serial(m, ctx), bv = N_VNew_Serial(m, ctx);
    flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
    if (!flag) flag = LGNGetConsistentIC(mem, qo, vo);
    if (!flag) {
      SUNMatZero(Bf);
      Phi(0.0, qo, phi, md);
      Jac(0.0, qo, Bf, md);
      SUNMatMatvec(Bf, vo, bv);
      res.ic_phi = N_VMaxNorm(phi);
      res.ic_bv  = N_VMaxNorm(bv);
    }
    SUNMatDestroy(Bf);
    N_VDestroy(phi);
    N_VDestroy(bv);
  }
  for (k = 1; !flag && k <= o->nout; k++) {
    flag = LGNSolve(mem, o->tf * k / o->nout, &t, qo, vo, LGN_NORMAL);
    if (!flag && o->out != NULL) o->out(k, t, qo, vo, o->ctx);
  }
  res.flag  = flag;
  res.t     = t;
  res.nwarn = nwarn;
  LGNGetRedundantConstraints(mem, &res.nred, res.rows);
  if (LGNGetMultipliers(mem, lam) == LGN_SUCCESS && flag == LGN_SUCCESS)
    for (k = 0; k < m && k < 32; k++) res.lambda[k] = N_VGetArrayPointer(lam)[k];
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(qo);
  N_VDestroy(vo);
  N_VDestroy(lam);
  SUNContext_Free(&ctx);
  return res;
}

/* =============================================================================
 * (a) The four-bar and its minimal-coordinate reference
 * ===========================================================================*/

static const double L1 = 0.3, L2 = 1.0, L3 = 0.8; /* crank, coupler, rocker */

/* The four-bar at crank angle th: joint points B, C, the rods' centres
 * x[k] and angles phi[k] (A = 0, D = (1, 0, 0); the branch of test_singular). */
static void FourBarAt(double th, double B[2], double C[2], double x[3][2], double phi[3])
{
  const double D[2] = {1.0, 0.0};
  double d, a, hh, mid[2];
  B[0] = L1 * cos(th);
  B[1] = L1 * sin(th);
  d    = hypot(D[0] - B[0], D[1] - B[1]);
  a    = (L2 * L2 - L3 * L3 + d * d) / (2 * d);
  hh   = sqrt(L2 * L2 - a * a);
  mid[0] = B[0] + a * (D[0] - B[0]) / d;
  mid[1] = B[1] + a * (D[1] - B[1]) / d;
  C[0] = mid[0] - hh * (D[1] - B[1]) / d;
  C[1] = mid[1] + hh * (D[0] - B[0]) / d;
  x[0][0] = 0.5 * B[0]; x[0][1] = 0.5 * B[1];
  x[1][0] = 0.5 * (B[0] + C[0]); x[1][1] = 0.5 * (B[1] + C[1]);
  x[2][0] = 0.5 * (D[0] + C[0]); x[2][1] = 0.5 * (D[1] + C[1]);
  phi[0] = th;
  phi[1] = atan2(C[1] - B[1], C[0] - B[0]);
  phi[2] = atan2(C[1] - D[1], C[0] - D[0]);
}

/* unit masses, J_z = L^2/12 (+ the section's, 0 here: a = 0.02) */
static double Jz(int k) { const double L[3] = {L1, L2, L3}; return (L[k] * L[k] + 4e-4) / 12.0; }

/* the generalised mass m(th) = sum |dx_k/dth|^2 + J_k (dphi_k/dth)^2 and
 * the potential V(th) = g sum y_k, by 4th-order central differences */
static double GenMass(double th)
{
  const double e = 1e-3;
  double B[2], C[2], x[4][3][2], phi[4][3], m = 0.0;
  const double s[4] = {-2, -1, 1, 2};
  int j, k, i;
  for (j = 0; j < 4; j++) FourBarAt(th + s[j] * e, B, C, x[j], phi[j]);
  for (k = 0; k < 3; k++) {
    for (i = 0; i < 2; i++) {
      const double dx = (x[0][k][i] - 8 * x[1][k][i] + 8 * x[2][k][i] - x[3][k][i]) / (12 * e);
      m += dx * dx;
    }
    {
      double p[4], dp;
      for (j = 0; j < 4; j++) p[j] = phi[j][k];
      for (j = 1; j < 4; j++) p[j] += 2 * LGN_PI * floor((p[0] - p[j]) / (2 * LGN_PI) + 0.5);
      dp = (p[0] - 8 * p[1] + 8 * p[2] - p[3]) / (12 * e);
      m += Jz(k) * dp * dp;
    }
  }
  return m;
}

static double Potential(double th)
{
  double B[2], C[2], x[3][2], phi[3];
  FourBarAt(th, B, C, x, phi);
  return GRAV * (x[0][1] + x[1][1] + x[2][1]);
}

static double D4(double (*f)(double), double th)
{
  const double e = 1e-3;
  return (f(th - 2 * e) - 8 * f(th - e) + 8 * f(th + e) - f(th + 2 * e)) / (12 * e);
}

/* Lagrange: m th'' + m'/2 th'^2 + V' = 0 */
static void Rhs(const double y[2], double f[2])
{
  f[0] = y[1];
  f[1] = -(0.5 * D4(GenMass, y[0]) * y[1] * y[1] + D4(Potential, y[0])) / GenMass(y[0]);
}

#define FB_NOUT 20
#define FB_TF   2.0
#define FB_TOL  1e-9
/* generalized-alpha's error control is per unit step (steps ~ tol^(-1/2)):
 * tol 1e-7 gives it errors of the order of BDF's at 1e-9 */
#define FB_TOL_GA 1e-7
/* a wrong elimination moves C by O(0.1); the integrators' own global error
 * at tol 1e-9 over 2 s is 1e-6 (index 3) to 2e-5 (index 2, GGL with
 * generalized-alpha), and falls with the tolerance (8e-7 and 6e-6 at 1e-10) */
#define FB_ERR  3e-5
static double fb_ref[FB_NOUT + 1][2]; /* C at t_k = k TF / NOUT */

static void FourBarReference(double th0)
{
  double y[2] = {th0, 0.0}, k1[2], k2[2], k3[2], k4[2], yt[2];
  const int nsub = 1000; /* dt = 1e-4 */
  const double dt = FB_TF / FB_NOUT / nsub;
  int k, s, i;
  for (k = 0; k <= FB_NOUT; k++) {
    double B[2], x[3][2], phi[3];
    if (k > 0)
      for (s = 0; s < nsub; s++) {
        Rhs(y, k1);
        for (i = 0; i < 2; i++) yt[i] = y[i] + 0.5 * dt * k1[i];
        Rhs(yt, k2);
        for (i = 0; i < 2; i++) yt[i] = y[i] + 0.5 * dt * k2[i];
        Rhs(yt, k3);
        for (i = 0; i < 2; i++) yt[i] = y[i] + dt * k3[i];
        Rhs(yt, k4);
        for (i = 0; i < 2; i++) y[i] += dt / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      }
    FourBarAt(y[0], B, fb_ref[k], x, phi);
  }
}

/* the deviation of C (body 1's end: x_1 + R_1 s) from the reference */
typedef struct { double s[3]; double err; } FourBarOut;

static void Rotate(const double *quat, const double s[3], double out[3])
{
  const double w = quat[0], x = quat[1], y = quat[2], z = quat[3];
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  int i;
  for (i = 0; i < 3; i++) out[i] = R[i][0] * s[0] + R[i][1] * s[1] + R[i][2] * s[2];
}

static void FourBarOutput(int k, double t, N_Vector q, N_Vector v, void *ctx)
{
  FourBarOut *o = (FourBarOut *)ctx;
  const double *qd = N_VGetArrayPointer(q);
  double c[3];
  (void)t; (void)v;
  Rotate(qd + 7 + 3, o->s, c);
  o->err = fmax(o->err, hypot(qd[7] + c[0] - fb_ref[k][0], qd[8] + c[1] - fb_ref[k][1]));
}

static void FourBar(void)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G, f[3];
  Model md;
  const double th0 = LGN_PI / 3, z[3] = {0, 0, 1}, A[3] = {0, 0, 0}, D[3] = {1, 0, 0};
  double B2[2], C2[2], x2[3][2], phi[3], x[3][3], B[3], C[3], g[3] = {0, -GRAV, 0}, *qd;
  N_Vector q, v;
  sunindextype m, i;
  int k, c;
  static const struct { int sparse, index, bdf; const char *name; } cases[] = {
    {0, LGN_CONSTR_INDEX3, 0, "dense, index 3, generalized-alpha"},
    {0, LGN_CONSTR_INDEX2, 0, "dense, index 2, generalized-alpha"},
    {0, LGN_CONSTR_GGL, 0, "dense, GGL, generalized-alpha"},
    {0, LGN_CONSTR_INDEX3, 1, "dense, index 3, BDF"},
    {0, LGN_CONSTR_GGL, 1, "dense, GGL, BDF"},
    {1, LGN_CONSTR_INDEX3, 0, "KLU, index 3, generalized-alpha"},
    {1, LGN_CONSTR_INDEX2, 1, "KLU, index 2, BDF"}};

  SUNContext_Create(NULL, &ctx);
  FourBarReference(th0);
  f[0] = f[1] = f[2] = body;
  G    = LGNGroup_Product(3, f);
  md.J = LGNJoints_Create(G);
  md.B = LGNBodies_Create(G);
  md.drift = 0.0;
  LGNBodies_SetGravity(md.B, g);
  FourBarAt(th0, B2, C2, x2, phi);
  B[0] = B2[0]; B[1] = B2[1]; B[2] = 0; C[0] = C2[0]; C[1] = C2[1]; C[2] = 0;
  q  = N_VNew_Serial(21, ctx);
  v  = N_VNew_Serial(18, ctx);
  N_VConst(0.0, v);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < 3; k++) {
    const double J[3] = {Jz(k), Jz(k), Jz(k)};
    x[k][0] = x2[k][0]; x[k][1] = x2[k][1]; x[k][2] = 0.0;
    SetPose(qd, k, x[k]);
    LGNBodies_SetPrincipalInertia(md.B, k, 1.0, J);
  }
  {
    double s0[3], s1[3];
    for (i = 0; i < 3; i++) s0[i] = A[i] - x[0][i];
    LGNJoints_AddRevolute(md.J, LGN_GROUND, A, z, 0, s0, z);
    for (i = 0; i < 3; i++) { s0[i] = B[i] - x[0][i]; s1[i] = B[i] - x[1][i]; }
    LGNJoints_AddRevolute(md.J, 0, s0, z, 1, s1, z);
    for (i = 0; i < 3; i++) { s0[i] = C[i] - x[1][i]; s1[i] = C[i] - x[2][i]; }
    LGNJoints_AddRevolute(md.J, 1, s0, z, 2, s1, z);
    for (i = 0; i < 3; i++) s0[i] = D[i] - x[2][i];
    LGNJoints_AddRevolute(md.J, 2, s0, z, LGN_GROUND, D, z);
  }
  m = LGNJoints_NumConstraints(md.J);
  CHECK(m == 20, "20 rows, got %lld", (long long)m);
  for (c = 0; c < (int)(sizeof cases / sizeof cases[0]); c++) {
    FourBarOut out;
    RunOpts o = {cases[c].sparse, cases[c].index, cases[c].bdf, 0,
                 cases[c].bdf ? FB_TOL : FB_TOL_GA, FB_TF, FB_NOUT, FourBarOutput, NULL};
    RunResult r;
    double lam_out = 0.0;
#if !defined(LGN_HAVE_KLU)
    if (cases[c].sparse) continue;
#endif
    memset(&out, 0, sizeof out);
    for (i = 0; i < 3; i++) out.s[i] = C[i] - x[1][i];
    o.ctx = &out;
    r     = Run(&md, G, q, v, m, &o);
    for (i = 0; i < r.nred && i < 3; i++) lam_out = fmax(lam_out, fabs(r.lambda[r.rows[i]]));
    printf("(a) four-bar, %-34s: %s, |C - C_ref| <= %.2e, %lld rows left out\n",
           cases[c].name, LGNGetReturnFlagName(r.flag), out.err, (long long)r.nred);
    CHECK(r.flag == LGN_SUCCESS, "four-bar (%s) runs: %s (%s)", cases[c].name,
          LGNGetReturnFlagName(r.flag), last_msg);
    CHECK(out.err <= FB_ERR, "four-bar (%s): C within 3e-5 of the reference, %.3e",
          cases[c].name, out.err);
    CHECK(r.nred == 3 && r.nwarn == 1, "three rows left out (%lld), one warning (%d)",
          (long long)r.nred, r.nwarn);
    CHECK(lam_out == 0.0, "multipliers of the rows left out are 0 (%g)", lam_out);
  }
  {
    /* LGNCalcIC from a start off the constraints (1e-4) with a velocity
     * off them: the rows are selected at that q0 (where the offset hides
     * a dependence: rank 18) and again at the projected one (rank 17),
     * which then satisfies all 20 rows */
    RunOpts o = {0, LGN_CONSTR_INDEX3, 0, 1, FB_TOL, 0.5, 5, NULL, NULL};
    RunResult r;
    N_Vector qp = N_VClone(q), vp = N_VClone(v);
    N_VScale(1.0, q, qp);
    N_VConst(0.0, vp);
    N_VGetArrayPointer(qp)[7] += 1e-4;
    N_VGetArrayPointer(qp)[8] -= 1e-4;
    N_VGetArrayPointer(vp)[5] = 2.0; /* the crank turning about z, and more */
    N_VGetArrayPointer(vp)[6] = 0.3;
    r = Run(&md, G, qp, vp, m, &o);
    printf("(a) four-bar, LGNCalcIC from a start 1e-4 off: %s, |Phi| = %.1e, |B v| = %.1e "
           "(all 20 rows), %lld rows left out, %d warnings (two selections)\n",
           LGNGetReturnFlagName(r.flag), r.ic_phi, r.ic_bv, (long long)r.nred, r.nwarn);
    CHECK(r.nwarn == 2, "two selections, each named once: %d warnings", r.nwarn);
    CHECK(r.flag == LGN_SUCCESS, "LGNCalcIC and the run: %s (%s)", LGNGetReturnFlagName(r.flag),
          last_msg);
    CHECK(r.ic_phi <= 1e-12 && r.ic_bv <= 1e-12 && r.nred == 3,
          "the projected start satisfies all 20 rows: %.2e, %.2e", r.ic_phi, r.ic_bv);
    N_VDestroy(qp);
    N_VDestroy(vp);
  }
  LGNJoints_Destroy(&md.J);
  LGNBodies_Destroy(&md.B);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}

/* =============================================================================
 * (b) Bricard's mechanism against the same with one universal joint
 * ===========================================================================*/

#define BR_NOUT 50
#define BR_TF   10.0
/* at tol 1e-10 the runs agree to 1.7e-7 (P3) and 6e-8 (energy) over 10 s;
 * at 1e-9 to 1.3e-6 and 6.5e-7: the integrator's own global error, which
 * falls 8x per decade of the tolerance in both runs */
#define BR_TOL  1e-10
typedef struct { double p3[BR_NOUT + 1][3], energy[BR_NOUT + 1]; Model *md; } BricardOut;

static void BricardOutput(int k, double t, N_Vector q, N_Vector v, void *ctx)
{
  BricardOut *o = (BricardOut *)ctx;
  const double *qd = N_VGetArrayPointer(q);
  const double s[3] = {0.0, 0.0, 0.5}; /* rod 2 runs along z: its end P3 */
  double c[3], T = 0.0, V = 0.0;
  int i;
  (void)t;
  Rotate(qd + 14 + 3, s, c);
  for (i = 0; i < 3; i++) o->p3[k][i] = qd[14 + i] + c[i];
  LGNBodies_Energy(o->md->B, q, v, &T, &V);
  o->energy[k] = T + V;
}

/* the skew hexagon of a unit cube's edges: rod k from P_k to P_{k+1}, the
 * ground from P5 to P0; the axis at P_k is normal to both edges there */
static void BuildBricard(Model *md, double *qd, int universal)
{
  static const double P[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, {0, 0, 1}};
  static const double axis[6][3] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0},
                                    {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
  static const int along[5] = {0, 1, 2, 0, 1}; /* the rods' directions */
  double x[5][3], sa[3], sb[3];
  int k, i;
  for (k = 0; k < 5; k++) {
    for (i = 0; i < 3; i++) x[k][i] = 0.5 * (P[k][i] + P[k + 1][i]);
    SetPose(qd, k, x[k]);
    RodInertia(md->B, k, 1.0, 0.1, along[k]);
  }
  for (i = 0; i < 3; i++) sb[i] = P[0][i] - x[0][i];
  LGNJoints_AddRevolute(md->J, LGN_GROUND, P[0], axis[0], 0, sb, axis[0]);
  for (k = 1; k < 5; k++) {
    for (i = 0; i < 3; i++) { sa[i] = P[k][i] - x[k - 1][i]; sb[i] = P[k][i] - x[k][i]; }
    LGNJoints_AddRevolute(md->J, k - 1, sa, axis[k], k, sb, axis[k]);
  }
  for (i = 0; i < 3; i++) sa[i] = P[5][i] - x[4][i];
  if (!universal) {
    LGNJoints_AddRevolute(md->J, 4, sa, axis[5], LGN_GROUND, P[5], axis[5]);
  } else { /* the revolute's axis on the rod, a normal one on the ground */
    const double ny[3] = {0, 1, 0};
    LGNJoints_AddUniversal(md->J, 4, sa, axis[5], LGN_GROUND, P[5], ny);
  }
}

static void Bricard(int sparse)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G, f[5];
  Model md[2];
  BricardOut out[2];
  RunResult r[2];
  N_Vector q[2], v;
  const double g[3] = {0, -GRAV, 0};
  double dp = 0.0, de = 0.0, moved = 0.0;
  int k, u, i;
  SUNContext_Create(NULL, &ctx);
  for (k = 0; k < 5; k++) f[k] = body;
  G = LGNGroup_Product(5, f);
  v = N_VNew_Serial(30, ctx);
  N_VConst(0.0, v);
  for (u = 0; u < 2; u++) {
    /* BDF (order up to 5); KLU over the first 2 s only (the same code) */
    RunOpts o = {sparse, LGN_CONSTR_INDEX3, 1, 0, BR_TOL, sparse ? 2.0 : BR_TF, BR_NOUT,
                 BricardOutput, NULL};
    md[u].J = LGNJoints_Create(G);
    md[u].B = LGNBodies_Create(G);
    md[u].drift = 0.0;
    LGNBodies_SetGravity(md[u].B, g);
    q[u] = N_VNew_Serial(35, ctx);
    BuildBricard(&md[u], N_VGetArrayPointer(q[u]), u);
    CHECK(LGNJoints_NumConstraints(md[u].J) == (u ? 29 : 30), "Bricard: %d rows",
          (int)LGNJoints_NumConstraints(md[u].J));
    out[u].md = &md[u];
    o.ctx     = &out[u];
    r[u]      = Run(&md[u], G, q[u], v, LGNJoints_NumConstraints(md[u].J), &o);
  }
  for (k = 1; k <= BR_NOUT; k++) {
    for (i = 0; i < 3; i++) dp = fmax(dp, fabs(out[0].p3[k][i] - out[1].p3[k][i]));
    de    = fmax(de, fabs(out[0].energy[k] - out[1].energy[k]));
    moved = fmax(moved, hypot(hypot(out[0].p3[k][0] - out[0].p3[1][0],
                                     out[0].p3[k][1] - out[0].p3[1][1]),
                               out[0].p3[k][2] - out[0].p3[1][2]));
  }
  printf("(b) Bricard (%s): %s / %s (universal), rows left out %lld / %lld, "
         "|P3 - P3_U| <= %.2e, |E - E_U| <= %.2e; P3 moved by %.2f; "
         "energy drift %.2e / %.2e\n",
         sparse ? "KLU" : "dense", LGNGetReturnFlagName(r[0].flag),
         LGNGetReturnFlagName(r[1].flag), (long long)r[0].nred, (long long)r[1].nred, dp, de,
         moved, out[0].energy[BR_NOUT] - out[0].energy[1],
         out[1].energy[BR_NOUT] - out[1].energy[1]);
  CHECK(r[0].flag == LGN_SUCCESS && r[1].flag == LGN_SUCCESS, "Bricard runs: %s", last_msg);
  CHECK(r[0].nred == 1 && r[1].nred == 0, "one row left out (%lld), none with the universal "
        "joint (%lld)", (long long)r[0].nred, (long long)r[1].nred);
  CHECK(dp <= 1e-6 && de <= 1e-6, "Bricard = Bricard with a universal joint: %.2e, %.2e", dp,
        de);
  CHECK(moved > 0.1, "the mechanism moves (P3 by %.2f)", moved);
  for (u = 0; u < 2; u++) {
    LGNJoints_Destroy(&md[u].J);
    LGNBodies_Destroy(&md[u].B);
    N_VDestroy(q[u]);
  }
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}

/* =============================================================================
 * (c) Inconsistent redundancy: a body pinned twice
 * ===========================================================================*/

static void PinnedTwice(double offset, double speed)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md;
  N_Vector q, v;
  const double g[3] = {0, -GRAV, 0}, a[3] = {0, 0, 0}, s[3] = {-0.5, 0, 0};
  double a2[3] = {0, 0, 0};
  RunResult r;
  RunOpts o = {0, LGN_CONSTR_INDEX3, 0, 0, 1e-8, 0.5, 50, NULL, NULL};
  SUNContext_Create(NULL, &ctx);
  md.J = LGNJoints_Create(G);
  md.B = LGNBodies_Create(G);
  md.drift = speed;
  LGNBodies_SetGravity(md.B, g);
  RodInertia(md.B, 0, 1.0, 0.1, 0);
  a2[0] = offset;
  LGNJoints_AddSpherical(md.J, LGN_GROUND, a, 0, s);
  LGNJoints_AddSpherical(md.J, LGN_GROUND, a2, 0, s);
  q = N_VNew_Serial(7, ctx);
  v = N_VNew_Serial(6, ctx);
  N_VConst(0.0, v);
  {
    const double x[3] = {0.5, 0, 0};
    SetPose(N_VGetArrayPointer(q), 0, x);
  }
  r = Run(&md, G, q, v, 6, &o);
  printf("(c) pinned twice, offset %g, drift %g: %s at t = %g\n    %s\n", offset, speed,
         LGNGetReturnFlagName(r.flag), r.t, last_msg);
  CHECK(r.flag == LGN_REDUNDANT_INCONSISTENT, "inconsistent redundancy flagged: %s",
        LGNGetReturnFlagName(r.flag));
  CHECK(strstr(last_msg, "not consistent") != NULL, "the message says so: %s", last_msg);
  if (speed > 0.0)
    CHECK(r.t > 0.0 && r.t < 0.1, "flagged soon after the pins part (t = %g)", r.t);
  LGNJoints_Destroy(&md.J);
  LGNBodies_Destroy(&md.B);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
}

static void BadMode(void)
{
  SUNContext ctx;
  void *mem;
  SUNContext_Create(NULL, &ctx);
  mem = LGNCreate(ctx);
  LGNSetErrHandlerFn(mem, Capture, NULL);
  CHECK(LGNSetRedundantConstraints(mem, 0) == LGN_ILL_INPUT &&
        strstr(last_msg, "mode") != NULL, "a bad mode is refused, naming it: %s", last_msg);
  CHECK(LGNSetRedundantConstraints(NULL, LGN_REDUNDANT_REFUSE) == LGN_MEM_NULL, "mem NULL");
  CHECK(LGNSetRedundantConstraints(mem, LGN_REDUNDANT_REFUSE) == LGN_SUCCESS, "refuse");
  LGNFree(&mem);
  SUNContext_Free(&ctx);
}

int main(void)
{
  FourBar();
  Bricard(0);
#if defined(LGN_HAVE_KLU)
  Bricard(1);
#endif
  PinnedTwice(1e-3, 0.0);
  PinnedTwice(0.0, 0.1);
  BadMode();
  return test_summary("test_redundant");
}
