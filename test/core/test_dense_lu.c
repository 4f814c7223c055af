/* -----------------------------------------------------------------------------
 * Lignum's dense LU solver (LGNLinSol_Dense) against SUNDIALS' SUNLinSol_Dense:
 *  (a) random matrices of several sizes (1 ... 100): the solutions agree to
 *      roundoff (max |x - x_sun| / max |x_sun| <= 100 n eps; the measured
 *      maximum is printed), the factors too, and the residual is small;
 *      x aliasing b gives the same solution;
 *  (b) pivoting: matrices that cannot be factored without row swaps (a zero
 *      and a tiny leading entry, a permutation): exact solutions;
 *  (c) singular matrices (a zero column, a zero pivot after elimination):
 *      SUNLS_LUFACT_FAIL and SUNLinSolLastFlag = 1 + the column of the zero
 *      pivot, as SUNLinSol_Dense's, and a solve then fails;
 *  (d) misuse: a solve before any setup, a matrix of another size, and bad
 *      constructor arguments (NULL, sparse, not square, wrong length): NULL
 *      with a message naming the argument.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "test_util.h"

static SUNContext ctx;

/* A uniform random number in [-1, 1) (a fixed LCG: the same matrices on
 * every machine). */
static double Rand(unsigned long *state)
{
  *state = (*state * 6364136223846793005UL + 1442695040888963407UL) & 0xffffffffffffUL;
  return (double)(*state >> 16) / 2147483648.0 - 1.0;
}

/* Factor copies of A0 with both solvers and solve A x = b; returns
 * max |x - x_sun| / max |x_sun| and sets *factors to the same measure for
 * the LU factors, *resid to max |A0 x - b| / (max |A0| max |x|). */
static double Compare(SUNMatrix A0, N_Vector b, double *factors, double *resid)
{
  const sunindextype n = SM_ROWS_D(A0);
  SUNMatrix A1 = SUNDenseMatrix(n, n, ctx), A2 = SUNDenseMatrix(n, n, ctx);
  N_Vector x1 = N_VClone(b), x2 = N_VClone(b), x3 = N_VClone(b);
  SUNLinearSolver L1 = LGNLinSol_Dense(b, A1, ctx), L2 = SUNLinSol_Dense(b, A2, ctx);
  double dx = 0.0, xmax = 0.0, df = 0.0, fbig = 0.0, r = 0.0, amax = 0.0;
  sunindextype i, j;
  int f1, f2;

  SUNMatCopy(A0, A1);
  SUNMatCopy(A0, A2);
  CHECK(SUNLinSolInitialize(L1) == 0 && SUNLinSolInitialize(L2) == 0, "initialise");
  f1 = SUNLinSolSetup(L1, A1);
  f2 = SUNLinSolSetup(L2, A2);
  CHECK(f1 == SUNLS_SUCCESS && f2 == SUNLS_SUCCESS, "n = %lld: setups %d, %d",
        (long long)n, f1, f2);
  f1 = SUNLinSolSolve(L1, A1, x1, b, 0.0);
  f2 = SUNLinSolSolve(L2, A2, x2, b, 0.0);
  CHECK(f1 == SUNLS_SUCCESS && f2 == SUNLS_SUCCESS, "n = %lld: solves %d, %d",
        (long long)n, f1, f2);
  /* in place: x = b */
  N_VScale(1.0, b, x3);
  CHECK(SUNLinSolSolve(L1, A1, x3, x3, 0.0) == SUNLS_SUCCESS, "solve in place");
  for (i = 0; i < n; i++) {
    const double *p1 = N_VGetArrayPointer(x1), *p2 = N_VGetArrayPointer(x2);
    dx   = fmax(dx, fabs(p1[i] - p2[i]));
    xmax = fmax(xmax, fabs(p2[i]));
    CHECK(N_VGetArrayPointer(x3)[i] == p1[i], "n = %lld: x = b gives the same x", (long long)n);
    for (j = 0; j < n; j++) {
      df   = fmax(df, fabs(SM_ELEMENT_D(A1, i, j) - SM_ELEMENT_D(A2, i, j)));
      fbig = fmax(fbig, fabs(SM_ELEMENT_D(A2, i, j)));
      amax = fmax(amax, fabs(SM_ELEMENT_D(A0, i, j)));
    }
  }
  for (i = 0; i < n; i++) {
    double s = -N_VGetArrayPointer(b)[i];
    for (j = 0; j < n; j++) s += SM_ELEMENT_D(A0, i, j) * N_VGetArrayPointer(x1)[j];
    r = fmax(r, fabs(s));
  }
  *factors = df / fbig;
  *resid   = r / (amax * fmax(xmax, DBL_MIN));
  SUNLinSolFree(L1);
  SUNLinSolFree(L2);
  SUNMatDestroy(A1);
  SUNMatDestroy(A2);
  N_VDestroy(x1);
  N_VDestroy(x2);
  N_VDestroy(x3);
  return dx / xmax;
}

/* (a) */
static void RandomMatrices(void)
{
  static const sunindextype sizes[] = {1, 2, 3, 6, 9, 12, 20, 30, 60, 100};
  unsigned long state = 12345;
  double worst = 0.0, worst_f = 0.0, worst_r = 0.0;
  size_t s;
  int trial;
  for (s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
    const sunindextype n = sizes[s];
    for (trial = 0; trial < 5; trial++) {
      SUNMatrix A = SUNDenseMatrix(n, n, ctx);
      N_Vector b  = N_VNew_Serial(n, ctx);
      double dx, df, r;
      sunindextype i, j;
      for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) SM_ELEMENT_D(A, i, j) = Rand(&state);
      if (trial == 1) /* some exact zeros (the skipped updates) */
        for (j = 0; j < n; j++)
          for (i = 0; i < n; i++)
            if ((i + 2 * j) % 3 == 0 && i != j) SM_ELEMENT_D(A, i, j) = 0.0;
      for (i = 0; i < n; i++) N_VGetArrayPointer(b)[i] = Rand(&state);
      dx = Compare(A, b, &df, &r);
      CHECK(dx <= 100.0 * (double)n * DBL_EPSILON,
            "n = %lld: solutions differ by %.3e (bound 100 n eps = %.3e)",
            (long long)n, dx, 100.0 * (double)n * DBL_EPSILON);
      CHECK(df <= 100.0 * (double)n * DBL_EPSILON, "n = %lld: factors differ by %.3e",
            (long long)n, df);
      CHECK(r <= 100.0 * (double)n * DBL_EPSILON, "n = %lld: residual %.3e",
            (long long)n, r);
      worst   = fmax(worst, dx);
      worst_f = fmax(worst_f, df);
      worst_r = fmax(worst_r, r);
      SUNMatDestroy(A);
      N_VDestroy(b);
    }
  }
  printf("(a) random matrices n = 1 ... 100, 5 each: max relative difference "
         "from SUNLinSol_Dense: solutions %.3e, factors %.3e; max scaled "
         "residual %.3e\n",
         worst, worst_f, worst_r);
}

/* (b) A x = b with the exact solution x = (1, 2, ..., n) for an A that
 * needs row swaps; returns max |x - exact|. */
static double SolveExact(SUNMatrix A)
{
  const sunindextype n = SM_ROWS_D(A);
  SUNMatrix F        = SUNDenseMatrix(n, n, ctx);
  N_Vector b         = N_VNew_Serial(n, ctx), x = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(b, F, ctx);
  double err         = 0.0;
  sunindextype i, j;
  for (i = 0; i < n; i++) {
    double s = 0.0;
    for (j = 0; j < n; j++) s += SM_ELEMENT_D(A, i, j) * (double)(j + 1);
    N_VGetArrayPointer(b)[i] = s;
  }
  SUNMatCopy(A, F);
  CHECK(SUNLinSolSetup(LS, F) == SUNLS_SUCCESS, "pivoting: setup");
  CHECK(SUNLinSolSolve(LS, F, x, b, 0.0) == SUNLS_SUCCESS, "pivoting: solve");
  for (i = 0; i < n; i++) err = fmax(err, fabs(N_VGetArrayPointer(x)[i] - (double)(i + 1)));
  SUNLinSolFree(LS);
  SUNMatDestroy(F);
  N_VDestroy(b);
  N_VDestroy(x);
  return err;
}

static void Pivoting(void)
{
  SUNMatrix A = SUNDenseMatrix(3, 3, ctx), P = SUNDenseMatrix(5, 5, ctx);
  double e1, e2, e3;
  /* a zero leading entry: no LU without a row swap */
  SM_ELEMENT_D(A, 0, 0) = 0.0; SM_ELEMENT_D(A, 0, 1) = 2.0; SM_ELEMENT_D(A, 0, 2) = 1.0;
  SM_ELEMENT_D(A, 1, 0) = 1.0; SM_ELEMENT_D(A, 1, 1) = 1.0; SM_ELEMENT_D(A, 1, 2) = 0.0;
  SM_ELEMENT_D(A, 2, 0) = 2.0; SM_ELEMENT_D(A, 2, 1) = 0.0; SM_ELEMENT_D(A, 2, 2) = 1.0;
  e1 = SolveExact(A);
  /* a tiny leading entry: without pivoting the multiplier 1e20 would wipe
   * out the rest ([[1e-20, 1], [1, 1]] x = b, x = (1, 2)) */
  SUNMatZero(A);
  SM_ELEMENT_D(A, 0, 0) = 1e-20; SM_ELEMENT_D(A, 0, 1) = 1.0;
  SM_ELEMENT_D(A, 1, 0) = 1.0;   SM_ELEMENT_D(A, 1, 1) = 1.0;
  SM_ELEMENT_D(A, 2, 2) = 1.0;
  e2 = SolveExact(A);
  /* a permutation (every step swaps) */
  SM_ELEMENT_D(P, 0, 3) = 1.0; SM_ELEMENT_D(P, 1, 0) = 1.0; SM_ELEMENT_D(P, 2, 4) = 1.0;
  SM_ELEMENT_D(P, 3, 1) = 1.0; SM_ELEMENT_D(P, 4, 2) = 1.0;
  e3 = SolveExact(P);
  printf("(b) pivoting: errors %.3e (zero leading entry), %.3e (1e-20), %.3e (permutation)\n",
         e1, e2, e3);
  CHECK(e1 <= 1e-15 && e2 <= 1e-15 && e3 == 0.0, "pivoted solutions exact: %.3e %.3e %.3e",
        e1, e2, e3);
  SUNMatDestroy(A);
  SUNMatDestroy(P);
}

/* (c) Both solvers on A (n x n): the setup flags and last flags, equal
 * to each other and to SUNLS_LUFACT_FAIL and 1 + col; a solve then fails. */
static void SingularCase(SUNMatrix A, sunindextype col, const char *what)
{
  const sunindextype n = SM_ROWS_D(A);
  SUNMatrix A1 = SUNDenseMatrix(n, n, ctx), A2 = SUNDenseMatrix(n, n, ctx);
  N_Vector b = N_VNew_Serial(n, ctx), x = N_VNew_Serial(n, ctx);
  SUNLinearSolver L1 = LGNLinSol_Dense(b, A1, ctx), L2 = SUNLinSol_Dense(b, A2, ctx);
  int f1, f2;
  sunindextype i, j, same = 1;
  SUNMatCopy(A, A1);
  SUNMatCopy(A, A2);
  f1 = SUNLinSolSetup(L1, A1);
  f2 = SUNLinSolSetup(L2, A2);
  printf("(c) %s: setup %d, last flag %lld (SUNLinSol_Dense: %d, %lld)\n", what, f1,
         (long long)SUNLinSolLastFlag(L1), f2, (long long)SUNLinSolLastFlag(L2));
  CHECK(f1 == SUNLS_LUFACT_FAIL && f2 == SUNLS_LUFACT_FAIL, "%s: SUNLS_LUFACT_FAIL (%d, %d)",
        what, f1, f2);
  CHECK(SUNLinSolLastFlag(L1) == col + 1 && SUNLinSolLastFlag(L2) == col + 1,
        "%s: last flag %lld and %lld, expected %lld", what,
        (long long)SUNLinSolLastFlag(L1), (long long)SUNLinSolLastFlag(L2),
        (long long)(col + 1));
  for (j = 0; j < n; j++) /* the partial factorisation is SUNDIALS' */
    for (i = 0; i < n; i++) same = same && SM_ELEMENT_D(A1, i, j) == SM_ELEMENT_D(A2, i, j);
  CHECK(same, "%s: the matrix after the failed setup is SUNLinSol_Dense's", what);
  N_VConst(7.0, x);
  N_VConst(1.0, b);
  CHECK(SUNLinSolSolve(L1, A1, x, b, 0.0) == SUNLS_ILL_INPUT &&
        N_VGetArrayPointer(x)[0] == 7.0,
        "%s: a solve after the failed setup fails and leaves x alone", what);
  SUNLinSolFree(L1);
  SUNLinSolFree(L2);
  SUNMatDestroy(A1);
  SUNMatDestroy(A2);
  N_VDestroy(b);
  N_VDestroy(x);
}

static void Singular(void)
{
  unsigned long state = 777;
  SUNMatrix A = SUNDenseMatrix(9, 9, ctx), U = SUNDenseMatrix(6, 6, ctx);
  sunindextype i, j;
  for (j = 0; j < 9; j++)
    for (i = 0; i < 9; i++) SM_ELEMENT_D(A, i, j) = j == 4 ? 0.0 : Rand(&state);
  SingularCase(A, 4, "9 x 9 with column 4 zero");
  /* upper triangular but for a swap, U(2,2) = 0: the pivot of column 2
   * is zero after two steps of elimination */
  for (j = 0; j < 6; j++)
    for (i = 0; i <= j; i++) SM_ELEMENT_D(U, i, j) = 1.0 + (double)(i + j);
  SM_ELEMENT_D(U, 2, 2) = 0.0;
  for (j = 0; j < 6; j++) { /* swap rows 0 and 1 */
    const double t = SM_ELEMENT_D(U, 0, j);
    SM_ELEMENT_D(U, 0, j) = SM_ELEMENT_D(U, 1, j);
    SM_ELEMENT_D(U, 1, j) = t;
  }
  SingularCase(U, 2, "6 x 6 with a zero pivot in column 2 after two steps");
  SUNMatDestroy(A);
  SUNMatDestroy(U);
}

/* LGNLinSol_Dense with stderr into a file; the text in captured. */
static char captured[4096];
static SUNLinearSolver CaptureCreate(N_Vector y, SUNMatrix A, SUNContext c)
{
  FILE *tmp = tmpfile();
  int saved;
  size_t len;
  SUNLinearSolver LS;
  fflush(stderr);
  saved = dup(fileno(stderr));
  dup2(fileno(tmp), fileno(stderr));
  LS = LGNLinSol_Dense(y, A, c);
  fflush(stderr);
  dup2(saved, fileno(stderr));
  close(saved);
  rewind(tmp);
  len           = fread(captured, 1, sizeof captured - 1, tmp);
  captured[len] = '\0';
  fclose(tmp);
  return LS;
}

/* (d) */
static void Misuse(void)
{
  SUNMatrix A = SUNDenseMatrix(4, 4, ctx), A3 = SUNDenseMatrix(3, 3, ctx);
  SUNMatrix R = SUNDenseMatrix(4, 3, ctx), S = SUNSparseMatrix(4, 4, 4, CSC_MAT, ctx);
  N_Vector y = N_VNew_Serial(4, ctx), y3 = N_VNew_Serial(3, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  long int lrw = -1, liw = -1;
  struct {
    N_Vector y;
    SUNMatrix A;
    SUNContext c;
    const char *word;
  } bad[] = {{NULL, A, ctx, "y = NULL"},         {y, NULL, ctx, "A = NULL"},
             {y, A, NULL, "sunctx = NULL"},      {y, S, ctx, "SUNDenseMatrix"},
             {y, R, ctx, "square"},              {y3, A, ctx, "length 3"}};
  size_t k;

  CHECK(LS != NULL, "created");
  CHECK(SUNLinSolGetType(LS) == SUNLINEARSOLVER_DIRECT, "a direct solver");
  CHECK(SUNLinSolGetID(LS) == SUNLINEARSOLVER_CUSTOM, "ID custom");
  CHECK(SUNLinSolSpace(LS, &lrw, &liw) == 0 && lrw == 0 && liw == 6, "space %ld %ld", lrw, liw);
  N_VConst(3.0, y);
  CHECK(SUNLinSolSolve(LS, A, y, y, 0.0) == SUNLS_ILL_INPUT &&
            SUNLinSolLastFlag(LS) == SUNLS_ILL_INPUT && N_VGetArrayPointer(y)[1] == 3.0,
        "a solve before any setup fails cleanly");
  CHECK(SUNLinSolSetup(LS, A3) == SUNLS_ILL_INPUT, "setup with a 3 x 3 matrix refused");
  CHECK(SUNLinSolSetup(LS, S) == SUNLS_ILL_INPUT, "setup with a sparse matrix refused");
  CHECK(SUNLinSolSetup(LS, NULL) == SUNLS_MEM_NULL, "setup with A = NULL");
  SM_ELEMENT_D(A, 0, 0) = SM_ELEMENT_D(A, 1, 1) = SM_ELEMENT_D(A, 2, 2) = SM_ELEMENT_D(A, 3, 3) = 2.0;
  CHECK(SUNLinSolSetup(LS, A) == SUNLS_SUCCESS, "setup of 2 I");
  CHECK(SUNLinSolSolve(LS, A, y3, y3, 0.0) == SUNLS_ILL_INPUT, "solve with a vector of length 3");
  CHECK(SUNLinSolSolve(LS, A, y, y, 0.0) == SUNLS_SUCCESS && N_VGetArrayPointer(y)[2] == 1.5,
        "solve after the setup");
  for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    SUNLinearSolver L = CaptureCreate(bad[k].y, bad[k].A, bad[k].c);
    CHECK(L == NULL, "bad argument %s: NULL", bad[k].word);
    CHECK(strstr(captured, bad[k].word) != NULL && strstr(captured, "LGNLinSol_Dense") != NULL,
          "bad argument %s: the message names it: %s", bad[k].word, captured);
    if (L != NULL) SUNLinSolFree(L);
  }
  printf("(d) misuse refused; the last message:\n%s", captured);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  SUNMatDestroy(A3);
  SUNMatDestroy(R);
  SUNMatDestroy(S);
  N_VDestroy(y);
  N_VDestroy(y3);
}

int main(void)
{
  SUNContext_Create(NULL, &ctx);
  RandomMatrices();
  Pivoting();
  Singular();
  Misuse();
  SUNContext_Free(&ctx);
  return test_summary("test_dense_lu");
}
