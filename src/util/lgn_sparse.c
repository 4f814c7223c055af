/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Compressed sparse column kernels of the sparse path: views of SUNDIALS
 * sparse matrices (a CSR matrix is read as the CSC matrix of its transpose:
 * transposed when its pattern changes, its values gathered otherwise),
 * transposition, and the greedy column colouring of a symmetric pattern.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_math.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_sparse.h"

void lgnCscFree(LGNCsc *A)
{
  if (A->cap > 0 || A->capcol > 0) {
    free(A->colptr);
    free(A->rowind);
    free(A->val);
  }
  memset(A, 0, sizeof *A);
}

/* Owned storage for at least nnz entries and ncols columns. */
int lgnCscReserve(LGNCsc *A, sunindextype nrows, sunindextype ncols,
                  sunindextype nnz)
{
  if (A->cap == 0 && A->capcol == 0) { /* a view: forget it */
    A->colptr = NULL;
    A->rowind = NULL;
    A->val    = NULL;
  }
  if (ncols + 1 > A->capcol) {
    sunindextype *p = (sunindextype *)realloc(A->colptr, (size_t)(ncols + 1) * sizeof *p);
    if (p == NULL) return LGN_MEM_FAIL;
    A->colptr = p;
    A->capcol = ncols + 1;
  }
  if (nnz > A->cap || A->rowind == NULL) {
    sunindextype cap = SUNMAX(nnz, 1);
    sunindextype *r  = (sunindextype *)realloc(A->rowind, (size_t)cap * sizeof *r);
    sunrealtype *v;
    if (r == NULL) return LGN_MEM_FAIL;
    A->rowind = r;
    v = (sunrealtype *)realloc(A->val, (size_t)cap * sizeof *v);
    if (v == NULL) return LGN_MEM_FAIL;
    A->val = v;
    A->cap = cap;
  }
  A->nrows = nrows;
  A->ncols = ncols;
  return LGN_SUCCESS;
}

static int CompareIndex(const void *a, const void *b)
{
  const sunindextype x = *(const sunindextype *)a, y = *(const sunindextype *)b;
  return (x > y) - (x < y);
}

/* Append the rows collected in cb, sorted, as column cb->col of P (whose
 * colptr[cb->col] is set), growing P's storage as needed. */
int lgnCscAppendColumn(LGNCsc *P, LGNColumnBuilder *cb)
{
  const sunindextype nnz = P->colptr[cb->col];
  if (nnz + cb->cnt > P->cap) {
    int flag = lgnCscReserve(P, P->nrows, P->ncols, 2 * (nnz + cb->cnt));
    if (flag != LGN_SUCCESS) return flag;
  }
  qsort(cb->list, (size_t)cb->cnt, sizeof *cb->list, CompareIndex);
  memcpy(P->rowind + nnz, cb->list, (size_t)cb->cnt * sizeof *cb->list);
  P->colptr[cb->col + 1] = nnz + cb->cnt;
  return LGN_SUCCESS;
}

/* At = A^T, and perm[p] = the position in At of entry p of A (perm may be
 * NULL); row indices come out sorted in every column of At. */
static int Transpose(const LGNCsc *A, LGNCsc *At, sunindextype *perm)
{
  sunindextype i, j, p, nnz = A->colptr[A->ncols];
  int flag = lgnCscReserve(At, A->ncols, A->nrows, nnz);
  if (flag != LGN_SUCCESS) return flag;
  memset(At->colptr, 0, (size_t)(At->ncols + 1) * sizeof(sunindextype));
  for (p = 0; p < nnz; p++) At->colptr[A->rowind[p] + 1]++;
  for (i = 0; i < At->ncols; i++) At->colptr[i + 1] += At->colptr[i];
  for (j = 0; j < A->ncols; j++)
    for (p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
      sunindextype q = At->colptr[A->rowind[p]]++;
      At->rowind[q]  = j;
      At->val[q]     = A->val[p];
      if (perm != NULL) perm[p] = q;
    }
  for (i = At->ncols; i > 0; i--) At->colptr[i] = At->colptr[i - 1];
  At->colptr[0] = 0;
  return LGN_SUCCESS;
}

int lgnCscTranspose(const LGNCsc *A, LGNCsc *At)
{
  return Transpose(A, At, NULL);
}

/* A CSC view of the sparse SUNMatrix S: its own arrays when S is CSC, a
 * transposed copy (owned by view) when S is CSR. */
int lgnCscView(SUNMatrix S, LGNCsc *view)
{
  LGNCsc raw;
  raw.colptr = SUNSparseMatrix_IndexPointers(S);
  raw.rowind = SUNSparseMatrix_IndexValues(S);
  raw.val    = SUNSparseMatrix_Data(S);
  raw.cap = raw.capcol = 0;
  if (SUNSparseMatrix_SparseType(S) == CSC_MAT) {
    if (view->cap > 0 || view->capcol > 0) lgnCscFree(view);
    raw.nrows = SUNSparseMatrix_Rows(S);
    raw.ncols = SUNSparseMatrix_Columns(S);
    *view     = raw;
    return LGN_SUCCESS;
  }
  /* CSR of S = CSC of S^T */
  raw.nrows = SUNSparseMatrix_Columns(S);
  raw.ncols = SUNSparseMatrix_Rows(S);
  return lgnCscTranspose(&raw, view);
}

void lgnPatternMemoFree(LGNPatternMemo *seen)
{
  free(seen->ptr);
  free(seen->ind);
  free(seen->perm);
  memset(seen, 0, sizeof *seen);
}

/* Room in seen for np + 1 pointers and nnz entries (and their permutation
 * when csr). */
static int MemoReserve(LGNPatternMemo *seen, sunindextype np, sunindextype nnz,
                       sunbooleantype csr)
{
  if (np + 1 > seen->capp) {
    sunindextype *p = (sunindextype *)realloc(seen->ptr, (size_t)(np + 1) * sizeof *p);
    if (p == NULL) return LGN_MEM_FAIL;
    seen->ptr  = p;
    seen->capp = np + 1;
  }
  if (nnz > seen->cap || seen->ind == NULL || (csr && seen->perm == NULL)) {
    const sunindextype cap = SUNMAX(SUNMAX(nnz, seen->cap), 1);
    sunindextype *i = (sunindextype *)realloc(seen->ind, (size_t)cap * sizeof *i);
    if (i == NULL) return LGN_MEM_FAIL;
    seen->ind = i;
    if (csr) {
      sunindextype *p = (sunindextype *)realloc(seen->perm, (size_t)cap * sizeof *p);
      if (p == NULL) return LGN_MEM_FAIL;
      seen->perm = p;
    }
    seen->cap = cap;
  }
  return LGN_SUCCESS;
}

/* lgnCscView of a matrix that its callback has just written: *changed says
 * whether its pattern differs from the one seen last (it does at the first
 * call), and the new one is recorded. seen belongs to view: a CSR matrix
 * whose pattern is unchanged keeps the indices of its CSC copy and only
 * gathers the values, through the permutation recorded at the last
 * transposition. */
int lgnCscViewSeen(SUNMatrix S, LGNCsc *view, LGNPatternMemo *seen,
                   sunbooleantype *changed)
{
  const sunbooleantype csr = SUNSparseMatrix_SparseType(S) == CSR_MAT;
  const sunindextype np = SUNSparseMatrix_NP(S);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(S);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(S);
  const sunindextype nnz = ptr[np];
  sunindextype p;
  int flag;

  *changed = !(seen->seen && seen->np == np && seen->nnz == nnz &&
               memcmp(seen->ptr, ptr, (size_t)(np + 1) * sizeof *ptr) == 0 &&
               (nnz == 0 || memcmp(seen->ind, ind, (size_t)nnz * sizeof *ind) == 0));
  if (!*changed && csr) {
    const sunrealtype *val = SUNSparseMatrix_Data(S);
    for (p = 0; p < nnz; p++) view->val[seen->perm[p]] = val[p];
    return LGN_SUCCESS;
  }
  if (!*changed) return lgnCscView(S, view);

  seen->seen = SUNFALSE;
  flag = MemoReserve(seen, np, nnz, csr);
  if (flag == LGN_SUCCESS && csr) {
    LGNCsc raw; /* CSR of S = CSC of S^T */
    raw.nrows  = SUNSparseMatrix_Columns(S);
    raw.ncols  = SUNSparseMatrix_Rows(S);
    raw.colptr = SUNSparseMatrix_IndexPointers(S);
    raw.rowind = SUNSparseMatrix_IndexValues(S);
    raw.val    = SUNSparseMatrix_Data(S);
    raw.cap = raw.capcol = 0;
    flag = Transpose(&raw, view, seen->perm);
  } else if (flag == LGN_SUCCESS) {
    flag = lgnCscView(S, view);
  }
  if (flag != LGN_SUCCESS) return flag;
  memcpy(seen->ptr, ptr, (size_t)(np + 1) * sizeof *ptr);
  if (nnz > 0) memcpy(seen->ind, ind, (size_t)nnz * sizeof *ind);
  seen->np   = np;
  seen->nnz  = nnz;
  seen->seen = SUNTRUE;
  return LGN_SUCCESS;
}

void lgnColoringFree(LGNColoring *c)
{
  free(c->ptr);
  free(c->cols);
  memset(c, 0, sizeof *c);
}

/* Greedy colouring of the columns of a structurally symmetric pattern: two
 * columns get different colours when some row has entries in both, i.e.
 * when they are within distance 2 in the graph of the pattern. */
int lgnColorColumns(const LGNCsc *sym, sunindextype *mark, LGNColoring *c)
{
  const sunindextype n = sym->ncols;
  sunindextype i, j, k, p, q, col, *color;

  lgnColoringFree(c);
  color  = (sunindextype *)malloc((size_t)SUNMAX(n, 1) * sizeof *color);
  c->ptr = (sunindextype *)calloc((size_t)(n + 1), sizeof *c->ptr);
  c->cols = (sunindextype *)malloc((size_t)SUNMAX(n, 1) * sizeof *c->cols);
  if (color == NULL || c->ptr == NULL || c->cols == NULL) {
    free(color);
    lgnColoringFree(c);
    return LGN_MEM_FAIL;
  }
  for (j = 0; j < n; j++) {
    color[j] = -1;
    mark[j]  = -1;
  }
  c->ncolors = 0;
  for (j = 0; j < n; j++) {
    for (p = sym->colptr[j]; p < sym->colptr[j + 1]; p++) {
      i = sym->rowind[p];
      for (q = sym->colptr[i]; q < sym->colptr[i + 1]; q++) {
        k = sym->rowind[q];
        if (color[k] >= 0) mark[color[k]] = j; /* colour taken near j */
      }
    }
    for (col = 0; mark[col] == j; col++) {}
    color[j]   = col;
    c->ncolors = SUNMAX(c->ncolors, col + 1);
  }
  for (j = 0; j < n; j++) c->ptr[color[j] + 1]++;
  for (k = 0; k < c->ncolors; k++) c->ptr[k + 1] += c->ptr[k];
  for (j = 0; j < n; j++) c->cols[c->ptr[color[j]]++] = j;
  for (k = c->ncolors; k > 0; k--) c->ptr[k] = c->ptr[k - 1];
  c->ptr[0] = 0;
  for (j = 0; j < n; j++) mark[j] = -1;
  free(color);
  return LGN_SUCCESS;
}

