/* -----------------------------------------------------------------------------
 * Lignum test: error control (LGN_STEP_ADAPTIVE).
 *
 *  (a) the local error estimate against the true one-step error (exact flow
 *      through the step's start) on SO(3) (torque-free symmetric top,
 *      analytic), R^3 x SO(3) (a free body under gravity, analytic) and R^2
 *      (a nonlinear oscillator, RK4 reference), for the simplified, exact and
 *      sigma kinematics: |estimate| / |true| in [0.8, 1.25], and the
 *      directions agree (cosine > 0.99);
 *  (b) tolerance proportionality on the heavy top (ARKODE reference) and a
 *      chain of 5 bodies (BDF5 reference): the error at t = 1 follows tol^p
 *      over four decades, p fitted near 1 (error per unit step);
 *  (c) order 2 under the step pattern H, H/4, H, H/4, ... (prescribed with
 *      hmin = hmax) for generalized-alpha, simplified and exact kinematics;
 *  (d) dense output: order 2 at step midpoints, continuity at step ends;
 *  (e) a rejected attempt leaves the state bit for bit: failures at the
 *      limits (error test, recoverable callback) return their flags with t
 *      and h in the message and the state as it was, and the step accepted
 *      after rejections equals that step taken directly;
 *  (f) the stop time is landed on exactly; the output grid does not change
 *      the solution; bad arguments of every new setter are refused with a
 *      message naming them.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "models/chain.h"
#include "models/heavy_top.h"
#include "lgn_reference.h"
#include "test_util.h"

static SUNContext ctx;

/* the kinematics variants by index */
static const int KIN[3] = {LGN_KINEMATICS_SIMPLIFIED, LGN_KINEMATICS_EXACT,
                           LGN_KINEMATICS_SIGMA};

/* =============================================================================
 * Models
 * ===========================================================================*/

/* A symmetric body: J = diag(J1, J1, J3), mass m; on SO(3) (nq 4, nv 3) or
 * R^3 x SO(3) (nq 7, nv 6) under gravity along -z; on R^2 the oscillator
 * x'' + x + x^3 = 0 in each component. */
typedef enum { SO3_TOP, R3SO3_BODY, R2_OSC } Model;

static const double J[3] = {0.234375, 0.234375, 0.46875};
#define MASS 2.0
#define GRAV 9.81

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const Model model = *(const Model *)ud;
  int i;
  (void)t;
  (void)q;
  if (model == R2_OSC) {
    SM_ELEMENT_D(M, 0, 0) = SM_ELEMENT_D(M, 1, 1) = 1.0;
    return 0;
  }
  for (i = 0; i < 3; i++) {
    if (model == R3SO3_BODY) SM_ELEMENT_D(M, i, i) = MASS;
    SM_ELEMENT_D(M, i + (model == R3SO3_BODY ? 3 : 0), i + (model == R3SO3_BODY ? 3 : 0)) = J[i];
  }
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const Model model = *(const Model *)ud;
  const double *x = N_VGetArrayPointer(q), *W = N_VGetArrayPointer(v);
  double *gg = N_VGetArrayPointer(g);
  (void)t;
  if (model == R2_OSC) {
    gg[0] = x[0] + x[0] * x[0] * x[0];
    gg[1] = x[1] + x[1] * x[1] * x[1];
    return 0;
  }
  if (model == R3SO3_BODY) {
    gg[0] = gg[1] = 0.0;
    gg[2] = MASS * GRAV;
    W += 3;
    gg += 3;
  }
  gg[0] = W[1] * J[2] * W[2] - W[2] * J[1] * W[1];
  gg[1] = W[2] * J[0] * W[0] - W[0] * J[2] * W[2];
  gg[2] = W[0] * J[1] * W[1] - W[1] * J[0] * W[0];
  return 0;
}

/* The exact rotation of the symmetric top from (p0, W0) after time t. */
static void TopFlow(const double p0[4], const double W0[3], double t, double p[4])
{
  const double nu = W0[2] * (J[2] - J[0]) / J[0];
  double R0[9], JW[3], pi[3], a[3], b[3], pa[4], pb[4];
  int i;
  LGNQuaternionToRotation(p0, R0);
  for (i = 0; i < 3; i++) JW[i] = J[i] * W0[i];
  for (i = 0; i < 3; i++) pi[i] = R0[3 * i] * JW[0] + R0[3 * i + 1] * JW[1] + R0[3 * i + 2] * JW[2];
  for (i = 0; i < 3; i++) a[i] = t * pi[i] / J[0];
  b[0] = b[1] = 0.0;
  b[2] = -t * nu;
  LGNQuaternionFromRotationVector(a, pa);
  LGNQuaternionFromRotationVector(b, pb);
  LGNQuaternionMultiply(pa, p0, p);
  LGNQuaternionMultiply(p, pb, p);
}

/* R^2 oscillator: RK4 with n substeps from (x, v) over t. */
static void OscFlow(const double x0[2], const double v0[2], double t, int n,
                    double x[2], double v[2])
{
  const double dt = t / n;
  int k, i;
  for (i = 0; i < 2; i++) {
    x[i] = x0[i];
    v[i] = v0[i];
  }
  for (k = 0; k < n; k++) {
    for (i = 0; i < 2; i++) {
      double k1x = v[i], k1v = -(x[i] + x[i] * x[i] * x[i]);
      double y = x[i] + 0.5 * dt * k1x, w = v[i] + 0.5 * dt * k1v;
      double k2x = w, k2v = -(y + y * y * y);
      double k3x, k3v, k4x, k4v;
      y = x[i] + 0.5 * dt * k2x;
      w = v[i] + 0.5 * dt * k2v;
      k3x = w;
      k3v = -(y + y * y * y);
      y = x[i] + dt * k3x;
      w = v[i] + dt * k3v;
      k4x = w;
      k4v = -(y + y * y * y);
      x[i] += dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v[i] += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
}

/* The rotation vector log(p_a^{-1} p_b). */
static void RotationDifference(const double pa[4], const double pb[4], double d[3])
{
  double inv[4] = {pa[0], -pa[1], -pa[2], -pa[3]}, r[4];
  LGNQuaternionMultiply(inv, pb, r);
  LGNRotationVectorFromQuaternion(r, d);
}

typedef struct {
  Model model;
  LGNGroup G;
  N_Vector q, v;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} Problem;

static const double PSI0[3] = {0.3, -0.2, 0.1}, W0[3] = {1.0, -2.0, 20.0};

/* An integrator on the model: generalized-alpha rho_inf, kinematics kin,
 * error control with rtol, atol. */
static int ProblemCreate(Problem *pb, Model model, double rho_inf, int kin,
                         double rtol, double atol)
{
  const sunindextype nq = model == SO3_TOP ? 4 : model == R3SO3_BODY ? 7 : 2;
  const sunindextype nv = model == SO3_TOP ? 3 : model == R3SO3_BODY ? 6 : 2;
  double *q, *v;
  int flag, i;
  memset(pb, 0, sizeof *pb);
  pb->model = model;
  pb->G     = model == SO3_TOP ? LGNGroup_SO3() : model == R3SO3_BODY ? LGNGroup_R3xSO3()
                                                                     : LGNGroup_Rn(2);
  pb->q  = N_VNew_Serial(nq, ctx);
  pb->v  = N_VNew_Serial(nv, ctx);
  pb->A  = SUNDenseMatrix(nv, nv, ctx);
  pb->LS = SUNLinSol_Dense(pb->v, pb->A, ctx);
  pb->mem = LGNCreate(ctx);
  q = N_VGetArrayPointer(pb->q);
  v = N_VGetArrayPointer(pb->v);
  if (model == R2_OSC) {
    q[0] = 1.0;
    q[1] = -0.5;
    v[0] = 0.3;
    v[1] = 1.2;
  } else {
    const int o = model == R3SO3_BODY ? 3 : 0;
    if (o) {
      q[0] = 0.1; q[1] = -0.2; q[2] = 0.3;
      v[0] = 1.0; v[1] = 0.5; v[2] = 2.0;
    }
    LGNQuaternionFromRotationVector(PSI0, q + o);
    for (i = 0; i < 3; i++) v[o + i] = W0[i];
  }
  flag = LGNSetGroup(pb->mem, pb->G);
  if (!flag) flag = LGNSetUserData(pb->mem, &pb->model);
  if (!flag) flag = LGNSetMassFn(pb->mem, Mass);
  if (!flag) flag = LGNSetForceFn(pb->mem, Force);
  if (!flag) flag = LGNInit(pb->mem, 0.0, pb->q, pb->v);
  if (!flag) flag = LGNSetLinearSolver(pb->mem, pb->LS, pb->A);
  if (!flag) flag = LGNSetGenAlpha(pb->mem, rho_inf);
  if (!flag) flag = LGNSetKinematics(pb->mem, kin);
  if (!flag) flag = LGNSetStepControl(pb->mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(pb->mem, rtol, atol);
  return flag;
}

static void ProblemFree(Problem *pb)
{
  LGNFree(&pb->mem);
  SUNLinSolFree(pb->LS);
  SUNMatDestroy(pb->A);
  N_VDestroy(pb->q);
  N_VDestroy(pb->v);
  LGNGroup_Destroy(pb->G);
}

/* Prescribe the next step size: hmin = hmax = h (in an order the setters
 * accept). */
static int ForceStep(void *mem, double h)
{
  int flag = LGNSetMinStep(mem, 0.0);
  if (!flag) flag = LGNSetMaxStep(mem, h);
  if (!flag) flag = LGNSetMinStep(mem, h);
  return flag;
}

/* The true error of the last step from (q_n, v_n) over h, in the Lie
 * algebra, into e (nv). */
static void TrueStepError(const Problem *pb, const double *qn, const double *vn,
                          double h, double *e)
{
  const double *q = N_VGetArrayPointer(pb->q);
  if (pb->model == R2_OSC) {
    double x[2], v[2];
    OscFlow(qn, vn, h, 2000, x, v);
    e[0] = q[0] - x[0];
    e[1] = q[1] - x[1];
  } else if (pb->model == SO3_TOP) {
    double p[4];
    TopFlow(qn, vn, h, p);
    RotationDifference(p, q, e);
  } else {
    /* R^3 x SO(3): x(t) = x + u t - g t^2/2 e3; the rotation as the top */
    double p[4];
    int i;
    for (i = 0; i < 3; i++) e[i] = q[i] - (qn[i] + vn[i] * h);
    e[2] += 0.5 * GRAV * h * h;
    TopFlow(qn + 3, vn + 3, h, p);
    RotationDifference(p, q + 3, e + 3);
  }
}

/* =============================================================================
 * (a) the estimate against the true one-step error
 * ===========================================================================*/

static void Estimator(void)
{
  const char *mname[3] = {"SO(3)", "R^3 x SO(3)", "R^2"};
  const char *kname[3] = {"simplified", "exact", "sigma"};
  int model, kin, j;
  printf("(a) local error estimate / true one-step error\n");
  for (model = 0; model < 3; model++)
    for (kin = 0; kin < 3; kin++)
      for (j = 0; j < 3; j++) {
        const double h = 2e-3 / (double)(1 << j);
        Problem pb;
        N_Vector ele;
        double qn[7], vn[6], e[6], t, ne = 0, nt = 0, dot = 0, ratio, cosine;
        sunindextype i, nq, nv;
        int flag, k;
        /* error test passes always (atol 1); Newton to 1e-12 */
        flag = ProblemCreate(&pb, (Model)model, 0.9, KIN[kin], 1e-14, 1.0);
        if (!flag) flag = LGNSetNonlinConvCoef(pb.mem, 1e-12);
        if (!flag) flag = ForceStep(pb.mem, h);
        for (k = 0; k < 10 && !flag; k++) flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
        nq = N_VGetLength(pb.q);
        nv = N_VGetLength(pb.v);
        memcpy(qn, N_VGetArrayPointer(pb.q), (size_t)nq * sizeof(double));
        memcpy(vn, N_VGetArrayPointer(pb.v), (size_t)nv * sizeof(double));
        if (!flag) flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
        CHECK(flag == LGN_SUCCESS, "%s %s h = %g: %s", mname[model], kname[kin], h,
              LGNGetReturnFlagName(flag));
        ele = N_VNew_Serial(nv, ctx);
        LGNGetEstLocalErrors(pb.mem, ele);
        TrueStepError(&pb, qn, vn, h, e);
        for (i = 0; i < nv; i++) {
          const double x = N_VGetArrayPointer(ele)[i];
          ne += x * x;
          nt += e[i] * e[i];
          dot += x * e[i];
        }
        ratio  = sqrt(ne / nt);
        cosine = dot / sqrt(ne * nt);
        printf("  %-12s %-10s h = %.1e  |est| = %.3e  |true| = %.3e  ratio %.4f  cos %.5f\n",
               mname[model], kname[kin], h, sqrt(ne), sqrt(nt), ratio, cosine);
        CHECK(ratio >= 0.8 && ratio <= 1.25, "%s %s h = %g: ratio %.4f outside [0.8, 1.25]",
              mname[model], kname[kin], h, ratio);
        CHECK(cosine > 0.99, "%s %s h = %g: cosine %.4f", mname[model], kname[kin], h, cosine);
        N_VDestroy(ele);
        ProblemFree(&pb);
      }
}

/* =============================================================================
 * (b) tolerance proportionality on the heavy top
 * ===========================================================================*/

static double Slope(const double *x, const double *y, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    sx += log(x[i]);
    sy += log(y[i]);
    sxx += log(x[i]) * log(x[i]);
    sxy += log(x[i]) * log(y[i]);
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void Proportionality(void)
{
  const char *kname[2] = {"simplified", "exact"};
  LGNRefHeavyTop ref;
  const double t1 = 1.0;
  int kin, j;
  CHECK(lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) == 0, "reference");
  printf("(b) heavy top, error at t = 1 against tolerance\n");
  for (kin = 0; kin < 2; kin++) {
    double tol[4], err[4], steps[4], p, q;
    for (j = 0; j < 4; j++) {
      HeavyTopOptions o;
      HeavyTopResult r;
      int i;
      heavy_top_default_options(&o);
      o.kinematics   = KIN[kin];
      o.single_solve = 1;
      o.adaptive     = 1;
      o.rtol = o.atol = tol[j] = 1e-5 / pow(10.0, j);
      heavy_top_run(&o, &r);
      CHECK(r.flag == LGN_SUCCESS && r.t == 1.0, "%s tol %g: %s at t = %.17g", kname[kin],
            tol[j], LGNGetReturnFlagName(r.flag), r.t);
      err[j] = 0.0;
      for (i = 0; i < 3; i++) err[j] = fmax(err[j], fabs(r.x[i] - ref.x[i]));
      steps[j] = (double)r.nsteps;
      printf("  %-10s tol %.0e  steps %6ld  rejected %4ld  error %.3e\n", kname[kin], tol[j],
             r.nsteps, r.netfails, err[j]);
    }
    p = Slope(tol, err, 4);
    q = Slope(tol, steps, 4);
    printf("  %-10s error ~ tol^%.3f, steps ~ tol^%.3f\n", kname[kin], p, q);
    /* error per unit step of an order-2 method: ~1 (measured 0.96 - 1.0;
     * the error per step of earlier releases gave 0.6 - 0.8) */
    CHECK(p > 0.85 && p < 1.15, "%s: error ~ tol^%.3f, not near 1", kname[kin], p);
    CHECK(q < -0.4 && q > -0.6, "%s: steps ~ tol^%.3f, not near -1/2", kname[kin], q);
  }
}

/* The chain of 5 bodies (models/chain.h), error control: the
 * final state against a BDF run (maxord 5) at tolerance 1e-11, another
 * method (generalized-alpha at 1e-11 would take 10^6 steps). */
static double ChainRun(double tol, int bdf, double *q, long int *nsteps)
{
  RigidSystem *sys = chain_create(5, RB_R3XSO3, ctx);
  RigidRunOptions o;
  RigidRunResult r;
  int flag, i;
  rigid_default_run_options(&o);
  o.adaptive = 1;
  o.rtol = o.atol = tol;
  o.t_end = 1.0;
  o.h = 0.1;
  o.bdf_maxord = bdf;
  flag = rigid_run(sys, &o, &r);
  CHECK(flag == LGN_SUCCESS, "chain at tol %g: %s", tol, LGNGetReturnFlagName(flag));
  for (i = 0; i < 35; i++) q[i] = r.q[i];
  *nsteps = r.nsteps;
  rigid_result_free(&r);
  rigid_free(&sys);
  return 0.0;
}

static void ChainProportionality(void)
{
  double ref[35], q[35], tol[4], err[4], steps[4], p;
  long int ns;
  int j, i;
  ChainRun(1e-11, 5, ref, &ns);
  printf("(b) chain of 5 bodies, error at t = 1 against tolerance (reference: BDF5 at tol 1e-11, %ld steps)\n", ns);
  for (j = 0; j < 4; j++) {
    tol[j] = 1e-5 / pow(10.0, j);
    ChainRun(tol[j], 0, q, &ns);
    err[j] = 0.0;
    for (i = 0; i < 5; i++) { /* centres of mass */
      int k;
      for (k = 0; k < 3; k++) err[j] = fmax(err[j], fabs(q[7 * i + k] - ref[7 * i + k]));
    }
    steps[j] = (double)ns;
    printf("  tol %.0e  steps %6ld  error %.3e\n", tol[j], ns, err[j]);
  }
  p = Slope(tol, err, 4);
  printf("  error ~ tol^%.3f, steps ~ tol^%.3f\n", p, Slope(tol, steps, 4));
  CHECK(p > 0.85 && p < 1.15, "chain: error ~ tol^%.3f, not near 1", p);
}

/* =============================================================================
 * (c) order under the step pattern H, H/4, H, H/4, ...
 * ===========================================================================*/

static double PatternRun(int kin, double H, int npairs, double *T)
{
  Problem pb;
  double t = 0.0, p[4], d[3];
  int k, flag;
  flag = ProblemCreate(&pb, SO3_TOP, 0.9, KIN[kin], 1e-14, 1.0);
  if (!flag) flag = LGNSetNonlinConvCoef(pb.mem, 1e-12);
  for (k = 0; k < 2 * npairs && !flag; k++) {
    flag = ForceStep(pb.mem, k % 2 == 0 ? H : 0.25 * H);
    if (!flag) flag = LGNSolve(pb.mem, 10.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  }
  CHECK(flag == LGN_SUCCESS, "pattern run: %s", LGNGetReturnFlagName(flag));
  *T = t;
  {
    double p0[4];
    LGNQuaternionFromRotationVector(PSI0, p0);
    TopFlow(p0, W0, t, p);
  }
  RotationDifference(p, N_VGetArrayPointer(pb.q), d);
  ProblemFree(&pb);
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static void StepPattern(void)
{
  const char *kname[2] = {"simplified", "exact"};
  int kin, j;
  printf("(c) order under the step pattern H, H/4, H, H/4, ... (torque-free top, t = 0.5)\n");
  for (kin = 0; kin < 2; kin++) {
    double H[4], err[4], T, order;
    for (j = 0; j < 4; j++) {
      const int npairs = 40 << j;
      H[j]   = 0.5 / (1.25 * npairs);
      err[j] = PatternRun(kin, H[j], npairs, &T);
      printf("  %-10s H = %.3e  error %.3e  (t = %.6f)\n", kname[kin], H[j], err[j], T);
    }
    order = Slope(H, err, 4);
    printf("  %-10s fitted order %.3f\n", kname[kin], order);
    CHECK(fabs(order - 2.0) <= 0.1, "%s: order %.3f under the step pattern", kname[kin], order);
  }
}

/* =============================================================================
 * (d) dense output
 * ===========================================================================*/

static void DenseOutput(void)
{
  const char *kname[3] = {"simplified", "exact", "sigma"};
  int kin, j;
  printf("(d) dense output at step midpoints; continuity at step ends\n");
  for (kin = 0; kin < 3; kin++) {
    double hs[3], err[3], order, jump_q = 0.0, jump_v = 0.0;
    for (j = 0; j < 3; j++) {
      Problem pb;
      N_Vector qm = N_VNew_Serial(4, ctx), vm = N_VNew_Serial(3, ctx);
      double t = 0.0, p[4], p0[4], d[3], tprev = 0.0;
      const double h = 4e-3 / (double)(1 << j);
      int flag, k;
      hs[j]  = h;
      err[j] = 0.0;
      LGNQuaternionFromRotationVector(PSI0, p0);
      flag = ProblemCreate(&pb, SO3_TOP, 0.9, KIN[kin], 1e-14, 1.0);
      if (!flag) flag = LGNSetNonlinConvCoef(pb.mem, 1e-12);
      if (!flag) flag = ForceStep(pb.mem, h);
      for (k = 0; k < (int)(0.2 / h + 0.5) && !flag; k++) {
        flag = LGNSolve(pb.mem, 10.0, &t, pb.q, pb.v, LGN_ONE_STEP);
        if (!flag) flag = LGNGetDky(pb.mem, 0.5 * (tprev + t), 0, qm);
        if (!flag) {
          TopFlow(p0, W0, 0.5 * (tprev + t), p);
          RotationDifference(p, N_VGetArrayPointer(qm), d);
          err[j] = fmax(err[j], sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
        /* continuity: the interpolant just before the step's end */
        if (!flag && j == 0) {
          sunindextype i;
          const double te = t - 1e-12 * h;
          flag = LGNGetDky(pb.mem, te, 0, qm);
          if (!flag) flag = LGNGetDky(pb.mem, te, 1, vm);
          for (i = 0; i < 4; i++)
            jump_q = fmax(jump_q, fabs(N_VGetArrayPointer(qm)[i] - N_VGetArrayPointer(pb.q)[i]));
          for (i = 0; i < 3; i++)
            jump_v = fmax(jump_v, fabs(N_VGetArrayPointer(vm)[i] - N_VGetArrayPointer(pb.v)[i]) /
                                      20.0);
        }
        tprev = t;
      }
      CHECK(flag == LGN_SUCCESS, "dense output run: %s", LGNGetReturnFlagName(flag));
      N_VDestroy(qm);
      N_VDestroy(vm);
      ProblemFree(&pb);
    }
    order = Slope(hs, err, 3);
    printf("  %-10s max midpoint error %.3e %.3e %.3e, order %.3f; jumps |dq| %.2e, |dv|/|v| %.2e\n",
           kname[kin], err[0], err[1], err[2], order, jump_q, jump_v);
    CHECK(fabs(order - 2.0) <= 0.15, "%s: dense output order %.3f", kname[kin], order);
    /* q and v are matched at the ends: only the 1e-12 h offset and
     * roundoff remain; the sigma variant's increment (its q1 is composed
     * of corrections) is tracked to O(|correction|^2 |increment|):
     * measured 1e-10 at h = 4e-3 */
    CHECK(jump_q < (kin == 2 ? 1e-9 : 1e-12) && jump_v < 1e-12,
          "%s: dense output discontinuous at the step end (%.3g, %.3g)", kname[kin],
          jump_q, jump_v);
  }
}

/* =============================================================================
 * (e) rejections and failures leave the state bit for bit
 * ===========================================================================*/

static char last_msg[512];
static int last_code;
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)module;
  (void)d;
  last_code = code;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

typedef struct {
  double t, q[7], v[6], vdot[6], a[6];
} Snapshot;

static void Snap(const Problem *pb, Snapshot *s)
{
  N_Vector x = N_VNew_Serial(6, ctx);
  memset(s, 0, sizeof *s);
  LGNGetCurrentTime(pb->mem, &s->t);
  memcpy(s->q, N_VGetArrayPointer(pb->q), 7 * sizeof(double));
  memcpy(s->v, N_VGetArrayPointer(pb->v), 6 * sizeof(double));
  LGNGetAcceleration(pb->mem, x);
  memcpy(s->vdot, N_VGetArrayPointer(x), 6 * sizeof(double));
  LGNGetAuxAcceleration(pb->mem, x);
  memcpy(s->a, N_VGetArrayPointer(x), 6 * sizeof(double));
  N_VDestroy(x);
}

static int ForceFail = 0;
static int FlakyForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return ForceFail ? 1 : Force(t, q, v, g, ud);
}

static void Rollback(void)
{
  Problem pb, pc;
  Snapshot s0, s1;
  double t;
  long int netf0 = 0, netf1 = 0;
  double hacc = 0.0;
  int flag, k;
  printf("(e) failures and rejections leave the state bit for bit\n");

  /* error-test failure at hmin */
  flag = ProblemCreate(&pb, R3SO3_BODY, 0.9, LGN_KINEMATICS_EXACT, 1e-6, 1e-6);
  if (!flag) flag = LGNSetErrHandlerFn(pb.mem, Capture, NULL);
  for (k = 0; k < 20 && !flag; k++) flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  Snap(&pb, &s0);
  if (!flag) flag = LGNSStolerances(pb.mem, 1e-14, 1e-14);
  if (!flag) flag = LGNSetMinStep(pb.mem, 1e-3);
  if (!flag) flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  CHECK(flag == LGN_ERR_FAILURE, "error test at hmin: %s", LGNGetReturnFlagName(flag));
  CHECK(strstr(last_msg, "h = ") != NULL && strstr(last_msg, "t = ") != NULL,
        "the message names t and h: \"%s\"", last_msg);
  Snap(&pb, &s1);
  CHECK(memcmp(&s0, &s1, sizeof s0) == 0, "state after LGN_ERR_FAILURE as before, bit for bit");

  /* a recoverable callback failure, retried up to maxncf */
  LGNSetMinStep(pb.mem, 0.0);
  LGNSStolerances(pb.mem, 1e-6, 1e-6);
  LGNSetForceFn(pb.mem, FlakyForce);
  LGNSetMaxConvFails(pb.mem, 4);
  ForceFail = 1;
  flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  ForceFail = 0;
  CHECK(flag == LGN_REPTD_CALLBACK_ERR, "recoverable callback failure: %s",
        LGNGetReturnFlagName(flag));
  CHECK(strstr(last_msg, "4 times") != NULL && strstr(last_msg, "h = ") != NULL,
        "the message names the count and h: \"%s\"", last_msg);
  Snap(&pb, &s1);
  CHECK(memcmp(&s0, &s1, sizeof s0) == 0, "state after LGN_REPTD_CALLBACK_ERR as before");
  flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  CHECK(flag == LGN_SUCCESS, "goes on once the callback recovers: %s", LGNGetReturnFlagName(flag));
  ProblemFree(&pb);

  /* the step accepted after rejections equals that step taken directly */
  flag = ProblemCreate(&pb, R3SO3_BODY, 0.9, LGN_KINEMATICS_EXACT, 1e-6, 1e-6);
  if (!flag) flag = ProblemCreate(&pc, R3SO3_BODY, 0.9, LGN_KINEMATICS_EXACT, 1e-6, 1e-6);
  for (k = 0; k < 20 && !flag; k++) {
    flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
    if (!flag) flag = LGNSolve(pc.mem, 1.0, &t, pc.q, pc.v, LGN_ONE_STEP);
  }
  /* tighter tolerances: the next attempt is rejected at least once */
  if (!flag) flag = LGNSStolerances(pb.mem, 1e-8, 1e-8);
  if (!flag) LGNGetNumErrTestFails(pb.mem, &netf0);
  if (!flag) flag = LGNSolve(pb.mem, 1.0, &t, pb.q, pb.v, LGN_ONE_STEP);
  if (!flag) LGNGetNumErrTestFails(pb.mem, &netf1);
  if (!flag) LGNGetLastStep(pb.mem, &hacc);
  CHECK(flag == LGN_SUCCESS && netf1 > netf0, "a rejection, then a step (%ld rejections)",
        netf1 - netf0);
  if (!flag) flag = LGNSStolerances(pc.mem, 1e-8, 1e-8);
  if (!flag) flag = ForceStep(pc.mem, hacc);
  if (!flag) flag = LGNSolve(pc.mem, 1.0, &t, pc.q, pc.v, LGN_ONE_STEP);
  Snap(&pb, &s0);
  Snap(&pc, &s1);
  CHECK(flag == LGN_SUCCESS && memcmp(&s0, &s1, sizeof s0) == 0,
        "the step after rejections equals the same step taken directly, bit for bit");
  ProblemFree(&pb);
  ProblemFree(&pc);
}

/* =============================================================================
 * (f) stop time, output grid, bad arguments
 * ===========================================================================*/

static void StopTimeAndGrid(void)
{
  Problem pa, pb;
  double t = 0.0, tout;
  int flag, k;
  printf("(f) stop time, output grid\n");
  flag = ProblemCreate(&pa, R3SO3_BODY, 0.9, LGN_KINEMATICS_EXACT, 1e-6, 1e-6);
  if (!flag) flag = ProblemCreate(&pb, R3SO3_BODY, 0.9, LGN_KINEMATICS_EXACT, 1e-6, 1e-6);
  if (!flag) flag = LGNSetStopTime(pa.mem, 0.3);
  if (!flag) flag = LGNSolve(pa.mem, 0.3, &t, pa.q, pa.v, LGN_NORMAL);
  CHECK(flag == LGN_TSTOP_RETURN && t == 0.3, "lands on the stop time: %s at t = %.17g",
        LGNGetReturnFlagName(flag), t);
  LGNGetCurrentTime(pa.mem, &t);
  CHECK(t == 0.3, "the integrator's time is the stop time exactly (%.17g)", t);
  /* the same with outputs every 0.01 in between (interpolated) */
  if (!flag || flag == LGN_TSTOP_RETURN) flag = LGNSetStopTime(pb.mem, 0.3);
  for (k = 1; k <= 30 && flag == LGN_SUCCESS; k++) {
    tout = 0.01 * k;
    flag = LGNSolve(pb.mem, tout, &t, pb.q, pb.v, LGN_NORMAL);
    if (k < 30) {
      CHECK(flag == LGN_SUCCESS && t == tout, "output at %g: %s, t = %.17g", tout,
            LGNGetReturnFlagName(flag), t);
    }
  }
  CHECK(flag == LGN_TSTOP_RETURN, "the last output is the stop time");
  CHECK(memcmp(N_VGetArrayPointer(pa.q), N_VGetArrayPointer(pb.q), 7 * sizeof(double)) == 0 &&
            memcmp(N_VGetArrayPointer(pa.v), N_VGetArrayPointer(pb.v), 6 * sizeof(double)) == 0,
        "30 outputs on the way change nothing at t = 0.3 (bit for bit)");
  ProblemFree(&pa);
  ProblemFree(&pb);
}

static int Refused(int flag, const char *name)
{
  return flag != LGN_SUCCESS && strstr(last_msg, name) != NULL;
}

static void BadArguments(void)
{
  Problem pb;
  N_Vector atol3 = N_VNew_Serial(3, ctx), atol6 = N_VNew_Serial(6, ctx);
  N_Vector q = N_VNew_Serial(7, ctx);
  double t;
  int flag;
  printf("(f) bad arguments\n");
  flag = ProblemCreate(&pb, R3SO3_BODY, 0.9, LGN_KINEMATICS_SIMPLIFIED, 1e-6, 1e-6);
  LGNSetErrHandlerFn(pb.mem, Capture, NULL);
  CHECK(!flag, "setup");
  CHECK(Refused(LGNSetStepControl(pb.mem, 7), "control"), "LGNSetStepControl(7): %s", last_msg);
  CHECK(Refused(LGNSVtolerances(pb.mem, NAN, atol6), "rtol"), "SV rtol NaN: %s", last_msg);
  CHECK(Refused(LGNSVtolerances(pb.mem, 1e-6, NULL), "atol"), "SV atol NULL: %s", last_msg);
  CHECK(Refused(LGNSVtolerances(pb.mem, 1e-6, atol3), "atol"), "SV atol length: %s", last_msg);
  N_VConst(1e-6, atol6);
  N_VGetArrayPointer(atol6)[4] = 0.0;
  CHECK(Refused(LGNSVtolerances(pb.mem, 1e-6, atol6), "atol[4]"), "SV atol entry 0: %s", last_msg);
  N_VGetArrayPointer(atol6)[4] = INFINITY;
  CHECK(Refused(LGNSVtolerances(pb.mem, 1e-6, atol6), "atol[4]"), "SV atol entry Inf: %s", last_msg);
  CHECK(Refused(LGNSetInitStep(pb.mem, -1.0), "h0"), "h0 < 0: %s", last_msg);
  CHECK(Refused(LGNSetInitStep(pb.mem, NAN), "h0"), "h0 NaN: %s", last_msg);
  CHECK(Refused(LGNSetMinStep(pb.mem, -1e-3), "hmin"), "hmin < 0: %s", last_msg);
  CHECK(Refused(LGNSetMaxStep(pb.mem, INFINITY), "hmax"), "hmax Inf: %s", last_msg);
  CHECK(LGNSetMaxStep(pb.mem, 1e-3) == LGN_SUCCESS, "hmax = 1e-3");
  CHECK(Refused(LGNSetMinStep(pb.mem, 1e-2), "hmin"), "hmin above hmax: %s", last_msg);
  CHECK(LGNSetMaxStep(pb.mem, 0.0) == LGN_SUCCESS && LGNSetMinStep(pb.mem, 1e-4) == LGN_SUCCESS,
        "no hmax, hmin = 1e-4");
  CHECK(Refused(LGNSetMaxStep(pb.mem, 1e-5), "hmax"), "hmax below hmin: %s", last_msg);
  CHECK(Refused(LGNSetMaxErrTestFails(pb.mem, -1), "maxnef"), "maxnef < 0: %s", last_msg);
  CHECK(Refused(LGNSetMaxConvFails(pb.mem, -2), "maxncf"), "maxncf < 0: %s", last_msg);
  CHECK(Refused(LGNSetNonlinConvCoef(pb.mem, 1.5), "epcon"), "epcon > 1: %s", last_msg);
  CHECK(Refused(LGNSetNonlinConvCoef(pb.mem, NAN), "epcon"), "epcon NaN: %s", last_msg);
  CHECK(Refused(LGNSetStopTime(pb.mem, NAN), "tstop"), "tstop NaN: %s", last_msg);
  CHECK(LGNGetDky(pb.mem, 0.0, 0, q) == LGN_BAD_T, "LGNGetDky before a step: %s", last_msg);
  LGNSetMinStep(pb.mem, 0.0);
  flag = LGNSolve(pb.mem, 0.1, &t, pb.q, pb.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "run to 0.1: %s", LGNGetReturnFlagName(flag));
  CHECK(Refused(LGNSetStopTime(pb.mem, 0.05), "tstop"), "tstop behind t: %s", last_msg);
  CHECK(LGNGetDky(pb.mem, t, 3, q) == LGN_BAD_K && strstr(last_msg, "k = 3"), "k = 3: %s", last_msg);
  CHECK(Refused(LGNGetDky(pb.mem, t, 1, q), "dky"), "dky of length nq for v: %s", last_msg);
  CHECK(Refused(LGNGetDky(pb.mem, t, 0, NULL), "dky"), "dky NULL: %s", last_msg);
  CHECK(LGNGetDky(pb.mem, t + 1.0, 0, q) == LGN_BAD_T && strstr(last_msg, "t = "),
        "t after the step: %s", last_msg);
  CHECK(LGNGetDky(pb.mem, 0.0, 0, q) == LGN_BAD_T, "t before the step: %s", last_msg);
  CHECK(LGNGetDky(NULL, t, 0, q) == LGN_MEM_NULL, "NULL memory");
  ProblemFree(&pb);

  /* error control without tolerances */
  flag = ProblemCreate(&pb, SO3_TOP, 0.9, LGN_KINEMATICS_SIMPLIFIED, 1e-6, 1e-6);
  LGNFree(&pb.mem);
  pb.mem = LGNCreate(ctx);
  LGNSetErrHandlerFn(pb.mem, Capture, NULL);
  LGNSetGroup(pb.mem, pb.G);
  LGNSetUserData(pb.mem, &pb.model);
  LGNSetMassFn(pb.mem, Mass);
  LGNSetForceFn(pb.mem, Force);
  LGNInit(pb.mem, 0.0, pb.q, pb.v);
  LGNSetLinearSolver(pb.mem, pb.LS, pb.A);
  LGNSetStepControl(pb.mem, LGN_STEP_ADAPTIVE);
  flag = LGNSolve(pb.mem, 0.1, &t, pb.q, pb.v, LGN_NORMAL);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "LGNSStolerances"),
        "error control without tolerances: %s", last_msg);
  ProblemFree(&pb);
  N_VDestroy(atol3);
  N_VDestroy(atol6);
  N_VDestroy(q);
}

int main(void)
{
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  Estimator();
  Proportionality();
  ChainProportionality();
  StepPattern();
  DenseOutput();
  Rollback();
  StopTimeAndGrid();
  BadArguments();
  SUNContext_Free(&ctx);
  return test_summary("test_error_control");
}
