/* -----------------------------------------------------------------------------
 * Helpers shared by the tests of the joint and body helpers: random rigid
 * configurations, dense products, and the comparison of a sparse matrix
 * with a dense one.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_RIGID_TEST_UTIL_H
#define LGN_RIGID_TEST_UTIL_H

#include <math.h>
#include <stdlib.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

static inline double Rand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

/* Random positions and unit quaternions of nb bodies (7 coordinates each). */
static inline void RandomConfiguration(int nb, double *qd)
{
  int k, i;
  for (k = 0; k < nb; k++) {
    double p[4], n = 0;
    for (i = 0; i < 3; i++) qd[7 * k + i] = Rand();
    for (i = 0; i < 4; i++) { p[i] = Rand(); n += p[i] * p[i]; }
    for (i = 0; i < 4; i++) qd[7 * k + 3 + i] = p[i] / sqrt(n);
  }
}

/* y = A x for dense A, or A^T x. */
static inline void DenseApply(SUNMatrix A, const double *x, double *y, int transpose)
{
  sunindextype i, j, M = SM_ROWS_D(A), N = SM_COLUMNS_D(A);
  for (i = 0; i < (transpose ? N : M); i++) y[i] = 0;
  for (j = 0; j < N; j++)
    for (i = 0; i < M; i++) {
      if (transpose) y[j] += SM_ELEMENT_D(A, i, j) * x[i];
      else y[i] += SM_ELEMENT_D(A, i, j) * x[j];
    }
}

/* max |S - D| over all entries, S sparse (a NaN counts as infinite). */
static inline double SparseVsDense(SUNMatrix S, SUNMatrix D)
{
  sunindextype k, p, n;
  const int csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  double err = 0;
  SUNMatrix T = SUNDenseMatrix(SM_ROWS_D(D), SM_COLUMNS_D(D), S->sunctx);
  SUNMatZero(T);
  n = csc ? SUNSparseMatrix_Columns(S) : SUNSparseMatrix_Rows(S);
  for (k = 0; k < n; k++)
    for (p = SUNSparseMatrix_IndexPointers(S)[k]; p < SUNSparseMatrix_IndexPointers(S)[k + 1]; p++) {
      sunindextype o = SUNSparseMatrix_IndexValues(S)[p];
      SM_ELEMENT_D(T, csc ? o : k, csc ? k : o) += SUNSparseMatrix_Data(S)[p];
    }
  for (k = 0; k < SM_ROWS_D(D) * SM_COLUMNS_D(D); k++) {
    const double e = fabs(SM_DATA_D(T)[k] - SM_DATA_D(D)[k]);
    err = fmax(err, isnan(e) ? HUGE_VAL : e);
  }
  SUNMatDestroy(T);
  return err;
}

#endif
