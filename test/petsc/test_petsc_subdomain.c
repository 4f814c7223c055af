/* -----------------------------------------------------------------------------
 * Lignum test: the PETSc/MUMPS solve of a matrix summed from the ranks'
 * subdomain matrices (LGNLinSol_PETScSubdomain). Run on 1 rank, and under
 * mpiexec on 2 and 4 (CTest petsc_subdomain_np*): every check is made on
 * every rank, and the failures are summed over the ranks.
 *
 * A random global matrix (diagonally dominant, or a saddle point with a
 * zero block; 60 and 200 unknowns) is made identically on every rank from
 * one seed, its rows split contiguously over the ranks, and each stored
 * entry (i, j) shared out among the ranks: the owner of row i keeps a part
 * (local row, column j a ghost when another rank owns it), the owner of
 * column j gets a part in a ghost row i, and often a third rank gets a
 * part with both row and column ghosts; the parts sum to the entry. The
 * values lie on a grid of 2^-23, so the parts sum exactly in any order and
 * the assembled matrix IS the global one.
 *
 *  (a) the owned parts of the solution agree with a dense LU of the whole
 *      global matrix to a relative 1e-12: CSR and CSC, N_Vector_Parallel
 *      and MPIPlusX, a rank that owns nothing (on 2 and 4 ranks); the same
 *      pattern with new values, then a new pattern; in place (x = b);
 *  (b) the symbolic analysis is reused (PETSc's event counts): one per
 *      pattern, also when the pattern changes on rank 0 only;
 *  (c) a singular global matrix (row 0 copied into row N-1, owned by
 *      another rank on several ranks): SUNLS_LUFACT_FAIL on every rank with
 *      the same valid global column, no solve after it, then the same
 *      pattern with a regular matrix solves right again;
 *  (d) misuse: an owned index twice (another missing) or a ghost out of
 *      range on one rank
 *      only, A = NULL on one rank only (NULL on every rank, no hang), NULL
 *      arguments, a serial y; a bad matrix or vector on one rank only in
 *      setup or solve (the same flag on every rank, and the solver works
 *      afterwards).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>
#include <petscksp.h>

#include <lignum/lignum.h>
#include <lignum/lignum_petsc.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_parallel.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

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

/* Is the int v the same on every rank? */
static int SameOnAll(long long v)
{
  long long lo = 0, hi = 0;
  MPI_Allreduce(&v, &lo, 1, MPI_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&v, &hi, 1, MPI_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
  return lo == hi;
}

static PetscBool PetscIsUp(void)
{
  PetscBool up = PETSC_FALSE;
  PetscInitialized(&up);
  return up;
}

/* =============================================================================
 * Random numbers: one sequence the same on every rank, one of this rank
 * ===========================================================================*/

static unsigned long seed = 12345UL, local_seed = 777UL;
static double NextRand(unsigned long *s) /* in [-1, 1) */
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)((*s >> 11) & 0xFFFFFFFFFUL) / (double)0x800000000UL - 1.0;
}
static double Rand(void) { return NextRand(&seed); }
static double LocalRand(void) { return NextRand(&local_seed); }

/* x on the grid of 2^-20: sums of such numbers (up to 2^30) are exact */
static double Q(double x) { return ldexp(nearbyint(ldexp(x, 20)), -20); }

/* =============================================================================
 * The global matrix and its split
 * ===========================================================================*/

#define MAXRANKS 64

/* Rank r owns the global rows lo[r] .. lo[r+1]-1; with empty_last (on 2
 * ranks or more) the last rank owns none. */
typedef struct {
  sunindextype N, lo[MAXRANKS + 1];
} Layout;

static void MakeLayout(Layout *L, sunindextype N, int empty_last)
{
  const int p = empty_last && nranks > 1 ? nranks - 1 : nranks;
  int r;
  L->N     = N;
  L->lo[0] = 0;
  for (r = 0; r < nranks; r++)
    L->lo[r + 1] = L->lo[r] + (r < p ? N / p + (r < (int)(N % p) ? 1 : 0) : 0);
}

static int Owner(const Layout *L, sunindextype g)
{
  int r = 0;
  while (g >= L->lo[r + 1]) r++;
  return r;
}

/* A random N x N matrix (column-major D, its pattern M): kind 0
 * diagonally dominant with about 5 entries a row; kind 1 a saddle point
 * [K B^T; B 0], K diagonally dominant (N - N/4), B sparse with a
 * full-rank diagonal. Values on the grid of Q. */
static void RandomGlobal(int kind, sunindextype n, double *D, unsigned char *M)
{
  sunindextype i, j, k, nv = n - n / 4;
  memset(D, 0, (size_t)(n * n) * sizeof *D);
  if (kind == 0) {
    for (i = 0; i < n; i++) {
      for (k = 0; k < 5; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)n) % n;
        D[i + j * n] = Q(Rand());
      }
      D[i + i * n] = Q(6.0 + Rand());
    }
  } else {
    for (i = 0; i < nv; i++) {
      for (k = 0; k < 3; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)nv) % nv;
        D[i + j * n] = D[j + i * n] = Q(0.3 * Rand());
      }
      D[i + i * n] = Q(4.0 + Rand());
    }
    for (i = nv; i < n; i++) { /* row i of B, and its transpose */
      D[i + (i - nv) * n] = D[(i - nv) + i * n] = Q(1.0 + 0.5 * Rand());
      for (k = 0; k < 2; k++) {
        j = (sunindextype)((Rand() + 1.0) * 0.5 * (double)nv) % nv;
        D[i + j * n] = D[j + i * n] = Q(Rand());
      }
    }
  }
  for (k = 0; k < n * n; k++) M[k] = D[k] != 0.0;
}

/* One part of an entry of the global matrix given to this rank. */
typedef struct {
  sunindextype i, j;
  double v;
} Part;

typedef struct {
  Part *p;
  sunindextype n, cap;
} Parts;

static void Push(Parts *P, sunindextype i, sunindextype j, double v)
{
  if (P->n == P->cap) {
    P->cap = P->cap > 0 ? 2 * P->cap : 256;
    P->p   = (Part *)realloc(P->p, (size_t)P->cap * sizeof *P->p);
  }
  P->p[P->n].i = i;
  P->p[P->n].j = j;
  P->p[P->n].v = v;
  P->n++;
}

/* This rank's parts of the stored entries of (D, M). Every rank draws the
 * same random numbers (the split of all ranks is decided everywhere), so
 * the parts of one entry sum to it over the ranks. An entry (i, j) goes
 * to the owner of row i, the owner of column j (a ghost row there) and,
 * every other time, a third rank (ghost row and column). */
static void Split(const Layout *L, const double *D, const unsigned char *M, Parts *mine)
{
  const sunindextype n = L->N;
  sunindextype i, j;
  mine->n = 0;
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++) {
      const double a = D[i + j * n];
      const double f = Rand(), g = Rand();
      int who[3], k, np = 0;
      double rest = a;
      if (!M[i + j * n]) continue;
      who[np++] = Owner(L, i);
      if (Owner(L, j) != who[0]) who[np++] = Owner(L, j);
      if (nranks > 1 && g > 0.0) {
        const int r3 = (int)((g * 1e6)) % nranks;
        if (r3 != who[0] && (np == 1 || r3 != who[1])) who[np++] = r3;
      }
      for (k = 0; k < np; k++) {
        /* a random share, the last one the rest (exact on the grid) */
        const double part = k + 1 < np ? Q(a * (0.5 + 0.4 * f) / (double)(k + 1)) : rest;
        rest -= part;
        if (who[k] == rank) Push(mine, i, j, part);
      }
    }
}

/* This rank's local unknowns: owned lo .. hi-1, then the ghosts any of
 * the part lists needs, in a random order of this rank. loc[g] is the
 * local index of global g (-1: not local). */
typedef struct {
  sunindextype n_own, n_loc, lo;
  sunindextype *gidx, *loc;
} Subdomain;

static void MakeSubdomain(const Layout *L, Parts *const *lists, int nlists, Subdomain *S)
{
  const sunindextype N = L->N;
  sunindextype g, k, m;
  int l;
  S->lo    = L->lo[rank];
  S->n_own = L->lo[rank + 1] - L->lo[rank];
  S->loc   = (sunindextype *)malloc((size_t)N * sizeof *S->loc);
  S->gidx  = (sunindextype *)malloc((size_t)(N + 1) * sizeof *S->gidx);
  for (g = 0; g < N; g++) S->loc[g] = -1;
  for (k = 0; k < S->n_own; k++) {
    S->gidx[k]          = S->lo + k;
    S->loc[S->lo + k] = k;
  }
  S->n_loc = S->n_own;
  for (l = 0; l < nlists; l++)
    for (k = 0; k < lists[l]->n; k++) {
      const sunindextype ij[2] = {lists[l]->p[k].i, lists[l]->p[k].j};
      for (m = 0; m < 2; m++)
        if (S->loc[ij[m]] < 0) {
          S->loc[ij[m]]       = S->n_loc;
          S->gidx[S->n_loc++] = ij[m];
        }
    }
  if (S->n_loc == 0) { /* nothing here at all: one (empty) ghost */
    S->gidx[0] = 0;
    S->loc[0]  = 0;
    S->n_loc   = 1;
  }
  for (k = S->n_loc - 1; k > S->n_own; k--) { /* shuffle the ghosts */
    const sunindextype r = S->n_own + (sunindextype)((LocalRand() + 1.0) * 0.5 * (double)(k - S->n_own + 1)) % (k - S->n_own + 1);
    const sunindextype t = S->gidx[k];
    S->gidx[k] = S->gidx[r];
    S->gidx[r] = t;
  }
  for (k = S->n_own; k < S->n_loc; k++) S->loc[S->gidx[k]] = k;
}

static void FreeSubdomain(Subdomain *S)
{
  free(S->gidx);
  free(S->loc);
}

/* The subdomain matrix A (CSR or CSC, n_loc x n_loc) of this rank's parts:
 * every part stored, zeros too (they are the pattern). */
static void FillLocal(const Subdomain *S, const Parts *P, SUNMatrix A)
{
  const sunindextype nl = S->n_loc;
  const int csr = SUNSparseMatrix_SparseType(A) == CSR_MAT;
  double *Dl = (double *)calloc((size_t)(nl * nl), sizeof *Dl);
  unsigned char *Ml = (unsigned char *)calloc((size_t)(nl * nl), 1);
  sunindextype *ptr = SUNSparseMatrix_IndexPointers(A), *ind = SUNSparseMatrix_IndexValues(A);
  double *val = SUNSparseMatrix_Data(A);
  sunindextype k, a, b, p = 0;
  for (k = 0; k < P->n; k++) {
    const sunindextype li = S->loc[P->p[k].i], lj = S->loc[P->p[k].j];
    Dl[li + lj * nl] += P->p[k].v;
    Ml[li + lj * nl] = 1;
  }
  for (a = 0; a < nl; a++) { /* a: row (CSR) or column (CSC) */
    ptr[a] = p;
    for (b = 0; b < nl; b++) {
      const sunindextype q = csr ? a + b * nl : b + a * nl;
      if (Ml[q]) {
        ind[p] = b;
        val[p] = Dl[q];
        p++;
      }
    }
  }
  ptr[nl] = p;
  free(Dl);
  free(Ml);
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

/* =============================================================================
 * Vectors of the owned parts
 * ===========================================================================*/

enum { VEC_PARALLEL, VEC_MPIPLUSX };

static N_Vector OwnedVector(int type, sunindextype n_own, sunindextype N, SUNContext ctx)
{
  if (type == VEC_PARALLEL) return N_VNew_Parallel(MPI_COMM_WORLD, n_own, N, ctx);
  return N_VMake_MPIPlusX(MPI_COMM_WORLD, N_VNew_Serial(n_own, ctx), ctx);
}

static void DestroyOwned(N_Vector v)
{
  if (v == NULL) return;
  if (N_VGetVectorID(v) == SUNDIALS_NVEC_MPIPLUSX) N_VDestroy(N_VGetLocalVector_MPIPlusX(v));
  N_VDestroy(v);
}

/* max over the owned parts of |x - xref[lo ..]|, over max |xref|, over all
 * ranks */
static double OwnedRelDiff(N_Vector x, const Subdomain *S, const double *xref, sunindextype N)
{
  const double *xd = N_VGetArrayPointer(x);
  double d = 0.0, s = 0.0, dmax = 0.0;
  sunindextype k;
  for (k = 0; k < N; k++) s = fmax(s, fabs(xref[k]));
  for (k = 0; k < S->n_own; k++) d = fmax(d, fabs(xd[k] - xref[S->lo + k]));
  MPI_Allreduce(&d, &dmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return s > 0.0 ? dmax / s : dmax;
}

static void SetOwned(N_Vector v, const Subdomain *S, const double *glob)
{
  if (S->n_own > 0)
    memcpy(N_VGetArrayPointer(v), glob + S->lo, (size_t)S->n_own * sizeof *glob);
}

/* =============================================================================
 * (a), (c) random systems
 * ===========================================================================*/

static double worst = 0.0;

/* One global problem: three matrices (a pattern with two sets of values,
 * then another pattern) and a singular one with a regular one of its
 * pattern, all over the same local unknowns. */
typedef struct {
  Layout L;
  sunindextype N;
  double *D[5];         /* 0, 1: pattern 1; 2: pattern 2; 3 singular, 4 regular */
  unsigned char *M[5];
  Parts parts[5];
  Subdomain S;
  double *b, *xref;
} Problem;

static void MakeProblem(Problem *pb, int kind, sunindextype N, int empty_last)
{
  const size_t nn = (size_t)(N * N);
  unsigned long s;
  sunindextype i, k;
  Parts *lists[5];
  int m;
  memset(pb, 0, sizeof *pb);
  pb->N = N;
  MakeLayout(&pb->L, N, empty_last);
  for (m = 0; m < 5; m++) {
    pb->D[m] = (double *)malloc(nn * sizeof(double));
    pb->M[m] = (unsigned char *)malloc(nn);
    lists[m] = &pb->parts[m];
  }
  RandomGlobal(kind, N, pb->D[0], pb->M[0]);
  s = seed;
  Split(&pb->L, pb->D[0], pb->M[0], &pb->parts[0]);
  /* the same pattern and split, new values (on the grid of 2^-23) */
  for (k = 0; k < (sunindextype)nn; k++)
    pb->D[1][k] = pb->D[0][k] * (1.0 + (double)(k % 7) / 8.0);
  memcpy(pb->M[1], pb->M[0], nn);
  seed = s;
  Split(&pb->L, pb->D[1], pb->M[1], &pb->parts[1]);
  RandomGlobal(kind, N, pb->D[2], pb->M[2]);
  Split(&pb->L, pb->D[2], pb->M[2], &pb->parts[2]);
  /* singular: row N-1 a copy of row 0, with (N-1, N-1) stored (maybe a
   * zero); regular: the same pattern, 10 added at (N-1, N-1) */
  memcpy(pb->D[3], pb->D[2], nn * sizeof(double));
  memcpy(pb->M[3], pb->M[2], nn);
  for (i = 0; i < N; i++) {
    pb->D[3][(N - 1) + i * N] = pb->D[3][0 + i * N];
    pb->M[3][(N - 1) + i * N] = pb->M[3][0 + i * N];
  }
  pb->M[3][(N - 1) + (N - 1) * N] = 1;
  memcpy(pb->D[4], pb->D[3], nn * sizeof(double));
  memcpy(pb->M[4], pb->M[3], nn);
  pb->D[4][(N - 1) + (N - 1) * N] += 10.0;
  s = seed;
  Split(&pb->L, pb->D[3], pb->M[3], &pb->parts[3]);
  seed = s;
  Split(&pb->L, pb->D[4], pb->M[4], &pb->parts[4]);
  MakeSubdomain(&pb->L, lists, 5, &pb->S);
  pb->b    = (double *)malloc((size_t)N * sizeof *pb->b);
  pb->xref = (double *)malloc((size_t)N * sizeof *pb->xref);
  for (i = 0; i < N; i++) pb->b[i] = Rand();
}

static void FreeProblem(Problem *pb)
{
  int m;
  for (m = 0; m < 5; m++) {
    free(pb->D[m]);
    free(pb->M[m]);
    free(pb->parts[m].p);
  }
  FreeSubdomain(&pb->S);
  free(pb->b);
  free(pb->xref);
}

/* How the parts of (D, M) lie on the ranks, summed over the ranks: [0]
 * parts in a ghost row only, [1] in a ghost column only, [2] in both. The
 * test is a test of the sum across the ranks only if none is zero. */
static void SplitStats(const Problem *pb, int m, long long st[3])
{
  const Parts *P = &pb->parts[m];
  const sunindextype lo = pb->S.lo, hi = pb->S.lo + pb->S.n_own;
  long long mine[3] = {0, 0, 0};
  sunindextype k;
  for (k = 0; k < P->n; k++) {
    const int gr = P->p[k].i < lo || P->p[k].i >= hi, gc = P->p[k].j < lo || P->p[k].j >= hi;
    if (gr || gc) mine[gr && gc ? 2 : gr ? 0 : 1]++;
  }
  MPI_Allreduce(mine, st, 3, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
}

/* Is global column col (0-based) where a null vector z of the singular
 * D (rows 0 and N-1 equal: a one-dimensional null space) is largest?
 * z from D with row N-1 replaced by e_col^T: D z = 0 except that row, and
 * z_col = 1 (a regular system only if z_col can be nonzero). Returns
 * |z_col| / max |z| (0 when that system is singular). */
static double NullColumnShare(const double *D, sunindextype N, sunindextype col, SUNContext ctx)
{
  double *Dm = (double *)malloc((size_t)(N * N) * sizeof *Dm);
  double *e = (double *)calloc((size_t)N, sizeof *e), *z = (double *)malloc((size_t)N * sizeof *z);
  double zmax = 0.0, share = 0.0;
  sunindextype k;
  memcpy(Dm, D, (size_t)(N * N) * sizeof *Dm);
  for (k = 0; k < N; k++) Dm[(N - 1) + k * N] = k == col ? 1.0 : 0.0;
  e[N - 1] = 1.0;
  if (col >= 0 && col < N && DenseSolve(Dm, N, e, z, ctx) == 0) {
    for (k = 0; k < N; k++) zmax = fmax(zmax, fabs(z[k]));
    share = zmax > 0.0 ? fabs(z[col]) / zmax : 0.0;
  }
  free(Dm);
  free(e);
  free(z);
  return share;
}

static const char *Name(int fmt, int vt)
{
  static const char *names[4] = {"CSR Parallel", "CSR MPIPlusX", "CSC Parallel", "CSC MPIPlusX"};
  return names[2 * fmt + vt];
}

static void RandomSystems(SUNContext ctx)
{
  const sunindextype sizes[2] = {60, 200};
  int s, kind, fmt, rep, empty;
  for (empty = 0; empty < (nranks > 1 ? 2 : 1); empty++)
    for (s = 0; s < 2; s++)
      for (kind = 0; kind < 2; kind++)
        for (fmt = 0; fmt < 2; fmt++) {
          const sunindextype N = sizes[s];
          const int vt = (s + kind + fmt) % 2; /* both vector types, in turn */
          Problem pb;
          SUNMatrix A;
          N_Vector x, b;
          SUNLinearSolver LS;
          sunindextype col;
          int flag;
          MakeProblem(&pb, kind, N, empty);
          if (nranks > 1) {
            long long st[3];
            SplitStats(&pb, 0, st);
            /* (on 2 ranks with the last one owning nothing, rank 0 owns
             * all rows and rank 1 holds ghost-ghost parts only) */
            CHECK((nranks - empty < 2 || (st[0] > 0 && st[1] > 0)) && st[2] > 0,
                  "parts in ghost rows (%lld), ghost columns (%lld), both (%lld)", st[0], st[1],
                  st[2]);
            if (rank == 0 && s == 1 && kind == 0 && fmt == 0)
              printf("(a) N = %lld%s: parts in a ghost row %lld, a ghost column %lld, both "
                     "%lld; subdomain of rank 0: %lld owned + %lld ghosts\n",
                     (long long)N, empty ? ", last rank owning nothing" : "", st[0], st[1],
                     st[2], (long long)pb.S.n_own, (long long)(pb.S.n_loc - pb.S.n_own));
          }
          A  = SUNSparseMatrix(pb.S.n_loc, pb.S.n_loc, pb.S.n_loc * pb.S.n_loc,
                               fmt == 0 ? CSR_MAT : CSC_MAT, ctx);
          x  = OwnedVector(vt, pb.S.n_own, N, ctx);
          b  = OwnedVector(vt, pb.S.n_own, N, ctx);
          FillLocal(&pb.S, &pb.parts[0], A);
          LS = LGNLinSol_PETScSubdomain(x, A, pb.S.gidx, ctx);
          CHECK(LS != NULL, "created (N = %lld, %s)", (long long)N, Name(fmt, vt));
          if (LS == NULL) {
            FreeProblem(&pb);
            return;
          }
          for (rep = 0; rep < 3; rep++) { /* pattern 1 twice, then pattern 2 */
            FillLocal(&pb.S, &pb.parts[rep], A);
            SetOwned(b, &pb.S, pb.b);
            flag = SUNLinSolSetup(LS, A);
            CHECK(flag == 0, "setup N=%lld kind %d %s%s rep %d: %d", (long long)N, kind,
                  Name(fmt, vt), empty ? " (last rank empty)" : "", rep, flag);
            flag = SUNLinSolSolve(LS, A, x, b, 0.0);
            CHECK(flag == 0, "solve: %d", flag);
            CHECK(DenseSolve(pb.D[rep], N, pb.b, pb.xref, ctx) == 0, "dense LU solve");
            {
              const double d = OwnedRelDiff(x, &pb.S, pb.xref, N);
              worst = fmax(worst, d);
              CHECK(d <= 1e-12, "N=%lld kind %d %s%s rep %d: |x - x_dense|/|x| = %.3e",
                    (long long)N, kind, Name(fmt, vt), empty ? " (last rank empty)" : "",
                    rep, d);
            }
            flag = SUNLinSolSolve(LS, A, b, b, 0.0); /* in place */
            CHECK(flag == 0 && OwnedRelDiff(b, &pb.S, pb.xref, N) <= 1e-12,
                  "solve in place: %d, %.3e", flag, OwnedRelDiff(b, &pb.S, pb.xref, N));
          }
          /* (c) singular, then regular with the same pattern */
          FillLocal(&pb.S, &pb.parts[3], A);
          flag = SUNLinSolSetup(LS, A);
          col  = SUNLinSolLastFlag(LS);
          CHECK(flag == SUNLS_LUFACT_FAIL, "singular: setup %d (SUNLS_LUFACT_FAIL expected)",
                flag);
          CHECK(col >= 1 && col <= N && SameOnAll(col),
                "singular: last flag %lld, a global column, the same on every rank",
                (long long)col);
          {
            const double share = NullColumnShare(pb.D[3], N, col - 1, ctx);
            CHECK(share > 0.999,
                  "singular: the null vector's largest entry is at global column %lld "
                  "(|z_col|/max|z| = %.3f)", (long long)(col - 1), share);
          }
          if (rank == 0 && s == 0 && kind == 0 && fmt == 0 && !empty)
            printf("(c) singular global matrix: SUNLS_LUFACT_FAIL, last flag %lld\n",
                   (long long)col);
          CHECK(SUNLinSolSolve(LS, A, x, b, 0.0) == SUNLS_ILL_INPUT,
                "no solve after a failed setup");
          FillLocal(&pb.S, &pb.parts[4], A);
          SetOwned(b, &pb.S, pb.b);
          flag = SUNLinSolSetup(LS, A);
          CHECK(flag == 0, "setup after a singular one: %d", flag);
          CHECK(SUNLinSolSolve(LS, A, x, b, 0.0) == 0, "solve after it");
          CHECK(DenseSolve(pb.D[4], N, pb.b, pb.xref, ctx) == 0 &&
                    OwnedRelDiff(x, &pb.S, pb.xref, N) <= 1e-12,
                "after the singular one: |x - x_dense|/|x| = %.3e",
                OwnedRelDiff(x, &pb.S, pb.xref, N));
          SUNLinSolFree(LS);
          DestroyOwned(x);
          DestroyOwned(b);
          SUNMatDestroy(A);
          FreeProblem(&pb);
        }
  if (rank == 0)
    printf("(a) random systems (N = 60, 200; CSR, CSC; Parallel, MPIPlusX%s; 3 setups each): "
           "max |x - x_dense|/|x| = %.2e\n",
           nranks > 1 ? "; a rank owning nothing" : "", worst);
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

/* A stored zero at a position of the subdomain that has none (rank 0's
 * pattern changes, the others' do not); returns 0 if there is none. */
static int AddStoredZero(const Problem *pb, Parts *P)
{
  sunindextype i, j, k;
  for (i = 0; i < pb->N; i++)
    for (j = 0; j < pb->N; j++) {
      int found = 0;
      if (pb->S.loc[i] < 0 || pb->S.loc[j] < 0) continue;
      for (k = 0; k < P->n && !found; k++) found = P->p[k].i == i && P->p[k].j == j;
      if (!found) {
        Push(P, i, j, 0.0);
        return 1;
      }
    }
  return 0;
}

static void SymbolicReuse(SUNContext ctx)
{
  const sunindextype N = 200;
  Problem pb;
  SUNMatrix A;
  N_Vector x, b;
  SUNLinearSolver LS;
  PetscInt sym0, num0, sym, num;
  int k, ok = 1, added;
  CHECK(PetscInitializeNoArguments() == 0 && PetscLogDefaultBegin() == 0 &&
            KSPInitializePackage() == 0 && MatInitializePackage() == 0,
        "the test initialises PETSc (with logging, its events registered)");
  MakeProblem(&pb, 0, N, 0);
  A  = SUNSparseMatrix(pb.S.n_loc, pb.S.n_loc, pb.S.n_loc * pb.S.n_loc, CSR_MAT, ctx);
  x  = OwnedVector(VEC_PARALLEL, pb.S.n_own, N, ctx);
  b  = OwnedVector(VEC_PARALLEL, pb.S.n_own, N, ctx);
  FillLocal(&pb.S, &pb.parts[0], A);
  LS = LGNLinSol_PETScSubdomain(x, A, pb.S.gidx, ctx);
  CHECK(LS != NULL, "created");
  sym0 = EventCount("MatLUFactorSym");
  num0 = EventCount("MatLUFactorNum");
  for (k = 0; k < 5; k++) { /* five setups, one pattern, values 0 and 1 */
    FillLocal(&pb.S, &pb.parts[k % 2], A);
    ok = ok && SUNLinSolSetup(LS, A) == 0;
  }
  sym = EventCount("MatLUFactorSym") - sym0;
  num = EventCount("MatLUFactorNum") - num0;
  CHECK(ok, "five setups");
  CHECK(sym == 1 && num == 5, "one pattern: %d symbolic and %d numeric factorisations (1, 5)",
        (int)sym, (int)num);
  /* the values of the last setup (parts[0]) are right */
  SetOwned(b, &pb.S, pb.b);
  CHECK(SUNLinSolSolve(LS, A, x, b, 0.0) == 0 && DenseSolve(pb.D[0], N, pb.b, pb.xref, ctx) == 0 &&
            OwnedRelDiff(x, &pb.S, pb.xref, N) <= 1e-12,
        "after 5 setups: |x - x_dense|/|x| = %.3e", OwnedRelDiff(x, &pb.S, pb.xref, N));
  if (rank == 0)
    printf("(b) 5 setups of one pattern: %d symbolic, %d numeric factorisations (PETSc's log)\n",
           (int)sym, (int)num);
  /* a new pattern on rank 0 only: a new analysis on every rank */
  added = rank == 0 ? AddStoredZero(&pb, &pb.parts[0]) : 0;
  MPI_Bcast(&added, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (added) {
    FillLocal(&pb.S, &pb.parts[0], A);
    CHECK(SUNLinSolSetup(LS, A) == 0, "setup with a new pattern on rank 0");
    sym = EventCount("MatLUFactorSym") - sym0;
    CHECK(sym == 2, "a new pattern on rank 0 only: a new analysis (%d in all, 2 expected)",
          (int)sym);
    CHECK(SUNLinSolSolve(LS, A, x, b, 0.0) == 0 && OwnedRelDiff(x, &pb.S, pb.xref, N) <= 1e-12,
          "with rank 0's stored zero: |x - x_dense|/|x| = %.3e",
          OwnedRelDiff(x, &pb.S, pb.xref, N));
  }
  FillLocal(&pb.S, &pb.parts[2], A); /* another pattern everywhere */
  CHECK(SUNLinSolSetup(LS, A) == 0, "setup with a new pattern");
  sym = EventCount("MatLUFactorSym") - sym0;
  CHECK(sym == 2 + added, "a new pattern: a new analysis (%d in all, %d expected)", (int)sym,
        2 + added);
  if (rank == 0)
    printf("(b) a new pattern on rank 0 only, then on all: %d analyses in all\n", (int)sym);
  SUNLinSolFree(LS);
  CHECK(PetscIsUp(), "PETSc initialised by the application stays initialised");
  CHECK(PetscFinalize() == 0, "the test finalises PETSc");
  DestroyOwned(x);
  DestroyOwned(b);
  SUNMatDestroy(A);
  FreeProblem(&pb);
}

/* =============================================================================
 * (d) misuse
 * ===========================================================================*/

static void Misuse(SUNContext ctx)
{
  const int last = nranks - 1;
  Problem pb;
  SUNMatrix A, Abig, Ad;
  N_Vector x, b, ys, wrong;
  SUNLinearSolver LS;
  sunindextype *gi;
  int flag;
  printf("%s", rank == 0 ? "(d) misuse (the messages below are expected):\n" : "");
  fflush(stdout);
  MakeProblem(&pb, 0, 40, 0);
  A  = SUNSparseMatrix(pb.S.n_loc, pb.S.n_loc, pb.S.n_loc * pb.S.n_loc, CSR_MAT, ctx);
  Abig = SUNSparseMatrix(pb.S.n_loc + 1, pb.S.n_loc + 1, 1, CSR_MAT, ctx);
  Ad = SUNDenseMatrix(pb.S.n_loc, pb.S.n_loc, ctx);
  FillLocal(&pb.S, &pb.parts[0], A);
  x  = OwnedVector(VEC_PARALLEL, pb.S.n_own, pb.N, ctx);
  b  = OwnedVector(VEC_MPIPLUSX, pb.S.n_own, pb.N, ctx);
  ys = N_VNew_Serial(pb.S.n_own, ctx);
  gi = (sunindextype *)malloc((size_t)pb.S.n_loc * sizeof *gi);

  CHECK(LGNLinSol_PETScSubdomain(NULL, A, pb.S.gidx, ctx) == NULL, "y = NULL");
  CHECK(LGNLinSol_PETScSubdomain(ys, A, pb.S.gidx, ctx) == NULL, "a serial y");
  CHECK(LGNLinSol_PETScSubdomain(x, A, NULL, ctx) == NULL, "global_index = NULL");
  CHECK(LGNLinSol_PETScSubdomain(x, A, pb.S.gidx, NULL) == NULL, "sunctx = NULL");
  CHECK(LGNLinSol_PETScSubdomain(x, rank == last ? NULL : A, pb.S.gidx, ctx) == NULL,
        "A = NULL on the last rank only: NULL on every rank");
  CHECK(LGNLinSol_PETScSubdomain(x, rank == last ? Ad : A, pb.S.gidx, ctx) == NULL,
        "a dense A on the last rank only");
  /* an owned index twice (and so another missing) on the last rank only */
  memcpy(gi, pb.S.gidx, (size_t)pb.S.n_loc * sizeof *gi);
  if (rank == last && pb.S.n_own >= 2) gi[1] = pb.S.gidx[0];
  {
    /* collective: every rank calls; refused if the last rank could spoil */
    int spoilt = rank == last && pb.S.n_own >= 2;
    SUNLinearSolver bad;
    MPI_Allreduce(MPI_IN_PLACE, &spoilt, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    bad = LGNLinSol_PETScSubdomain(x, A, gi, ctx);
    CHECK(!spoilt || bad == NULL, "an owned index twice on the last rank: NULL on every rank");
    if (bad != NULL) SUNLinSolFree(bad);
  }
  /* a ghost out of range on rank 0 only (if it has one) */
  memcpy(gi, pb.S.gidx, (size_t)pb.S.n_loc * sizeof *gi);
  if (rank == 0) gi[pb.S.n_loc - 1] = pb.S.n_loc > pb.S.n_own ? pb.N : -1;
  CHECK(LGNLinSol_PETScSubdomain(x, A, gi, ctx) == NULL,
        "a ghost (or owned index) out of range on rank 0: NULL on every rank");
  CHECK(!PetscIsUp(), "PETSc not initialised by the failed constructors");

  /* the caller's copy of global_index may go: the solver keeps its own */
  memcpy(gi, pb.S.gidx, (size_t)pb.S.n_loc * sizeof *gi);
  LS = LGNLinSol_PETScSubdomain(x, A, gi, ctx);
  memset(gi, 0xff, (size_t)pb.S.n_loc * sizeof *gi);
  CHECK(LS != NULL && PetscIsUp(), "created, PETSc initialised");
  if (LS != NULL) {
    SetOwned(b, &pb.S, pb.b);
    CHECK(SUNLinSolSolve(LS, A, x, b, 0.0) == SUNLS_ILL_INPUT, "solve before setup");
    flag = SUNLinSolSetup(LS, rank == last ? Abig : A);
    CHECK(flag == SUNLS_ILL_INPUT, "a matrix of another size on the last rank only: %d", flag);
    flag = SUNLinSolSetup(LS, rank == last ? Ad : A);
    CHECK(flag == SUNLS_ILL_INPUT, "a dense matrix on the last rank only: %d", flag);
    if (rank == 0) SUNSparseMatrix_IndexValues(A)[0] = pb.S.n_loc; /* out of range */
    flag = SUNLinSolSetup(LS, A);
    CHECK(flag == SUNLS_ILL_INPUT, "an index out of range on rank 0 only: %d", flag);
    FillLocal(&pb.S, &pb.parts[0], A);
    flag = SUNLinSolSetup(LS, A);
    CHECK(flag == 0, "then a good setup: %d", flag);
    wrong = OwnedVector(VEC_PARALLEL, pb.S.n_own + (rank == last ? 1 : 0), pb.N + 1, ctx);
    flag = SUNLinSolSolve(LS, A, wrong, b, 0.0);
    CHECK(flag == SUNLS_ILL_INPUT, "x of another length: %d", flag);
    flag = SUNLinSolSolve(LS, A, rank == last ? ys : x, b, 0.0);
    CHECK(flag == SUNLS_ILL_INPUT, "a serial x on the last rank only: %d", flag);
    flag = SUNLinSolSolve(LS, A, x, b, 0.0);
    CHECK(flag == 0 && DenseSolve(pb.D[0], pb.N, pb.b, pb.xref, ctx) == 0 &&
              OwnedRelDiff(x, &pb.S, pb.xref, pb.N) <= 1e-12,
          "then a good solve: %d, %.3e", flag, OwnedRelDiff(x, &pb.S, pb.xref, pb.N));
    DestroyOwned(wrong);
    SUNLinSolFree(LS);
  }
  CHECK(!PetscIsUp(), "PETSc finalised by the free of the last solver");
  free(gi);
  N_VDestroy(ys);
  DestroyOwned(x);
  DestroyOwned(b);
  SUNMatDestroy(A);
  SUNMatDestroy(Abig);
  SUNMatDestroy(Ad);
  FreeProblem(&pb);
}

int main(int argc, char **argv)
{
  SUNContext ctx = NULL;
  MPI_Comm comm = MPI_COMM_WORLD;
  int total = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  if (nranks > MAXRANKS) {
    if (rank == 0) printf("at most %d ranks\n", MAXRANKS);
    MPI_Finalize();
    return 1;
  }
  local_seed += 1000UL * (unsigned long)rank;
  if (rank == 0) printf("LGNLinSol_PETScSubdomain on %d rank(s)\n", nranks);
  SUNContext_Create(&comm, &ctx);
  if (rank != 0) { /* one copy of the expected complaints */
    if (freopen("/dev/null", "w", stderr) == NULL) return 1;
  }
  Misuse(ctx);
  RandomSystems(ctx);
  CHECK(!PetscIsUp(), "PETSc finalised after the random systems");
  SymbolicReuse(ctx);
  CHECK(!PetscIsUp(), "PETSc finalised at the end");
  SUNContext_Free(&ctx);
  MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    printf("test_petsc_subdomain (%d rank(s)): %d checks per rank, %d failures on all ranks\n",
           nranks, checks, total);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
