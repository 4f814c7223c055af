/* -----------------------------------------------------------------------------
 * Lignum study models: a system of rigid bodies joined by joints, under gravity.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Equations of body k (mass m, principal moments J, f = m g the weight):
 *   R^3 x SO(3):  m udot - f = 0,                 J Omegadot + Omega x J Omega = 0
 *   SE(3):        m (Udot + Omega x U) - R^T f = 0, J Omegadot + Omega x J Omega = 0
 * plus B^T lambda of the joints. Tangent matrices (doc/theory.md):
 *   C_t: Omega block  Omega~ J - (J Omega)~;  SE(3): U block m Omega~, U-Omega
 *        block -m U~;
 *   K_t: the joints' geometric stiffness; SE(3) adds d(-R^T f)/dtheta = -(R^T f)~
 *        in the U-Omega block.
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include "rigid_bodies.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum_config.h> /* LGN_HAVE_KLU */
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

RigidSystem *rigid_create(int n, RigidFormulation formulation, SUNContext ctx)
{
  RigidSystem *sys = (RigidSystem *)calloc(1, sizeof *sys);
  LGNGroup *factors;
  int k;
  if (sys == NULL || n < 1) {
    free(sys);
    return NULL;
  }
  sys->n           = n;
  sys->formulation = formulation;
  sys->mass        = (double *)malloc((size_t)n * sizeof(double));
  sys->inertia     = (double *)malloc((size_t)(3 * n) * sizeof(double));
  sys->body        = formulation == RB_SE3 ? LGNGroup_SE3() : LGNGroup_R3xSO3();
  factors          = (LGNGroup *)malloc((size_t)n * sizeof(LGNGroup));
  if (sys->mass == NULL || sys->inertia == NULL || sys->body == NULL || factors == NULL) {
    free(factors);
    rigid_free(&sys);
    return NULL;
  }
  for (k = 0; k < n; k++) {
    factors[k]           = sys->body;
    sys->mass[k]         = 1.0;
    sys->inertia[3 * k]  = sys->inertia[3 * k + 1] = sys->inertia[3 * k + 2] = 1.0;
  }
  sys->G = LGNGroup_Product(n, factors);
  free(factors);
  sys->gravity[0] = sys->gravity[1] = 0.0;
  sys->gravity[2] = -9.81;
  if (sys->G == NULL) {
    rigid_free(&sys);
    return NULL;
  }
  sys->joints = LGNJoints_Create(sys->G);
  sys->q0     = N_VNew_Serial(sys->G->nq, ctx);
  sys->v0     = N_VNew_Serial(sys->G->nv, ctx);
  if (sys->joints == NULL || sys->q0 == NULL || sys->v0 == NULL) {
    rigid_free(&sys);
    return NULL;
  }
  N_VConst(0.0, sys->v0);
  for (k = 0; k < n; k++) LGNGroup_Identity(sys->body, N_VGetArrayPointer(sys->q0) + 7 * k);
  return sys;
}

void rigid_free(RigidSystem **sysp)
{
  RigidSystem *sys;
  if (sysp == NULL || *sysp == NULL) return;
  sys = *sysp;
  LGNJoints_Destroy(&sys->joints);
  if (sys->q0 != NULL) N_VDestroy(sys->q0);
  if (sys->v0 != NULL) N_VDestroy(sys->v0);
  LGNGroup_Destroy(sys->G);
  LGNGroup_Destroy(sys->body);
  free(sys->mass);
  free(sys->inertia);
  free(sys);
  *sysp = NULL;
}

void rigid_set_cylinder(RigidSystem *sys, int k, double L, double m, double r)
{
  sys->mass[k]            = m;
  sys->inertia[3 * k]     = m * (3.0 * r * r + L * L) / 12.0;
  sys->inertia[3 * k + 1] = sys->inertia[3 * k];
  sys->inertia[3 * k + 2] = 0.5 * m * r * r;
}

void rigid_place(RigidSystem *sys, int k, const double x[3], const double R[9])
{
  double *q = N_VGetArrayPointer(sys->q0) + 7 * k, rv[3], c, s, tr;
  /* rotation vector of R (angle < pi here), then the quaternion */
  tr = R[0] + R[4] + R[8];
  c  = 0.5 * (tr - 1.0);
  s  = 0.5 * sqrt((R[7] - R[5]) * (R[7] - R[5]) + (R[2] - R[6]) * (R[2] - R[6]) +
                  (R[3] - R[1]) * (R[3] - R[1]));
  {
    double angle = atan2(s, c), f = s > 1e-12 ? angle / (2.0 * s) : 0.5;
    rv[0] = f * (R[7] - R[5]);
    rv[1] = f * (R[2] - R[6]);
    rv[2] = f * (R[3] - R[1]);
  }
  q[0] = x[0];
  q[1] = x[1];
  q[2] = x[2];
  LGNQuaternionFromRotationVector(rv, q + 3);
}

double rigid_energy(const RigidSystem *sys, N_Vector q, N_Vector v)
{
  const double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  double E = 0.0;
  int k, i;
  for (k = 0; k < sys->n; k++) {
    const double *u = vd + 6 * k, *w = u + 3, *J = sys->inertia + 3 * k;
    for (i = 0; i < 3; i++) E += 0.5 * (sys->mass[k] * u[i] * u[i] + J[i] * w[i] * w[i]);
    for (i = 0; i < 3; i++) E -= sys->mass[k] * sys->gravity[i] * qd[7 * k + i];
  }
  return E;
}

/* ---------------------------------------------------------------------------
 * Callbacks
 * ------------------------------------------------------------------------ */

/* Write a block-diagonal nv x nv matrix with 6x6 blocks blk(k) (column-major
 * 36 values) into a dense or sparse matrix; a sparse one stores the entries
 * of the block pattern stored (column-major, 1 = stored). */
typedef void (*BlockFn)(const RigidSystem *sys, int k, const double *q,
                        const double *v, double *blk);

static void WriteBlockDiagonal(const RigidSystem *sys, SUNMatrix A, BlockFn fn,
                               const double *q, const double *v,
                               const unsigned char stored[36])
{
  double blk[36];
  int k, r, c, per = 0;
  if (SUNMatGetID(A) == SUNMATRIX_DENSE) {
    for (k = 0; k < sys->n; k++) {
      fn(sys, k, q, v, blk);
      for (c = 0; c < 6; c++)
        for (r = 0; r < 6; r++) SM_ELEMENT_D(A, 6 * k + r, 6 * k + c) = blk[r + 6 * c];
    }
    return;
  }
  for (r = 0; r < 36; r++) per += stored[r];
  {
    const int csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    sunindextype *ptr, *ind, p = 0;
    double *val;
    if (SUNSparseMatrix_NNZ(A) < (sunindextype)per * sys->n)
      SUNSparseMatrix_Reallocate(A, (sunindextype)per * sys->n);
    ptr = SUNSparseMatrix_IndexPointers(A);
    ind = SUNSparseMatrix_IndexValues(A);
    val = SUNSparseMatrix_Data(A);
    ptr[0] = 0;
    for (k = 0; k < sys->n; k++) {
      fn(sys, k, q, v, blk);
      /* CSC: column c lists rows r; CSR: row c lists columns r */
      for (c = 0; c < 6; c++) {
        for (r = 0; r < 6; r++) {
          if (!stored[csc ? r + 6 * c : c + 6 * r]) continue;
          ind[p] = 6 * k + r;
          val[p] = csc ? blk[r + 6 * c] : blk[c + 6 * r];
          p++;
        }
        ptr[6 * k + c + 1] = p;
      }
    }
  }
}

/* Block patterns (column-major): the diagonal (mass); the gyroscopic
 * damping, rotations only in R^3 x SO(3), and in SE(3) also the translation
 * rows, d m (w x U) (see DampingBlock). */
static const unsigned char DiagonalPattern[36] = {
    1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,
    0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};
static const unsigned char RotationPattern[36] = {
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1};
static const unsigned char SE3DampingPattern[36] = {
    1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0,
    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};

static void MassBlock(const RigidSystem *sys, int k, const double *q,
                      const double *v, double *blk)
{
  int i;
  (void)q;
  (void)v;
  memset(blk, 0, 36 * sizeof(double));
  for (i = 0; i < 3; i++) {
    blk[i + 6 * i]             = sys->mass[k];
    blk[(3 + i) + 6 * (3 + i)] = sys->inertia[3 * k + i];
  }
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t;
  WriteBlockDiagonal((RigidSystem *)ud, M, MassBlock, N_VGetArrayPointer(q), NULL,
                     DiagonalPattern);
  return 0;
}

static void Cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* mu = R^T f for body k (weight in the body frame). */
static void BodyWeight(const RigidSystem *sys, int k, const double *q, double *mu)
{
  double R[9];
  int i;
  LGNQuaternionToRotation(q + 7 * k + 3, R);
  for (i = 0; i < 3; i++)
    mu[i] = sys->mass[k] * (R[i] * sys->gravity[0] + R[3 + i] * sys->gravity[1] +
                            R[6 + i] * sys->gravity[2]);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const RigidSystem *sys = (const RigidSystem *)ud;
  const double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  double *gd = N_VGetArrayPointer(g), Jw[3], mu[3];
  int k, i;
  (void)t;
  for (k = 0; k < sys->n; k++) {
    const double *u = vd + 6 * k, *w = u + 3, *J = sys->inertia + 3 * k;
    double *gk = gd + 6 * k;
    for (i = 0; i < 3; i++) Jw[i] = J[i] * w[i];
    Cross(w, Jw, gk + 3);
    if (sys->formulation == RB_SE3) {
      BodyWeight(sys, k, qd, mu);
      Cross(w, u, gk);
      for (i = 0; i < 3; i++) gk[i] = sys->mass[k] * gk[i] - mu[i];
    } else {
      for (i = 0; i < 3; i++) gk[i] = -sys->mass[k] * sys->gravity[i];
    }
  }
  return 0;
}

/* Add f x~ (column-major 3x3 of the skew matrix) at (r0, c0) of blk. */
static void AddSkew(double *blk, int r0, int c0, const double *x, double f)
{
  blk[(r0 + 1) + 6 * (c0 + 0)] += f * x[2];
  blk[(r0 + 2) + 6 * (c0 + 0)] -= f * x[1];
  blk[(r0 + 0) + 6 * (c0 + 1)] -= f * x[2];
  blk[(r0 + 2) + 6 * (c0 + 1)] += f * x[0];
  blk[(r0 + 0) + 6 * (c0 + 2)] += f * x[1];
  blk[(r0 + 1) + 6 * (c0 + 2)] -= f * x[0];
}

static void DampingBlock(const RigidSystem *sys, int k, const double *q,
                         const double *v, double *blk)
{
  const double *u = v + 6 * k, *w = u + 3, *J = sys->inertia + 3 * k;
  double Jw[3];
  int i, j;
  (void)q;
  memset(blk, 0, 36 * sizeof(double));
  for (i = 0; i < 3; i++) Jw[i] = J[i] * w[i];
  /* d(w x J w)/dw = w~ J - (J w)~ */
  for (j = 0; j < 3; j++) {
    double e[3] = {0, 0, 0}, c1[3];
    e[j] = J[j];
    Cross(w, e, c1);
    for (i = 0; i < 3; i++) blk[(3 + i) + 6 * (3 + j)] += c1[i];
  }
  AddSkew(blk, 3, 3, Jw, -1.0);
  if (sys->formulation == RB_SE3) { /* d m (w x U) = m w~ dU - m U~ dw */
    AddSkew(blk, 0, 0, w, sys->mass[k]);
    AddSkew(blk, 0, 3, u, -sys->mass[k]);
  }
}

static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  const RigidSystem *sys = (const RigidSystem *)ud;
  (void)t;
  WriteBlockDiagonal(sys, C, DampingBlock, N_VGetArrayPointer(q), N_VGetArrayPointer(v),
                     sys->formulation == RB_SE3 ? SE3DampingPattern : RotationPattern);
  return 0;
}

/* K entry (r, c) += x in a dense or sparse matrix whose pattern holds it. */
static void AddEntry(SUNMatrix K, sunindextype r, sunindextype c, double x)
{
  sunindextype p, o, k;
  if (SUNMatGetID(K) == SUNMATRIX_DENSE) {
    SM_ELEMENT_D(K, r, c) += x;
    return;
  }
  k = SUNSparseMatrix_SparseType(K) == CSC_MAT ? c : r;
  o = SUNSparseMatrix_SparseType(K) == CSC_MAT ? r : c;
  for (p = SUNSparseMatrix_IndexPointers(K)[k]; p < SUNSparseMatrix_IndexPointers(K)[k + 1]; p++)
    if (SUNSparseMatrix_IndexValues(K)[p] == o) {
      SUNSparseMatrix_Data(K)[p] += x;
      return;
    }
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K, void *ud)
{
  RigidSystem *sys = (RigidSystem *)ud;
  int flag, k;
  (void)v;
  (void)vdot;
  flag = LGNJoints_Stiffness(sys->joints, t, q, lambda, K);
  if (flag != 0) return -1;
  if (sys->formulation == RB_SE3) {
    /* d(-R^T f)/dtheta = -(R^T f)~, in the body's diagonal block */
    for (k = 0; k < sys->n; k++) {
      double mu[3];
      const sunindextype o = 6 * k;
      BodyWeight(sys, k, N_VGetArrayPointer(q), mu);
      AddEntry(K, o + 1, o + 3, -mu[2]);
      AddEntry(K, o + 2, o + 3, mu[1]);
      AddEntry(K, o + 0, o + 4, mu[2]);
      AddEntry(K, o + 2, o + 4, -mu[0]);
      AddEntry(K, o + 0, o + 5, -mu[1]);
      AddEntry(K, o + 1, o + 5, mu[0]);
    }
  }
  return 0;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

static int ConstrForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  return LGNJoints_ConstraintForce(((RigidSystem *)ud)->joints, t, q, lambda, f) == 0 ? 0 : -1;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((RigidSystem *)ud)->joints, t, q, v, z) == 0 ? 0 : -1;
}

void rigid_get_callbacks(RigidCallbacks *cb)
{
  cb->mass      = Mass;
  cb->force     = Force;
  cb->stiffness = Stiffness;
  cb->damping   = Damping;
}

/* ---------------------------------------------------------------------------
 * Running
 * ------------------------------------------------------------------------ */

void rigid_default_run_options(RigidRunOptions *opt)
{
  memset(opt, 0, sizeof *opt);
  opt->solver      = rigid_solver_available(RB_KLU_CSC) ? RB_KLU_CSC : RB_DENSE;
  opt->method      = 1;
  opt->rho_inf     = 0.9;
  opt->beta        = 0.25;
  opt->gamma       = 0.5;
  opt->kinematics  = LGN_KINEMATICS_SIMPLIFIED;
  opt->constraints = LGN_CONSTR_INDEX3;
  opt->newton      = LGN_NEWTON_FULL;
  opt->predictor   = LGN_PREDICTOR_ZERO;
  opt->analytic    = 1;
  opt->h           = 1e-3;
  opt->t_end       = 1.0;
  opt->outputs     = 100;
  opt->krylov_restarts = 2;
}

int rigid_solver_available(RigidSolver s)
{
#if defined(LGN_HAVE_KLU)
  return s == RB_DENSE || s == RB_KLU_CSC || s == RB_KLU_CSR || s == RB_SPGMR;
#else
  return s == RB_DENSE || s == RB_SPGMR;
#endif
}

const char *rigid_solver_name(RigidSolver s)
{
  return s == RB_DENSE ? "dense"
       : s == RB_KLU_CSC ? "klu"
       : s == RB_KLU_CSR ? "klu-csr"
                         : "spgmr";
}

static double CpuSeconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void rigid_result_free(RigidRunResult *res)
{
  free(res->q);
  free(res->v);
  res->q = res->v = NULL;
}

/* The floor under a Newton iteration: CPU time of one solve and one
 * factorisation with the last iteration matrix (the fastest of a few calls,
 * after the run, as the least disturbed on a shared machine; the matrix and
 * the solver are discarded afterwards). */
static void TimeLinearAlgebra(SUNLinearSolver LS, SUNMatrix A, sunindextype n,
                              SUNContext ctx, RigidRunResult *res)
{
  const int reps = 9;
  N_Vector b = N_VNew_Serial(n, ctx), x = N_VNew_Serial(n, ctx);
  double t0, t;
  int r, fail = 0;
  if (b == NULL || x == NULL) goto done;
  N_VConst(1.0, b);
  res->solve_seconds = res->setup_seconds = HUGE_VAL;
  for (r = 0; r < reps; r++) {
    t0 = CpuSeconds();
    fail |= SUNLinSolSolve(LS, A, x, b, 0.0) != 0;
    t = CpuSeconds() - t0;
    res->solve_seconds = t < res->solve_seconds ? t : res->solve_seconds;
  }
  for (r = 0; r < reps; r++) {
    t0 = CpuSeconds();
    fail |= SUNLinSolSetup(LS, A) != 0;
    t = CpuSeconds() - t0;
    res->setup_seconds = t < res->setup_seconds ? t : res->setup_seconds;
  }
  if (fail) res->solve_seconds = res->setup_seconds = 0.0;
done:
  if (b != NULL) N_VDestroy(b);
  if (x != NULL) N_VDestroy(x);
}

int rigid_run(RigidSystem *sys, const RigidRunOptions *opt, RigidRunResult *res)
{
  SUNContext ctx = sys->q0->sunctx;
  const sunindextype nq = sys->G->nq, nv = sys->G->nv;
  const sunindextype m = LGNJoints_NumConstraints(sys->joints), n = nv + m;
  void *mem = LGNCreate(ctx);
  SUNMatrix A;
  SUNLinearSolver LS;
  N_Vector q, v, phi;
  sunrealtype t = 0.0;
  int flag = 0, k;

  memset(res, 0, sizeof *res);
  q   = N_VClone(sys->q0);
  v   = N_VClone(sys->v0);
  phi = N_VNew_Serial(m, ctx);
  {
    N_Vector y = N_VNew_Serial(n, ctx); /* template of the (nv + m) unknowns */
    if (opt->solver == RB_SPGMR) { /* matrix-free: Lignum applies A */
      A  = NULL;
      LS = SUNLinSol_SPGMR(y, opt->krylov_blocks > 0 ? SUN_PREC_LEFT : SUN_PREC_NONE,
                           opt->krylov_maxl > 0 ? opt->krylov_maxl : 30, ctx);
      if (LS != NULL) SUNLinSol_SPGMRSetMaxRestarts(LS, opt->krylov_restarts);
    } else if (opt->solver == RB_DENSE) {
      A  = SUNDenseMatrix(n, n, ctx);
      LS = opt->own_dense_lu ? LGNLinSol_Dense(y, A, ctx) : SUNLinSol_Dense(y, A, ctx);
    } else {
      A  = SUNSparseMatrix(n, n, 30 * n, opt->solver == RB_KLU_CSC ? CSC_MAT : CSR_MAT, ctx);
#if defined(LGN_HAVE_KLU)
      LS = SUNLinSol_KLU(y, A, ctx);
      /* default AMD (0): the iteration matrix has a symmetric pattern, for
       * which AMD is made (COLAMD, SUNDIALS' default, orders for an
       * unsymmetric one: on the 10000-body chain its L + U has 1.6 times the
       * entries and 2.8 times the flops) */
      if (LS != NULL && SUNLinSol_KLUSetOrdering(LS, opt->klu_ordering) != 0) {
        SUNLinSolFree(LS);
        LS = NULL;
      }
#else
      LS = NULL; /* rigid_parse_option refuses KLU; LGNSetLinearSolver reports it */
#endif
    }
    N_VDestroy(y);
  }

  flag = LGNSetGroup(mem, sys->G);
  if (flag == 0 && opt->ehfun != NULL) flag = LGNSetErrHandlerFn(mem, opt->ehfun, opt->eh_data);
  if (flag == 0 && opt->reject_stalls) flag = LGNSetAcceptStalls(mem, SUNFALSE);
  if (flag == 0) flag = LGNInit(mem, 0.0, sys->q0, sys->v0);
  if (flag == 0) flag = LGNSetUserData(mem, sys);
  if (flag == 0) flag = LGNSetMassFn(mem, Mass);
  if (flag == 0) flag = LGNSetForceFn(mem, Force);
  if (flag == 0) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  /* M = diag(m I, J) in body-fixed velocities: constant; B^T lambda from
   * the joints without forming B (both optional, see plain_residual) */
  if (flag == 0 && !opt->plain_residual) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (flag == 0 && !opt->plain_residual) flag = LGNSetConstraintForceFn(mem, ConstrForce);
  if (flag == 0 && opt->analytic) {
    flag = LGNSetStiffnessFn(mem, Stiffness);
    if (flag == 0) flag = LGNSetDampingFn(mem, Damping);
    if (flag == 0) flag = LGNSetCurvatureFn(mem, Curvature);
  }
  if (flag == 0) flag = LGNSetLinearSolver(mem, LS, A);
  /* Lignum's solves on a copy of KLU's factors, off by default in the
   * library: the tools opt in (--klu-solve lignum) unless the versions
   * of KLU and SUNDIALS are not those the copy accepts (LGN_ILL_INPUT, with
   * a message naming them: KLU's own solves then) */
  if (flag == 0 && opt->solver == RB_SPGMR && opt->krylov_blocks > 0)
    flag = LGNSetBlockPreconditioner(mem, opt->krylov_blocks, NULL);
  if (flag == 0 && opt->solver == RB_SPGMR) flag = LGNSetEpsLin(mem, opt->krylov_eplifac);
  if (flag == 0 && opt->solver != RB_DENSE && opt->solver != RB_SPGMR) {
    flag = LGNSetOwnKLUSolves(mem, !opt->klu_solve_sundials);
    if (flag == LGN_ILL_INPUT) flag = 0;
  }
  if (flag == 0) flag = LGNSetStepSize(mem, opt->h);
  if (flag == 0)
    flag = opt->method == 1 ? LGNSetGenAlpha(mem, opt->rho_inf)
                            : LGNSetNewmark(mem, opt->beta, opt->gamma);
  if (flag == 0 && opt->bdf_maxord == 0) flag = LGNSetKinematics(mem, opt->kinematics);
  if (flag == 0 && opt->bdf_maxord > 0) flag = LGNSetBDF(mem, opt->bdf_maxord);
  if (flag == 0) flag = LGNSetNewtonMode(mem, opt->newton);
  if (flag == 0) flag = LGNSetLSetupFrequency(mem, opt->msbp);
  if (flag == 0) flag = LGNSetPredictor(mem, opt->predictor);
  if (flag == 0) flag = LGNSetConstraintIndex(mem, opt->constraints);
  if (flag == 0 && opt->adaptive) {
    /* the error test's tolerances (the library's defaults, 1e-8, are meant
     * for the Newton iteration of fixed steps) */
    flag = LGNSStolerances(mem, opt->rtol > 0 ? opt->rtol : 1e-6,
                           opt->atol > 0 ? opt->atol : 1e-6);
    if (flag == 0) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (flag == 0) flag = LGNSetInitStep(mem, opt->h);
    if (flag == 0 && opt->hmax > 0) flag = LGNSetMaxStep(mem, opt->hmax);
    if (flag == 0) flag = LGNSetStopTime(mem, opt->t_end);
  } else if (flag == 0 && opt->rtol > 0) {
    flag = LGNSStolerances(mem, opt->rtol, opt->atol);
  }
  if (flag == 0 && opt->max_steps > 0) flag = LGNSetMaxNumSteps(mem, opt->max_steps);

  res->energy0 = rigid_energy(sys, sys->q0, sys->v0);
  res->energy  = res->energy0;
  LGNJoints_Residual(sys->joints, t, sys->q0, phi);
  res->max_phi = N_VMaxNorm(phi);
  if (opt->csv != NULL) fprintf(opt->csv, "t,energy,max_phi\n0,%.17g,%.3e\n", res->energy0, res->max_phi);
  if (flag == 0 && opt->adaptive && opt->step_log != NULL) {
    /* every accepted step: LGN_ONE_STEP up to the stop time t_end */
    const double t0 = CpuSeconds();
    sunrealtype hlast = 0.0;
    fprintf(opt->step_log, "t,h,order\n");
    while (flag == 0 && t < opt->t_end) {
      flag = LGNSolve(mem, opt->t_end, &t, q, v, LGN_ONE_STEP);
      if (flag == 0 || flag == LGN_TSTOP_RETURN) {
        int order = 2;
        LGNGetLastStep(mem, &hlast);
        LGNGetLastOrder(mem, &order);
        fprintf(opt->step_log, "%.10g,%.6e,%d\n", t, hlast, order);
      }
      if (flag == LGN_TSTOP_RETURN) flag = 0;
    }
    res->cpu_seconds = CpuSeconds() - t0;
    if (flag == 0) {
      res->energy    = rigid_energy(sys, q, v);
      res->max_drift = fabs(res->energy - res->energy0);
      LGNJoints_Residual(sys->joints, t, q, phi);
      res->max_phi = fmax(res->max_phi, N_VMaxNorm(phi));
    }
  }
  for (k = 1; k <= opt->outputs && flag == 0 && opt->step_log == NULL; k++) {
    const double tout = opt->t_end * k / opt->outputs, t0 = CpuSeconds();
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (flag == LGN_TSTOP_RETURN) flag = 0; /* t_end reached (error control) */
    res->cpu_seconds += CpuSeconds() - t0;
    if (k == 1) {
      res->cpu_first_seconds = res->cpu_seconds;
      LGNGetNumSteps(mem, &res->nsteps_first);
      LGNGetNumNewtonIters(mem, &res->nni_first);
    }
    if (flag != 0) break;
    res->energy    = rigid_energy(sys, q, v);
    res->max_drift = fmax(res->max_drift, fabs(res->energy - res->energy0));
    LGNJoints_Residual(sys->joints, t, q, phi);
    res->max_phi = fmax(res->max_phi, N_VMaxNorm(phi));
    if (opt->csv != NULL) fprintf(opt->csv, "%.10g,%.17g,%.3e\n", t, res->energy, N_VMaxNorm(phi));
  }
  res->flag = flag;
  res->t    = t;
  LGNJoints_Residual(sys->joints, t, q, phi);
  res->phi_end = N_VMaxNorm(phi);
  LGNGetNumSteps(mem, &res->nsteps);
  LGNGetNumNewtonIters(mem, &res->nni);
  LGNGetNumResEvals(mem, &res->nre);
  LGNGetNumDQEvals(mem, &res->ndq);
  LGNGetNumJacEvals(mem, &res->nje);
  LGNGetNumLinSolvSetups(mem, &res->nlsetups);
  LGNGetNumMatrixReuses(mem, &res->nreuse);
  LGNGetNumNewtonStalls(mem, &res->nstall);
  LGNGetNumErrTestFails(mem, &res->netf);
  LGNGetNumNewtonConvFails(mem, &res->nncf);
  LGNGetNumSparsityAnalyses(mem, &res->nanalyses);
  LGNGetNumDQColors(mem, &res->ncolors);
  LGNGetIterationMatrixNnz(mem, &res->nnz);
  LGNGetWorkSpace(mem, &res->lenrw, &res->leniw);
#if defined(LGN_HAVE_KLU)
  LGNGetNumLinIters(mem, &res->nli);
  LGNGetNumPrecEvals(mem, &res->npe);
  LGNGetNumPrecSolves(mem, &res->nps);
  LGNGetNumJtimesEvals(mem, &res->njtimes);
  LGNGetNumLinConvFails(mem, &res->nlcf);
  if ((opt->solver == RB_KLU_CSC || opt->solver == RB_KLU_CSR) && LS != NULL)
    res->klu_peak_bytes = (double)SUNLinSol_KLUGetCommon(LS)->mempeak;
#endif
  if (flag == 0 && opt->time_linear_algebra && A != NULL) TimeLinearAlgebra(LS, A, n, ctx, res);
  res->q = (double *)malloc((size_t)nq * sizeof(double));
  res->v = (double *)malloc((size_t)nv * sizeof(double));
  if (res->q != NULL) memcpy(res->q, N_VGetArrayPointer(q), (size_t)nq * sizeof(double));
  if (res->v != NULL) memcpy(res->v, N_VGetArrayPointer(v), (size_t)nv * sizeof(double));

  LGNFree(&mem);
  SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(phi);
  return flag;
}

/* ---------------------------------------------------------------------------
 * Command line
 * ------------------------------------------------------------------------ */

void rigid_print_usage(FILE *out)
{
  fprintf(out,
          "          [--solver dense|klu|klu-csr|spgmr] [--formulation r3so3|se3]\n"
          "          [--method newmark|genalpha] [--rho-inf R] [--beta B --gamma G]\n"
          "          [--bdf MAXORD (1..5: the BDF family instead of --method)]\n"
          "          [--kinematics simplified|exact] [--constraints index3|index2]\n"
          "          [--jacobian analytic|dq] [--h H] [--t-end T] [--outputs K]\n"
          "          [--rtol R] [--atol A] [--newton full|modified] [--msbp N]\n"
          "          [--predictor zero|extrapolate] [--ordering amd|colamd|natural]\n"
          "          [--klu-solve lignum|klu] [--blocks NB] [--maxl L]\n"
          "          [--residual shortcuts|plain]\n"
          "          [--csv FILE] [--adaptive] [--hmax H]\n"
          "          (--adaptive: error control, --rtol/--atol the error test's\n"
          "          tolerances (default 1e-6), --h the first step tried)\n");
}

/* A finite number, the whole string (no trailing characters). */
static int ParseNumber(const char *s, double *x)
{
  char *end;
  *x = strtod(s, &end);
  return (end == s || *end != '\0' || !isfinite(*x)) ? 1 : 0;
}

int rigid_parse_option(int argc, char **argv, int *i, RigidRunOptions *opt,
                       RigidFormulation *formulation)
{
  int bad = 0;
  const char *key = argv[*i], *val;
  if (strcmp(key, "--adaptive") == 0) { /* a flag: no value */
    opt->adaptive = 1;
    return 1;
  }
  if (strncmp(key, "--", 2) != 0 || *i + 1 >= argc) return 0;
  val = argv[*i + 1];
#define IS(s) (strcmp(key, s) == 0)
#define VAL(s) (strcmp(val, s) == 0)
  if (IS("--solver")) {
    if (VAL("dense")) opt->solver = RB_DENSE;
    else if (VAL("klu")) opt->solver = RB_KLU_CSC;
    else if (VAL("klu-csr")) opt->solver = RB_KLU_CSR;
    else if (VAL("spgmr")) opt->solver = RB_SPGMR;
    else return -1;
    if (!rigid_solver_available(opt->solver)) {
      fprintf(stderr, "--solver %s: Lignum was built without KLU (LGN_ENABLE_KLU=OFF)\n", val);
      return -1;
    }
  } else if (IS("--blocks")) { /* --solver spgmr: the block preconditioner */
    opt->krylov_blocks = atoi(val);
    if (opt->krylov_blocks < 0) return -1;
  } else if (IS("--maxl")) {
    opt->krylov_maxl = atoi(val);
    if (opt->krylov_maxl < 0) return -1;
  } else if (IS("--formulation")) {
    if (VAL("r3so3")) *formulation = RB_R3XSO3;
    else if (VAL("se3")) *formulation = RB_SE3;
    else return -1;
  } else if (IS("--method")) {
    if (VAL("newmark")) opt->method = 0;
    else if (VAL("genalpha")) opt->method = 1;
    else return -1;
  } else if (IS("--bdf")) { /* the BDF family of this highest order */
    opt->bdf_maxord = atoi(val);
    if (opt->bdf_maxord < 1 || opt->bdf_maxord > 5) return -1;
  } else if (IS("--kinematics")) {
    if (VAL("simplified")) opt->kinematics = LGN_KINEMATICS_SIMPLIFIED;
    else if (VAL("exact")) opt->kinematics = LGN_KINEMATICS_EXACT;
    else return -1;
  } else if (IS("--constraints")) {
    if (VAL("index3")) opt->constraints = LGN_CONSTR_INDEX3;
    else if (VAL("index2")) opt->constraints = LGN_CONSTR_INDEX2;
    else return -1;
  } else if (IS("--jacobian")) {
    if (VAL("analytic")) opt->analytic = 1;
    else if (VAL("dq")) opt->analytic = 0;
    else return -1;
  } else if (IS("--newton")) {
    if (VAL("full")) opt->newton = LGN_NEWTON_FULL;
    else if (VAL("modified")) opt->newton = LGN_NEWTON_MODIFIED;
    else return -1;
  } else if (IS("--predictor")) {
    if (VAL("zero")) opt->predictor = LGN_PREDICTOR_ZERO;
    else if (VAL("extrapolate")) opt->predictor = LGN_PREDICTOR_EXTRAPOLATE;
    else return -1;
  } else if (IS("--residual")) {
    if (VAL("shortcuts")) opt->plain_residual = 0;
    else if (VAL("plain")) opt->plain_residual = 1;
    else return -1;
  } else if (IS("--ordering")) {
    if (VAL("amd")) opt->klu_ordering = 0;
    else if (VAL("colamd")) opt->klu_ordering = 1;
    else if (VAL("natural")) opt->klu_ordering = 2;
    else return -1;
  } else if (IS("--klu-solve")) {
    if (VAL("lignum")) opt->klu_solve_sundials = 0;
    else if (VAL("klu")) opt->klu_solve_sundials = 1;
    else return -1;
  } else if (IS("--msbp")) opt->msbp = atol(val);
  else if (IS("--rho-inf")) bad = ParseNumber(val, &opt->rho_inf);
  else if (IS("--beta")) bad = ParseNumber(val, &opt->beta);
  else if (IS("--gamma")) bad = ParseNumber(val, &opt->gamma);
  else if (IS("--h")) bad = ParseNumber(val, &opt->h);
  else if (IS("--t-end")) bad = ParseNumber(val, &opt->t_end);
  else if (IS("--outputs")) opt->outputs = atoi(val);
  else if (IS("--rtol")) bad = ParseNumber(val, &opt->rtol) || opt->rtol < 0;
  else if (IS("--atol")) bad = ParseNumber(val, &opt->atol) || opt->atol < 0;
  else if (IS("--hmax")) bad = ParseNumber(val, &opt->hmax) || opt->hmax < 0;
  else return 0;
#undef IS
#undef VAL
  if (bad || !(opt->h > 0) || !(opt->t_end > 0) || opt->outputs < 1) return -1;
  (*i)++;
  return 1;
}
