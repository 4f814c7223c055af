/* -----------------------------------------------------------------------------
 * Lignum unit test: the independent rows of a rank-deficient B
 * (lgnRankRevealingRows, lgn_redundancy.c): LAPACK's dgeqp3 for a dense B,
 * SuiteSparseQR for a sparse one (CSC and CSR).
 *
 * B = U V (m x r times r x nv, random, r < m) has rank r. Checked: the rank
 * found is r for each storage; the rows returned first are r rows of rank r
 * (their own factorisation finds them all independent) and ascending, the
 * rest ascending; with a block of duplicated rows (a joint added twice)
 * exactly one of each pair is left out; a floor above the smallest R_kk
 * lowers the rank (the floor of a q0 off the constraints).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"
#include "test_util.h"

static double Rand(unsigned *s)
{
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffff) / 65536.0 - 0.5;
}

/* rows[0 .. r-1] of D (m x nv) as a dense matrix */
static SUNMatrix KeptRows(SUNMatrix D, const sunindextype *rows, sunindextype r,
                          SUNContext ctx)
{
  const sunindextype nv = SM_COLUMNS_D(D);
  SUNMatrix K = SUNDenseMatrix(r, nv, ctx);
  sunindextype i, j;
  for (i = 0; i < r; i++)
    for (j = 0; j < nv; j++) SM_ELEMENT_D(K, i, j) = SM_ELEMENT_D(D, rows[i], j);
  return K;
}

static int Ascending(const sunindextype *x, sunindextype n)
{
  sunindextype i;
  for (i = 1; i < n; i++)
    if (x[i] <= x[i - 1]) return 0;
  return 1;
}

static void Case(sunindextype m, sunindextype nv, sunindextype r, SUNContext ctx)
{
  SUNMatrix D = SUNDenseMatrix(m, nv, ctx), S[2];
  sunindextype rows[64], rows2[64], rank = -1, rank2 = -1, i, j, k;
  double U[64][8], V[8][64];
  unsigned seed = 7u + (unsigned)(m + nv + r);
  int s;
  for (i = 0; i < m; i++)
    for (k = 0; k < r; k++) U[i][k] = Rand(&seed);
  for (k = 0; k < r; k++)
    for (j = 0; j < nv; j++) V[k][j] = (j % 3 == k % 3) ? Rand(&seed) : 0.0; /* sparse-ish */
  for (i = 0; i < m; i++)
    for (j = 0; j < nv; j++) {
      double x = 0.0;
      for (k = 0; k < r; k++) x += U[i][k] * V[k][j];
      SM_ELEMENT_D(D, i, j) = x;
    }
  CHECK(lgnRankRevealingRows(D, m, nv, 0.0, &rank, rows) == 0 && rank == r,
        "dense %lld x %lld of rank %lld: found %lld", (long long)m, (long long)nv, (long long)r,
        (long long)rank);
  if (rank == r) {
    SUNMatrix K = KeptRows(D, rows, r, ctx);
    CHECK(lgnRankRevealingRows(K, r, nv, 0.0, &rank2, rows2) == 0 && rank2 == r,
          "the kept rows are independent (%lld)", (long long)rank2);
    CHECK(Ascending(rows, r) && Ascending(rows + r, m - r), "ascending");
    SUNMatDestroy(K);
  }
  S[0] = SUNSparseFromDenseMatrix(D, 1e-300, CSC_MAT);
  S[1] = SUNSparseFromDenseMatrix(D, 1e-300, CSR_MAT);
  for (s = 0; s < 2; s++) {
    rank = -1;
    CHECK(lgnRankRevealingRows(S[s], m, nv, 0.0, &rank, rows) == 0 && rank == r,
          "sparse (%s) of rank %lld: found %lld", s ? "CSR" : "CSC", (long long)r,
          (long long)rank);
    if (rank == r) {
      SUNMatrix K = KeptRows(D, rows, r, ctx);
      CHECK(lgnRankRevealingRows(K, r, nv, 0.0, &rank2, rows2) == 0 && rank2 == r,
            "sparse (%s): the kept rows are independent (%lld)", s ? "CSR" : "CSC",
            (long long)rank2);
      CHECK(Ascending(rows, r) && Ascending(rows + r, m - r), "ascending");
      SUNMatDestroy(K);
    }
    SUNMatDestroy(S[s]);
  }
  /* a floor above every R_kk: nothing is independent */
  CHECK(lgnRankRevealingRows(D, m, nv, 1e6, &rank, rows) == 0 && rank == 0,
        "a floor of 1e6 gives rank 0 (%lld)", (long long)rank);
  SUNMatDestroy(D);
}

/* three rows, each twice (rows i and i + 3): one of each pair is left out */
static void Pairs(SUNContext ctx, int sparse)
{
  SUNMatrix D = SUNDenseMatrix(6, 6, ctx), B;
  sunindextype rows[6], rank = -1, i;
  int ok = 1;
  SUNMatZero(D);
  for (i = 0; i < 3; i++) {
    SM_ELEMENT_D(D, i, i) = SM_ELEMENT_D(D, i + 3, i) = 1.0;
    SM_ELEMENT_D(D, i, i + 3) = SM_ELEMENT_D(D, i + 3, i + 3) = 0.5 * (double)(i + 1);
  }
  B = sparse ? SUNSparseFromDenseMatrix(D, 1e-300, CSC_MAT) : D;
  CHECK(lgnRankRevealingRows(B, 6, 6, 0.0, &rank, rows) == 0 && rank == 3,
        "pairs (%s): rank 3 (%lld)", sparse ? "sparse" : "dense", (long long)rank);
  for (i = 0; i < 3 && rank == 3; i++) {
    int count = 0, k;
    for (k = 3; k < 6; k++) count += rows[k] == i || rows[k] == i + 3;
    ok = ok && count == 1;
  }
  CHECK(ok, "one of each pair left out");
  if (sparse) SUNMatDestroy(B);
  SUNMatDestroy(D);
}

int main(void)
{
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  Case(20, 30, 5, ctx);
  Case(40, 60, 8, ctx);
  Case(12, 10, 7, ctx); /* more rows than columns */
  Pairs(ctx, 0);
  Pairs(ctx, 1);
  SUNContext_Free(&ctx);
  return test_summary("test_rank_rows");
}
