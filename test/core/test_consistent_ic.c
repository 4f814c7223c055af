/* -----------------------------------------------------------------------------
 * Consistent initial values (LGNCalcIC, LGNGetConsistentIC, the check of the
 * first LGNSolve, LGNSetPerturbedStart) on the heavy top in R^3 x SO(3)
 * (doc/accuracy-study.md: m = 15, J = diag(0.234375, 0.46875, 0.234375),
 * X = e_y, spherical joint Phi = X - R^T x), with a model of its own that
 * fills dense and sparse (CSC) matrices; K_t, C_t, Z by difference quotients.
 *  (a) LGNCalcIC from q0 1 cm off the joint and a v0 off B v = 0, dense and
 *      KLU, index 3 and index 2: |Phi| <= 1e-12, |B v| <= 1e-12, the
 *      projected state is the minimum-norm correction (its q, v differences
 *      match the first-order M-orthogonal projection, and it is within about
 *      the violation of the perturbed state), LGNSolve then succeeds;
 *  (b) without LGNCalcIC the first LGNSolve fails with LGN_INCONSISTENT_IC,
 *      names the violation, takes no step; a consistent start passes;
 *  (c) the perturbed start: order of max_t |lambda - lambda_ref| over
 *      h = 2e-3 ... 2.5e-4 against the ARKODE reference (lgn_reference) is
 *      2.0 +- 0.2 with it and about 1 without (index 3, rho_inf = 0.9);
 *  (d) bad input to every new function: a flag and a message naming it;
 *      a projection that cannot converge: LGN_IC_FAIL with |Phi|.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#ifdef LGN_HAVE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include "lgn_reference.h"
#include "test_util.h"

#define MASS 15.0
static const double J[3] = {0.234375, 0.46875, 0.234375};
static const double XB[3] = {0.0, 1.0, 0.0};

/* ---- the model ---------------------------------------------------------- */

/* A (rows x cols) from the dense row-major D: dense, or sparse CSC / CSR. */
static int Fill(SUNMatrix A, const double *D, int rows, int cols)
{
  int i, j;
  if (SUNMatGetID(A) == SUNMATRIX_DENSE) {
    for (i = 0; i < rows; i++)
      for (j = 0; j < cols; j++) SM_ELEMENT_D(A, i, j) = D[i * cols + j];
    return 0;
  } else {
    const int csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    const int nout = csc ? cols : rows, nin = csc ? rows : cols;
    sunindextype nnz = 0, *ptr, *ind;
    double *val;
    int o, k;
    for (i = 0; i < rows * cols; i++) nnz += D[i] != 0.0;
    if (SUNSparseMatrix_NNZ(A) < nnz && SUNSparseMatrix_Reallocate(A, nnz) != 0) return -1;
    ptr = SUNSparseMatrix_IndexPointers(A);
    ind = SUNSparseMatrix_IndexValues(A);
    val = SUNSparseMatrix_Data(A);
    nnz = 0;
    for (o = 0; o < nout; o++) {
      ptr[o] = nnz;
      for (k = 0; k < nin; k++) {
        const double d = csc ? D[k * cols + o] : D[o * cols + k];
        if (d != 0.0) {
          ind[nnz] = k;
          val[nnz] = d;
          nnz++;
        }
      }
    }
    ptr[nout] = nnz;
    return 0;
  }
}

static void Rot(N_Vector q, double R[9]) { LGNQuaternionToRotation(N_VGetArrayPointer(q) + 3, R); }

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  double D[36] = {0};
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) {
    D[i * 6 + i] = MASS;
    D[(3 + i) * 6 + 3 + i] = J[i];
  }
  return Fill(M, D, 6, 6);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *w = N_VGetArrayPointer(v) + 3;
  double *gg = N_VGetArrayPointer(g);
  (void)t; (void)q; (void)ud;
  gg[0] = 0.0;
  gg[1] = 0.0;
  gg[2] = MASS * 9.81;
  gg[3] = w[1] * J[2] * w[2] - w[2] * J[1] * w[1];
  gg[4] = w[2] * J[0] * w[0] - w[0] * J[2] * w[2];
  gg[5] = w[0] * J[1] * w[1] - w[1] * J[0] * w[0];
  return 0;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double *x = N_VGetArrayPointer(q);
  double R[9], *ph = N_VGetArrayPointer(phi);
  int i;
  (void)t; (void)ud;
  Rot(q, R);
  for (i = 0; i < 3; i++) ph[i] = XB[i] - (R[i] * x[0] + R[3 + i] * x[1] + R[6 + i] * x[2]);
  return 0;
}

/* B = [-R^T, -X~] */
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  double R[9], D[18] = {0};
  int i, j;
  (void)t; (void)ud;
  Rot(q, R);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) D[i * 6 + j] = -R[3 * j + i];
  /* -X~ for X = e_y: X~ = [[0,0,1],[0,0,0],[-1,0,0]] */
  D[0 * 6 + 5] = -1.0;
  D[2 * 6 + 3] = 1.0;
  return Fill(B, D, 3, 6);
}

/* ---- a run -------------------------------------------------------------- */

typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, lambda, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} Run;

static char last_msg[1024];
static int last_code;
static void Capture(int code, const char *mod, const char *fn, const char *msg, void *d)
{
  (void)mod; (void)fn; (void)d;
  last_code = code;
  snprintf(last_msg, sizeof last_msg, "%s", msg);
}

/* The exact start of the benchmark, then a perturbation: x0 by dx (m),
 * u0 by du (m/s). */
static void Start(Run *r, const double dx[3], const double du[3])
{
  double *q = N_VGetArrayPointer(r->q), *v = N_VGetArrayPointer(r->v);
  int i;
  memset(q, 0, 7 * sizeof(double));
  memset(v, 0, 6 * sizeof(double));
  q[1] = 1.0;
  q[3] = 1.0;
  v[0] = 4.61538; /* Omega0 x X */
  v[4] = 150.0;
  v[5] = -4.61538;
  for (i = 0; i < 3; i++) {
    q[i] += dx[i];
    v[i] += du[i];
  }
}

static int RunCreate(Run *r, SUNContext ctx, int klu, int index, double h,
                     const double dx[3], const double du[3])
{
  int flag;
  memset(r, 0, sizeof *r);
  r->ctx = ctx;
  r->G = LGNGroup_R3xSO3();
  r->q = N_VNew_Serial(7, ctx);
  r->v = N_VNew_Serial(6, ctx);
  r->lambda = N_VNew_Serial(3, ctx);
  r->tmpl = N_VNew_Serial(9, ctx);
#ifdef LGN_HAVE_KLU
  if (klu) {
    r->A = SUNSparseMatrix(9, 9, 40, CSC_MAT, ctx);
    r->LS = SUNLinSol_KLU(r->tmpl, r->A, ctx);
  }
#endif
  if (!klu) {
    r->A = SUNDenseMatrix(9, 9, ctx);
    r->LS = SUNLinSol_Dense(r->tmpl, r->A, ctx);
  }
  r->mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(r->mem, SUNFALSE);
  LGNSetProjectOutputs(r->mem, LGN_PROJECT_NONE);
  if (!r->G || !r->q || !r->v || !r->A || !r->LS || !r->mem) return LGN_MEM_FAIL;
  Start(r, dx, du);
  flag = LGNSetGroup(r->mem, r->G);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, Force);
  if (!flag) flag = LGNSetConstraints(r->mem, 3, Constr, ConstrJac);
  if (!flag) flag = LGNInit(r->mem, 0.0, r->q, r->v);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = LGNSetGenAlpha(r->mem, 0.9);
  if (!flag) flag = LGNSetConstraintIndex(r->mem, index);
  if (!flag) flag = LGNSetStepSize(r->mem, h);
  if (!flag) flag = LGNSStolerances(r->mem, 1e-10, 1e-10);
  if (!flag) flag = LGNSetErrHandlerFn(r->mem, Capture, NULL);
  return flag;
}

static void RunFree(Run *r)
{
  LGNFree(&r->mem);
  if (r->LS) SUNLinSolFree(r->LS);
  if (r->A) SUNMatDestroy(r->A);
  if (r->q) N_VDestroy(r->q);
  if (r->v) N_VDestroy(r->v);
  if (r->lambda) N_VDestroy(r->lambda);
  if (r->tmpl) N_VDestroy(r->tmpl);
  LGNGroup_Destroy(r->G);
}

/* |Phi(q)|_inf and |B(q) v|_inf with the model's own callbacks (dense). */
static void Violation(SUNContext ctx, N_Vector q, N_Vector v, double *phi, double *bv)
{
  N_Vector p = N_VNew_Serial(3, ctx);
  SUNMatrix B = SUNDenseMatrix(3, 6, ctx);
  double *vv = N_VGetArrayPointer(v);
  int i, j;
  Constr(0.0, q, p, NULL);
  ConstrJac(0.0, q, B, NULL);
  *phi = N_VMaxNorm(p);
  *bv = 0.0;
  for (i = 0; i < 3; i++) {
    double s = 0.0;
    for (j = 0; j < 6; j++) s += SM_ELEMENT_D(B, i, j) * vv[j];
    *bv = fmax(*bv, fabs(s));
  }
  N_VDestroy(p);
  SUNMatDestroy(B);
}

/* ---- (a) LGNCalcIC ------------------------------------------------------ */

static void CalcIC(SUNContext ctx, int klu, int index)
{
  const double dx[3] = {0.01, 0.0, 0.0}, du[3] = {0.0, 0.3, -0.2};
  const char *name = klu ? "KLU" : "dense";
  Run r;
  N_Vector q0 = N_VNew_Serial(7, ctx), v0 = N_VNew_Serial(6, ctx);
  N_Vector qp = N_VNew_Serial(7, ctx), vp = N_VNew_Serial(6, ctx);
  double phi, bv, dq, dv, t = 0.0, R[9], Rt_dx[3];
  int flag, i;

  flag = RunCreate(&r, ctx, klu, index, 1e-3, dx, du);
  N_VScale(1.0, r.q, qp);
  N_VScale(1.0, r.v, vp);
  Violation(ctx, qp, vp, &phi, &bv);
  CHECK(flag == 0 && phi > 0.009 && bv > 0.1,
        "%s idx%d: the perturbed start is off the constraints (|Phi| = %g, |B v| = %g)",
        name, index, phi, bv);
  if (!flag) flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_QV);
  CHECK(flag == LGN_SUCCESS, "%s idx%d: LGNCalcIC: %s (%s)", name, index,
        LGNGetReturnFlagName(flag), last_msg);
  if (!flag) flag = LGNGetConsistentIC(r.mem, q0, v0);
  CHECK(flag == LGN_SUCCESS, "%s idx%d: LGNGetConsistentIC: %s", name, index,
        LGNGetReturnFlagName(flag));
  {
    long int nnz = -1;
    LGNGetIterationMatrixNnz(r.mem, &nnz);
    CHECK(klu ? (nnz > 0 && nnz < 81) : nnz == 81,
          "%s idx%d: the saddle-point matrix was assembled %s (nnz = %ld)", name, index,
          klu ? "sparse" : "dense", nnz);
  }
  Violation(ctx, q0, v0, &phi, &bv);
  CHECK(phi <= 1e-12 && bv <= 1e-12,
        "%s idx%d: projected onto the constraints: |Phi| = %.3g, |B v| = %.3g (<= 1e-12)",
        name, index, phi, bv);
  /* close to the perturbed state: the correction is about the 1 cm */
  dq = 0.0;
  for (i = 0; i < 3; i++) dq = fmax(dq, fabs(N_VGetArrayPointer(q0)[i] - N_VGetArrayPointer(qp)[i]));
  for (i = 3; i < 7; i++) dq = fmax(dq, fabs(N_VGetArrayPointer(q0)[i] - N_VGetArrayPointer(qp)[i]));
  CHECK(dq > 0.0 && dq <= 1.5 * 0.01, "%s idx%d: q0 moved by %.3g (close to the perturbed one: <= 1.5 cm)",
        name, index, dq);
  /* the minimum-norm property (to first order in the 1 cm): M dq in the
   * range of B^T = [-R; X~], i.e. m dx = -R mu and J dtheta = X~ mu, so
   * J dtheta = -X x (m R^T dx) */
  {
    double th[3], xc[3], lhs[3], rhs[3], err = 0.0, scale = 0.0;
    const double *a = N_VGetArrayPointer(q0), *b = N_VGetArrayPointer(qp);
    LGNRotationVectorFromQuaternion(a + 3, th);
    for (i = 0; i < 3; i++) xc[i] = MASS * (a[i] - b[i]);
    Rot(q0, R);
    for (i = 0; i < 3; i++) Rt_dx[i] = R[i] * xc[0] + R[3 + i] * xc[1] + R[6 + i] * xc[2];
    rhs[0] = XB[1] * Rt_dx[2] - XB[2] * Rt_dx[1];
    rhs[1] = XB[2] * Rt_dx[0] - XB[0] * Rt_dx[2];
    rhs[2] = XB[0] * Rt_dx[1] - XB[1] * Rt_dx[0];
    for (i = 0; i < 3; i++) {
      lhs[i] = J[i] * th[i];
      err = fmax(err, fabs(lhs[i] + rhs[i]));
      scale = fmax(scale, fabs(rhs[i]));
    }
    CHECK(scale > 0.0 && err <= 0.02 * scale,
          "%s idx%d: the correction of q is M-orthogonal to the constraint manifold "
          "(J dtheta + X x (m R^T dx) = %.3g of %.3g)", name, index, err, scale);
  }
  /* v: M-orthogonal, M (v0 - vp) in the range of B^T (same relation, exact) */
  {
    const double *a = N_VGetArrayPointer(v0), *b = N_VGetArrayPointer(vp);
    double mu[3], rt[3], err = 0.0, scale = 0.0, rhs[3];
    for (i = 0; i < 3; i++) mu[i] = MASS * (a[i] - b[i]);
    Rot(q0, R);
    for (i = 0; i < 3; i++) rt[i] = R[i] * mu[0] + R[3 + i] * mu[1] + R[6 + i] * mu[2];
    rhs[0] = XB[1] * rt[2] - XB[2] * rt[1];
    rhs[1] = XB[2] * rt[0] - XB[0] * rt[2];
    rhs[2] = XB[0] * rt[1] - XB[1] * rt[0];
    dv = 0.0;
    for (i = 0; i < 3; i++) {
      err = fmax(err, fabs(J[i] * (a[3 + i] - b[3 + i]) + rhs[i]));
      scale = fmax(scale, fabs(rhs[i]));
    }
    for (i = 0; i < 6; i++) dv = fmax(dv, fabs(a[i] - b[i]));
    CHECK(scale > 0.0 && err <= 1e-9 * scale && dv <= 1.5 * 0.3,
          "%s idx%d: the correction of v is M-orthogonal (J dOmega + X x (m R^T du) = %.3g "
          "of %.3g), |dv| = %.3g", name, index, err, scale, dv);
  }
  /* LGNSolve at t0 returns the projected state, and integrates on */
  flag = LGNSolve(r.mem, 0.0, &t, r.q, r.v, LGN_NORMAL);
  N_VLinearSum(1.0, r.q, -1.0, q0, qp);
  N_VLinearSum(1.0, r.v, -1.0, v0, vp);
  CHECK(flag == LGN_SUCCESS && N_VMaxNorm(qp) == 0.0 && N_VMaxNorm(vp) == 0.0,
        "%s idx%d: LGNSolve(t0) returns the projected state (%s)", name, index,
        LGNGetReturnFlagName(flag));
  flag = LGNSolve(r.mem, 0.1, &t, r.q, r.v, LGN_NORMAL);
  Violation(ctx, r.q, r.v, &phi, &bv);
  CHECK(flag == LGN_SUCCESS && (index == LGN_CONSTR_INDEX2 || phi <= 1e-8),
        "%s idx%d: LGNSolve to 0.1 after LGNCalcIC: %s, |Phi| = %.3g", name, index,
        LGNGetReturnFlagName(flag), phi);
  RunFree(&r);
  N_VDestroy(q0);
  N_VDestroy(v0);
  N_VDestroy(qp);
  N_VDestroy(vp);
}

/* Only q, only v. */
static void CalcICParts(SUNContext ctx)
{
  const double dx[3] = {0.0, 0.0, 0.01}, du[3] = {0.0, 0.5, 0.0};
  Run r;
  N_Vector q0 = N_VNew_Serial(7, ctx), v0 = N_VNew_Serial(6, ctx);
  double phi, bv;
  int flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, dx, du);
  if (!flag) flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_Q);
  if (!flag) flag = LGNGetConsistentIC(r.mem, q0, v0);
  Violation(ctx, q0, v0, &phi, &bv);
  CHECK(flag == 0 && phi <= 1e-12 && bv > 0.1 && N_VGetArrayPointer(v0)[1] == 0.5,
        "LGN_IC_PROJECT_Q: q projected (|Phi| = %.3g), v kept (|B v| = %.3g): %s",
        phi, bv, LGNGetReturnFlagName(flag));
  RunFree(&r);
  flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, dx, du);
  if (!flag) flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_V);
  if (!flag) flag = LGNGetConsistentIC(r.mem, q0, v0);
  Violation(ctx, q0, v0, &phi, &bv);
  CHECK(flag == 0 && phi > 0.009 && bv <= 1e-12 && N_VGetArrayPointer(q0)[2] == 0.01,
        "LGN_IC_PROJECT_V: q kept (|Phi| = %.3g), v projected (|B v| = %.3g): %s",
        phi, bv, LGNGetReturnFlagName(flag));
  RunFree(&r);
  N_VDestroy(q0);
  N_VDestroy(v0);
}

/* A constraint without a zero, Phi(x) = exp(x) on R^1: Newton creeps by
 * dx = -1 per iteration and |Phi| falls only by e each time. */
static int MassR1(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  return 0;
}
static int ForceR1(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  N_VGetArrayPointer(g)[0] = 0.0;
  return 0;
}
static int PhiExp(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  (void)t; (void)ud;
  N_VGetArrayPointer(phi)[0] = exp(N_VGetArrayPointer(q)[0]);
  return 0;
}
static int JacExp(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  (void)t; (void)ud;
  SM_ELEMENT_D(B, 0, 0) = exp(N_VGetArrayPointer(q)[0]);
  return 0;
}

static void NoConvergence(SUNContext ctx)
{
  LGNGroup G = LGNGroup_Rn(1);
  N_Vector q = N_VNew_Serial(1, ctx), v = N_VNew_Serial(1, ctx), t2 = N_VNew_Serial(2, ctx);
  SUNMatrix A = SUNDenseMatrix(2, 2, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(t2, A, ctx);
  void *mem = LGNCreate(ctx);
  int flag;
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  LGNSetErrHandlerFn(mem, Capture, NULL);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, MassR1);
  if (!flag) flag = LGNSetForceFn(mem, ForceR1);
  if (!flag) flag = LGNSetConstraints(mem, 1, PhiExp, JacExp);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  last_msg[0] = '\0';
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_Q);
  /* B = e^x vanishes as x -> -inf: the projection either runs out of
   * iterations (|Phi| = e^-20 after 20) or, first, meets a numerically
   * singular [[M, B^T], [B, 0]] (pivot -B^2 below 1e-13 from x ~ -15),
   * which the singular-matrix check of the linear solver bridge reports */
  CHECK(flag == LGN_IC_FAIL &&
            ((strstr(last_msg, "did not converge in 20") != NULL &&
              strstr(last_msg, "|Phi|_inf = 2.06") != NULL) ||
             strstr(last_msg, "singular") != NULL),
        "Phi = exp(x): LGNCalcIC fails with LGN_IC_FAIL (no zero of Phi): %s \"%s\"",
        LGNGetReturnFlagName(flag), last_msg);
  N_VConst(-1.0, q);
  flag = LGNGetConsistentIC(mem, q, NULL);
  CHECK(flag == LGN_SUCCESS && N_VGetArrayPointer(q)[0] == 0.0,
        "after the failure q0 is as it was (%g)", N_VGetArrayPointer(q)[0]);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(t2);
  LGNGroup_Destroy(G);
}

/* ---- (b) the check ------------------------------------------------------- */

static void Check(SUNContext ctx)
{
  const double dx[3] = {0.01, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
  const double du[3] = {0.0, 0.02, 0.0};
  Run r;
  long int nst = -1;
  double t = -1.0;
  int flag;

  /* index 3, q0 1 cm off */
  flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, dx, zero);
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(r.mem, 0.1, &t, r.q, r.v, LGN_NORMAL);
  LGNGetNumSteps(r.mem, &nst);
  CHECK(flag == LGN_INCONSISTENT_IC && last_code == LGN_INCONSISTENT_IC && nst == 0 && t == 0.0,
        "idx3, q0 1 cm off: LGNSolve fails with LGN_INCONSISTENT_IC before any step (%s, %ld steps)",
        LGNGetReturnFlagName(flag), nst);
  CHECK(strstr(last_msg, "|Phi(q0)|_inf = 0.01 ") != NULL && strstr(last_msg, "LGNCalcIC") != NULL,
        "idx3: the message names the violation and the remedy: \"%s\"", last_msg);
  CHECK(strcmp(LGNGetReturnFlagName(LGN_INCONSISTENT_IC), "LGN_INCONSISTENT_IC") == 0,
        "flag name: %s", LGNGetReturnFlagName(LGN_INCONSISTENT_IC));
  /* and after LGNCalcIC it runs */
  flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_QV);
  if (!flag) flag = LGNSolve(r.mem, 0.01, &t, r.q, r.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "idx3: after LGNCalcIC: %s", LGNGetReturnFlagName(flag));
  RunFree(&r);

  /* index 2, v0 off B v = 0 by 2 cm/s */
  flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX2, 1e-3, zero, du);
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(r.mem, 0.1, &t, r.q, r.v, LGN_NORMAL);
  CHECK(flag == LGN_INCONSISTENT_IC && strstr(last_msg, "|B(q0) v0|_inf = 0.02 ") != NULL,
        "idx2, v0 off: LGN_INCONSISTENT_IC naming |B v| (%s: \"%s\")",
        LGNGetReturnFlagName(flag), last_msg);
  RunFree(&r);

  /* a consistent start, and one within the tolerance 100 (atol + rtol |q|)
   * = 2e-8 (tolerances 1e-10): no complaint */
  {
    const double small[3] = {1.5e-8, 0.0, 0.0}, big[3] = {3e-8, 0.0, 0.0};
    flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, small, zero);
    if (!flag) flag = LGNSolve(r.mem, 0.01, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS, "idx3, |Phi| = 1.5e-8 within 2e-8: %s", LGNGetReturnFlagName(flag));
    RunFree(&r);
    flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, big, zero);
    if (!flag) flag = LGNSolve(r.mem, 0.01, &t, r.q, r.v, LGN_NORMAL);
    CHECK(flag == LGN_INCONSISTENT_IC, "idx3, |Phi| = 3e-8 beyond 2e-8: %s", LGNGetReturnFlagName(flag));
    RunFree(&r);
  }
}

/* ---- (c) the perturbed start: order of max_t |lambda error| ------------- */

static double MaxLambdaError(SUNContext ctx, double h, int pstart, int *flag_out)
{
  const double zero[3] = {0.0, 0.0, 0.0}, T = 1.0;
  const int n = (int)lround(T / h);
  static LGNRefHeavyTop ref[8001];
  Run r;
  double t = 0.0, err = 0.0;
  int k, i, flag;

  if (n > 8000 || lgnref_heavy_top_uniform(T, n, ref, LGNREF_FEHLBERG_8) != 0) {
    *flag_out = -1;
    return -1.0;
  }
  flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, h, zero, zero);
  if (!flag && pstart >= 0) flag = LGNSetPerturbedStart(r.mem, pstart ? SUNTRUE : SUNFALSE);
  for (k = 1; flag == 0 && k <= n; k++) {
    flag = LGNSolve(r.mem, T * k / n, &t, r.q, r.v, LGN_NORMAL);
    if (!flag) flag = LGNGetMultipliers(r.mem, r.lambda);
    for (i = 0; flag == 0 && i < 3; i++)
      err = fmax(err, fabs(N_VGetArrayPointer(r.lambda)[i] - ref[k].lambda[i]));
  }
  *flag_out = flag;
  RunFree(&r);
  return err;
}

static double FitOrder(const double *h, const double *e, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double x = log(h[i]), y = log(e[i]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void PerturbedStart(SUNContext ctx)
{
  const double h[4] = {2e-3, 1e-3, 5e-4, 2.5e-4};
  double e_on[4], e_off[4], e_def[4], p_on, p_off;
  int i, f1, f2, f3;
  printf("  h         max|dlambda| off  on (perturbed start)\n");
  for (i = 0; i < 4; i++) {
    e_off[i] = MaxLambdaError(ctx, h[i], 0, &f1);
    e_on[i]  = MaxLambdaError(ctx, h[i], 1, &f2);
    e_def[i] = MaxLambdaError(ctx, h[i], -1, &f3);
    printf("  %-9.3g %-16.6g %-.6g\n", h[i], e_off[i], e_on[i]);
    CHECK(f1 == 0 && f2 == 0 && f3 == 0, "h = %g: runs succeed (%d %d %d)", h[i], f1, f2, f3);
    CHECK(e_def[i] == e_off[i],
          "h = %g: the default is off, bit for bit (%.17g vs %.17g)", h[i],
          e_def[i], e_off[i]);
  }
  p_on  = FitOrder(h, e_on, 4);
  p_off = FitOrder(h, e_off, 4);
  printf("  fitted order: off %.3f, on %.3f\n", p_off, p_on);
  CHECK(fabs(p_on - 2.0) <= 0.2, "perturbed start: order of max_t |lambda error| %.3f (2.0 +- 0.2)", p_on);
  CHECK(p_off >= 0.7 && p_off <= 1.3, "without: order %.3f (about 1)", p_off);
  CHECK(e_on[3] < 0.05 * e_off[3], "h = 2.5e-4: %.3g with vs %.3g without", e_on[3], e_off[3]);

  /* index 2 (a_0 only) and error control (with the first step tried):
   * it runs, and changes the result */
  {
    const double zero[3] = {0.0, 0.0, 0.0};
    double x_on[2][7], x_off[2][7], t;
    int mode, on, flag;
    for (mode = 0; mode < 2; mode++)
      for (on = 0; on < 2; on++) {
        Run r;
        flag = RunCreate(&r, ctx, 0, mode == 0 ? LGN_CONSTR_INDEX2 : LGN_CONSTR_INDEX3,
                         1e-3, zero, zero);
        if (!flag && mode == 1) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
        if (!flag && mode == 1) flag = LGNSStolerances(r.mem, 1e-6, 1e-6);
        if (!flag) flag = LGNSetPerturbedStart(r.mem, on);
        if (!flag) flag = LGNSolve(r.mem, 0.05, &t, r.q, r.v, LGN_NORMAL);
        CHECK(flag == LGN_SUCCESS, "%s, perturbed start %s: %s",
              mode == 0 ? "index 2" : "error control", on ? "on" : "off",
              LGNGetReturnFlagName(flag));
        for (i = 0; i < 7; i++) (on ? x_on : x_off)[mode][i] = N_VGetArrayPointer(r.q)[i];
        RunFree(&r);
      }
    for (mode = 0; mode < 2; mode++) {
      double d = 0.0;
      for (i = 0; i < 7; i++) d = fmax(d, fabs(x_on[mode][i] - x_off[mode][i]));
      CHECK(d > 0.0 && d < 1e-3, "%s: the perturbed start changes q(0.05) a little (%.3g)",
            mode == 0 ? "index 2" : "error control", d);
    }
  }
}

/* ---- (d) bad input ------------------------------------------------------ */

static void BadInput(SUNContext ctx)
{
  const double zero[3] = {0.0, 0.0, 0.0};
  Run r;
  N_Vector w5 = N_VNew_Serial(5, ctx), q0 = N_VNew_Serial(7, ctx);
  void *bare = LGNCreate(ctx);
  double t;
  int flag;

  CHECK(LGNCalcIC(NULL, LGN_IC_PROJECT_QV) == LGN_MEM_NULL, "LGNCalcIC(NULL)");
  CHECK(LGNGetConsistentIC(NULL, q0, NULL) == LGN_MEM_NULL, "LGNGetConsistentIC(NULL)");
  CHECK(LGNSetPerturbedStart(NULL, SUNTRUE) == LGN_MEM_NULL, "LGNSetPerturbedStart(NULL)");
  LGNSetErrHandlerFn(bare, Capture, NULL);
  CHECK(LGNCalcIC(bare, LGN_IC_PROJECT_QV) == LGN_NO_MALLOC, "LGNCalcIC before LGNInit");
  CHECK(LGNGetConsistentIC(bare, q0, NULL) == LGN_NO_MALLOC, "LGNGetConsistentIC before LGNInit");
  LGNFree(&bare);

  flag = RunCreate(&r, ctx, 0, LGN_CONSTR_INDEX3, 1e-3, zero, zero);
  last_msg[0] = '\0';
  flag = LGNCalcIC(r.mem, 7);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "icopt") != NULL,
        "LGNCalcIC(icopt = 7): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNCalcIC(r.mem, 0);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "icopt") != NULL,
        "LGNCalcIC(icopt = 0): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNGetConsistentIC(r.mem, w5, NULL);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "q0") != NULL,
        "LGNGetConsistentIC(q0 of length 5): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNGetConsistentIC(r.mem, NULL, w5);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "v0") != NULL,
        "LGNGetConsistentIC(v0 of length 5): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNGetConsistentIC(r.mem, NULL, NULL);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "q0") != NULL && strstr(last_msg, "v0") != NULL,
        "LGNGetConsistentIC(NULL, NULL): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  last_msg[0] = '\0';
  flag = LGNSetPerturbedStart(r.mem, 2);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "on") != NULL,
        "LGNSetPerturbedStart(on = 2): %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  /* after a step the initial values are gone */
  flag = LGNSolve(r.mem, 1e-3, &t, r.q, r.v, LGN_NORMAL);
  last_msg[0] = '\0';
  if (!flag) flag = LGNGetConsistentIC(r.mem, q0, NULL);
  CHECK(flag == LGN_ILL_INPUT && strstr(last_msg, "first step") != NULL,
        "LGNGetConsistentIC after a step: %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
  RunFree(&r);

  /* no linear solver */
  {
    LGNGroup G = LGNGroup_R3xSO3();
    void *mem = LGNCreate(ctx);
    N_Vector q = N_VNew_Serial(7, ctx), v = N_VNew_Serial(6, ctx);
    N_VConst(0.0, q);
    N_VConst(0.0, v);
    N_VGetArrayPointer(q)[3] = 1.0;
    LGNSetErrHandlerFn(mem, Capture, NULL);
    LGNSetGroup(mem, G);
    LGNSetMassFn(mem, Mass);
    LGNSetForceFn(mem, Force);
    LGNSetConstraints(mem, 3, Constr, ConstrJac);
    LGNInit(mem, 0.0, q, v);
    last_msg[0] = '\0';
    flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
    CHECK(flag == LGN_NO_LINSOL && strstr(last_msg, "linear solver") != NULL,
          "LGNCalcIC without a linear solver: %s \"%s\"", LGNGetReturnFlagName(flag), last_msg);
    LGNFree(&mem);
    LGNGroup_Destroy(G);
    N_VDestroy(q);
    N_VDestroy(v);
  }
  N_VDestroy(w5);
  N_VDestroy(q0);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  CalcIC(ctx, 0, LGN_CONSTR_INDEX3);
  CalcIC(ctx, 0, LGN_CONSTR_INDEX2);
#ifdef LGN_HAVE_KLU
  CalcIC(ctx, 1, LGN_CONSTR_INDEX3);
  CalcIC(ctx, 1, LGN_CONSTR_INDEX2);
#endif
  CalcICParts(ctx);
  NoConvergence(ctx);
  Check(ctx);
  BadInput(ctx);
  PerturbedStart(ctx);
  SUNContext_Free(&ctx);
  return test_summary("test_consistent_ic");
}
