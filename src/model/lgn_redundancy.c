/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Redundant but consistent constraints (LGNSetRedundantConstraints).
 *
 * The user describes m_user constraint rows; B(q) may have a smaller rank r
 * (Bricard's mechanism: rank 29 of 30; a four-bar built in space: 17 of
 * 20). At the start (LGNSolve or LGNCalcIC with new initial values) a QR
 * factorisation with column pivoting of B(q0)^T (LAPACK dgeqp3),
 *
 *     B^T P = Q R,   |R_11| >= |R_22| >= ...,
 *
 * (a sparse B: SuiteSparseQR's QR of B^T, whose rank detection, Heath's
 * method, drops the columns whose remaining norm is below the same
 * tolerance and moves them last)
 * gives the numerical rank r (|R_kk| > 1e-10 |R_11|) and, in the first r
 * pivoted columns, a maximal independent set of rows. (LGNCalcIC selects
 * the rows again at the projected q0: a q0 off the constraints may hide
 * their dependence.) The integrator then
 * works on those r rows only: mem->m = r, and the user's callbacks of
 * constraint type are called here, through the selection (the output of
 * Phi, B, Phi_t and the curvature gathered to the kept rows; the
 * multipliers given to B^T lambda and K_t expanded with zeros on the rows
 * left out). Nothing else in the integrator knows of the selection.
 *
 * The multipliers returned on the rows left out are zero: B^T lambda is
 * the joint force that the dynamics determines, and the kept rows carry
 * all of it (the split among dependent rows is statically indeterminate).
 *
 * After every step the rows left out are checked (lgnRedundancyCheck):
 * a consistent redundancy keeps them satisfied as well as the kept ones;
 * if one is violated beyond that, the redundancy was not consistent (or
 * B's rank grew) and LGNSolve stops with LGN_REDUNDANT_INCONSISTENT.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"
#if defined(LGN_HAVE_SPQR)
#include <SuiteSparseQR_C.h>
#endif

#define LGN_RED_RANK_TOL   SUN_RCONST(1.0e-10) /* |R_kk| > tol |R_11|: independent */
#define LGN_RED_CHECK_FAC  SUN_RCONST(100.0)   /* rows left out: 100 x the kept rows' */
#define LGN_RED_MAX_ENTRIES 4000000L           /* dense B^T for the QR: 32 MB */

/* LAPACK: QR with column pivoting (reference LAPACK, 32-bit integers). */
extern void dgeqp3_(const int *m, const int *n, double *a, const int *lda, int *jpvt,
                    double *tau, double *work, const int *lwork, int *info);

/* =============================================================================
 * The rank-revealing factorisation
 * ===========================================================================*/

/* B (dense or sparse, m x nv) transposed into the column-major nv x m Bt. */
static void DenseTranspose(SUNMatrix B, sunindextype m, sunindextype nv, double *Bt)
{
  sunindextype i, j, p;
  if (lgnMatID(B) == SUNMATRIX_DENSE) {
    for (j = 0; j < nv; j++)
      for (i = 0; i < m; i++) Bt[j + i * nv] = SM_ELEMENT_D(B, i, j);
    return;
  }
  memset(Bt, 0, (size_t)(m * nv) * sizeof(double));
  {
    const sunindextype np = SUNSparseMatrix_NP(B);
    const sunindextype *ptr = SUNSparseMatrix_IndexPointers(B);
    const sunindextype *ind = SUNSparseMatrix_IndexValues(B);
    const sunrealtype *val = SUNSparseMatrix_Data(B);
    const sunbooleantype csc = SUNSparseMatrix_SparseType(B) == CSC_MAT;
    for (j = 0; j < np; j++)
      for (p = ptr[j]; p < ptr[j + 1]; p++) {
        if (csc) Bt[j + ind[p] * nv] += val[p]; /* B(ind, j) */
        else Bt[ind[p] + j * nv] += val[p];     /* B(j, ind) */
      }
  }
}

static void SortAscending(sunindextype *x, sunindextype n)
{
  sunindextype i, j;
  for (i = 1; i < n; i++) { /* insertion sort: rows of one mechanism */
    const sunindextype v = x[i];
    for (j = i; j > 0 && x[j - 1] > v; j--) x[j] = x[j - 1];
    x[j] = v;
  }
}

#if defined(LGN_HAVE_SPQR)
/* The sparse B's independent rows: SuiteSparseQR's B^T E = Q R with rank
 * detection; the first rank columns of E are the independent rows. B^T in
 * compressed columns is B in compressed rows: B's arrays for CSR, its
 * transpose for CSC. */
static int SparseRankRows(SUNMatrix B, sunindextype m, sunindextype nv, sunrealtype rank_floor,
                          sunindextype *rank, sunindextype *rows)
{
  const sunindextype np = SUNSparseMatrix_NP(B);
  const sunindextype *bp = SUNSparseMatrix_IndexPointers(B);
  const sunindextype *bi = SUNSparseMatrix_IndexValues(B);
  const sunrealtype *bx = SUNSparseMatrix_Data(B);
  const sunindextype nnz = bp[np];
  sunindextype *tp = NULL, *ti = NULL, *E = NULL, i, j, p;
  sunrealtype *tx = NULL, colmax = SUN_RCONST(0.0);
  cholmod_sparse At, *R = NULL;
  cholmod_common cc;
  SuiteSparse_long r = -1;
  int flag = -1;

  *rank = -1;
  if (SUNSparseMatrix_SparseType(B) == CSR_MAT) {
    tp = (sunindextype *)bp;
    ti = (sunindextype *)bi;
    tx = (sunrealtype *)bx;
  } else { /* the transpose of compressed columns */
    tp = (sunindextype *)calloc((size_t)(m + 1), sizeof(sunindextype));
    ti = (sunindextype *)malloc((size_t)SUNMAX(nnz, 1) * sizeof(sunindextype));
    tx = (sunrealtype *)malloc((size_t)SUNMAX(nnz, 1) * sizeof(sunrealtype));
    if (tp == NULL || ti == NULL || tx == NULL) goto done;
    for (p = 0; p < nnz; p++) tp[bi[p] + 1]++;
    for (i = 0; i < m; i++) tp[i + 1] += tp[i];
    for (j = 0; j < np; j++)
      for (p = bp[j]; p < bp[j + 1]; p++) {
        const sunindextype k = tp[bi[p]]++;
        ti[k] = j;
        tx[k] = bx[p];
      }
    for (i = m; i > 0; i--) tp[i] = tp[i - 1];
    tp[0] = 0;
  }
  for (i = 0; i < m; i++) { /* the largest row norm of B: the scale */
    sunrealtype s = SUN_RCONST(0.0);
    for (p = tp[i]; p < tp[i + 1]; p++) s += tx[p] * tx[p];
    colmax = SUNMAX(colmax, sqrt(s));
  }
  memset(&At, 0, sizeof At);
  At.nrow = (size_t)nv;
  At.ncol = (size_t)m;
  At.nzmax = (size_t)SUNMAX(nnz, 1);
  At.p = tp;
  At.i = ti;
  At.x = tx;
  At.stype = 0;
  At.itype = CHOLMOD_LONG;
  At.xtype = CHOLMOD_REAL;
  At.dtype = CHOLMOD_DOUBLE;
  At.sorted = 0;
  At.packed = 1;
  cholmod_l_start(&cc);
  /* AMD's ordering: on spherical chains of 1e3 and 1e4 bodies (B^T 6000 x
   * 3000, 60000 x 30000) 5.5 and 46 ms of CPU, against 7 and 351 ms with
   * SuiteSparseQR's default choice */
  r = SuiteSparseQR_C(SPQR_ORDERING_AMD, SUNMAX(LGN_RED_RANK_TOL * colmax, rank_floor), 0, 0,
                      &At, NULL, NULL, NULL, NULL, &R, (SuiteSparse_long **)&E, NULL, NULL,
                      NULL, &cc);
  if (r >= 0) {
    for (i = 0; i < m; i++) rows[i] = E != NULL ? E[i] : i;
    SortAscending(rows, (sunindextype)r);
    SortAscending(rows + r, m - (sunindextype)r);
    *rank = (sunindextype)r;
    flag  = 0;
  }
  cholmod_l_free_sparse(&R, &cc);
  if (E != NULL) cholmod_l_free((size_t)m, sizeof(SuiteSparse_long), E, &cc);
  cholmod_l_finish(&cc);
done:
  if (SUNSparseMatrix_SparseType(B) != CSR_MAT) {
    free(tp);
    free(ti);
    free(tx);
  }
  return flag;
}
#endif

int lgnRankRevealingRows(SUNMatrix B, sunindextype m, sunindextype nv, sunrealtype rank_floor,
                         sunindextype *rank, sunindextype *rows)
{
  double *Bt = NULL, *tau = NULL, *work = NULL, wq = 0.0, r11;
  int *jpvt = NULL, im = (int)nv, in = (int)m, lwork = -1, info = 0, k;
  sunindextype r = 0;
  int flag = -1;

  *rank = -1;
#if defined(LGN_HAVE_SPQR)
  if (m > 0 && nv > 0 && lgnMatIsSparse(B))
    return SparseRankRows(B, m, nv, rank_floor, rank, rows);
#endif
  if (m == 0 || nv == 0 || (long int)m * (long int)nv > LGN_RED_MAX_ENTRIES) return -1;
  Bt   = (double *)malloc((size_t)(m * nv) * sizeof(double));
  tau  = (double *)malloc((size_t)m * sizeof(double));
  jpvt = (int *)calloc((size_t)m, sizeof(int)); /* 0: every column is free */
  if (Bt == NULL || tau == NULL || jpvt == NULL) goto done;
  DenseTranspose(B, m, nv, Bt);
  dgeqp3_(&im, &in, Bt, &im, jpvt, tau, &wq, &lwork, &info);
  lwork = (int)wq;
  work  = (double *)malloc((size_t)SUNMAX(lwork, 1) * sizeof(double));
  if (info != 0 || work == NULL) goto done;
  dgeqp3_(&im, &in, Bt, &im, jpvt, tau, work, &lwork, &info);
  if (info != 0) goto done;
  r11 = fabs(Bt[0]);
  for (k = 0; k < (int)SUNMIN(m, nv); k++)
    if (fabs(Bt[k + k * nv]) > SUNMAX(LGN_RED_RANK_TOL * r11, rank_floor)) r = k + 1;
  /* the independent rows, then the dependent ones (jpvt is 1-based) */
  for (k = 0; k < in; k++) rows[k] = (sunindextype)(jpvt[k] - 1);
  SortAscending(rows, r);
  SortAscending(rows + r, m - r);
  *rank = r;
  flag  = 0;
done:
  free(Bt);
  free(tau);
  free(jpvt);
  free(work);
  return flag;
}

/* =============================================================================
 * The selection at the start
 * ===========================================================================*/

/* Is the rank found by the sparse QR (a sparse B, built with SuiteSparseQR)? */
static sunbooleantype RankSparse(const LGNMem mem)
{
#if defined(LGN_HAVE_SPQR)
  return mem->krylov || (mem->A != NULL && lgnMatIsSparse(mem->A));
#else
  (void)mem;
  return SUNFALSE;
#endif
}

/* "3, 17 and 29" into buf: the rows left out. */
static void ListRows(const sunindextype *rows, sunindextype n, char *buf, size_t len)
{
  size_t used = 0;
  sunindextype i;
  buf[0] = '\0';
  for (i = 0; i < n && used + 24 < len; i++)
    used += (size_t)snprintf(buf + used, len - used, "%s%lld",
                             i == 0 ? "" : (i + 1 == n ? " and " : ", "), (long long)rows[i]);
  if (i < n) snprintf(buf + used, len - used, ", ...");
}

/* The work space is rebuilt for another m: vdot_0 and lambda_0 given with
 * LGNSetInitialAcceleration before the rows were selected (no linear
 * solver attached then) cannot be kept; the consistent ones are computed. */
static void NewSizes(LGNMem mem)
{
  if (mem->user_vdot0)
    LGN_ERROR(mem, LGN_WARNING,
              "vdot0 and lambda0 of LGNSetInitialAcceleration are replaced by consistent "
              "values: the redundant constraint rows were selected after them (attach "
              "the linear solver before LGNSetInitialAcceleration to keep them).");
  mem->user_vdot0 = SUNFALSE;
  lgnInvalidate(mem, LGN_CHANGE_SIZES);
}

/* The selection sel[0 .. r-1] kept, sel[r .. m_user-1] left out, made
 * current (into mem->red_rows, and red_keep: the kept index of each user
 * row, -1 if left out); the work space is rebuilt for r rows when that
 * changes the integrator's m. */
static void UseSelection(LGNMem mem, sunindextype r, const sunindextype *sel)
{
  const sunindextype mu = mem->m_user;
  sunindextype i;
  memmove(mem->red_rows, sel, (size_t)mu * sizeof(sunindextype));
  for (i = 0; i < mu; i++) mem->red_keep[i] = -1;
  for (i = 0; i < r; i++) mem->red_keep[mem->red_rows[i]] = i;
  mem->red_nout = mu - r;
  mem->red_nsel++;
  if (mem->m != r) {
    mem->m = r;
    NewSizes(mem);
  } else {
    lgnInvalidate(mem, LGN_CHANGE_MODEL); /* other rows, same sizes */
  }
}

/* Back to all of the user's rows (nothing left out). */
static void UseAllRows(LGNMem mem)
{
  if (mem->red_nout == 0 && mem->m == mem->m_user) return;
  mem->red_nout = 0;
  mem->red_nsel++;
  mem->m        = mem->m_user;
  NewSizes(mem);
}

int lgnRedundancyAnalyse(LGNMem mem, const char *func)
{
  const sunindextype mu = mem->m_user;
  sunindextype rank, *sel;
  char list[200];
  int ret, flag;

  if (mu == 0 || mem->red_mode == LGN_REDUNDANT_REFUSE || mem->par != NULL ||
      (!RankSparse(mem) && (long int)mu * (long int)mem->nv > LGN_RED_MAX_ENTRIES)) {
    /* the integrator sees every row: a redundant one makes its matrix
     * singular, and lgn_diag.c names it */
    UseAllRows(mem);
    return LGN_SUCCESS;
  }
  flag = lgnAllocRedundancy(mem);
  if (flag != LGN_SUCCESS) return flag;
  lgnMatClear(mem->red_B);
  ret  = mem->constr_jac(mem->tn, mem->q, mem->red_B, mem->user_data);
  flag = lgnCallbackMatrix(mem, LGN_CB_CONSTR_JAC, ret, mem->red_B, func);
  if (flag != LGN_SUCCESS) return flag;
  sel = mem->red_rows + mu; /* the second half: scratch */
  if (lgnRankRevealingRows(mem->red_B, mu, mem->nv, SUN_RCONST(0.0), &rank, sel) != 0) {
    lgnProcessError(mem, LGN_MEM_FAIL, __LINE__, func, __FILE__, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  if (rank == mu || rank == 0) {
    UseAllRows(mem);
    return LGN_SUCCESS;
  }
  if (mem->red_nout > 0 && mem->m == rank &&
      memcmp(mem->red_rows, sel, (size_t)mu * sizeof(sunindextype)) == 0)
    return LGN_SUCCESS; /* the same selection as before: said already */
  ListRows(sel + rank, mu - rank, list, sizeof list);
  lgnProcessError(mem, LGN_WARNING, __LINE__, func, __FILE__,
                  MSG_TIME "redundant constraints: B(q) has rank %lld of %lld; "
                  "constraint%s %s depend%s on the others and %s left out (%s 0; %s "
                  "checked after every step). "
                  "LGNGetRedundantConstraints lists them, LGNJoints_DescribeConstraint "
                  "names their joints; LGNSetRedundantConstraints(mem, "
                  "LGN_REDUNDANT_REFUSE) refuses such a model.",
                  (double)mem->tn, (long long)rank, (long long)mu,
                  mu - rank > 1 ? "s" : "", list, mu - rank > 1 ? "" : "s",
                  mu - rank > 1 ? "are" : "is",
                  mu - rank > 1 ? "their multipliers are" : "its multiplier is",
                  mu - rank > 1 ? "they are" : "it is");
  UseSelection(mem, rank, sel);
  return LGN_SUCCESS;
}

/* =============================================================================
 * The check after each step
 * ===========================================================================*/

int lgnRedundancyCheck(LGNMem mem, sunrealtype t, N_Vector q, const char *func)
{
  const sunindextype mu = mem->m_user, r = mem->m;
  const sunrealtype *phi;
  sunrealtype kept = SUN_RCONST(0.0), out = SUN_RCONST(0.0), qs = SUN_RCONST(1.0), tol;
  sunindextype i, worst = -1;
  int ret, flag;

  if (mem->red_nout == 0) return LGN_SUCCESS;
  N_VConst(SUN_RCONST(0.0), mem->red_full);
  ret  = mem->constr(t, q, mem->red_full, mem->user_data);
  flag = lgnCallbackVector(mem, LGN_CB_CONSTR, ret, mem->red_full, func);
  if (flag != LGN_SUCCESS) return flag;
  phi = lgnData(mem->red_full);
  for (i = 0; i < r; i++) kept = SUNMAX(kept, fabs(phi[mem->red_rows[i]]));
  for (i = r; i < mu; i++)
    if (!(fabs(phi[mem->red_rows[i]]) <= out)) { /* NaN counts as the largest */
      out   = fabs(phi[mem->red_rows[i]]);
      worst = mem->red_rows[i];
    }
  for (i = 0; i < mem->nq; i++) qs = SUNMAX(qs, fabs(lgnData(q)[i]));
  /* the kept rows' own level (index 2 lets Phi drift), or the tolerances' */
  tol = LGN_RED_CHECK_FAC * SUNMAX(kept, mem->atol + mem->rtol * qs);
  mem->red_viol = out;
  if (worst < 0 || out <= tol) return LGN_SUCCESS;
  lgnProcessError(mem, LGN_REDUNDANT_INCONSISTENT, __LINE__, func, __FILE__,
                  MSG_TIME "the redundant constraints are not consistent: constraint %lld, "
                  "left out as dependent on the others, has |Phi| = %g while the kept "
                  "ones have at most %g (tolerance %g = 100 max(that, atol + rtol "
                  "max(1, |q|_inf))). The mechanism cannot satisfy all its "
                  "constraints, or B(q) gained rank since the start (restart with "
                  "LGNReInit to select the rows anew).",
                  (double)t, (long long)worst, (double)out, (double)kept, (double)tol);
  return LGN_REDUNDANT_INCONSISTENT;
}

/* =============================================================================
 * The user's callbacks through the selection
 * ===========================================================================*/

/* out (length m) = the kept rows of mem->red_full. */
static void GatherRows(LGNMem mem, N_Vector out)
{
  const sunrealtype *full = lgnData(mem->red_full);
  sunrealtype *o = lgnData(out);
  sunindextype i;
  for (i = 0; i < mem->m; i++) o[i] = full[mem->red_rows[i]];
}

void lgnRedundancyExpand(const LGNMem mem, const sunrealtype *lambda, sunrealtype *full)
{
  sunindextype i;
  if (mem->red_nout == 0) {
    memcpy(full, lambda, (size_t)mem->m * sizeof(sunrealtype));
    return;
  }
  for (i = 0; i < mem->m_user; i++) full[i] = SUN_RCONST(0.0);
  for (i = 0; i < mem->m; i++) full[mem->red_rows[i]] = lambda[i];
}

sunindextype lgnUserRow(const LGNMem mem, sunindextype k)
{
  return mem->red_nout == 0 || k < 0 || k >= mem->m ? k : mem->red_rows[k];
}

int lgnUserConstr(LGNMem mem, sunrealtype t, N_Vector q, N_Vector phi)
{
  int ret;
  if (mem->red_nout == 0) return mem->constr(t, q, phi, mem->user_data);
  N_VConst(SUN_RCONST(0.0), mem->red_full);
  ret = mem->constr(t, q, mem->red_full, mem->user_data);
  GatherRows(mem, phi);
  return ret;
}

int lgnUserConstrTime(LGNMem mem, sunrealtype t, N_Vector q, N_Vector phit)
{
  int ret;
  if (mem->red_nout == 0) return mem->constr_time(t, q, phit, mem->user_data);
  N_VConst(SUN_RCONST(0.0), mem->red_full);
  ret = mem->constr_time(t, q, mem->red_full, mem->user_data);
  GatherRows(mem, phit);
  return ret;
}

int lgnUserCurvature(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v, N_Vector z)
{
  int ret;
  if (mem->red_nout == 0) return mem->curvature(t, q, v, z, mem->user_data);
  N_VConst(SUN_RCONST(0.0), mem->red_full);
  ret = mem->curvature(t, q, v, mem->red_full, mem->user_data);
  GatherRows(mem, z);
  return ret;
}

int lgnUserConstrForce(LGNMem mem, sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f)
{
  if (mem->red_nout == 0) return mem->constr_force(t, q, lambda, f, mem->user_data);
  lgnRedundancyExpand(mem, lgnData(lambda), lgnData(mem->red_lam));
  return mem->constr_force(t, q, mem->red_lam, f, mem->user_data);
}

int lgnUserStiffness(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K)
{
  if (mem->red_nout == 0 || lambda == NULL)
    return mem->stiffness(t, q, v, vdot, lambda, K, mem->user_data);
  lgnRedundancyExpand(mem, lgnData(lambda), lgnData(mem->red_lam));
  return mem->stiffness(t, q, v, vdot, mem->red_lam, K, mem->user_data);
}

/* The kept rows of the sparse F (m_user x nv) into the sparse B (m x nv):
 * compressed rows are copied row by row, compressed columns filtered and
 * renumbered (keep[i]: the kept index of user row i, or -1). */
static int GatherSparse(LGNMem mem, SUNMatrix F, SUNMatrix B)
{
  const sunindextype np = SUNSparseMatrix_NP(F);
  const sunindextype *fp = SUNSparseMatrix_IndexPointers(F);
  const sunindextype *fi = SUNSparseMatrix_IndexValues(F);
  const sunrealtype *fv = SUNSparseMatrix_Data(F);
  sunindextype *bp, *bi, *keep = mem->red_keep;
  sunrealtype *bv;
  sunindextype i, j, p, nnz = 0;

  if (SUNSparseMatrix_NNZ(B) < fp[np] && SUNSparseMatrix_Reallocate(B, fp[np]) != 0)
    return LGN_MEM_FAIL;
  bp = SUNSparseMatrix_IndexPointers(B);
  bi = SUNSparseMatrix_IndexValues(B);
  bv = SUNSparseMatrix_Data(B);
  if (SUNSparseMatrix_SparseType(F) == CSR_MAT) {
    for (i = 0; i < mem->m; i++) {
      const sunindextype row = mem->red_rows[i];
      bp[i] = nnz;
      for (p = fp[row]; p < fp[row + 1]; p++, nnz++) {
        bi[nnz] = fi[p];
        bv[nnz] = fv[p];
      }
    }
    bp[mem->m] = nnz;
    return LGN_SUCCESS;
  }
  for (j = 0; j < np; j++) {
    bp[j] = nnz;
    for (p = fp[j]; p < fp[j + 1]; p++)
      if (keep[fi[p]] >= 0) {
        bi[nnz] = keep[fi[p]];
        bv[nnz] = fv[p];
        nnz++;
      }
  }
  bp[np] = nnz;
  return LGN_SUCCESS;
}

int lgnUserConstrJac(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B)
{
  sunindextype i, j;
  int ret;
  if (mem->red_nout == 0) return mem->constr_jac(t, q, B, mem->user_data);
  lgnMatClear(mem->red_B);
  ret = mem->constr_jac(t, q, mem->red_B, mem->user_data);
  if (ret != 0) return ret;
  if (lgnMatIsSparse(B)) {
    if (GatherSparse(mem, mem->red_B, B) != LGN_SUCCESS) {
      LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
      return -1;
    }
    return 0;
  }
  for (j = 0; j < mem->nv; j++) {
    const sunrealtype *col = SM_COLUMN_D(mem->red_B, j);
    sunrealtype *out = SM_COLUMN_D(B, j);
    for (i = 0; i < mem->m; i++) out[i] = col[mem->red_rows[i]];
  }
  return 0;
}
