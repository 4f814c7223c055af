/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Matrix and vector kernels on SUNDIALS' dense and sparse matrices that
 * SUNDIALS 6.4 lacks (y (+)= A x, y (+)= A^T x, emptying a matrix) and the
 * finiteness test. A pure helper: no integrator record.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_matops.h"

sunbooleantype lgnAllFinite(const sunrealtype *x, sunindextype n)
{
  /* x - x is 0 for a finite x and NaN for an Inf or a NaN, so the sum is 0
   * exactly when all are finite; four partial sums, so that the additions
   * do not wait for each other */
  sunrealtype s[4] = {SUN_RCONST(0.0), SUN_RCONST(0.0), SUN_RCONST(0.0),
                      SUN_RCONST(0.0)};
  sunindextype i;
  for (i = 0; i + 4 <= n; i += 4) {
    s[0] += x[i] - x[i];
    s[1] += x[i + 1] - x[i + 1];
    s[2] += x[i + 2] - x[i + 2];
    s[3] += x[i + 3] - x[i + 3];
  }
  for (; i < n; i++) s[0] += x[i] - x[i];
  return ((s[0] + s[1]) + (s[2] + s[3])) == SUN_RCONST(0.0) ? SUNTRUE : SUNFALSE;
}

/* y (+)= A x and y (+)= A^T x for a dense (column-major) or sparse (CSC or
 * CSR) matrix A. A CSC matrix is read by columns and a CSR matrix by rows,
 * so "A x" of one is "A^T x" of the other with the roles of rows and
 * columns swapped. */
static void SparseCompressedMatvec(const sunindextype *ptr,
                                   const sunindextype *ind,
                                   const sunrealtype *val, sunindextype nptr,
                                   const sunrealtype *x, sunrealtype *y,
                                   sunbooleantype scatter)
{
  sunindextype k, p;
  sunrealtype s;
  for (k = 0; k < nptr; k++) {
    if (scatter) { /* y(ind) += val * x(k) */
      const sunrealtype xk = x[k];
      for (p = ptr[k]; p < ptr[k + 1]; p++) y[ind[p]] += val[p] * xk;
    } else {       /* y(k) += val . x(ind) */
      s = SUN_RCONST(0.0);
      for (p = ptr[k]; p < ptr[k + 1]; p++) s += val[p] * x[ind[p]];
      y[k] += s;
    }
  }
}

/* y (+)= A x and y (+)= A^T x for the column-major M x N array a. restrict:
 * y overlaps neither a nor x, so the compiler needs no run-time overlap
 * test before the short loops (a third of their cost at n = 6). */
static void DenseMatvec(sunindextype M, sunindextype N, const sunrealtype *restrict a,
                        const sunrealtype *restrict x, sunrealtype *restrict y,
                        sunbooleantype add, sunbooleantype transpose)
{
  sunindextype i, j;
  if (!transpose) {
    if (!add)
      for (i = 0; i < M; i++) y[i] = SUN_RCONST(0.0);
    for (j = 0; j < N; j++) {
      const sunrealtype *restrict col = a + j * M, xj = x[j];
      for (i = 0; i < M; i++) y[i] += col[i] * xj;
    }
  } else {
    for (j = 0; j < N; j++) {
      const sunrealtype *restrict col = a + j * M;
      sunrealtype s = add ? y[j] : SUN_RCONST(0.0);
      for (i = 0; i < M; i++) s += col[i] * x[i];
      y[j] = s;
    }
  }
}

static void Matvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
                   sunbooleantype add, sunbooleantype transpose)
{
  sunindextype i, M;
  if (lgnMatIsSparse(A)) {
    const sunbooleantype csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    M = transpose ? SUNSparseMatrix_Columns(A) : SUNSparseMatrix_Rows(A);
    if (!add)
      for (i = 0; i < M; i++) y[i] = SUN_RCONST(0.0);
    SparseCompressedMatvec(SUNSparseMatrix_IndexPointers(A),
                           SUNSparseMatrix_IndexValues(A),
                           SUNSparseMatrix_Data(A),
                           csc ? SUNSparseMatrix_Columns(A) : SUNSparseMatrix_Rows(A),
                           x, y, csc != transpose);
    return;
  }
  DenseMatvec(SM_ROWS_D(A), SM_COLUMNS_D(A), SM_DATA_D(A), x, y, add, transpose);
}

void lgnMatvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
               sunbooleantype add)
{
  Matvec(A, x, y, add, SUNFALSE);
}

void lgnMatTvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
                sunbooleantype add)
{
  Matvec(A, x, y, add, SUNTRUE);
}

/* Empty a model matrix before a callback fills it: a dense one is zeroed
 * (by memset: SUNMatZero costs several times more on small matrices);
 * a sparse one gets no entries (its index pointers zeroed), since the
 * callback writes its whole structure; zeroing all of its capacity, as
 * SUNMatZero does, would cost more than the evaluation. */
void lgnMatClear(SUNMatrix A)
{
  if (lgnMatIsSparse(A)) {
    const sunindextype np = SUNSparseMatrix_NP(A);
    memset(SUNSparseMatrix_IndexPointers(A), 0, (size_t)(np + 1) * sizeof(sunindextype));
  } else {
    /* dense (lgnMatID): the fields directly, without SUNDenseMatrix_Data's
     * second type check through a function call */
    memset(SM_DATA_D(A), 0, (size_t)SM_LDATA_D(A) * sizeof(sunrealtype));
  }
}


sunbooleantype lgnMatIsEmpty(SUNMatrix A)
{
  return lgnMatIsSparse(A) && SUNSparseMatrix_IndexPointers(A)[SUNSparseMatrix_NP(A)] == 0;
}

/* Sort the entries [lo, hi) of a compressed column (or row) by index
 * (insertion sort: a column of the helpers holds a few dozen entries). */
static void SortEntries(sunindextype *ind, sunrealtype *val, sunindextype lo, sunindextype hi)
{
  sunindextype p, r;
  for (p = lo + 1; p < hi; p++) {
    const sunindextype i = ind[p];
    const sunrealtype x  = val[p];
    for (r = p; r > lo && ind[r - 1] > i; r--) {
      ind[r] = ind[r - 1];
      val[r] = val[r - 1];
    }
    ind[r] = i;
    val[r] = x;
  }
}

int lgnSparseAdd(SUNMatrix A, SUNMatrix W)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype ni = SUNSparseMatrix_SparseType(A) == CSC_MAT ? SUNSparseMatrix_Rows(A)
                                                                    : SUNSparseMatrix_Columns(A);
  const sunindextype *ap = SUNSparseMatrix_IndexPointers(A), *ai = SUNSparseMatrix_IndexValues(A);
  const sunindextype *wp = SUNSparseMatrix_IndexPointers(W), *wi = SUNSparseMatrix_IndexValues(W);
  const sunrealtype *wx  = SUNSparseMatrix_Data(W);
  sunindextype *pos, *newp = NULL, *newi = NULL, j, p, extra = 0;
  sunrealtype *newx = NULL;
  /* pos[i]: where entry i of the current column sits in A (-1: absent) */
  pos = (sunindextype *)malloc((size_t)(ni > 0 ? ni : 1) * sizeof *pos);
  if (pos == NULL) return LGN_MEM_FAIL;
  for (j = 0; j < ni; j++) pos[j] = -1;
  for (j = 0; j < np; j++) {
    for (p = ap[j]; p < ap[j + 1]; p++) pos[ai[p]] = p;
    for (p = wp[j]; p < wp[j + 1]; p++)
      if (pos[wi[p]] < 0) {
        pos[wi[p]] = ap[j + 1]; /* counted once: no entry of A is there */
        extra++;
      }
    for (p = ap[j]; p < ap[j + 1]; p++) pos[ai[p]] = -1;
    for (p = wp[j]; p < wp[j + 1]; p++) pos[wi[p]] = -1;
  }
  if (extra == 0) { /* W's pattern within A's: add in place */
    sunrealtype *ax = SUNSparseMatrix_Data(A);
    for (j = 0; j < np; j++) {
      for (p = ap[j]; p < ap[j + 1]; p++) pos[ai[p]] = p;
      for (p = wp[j]; p < wp[j + 1]; p++) ax[pos[wi[p]]] += wx[p];
      for (p = ap[j]; p < ap[j + 1]; p++) pos[ai[p]] = -1;
    }
    free(pos);
    return LGN_SUCCESS;
  }
  {
    const sunindextype nnz = ap[np] + extra;
    const sunrealtype *ax  = SUNSparseMatrix_Data(A);
    sunindextype q = 0;
    newp = (sunindextype *)malloc((size_t)(np + 1) * sizeof *newp);
    newi = (sunindextype *)malloc((size_t)nnz * sizeof *newi);
    newx = (sunrealtype *)malloc((size_t)nnz * sizeof *newx);
    if (newp == NULL || newi == NULL || newx == NULL) {
      free(pos);
      free(newp);
      free(newi);
      free(newx);
      return LGN_MEM_FAIL;
    }
    newp[0] = 0;
    for (j = 0; j < np; j++) {
      const sunindextype first = q;
      for (p = ap[j]; p < ap[j + 1]; p++) {
        newi[q]     = ai[p];
        newx[q]     = ax[p];
        pos[ai[p]]  = q++;
      }
      for (p = wp[j]; p < wp[j + 1]; p++) {
        if (pos[wi[p]] >= first) newx[pos[wi[p]]] += wx[p];
        else {
          newi[q]    = wi[p];
          newx[q]    = wx[p];
          pos[wi[p]] = q++;
        }
      }
      for (p = first; p < q; p++) pos[newi[p]] = -1;
      SortEntries(newi, newx, first, q);
      newp[j + 1] = q;
    }
    free(pos);
    if (SUNSparseMatrix_NNZ(A) < nnz && SUNSparseMatrix_Reallocate(A, nnz) != 0) {
      free(newp);
      free(newi);
      free(newx);
      return LGN_MEM_FAIL;
    }
    memcpy(SUNSparseMatrix_IndexPointers(A), newp, (size_t)(np + 1) * sizeof *newp);
    memcpy(SUNSparseMatrix_IndexValues(A), newi, (size_t)nnz * sizeof *newi);
    memcpy(SUNSparseMatrix_Data(A), newx, (size_t)nnz * sizeof *newx);
    free(newp);
    free(newi);
    free(newx);
  }
  return LGN_SUCCESS;
}

SUNMatrix lgnSparseWorkLike(SUNMatrix *W, SUNMatrix A)
{
  if (*W != NULL && (SUNSparseMatrix_SparseType(*W) != SUNSparseMatrix_SparseType(A) ||
                     SUNSparseMatrix_Rows(*W) != SUNSparseMatrix_Rows(A) ||
                     SUNSparseMatrix_Columns(*W) != SUNSparseMatrix_Columns(A))) {
    SUNMatDestroy(*W);
    *W = NULL;
  }
  if (*W == NULL)
    *W = SUNSparseMatrix(SUNSparseMatrix_Rows(A), SUNSparseMatrix_Columns(A), 1,
                         SUNSparseMatrix_SparseType(A), A->sunctx);
  if (*W != NULL) lgnMatClear(*W);
  return *W;
}
