/* -----------------------------------------------------------------------------
 * Lignum benchmark: dense LU solvers for small matrices (issue 22, item 2).
 *
 *   dense_lu [--csv file] [--reps k] [--callgrind lgn|sun|lapack]
 *
 * 1. Setup (factorisation) + one solve of a random n x n system, n = 6, 9,
 *    12, 20, 30, 60, 100, per call, with
 *      lgn     LGNLinSol_Dense (Lignum's, compiled with Lignum's flags),
 *      sun     SUNLinSol_Dense (Debian's SUNDIALS, compiled at -O0),
 *      lapack  dgetrf + dgetrs of the system's LAPACK (Debian: reference
 *              LAPACK), called directly: SUNLinSol_LapackDense itself is
 *              not shipped by Debian's libsundials-dev 6.4.1.
 *    Each call refills the matrix (the factorisation overwrites it); the
 *    refill, timed alone, is subtracted. Wall time, best of k repetitions
 *    (default 7) of a loop of about 20 ms.
 * 2. The heavy top (models/heavy_top.c: R^3 x SO(3), generalized-
 *    alpha rho = 0.9, index 3, h = 1e-3, 1000 steps, 9 x 9 iteration
 *    matrix), CPU time per step with full and modified Newton, with
 *    SUNLinSol_Dense and with LGNLinSol_Dense, best of k runs.
 * The table goes to stdout and, with the ratios, to the CSV (default
 * dense_lu.csv): columns kind,n,solver,seconds_per_call,ratio_to_lgn.
 *
 * --callgrind S runs 1000 setup+solve calls of S at n = 9 in the function
 * OneCall only (for valgrind --tool=callgrind --toggle-collect=OneCall;
 * instructions per call = Ir / 1000).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "models/heavy_top.h"

/* LAPACK (Fortran interface, 32-bit integers as Debian's reference LAPACK) */
extern void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv,
                    int *info);
extern void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a,
                    const int *lda, const int *ipiv, double *b, const int *ldb, int *info);

enum { S_LGN = 0, S_SUN = 1, S_LAPACK = 2, NSOLVERS = 3 };
static const char *solver_name[NSOLVERS] = {"LGNLinSol_Dense", "SUNLinSol_Dense",
                                            "LAPACK dgetrf+dgetrs"};

static double Now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One n x n problem and a solver of kind s for it. */
typedef struct {
  sunindextype n;
  int s;
  SUNMatrix A;
  N_Vector b, x;
  SUNLinearSolver LS;
  double *A0;
  int *ipiv;
} Problem;

static void ProblemInit(Problem *p, sunindextype n, int s, SUNContext ctx)
{
  unsigned long state = 4242UL + (unsigned long)n;
  sunindextype i;
  p->n    = n;
  p->s    = s;
  p->A    = SUNDenseMatrix(n, n, ctx);
  p->b    = N_VNew_Serial(n, ctx);
  p->x    = N_VNew_Serial(n, ctx);
  p->A0   = (double *)malloc((size_t)(n * n) * sizeof(double));
  p->ipiv = (int *)malloc((size_t)n * sizeof(int));
  for (i = 0; i < n * n; i++) { /* uniform in [-1, 1), a fixed LCG */
    state    = (state * 6364136223846793005UL + 1442695040888963407UL) & 0xffffffffffffUL;
    p->A0[i] = (double)(state >> 16) / 2147483648.0 - 1.0;
  }
  N_VConst(1.0, p->b);
  p->LS = s == S_LGN ? LGNLinSol_Dense(p->b, p->A, ctx)
        : s == S_SUN ? SUNLinSol_Dense(p->b, p->A, ctx)
                     : NULL;
  if (p->LS != NULL) SUNLinSolInitialize(p->LS);
}

static void ProblemFree(Problem *p)
{
  if (p->LS != NULL) SUNLinSolFree(p->LS);
  SUNMatDestroy(p->A);
  N_VDestroy(p->b);
  N_VDestroy(p->x);
  free(p->A0);
  free(p->ipiv);
}

/* Refill A, factor, solve once; returns nonzero on a failure. */
static int SetupSolve(Problem *p)
{
  const int n = (int)p->n, one = 1;
  int info = 0;
  memcpy(SM_DATA_D(p->A), p->A0, (size_t)(n * n) * sizeof(double));
  if (p->s == S_LAPACK) {
    memcpy(N_VGetArrayPointer(p->x), N_VGetArrayPointer(p->b), (size_t)n * sizeof(double));
    dgetrf_(&n, &n, SM_DATA_D(p->A), &n, p->ipiv, &info);
    if (info == 0)
      dgetrs_("N", &n, &one, SM_DATA_D(p->A), &n, p->ipiv, N_VGetArrayPointer(p->x), &n,
              &info);
    return info;
  }
  if (SUNLinSolSetup(p->LS, p->A) != 0) return 1;
  return SUNLinSolSolve(p->LS, p->A, p->x, p->b, 0.0);
}

/* The refill alone (subtracted from the times). */
static int RefillOnly(Problem *p)
{
  memcpy(SM_DATA_D(p->A), p->A0, (size_t)(p->n * p->n) * sizeof(double));
  return SM_DATA_D(p->A)[0] == 12345.0;
}

/* Seconds per call of f, best of reps loops of about 20 ms. */
static double TimePerCall(int (*f)(Problem *), Problem *p, int reps)
{
  long int calls = 1, k;
  double best = HUGE_VAL, t;
  int r, bad = 0;
  for (;;) { /* calibrate */
    t = Now();
    for (k = 0; k < calls; k++) bad |= f(p);
    t = Now() - t;
    if (t > 0.02 || calls > (1L << 28)) break;
    calls *= 2;
  }
  for (r = 0; r < reps; r++) {
    t = Now();
    for (k = 0; k < calls; k++) bad |= f(p);
    t = (Now() - t) / (double)calls;
    if (t < best) best = t;
  }
  if (bad) fprintf(stderr, "dense_lu: a setup or solve failed (n = %lld)\n", (long long)p->n);
  return best;
}

/* Instructions of 1000 calls at n = 9, for callgrind (noinline: the
 * function --toggle-collect names). */
__attribute__((noinline)) static int OneCall(Problem *p)
{
  int k, bad = 0;
  for (k = 0; k < 1000; k++) bad |= SetupSolve(p);
  return bad;
}

/* Heavy top, CPU seconds per step, best of reps runs. */
static double HeavyTopPerStep(int newton, int lgn, int reps, long int *nsteps)
{
  HeavyTopOptions opt;
  HeavyTopResult res;
  double best = HUGE_VAL;
  int r;
  heavy_top_default_options(&opt);
  opt.newton       = newton;
  opt.single_solve = 1;
  opt.make_ls      = lgn ? LGNLinSol_Dense : NULL;
  for (r = 0; r < reps; r++) {
    if (heavy_top_run(&opt, &res) != LGN_SUCCESS || res.nsteps <= 0) {
      fprintf(stderr, "dense_lu: heavy top failed (%s)\n", LGNGetReturnFlagName(res.flag));
      return NAN;
    }
    *nsteps = res.nsteps;
    if (res.cpu_seconds / (double)res.nsteps < best) best = res.cpu_seconds / (double)res.nsteps;
  }
  return best;
}

int main(int argc, char **argv)
{
  static const sunindextype sizes[] = {6, 9, 12, 20, 30, 60, 100};
  const int nsizes = (int)(sizeof sizes / sizeof sizes[0]);
  const char *csv_name = "dense_lu.csv";
  const char *cg = NULL;
  int reps = 7, i, s;
  SUNContext ctx;
  FILE *csv;

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv_name = argv[++i];
    else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
    else if (strcmp(argv[i], "--callgrind") == 0 && i + 1 < argc) cg = argv[++i];
    else {
      fprintf(stderr, "usage: %s [--csv file] [--reps k] [--callgrind lgn|sun|lapack]\n",
              argv[0]);
      return 2;
    }
  }
  if (reps < 1) reps = 1;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;

  if (cg != NULL) {
    Problem p;
    const int kind = strcmp(cg, "lgn") == 0 ? S_LGN : strcmp(cg, "sun") == 0 ? S_SUN : S_LAPACK;
    int bad;
    ProblemInit(&p, 9, kind, ctx);
    bad = SetupSolve(&p) | OneCall(&p);
    printf("callgrind: 1000 setup+solve calls of %s at n = 9 in OneCall\n", solver_name[kind]);
    ProblemFree(&p);
    SUNContext_Free(&ctx);
    return bad != 0;
  }

  csv = fopen(csv_name, "w");
  if (csv == NULL) {
    fprintf(stderr, "dense_lu: cannot write %s\n", csv_name);
    return 1;
  }
  fprintf(csv, "kind,n,solver,seconds_per_call,ratio_to_lgn\n");
  printf("Setup + solve per call (wall, best of %d; the matrix refill subtracted), us\n", reps);
  printf("%5s %16s %16s %22s %10s %10s\n", "n", solver_name[0], solver_name[1], solver_name[2],
         "SUN/LGN", "LAPACK/LGN");
  for (i = 0; i < nsizes; i++) {
    double t[NSOLVERS], refill;
    Problem p;
    ProblemInit(&p, sizes[i], S_LAPACK, ctx);
    refill = TimePerCall(RefillOnly, &p, reps);
    ProblemFree(&p);
    for (s = 0; s < NSOLVERS; s++) {
      ProblemInit(&p, sizes[i], s, ctx);
      t[s] = TimePerCall(SetupSolve, &p, reps) - refill;
      ProblemFree(&p);
    }
    printf("%5lld %16.3f %16.3f %22.3f %10.2f %10.2f\n", (long long)sizes[i], 1e6 * t[0],
           1e6 * t[1], 1e6 * t[2], t[1] / t[0], t[2] / t[0]);
    for (s = 0; s < NSOLVERS; s++)
      fprintf(csv, "setup+solve,%lld,%s,%.6e,%.4f\n", (long long)sizes[i], solver_name[s], t[s],
              t[s] / t[0]);
  }

  printf("\nHeavy top (R^3 x SO(3), gen.-alpha 0.9, index 3, h = 1e-3, t = 1; 9 x 9), "
         "CPU us per step, best of %d\n",
         reps);
  printf("%16s %16s %16s %10s\n", "Newton", solver_name[0], solver_name[1], "SUN/LGN");
  for (s = 0; s < 2; s++) {
    const int newton = s == 0 ? LGN_NEWTON_FULL : LGN_NEWTON_MODIFIED;
    long int nsteps = 0;
    const double tl = HeavyTopPerStep(newton, 1, reps, &nsteps);
    const double ts = HeavyTopPerStep(newton, 0, reps, &nsteps);
    printf("%16s %16.3f %16.3f %10.2f\n", s == 0 ? "full" : "modified", 1e6 * tl, 1e6 * ts,
           ts / tl);
    fprintf(csv, "heavy_top_%s_newton,9,%s,%.6e,1.0000\n", s == 0 ? "full" : "modified",
            solver_name[0], tl);
    fprintf(csv, "heavy_top_%s_newton,9,%s,%.6e,%.4f\n", s == 0 ? "full" : "modified",
            solver_name[1], ts, ts / tl);
  }
  fclose(csv);
  printf("\nCSV: %s\n", csv_name);
  SUNContext_Free(&ctx);
  return 0;
}
