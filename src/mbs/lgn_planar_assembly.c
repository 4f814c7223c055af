/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Matrix assembly of the planar sets (lgn_planar.h): a generator emits the
 * entries of a matrix in a fixed order; a dense matrix gets them added or
 * set, a sparse one (CSC or CSR) is written with the pattern collected
 * from the first evaluation in that format (duplicates summed): an empty
 * one (or any, for set) directly, one that holds entries through a work
 * matrix added to it (lgnSparseAdd), as the spatial sets do.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_matops.h"
#include "lgn_planar.h"

void lgnPlanarEmit(lgnPlanarSink *s, sunindextype r, sunindextype c, sunrealtype v)
{
  switch (s->mode) {
  case LGN_PA_DENSE_ADD: SM_ELEMENT_D(s->A, r, c) += v; break;
  case LGN_PA_DENSE_SET: SM_ELEMENT_D(s->A, r, c) = v; break;
  case LGN_PA_SPARSE:    s->data[s->pat->pos[s->k++]] += v; break;
  case LGN_PA_COLLECT:
    if (s->k == s->cap) {
      const sunindextype cap = 2 * s->cap + 64;
      sunindextype *row = (sunindextype *)realloc(s->row, (size_t)cap * sizeof *row);
      sunindextype *col;
      if (row == NULL) { s->memfail = 1; return; }
      s->row = row;
      col = (sunindextype *)realloc(s->col, (size_t)cap * sizeof *col);
      if (col == NULL) { s->memfail = 1; return; }
      s->col = col;
      s->cap = cap;
    }
    s->row[s->k] = r;
    s->col[s->k] = c;
    s->k++;
    break;
  }
}

void lgnPlanarPatternFree(lgnPlanarPattern *pat)
{
  if (pat->work != NULL) SUNMatDestroy(pat->work);
  free(pat->ptr);
  free(pat->ind);
  free(pat->pos);
  memset(pat, 0, sizeof *pat);
  pat->fmt = -1;
}

typedef struct {
  sunindextype major, minor, k;
} Key;

static int CompareKey(const void *x, const void *y)
{
  const Key *a = (const Key *)x, *b = (const Key *)y;
  if (a->major != b->major) return a->major < b->major ? -1 : 1;
  if (a->minor != b->minor) return a->minor < b->minor ? -1 : 1;
  return 0;
}

/* Collect the entries of gen and build the pattern in format fmt with
 * nmajor columns (CSC) or rows (CSR). */
static int BuildPattern(lgnPlanarPattern *pat, int fmt, sunindextype nmajor,
                        lgnPlanarGenFn gen, void *ctx)
{
  lgnPlanarSink s;
  Key *key = NULL;
  sunindextype i, n;
  int ret;
  lgnPlanarPatternFree(pat);
  memset(&s, 0, sizeof s);
  s.mode = LGN_PA_COLLECT;
  ret = gen(ctx, &s);
  if (s.memfail) ret = LGN_MEM_FAIL;
  n = s.k;
  if (ret == LGN_SUCCESS) {
    key      = (Key *)malloc((size_t)(n > 0 ? n : 1) * sizeof *key);
    pat->pos = (sunindextype *)malloc((size_t)(n > 0 ? n : 1) * sizeof *pat->pos);
    pat->ptr = (sunindextype *)calloc((size_t)nmajor + 1, sizeof *pat->ptr);
    pat->ind = (sunindextype *)malloc((size_t)(n > 0 ? n : 1) * sizeof *pat->ind);
    if (key == NULL || pat->pos == NULL || pat->ptr == NULL || pat->ind == NULL)
      ret = LGN_MEM_FAIL;
  }
  if (ret == LGN_SUCCESS) {
    for (i = 0; i < n; i++) {
      key[i].major = fmt == CSC_MAT ? s.col[i] : s.row[i];
      key[i].minor = fmt == CSC_MAT ? s.row[i] : s.col[i];
      key[i].k     = i;
    }
    qsort(key, (size_t)n, sizeof *key, CompareKey);
    pat->nnz = 0;
    for (i = 0; i < n; i++) {
      if (i == 0 || CompareKey(key + i, key + i - 1) != 0) {
        pat->ind[pat->nnz] = key[i].minor;
        pat->ptr[key[i].major + 1]++;
        pat->nnz++;
      }
      pat->pos[key[i].k] = pat->nnz - 1;
    }
    for (i = 0; i < nmajor; i++) pat->ptr[i + 1] += pat->ptr[i];
    pat->nent   = n;
    pat->nmajor = nmajor;
    pat->fmt    = fmt;
  }
  free(key);
  free(s.row);
  free(s.col);
  if (ret != LGN_SUCCESS) lgnPlanarPatternFree(pat);
  return ret;
}

sunindextype lgnPlanarCount(lgnPlanarPattern *pat, sunindextype ncols,
                            lgnPlanarGenFn gen, void *ctx)
{
  if (pat->fmt == -1 && BuildPattern(pat, CSC_MAT, ncols, gen, ctx) != LGN_SUCCESS)
    return -1;
  return pat->nnz;
}

int lgnPlanarWrite(lgnPlanarPattern *pat, SUNMatrix A, sunbooleantype set,
                   lgnPlanarGenFn gen, void *ctx, const LGNErrSink *err,
                   const char *func)
{
  lgnPlanarSink s;
  memset(&s, 0, sizeof s);
  s.A = A;
  if (!lgnMatIsSparse(A)) {
    s.mode = set ? LGN_PA_DENSE_SET : LGN_PA_DENSE_ADD;
    return gen(ctx, &s);
  }
  if (!set && !lgnMatIsEmpty(A)) { /* A += the term, through pat->work */
    SUNMatrix W = lgnSparseWorkLike(&pat->work, A);
    int ret;
    if (W == NULL) {
      lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
      return LGN_MEM_FAIL;
    }
    pat->work = NULL; /* held here: a new pattern frees pat's arrays */
    ret = lgnPlanarWrite(pat, W, SUNTRUE, gen, ctx, err, func);
    if (ret == LGN_SUCCESS && lgnSparseAdd(A, W) != LGN_SUCCESS) {
      lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
      ret = LGN_MEM_FAIL;
    }
    pat->work = W;
    return ret;
  }
  {
    const int fmt = SUNSparseMatrix_SparseType(A);
    const sunindextype nmajor =
        fmt == CSC_MAT ? SUNSparseMatrix_Columns(A) : SUNSparseMatrix_Rows(A);
    sunindextype i;
    int ret;
    if (pat->fmt != fmt || pat->nmajor != nmajor) {
      ret = BuildPattern(pat, fmt, nmajor, gen, ctx);
      if (ret == LGN_MEM_FAIL) lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
      if (ret != LGN_SUCCESS) return ret;
    }
    if (SUNSparseMatrix_NNZ(A) < pat->nnz && SUNSparseMatrix_Reallocate(A, pat->nnz) != 0) {
      lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
      return LGN_MEM_FAIL;
    }
    memcpy(SUNSparseMatrix_IndexPointers(A), pat->ptr, (size_t)(nmajor + 1) * sizeof *pat->ptr);
    memcpy(SUNSparseMatrix_IndexValues(A), pat->ind, (size_t)pat->nnz * sizeof *pat->ind);
    s.data = SUNSparseMatrix_Data(A);
    for (i = 0; i < pat->nnz; i++) s.data[i] = 0;
    s.mode = LGN_PA_SPARSE;
    s.pat  = pat;
    return gen(ctx, &s);
  }
}

int lgnPlanarCheckMat(SUNMatrix A, sunindextype rows, sunindextype cols,
                      const char *name, const LGNErrSink *err, const char *func)
{
  if (A == NULL ||
      (lgnMatID(A) == SUNMATRIX_DENSE && (SM_ROWS_D(A) != rows || SM_COLUMNS_D(A) != cols)) ||
      (lgnMatIsSparse(A) &&
       (SUNSparseMatrix_Rows(A) != rows || SUNSparseMatrix_Columns(A) != cols)) ||
      (lgnMatID(A) != SUNMATRIX_DENSE && lgnMatID(A) != SUNMATRIX_SPARSE)) {
    lgnReport(err, LGN_ILL_INPUT, func, "%s must be a dense or sparse %lld x %lld matrix.",
              name, (long long)rows, (long long)cols);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}
