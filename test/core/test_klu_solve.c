/* Lignum's own solves with a copy of KLU's factors (lgn_klu_solve.c,
 * LGNSetOwnKLUSolves), built with KLU only:
 *  (a) on matrices that exercise every part of KLU's factorisation -- a
 *      random diagonally dominant one, a non-symmetric saddle point
 *      [[K, B^T], [B, 0]] that needs off-diagonal pivots, and a permuted
 *      block triangular one for which BTF finds several blocks, singletons
 *      among them -- in CSC and CSR storage, the copy's solve agrees with
 *      SUNLinSolSolve on the same factors (by columns, CSR, to 1e-13, in
 *      fact to the last bit, reported; by rows, CSC, with U's rows divided
 *      by the diagonal, within 10 times KLU's backward error) and the true
 *      solution to cond(A) times round-off;
 *      after a refactorisation with new values (pivots and pattern kept)
 *      the refresh takes the values only, and the copy then equals a whole
 *      new copy of the factors bit for bit; for CSC the copy holds L and U
 *      by rows (a banded matrix among the others, so that rows with two,
 *      one and no carried entries all occur), for CSR by columns in KLU's
 *      order, and lgnKluCopyPlace finds each of KLU's entries in it;
 *  (b) after a factorisation with new pivots (SUNDIALS factors anew when
 *      klu_refactor leaves a tiny pivot: the factors change and grow), the
 *      refresh makes a whole copy, which follows, while the old copy is
 *      far off; so it does when only the pivots change (a dense matrix),
 *      or only a row index of L (a new analysis of a moved entry), the
 *      place and length of every column of L and U staying the same;
 *  (c) through the public API: a sparse chain of point masses and the
 *      rigid-body chain of the examples give the same trajectories (and
 *      Newton iterations) with the switch on and off; the copy is made at
 *      the second solve with a factorisation (modified Newton), not for
 *      factorisations solved with once (full Newton); the switch off
 *      releases it and leaves Lignum on SUNLinSolSolve; it can be flipped
 *      during a run; the copy is counted in LGNGetWorkSpace; the
 *      refreshes after refactorisations take the values only; the public
 *      getters (LGNGetNumKLUFactorCopies, ...) count what the copy did;
 *  (d) the versions the copy accepts (lgnKluCopySupported, fake versions):
 *      exactly KLU 1.3 (the one installed here) with SUNDIALS 6.4;
 *  (e) the copy is off by default (LGNCreate); switched on, its counters
 *      are in LGNPrintAllStats and restart at LGNReInit; the getters name
 *      a NULL output argument. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"      /* private: the memory record */
#include "lgn_klu_solve.h" /* private: the copy */
#include "models/chain.h"
#include "test_util.h"

#define EPS 2.220446049250313e-16

/* ---------------------------------------------------------------------------
 * Dense test matrices and their sparse storage
 * ------------------------------------------------------------------------ */

static unsigned long rng_state = 12345;
static double Rand(void) /* uniform in [-1, 1) */
{
  rng_state = rng_state * 6364136223846793005UL + 1442695040888963407UL;
  return (double)((rng_state >> 11) & ((1UL << 53) - 1)) / (double)(1UL << 52) - 1.0;
}

typedef struct {
  int n;
  double *a;     /* n x n, column-major; structural entries have pat = 1 */
  char *pat;
} Dense;

static Dense DenseNew(int n)
{
  Dense D;
  D.n   = n;
  D.a   = (double *)calloc((size_t)(n * n), sizeof(double));
  D.pat = (char *)calloc((size_t)(n * n), 1);
  return D;
}

static void DenseFree(Dense *D)
{
  free(D->a);
  free(D->pat);
}

static void Set(Dense *D, int i, int j, double v)
{
  D->a[i + j * D->n]   = v;
  D->pat[i + j * D->n] = 1;
}

/* A SUNSparseMatrix (CSC or CSR) holding the pattern and values of D. */
static void ToSparse(const Dense *D, SUNMatrix S)
{
  const int n = D->n, csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  sunindextype *ptr = SUNSparseMatrix_IndexPointers(S);
  sunindextype *ind = SUNSparseMatrix_IndexValues(S);
  double *val = SUNSparseMatrix_Data(S);
  int o, i, nz = 0;
  for (o = 0; o < n; o++) { /* column (CSC) or row (CSR) o */
    ptr[o] = nz;
    for (i = 0; i < n; i++) {
      const int r = csc ? i : o, c = csc ? o : i;
      if (!D->pat[r + c * n]) continue;
      ind[nz]   = i;
      val[nz++] = D->a[r + c * n];
    }
  }
  ptr[n] = nz;
}

static void MatVec(const Dense *D, const double *x, double *y)
{
  int i, j;
  for (i = 0; i < D->n; i++) y[i] = 0.0;
  for (j = 0; j < D->n; j++)
    for (i = 0; i < D->n; i++) y[i] += D->a[i + j * D->n] * x[j];
}

/* Random non-symmetric diagonally dominant: 4 off-diagonal entries per
 * column. */
static Dense DiagDominant(int n)
{
  Dense D = DenseNew(n);
  int i, j, k;
  for (j = 0; j < n; j++) {
    double s = 0.0;
    for (k = 0; k < 4; k++) {
      i = (int)((Rand() + 1.0) * 0.5 * n) % n;
      if (i == j || D.pat[i + j * n]) continue;
      Set(&D, i, j, Rand());
    }
    for (i = 0; i < n; i++) s += fabs(D.a[i + j * n]);
    for (i = 0; i < n; i++) s += fabs(D.a[j + i * n]);
    Set(&D, j, j, s + 1.0);
  }
  return D;
}

/* Banded: entries (i +- 1, i), (i +- 2, i), each left out with probability
 * 0.2, a few far ones, a dominant diagonal: rows of L and U by rows with
 * two, one and none of the adjacent columns last (LowerByRows). */
static Dense Banded(int n)
{
  Dense D = DenseNew(n);
  int i, j, d;
  for (j = 0; j < n; j++) {
    for (d = -2; d <= 2; d++) {
      i = j + d;
      if (d == 0 || i < 0 || i >= n || Rand() < -0.6) continue;
      Set(&D, i, j, Rand());
    }
    if (Rand() > 0.9) Set(&D, (j + n / 2) % n, j, Rand());
  }
  for (j = 0; j < n; j++) Set(&D, j, j, 6.0 + Rand());
  return D;
}

/* [[K, B^T], [B, 0]]: K (nv x nv) non-symmetric sparse with a dominant
 * diagonal, B (m x nv) of full row rank; the zero block forces KLU to pivot
 * off the diagonal. */
static Dense SaddlePoint(int nv, int m)
{
  Dense D = DenseNew(nv + m);
  double b, v;
  int i, j, k;
  for (j = 0; j < nv; j++) {
    Set(&D, j, j, 4.0 + Rand());
    if (j + 1 < nv) Set(&D, j + 1, j, Rand());
    if (j + 3 < nv) Set(&D, j, j + 3, Rand());
  }
  for (i = 0; i < m; i++) {
    b = 1.0 + 0.5 * Rand();
    Set(&D, nv + i, 2 * i, b); /* distinct columns: full row rank */
    Set(&D, 2 * i, nv + i, b);
    for (k = 0; k < 2; k++) {
      j = (int)((Rand() + 1.0) * 0.5 * nv) % nv;
      if (j == 2 * i) continue;
      v = Rand();
      Set(&D, nv + i, j, v);
      Set(&D, j, nv + i, v);
    }
  }
  return D;
}

/* A block upper triangular matrix with diagonal blocks of the sizes in
 * `sizes` (irreducible: a cycle through each block plus its diagonal),
 * entries above the blocks, and rows and columns permuted at random, so
 * that KLU's BTF has to find the blocks again. */
static Dense BlockTriangular(const int *sizes, int nsizes)
{
  int n = 0, b, i, j, k0 = 0, *pr, *pc;
  Dense T, D;
  for (b = 0; b < nsizes; b++) n += sizes[b];
  T  = DenseNew(n);
  pr = (int *)malloc((size_t)n * sizeof(int));
  pc = (int *)malloc((size_t)n * sizeof(int));
  for (b = 0; b < nsizes; b++) {
    const int s = sizes[b];
    for (i = 0; i < s; i++) {
      Set(&T, k0 + i, k0 + i, 3.0 + Rand());
      if (s > 1) Set(&T, k0 + (i + 1) % s, k0 + i, Rand()); /* the cycle */
    }
    for (j = k0 + s; j < n; j++) /* above the block */
      if (Rand() > 0.6) Set(&T, k0 + (j % s), j, Rand());
    k0 += s;
  }
  for (i = 0; i < n; i++) pr[i] = pc[i] = i;
  for (i = n - 1; i > 0; i--) {
    int r = (int)((Rand() + 1.0) * 0.5 * (i + 1)) % (i + 1), t;
    t = pr[i]; pr[i] = pr[r]; pr[r] = t;
    r = (int)((Rand() + 1.0) * 0.5 * (i + 1)) % (i + 1);
    t = pc[i]; pc[i] = pc[r]; pc[r] = t;
  }
  D = DenseNew(n);
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (T.pat[pr[i] + pc[j] * n]) Set(&D, i, j, T.a[pr[i] + pc[j] * n]);
  DenseFree(&T);
  free(pr);
  free(pc);
  return D;
}

/* ---------------------------------------------------------------------------
 * (a) the copy's solve against SUNLinSolSolve and the true solution
 * ------------------------------------------------------------------------ */

static double MaxAbs(const double *x, int n)
{
  double m = 0.0;
  int i;
  for (i = 0; i < n; i++) m = fmax(m, fabs(x[i]));
  return m;
}

static double MaxDiff(const double *x, const double *y, int n)
{
  double m = 0.0;
  int i;
  for (i = 0; i < n; i++) m = fmax(m, fabs(x[i] - y[i]));
  return m;
}

/* |A|_inf: the largest row sum */
static double NormInf(const Dense *D)
{
  double m = 0.0, s;
  int i, j;
  for (i = 0; i < D->n; i++) {
    for (s = 0.0, j = 0; j < D->n; j++) s += fabs(D->a[i + j * D->n]);
    m = fmax(m, s);
  }
  return m;
}

/* |A^{-1}|_inf, the columns of A^{-1} from SUNLinSolSolve with e_j */
/* The backward error |b - A x|_inf / (|A|_inf |x|_inf) of x for D x = b
 * (res: n doubles of work). */
static double BackwardError(const Dense *D, const double *x, const double *b,
                            double *res)
{
  int i;
  MatVec(D, x, res);
  for (i = 0; i < D->n; i++) res[i] -= b[i];
  return MaxAbs(res, D->n) / (NormInf(D) * MaxAbs(x, D->n));
}

/* The same for a SUNSparseMatrix A (CSC or CSR). */
static double SparseBackwardError(SUNMatrix A, const double *x, const double *b)
{
  const int n   = (int)SUNSparseMatrix_NP(A);
  const int csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
  const double *val = SUNSparseMatrix_Data(A);
  double *res = (double *)calloc((size_t)n, sizeof(double));
  double *rowsum = (double *)calloc((size_t)n, sizeof(double)), e;
  sunindextype p;
  int o;
  for (o = 0; o < n; o++)
    for (p = ptr[o]; p < ptr[o + 1]; p++) {
      const int r = csc ? (int)ind[p] : o, c = csc ? o : (int)ind[p];
      res[r] += val[p] * x[c];
      rowsum[r] += fabs(val[p]);
    }
  for (o = 0; o < n; o++) res[o] -= b[o];
  e = MaxAbs(res, n) / (MaxAbs(rowsum, n) * MaxAbs(x, n));
  free(res);
  free(rowsum);
  return e;
}

static int bitwise_all = 1; /* every comparison by columns with SUNLinSolSolve exact */

/* Does Lignum's solution xl of A x = b with the copy c agree with xs, that
 * of SUNLinSolSolve on the same factors? By columns the copy does KLU's
 * operations in KLU's order: to 1e-13 (bit for bit is reported through
 * bitwise_all). By rows U's rows are kept divided by its diagonal, so the
 * two are differently rounded solves with the same factors: Lignum's
 * backward error within max(10 times KLU's, 10 eps). *rel: |xl - xs| /
 * |xs|, for the report. */
static int AgreesWithKLU(const LGNKluCopy *c, SUNMatrix A, const double *b,
                         const double *xl, const double *xs, double *rel)
{
  const int n = c->n;
  *rel = MaxDiff(xl, xs, n) / MaxAbs(xs, n);
  if (!c->rows) {
    if (*rel != 0.0) bitwise_all = 0;
    return *rel <= 1e-13;
  }
  return SparseBackwardError(A, xl, b) <=
         fmax(10.0 * SparseBackwardError(A, xs, b), 10.0 * EPS);
}

/* KLU's pivot growth max(1, max |U|) (the rows of Rs^{-1} A have largest
 * entries up to 1 with the default scaling), from the copy: by rows U's
 * entries are stored divided by the diagonal of their row. */
static double Growth(const LGNKluCopy *c)
{
  double rho = 1.0;
  int32_t i, q;
  for (i = 0; i < c->n; i++) {
    rho = fmax(rho, fabs(c->Udiag[i]));
    if (c->rows)
      for (q = c->Urp[i]; q < c->Urp[i + 1]; q++)
        rho = fmax(rho, fabs(c->Ux[q] * c->Udiag[i]));
  }
  if (!c->rows)
    for (q = 0; q < c->Up[c->n]; q++) rho = fmax(rho, fabs(c->Ux[q]));
  return rho;
}

/* The backward error of the factorisation in a copy by rows, elementwise
 * over its diagonal blocks: max |S - L U|_kl / (|L| |U|)_kl with
 * S = Rs^{-1} D(P, Q) (its values as Lignum's refactorisation scatters
 * them) and U's entries U(i, j) = Ux U(i, i); HUGE_VAL if S has an entry
 * where |L| |U| has none. The textbook bound (Higham, Accuracy and
 * Stability, Thm 9.3) is gamma_n = n u / (1 - n u), u = eps / 2, for any
 * order of the elimination; the test's own product and U's entries add a
 * few roundings. */
static double FactorBackwardError(const LGNKluCopy *c, const Dense *D)
{
  const int32_t n = c->n;
  double *e = (double *)calloc((size_t)n, sizeof(double));
  double *t = (double *)calloc((size_t)n, sizeof(double)), worst = 0.0;
  int32_t blk, i, k, p, q, j;
  for (blk = 0; blk < c->nblocks; blk++)
    for (i = c->R[blk]; i < c->R[blk + 1]; i++) {
      for (k = c->R[blk]; k < c->R[blk + 1]; k++) e[k] = t[k] = 0.0;
      /* row i of L U: L(i, j) U(j, :) for j < i, then U(i, :) */
      for (p = c->Lrp[i]; p <= c->Lrp[i + 1]; p++) {
        const int last = p == c->Lrp[i + 1];
        const double l = last ? 1.0 : c->Lx[p];
        j = last ? i : c->Li[p];
        e[j] += l * c->Udiag[j];
        t[j] += fabs(l * c->Udiag[j]);
        for (q = c->Urp[j]; q < c->Urp[j + 1]; q++) {
          const double lu = l * (c->Ux[q] * c->Udiag[j]);
          e[c->Ui[q]] += lu;
          t[c->Ui[q]] += fabs(lu);
        }
      }
      for (k = c->R[blk]; k < c->R[blk + 1]; k++) {
        const double a = D->a[c->P[i] + c->Q[k] * D->n];
        const double s = c->scaled ? a / c->Rs[i] : a;
        const double err = fabs(s - e[k]);
        if (t[k] > 0.0) worst = fmax(worst, err / t[k]);
        else if (err != 0.0) worst = HUGE_VAL;
      }
    }
  free(e);
  free(t);
  return worst;
}

static long total_carried[3]; /* CountCarried over the matrices of (a) */

/* Whether two copies hold the same factorisation, bit for bit: sizes,
 * permutations, blocks, patterns, values and the exchanged entries. */
#define SAME(a, b, count) (memcmp((a), (b), (size_t)(count) * sizeof *(a)) == 0)
static int SameCopy(const LGNKluCopy *a, const LGNKluCopy *b)
{
  const int32_t n = a->n;
  return n == b->n && a->nblocks == b->nblocks && a->transpose == b->transpose &&
         a->scaled == b->scaled && SAME(a->P, b->P, n) && SAME(a->Q, b->Q, n) &&
         SAME(a->R, b->R, a->nblocks + 1) && SAME(a->Rs, b->Rs, n) &&
         SAME(a->Lp, b->Lp, n + 1) && SAME(a->Li, b->Li, a->Lp[n]) &&
         SAME(a->Lx, b->Lx, a->Lp[n]) && SAME(a->Lswap, b->Lswap, n) &&
         SAME(a->Up, b->Up, n + 1) && SAME(a->Ui, b->Ui, a->Up[n]) &&
         SAME(a->Ux, b->Ux, a->Up[n]) && SAME(a->Uswap, b->Uswap, n) &&
         SAME(a->Udiag, b->Udiag, n) && SAME(a->Fp, b->Fp, n + 1) &&
         SAME(a->Fi, b->Fi, a->Fp[n]) && SAME(a->Fx, b->Fx, a->Fp[n]) &&
         a->rows == b->rows &&
         (!a->rows ||
          (SAME(a->Lrp, b->Lrp, n + 1) && SAME(a->Urp, b->Urp, n + 1) &&
           SAME(a->Lmap, b->Lmap, a->Lp[n]) && SAME(a->Umap, b->Umap, a->Up[n])));
}

/* Whether lgnKluCopyPlace finds each entry of KLU's packed columns of L
 * and U (the blocks that are not singletons) in the copy: the same value
 * (by rows, one of U divided by U's diagonal entry of its row) and, by
 * rows, in KLU's column (by columns: in KLU's row). */
static int PlacesMatch(const LGNKluCopy *c, SUNLinearSolver LS)
{
  const klu_l_numeric *N = SUNLinSol_KLUGetNumeric(LS);
  const double *LU;
  const int64_t *ki;
  const double *kx;
  int32_t blk, k, k1, k2, j, q, len, lower;
  int64_t ip;
  for (blk = 0; blk < c->nblocks; blk++) {
    k1 = c->R[blk];
    k2 = c->R[blk + 1];
    if (k2 - k1 == 1) continue;
    LU = (const double *)N->LUbx[blk];
    for (k = k1; k < k2; k++)
      for (lower = 0; lower < 2; lower++) {
        ip  = lower ? N->Lip[k] : N->Uip[k];
        len = (int32_t)(lower ? N->Llen[k] : N->Ulen[k]);
        ki  = (const int64_t *)(const void *)(LU + ip);
        kx  = LU + ip + len;
        for (j = 0; j < len; j++) {
          const double v = lower || !c->rows ? kx[j] : kx[j] / c->Udiag[k1 + ki[j]];
          q = lgnKluCopyPlace(c, lower, k, j);
          if ((lower ? c->Lx : c->Ux)[q] != v ||
              (lower ? c->Li : c->Ui)[q] != (c->rows ? k : k1 + ki[j]))
            return 0;
        }
      }
  }
  return 1;
}

/* The rows of L and U by rows whose last two entries are the adjacent
 * columns (i - 2, i - 1 in L, i + 2, i + 1 in U; carried[2]), only the
 * nearest one (carried[1]), or neither (carried[0]): the three paths of
 * LowerByRows and UpperByRows. */
static void CountCarried(const LGNKluCopy *c, long carried[3])
{
  const int32_t n = c->n;
  int32_t i, s, p, pend, two, one;
  const int32_t *Rp, *Ci;
  carried[0] = carried[1] = carried[2] = 0;
  for (s = -1; s <= 1; s += 2) { /* L: s = -1 */
    Rp = s < 0 ? c->Lrp : c->Urp;
    Ci = s < 0 ? c->Li : c->Ui;
    for (i = 0; i < n; i++) {
      p    = Rp[i];
      pend = Rp[i + 1];
      one  = pend > p && Ci[pend - 1] == i + s;
      two  = one && pend - p >= 2 && Ci[pend - 2] == i + 2 * s;
      carried[two ? 2 : one]++;
    }
  }
}

/* The copy *copy of LS's factors against a whole new copy (bit for bit)
 * and against SUNLinSolSolve for b (AgreesWithKLU); returns
 * |x - x(SUNLinSolSolve)| / |x|. */
static double CheckCopy(const char *what, LGNKluCopy *copy, SUNLinearSolver LS,
                        SUNMatrix A, N_Vector b, N_Vector xs)
{
  const int n = (int)N_VGetLength(b);
  double *xl = (double *)malloc((size_t)n * sizeof(double)), rel;
  LGNKluCopy *fresh = NULL;
  CHECK(lgnKluCopyRefresh(&fresh, LS) == LGN_SUCCESS && fresh->nfull == 1 &&
            SameCopy(copy, fresh),
        "%s: the copy equals a whole new copy, bit for bit", what);
  SUNLinSolSolve(LS, A, xs, b, 0.0);
  lgnKluCopySolve(copy, N_VGetArrayPointer(b), xl);
  CHECK(AgreesWithKLU(copy, A, N_VGetArrayPointer(b), xl, N_VGetArrayPointer(xs), &rel),
        "%s: agrees with SUNLinSolSolve (|x - x(SUNLinSolSolve)| / |x| = %.3e)",
        what, rel);
  CHECK(PlacesMatch(copy, LS), "%s: lgnKluCopyPlace finds KLU's entries", what);
  lgnKluCopyFree(&fresh);
  free(xl);
  return rel;
}

/* The largest difference between the values of two copies of the same
 * layout (L, U, U's diagonal, F, Rs), relative to the largest entry of
 * each. */
static double FactorDiff(const LGNKluCopy *a, const LGNKluCopy *b)
{
  const int n = a->n;
  double d = 0.0;
  d = fmax(d, MaxDiff(a->Lx, b->Lx, a->Lp[n]) / fmax(MaxAbs(b->Lx, b->Lp[n]), 1e-300));
  d = fmax(d, MaxDiff(a->Ux, b->Ux, a->Up[n]) / fmax(MaxAbs(b->Ux, b->Up[n]), 1e-300));
  d = fmax(d, MaxDiff(a->Udiag, b->Udiag, n) / MaxAbs(b->Udiag, n));
  if (a->Fp[n] > 0)
    d = fmax(d, MaxDiff(a->Fx, b->Fx, a->Fp[n]) / fmax(MaxAbs(b->Fx, b->Fp[n]), 1e-300));
  return fmax(d, MaxDiff(a->Rs, b->Rs, n) / MaxAbs(b->Rs, n));
}

/* Lignum's refactorisation (lgnKluCopyRefactor) into *copy, which holds
 * KLU's factors of A, with the values of D changed by up to 20%: a
 * factorisation whose backward error is within the textbook bound, as is
 * that of KLU's own refactorisation of those values (a whole copy of
 * them; the difference between the two is reported), and a solution with
 * a backward error within 10 times that of KLU's; a
 * matrix of zeros is refused (LGN_KLU_PIVOT: KLU's rcond below
 * eps^(2/3)), which leaves the copy incomplete, and the next refresh
 * copies KLU's factors whole. A copy by columns (CSR) is not refactored. */
static void CheckOwnRefactor(const char *what, const Dense *D, SUNMatrix A,
                             SUNLinearSolver LS, LGNKluCopy **copy,
                             SUNContext ctx)
{
  const int n = D->n, scale = SUNLinSol_KLUGetCommon(LS)->scale;
  N_Vector b = N_VNew_Serial(n, ctx), xs = N_VNew_Serial(n, ctx);
  double *bd = N_VGetArrayPointer(b), *xl = (double *)malloc((size_t)n * sizeof(double));
  double *r = (double *)malloc((size_t)n * sizeof(double)), diff, berr, berr_klu;
  double fbe, fbe_klu;
  LGNKluCopy *klu = NULL;
  Dense D3 = DenseNew(n);
  long nfull;
  int i, j, flag;

  if (!(*copy)->rows) {
    CHECK(lgnKluCopyRefactor(*copy, A, 1, scale) == LGN_KLU_NO_COPY,
          "%s: a copy by columns is not refactored by Lignum", what);
    goto done;
  }
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (D->pat[i + j * n])
        Set(&D3, i, j, D->a[i + j * n] * (1.0 + 0.2 * cos(2.0 + 3.0 * i + j)));
  ToSparse(&D3, A);
  flag = lgnKluCopyRefactor(*copy, A, 1, scale);
  CHECK(flag == LGN_SUCCESS && (*copy)->complete && (*copy)->nrefactor >= 1,
        "%s: Lignum refactors (%d)", what, flag);
  CHECK(SUNLinSolSetup(LS, A) == 0 && lgnKluCopyRefresh(&klu, LS) == LGN_SUCCESS,
        "%s: KLU refactors the same values", what);
  /* the same elimination in another order of operations (by rows, with
   * U's rows divided by the diagonal): backward stable like KLU's, and the
   * factors (the same pivots, so the same factors in exact arithmetic)
   * differ from KLU's by round-off, reported */
  diff = FactorDiff(*copy, klu);
  fbe  = FactorBackwardError(*copy, &D3);
  fbe_klu = FactorBackwardError(klu, &D3);
  CHECK(fbe <= n * EPS && fbe_klu <= n * EPS,
        "%s: |S - L U| <= n eps |L| |U| for Lignum's factors (%.1f eps) and "
        "KLU's (%.1f eps)", what, fbe / EPS, fbe_klu / EPS);
  /* backward errors |b - A x| / (|A| |x|) of both: Lignum's within 10
   * times KLU's (which carries KLU's pivot growth), or 10 eps */
  for (i = 0; i < n; i++) bd[i] = sin(1.0 + i);
  SUNLinSolSolve(LS, A, xs, b, 0.0);
  berr_klu = BackwardError(&D3, N_VGetArrayPointer(xs), bd, r);
  lgnKluCopySolve(*copy, bd, xl);
  berr = BackwardError(&D3, xl, bd, r);
  CHECK(berr <= fmax(10.0 * berr_klu, 10.0 * EPS),
        "%s: Lignum's refactorisation, backward error %.1e > max(10 x KLU's %.1e, "
        "10 eps)", what, berr, berr_klu);
  printf("  %-23s Lignum's refactorisation: factors vs KLU's %.0e, |S - L U| / "
         "|L| |U| %.1f eps (KLU's %.1f), solve's backward error %.0e (KLU's %.0e)\n",
         what, diff, fbe / EPS, fbe_klu / EPS, berr, berr_klu);

  /* no pivot left: refused, and the next refresh copies whole */
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (D->pat[i + j * n]) Set(&D3, i, j, 0.0);
  ToSparse(&D3, A);
  nfull = (*copy)->nfull;
  CHECK(lgnKluCopyRefactor(*copy, A, 1, scale) == LGN_KLU_PIVOT && !(*copy)->complete,
        "%s: a zero matrix is refused, the copy left incomplete", what);
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (D->pat[i + j * n]) Set(&D3, i, j, D->a[i + j * n]);
  ToSparse(&D3, A);
  CHECK(SUNLinSolSetup(LS, A) == 0 && lgnKluCopyRefresh(copy, LS) == LGN_SUCCESS &&
            (*copy)->nfull == nfull + 1 && (*copy)->complete,
        "%s: after a refusal, KLU's factors are copied whole", what);
done:
  lgnKluCopyFree(&klu);
  DenseFree(&D3);
  free(xl);
  free(r);
  N_VDestroy(b);
  N_VDestroy(xs);
}

/* Refactor with the values of D changed by up to 10% (deterministically,
 * leaving the random sequence of the other tests alone): SUNDIALS keeps
 * the pivots, the stale copy is off, the refresh takes the values only
 * and the copy equals a whole new one. Returns the number of columns of L
 * and U with an entry exchanged with the first (CompactFactor). */
static int CheckValueRefresh(const char *what, const Dense *D, SUNMatrix A,
                              SUNLinearSolver LS, LGNKluCopy **copy,
                              SUNContext ctx)
{
  const int n = D->n;
  const long nfull = (*copy)->nfull, nvalues = (*copy)->nvalues;
  N_Vector b = N_VNew_Serial(n, ctx), xs = N_VNew_Serial(n, ctx);
  double *bd = N_VGetArrayPointer(b), *xsd = N_VGetArrayPointer(xs);
  double *xl = (double *)malloc((size_t)n * sizeof(double)), rel;
  sunindextype *P0 = (sunindextype *)malloc((size_t)n * sizeof(sunindextype));
  Dense D2 = DenseNew(n);
  int i, j, nswap;

  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (D->pat[i + j * n])
        Set(&D2, i, j, D->a[i + j * n] * (1.0 + 0.1 * sin(1.0 + i + 2.0 * j)));
  for (i = 0; i < n; i++) bd[i] = cos(3.0 * i);
  memcpy(P0, SUNLinSol_KLUGetNumeric(LS)->Pnum, (size_t)n * sizeof(sunindextype));
  ToSparse(&D2, A);
  CHECK(SUNLinSolSetup(LS, A) == 0 &&
            memcmp(P0, SUNLinSol_KLUGetNumeric(LS)->Pnum,
                   (size_t)n * sizeof(sunindextype)) == 0,
        "%s: refactored, the pivots kept", what);
  SUNLinSolSolve(LS, A, xs, b, 0.0);
  lgnKluCopySolve(*copy, bd, xl); /* the stale copy: the test can fail */
  CHECK(MaxDiff(xl, xsd, n) > 1e-6 * MaxAbs(xsd, n),
        "%s: new values, the stale copy differs from SUNLinSolSolve", what);
  CHECK(lgnKluCopyRefresh(copy, LS) == LGN_SUCCESS && (*copy)->nfull == nfull &&
            (*copy)->nvalues == nvalues + 1,
        "%s: the refresh takes the values only (%ld whole copies, %ld of "
        "values)", what, (*copy)->nfull, (*copy)->nvalues);
  rel = CheckCopy(what, *copy, LS, A, b, xs);
  for (nswap = 0, j = 0; j < n; j++)
    nswap += ((*copy)->Lswap[j] != 0) + ((*copy)->Uswap[j] != 0);
  printf("  %-23s refactored, values refreshed: vs SUNLinSolSolve %.0e (%d "
         "columns of L and U with an exchanged entry)\n", what, rel, nswap);
  CheckOwnRefactor(what, D, A, LS, copy, ctx);
  DenseFree(&D2);
  free(P0);
  free(xl);
  N_VDestroy(b);
  N_VDestroy(xs);
  return nswap;
}

static double InverseNormInf(SUNLinearSolver LS, SUNMatrix A, int n, SUNContext ctx)
{
  N_Vector e = N_VNew_Serial(n, ctx), col = N_VNew_Serial(n, ctx);
  double *rows = (double *)calloc((size_t)n, sizeof(double)), m;
  int i, j;
  for (j = 0; j < n; j++) {
    N_VConst(0.0, e);
    N_VGetArrayPointer(e)[j] = 1.0;
    SUNLinSolSolve(LS, A, col, e, 0.0);
    for (i = 0; i < n; i++) rows[i] += fabs(N_VGetArrayPointer(col)[i]);
  }
  m = MaxAbs(rows, n);
  free(rows);
  N_VDestroy(e);
  N_VDestroy(col);
  return m;
}

/* Factor D (stored as `type`) with SUNLinSol_KLU, copy the factors, solve
 * A x = A x_true both ways. Returns KLU's Symbolic/Numeric facts through
 * the pointers for the structural checks of the caller. */
static void CheckSolve(const char *name, const Dense *D, int type,
                       SUNContext ctx, long *nblocks, long *nsingletons,
                       long *noffdiag_pivots, long *nzoff)
{
  const int n = D->n;
  const char *fmt = type == CSC_MAT ? "CSC" : "CSR";
  SUNMatrix A = SUNSparseMatrix(n, n, (sunindextype)n * n, type, ctx);
  N_Vector xt = N_VNew_Serial(n, ctx), b = N_VNew_Serial(n, ctx);
  N_Vector xs = N_VNew_Serial(n, ctx), xl = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = SUNLinSol_KLU(b, A, ctx);
  LGNKluCopy *copy = NULL;
  double *xtd = N_VGetArrayPointer(xt), *bd = N_VGetArrayPointer(b);
  double *xsd = N_VGetArrayPointer(xs), *xld = N_VGetArrayPointer(xl);
  double *res = (double *)malloc((size_t)n * sizeof(double));
  double rel_sun, rel_true, cond, rho, backward, tol_true;
  char what[64];
  klu_l_numeric *Num;
  klu_l_symbolic *Sym;
  int i, k, flag, nswap;
  long carried[3];

  ToSparse(D, A);
  CHECK(SUNLinSolInitialize(LS) == 0, "%s %s: initialize", name, fmt);
  /* before any factorisation there is nothing to copy */
  CHECK(lgnKluCopyRefresh(&copy, LS) == LGN_KLU_NO_COPY && copy == NULL,
        "%s %s: no copy before the first setup", name, fmt);
  CHECK(SUNLinSolSetup(LS, A) == 0, "%s %s: setup", name, fmt);
  flag = lgnKluCopyRefresh(&copy, LS);
  CHECK(flag == LGN_SUCCESS && copy != NULL, "%s %s: copy (%d)", name, fmt, flag);
  if (flag != LGN_SUCCESS) goto done;
  CHECK(copy->transpose == (type == CSR_MAT), "%s %s: transposed solve iff CSR",
        name, fmt);

  for (i = 0; i < n; i++) xtd[i] = Rand();
  MatVec(D, xtd, bd);
  SUNLinSolSolve(LS, A, xs, b, 0.0);
  lgnKluCopySolve(copy, bd, xld);
  CHECK(AgreesWithKLU(copy, A, bd, xld, xsd, &rel_sun),
        "%s %s: agrees with SUNLinSolSolve (|x - x(SUNLinSolSolve)| / |x| = %.3e)",
        name, fmt, rel_sun);

  /* the errors: backward, |b - A x| / (|A| |x|), round-off times KLU's
   * pivot growth rho = max |U| / max |Rs^{-1} A| (its pivoting prefers the
   * diagonal down to 1e-3 times the column's largest entry, so rho can be
   * large; with the default scaling max |Rs^{-1} A| = 1); forward, against
   * the true solution, that times the condition number cond_inf(A) =
   * |A| |A^{-1}| (A^{-1} by columns, from n solves) */
  Sym  = SUNLinSol_KLUGetSymbolic(LS);
  Num  = SUNLinSol_KLUGetNumeric(LS);
  cond = NormInf(D) * InverseNormInf(LS, A, n, ctx);
  rho  = Growth(copy);
  backward = BackwardError(D, xld, bd, res);
  CHECK(backward <= 10.0 * n * EPS * rho, "%s %s: |b - A x| / (|A| |x|) = %.3e > "
        "10 n eps rho = %.3e", name, fmt, backward, 10.0 * n * EPS * rho);
  rel_true = MaxDiff(xld, xtd, n) / MaxAbs(xtd, n);
  tol_true = 10.0 * n * EPS * rho * cond;
  CHECK(rel_true <= tol_true, "%s %s: |x - x_true| / |x_true| = %.3e > %.3e "
        "(10 n eps rho cond, rho = %.1e, cond = %.2e)", name, fmt, rel_true,
        tol_true, rho, cond);
  printf("  %-19s %s n %3d  blocks %2ld  L+U %5ld  F %2ld  cond %.0e  rho %.0e  "
         "vs SUNLinSolSolve %.0e  backward %.0e  vs x_true %.0e\n", name, fmt,
         n, (long)Sym->nblocks, (long)(Num->lnz + Num->unz), (long)Num->nzoff,
         cond, rho, rel_sun, backward, rel_true);

  /* in place: x and b the same array, the same solution bit for bit */
  memcpy(res, bd, (size_t)n * sizeof(double));
  lgnKluCopySolve(copy, res, res);
  CHECK(memcmp(res, xld, (size_t)n * sizeof(double)) == 0, "%s %s: in place", name, fmt);

  /* what KLU did, for the caller's structural checks */
  *nblocks = (long)Sym->nblocks;
  *nzoff   = (long)Num->nzoff;
  *nsingletons = *noffdiag_pivots = 0;
  for (k = 0; k < Sym->nblocks; k++)
    if (Sym->R[k + 1] - Sym->R[k] == 1) (*nsingletons)++;
  for (k = 0; k < n; k++)
    if (Num->Pnum[k] != Sym->Q[k]) (*noffdiag_pivots)++;

  snprintf(what, sizeof what, "%s %s", name, fmt);
  nswap = CheckValueRefresh(what, D, A, LS, &copy, ctx);
  /* CSC (klu_solve): L and U by rows; CSR (klu_tsolve): by columns, in
   * KLU's order (no entry exchanged) */
  CHECK(copy->rows == (type == CSC_MAT) && nswap == 0,
        "%s: by rows iff CSC, KLU's order of entries (%d exchanged)", what, nswap);
  if (copy->rows) {
    CountCarried(copy, carried);
    printf("  %-23s rows of L and U with 2, 1, 0 carried entries: %ld %ld %ld\n",
           what, carried[2], carried[1], carried[0]);
    total_carried[0] += carried[0];
    total_carried[1] += carried[1];
    total_carried[2] += carried[2];
  }

done:
  free(res);
  lgnKluCopyFree(&copy);
  CHECK(copy == NULL, "lgnKluCopyFree sets NULL");
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(xt);
  N_VDestroy(b);
  N_VDestroy(xs);
  N_VDestroy(xl);
}

static void Matrices(SUNContext ctx)
{
  const int sizes[] = {1, 3, 1, 1, 5, 2, 1, 4, 6, 1};
  const int types[2] = {CSC_MAT, CSR_MAT};
  long nb, ns, npiv, nzoff;
  int t;
  Dense D;

  printf("(a) the copy's solve on KLU's factors\n");
  for (t = 0; t < 2; t++) {
    D = DiagDominant(300);
    CheckSolve("diagonally dominant", &D, types[t], ctx, &nb, &ns, &npiv, &nzoff);
    DenseFree(&D);

    D = Banded(400);
    CheckSolve("banded", &D, types[t], ctx, &nb, &ns, &npiv, &nzoff);
    DenseFree(&D);

    D = SaddlePoint(60, 25);
    CheckSolve("saddle point", &D, types[t], ctx, &nb, &ns, &npiv, &nzoff);
    CHECK(npiv > 0, "saddle point: KLU pivoted off the diagonal (%ld rows)", npiv);
    DenseFree(&D);

    D = BlockTriangular(sizes, (int)(sizeof sizes / sizeof sizes[0]));
    CheckSolve("block triangular", &D, types[t], ctx, &nb, &ns, &npiv, &nzoff);
    CHECK(nb == 10 && ns == 5 && nzoff > 0,
          "block triangular: BTF found %ld blocks (10), %ld singletons (5), "
          "%ld entries off the blocks", nb, ns, nzoff);
    DenseFree(&D);
  }
  CHECK(total_carried[0] > 0 && total_carried[1] > 0 && total_carried[2] > 0,
        "rows with 2, 1, 0 carried entries: %ld %ld %ld, all paths taken",
        total_carried[2], total_carried[1], total_carried[0]);
}

/* ---------------------------------------------------------------------------
 * (b) a factorisation with new pivots
 * ------------------------------------------------------------------------ */

/* A1: tridiagonal plus a full last row and column (an arrow), diagonally
 * dominant: with the natural order and no BTF (set below) KLU pivots on
 * the diagonal without fill. A2: the same pattern with a tiny (0, 0) entry
 * and (n-1, 0), (0, n-1) large, so that A1's pivots leave a tiny pivot
 * (rcond ~ 1e-26), and rows 5 and 6 nearly equal (condest ~ 1e13):
 * SUNLinSolSetup factors A2 afresh, pivots on the full row and U fills in.
 * Symmetric in the arrow, so that A2^T (CSR) behaves alike. */
static void RepivotMatrices(int n, Dense *A1, Dense *A2)
{
  int i, j;
  *A1 = DenseNew(n);
  *A2 = DenseNew(n);
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (abs(i - j) <= 1 || i == n - 1 || j == n - 1 ||
          ((i == 5 || i == 6) && j >= 4 && j <= 7))
        Set(A1, i, j, i == j ? 10.0 : 0.25 * Rand());
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      if (A1->pat[i + j * n]) Set(A2, i, j, A1->a[i + j * n]);
  A2->a[0]                     = 1e-14;
  A2->a[1] = A2->a[n]          = 0.1;  /* (1, 0), (0, 1)         */
  A2->a[n - 1] = A2->a[(n - 1) * n] = 10.0; /* (n-1, 0), (0, n-1) */
  for (j = 0; j < n; j++) A2->a[6 + j * n] = A2->a[5 + j * n];
  A2->a[6 + 6 * n] += 1e-12;
}

static void Repivot(SUNContext ctx, int type)
{
  const int n = 40;
  const char *fmt = type == CSC_MAT ? "CSC" : "CSR";
  const double uround23 = pow(EPS, 2.0 / 3.0);
  SUNMatrix A = SUNSparseMatrix(n, n, (sunindextype)n * n, type, ctx);
  N_Vector b = N_VNew_Serial(n, ctx), xs = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = SUNLinSol_KLU(b, A, ctx);
  klu_l_common *Cm = SUNLinSol_KLUGetCommon(LS);
  LGNKluCopy *copy = NULL;
  double *bd = N_VGetArrayPointer(b), *xsd = N_VGetArrayPointer(xs), xl[40], rel;
  long lnz1, unz1, lnz2, unz2, npiv = 0;
  sunindextype P1[40];
  size_t cap_l1, cap_u1;
  long nfull1, nvalues1;
  char what[64];
  Dense A1, A2;
  int i;

  RepivotMatrices(n, &A1, &A2);
  for (i = 0; i < n; i++) bd[i] = Rand();
  ToSparse(&A1, A);
  SUNLinSol_KLUSetOrdering(LS, 2); /* natural */
  Cm->btf = 0;
  SUNLinSolInitialize(LS);
  CHECK(SUNLinSolSetup(LS, A) == 0 && lgnKluCopyRefresh(&copy, LS) == LGN_SUCCESS,
        "repivot %s: A1 factored and copied", fmt);
  lnz1 = (long)SUNLinSol_KLUGetNumeric(LS)->lnz;
  unz1 = (long)SUNLinSol_KLUGetNumeric(LS)->unz;
  memcpy(P1, SUNLinSol_KLUGetNumeric(LS)->Pnum, sizeof P1);
  cap_l1 = copy->cap_l;
  cap_u1 = copy->cap_u;
  /* new values with A1's pattern: the values only */
  snprintf(what, sizeof what, "repivot %s, A1", fmt);
  CheckValueRefresh(what, &A1, A, LS, &copy, ctx);
  nfull1   = copy->nfull;
  nvalues1 = copy->nvalues;

  ToSparse(&A2, A);
  CHECK(SUNLinSolSetup(LS, A) == 0, "repivot %s: A2 set up", fmt);
  /* SUNDIALS' test for a new factorisation, and its outcome */
  CHECK(Cm->rcond < uround23 && Cm->condest > 1.0 / uround23,
        "repivot %s: refactor rcond %.2e, condest %.2e: SUNDIALS factors anew",
        fmt, Cm->rcond, Cm->condest);
  lnz2 = (long)SUNLinSol_KLUGetNumeric(LS)->lnz;
  unz2 = (long)SUNLinSol_KLUGetNumeric(LS)->unz;
  for (i = 0; i < n; i++)
    if (SUNLinSol_KLUGetNumeric(LS)->Pnum[i] != P1[i]) npiv++;
  CHECK(npiv > 0 && (lnz2 > lnz1 || unz2 > unz1),
        "repivot %s: new pivots (%ld rows) and a factor grew (L %ld -> %ld, "
        "U %ld -> %ld)", fmt, npiv, lnz1, lnz2, unz1, unz2);

  SUNLinSolSolve(LS, A, xs, b, 0.0);
  /* the old copy is far off: the test can fail */
  lgnKluCopySolve(copy, bd, xl);
  CHECK(MaxDiff(xl, xsd, n) > 1e-3 * MaxAbs(xsd, n),
        "repivot %s: the stale copy differs from SUNLinSolSolve", fmt);
  CHECK(lgnKluCopyRefresh(&copy, LS) == LGN_SUCCESS && copy->nfull == nfull1 + 1 &&
            copy->nvalues == nvalues1,
        "repivot %s: refreshed by a whole copy (%ld whole copies, %ld of "
        "values)", fmt, copy->nfull, copy->nvalues);
  CHECK(copy->cap_l >= (size_t)lnz2 && copy->cap_u >= (size_t)unz2 &&
            (copy->cap_l > cap_l1 || copy->cap_u > cap_u1),
        "repivot %s: the copy grew (L %zu -> %zu, U %zu -> %zu)", fmt, cap_l1,
        copy->cap_l, cap_u1, copy->cap_u);
  lgnKluCopySolve(copy, bd, xl);
  CHECK(AgreesWithKLU(copy, A, bd, xl, xsd, &rel),
        "repivot %s: agrees with SUNLinSolSolve (|x - x(SUNLinSolSolve)| / |x| = %.3e)",
        fmt, rel);
  snprintf(what, sizeof what, "repivot %s, A2", fmt);
  CheckCopy(what, copy, LS, A, b, xs);
  printf("(b) repivot %s: L %ld -> %ld, U %ld -> %ld entries, %ld pivots "
         "changed; refreshed copy vs SUNLinSolSolve %.1e\n", fmt, lnz1, lnz2,
         unz1, unz2, npiv, rel);

  lgnKluCopyFree(&copy);
  DenseFree(&A1);
  DenseFree(&A2);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(b);
  N_VDestroy(xs);
}

/* M1 = 10 I plus a subdiagonal of 0.5 and (5, 0) = 0.3; M2 the same with
 * (6, 0) in place of (5, 0). In the natural order and without BTF, KLU
 * factors both on the diagonal and without fill: L(:, 0) holds rows 1
 * and 5, or 1 and 6, the other columns of L one row, U only its diagonal.
 * For CSR the transposes are stored, so that KLU factors M1 and M2 too. */
static Dense MovedEntryMatrix(int n, int row, int csr)
{
  Dense M = DenseNew(n);
  int i;
  for (i = 0; i < n; i++) {
    Set(&M, i, i, 10.0);
    if (i + 1 < n) Set(&M, csr ? i : i + 1, csr ? i + 1 : i, 0.5);
  }
  Set(&M, csr ? 0 : row, csr ? row : 0, 0.3);
  return M;
}

/* Dense 4 x 4 (every entry stored, zeros too): M1 diagonally dominant,
 * factored on the diagonal; M2 with a tiny (0, 0), zeros below it in rows
 * 2 and 3 and those two rows nearly equal, so that refactoring with M1's
 * pivots leaves a tiny pivot (rcond ~ 1e-28) on a matrix with condest ~
 * 1e13: SUNDIALS factors it anew, pivoting on row 1 first. L and U are
 * dense either way. Rows of largest entry 1 (KLU's scaling keeps them);
 * for CSR the transposes. */
static Dense DensePivotMatrix(int which, int csr)
{
  static const double m[2][4][4] = {
    {{1.0, 0.1, 0.2, 0.1}, {0.2, 1.0, 0.1, 0.3}, {0.1, 0.3, 1.0, 0.2}, {0.3, 0.1, 0.2, 1.0}},
    {{1e-14, 1.0, 0.3, 0.2}, {1.0, 0.2, 0.4, 0.1}, {0.0, 0.5, 0.3, 1.0},
     {0.0, 0.5, 0.3, 1.0 - 1e-12}}};
  Dense M = DenseNew(4);
  int i, j;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) Set(&M, csr ? j : i, csr ? i : j, m[which - 1][i][j]);
  return M;
}

/* M1 factored and copied, then M2 factored (after a new analysis, as
 * Lignum does when the pattern of A changes, if reanalyse): KLU's blocks,
 * F (none) and the place and length of every column of L and U are M1's,
 * all that a value-only refresh could compare in O(n) besides the
 * permutations. What differs -- a row index of L (MovedEntryMatrix) or
 * the pivots (DensePivotMatrix) -- must make the refresh copy the whole
 * factorisation. */
static void WholeCopyOnSameLayout(SUNContext ctx, int type, const char *label,
                                  const Dense *M1, const Dense *M2,
                                  int reanalyse, int same_pivots)
{
  const int n = M1->n;
  const char *fmt = type == CSR_MAT ? "CSR" : "CSC";
  SUNMatrix A = SUNSparseMatrix(n, n, (sunindextype)n * n, type, ctx);
  N_Vector b = N_VNew_Serial(n, ctx), xs = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = SUNLinSol_KLU(b, A, ctx);
  klu_l_common *Cm = SUNLinSol_KLUGetCommon(LS);
  klu_l_numeric *Num;
  LGNKluCopy *copy = NULL;
  double *bd = N_VGetArrayPointer(b), *xsd = N_VGetArrayPointer(xs), xl[16];
  sunindextype layout[5][16]; /* Pnum, Lip, Llen, Uip, Ulen */
  const size_t bytes = (size_t)n * sizeof(sunindextype);
  long lnz, unz;
  char what[96];
  int i, same;

  snprintf(what, sizeof what, "%s %s", label, fmt);
  for (i = 0; i < n; i++) bd[i] = cos(1.0 + i);
  ToSparse(M1, A);
  SUNLinSol_KLUSetOrdering(LS, 2); /* natural */
  Cm->btf = 0;
  SUNLinSolInitialize(LS);
  CHECK(SUNLinSolSetup(LS, A) == 0 && lgnKluCopyRefresh(&copy, LS) == LGN_SUCCESS,
        "%s: M1 factored and copied", what);
  Num = SUNLinSol_KLUGetNumeric(LS);
  memcpy(layout[0], Num->Pnum, bytes);
  memcpy(layout[1], Num->Lip, bytes);
  memcpy(layout[2], Num->Llen, bytes);
  memcpy(layout[3], Num->Uip, bytes);
  memcpy(layout[4], Num->Ulen, bytes);
  lnz = (long)Num->lnz;
  unz = (long)Num->unz;

  ToSparse(M2, A);
  if (reanalyse)
    CHECK(SUNLinSol_KLUReInit(LS, A, (sunindextype)n * n, SUNKLU_REINIT_PARTIAL) == 0,
          "%s: a new analysis", what);
  CHECK(SUNLinSolSetup(LS, A) == 0, "%s: M2 factored", what);
  Num  = SUNLinSol_KLUGetNumeric(LS);
  same = SUNLinSol_KLUGetSymbolic(LS)->nblocks == 1 && Num->nzoff == 0 &&
         Num->lnz == lnz && Num->unz == unz &&
         memcmp(layout[1], Num->Lip, bytes) == 0 &&
         memcmp(layout[2], Num->Llen, bytes) == 0 &&
         memcmp(layout[3], Num->Uip, bytes) == 0 &&
         memcmp(layout[4], Num->Ulen, bytes) == 0;
  CHECK(same && (memcmp(layout[0], Num->Pnum, bytes) == 0) == same_pivots,
        "%s: the place and length of each column of L and U are M1's, the "
        "pivots %s", what, same_pivots ? "too" : "not");

  SUNLinSolSolve(LS, A, xs, b, 0.0);
  lgnKluCopySolve(copy, bd, xl); /* the stale copy */
  CHECK(MaxDiff(xl, xsd, n) > 1e-6 * MaxAbs(xsd, n),
        "%s: the stale copy differs from SUNLinSolSolve", what);
  CHECK(lgnKluCopyRefresh(&copy, LS) == LGN_SUCCESS && copy->nfull == 2 &&
            copy->nvalues == 0,
        "%s: refreshed by a whole copy (%ld whole copies, %ld of values)", what,
        copy->nfull, copy->nvalues);
  printf("(b) %s: a whole copy; vs SUNLinSolSolve %.1e\n", what,
         CheckCopy(what, copy, LS, A, b, xs));

  lgnKluCopyFree(&copy);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(b);
  N_VDestroy(xs);
}

static void SameLayoutCases(SUNContext ctx, int type)
{
  const int csr = type == CSR_MAT;
  Dense M1 = MovedEntryMatrix(12, 5, csr), M2 = MovedEntryMatrix(12, 6, csr);
  WholeCopyOnSameLayout(ctx, type, "moved entry, new analysis", &M1, &M2, 1, 1);
  DenseFree(&M1);
  DenseFree(&M2);
  M1 = DensePivotMatrix(1, csr);
  M2 = DensePivotMatrix(2, csr);
  WholeCopyOnSameLayout(ctx, type, "dense, new pivots", &M1, &M2, 0, 0);
  DenseFree(&M1);
  DenseFree(&M2);
}

/* ---------------------------------------------------------------------------
 * (c) the public switch: a planar chain of K point masses on R^2K, rigid
 *     links of length 1, M = I, gravity; sparse M and B in A's format,
 *     K_t, C_t and the curvature by difference quotients
 * ------------------------------------------------------------------------ */

#define NMASS 12

static int PMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  sunindextype *ptr = SUNSparseMatrix_IndexPointers(M);
  sunindextype *ind = SUNSparseMatrix_IndexValues(M), i;
  double *val = SUNSparseMatrix_Data(M);
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 2 * NMASS; i++) {
    ptr[i] = i;
    ind[i] = i;
    val[i] = 1.0;
  }
  ptr[2 * NMASS] = 2 * NMASS;
  return 0;
}

static int PForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  double *gg = N_VGetArrayPointer(g);
  int k;
  (void)t; (void)q; (void)v; (void)ud;
  for (k = 0; k < NMASS; k++) {
    gg[2 * k]     = 0.0;
    gg[2 * k + 1] = 9.81;
  }
  return 0;
}

/* link k from mass k - 1 (the origin for k = 0) to mass k */
static void Link(const double *x, int k, double d[2])
{
  d[0] = x[2 * k] - (k > 0 ? x[2 * k - 2] : 0.0);
  d[1] = x[2 * k + 1] - (k > 0 ? x[2 * k - 1] : 0.0);
}

static int PConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double *x = N_VGetArrayPointer(q);
  double d[2];
  int k;
  (void)t; (void)ud;
  for (k = 0; k < NMASS; k++) {
    Link(x, k, d);
    N_VGetArrayPointer(phi)[k] = 0.5 * (d[0] * d[0] + d[1] * d[1] - 1.0);
  }
  return 0;
}

/* B: row k has d_k at mass k and -d_k at mass k - 1 */
static int PConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const double *x = N_VGetArrayPointer(q);
  sunindextype *ptr, *ind;
  double *val, d[2];
  int k, a, nz = 0;
  (void)t; (void)ud;
  if (SUNSparseMatrix_NNZ(B) < 4 * NMASS &&
      SUNSparseMatrix_Reallocate(B, 4 * NMASS) != 0)
    return -1;
  ptr = SUNSparseMatrix_IndexPointers(B);
  ind = SUNSparseMatrix_IndexValues(B);
  val = SUNSparseMatrix_Data(B);
  if (SUNSparseMatrix_SparseType(B) == CSR_MAT) {
    for (k = 0; k < NMASS; k++) {
      ptr[k] = nz;
      Link(x, k, d);
      for (a = 0; a < 2 && k > 0; a++) {
        ind[nz]   = 2 * (k - 1) + a;
        val[nz++] = -d[a];
      }
      for (a = 0; a < 2; a++) {
        ind[nz]   = 2 * k + a;
        val[nz++] = d[a];
      }
    }
    ptr[NMASS] = nz;
  } else {
    for (k = 0; k < NMASS; k++)
      for (a = 0; a < 2; a++) { /* column 2k + a: rows k and k + 1 */
        ptr[2 * k + a] = nz;
        Link(x, k, d);
        ind[nz]   = k;
        val[nz++] = d[a];
        if (k + 1 < NMASS) {
          Link(x, k + 1, d);
          ind[nz]   = k + 1;
          val[nz++] = -d[a];
        }
      }
    ptr[2 * NMASS] = nz;
  }
  return 0;
}

typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} PChain;

/* The chain at 30 degrees from the vertical, at rest; modified Newton with
 * the extrapolating predictor (matrices reused over steps) or full Newton;
 * LGNSetOwnKLUSolves(own), or the default for own < 0. */
static void PChainSetup(PChain *c, SUNContext ctx, int type, int newton, int own)
{
  const sunindextype nv = 2 * NMASS, n = nv + NMASS;
  double *x;
  int k, flag;
  memset(c, 0, sizeof *c);
  c->ctx  = ctx;
  c->G    = LGNGroup_Rn(nv);
  c->q    = N_VNew_Serial(nv, ctx);
  c->v    = N_VNew_Serial(nv, ctx);
  c->tmpl = N_VNew_Serial(n, ctx);
  c->A    = SUNSparseMatrix(n, n, 1, type, ctx);
  c->LS   = SUNLinSol_KLU(c->tmpl, c->A, ctx);
  x       = N_VGetArrayPointer(c->q);
  for (k = 0; k < NMASS; k++) {
    x[2 * k]     = (k + 1) * 0.5;
    x[2 * k + 1] = -(k + 1) * sqrt(0.75);
  }
  N_VConst(0.0, c->v);
  c->mem = LGNCreate(ctx);
  flag = LGNSetGroup(c->mem, c->G);
  if (!flag) flag = LGNInit(c->mem, 0.0, c->q, c->v);
  if (!flag) flag = LGNSetMassFn(c->mem, PMass);
  if (!flag) flag = LGNSetForceFn(c->mem, PForce);
  if (!flag) flag = LGNSetConstraints(c->mem, NMASS, PConstr, PConstrJac);
  if (!flag) flag = LGNSetLinearSolver(c->mem, c->LS, c->A);
  if (!flag) flag = LGNSetStepSize(c->mem, 1e-3);
  if (!flag) flag = LGNSetNewtonMode(c->mem, newton);
  if (!flag) flag = LGNSetPredictor(c->mem, LGN_PREDICTOR_EXTRAPOLATE);
  if (!flag && own >= 0) flag = LGNSetOwnKLUSolves(c->mem, own);
  CHECK(flag == LGN_SUCCESS, "point chain: set-up (%d)", flag);
}

static void PChainFree(PChain *c)
{
  LGNFree(&c->mem);
  SUNLinSolFree(c->LS);
  SUNMatDestroy(c->A);
  N_VDestroy(c->q);
  N_VDestroy(c->v);
  N_VDestroy(c->tmpl);
  LGNGroup_Destroy(c->G);
}

/* The public counters of the copy, and the linear solver's. */
typedef struct {
  long int ncopy, nvalue, nrefactor, nsolve, npivot, npattern, nnocopy;
  long int nlsetup, nlsolve;
} Counts;

static Counts GetCounts(void *mem)
{
  Counts k;
  int flag = LGNGetNumKLUFactorCopies(mem, &k.ncopy);
  flag |= LGNGetNumKLUValueCopies(mem, &k.nvalue);
  flag |= LGNGetNumOwnKLURefactors(mem, &k.nrefactor);
  flag |= LGNGetNumOwnKLUSolves(mem, &k.nsolve);
  flag |= LGNGetNumKLUFallbacks(mem, &k.npivot, &k.npattern, &k.nnocopy);
  flag |= LGNGetNumLinSolvSetups(mem, &k.nlsetup);
  flag |= LGNGetNumLinSolves(mem, &k.nlsolve);
  CHECK(flag == LGN_SUCCESS, "the copy's getters succeed (%d)", flag);
  return k;
}

static void Switch(SUNContext ctx, int type, int newton)
{
  const char *fmt = type == CSC_MAT ? "CSC" : "CSR";
  const char *nwt = newton == LGN_NEWTON_FULL ? "full" : "modified";
  PChain on, off, flip;
  LGNMem mon, moff, mflip;
  sunrealtype t;
  long int nni_on, nni_off, nni_flip, rw_on, iw_on, rw_off, iw_off;
  long int nfull = 0, nvalues = 0, nrefactor = 0;
  const int byrows = type == CSC_MAT; /* Lignum refactors into the copy */
  double d;
  int f1, f2, f3;

  PChainSetup(&on, ctx, type, newton, SUNTRUE);
  PChainSetup(&off, ctx, type, newton, SUNFALSE);
  PChainSetup(&flip, ctx, type, newton, SUNTRUE);
  mon   = (LGNMem)on.mem;
  moff  = (LGNMem)off.mem;
  mflip = (LGNMem)flip.mem;

  /* the output times of the flipped run below (each tout shortens a step) */
  f1 = LGNSolve(on.mem, 0.1, &t, on.q, on.v, LGN_NORMAL);
  f2 = LGNSolve(off.mem, 0.1, &t, off.q, off.v, LGN_NORMAL);
  f1 |= LGNSolve(on.mem, 0.2, &t, on.q, on.v, LGN_NORMAL);
  f2 |= LGNSolve(off.mem, 0.2, &t, off.q, off.v, LGN_NORMAL);
  f1 |= LGNSolve(on.mem, 0.3, &t, on.q, on.v, LGN_NORMAL);
  f2 |= LGNSolve(off.mem, 0.3, &t, off.q, off.v, LGN_NORMAL);
  CHECK(f1 == LGN_SUCCESS && f2 == LGN_SUCCESS, "point chain %s %s: runs (%d, %d)",
        fmt, nwt, f1, f2);
  /* CSC: copied at the first solve with KLU's factorisation, then Lignum
   * refactors into the copy (full and modified Newton alike); CSR: copied
   * at the second solve with a factorisation, so never with full Newton
   * (one solve per factorisation), and refreshed after KLU's
   * refactorisations (values only) */
  if (mon->klu.copy != NULL) {
    nfull     = mon->klu.copy->nfull;
    nvalues   = mon->klu.copy->nvalues;
    nrefactor = mon->klu.copy->nrefactor;
  }
  if (newton == LGN_NEWTON_MODIFIED || byrows)
    CHECK(mon->klu.copy != NULL && mon->klu.valid, "point chain %s %s: on, the copy is used",
          fmt, nwt);
  if (byrows)
    CHECK(nfull == 1 && nvalues == 0 && nrefactor > 0 && mon->klu.nfallback == 0,
          "point chain %s %s: one copy of KLU's factors, then Lignum's "
          "refactorisations (%ld whole copies, %ld of values, %ld refactorisations, "
          "%ld handed back to KLU)", fmt, nwt, nfull, nvalues, nrefactor,
          mon->klu.nfallback);
  else if (newton == LGN_NEWTON_MODIFIED)
    CHECK(nfull >= 1 && nvalues > 0 && nrefactor == 0,
          "point chain %s %s: refreshes after refactorisations take the values "
          "only (%ld whole copies, %ld of values)", fmt, nwt, nfull, nvalues);
  else
    CHECK(mon->klu.copy == NULL && !mon->klu.valid,
          "point chain %s %s: on, factors solved with once are not copied", fmt, nwt);
  CHECK(moff->klu.copy == NULL && !moff->klu.valid,
        "point chain %s %s: off, no copy (SUNLinSolSolve)", fmt, nwt);
  {
    Counts on_c = GetCounts(on.mem), off_c = GetCounts(off.mem);
    CHECK(on_c.ncopy == nfull && on_c.nvalue == nvalues &&
              on_c.nrefactor == nrefactor && on_c.npivot == 0 &&
              on_c.npattern == 0 && on_c.nnocopy == 0,
          "point chain %s %s: the getters count the copy's refreshes and "
          "refactorisations (%ld/%ld, %ld/%ld, %ld/%ld)", fmt, nwt, on_c.ncopy,
          nfull, on_c.nvalue, nvalues, on_c.nrefactor, nrefactor);
    CHECK(on_c.nsolve > 0 ? (newton == LGN_NEWTON_MODIFIED || byrows)
                          : (newton == LGN_NEWTON_FULL && !byrows),
          "point chain %s %s: Lignum's solves counted (%ld of %ld)", fmt, nwt,
          on_c.nsolve, on_c.nlsolve);
    /* CSC: every setup after KLU's first is Lignum's, every solve too */
    if (byrows)
      CHECK(on_c.nrefactor == on_c.nlsetup - 1 && on_c.nsolve == on_c.nlsolve,
            "point chain %s %s: all setups but KLU's first are Lignum's (%ld of "
            "%ld), all solves (%ld of %ld)", fmt, nwt, on_c.nrefactor,
            on_c.nlsetup, on_c.nsolve, on_c.nlsolve);
    CHECK(off_c.ncopy == 0 && off_c.nvalue == 0 && off_c.nrefactor == 0 &&
              off_c.nsolve == 0 && off_c.npivot == 0 && off_c.npattern == 0 &&
              off_c.nnocopy == 0,
          "point chain %s %s: off, the copy's counters stay 0", fmt, nwt);
  }
  d = MaxDiff(N_VGetArrayPointer(on.q), N_VGetArrayPointer(off.q), 2 * NMASS);
  LGNGetNumNewtonIters(on.mem, &nni_on);
  LGNGetNumNewtonIters(off.mem, &nni_off);
  CHECK(d <= 1e-12 && nni_on == nni_off,
        "point chain %s %s: on = off: |q_on - q_off| = %.3e, Newton %ld / %ld",
        fmt, nwt, d, nni_on, nni_off);
  if (!byrows && d != 0.0) bitwise_all = 0; /* by rows: round-off */
  LGNGetWorkSpace(on.mem, &rw_on, &iw_on);
  LGNGetWorkSpace(off.mem, &rw_off, &iw_off);
  CHECK(newton == LGN_NEWTON_FULL && !byrows ? (rw_on == rw_off && iw_on == iw_off)
                                              : (rw_on > rw_off && iw_on > iw_off),
        "point chain %s %s: the copy is counted in LGNGetWorkSpace (%ld + %ld "
        "vs %ld + %ld)", fmt, nwt, rw_on, iw_on, rw_off, iw_off);

  /* flipped during the run: on, off (copy freed), on again */
  f1 = LGNSolve(flip.mem, 0.1, &t, flip.q, flip.v, LGN_NORMAL);
  f2 = LGNSetOwnKLUSolves(flip.mem, SUNFALSE);
  CHECK(f2 == LGN_SUCCESS && mflip->klu.copy == NULL && !mflip->klu.valid,
        "point chain %s %s: switched off, the copy is freed", fmt, nwt);
  f2 = LGNSolve(flip.mem, 0.2, &t, flip.q, flip.v, LGN_NORMAL);
  CHECK(mflip->klu.copy == NULL, "point chain %s %s: stays off", fmt, nwt);
  LGNSetOwnKLUSolves(flip.mem, SUNTRUE);
  f3 = LGNSolve(flip.mem, 0.3, &t, flip.q, flip.v, LGN_NORMAL);
  CHECK(f1 == LGN_SUCCESS && f2 == LGN_SUCCESS && f3 == LGN_SUCCESS &&
            (newton == LGN_NEWTON_FULL || (mflip->klu.copy != NULL && mflip->klu.valid)),
        "point chain %s %s: on again, the copy is back after a setup", fmt, nwt);
  d = MaxDiff(N_VGetArrayPointer(on.q), N_VGetArrayPointer(flip.q), 2 * NMASS);
  LGNGetNumNewtonIters(flip.mem, &nni_flip);
  CHECK(d <= 1e-12 && nni_flip == nni_on,
        "point chain %s %s: flipped run = on: |dq| = %.3e, Newton %ld / %ld",
        fmt, nwt, d, nni_flip, nni_on);
  if (!byrows && d != 0.0) bitwise_all = 0; /* by rows: round-off */

  /* a new linear solver drops the copy of the old one's factors */
  LGNSetLinearSolver(on.mem, on.LS, on.A);
  CHECK(mon->klu.copy == NULL && !mon->klu.valid,
        "point chain %s %s: LGNSetLinearSolver frees the copy", fmt, nwt);
  printf("(c) point chain %s, %s Newton: %ld Newton iterations, on = off, "
         "flipped = on; refreshes: %ld whole copies, %ld of values\n", fmt, nwt,
         nni_on, nfull, nvalues);

  PChainFree(&on);
  PChainFree(&off);
  PChainFree(&flip);
}

/* The examples' rigid-body chain (R^3 x SO(3) bodies, spherical joints,
 * analytic tangents) through rigid_run: on = off. */
static void RigidChain(SUNContext ctx, RigidSolver solver, int newton)
{
  RigidSystem *sys = chain_create(25, RB_R3XSO3, ctx);
  RigidRunOptions opt;
  RigidRunResult on, off;
  double d;
  int f1, f2;
  rigid_default_run_options(&opt);
  opt.solver    = solver;
  opt.newton    = newton;
  opt.predictor = LGN_PREDICTOR_EXTRAPOLATE;
  opt.t_end     = 0.05;
  opt.outputs   = 1;
  f1 = rigid_run(sys, &opt, &on);
  opt.klu_solve_sundials = 1;
  f2 = rigid_run(sys, &opt, &off);
  d = (on.q != NULL && off.q != NULL) ? MaxDiff(on.q, off.q, 7 * 25) : 1.0;
  CHECK(f1 == LGN_SUCCESS && f2 == LGN_SUCCESS && d <= 1e-12 && on.nni == off.nni,
        "rigid chain %s, %s Newton: Lignum's = KLU's solves: |dq| = %.3e, "
        "Newton %ld / %ld", rigid_solver_name(solver),
        newton == LGN_NEWTON_FULL ? "full" : "modified", d, on.nni, off.nni);
  if (solver == RB_KLU_CSR && d != 0.0) bitwise_all = 0; /* CSC: by rows */
  rigid_result_free(&on);
  rigid_result_free(&off);
  rigid_free(&sys);
}

/* (d) The versions the copy accepts (lgnKluCopySupported), with fake ones:
 * exactly KLU 1.3 with SUNDIALS 6.4, the KLU installed here. */
static void Versions(void)
{
  static const struct {
    int klu_major, klu_minor, sun_major, sun_minor, ok;
    const char *blame; /* in the reason */
  } cases[] = {
      {1, 3, 6, 4, 1, "supported"},
      {1, 2, 6, 4, 0, "KLU"},   /* older KLU */
      {1, 4, 6, 4, 0, "KLU"},
      {2, 0, 6, 4, 0, "KLU"},   /* SuiteSparse 6: KLU 2.0 */
      {2, 3, 7, 1, 0, "KLU"},   /* both: KLU named first */
      {1, 3, 6, 3, 0, "SUNDIALS"},
      {1, 3, 6, 5, 0, "SUNDIALS"},
      {1, 3, 7, 0, 0, "SUNDIALS"},
      {1, 3, 5, 4, 0, "SUNDIALS"},
      {1, 3, -1, -1, 0, "SUNDIALS"}, /* no version found */
  };
  size_t i;
  const char *why;
  CHECK(LGN_KLU_COPY_KLU_MAJOR == KLU_MAIN_VERSION &&
            LGN_KLU_COPY_KLU_MINOR == KLU_SUB_VERSION,
        "(d) the copy accepts the KLU installed here (%d.%d; accepts %d.%d)",
        KLU_MAIN_VERSION, KLU_SUB_VERSION, LGN_KLU_COPY_KLU_MAJOR,
        LGN_KLU_COPY_KLU_MINOR);
  for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    why = NULL;
    CHECK(lgnKluCopySupported(cases[i].klu_major, cases[i].klu_minor,
                              cases[i].sun_major, cases[i].sun_minor, &why) ==
                  cases[i].ok &&
              why != NULL && strstr(why, cases[i].blame) != NULL,
          "(d) KLU %d.%d with SUNDIALS %d.%d: %s (%s)", cases[i].klu_major,
          cases[i].klu_minor, cases[i].sun_major, cases[i].sun_minor,
          cases[i].ok ? "accepted" : "refused", why != NULL ? why : "no reason");
  }
  CHECK(lgnKluCopySupported(1, 3, 6, 4, NULL) == 1 &&
            lgnKluCopySupported(1, 3, 6, 5, NULL) == 0,
        "(d) why = NULL is allowed");
  printf("(d) versions: KLU %d.%d with SUNDIALS %d.%d accepted, others refused\n",
         LGN_KLU_COPY_KLU_MAJOR, LGN_KLU_COPY_KLU_MINOR, LGN_KLU_COPY_SUN_MAJOR,
         LGN_KLU_COPY_SUN_MINOR);
}

static char last_msg[512];
static void Capture(int code, const char *mod, const char *fn, const char *msg,
                    void *d)
{
  (void)code; (void)mod; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

/* Whether LGNPrintAllStats prints the copy's counters. */
static int StatsShowCopy(void *mem)
{
  FILE *f = tmpfile();
  char line[256];
  int found = 0;
  if (f == NULL) return -1;
  LGNPrintAllStats(mem, f, SUN_OUTPUTFORMAT_TABLE);
  rewind(f);
  while (fgets(line, sizeof line, f) != NULL)
    if (strstr(line, "Own KLU solves") != NULL) found = 1;
  fclose(f);
  return found;
}

/* (e) Through the public API: the copy is off by default (no copy, its
 * counters 0, not in LGNPrintAllStats); switched on it is counted, and
 * the counters restart at LGNReInit (0 until the next setup; after it,
 * with the copy kept, every setup is Lignum's and so is every solve);
 * the getters check their arguments. */
static void DefaultAndCounters(SUNContext ctx)
{
  PChain c;
  LGNMem m;
  Counts k;
  sunrealtype t;
  long int x;
  int flag;

  PChainSetup(&c, ctx, CSC_MAT, LGN_NEWTON_FULL, -1);
  m    = (LGNMem)c.mem;
  flag = LGNSolve(c.mem, 0.05, &t, c.q, c.v, LGN_NORMAL);
  k    = GetCounts(c.mem);
  CHECK(flag == LGN_SUCCESS && !m->klu.own_solves && m->klu.copy == NULL &&
            k.ncopy == 0 && k.nrefactor == 0 && k.nsolve == 0 &&
            k.nlsolve > 0 && StatsShowCopy(c.mem) == 0,
        "(e) default: no copy of KLU's factors (own %d, %ld copies, %ld own "
        "solves of %ld), none in LGNPrintAllStats",
        (int)m->klu.own_solves, k.ncopy, k.nsolve, k.nlsolve);

  CHECK(LGNSetOwnKLUSolves(c.mem, SUNTRUE) == LGN_SUCCESS && m->klu.own_solves,
        "(e) switched on (KLU %d.%d.%d with SUNDIALS %d.%d)", KLU_MAIN_VERSION,
        KLU_SUB_VERSION, KLU_SUBSUB_VERSION, SUNDIALS_VERSION_MAJOR,
        SUNDIALS_VERSION_MINOR);
  flag = LGNSolve(c.mem, 0.1, &t, c.q, c.v, LGN_NORMAL);
  k    = GetCounts(c.mem);
  CHECK(flag == LGN_SUCCESS && k.ncopy == 1 && k.nrefactor > 0 &&
            k.nsolve > 0 && k.nsolve < k.nlsolve && StatsShowCopy(c.mem) == 1,
        "(e) on: %ld copy, %ld refactorisations, %ld of %ld solves, in "
        "LGNPrintAllStats", k.ncopy, k.nrefactor, k.nsolve, k.nlsolve);

  flag = LGNReInit(c.mem, t, c.q, c.v);
  k    = GetCounts(c.mem);
  CHECK(flag == LGN_SUCCESS && k.ncopy == 0 && k.nrefactor == 0 &&
            k.nsolve == 0 && k.nvalue == 0 && k.npivot == 0,
        "(e) LGNReInit restarts the counters (%ld, %ld, %ld)", k.ncopy,
        k.nrefactor, k.nsolve);
  flag = LGNSolve(c.mem, t + 0.05, &t, c.q, c.v, LGN_NORMAL);
  k    = GetCounts(c.mem);
  CHECK(flag == LGN_SUCCESS && m->klu.copy != NULL && k.ncopy == 0 &&
            k.nrefactor == k.nlsetup && k.nsolve == k.nlsolve && k.nlsolve > 0,
        "(e) after LGNReInit the copy is kept: setups %ld of %ld and solves "
        "%ld of %ld Lignum's, %ld copies", k.nrefactor, k.nlsetup, k.nsolve,
        k.nlsolve, k.ncopy);

  /* the getters' arguments: each NULL output is named */
  LGNSetErrHandlerFn(c.mem, Capture, NULL);
  CHECK(LGNGetNumKLUFactorCopies(c.mem, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "ncopies = NULL") != NULL,
        "(e) ncopies = NULL: '%s'", last_msg);
  CHECK(LGNGetNumKLUValueCopies(c.mem, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "nvalues = NULL") != NULL,
        "(e) nvalues = NULL: '%s'", last_msg);
  CHECK(LGNGetNumOwnKLURefactors(c.mem, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "nrefactors = NULL") != NULL,
        "(e) nrefactors = NULL: '%s'", last_msg);
  CHECK(LGNGetNumOwnKLUSolves(c.mem, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "LGNGetNumOwnKLUSolves") != NULL &&
            strstr(last_msg, "nsolves = NULL") != NULL,
        "(e) nsolves = NULL: '%s'", last_msg);
  CHECK(LGNGetNumKLUFallbacks(c.mem, NULL, &x, &x) == LGN_ILL_INPUT &&
            strstr(last_msg, "npivot = NULL") != NULL,
        "(e) npivot = NULL: '%s'", last_msg);
  CHECK(LGNGetNumKLUFallbacks(c.mem, &x, NULL, &x) == LGN_ILL_INPUT &&
            strstr(last_msg, "npattern = NULL") != NULL,
        "(e) npattern = NULL: '%s'", last_msg);
  CHECK(LGNGetNumKLUFallbacks(c.mem, &x, &x, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "nnocopy = NULL") != NULL,
        "(e) nnocopy = NULL: '%s'", last_msg);
  CHECK(LGNGetNumKLUFactorCopies(NULL, &x) == LGN_MEM_NULL &&
            LGNGetNumKLUValueCopies(NULL, &x) == LGN_MEM_NULL &&
            LGNGetNumOwnKLURefactors(NULL, &x) == LGN_MEM_NULL &&
            LGNGetNumOwnKLUSolves(NULL, &x) == LGN_MEM_NULL &&
            LGNGetNumKLUFallbacks(NULL, &x, &x, &x) == LGN_MEM_NULL,
        "(e) the getters refuse a NULL memory block");

  /* off again: the copy is freed, nothing more is counted */
  CHECK(LGNSetOwnKLUSolves(c.mem, SUNFALSE) == LGN_SUCCESS && m->klu.copy == NULL &&
            !m->klu.own_solves && StatsShowCopy(c.mem) == 0,
        "(e) switched off: the copy is freed, not in LGNPrintAllStats");
  PChainFree(&c);
  printf("(e) default off, counters, LGNReInit, arguments: checked\n");
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  Matrices(ctx);
  Repivot(ctx, CSC_MAT);
  Repivot(ctx, CSR_MAT);
  SameLayoutCases(ctx, CSC_MAT);
  SameLayoutCases(ctx, CSR_MAT);
  Switch(ctx, CSC_MAT, LGN_NEWTON_MODIFIED);
  Switch(ctx, CSR_MAT, LGN_NEWTON_MODIFIED);
  Switch(ctx, CSC_MAT, LGN_NEWTON_FULL);
  RigidChain(ctx, RB_KLU_CSC, LGN_NEWTON_MODIFIED);
  RigidChain(ctx, RB_KLU_CSR, LGN_NEWTON_MODIFIED);
  RigidChain(ctx, RB_KLU_CSC, LGN_NEWTON_FULL);
  Versions();
  DefaultAndCounters(ctx);
  CHECK(LGNSetOwnKLUSolves(NULL, SUNTRUE) == LGN_MEM_NULL, "LGNSetOwnKLUSolves(NULL)");
  printf("every comparison with KLU's solve by columns (CSR), solves and "
         "trajectories, %s\n",
         bitwise_all ? "equal to the last bit" : "equal to round-off only");
  SUNContext_Free(&ctx);
  return test_summary("test_klu_solve");
}
