/* -----------------------------------------------------------------------------
 * Lignum test: the direct solve through PETSc and MUMPS (LGNLinSol_PETSc).
 * Run on 1 rank, and under mpiexec on 2 and 4 (CTest petsc_ls_np*): every
 * check is made on every rank, and the failures are summed over the ranks.
 *
 *  (a) random sparse systems (diagonally dominant, and saddle-point ones
 *      with a zero block), CSR and CSC: the solution agrees with Lignum's
 *      dense LU (and KLU when built) to a relative 1e-12, and is the same
 *      to the last bit on every rank; a new pattern, the same pattern with
 *      new values; a singular matrix gives SUNLS_LUFACT_FAIL with a column,
 *      and the same pattern with regular values works again afterwards;
 *      misuse (solve before setup, wrong arguments);
 *  (b) the symbolic analysis is reused: PETSc's own event counts
 *      (MatLUFactorSym, MatLUFactorNum) over several setups of one pattern
 *      and after a new pattern, with PETSc initialised by the test (which
 *      Lignum then does not finalise);
 *  (c) the chain of 8 bodies, index 3 and 2, full and modified Newton:
 *      the trajectory with LGNLinSol_PETSc (CSR; CSC once) equals the one
 *      with KLU (or LGNLinSol_Dense without KLU) to a relative 1e-10, and is
 *      the same on every rank; to t = 0.1 on one rank, to 0.02 on more
 *      (each MUMPS solve there waits on the other ranks: on a loaded 2-core
 *      machine 2 ranks took 30 times as long as one, 4 ranks 70 times);
 *  (d) a redundant constraint (a joint added twice): LGN_IC_FAIL or
 *      LGN_LSETUP_FAIL, three redundant constraints found by Lignum's
 *      diagnostics, and the zero pivot named at a multiplier.
 * PETSc is initialised by Lignum in (a), (c), (d) and finalised by the free
 * of the last solver (checked with PetscInitialized).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>
#include <petscksp.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_petsc.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

static int rank = 0, nranks = 1;
static int failures = 0, checks = 0;

#define CHECK(cond, ...)                                                \
  do {                                                                  \
    checks++;                                                           \
    if (!(cond)) {                                                      \
      failures++;                                                       \
      printf("[rank %d] FAIL %s:%d: ", rank, __FILE__, __LINE__);       \
      printf(__VA_ARGS__);                                              \
      printf("\n");                                                     \
    }                                                                   \
  } while (0)

/* max over the ranks of |x - x on rank 0| (0: the same everywhere) */
static double RankSpread(const double *x, sunindextype n)
{
  double *x0 = (double *)malloc((size_t)n * sizeof *x0), d = 0.0, dmax = 0.0;
  sunindextype i;
  memcpy(x0, x, (size_t)n * sizeof *x0);
  MPI_Bcast(x0, (int)n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (i = 0; i < n; i++) d = fmax(d, fabs(x[i] - x0[i]));
  MPI_Allreduce(&d, &dmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  free(x0);
  return dmax;
}

static double RelDiff(const double *x, const double *y, sunindextype n)
{
  double d = 0.0, s = 0.0;
  sunindextype i;
  for (i = 0; i < n; i++) {
    d = fmax(d, fabs(x[i] - y[i]));
    s = fmax(s, fabs(y[i]));
  }
  return s > 0.0 ? d / s : d;
}

static PetscBool PetscIsUp(void)
{
  PetscBool up = PETSC_FALSE;
  PetscInitialized(&up);
  return up;
}

/* =============================================================================
 * (a) random sparse systems
 * ===========================================================================*/

static unsigned long seed = 12345UL;
static double Rand(void) /* in [-1, 1), the same sequence on every rank */
{
  seed = seed * 6364136223846793005UL + 1442695040888963407UL;
  return (double)((seed >> 11) & 0xFFFFFFFFFUL) / (double)0x800000000UL - 1.0;
}

/* A random n x n dense matrix (column-major): kind 0 diagonally dominant
 * with about 5 entries a row; kind 1 a saddle point [M B^T; B 0], M
 * diagonal-dominant (n - n/4), B random sparse with a full-rank diagonal. */
static void RandomDense(int kind, sunindextype n, double *D)
{
  sunindextype i, j, k, nv = n - n / 4;
  memset(D, 0, (size_t)(n * n) * sizeof *D);
  if (kind == 0) {
    for (i = 0; i < n; i++) {
      for (k = 0; k < 5; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)n) % n;
        D[i + j * n] = Rand();
      }
      D[i + i * n] = 6.0 + Rand();
    }
  } else {
    for (i = 0; i < nv; i++) {
      for (k = 0; k < 3; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)nv) % nv;
        D[i + j * n] = D[j + i * n] = 0.3 * Rand();
      }
      D[i + i * n] = 4.0 + Rand();
    }
    for (i = nv; i < n; i++) { /* row i of B, and its transpose */
      D[i + (i - nv) * n] = D[(i - nv) + i * n] = 1.0 + 0.5 * Rand();
      for (k = 0; k < 2; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)nv) % nv;
        D[i + j * n] = D[j + i * n] = Rand();
      }
    }
  }
}

/* The sparse matrix (CSR or CSC) of the dense D. */
static void DenseToSparse(const double *D, sunindextype n, SUNMatrix S)
{
  const int csr = SUNSparseMatrix_SparseType(S) == CSR_MAT;
  sunindextype *ptr = SUNSparseMatrix_IndexPointers(S), *ind = SUNSparseMatrix_IndexValues(S);
  double *val = SUNSparseMatrix_Data(S);
  sunindextype i, j, p = 0;
  for (i = 0; i < n; i++) { /* i: row (CSR) or column (CSC) */
    ptr[i] = p;
    for (j = 0; j < n; j++) {
      const double a = csr ? D[i + j * n] : D[j + i * n];
      if (a != 0.0) {
        ind[p] = j;
        val[p] = a;
        p++;
      }
    }
  }
  ptr[n] = p;
}

/* x = D^{-1} b with Lignum's dense LU (D copied). */
static int DenseSolve(const double *D, sunindextype n, const double *b, double *x, SUNContext ctx)
{
  SUNMatrix A = SUNDenseMatrix(n, n, ctx);
  N_Vector v = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(v, A, ctx);
  int flag;
  memcpy(SM_DATA_D(A), D, (size_t)(n * n) * sizeof *D);
  memcpy(N_VGetArrayPointer(v), b, (size_t)n * sizeof *b);
  flag = SUNLinSolSetup(LS, A);
  if (!flag) flag = SUNLinSolSolve(LS, A, v, v, 0.0);
  memcpy(x, N_VGetArrayPointer(v), (size_t)n * sizeof *x);
  SUNLinSolFree(LS);
  N_VDestroy(v);
  SUNMatDestroy(A);
  return flag;
}

/* Solve with KLU when built (CSC copy of D); else returns 1 (not done). */
static int KluSolve(const double *D, sunindextype n, const double *b, double *x, SUNContext ctx)
{
#if defined(LGN_HAVE_KLU)
  SUNMatrix A = SUNSparseMatrix(n, n, n * n, CSC_MAT, ctx);
  N_Vector v = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS = SUNLinSol_KLU(v, A, ctx);
  int flag;
  DenseToSparse(D, n, A);
  memcpy(N_VGetArrayPointer(v), b, (size_t)n * sizeof *b);
  flag = SUNLinSolInitialize(LS);
  if (!flag) flag = SUNLinSolSetup(LS, A);
  if (!flag) flag = SUNLinSolSolve(LS, A, v, v, 0.0);
  memcpy(x, N_VGetArrayPointer(v), (size_t)n * sizeof *x);
  SUNLinSolFree(LS);
  N_VDestroy(v);
  SUNMatDestroy(A);
  return flag == 0 ? 0 : -1;
#else
  (void)D; (void)n; (void)b; (void)x; (void)ctx;
  return 1;
#endif
}

static double worst_dense = 0.0, worst_klu = 0.0;

/* One random system of each kind and format against the dense LU (and
 * KLU): setup and solve twice with new values (same pattern), then a
 * matrix of another pattern with the same solver. */
static void RandomSystems(SUNContext ctx)
{
  const sunindextype sizes[2] = {40, 200};
  int kind, fmt, s, rep;
  for (s = 0; s < 2; s++)
    for (kind = 0; kind < 2; kind++)
      for (fmt = 0; fmt < 2; fmt++) {
        const sunindextype n = sizes[s];
        double *D = (double *)malloc((size_t)(n * n) * sizeof *D);
        double *b = (double *)malloc((size_t)n * sizeof *b);
        double *xr = (double *)malloc((size_t)n * sizeof *xr);
        SUNMatrix A = SUNSparseMatrix(n, n, n * n, fmt == 0 ? CSR_MAT : CSC_MAT, ctx);
        N_Vector x = N_VNew_Serial(n, ctx), bv = N_VNew_Serial(n, ctx);
        SUNLinearSolver LS = LGNLinSol_PETSc(x, A, MPI_COMM_WORLD, ctx);
        sunindextype i;
        int flag;
        CHECK(LS != NULL, "LGNLinSol_PETSc created");
        if (LS == NULL) return;
        CHECK(SUNLinSolInitialize(LS) == 0, "initialize");
        unsigned long pattern_seed = seed;
        for (rep = 0; rep < 3; rep++) {
          /* rep 0, 1: one pattern, new values; rep 2: a new pattern */
          if (rep == 1) seed = pattern_seed;
          else pattern_seed = seed;
          RandomDense(kind, n, D);
          if (rep == 1) /* the same pattern: rescaled values */
            for (i = 0; i < n * n; i++) D[i] *= 1.0 + 0.1 * (double)(i % 7);
          for (i = 0; i < n; i++) b[i] = Rand();
          DenseToSparse(D, n, A);
          memcpy(N_VGetArrayPointer(bv), b, (size_t)n * sizeof *b);
          flag = SUNLinSolSetup(LS, A);
          CHECK(flag == 0, "setup n=%lld kind %d %s rep %d: %d", (long long)n, kind,
                fmt ? "CSC" : "CSR", rep, flag);
          flag = SUNLinSolSolve(LS, A, x, bv, 0.0);
          CHECK(flag == 0, "solve: %d", flag);
          CHECK(DenseSolve(D, n, b, xr, ctx) == 0, "dense LU solve");
          {
            const double d = RelDiff(N_VGetArrayPointer(x), xr, n);
            worst_dense = fmax(worst_dense, d);
            CHECK(d <= 1e-12, "n=%lld kind %d %s rep %d: |x - x_dense|/|x| = %.3e", (long long)n,
                  kind, fmt ? "CSC" : "CSR", rep, d);
          }
          if (KluSolve(D, n, b, xr, ctx) == 0) {
            const double d = RelDiff(N_VGetArrayPointer(x), xr, n);
            worst_klu = fmax(worst_klu, d);
            CHECK(d <= 1e-11, "|x - x_KLU|/|x| = %.3e", d);
          }
          CHECK(RankSpread(N_VGetArrayPointer(x), n) == 0.0, "the same solution on every rank");
          /* x may be b */
          flag = SUNLinSolSolve(LS, A, bv, bv, 0.0);
          /* (MUMPS' parallel solves may differ by roundoff from call to call) */
          CHECK(flag == 0 && RelDiff(N_VGetArrayPointer(bv), N_VGetArrayPointer(x), n) <= 1e-14,
                "solve in place: %d, %.3e", flag, RelDiff(N_VGetArrayPointer(bv), N_VGetArrayPointer(x), n));
        }
        /* singular: row/column 1 a copy of row/column 0 */
        for (i = 0; i < n; i++) D[1 + i * n] = D[0 + i * n];
        DenseToSparse(D, n, A);
        flag = SUNLinSolSetup(LS, A);
        CHECK(flag == SUNLS_LUFACT_FAIL, "singular: setup %d (SUNLS_LUFACT_FAIL expected)", flag);
        CHECK(SUNLinSolLastFlag(LS) >= 1 && SUNLinSolLastFlag(LS) <= n,
              "singular: last flag %lld names a column", (long long)SUNLinSolLastFlag(LS));
        if (rank == 0 && s == 0 && kind == 0 && fmt == 0)
          printf("(a) singular matrix: SUNLS_LUFACT_FAIL, last flag %lld\n",
                 (long long)SUNLinSolLastFlag(LS));
        CHECK(SUNLinSolSolve(LS, A, x, bv, 0.0) == SUNLS_ILL_INPUT, "no solve after a failed setup");
        /* regular again: the diagonal entry of row 1 raised (the same
         * pattern if it was there, else a new one) */
        D[1 + 1 * n] += 10.0;
        DenseToSparse(D, n, A);
        flag = SUNLinSolSetup(LS, A);
        {
          CHECK(flag == 0, "setup after a singular one: %d", flag);
          CHECK(SUNLinSolSolve(LS, A, x, bv, 0.0) == 0, "solve after it");
          CHECK(DenseSolve(D, n, N_VGetArrayPointer(bv), xr, ctx) == 0 &&
                    RelDiff(N_VGetArrayPointer(x), xr, n) <= 1e-12,
                "after the singular one: |x - x_dense|/|x| = %.3e",
                RelDiff(N_VGetArrayPointer(x), xr, n));
        }
        SUNLinSolFree(LS);
        N_VDestroy(x);
        N_VDestroy(bv);
        SUNMatDestroy(A);
        free(D);
        free(b);
        free(xr);
      }
  if (rank == 0)
    printf("(a) random systems (n = 40, 200; CSR, CSC; 3 setups each): max |x - x_dense|/|x| = "
           "%.2e, max |x - x_KLU|/|x| = %.2e\n", worst_dense, worst_klu);
}

static void Misuse(SUNContext ctx)
{
  SUNMatrix A = SUNSparseMatrix(4, 4, 16, CSR_MAT, ctx), Ad = SUNDenseMatrix(4, 4, ctx);
  N_Vector y = N_VNew_Serial(4, ctx), y5 = N_VNew_Serial(5, ctx);
  SUNLinearSolver LS;
  FILE *keep = stderr;
  (void)keep;
  printf("%s", rank == 0 ? "(a) misuse (the messages below are expected):\n" : "");
  fflush(stdout);
  CHECK(LGNLinSol_PETSc(NULL, A, MPI_COMM_WORLD, ctx) == NULL, "y = NULL");
  CHECK(LGNLinSol_PETSc(y, NULL, MPI_COMM_WORLD, ctx) == NULL, "A = NULL");
  CHECK(LGNLinSol_PETSc(y, A, MPI_COMM_WORLD, NULL) == NULL, "sunctx = NULL");
  CHECK(LGNLinSol_PETSc(y, A, MPI_COMM_NULL, ctx) == NULL, "comm = MPI_COMM_NULL");
  CHECK(LGNLinSol_PETSc(y, Ad, MPI_COMM_WORLD, ctx) == NULL, "dense A");
  CHECK(LGNLinSol_PETSc(y5, A, MPI_COMM_WORLD, ctx) == NULL, "y of another length");
  CHECK(!PetscIsUp(), "PETSc not initialised by the failed constructors");
  LS = LGNLinSol_PETSc(y, A, MPI_COMM_WORLD, ctx);
  CHECK(LS != NULL && PetscIsUp(), "created, PETSc initialised");
  CHECK(SUNLinSolSolve(LS, A, y, y, 0.0) == SUNLS_ILL_INPUT, "solve before setup");
  CHECK(SUNLinSolSetup(LS, Ad) == SUNLS_ILL_INPUT, "setup with a dense matrix");
  SUNLinSolFree(LS);
  CHECK(!PetscIsUp(), "PETSc finalised by the free of the last solver Lignum initialised it for");
  N_VDestroy(y);
  N_VDestroy(y5);
  SUNMatDestroy(A);
  SUNMatDestroy(Ad);
}

/* =============================================================================
 * (b) symbolic reuse, counted by PETSc
 * ===========================================================================*/

static PetscInt EventCount(const char *name)
{
  PetscLogEvent ev;
  PetscEventPerfInfo info;
  if (PetscLogEventGetId(name, &ev) != 0 || PetscLogEventGetPerfInfo(0, ev, &info) != 0)
    return -1;
  return (PetscInt)info.count;
}

static void SymbolicReuse(SUNContext ctx)
{
  const sunindextype n = 200;
  double *D = (double *)malloc((size_t)(n * n) * sizeof *D);
  SUNMatrix A = SUNSparseMatrix(n, n, n * n, CSR_MAT, ctx);
  N_Vector x = N_VNew_Serial(n, ctx);
  SUNLinearSolver LS;
  PetscInt sym0, num0, sym, num;
  sunindextype i;
  int k, ok = 1;
  CHECK(PetscInitializeNoArguments() == 0 && PetscLogDefaultBegin() == 0 &&
            KSPInitializePackage() == 0 && MatInitializePackage() == 0,
        "the test initialises PETSc (with logging, its events registered)");
  LS = LGNLinSol_PETSc(x, A, MPI_COMM_WORLD, ctx);
  CHECK(LS != NULL, "created");
  sym0 = EventCount("MatLUFactorSym");
  num0 = EventCount("MatLUFactorNum");
  RandomDense(0, n, D);
  for (k = 0; k < 5; k++) { /* five setups, one pattern */
    for (i = 0; i < n * n; i++) D[i] *= 1.01;
    DenseToSparse(D, n, A);
    ok = ok && SUNLinSolSetup(LS, A) == 0;
  }
  sym = EventCount("MatLUFactorSym") - sym0;
  num = EventCount("MatLUFactorNum") - num0;
  CHECK(ok, "five setups");
  CHECK(sym == 1 && num == 5, "one pattern: %d symbolic and %d numeric factorisations (1, 5)",
        (int)sym, (int)num);
  if (rank == 0)
    printf("(b) 5 setups of one pattern: %d symbolic, %d numeric factorisations (PETSc's log)\n",
           (int)sym, (int)num);
  RandomDense(0, n, D); /* another pattern */
  DenseToSparse(D, n, A);
  CHECK(SUNLinSolSetup(LS, A) == 0, "setup with a new pattern");
  sym = EventCount("MatLUFactorSym") - sym0;
  CHECK(sym == 2, "a new pattern: a new analysis (%d in all, 2 expected)", (int)sym);
  SUNLinSolFree(LS);
  CHECK(PetscIsUp(), "PETSc initialised by the application stays initialised");
  CHECK(PetscFinalize() == 0, "the test finalises PETSc");
  N_VDestroy(x);
  SUNMatDestroy(A);
  free(D);
}

/* =============================================================================
 * (c), (d) the chain
 * ===========================================================================*/

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Model *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  (void)v; (void)vdot;
  return LGNJoints_Stiffness(((Model *)ud)->joints, t, q, lambda, K) ? -1 : 0;
}

static char last_msg[2048];
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

enum { LS_PETSC_CSR, LS_PETSC_CSC, LS_REFERENCE };

#define NB 8          /* bodies */
#define NOUT 2        /* outputs: t = 0.05, 0.1 (0.01, 0.02 on more ranks) */

typedef struct {
  int flag;
  double q[NOUT][7 * NB], v[NOUT][6 * NB];
  long int nsteps, nsetups;
  sunindextype nred, red[16], pivot;
} ChainResult;

/* The chain of nb bodies (spherical joints; with `twice`, the joint of
 * body 0 to the ground is added twice: 3 redundant constraints),
 * generalized-alpha 0.9, h = 1e-3, outputs at 0.05 and 0.1 (on more than
 * one rank at 0.01 and 0.02). */
static void RunChain(int nb, int twice, int index, int newton, int solver, ChainResult *res,
                     SUNContext ctx)
{
  const sunrealtype L = 1.0, mass = 1.0, radius = 0.02;
  const sunrealtype J[3] = {0.5 * mass * radius * radius, mass * L * L / 12.0,
                            mass * L * L / 12.0};
  const sunrealtype gvec[3] = {0.0, 0.0, -9.81}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype left[3] = {-0.5 * L, 0.0, 0.0}, right[3] = {0.5 * L, 0.0, 0.0};
  LGNGroup body = LGNGroup_R3xSO3(), G, factors[NB];
  Model md;
  N_Vector q, v, y;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem;
  sunrealtype t = 0.0, *qd;
  sunindextype m, n;
  int k, flag = 0, o;

  memset(res, 0, sizeof *res);
  for (k = 0; k < nb; k++) factors[k] = body;
  G         = LGNGroup_Product(nb, factors);
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  flag      = LGNBodies_SetGravity(md.bodies, gvec);
  for (k = 0; k < nb && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, mass, J);
    if (!flag)
      flag = k == 0 ? LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, left)
                    : LGNJoints_AddSpherical(md.joints, k - 1, right, k, left);
  }
  if (!flag && twice) flag = LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, left);
  m = LGNJoints_NumConstraints(md.joints);
  n = G->nv + m;
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  y = N_VNew_Serial(n, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < nb; k++) { /* along x, bent a little downwards */
    qd[7 * k]     = (k + 0.5) * L;
    qd[7 * k + 3] = 1.0;
  }
  mem = LGNCreate(ctx);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetErrHandlerFn(mem, Capture, NULL);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (solver == LS_REFERENCE) {
#if defined(LGN_HAVE_KLU)
    A  = SUNSparseMatrix(n, n, 1, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(y, A, ctx);
#else
    A  = SUNDenseMatrix(n, n, ctx);
    LS = LGNLinSol_Dense(y, A, ctx);
#endif
  } else {
    A  = SUNSparseMatrix(n, n, 1, solver == LS_PETSC_CSR ? CSR_MAT : CSC_MAT, ctx);
    LS = LGNLinSol_PETSc(y, A, MPI_COMM_WORLD, ctx);
  }
  if (LS == NULL) flag = -1;
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  /* (d) diagnoses the singular matrix through PETSc's null pivots: the
   * refusal (by default the doubled rows are left out, test_redundant) */
  if (!flag && twice) flag = LGNSetRedundantConstraints(mem, LGN_REDUNDANT_REFUSE);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSetConstraintIndex(mem, index);
  if (!flag) flag = LGNSetNewtonMode(mem, newton);
  if (!flag) flag = LGNSStolerances(mem, 1e-10, 1e-10);
  last_msg[0] = '\0';
  for (o = 0; o < NOUT && !flag; o++) {
    flag = LGNSolve(mem, (nranks > 1 ? 0.01 : 0.05) * (o + 1), &t, q, v, LGN_NORMAL);
    memcpy(res->q[o], N_VGetArrayPointer(q), (size_t)(7 * nb) * sizeof(double));
    memcpy(res->v[o], N_VGetArrayPointer(v), (size_t)(6 * nb) * sizeof(double));
  }
  res->flag = flag;
  LGNGetNumSteps(mem, &res->nsteps);
  LGNGetNumLinSolvSetups(mem, &res->nsetups);
  LGNGetRedundantConstraints(mem, &res->nred, res->red);
  LGNGetZeroPivot(mem, &res->pivot);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
}

static void ChainTrajectories(SUNContext ctx)
{
  static ChainResult ref, pet;
  const int idx[2] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
  const int newt[2] = {LGN_NEWTON_FULL, LGN_NEWTON_MODIFIED};
  int i, j, o;
  for (i = 0; i < 2; i++)
    for (j = 0; j < 2; j++) {
      const int solver = (i == 0 && j == 0) ? LS_PETSC_CSC : LS_PETSC_CSR;
      double dq = 0.0, dv = 0.0, spread = 0.0;
      RunChain(NB, 0, idx[i], newt[j], LS_REFERENCE, &ref, ctx);
      RunChain(NB, 0, idx[i], newt[j], solver, &pet, ctx);
      CHECK(ref.flag == 0 && pet.flag == 0, "chain runs: reference %d, PETSc %d", ref.flag,
            pet.flag);
      for (o = 0; o < NOUT; o++) {
        dq = fmax(dq, RelDiff(pet.q[o], ref.q[o], 7 * NB));
        dv = fmax(dv, RelDiff(pet.v[o], ref.v[o], 6 * NB));
        spread = fmax(spread, RankSpread(pet.q[o], 7 * NB));
        spread = fmax(spread, RankSpread(pet.v[o], 6 * NB));
      }
      CHECK(dq <= 1e-10 && dv <= 1e-10, "chain %s %s: |q - q_ref|/|q| = %.2e, |v - v_ref|/|v| = %.2e",
            i ? "index 2" : "index 3", j ? "modified" : "full", dq, dv);
      CHECK(spread == 0.0, "the same trajectory on every rank (spread %.2e)", spread);
      CHECK(pet.nsteps == ref.nsteps && pet.nsetups == ref.nsetups,
            "the same steps (%ld, %ld) and setups (%ld, %ld)", pet.nsteps, ref.nsteps,
            pet.nsetups, ref.nsetups);
      if (rank == 0)
        printf("(c) chain of %d, %s, %s Newton, PETSc %s vs %s: %ld steps, %ld setups, "
               "max rel. diff q %.2e, v %.2e; ranks' spread %.1e\n",
               NB, i ? "index 2" : "index 3", j ? "modified" : "full",
               solver == LS_PETSC_CSC ? "CSC" : "CSR",
#if defined(LGN_HAVE_KLU)
               "KLU",
#else
               "dense LU",
#endif
               pet.nsteps, pet.nsetups, dq, dv, spread);
    }
}

static void Redundant(SUNContext ctx)
{
  static ChainResult res;
  const sunindextype nv = 6 * 3;
  sunindextype k;
  int dup_ok = 1;
  RunChain(3, 1, LGN_CONSTR_INDEX3, LGN_NEWTON_FULL, LS_PETSC_CSR, &res, ctx);
  if (rank == 0) printf("(d) a joint twice: %s\n    %s\n", LGNGetReturnFlagName(res.flag), last_msg);
  CHECK(res.flag == LGN_IC_FAIL || res.flag == LGN_LSETUP_FAIL, "a joint twice: %s",
        LGNGetReturnFlagName(res.flag));
  CHECK(res.nred == 3, "three redundant constraints, found %lld", (long long)res.nred);
  /* one of each pair: constraint i (the first joint) or 9 + i (its copy) */
  for (k = 0; k < res.nred && k < 3; k++)
    dup_ok = dup_ok && (res.red[k] < 3 || res.red[k] >= 9);
  CHECK(dup_ok, "the redundant ones are of the doubled joint");
  CHECK(strstr(last_msg, "Redundant constraints") != NULL && strstr(last_msg, "rank 9 of 12"),
        "the message names them: %s", last_msg);
  CHECK(res.pivot >= nv && res.pivot < nv + 12,
        "the zero pivot is a multiplier (unknown %lld)", (long long)res.pivot);
}

int main(int argc, char **argv)
{
  SUNContext ctx = NULL;
  int total = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  if (rank == 0) printf("LGNLinSol_PETSc on %d rank(s)\n", nranks);
  SUNContext_Create(NULL, &ctx);
  if (rank != 0) { /* one copy of the expected complaints */
    if (freopen("/dev/null", "w", stderr) == NULL) return 1;
  }
  Misuse(ctx);
  RandomSystems(ctx);
  CHECK(!PetscIsUp(), "PETSc finalised after the random systems");
  SymbolicReuse(ctx);
  ChainTrajectories(ctx);
  Redundant(ctx);
  CHECK(!PetscIsUp(), "PETSc finalised at the end");
  SUNContext_Free(&ctx);
  MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    printf("test_petsc_ls (%d rank(s)): %d checks per rank, %d failures on all ranks\n", nranks,
           checks, total);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
