/* -----------------------------------------------------------------------------
 * The stabilised index-2 formulation (LGN_CONSTR_GGL) with the Newmark /
 * generalized-alpha family (doc/theory.md section 7.1): the correction
 * B(q_n)^T nu enters the Newmark increment s = sigma + B_n^T nu, from which
 * v_{n+1} and vdot_{n+1} follow, while q_{n+1} = q_n o exp(sigma).
 * The heavy top of test_ggl (R^3 x SO(3), m = 3, ARKODE reference):
 *  (a) fixed steps, LGGalpha and mod. LGGalpha (rho_inf = 0.9; simplified
 *      and exact kinematics): the errors at t = 0.3 of the centre of mass,
 *      the velocities and the multipliers over four step sizes, fitted
 *      order 2 +- 0.2 in each; index 3 printed for comparison, and the
 *      largest multiplier error over the steps in (0, 0.02] (the start
 *      transient; also with LGNSetPerturbedStart) printed;
 *  (b) no drift: max |Phi| and max |B v| over t in [0, 1] (h = 1e-3) at
 *      round-off level, where index 3 lets |B v| and index 2 |Phi| drift;
 *  (c) an independent implementation: a planar pendulum in Cartesian
 *      coordinates (R^2, where simplified and exact kinematics are the
 *      classical method) against generalized-alpha with the stabilised
 *      index-2 correction written out here (Dq = v_n + (1/2 - beta) h a_n +
 *      beta h a_{n+1} - G(q_n)^T eta, q_{n+1} = q_n + h Dq, v_{n+1}, a_{n+1}
 *      and vdot_{n+1} as usual; M vdot + g + G^T lambda = 0, Phi = 0,
 *      G v = 0 at t_{n+1}; dense Newton with an analytic Jacobian), to
 *      1e-12 over 100 steps;
 *  (d) error control (LGN_STEP_ADAPTIVE), tol 1e-5 ... 1e-8: every run
 *      reaches t = 1 and the error follows tol^p, p in (0.55, 0.9) (per-step
 *      control of a second-order method: about 2/3, as index 3 in
 *      test_error_control);
 *  (e) a start off the velocity constraint is refused and LGNCalcIC
 *      (LGN_IC_PROJECT_QV) repairs it;
 *  (f) bad input: the sigma variant, a Krylov solver and (with KLU) a
 *      sparse matrix are refused at the solve with a message naming why;
 *  (g) rheonomic constraints (Phi_t; test_ggl's bead on a turning rod,
 *      exact solution known): fixed steps h = 0.02, 0.01, 0.005 to t = 1,
 *      order 2 +- 0.2, |Phi| and |B v + Phi_t| at round-off at t = 1;
 *  (h) LGNGetWorkSpace counts GGL's B(q_n) (m nv reals).
 * With --quick only (c), (e), (f) and (h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h> /* LGN_HAVE_KLU */
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "heavy_top_run.h"
#include "lgn_reference.h"
#include "test_util.h"

/* The method: generalized-alpha rho_inf = 0.9 with the given kinematics
 * and constraint formulation, fixed step h. */
static int RunMethod(Run *r, SUNContext ctx, int index, int kin, double h)
{
  int flag = RunCreate(r, ctx, index, index == LGN_CONSTR_GGL ? 12 : 9);
  if (!flag) flag = LGNSetGenAlpha(r->mem, 0.9);
  if (!flag) flag = LGNSetKinematics(r->mem, kin);
  if (!flag) flag = LGNSStolerances(r->mem, 1e-12, 1e-12);
  if (!flag) flag = LGNSetStepSize(r->mem, h);
  return flag;
}

/* (a) the errors at t_end with fixed steps h (HUGE_VAL on failure). */
static void FixedStepErrors(SUNContext ctx, int index, int kin, double h, double t_end,
                            const LGNRefHeavyTop *ref, double e[3])
{
  Run r;
  sunrealtype t;
  int flag = RunMethod(&r, ctx, index, kin, h);
  e[0] = e[1] = e[2] = HUGE_VAL;
  if (!flag) flag = LGNSolve(r.mem, t_end, &t, r.q, r.v, LGN_NORMAL);
  if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
  if (!flag) Errors(&r, ref, e);
  else printf("  h %g: flag %d\n", h, flag);
  RunFree(&r);
}

/* (a) the start transient: the largest multiplier error over the steps
 * in (0, 0.02] (HUGE_VAL on failure). */
static double StartLambdaError(SUNContext ctx, int index, int kin, double h, int perturbed)
{
  enum { NMAX = 200 };
  static LGNRefHeavyTop ref[NMAX];
  double times[NMAX], e[3], emax = 0;
  const int n = (int)(0.02 / h + 0.5);
  Run r;
  sunrealtype t;
  int flag = n > NMAX, k;
  for (k = 0; k < n && k < NMAX; k++) times[k] = (k + 1) * h;
  if (!flag) flag = lgnref_heavy_top(times, n, ref, LGNREF_FEHLBERG_8);
  if (!flag) flag = RunMethod(&r, ctx, index, kin, h);
  if (!flag && perturbed) flag = LGNSetPerturbedStart(r.mem, SUNTRUE);
  for (k = 0; !flag && k < n; k++) {
    flag = LGNSolve(r.mem, times[k], &t, r.q, r.v, LGN_NORMAL);
    if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
    if (!flag) Errors(&r, &ref[k], e);
    emax = fmax(emax, e[2]);
  }
  RunFree(&r);
  return flag ? HUGE_VAL : emax;
}

/* (b) the largest |Phi| and |B v| over a fixed-step run to t = 1. */
static int Drift(SUNContext ctx, int index, int kin, double *phi, double *bv)
{
  Run r;
  sunrealtype t;
  double p, b;
  int flag = RunMethod(&r, ctx, index, kin, 1e-3), n;
  *phi = *bv = 0;
  if (!flag) flag = LGNSStolerances(r.mem, 1e-10, 1e-10);
  for (n = 1; !flag && n <= 1000; n++) {
    flag = LGNSolve(r.mem, 1e-3 * n, &t, r.q, r.v, LGN_NORMAL);
    if (flag) break;
    Violations(&r, &p, &b);
    *phi = fmax(*phi, p);
    *bv  = fmax(*bv, b);
  }
  RunFree(&r);
  return flag;
}

/* (d) one error-controlled run to t = 1: the error of the centre of mass. */
static double AdaptiveRun(SUNContext ctx, int kin, double tol, const LGNRefHeavyTop *ref,
                          long int *nst, int *flag_out)
{
  Run r;
  sunrealtype t = 0;
  double e[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  int flag = RunMethod(&r, ctx, LGN_CONSTR_GGL, kin, 1e-3);
  if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(r.mem, tol, tol);
  if (!flag) flag = LGNSetStopTime(r.mem, 1.0);
  if (!flag) flag = LGNSolve(r.mem, 1.0, &t, r.q, r.v, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  if (!flag && t != 1.0) flag = -1;
  if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
  if (!flag) Errors(&r, ref, e);
  LGNGetNumSteps(r.mem, nst);
  *flag_out = flag;
  RunFree(&r);
  return e[0];
}

/* ---- (c) the planar pendulum on R^2 ---------------------------------------- */

#define PEND_M 2.0
#define PEND_G 9.81

static int PMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = PEND_M;
  SM_ELEMENT_D(M, 1, 1) = PEND_M;
  return 0;
}

/* g = -f: gravity along -y */
static int PForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 0.0;
  NV_Ith_S(g, 1) = PEND_M * PEND_G;
  return 0;
}

static int PConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double x = NV_Ith_S(q, 0), y = NV_Ith_S(q, 1);
  (void)t; (void)ud;
  NV_Ith_S(phi, 0) = 0.5 * (x * x + y * y - 1.0);
  return 0;
}

static int PConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)t; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = NV_Ith_S(q, 0);
  SM_ELEMENT_D(B, 0, 1) = NV_Ith_S(q, 1);
  return 0;
}

/* K_t = D_q(B^T lambda) = lambda I */
static int PStiff(sunrealtype t, N_Vector q, N_Vector v, N_Vector vd, N_Vector l,
                  SUNMatrix K, void *ud)
{
  (void)t; (void)q; (void)v; (void)vd; (void)ud;
  SM_ELEMENT_D(K, 0, 0) = NV_Ith_S(l, 0);
  SM_ELEMENT_D(K, 1, 1) = NV_Ith_S(l, 0);
  return 0;
}

static int PDamp(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  (void)t; (void)q; (void)v; (void)C; (void)ud;
  return 0;
}

/* Z(q)(v, v) = d/dt (q . v) - q . vdot = v . v */
static int PCurv(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  (void)t; (void)q; (void)ud;
  NV_Ith_S(z, 0) = NV_Ith_S(v, 0) * NV_Ith_S(v, 0) + NV_Ith_S(v, 1) * NV_Ith_S(v, 1);
  return 0;
}

/* Gaussian elimination with partial pivoting, n <= 8: A x = b, x into b. */
static void SolveDense(int n, double A[8][8], double *b)
{
  int i, j, k, p;
  for (k = 0; k < n; k++) {
    double tmp;
    p = k;
    for (i = k + 1; i < n; i++)
      if (fabs(A[i][k]) > fabs(A[p][k])) p = i;
    for (j = 0; j < n; j++) { tmp = A[k][j]; A[k][j] = A[p][j]; A[p][j] = tmp; }
    tmp = b[k]; b[k] = b[p]; b[p] = tmp;
    for (i = k + 1; i < n; i++) {
      const double f = A[i][k] / A[k][k];
      for (j = k; j < n; j++) A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  for (i = n - 1; i >= 0; i--) {
    for (j = i + 1; j < n; j++) b[i] -= A[i][j] * b[j];
    b[i] /= A[i][i];
  }
}

/* The pendulum's state for the textbook method. */
typedef struct {
  double q[2], v[2], vd[2], a[2], l;
} PendState;

/* Generalized-alpha with the stabilised index-2 correction (Arnold, Cardona
 * and Brüls 2015) on R^2, one step: unknowns z = (a_{n+1} (2), lambda, eta);
 * residual (M vdot + g + G^T lambda, Phi(q_{n+1}), G(q_{n+1}) v_{n+1}),
 * Newton with the analytic Jacobian until the correction is below 1e-15. */
static void TextbookStep(PendState *s, double h, double am, double af, double be, double ga)
{
  const double *q = s->q, *v = s->v, *an = s->a;
  double z[4] = {s->a[0], s->a[1], s->l, 0.0}, q1[2], v1[2], vd1[2], r[4], J[8][8];
  int it, i, j;
  for (it = 0; it < 50; it++) {
    double dz = 0;
    for (i = 0; i < 2; i++) {
      /* h Dq = h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1} - h G(q_n)^T eta */
      q1[i]  = q[i] + h * v[i] + h * h * ((0.5 - be) * an[i] + be * z[i]) - h * q[i] * z[3];
      v1[i]  = v[i] + h * ((1 - ga) * an[i] + ga * z[i]);
      vd1[i] = ((1 - am) * z[i] + am * an[i] - af * s->vd[i]) / (1 - af);
    }
    r[0] = PEND_M * vd1[0] + q1[0] * z[2];
    r[1] = PEND_M * vd1[1] + PEND_M * PEND_G + q1[1] * z[2];
    r[2] = 0.5 * (q1[0] * q1[0] + q1[1] * q1[1] - 1.0);
    r[3] = q1[0] * v1[0] + q1[1] * v1[1];
    /* d q1_i / d a_k = h^2 beta delta_ik, d q1_i / d eta = -h q_i,
     * d v1_i / d a_k = h gamma delta_ik, d vd1_i / d a_k = (1-am)/(1-af) delta_ik */
    for (i = 0; i < 4; i++)
      for (j = 0; j < 4; j++) J[i][j] = 0;
    for (i = 0; i < 2; i++) {
      J[i][i] = PEND_M * (1 - am) / (1 - af) + z[2] * h * h * be;
      J[i][2] = q1[i];
      J[i][3] = -z[2] * h * q[i];
      J[2][i] = q1[i] * h * h * be;
      J[3][i] = q1[i] * h * ga + v1[i] * h * h * be;
    }
    J[2][3] = -h * (q1[0] * q[0] + q1[1] * q[1]);
    J[3][3] = -h * (v1[0] * q[0] + v1[1] * q[1]);
    for (i = 0; i < 4; i++) r[i] = -r[i];
    SolveDense(4, J, r);
    for (i = 0; i < 4; i++) {
      z[i] += r[i];
      dz = fmax(dz, fabs(r[i]) / (1.0 + fabs(z[i])));
    }
    if (dz < 1e-15 && it > 1) break;
  }
  for (i = 0; i < 2; i++) {
    s->q[i]  = q[i] + h * v[i] + h * h * ((0.5 - be) * an[i] + be * z[i]) - h * q[i] * z[3];
    s->v[i]  = v[i] + h * ((1 - ga) * an[i] + ga * z[i]);
    s->vd[i] = ((1 - am) * z[i] + am * an[i] - af * s->vd[i]) / (1 - af);
    s->a[i]  = z[i];
  }
  s->l = z[2];
}

/* The consistent start: M vd + g + G^T l = 0, G vd + v . v = 0; a_0 = vd_0. */
static void TextbookStart(PendState *s)
{
  double A[8][8] = {{0}}, b[3];
  A[0][0] = A[1][1] = PEND_M;
  A[0][2] = A[2][0] = s->q[0];
  A[1][2] = A[2][1] = s->q[1];
  b[0] = 0;
  b[1] = -PEND_M * PEND_G;
  b[2] = -(s->v[0] * s->v[0] + s->v[1] * s->v[1]);
  SolveDense(3, A, b);
  s->vd[0] = s->a[0] = b[0];
  s->vd[1] = s->a[1] = b[1];
  s->l = b[2];
}

/* Lignum's GGL generalized-alpha (kinematics kin) against the textbook
 * step: the largest difference in q, v and lambda over nsteps steps. */
static double PendulumTextbook(SUNContext ctx, int kin, double rho, double h, int nsteps)
{
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q = N_VNew_Serial(2, ctx), v = N_VNew_Serial(2, ctx), y = N_VNew_Serial(4, ctx);
  N_Vector l = N_VNew_Serial(1, ctx);
  SUNMatrix A = SUNDenseMatrix(4, 4, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(mem, SUNFALSE);
  LGNSetProjectOutputs(mem, LGN_PROJECT_NONE);
  sunrealtype am, af, be, ga, t;
  PendState s = {{0.6, -0.8}, {1.2, 0.9}, {0, 0}, {0, 0}, 0};
  double dmax = HUGE_VAL;
  int flag, n, i;
  NV_Ith_S(q, 0) = s.q[0]; NV_Ith_S(q, 1) = s.q[1];
  NV_Ith_S(v, 0) = s.v[0]; NV_Ith_S(v, 1) = s.v[1];
  flag = LGNGenAlphaFromRhoInf(rho, &am, &af, &be, &ga);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, PMass);
  if (!flag) flag = LGNSetForceFn(mem, PForce);
  if (!flag) flag = LGNSetConstraints(mem, 1, PConstr, PConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, PStiff);
  if (!flag) flag = LGNSetDampingFn(mem, PDamp);
  if (!flag) flag = LGNSetCurvatureFn(mem, PCurv);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, rho);
  if (!flag) flag = LGNSetKinematics(mem, kin);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSStolerances(mem, 1e-13, 1e-13);
  if (!flag) flag = LGNSetStepSize(mem, h);
  TextbookStart(&s);
  if (!flag) dmax = 0;
  for (n = 1; !flag && n <= nsteps; n++) {
    flag = LGNSolve(mem, n * h, &t, q, v, LGN_NORMAL);
    if (!flag) flag = LGNGetMultipliers(mem, l);
    if (flag) break;
    TextbookStep(&s, h, am, af, be, ga);
    for (i = 0; i < 2; i++) {
      dmax = fmax(dmax, fabs(NV_Ith_S(q, i) - s.q[i]));
      dmax = fmax(dmax, fabs(NV_Ith_S(v, i) - s.v[i]));
    }
    dmax = fmax(dmax, fabs(NV_Ith_S(l, 0) - s.l) / PEND_M / PEND_G);
  }
  if (flag) {
    printf("  flag %d\n", flag);
    dmax = HUGE_VAL;
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  N_VDestroy(l);
  LGNGroup_Destroy(G);
  return dmax;
}

/* ---- (g) the bead on a turning rod (rheonomic; test_ggl's model) ---------- */

#define BEAD_M  2.0
#define BEAD_W  2.0
#define BEAD_R0 0.5
#define BEAD_RD 0.3

static int BMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = BEAD_M;
  SM_ELEMENT_D(M, 1, 1) = BEAD_M;
  return 0;
}

static int BForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)g; (void)ud; /* g = 0 */
  return 0;
}

static int BConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)ud;
  NV_Ith_S(phi, 0) = -NV_Ith_S(q, 0) * sin(BEAD_W * t) + NV_Ith_S(q, 1) * cos(BEAD_W * t);
  return 0;
}

static int BConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)q; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = -sin(BEAD_W * t);
  SM_ELEMENT_D(B, 0, 1) = cos(BEAD_W * t);
  return 0;
}

static int BConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  (void)ud;
  NV_Ith_S(phit, 0) =
      -BEAD_W * (NV_Ith_S(q, 0) * cos(BEAD_W * t) + NV_Ith_S(q, 1) * sin(BEAD_W * t));
  return 0;
}

/* Generalized-alpha (rho_inf 0.9) with GGL and fixed steps h to t = 1:
 * the position error, |Phi| and |B v + Phi_t| at t = 1 (flag != 0:
 * failed). */
static int BeadRun(SUNContext ctx, int kin, double h, double *err, double *phi, double *bv)
{
  LGNGroup G = LGNGroup_Rn(2);
  N_Vector q = N_VNew_Serial(2, ctx), v = N_VNew_Serial(2, ctx), y = N_VNew_Serial(4, ctx);
  N_Vector p = N_VNew_Serial(1, ctx), pt = N_VNew_Serial(1, ctx);
  SUNMatrix A = SUNDenseMatrix(4, 4, ctx), B = SUNDenseMatrix(1, 2, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(mem, SUNFALSE);
  LGNSetProjectOutputs(mem, LGN_PROJECT_NONE);
  sunrealtype t;
  double r;
  int flag;
  NV_Ith_S(q, 0) = BEAD_R0;
  NV_Ith_S(q, 1) = 0.0;
  NV_Ith_S(v, 0) = BEAD_RD;
  NV_Ith_S(v, 1) = BEAD_R0 * BEAD_W; /* co-rotating: consistent */
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, BMass);
  if (!flag) flag = LGNSetForceFn(mem, BForce);
  if (!flag) flag = LGNSetConstraints(mem, 1, BConstr, BConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, BConstrTime);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_GGL);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetKinematics(mem, kin);
  if (!flag) flag = LGNSStolerances(mem, 1e-12, 1e-12);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNSolve(mem, 1.0, &t, q, v, LGN_NORMAL);
  if (!flag) {
    r = BEAD_R0 * cosh(BEAD_W * t) + BEAD_RD / BEAD_W * sinh(BEAD_W * t);
    *err = hypot(NV_Ith_S(q, 0) - r * cos(BEAD_W * t), NV_Ith_S(q, 1) - r * sin(BEAD_W * t));
    BConstr(t, q, p, NULL);
    BConstrJac(t, q, B, NULL);
    BConstrTime(t, q, pt, NULL);
    *phi = fabs(NV_Ith_S(p, 0));
    *bv = fabs(SM_ELEMENT_D(B, 0, 0) * NV_Ith_S(v, 0) + SM_ELEMENT_D(B, 0, 1) * NV_Ith_S(v, 1) +
               NV_Ith_S(pt, 0));
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  SUNMatDestroy(B);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  N_VDestroy(p);
  N_VDestroy(pt);
  LGNGroup_Destroy(G);
  return flag;
}

/* Did the last message contain s? */
static char last_msg[1024];
static void ErrHandler(int code, const char *module, const char *func, const char *msg,
                       void *ud)
{
  (void)code; (void)module; (void)func; (void)ud;
  snprintf(last_msg, sizeof last_msg, "%s", msg);
}

int main(int argc, char **argv)
{
  const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
  SUNContext ctx;
  LGNRefHeavyTop ref03, ref1;
  const double t03 = 0.3, t1 = 1.0;
  static const char *what[3] = {"positions", "velocities", "multipliers"};
  static const char *kname[2] = {"LGGalpha", "mod. LGGalpha"};
  const int kins[2] = {LGN_KINEMATICS_SIMPLIFIED, LGN_KINEMATICS_EXACT};
  int k, i, c;

  SUNContext_Create(NULL, &ctx);
  CHECK(lgnref_heavy_top(&t03, 1, &ref03, LGNREF_FEHLBERG_8) == 0, "reference");
  CHECK(lgnref_heavy_top(&t1, 1, &ref1, LGNREF_FEHLBERG_8) == 0, "reference");

  /* (a) orders with fixed steps */
  if (!quick) {
    const double hs[4] = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
    const int idx[2] = {LGN_CONSTR_GGL, LGN_CONSTR_INDEX3};
    static const char *iname[2] = {"GGL", "index 3"};
    int x;
    printf("(a) fixed steps, errors at t = 0.3 (h = 1e-3 ... 1.25e-4)\n");
    for (k = 0; k < 2; k++)
      for (x = 0; x < 2; x++) {
        double err[3][4], e[3], p;
        for (i = 0; i < 4; i++) {
          FixedStepErrors(ctx, idx[x], kins[k], hs[i], t03, &ref03, e);
          for (c = 0; c < 3; c++) err[c][i] = e[c];
        }
        for (c = 0; c < 3; c++) {
          p = Fit(hs, err[c], 4);
          printf("  %-13s %-7s %-11s: %.3e %.3e %.3e %.3e, fitted order %.3f\n", kname[k],
                 iname[x], what[c], err[c][0], err[c][1], err[c][2], err[c][3], p);
          if (x == 0)
            CHECK(fabs(p - 2) <= 0.2, "(a) %s GGL %s: fitted order %.3f", kname[k], what[c], p);
        }
      }
  }

  /* (a) the multipliers' start transient (printed: GGL's is first order
   * too, as index 3's; a consistent start a_0 = vdot_0, doc/theory.md
   * section 6) */
  if (!quick) {
    const double hs[4] = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
    const int idx[2] = {LGN_CONSTR_GGL, LGN_CONSTR_INDEX3};
    static const char *iname[2] = {"GGL", "index 3"};
    int x;
    int pert;
    printf("(a) max multiplier error over the steps in (0, 0.02]\n");
    for (pert = 0; pert < 2; pert++)
      for (k = 0; k < 2; k++)
        for (x = 0; x < 2; x++) {
          double err[4];
          for (i = 0; i < 4; i++) err[i] = StartLambdaError(ctx, idx[x], kins[k], hs[i], pert);
          printf("  %-13s %-7s%s: %.3e %.3e %.3e %.3e, fitted order %.3f\n", kname[k],
                 iname[x], pert ? " perturbed start" : "", err[0], err[1], err[2], err[3],
                 Fit(hs, err, 4));
          CHECK(err[3] < HUGE_VAL, "(a) start transient %s %s: the runs succeed", kname[k],
                iname[x]);
        }
  }

  /* (b) no drift */
  if (!quick) {
    const int idx[3] = {LGN_CONSTR_GGL, LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
    static const char *iname[3] = {"GGL", "index 3", "index 2"};
    printf("(b) h = 1e-3 to t = 1: max |Phi| and max |B v| along the solution\n");
    for (k = 0; k < 2; k++) {
      double phi[3], bv[3];
      for (i = 0; i < 3; i++) {
        const int flag = Drift(ctx, idx[i], kins[k], &phi[i], &bv[i]);
        printf("  %-13s %-8s: |Phi| %.3e, |B v| %.3e (flag %d)\n", kname[k], iname[i], phi[i],
               bv[i], flag);
        CHECK(flag == 0, "(b) %s %s: flag %d", kname[k], iname[i], flag);
      }
      CHECK(phi[0] <= 1e-13 && bv[0] <= 1e-11, "(b) %s GGL: |Phi| %.3e, |B v| %.3e", kname[k],
            phi[0], bv[0]);
      CHECK(bv[1] > 1e3 * bv[0], "(b) %s: index 3 |B v| %.3e against GGL's %.3e", kname[k],
            bv[1], bv[0]);
      CHECK(phi[2] > 1e3 * phi[0], "(b) %s: index 2 |Phi| %.3e against GGL's %.3e", kname[k],
            phi[2], phi[0]);
    }
  }

  /* (c) against the textbook method on R^2 */
  printf("(c) pendulum on R^2 against generalized-alpha GGL written out, 100 steps\n");
  for (k = 0; k < 2; k++) {
    const double rhos[2] = {0.9, 0.6};
    int j;
    for (j = 0; j < 2; j++) {
      const double d = PendulumTextbook(ctx, kins[k], rhos[j], 0.01, 100);
      printf("  %-13s rho_inf %.1f: max difference in q, v, lambda/(m g) %.3e\n", kname[k],
             rhos[j], d);
      CHECK(d <= 1e-12, "(c) %s rho_inf %.1f: difference %.3e", kname[k], rhos[j], d);
    }
  }

  /* (d) error control */
  if (!quick) {
    const double tols[4] = {1e-5, 1e-6, 1e-7, 1e-8};
    printf("(d) GGL, error control to t = 1\n");
    for (k = 0; k < 2; k++) {
      double err[4], p;
      long int nst[4];
      for (i = 0; i < 4; i++) {
        int flag;
        err[i] = AdaptiveRun(ctx, kins[k], tols[i], &ref1, &nst[i], &flag);
        printf("  %-13s tol %.0e: error %.3e, %5ld steps (flag %d)\n", kname[k], tols[i],
               err[i], nst[i], flag);
        CHECK(flag == 0, "(d) %s tol %.0e: flag %d", kname[k], tols[i], flag);
      }
      p = Fit(tols, err, 4);
      printf("  %-13s error ~ tol^%.3f\n", kname[k], p);
      /* error per unit step: ~ tol^1 (the error per step gave 0.6 - 0.8) */
      CHECK(p > 0.85 && p < 1.15, "(d) %s: error ~ tol^%.3f", kname[k], p);
    }
  }

  /* (g) rheonomic constraints */
  if (!quick) {
    const double hs[3] = {0.02, 0.01, 0.005};
    printf("(g) bead on a turning rod (Phi_t), GGL, fixed steps to t = 1\n");
    for (k = 0; k < 2; k++) {
      double err[3], phi = HUGE_VAL, bv = HUGE_VAL, p;
      for (i = 0; i < 3; i++) {
        const int flag = BeadRun(ctx, kins[k], hs[i], &err[i], &phi, &bv);
        printf("  %-13s h %.3f: error %.3e, |Phi| %.3e, |B v + Phi_t| %.3e (flag %d)\n",
               kname[k], hs[i], err[i], phi, bv, flag);
        CHECK(flag == 0 && phi <= 1e-14 && bv <= 1e-12,
              "(g) %s h %g: flag %d, |Phi| %.3e, |B v + Phi_t| %.3e", kname[k], hs[i], flag, phi,
              bv);
      }
      p = Fit(hs, err, 3);
      printf("  %-13s fitted order %.3f\n", kname[k], p);
      CHECK(fabs(p - 2) <= 0.2, "(g) %s: fitted order %.3f", kname[k], p);
    }
  }

  /* (e) a start off B v = 0, refused and repaired */
  for (k = 0; k < 2; k++) {
    Run r;
    sunrealtype t;
    double phi, bv;
    int flag = RunMethod(&r, ctx, LGN_CONSTR_GGL, kins[k], 1e-3);
    printf("(e) %s: inconsistent velocity under GGL\n", kname[k]);
    NV_Ith_S(r.v, 2) += 1e-3; /* B v = u - Omega x X at R = I */
    if (!flag) flag = LGNReInit(r.mem, 0.0, r.q, r.v);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_INCONSISTENT_IC, "(e) %s: |B v0| = 1e-3 under GGL: %s", kname[k],
          LGNGetReturnFlagName(flag));
    flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_QV);
    CHECK(flag == LGN_SUCCESS, "(e) LGNCalcIC: %s", LGNGetReturnFlagName(flag));
    if (!flag) flag = LGNSolve(r.mem, 0.0, &t, r.q, r.v, LGN_NORMAL);
    Violations(&r, &phi, &bv);
    printf("  after LGNCalcIC: |Phi| %.3e, |B v| %.3e\n", phi, bv);
    CHECK(phi <= 1e-14 && bv <= 1e-12, "(e) projected start: |Phi| %.3e, |B v| %.3e", phi, bv);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    Violations(&r, &phi, &bv);
    CHECK(flag == LGN_SUCCESS && phi <= 1e-13 && bv <= 1e-11,
          "(e) the run after LGNCalcIC: %s, |Phi| %.3e, |B v| %.3e",
          LGNGetReturnFlagName(flag), phi, bv);
    RunFree(&r);
  }

  /* (f) bad input */
  {
    Run r;
    sunrealtype t;
    int flag;
    printf("(f) bad input\n");
    flag = RunMethod(&r, ctx, LGN_CONSTR_GGL, LGN_KINEMATICS_SIGMA, 1e-3);
    if (!flag) flag = LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
    last_msg[0] = 0;
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    printf("  sigma variant: %s\n", last_msg);
    CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "sigma variant") != NULL,
          "(f) GGL with the sigma variant: %s (%s)", LGNGetReturnFlagName(flag), last_msg);
    /* the same memory runs with the exact variant */
    flag = LGNSetKinematics(r.mem, LGN_KINEMATICS_EXACT);
    if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "(f) GGL, exact, after the refusal: %s",
          LGNGetReturnFlagName(flag));
    RunFree(&r);
    /* a Krylov solver */
    flag = RunMethod(&r, ctx, LGN_CONSTR_GGL, LGN_KINEMATICS_SIMPLIFIED, 1e-3);
    {
      SUNLinearSolver kry = SUNLinSol_SPGMR(r.y, SUN_PREC_NONE, 20, ctx);
      if (!flag) flag = LGNSetLinearSolver(r.mem, kry, NULL);
      if (!flag) flag = LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
      last_msg[0] = 0;
      if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
      printf("  Krylov: %s\n", last_msg);
      CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "Krylov") != NULL &&
                strstr(last_msg, "dense assembly") != NULL,
            "(f) GGL with a Krylov solver: %s (%s)", LGNGetReturnFlagName(flag), last_msg);
      LGNFree(&r.mem); /* before the solver it holds */
      SUNLinSolFree(kry);
    }
    RunFree(&r);
#if defined(LGN_HAVE_KLU)
    flag = RunMethod(&r, ctx, LGN_CONSTR_GGL, LGN_KINEMATICS_EXACT, 1e-3);
    {
      SUNMatrix S = SUNSparseMatrix(12, 12, 1, CSC_MAT, ctx);
      SUNLinearSolver klu = SUNLinSol_KLU(r.y, S, ctx);
      if (!flag) flag = LGNSetLinearSolver(r.mem, klu, S);
      if (!flag) flag = LGNSetErrHandlerFn(r.mem, ErrHandler, NULL);
      last_msg[0] = 0;
      if (!flag) flag = LGNSolve(r.mem, 1e-2, &t, r.q, r.v, LGN_NORMAL);
      printf("  sparse: %s\n", last_msg);
      CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "sparse") != NULL &&
                strstr(last_msg, "dense assembly") != NULL,
            "(f) GGL with a sparse matrix (KLU): %s (%s)", LGNGetReturnFlagName(flag), last_msg);
      LGNFree(&r.mem);
      SUNLinSolFree(klu);
      SUNMatDestroy(S);
    }
    RunFree(&r);
#endif
  }

  /* (h) LGNGetWorkSpace counts GGL's B(q_n) (m x nv reals, held for the
   * Newmark family's correction): GGL's lenrw exceeds index 3's by at least
   * m nv + 2 m (B(q_n); the Newton vectors' m more rows each) */
  {
    Run r3, rg;
    sunrealtype t;
    long int rw3 = 0, iw3 = 0, rwg = 0, iwg = 0;
    int flag = RunMethod(&r3, ctx, LGN_CONSTR_INDEX3, LGN_KINEMATICS_EXACT, 1e-3);
    if (!flag) flag = LGNSolve(r3.mem, 2e-3, &t, r3.q, r3.v, LGN_NORMAL);
    if (!flag) flag = LGNGetWorkSpace(r3.mem, &rw3, &iw3);
    if (!flag) flag = RunMethod(&rg, ctx, LGN_CONSTR_GGL, LGN_KINEMATICS_EXACT, 1e-3);
    if (!flag) flag = LGNSolve(rg.mem, 2e-3, &t, rg.q, rg.v, LGN_NORMAL);
    if (!flag) flag = LGNGetWorkSpace(rg.mem, &rwg, &iwg);
    printf("(h) LGNGetWorkSpace: lenrw %ld (index 3), %ld (GGL)\n", rw3, rwg);
    CHECK(flag == LGN_SUCCESS, "(h) runs: %s", LGNGetReturnFlagName(flag));
    CHECK(rwg - rw3 >= 3 * 6 + 2 * 3,
          "(h) GGL's lenrw %ld exceeds index 3's %ld by %ld < m nv + 2 m = 24", rwg, rw3,
          rwg - rw3);
    RunFree(&r3);
    RunFree(&rg);
  }

  SUNContext_Free(&ctx);
  return test_summary("test_ggl_newmark");
}
