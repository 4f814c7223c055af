/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The direct solve through PETSc (lignum_petsc.h): a SUNLinearSolver over a
 * KSP of type KSPPREONLY with PCLU and MATSOLVERMUMPS, in two modes that
 * share everything but how PETSc's matrix is filled and what a solve
 * exchanges:
 *
 *   - full (LGNLinSol_PETSc): a SUNSparseMatrix (CSR or CSC) held
 *     identically on every rank of a communicator; the solution is
 *     gathered to every rank;
 *   - subdomain (LGNLinSol_PETScSubdomain): each rank holds a subdomain
 *     matrix A_r over its local unknowns (its owned ones, then ghosts
 *     owned elsewhere) with their global indices P_r; the global matrix
 *     is sum_r P_r^T A_r P_r (additive, finite-element assembly); the
 *     vectors of a solve are the owned parts only (no gather).
 *
 *   - Pattern. At each setup A's format and index arrays are compared with
 *     a copy of those of the last setup (collectively: a new pattern on
 *     any rank is a new pattern on all). A new pattern makes a new MATAIJ
 *     (MATSEQAIJ on one rank, MATMPIAIJ on several) and a new KSP: MUMPS
 *     analyses the pattern at the next factorisation.
 *       full: this rank's rows of A (PETSc's split) in CSR, columns
 *       sorted, with the position of each entry in A's data (perm: the
 *       transposition of a CSC matrix is done once per pattern), and a
 *       preallocation from them (MAT_NEW_NONZERO_LOCATION_ERR set);
 *       subdomain: the global (row, column) of every stored entry of A, in
 *       the order of A's data, given to MatSetPreallocationCOO: PETSc
 *       sends the entries of rows owned elsewhere to their owner and sums
 *       repeated ones, which is the sum over the ranks.
 *   - Values. Every setup inserts this setup's values; the pattern is then
 *     the same, and PCSetUp does only MUMPS' numerical factorisation
 *     (SAME_NONZERO_PATTERN: the analysis is reused).
 *       full: gathered through perm and inserted row by row (MatSetValues,
 *       INSERT_VALUES);
 *       subdomain: A's data as it is (MatSetValuesCOO, INSERT_VALUES: the
 *       contributions to one entry, from this rank and from the others,
 *       are summed and the sum replaces the old value; ADD_VALUES would
 *       add the sum to the value of the last setup).
 *   - Singular matrices: null pivot detection (ICNTL(24) = 1, ICNTL(13) =
 *     1 as PETSc sets it with -mat_mumps_icntl_24, CNTL(3) the relative
 *     threshold). Null pivots (INFOG(28) > 0) or a failed factorisation
 *     (PCGetFailedReason, INFOG(1) < 0) make the setup return
 *     SUNLS_LUFACT_FAIL. With null pivots, one solve with ICNTL(25) = 1
 *     returns MUMPS' first null-space vector; 1 + the (global) index of
 *     its largest entry is the last flag (the unknown Lignum's diagnostics
 *     name). MUMPS gives that vector only with a centralised solution, so
 *     on several ranks a sequential copy of the matrix is factored once
 *     more (full: on every rank, from A; subdomain: on rank 0, gathered
 *     from PETSc's matrix, and the column broadcast).
 *   - Solve: this rank's part of b into PETSc's vector, KSPSolve, and
 *       full: the parts of the solution gathered to every rank
 *       (MPI_Allgatherv); subdomain: this rank's part into x.
 *   - Failures on one rank. A check that fails on one rank only (a bad
 *     argument, memory) is agreed on with one MPI_Allreduce before the
 *     next collective call, so that every rank returns the failure and
 *     none waits for the others.
 *   - Initialisation: PETSc is initialised by the first solver if nobody
 *     did, and then finalised by the free of the last one (a count).
 * PETSc's headers are included as system headers (the include directories
 * of the imported target PkgConfig::PETSc), so -Wextra -Wpedantic -Werror
 * apply to this file and not to them.
 * Built as the library lignum_petsc (Lignum::lignum_petsc) on top of
 * liblignum's public API, so that liblignum itself needs neither PETSc nor
 * MPI; LGNSetLinearSolver takes it as a custom direct sparse solver.
 * ---------------------------------------------------------------------------*/

#include <petscksp.h>

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <lignum/lignum_petsc.h>

/* The library lignum_petsc sits on Lignum's public API (it cannot call
 * liblignum's hidden lgnReport): its messages go to stderr in Lignum's
 * default format. */
static void Report(const char *func, const char *fmt, ...)
{
  va_list ap;
  fprintf(stderr, "\n[LGN ERROR]  %s\n  ", func);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fprintf(stderr, "\n\n");
}

#if defined(PETSC_USE_COMPLEX) || !defined(PETSC_USE_REAL_DOUBLE)
#error "LGNLinSol_PETSc needs PETSc with real double-precision scalars"
#endif
/* A's data goes to PETSc as it is (memcpy, MatSetValuesCOO) */
_Static_assert(sizeof(sunrealtype) == sizeof(PetscScalar),
               "sunrealtype and PetscScalar must be the same type");

#define MSG_MEM_FAIL "A memory request failed." /* as the integrator's */

/* MUMPS' null pivot threshold, relative to the norm of the matrix it
 * factors (CNTL(3) > 0); the dense path of Lignum takes a matrix whose
 * pivots span more than 1e13 for singular, too (lgn_ls.c). */
#define LGN_PETSC_NULL_PIVOT_TOL 1.0e-13

/* MUMPS' workspace increase ICNTL(14), in percent: the first value, and
 * the largest the retries after a shortage go to (doubling). */
#define LGN_PETSC_ICNTL14_FIRST 50
#define LGN_PETSC_ICNTL14_MAX   800

/* The solver's content. */
typedef struct {
  MPI_Comm comm;          /* full: the user's communicator (PETSc
                             duplicates it for its objects); subdomain: a
                             duplicate of y's, freed by Free              */
  int owns_comm;          /* comm is that duplicate                        */
  int rank, size;
  int subdomain;          /* the mode: 0 full, 1 subdomain                 */
  sunindextype N;         /* global unknowns                               */
  sunindextype nA;        /* A's rows and columns: N, or the subdomain's   */
  PetscInt *gidx;         /* subdomain: the global index of each of A's
                             rows/columns (a copy of global_index)         */
  /* the pattern of the last setup: format, nnz, copies of A's arrays */
  int sparsetype;         /* CSR_MAT or CSC_MAT; -1: none yet              */
  sunindextype nnz;
  sunindextype *ptr, *ind;
  /* this rank's rows rstart .. rstart+nloc-1 of the global matrix */
  PetscInt rstart, nloc;
  /* full: the local rows in CSR, columns sorted */
  PetscInt *ia, *ja;      /* local row pointers (nloc+1), columns          */
  sunindextype *perm;     /* position in A's data of each local entry      */
  PetscScalar *va;        /* the local values of this setup                */
  int *counts, *displs;   /* rows of each rank (MPI_Allgatherv)            */
  /* subdomain: the global (row, column) of A's entries, in the order of
   * A's data, from a new pattern until PETSc's preallocation took them */
  PetscInt *coo_i, *coo_j;
  Mat P;                  /* PETSc's matrix                                */
  KSP ksp;
  Vec pb, px;             /* right-hand side and solution, distributed    */
  PetscInt icntl14;       /* MUMPS' workspace increase (%), raised when
                             the factorisation ran short of it            */
  sunindextype last_flag;
  sunbooleantype factored;
} PetscLUContent;

#define CONTENT(S) ((PetscLUContent *)(S)->content)

/* PETSc's initialisation: whether Lignum did it, and how many solvers are
 * alive (not thread-safe: documented in lignum_petsc.h). */
static int lgn_petsc_initialised_here = 0;
static long int lgn_petsc_nsolvers    = 0;

/* =============================================================================
 * Agreement across the ranks
 * ===========================================================================*/

/* The flag every rank continues with: a failure (< 0) on any rank makes
 * the smallest flag of all ranks the one of all (SUNLS_* failures are
 * negative). With newpat != NULL, *newpat becomes 1 on every rank when it
 * was 1 on any (in the same reduction). An MPI failure is
 * SUNLS_PACKAGE_FAIL_UNREC. Collective. */
static int AgreeFlag(MPI_Comm comm, int flag, int *newpat)
{
  int in[2], out[2];
  in[0] = flag;
  in[1] = newpat != NULL ? -*newpat : 0;
  if (MPI_Allreduce(in, out, 2, MPI_INT, MPI_MIN, comm) != MPI_SUCCESS)
    return SUNLS_PACKAGE_FAIL_UNREC;
  if (newpat != NULL) *newpat = -out[1];
  return out[0] < 0 ? out[0] : flag;
}

/* Is ok (1) true on every rank? A rank where it was true reports for func
 * that another rank refused (that rank said why). Collective. */
static int AllOk(MPI_Comm comm, int ok, const char *func)
{
  int all = 0;
  if (MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm) != MPI_SUCCESS) {
    Report(func, "MPI_Allreduce failed.");
    return 0;
  }
  if (ok && !all)
    Report(func, "Refused on another rank of the communicator (its message says why).");
  return all;
}

/* The length of x's rank-local part (all of x for a serial vector),
 * through the operation the deprecated N_VGetLocalLength calls. */
static sunindextype LocalLength(N_Vector x)
{
  return x->ops->nvgetlocallength != NULL ? x->ops->nvgetlocallength(x) : N_VGetLength(x);
}

/* =============================================================================
 * Pattern and values
 * ===========================================================================*/

/* Is A's pattern the one of the last setup? (this rank only) */
static sunbooleantype SamePattern(const PetscLUContent *c, SUNMatrix A)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  if (c->P == NULL || c->sparsetype != SUNSparseMatrix_SparseType(A) || c->nnz != ptr[np])
    return SUNFALSE;
  return memcmp(c->ptr, ptr, (size_t)(np + 1) * sizeof *ptr) == 0 &&
         memcmp(c->ind, SUNSparseMatrix_IndexValues(A), (size_t)c->nnz * sizeof *ptr) == 0;
}

/* Are A's index arrays valid: pointers from 0, not decreasing, within A's
 * room, indices in [0, nA)? A bad one is reported (SUNLS_ILL_INPUT). */
static int CheckIndices(const PetscLUContent *c, SUNMatrix A)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
  sunindextype k, p;
  if (ptr[0] != 0 || ptr[np] > SUNSparseMatrix_NNZ(A)) {
    Report("SUNLinSolSetup", "A's index pointers run from %lld to %lld (0 to at most %lld).",
           (long long)ptr[0], (long long)ptr[np], (long long)SUNSparseMatrix_NNZ(A));
    return SUNLS_ILL_INPUT;
  }
  for (k = 0; k < np; k++) {
    if (ptr[k + 1] < ptr[k]) {
      Report("SUNLinSolSetup", "A's index pointers decrease at %lld.", (long long)k);
      return SUNLS_ILL_INPUT;
    }
    for (p = ptr[k]; p < ptr[k + 1]; p++)
      if (ind[p] < 0 || ind[p] >= c->nA) {
        Report("SUNLinSolSetup", "A's index %lld (entry %lld) is outside [0, %lld).",
               (long long)ind[p], (long long)p, (long long)c->nA);
        return SUNLS_ILL_INPUT;
      }
  }
  return SUNLS_SUCCESS;
}

/* Sort columns j[lo..hi) with perm alongside (insertion sort: rows of a
 * multibody iteration matrix are short, and usually sorted already). */
static void SortRow(PetscInt *j, sunindextype *perm, PetscInt lo, PetscInt hi)
{
  PetscInt a, b;
  for (a = lo + 1; a < hi; a++) {
    const PetscInt col = j[a];
    const sunindextype p = perm[a];
    for (b = a; b > lo && j[b - 1] > col; b--) {
      j[b]    = j[b - 1];
      perm[b] = perm[b - 1];
    }
    j[b]    = col;
    perm[b] = p;
  }
}

static void FreeCoo(PetscLUContent *c)
{
  free(c->coo_i);
  free(c->coo_j);
  c->coo_i = c->coo_j = NULL;
}

static void FreePattern(PetscLUContent *c)
{
  free(c->ptr);
  free(c->ind);
  free(c->ia);
  free(c->ja);
  free(c->perm);
  free(c->va);
  FreeCoo(c);
  c->ptr = c->ind = c->perm = NULL;
  c->ia = c->ja = NULL;
  c->va         = NULL;
  c->sparsetype = -1;
  c->nnz        = 0;
}

/* Copies of A's format and index arrays (what SamePattern compares). */
static int CopyPattern(PetscLUContent *c, SUNMatrix A)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype nnz = ptr[np];
  c->ptr = (sunindextype *)malloc((size_t)(np + 1) * sizeof *c->ptr);
  c->ind = (sunindextype *)malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *c->ind);
  if (c->ptr == NULL || c->ind == NULL) return SUNLS_MEM_FAIL;
  memcpy(c->ptr, ptr, (size_t)(np + 1) * sizeof *ptr);
  memcpy(c->ind, SUNSparseMatrix_IndexValues(A), (size_t)nnz * sizeof *c->ind);
  c->sparsetype = (int)SUNSparseMatrix_SparseType(A);
  c->nnz        = nnz;
  return SUNLS_SUCCESS;
}

/* Full mode: the local CSR of A's pattern (this rank's rows rstart ..
 * rstart+nloc-1 of the N x N matrix A). */
static int BuildLocalCSR(PetscLUContent *c, SUNMatrix A)
{
  const sunindextype N = c->N;
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
  const sunindextype nnz = c->nnz;
  const sunindextype r0 = c->rstart, r1 = c->rstart + c->nloc;
  sunindextype i, k, p, nl = 0;

  c->ia = (PetscInt *)calloc((size_t)c->nloc + 1, sizeof *c->ia);
  if (c->ia == NULL) return SUNLS_MEM_FAIL;
  /* count the entries of each local row */
  if (SUNSparseMatrix_SparseType(A) == CSR_MAT) {
    for (i = r0; i < r1; i++) c->ia[i - r0 + 1] = (PetscInt)(ptr[i + 1] - ptr[i]);
  } else {
    for (p = 0; p < nnz; p++)
      if (ind[p] >= r0 && ind[p] < r1) c->ia[ind[p] - r0 + 1]++;
  }
  for (i = 0; i < c->nloc; i++) c->ia[i + 1] += c->ia[i];
  nl      = (sunindextype)c->ia[c->nloc];
  c->ja   = (PetscInt *)malloc((size_t)(nl > 0 ? nl : 1) * sizeof *c->ja);
  c->perm = (sunindextype *)malloc((size_t)(nl > 0 ? nl : 1) * sizeof *c->perm);
  c->va   = (PetscScalar *)malloc((size_t)(nl > 0 ? nl : 1) * sizeof *c->va);
  if (c->ja == NULL || c->perm == NULL || c->va == NULL) return SUNLS_MEM_FAIL;

  if (SUNSparseMatrix_SparseType(A) == CSR_MAT) {
    for (i = r0; i < r1; i++)
      for (p = ptr[i], k = c->ia[i - r0]; p < ptr[i + 1]; p++, k++) {
        c->ja[k]   = (PetscInt)ind[p];
        c->perm[k] = p;
      }
  } else { /* the transpose of the local rows: column by column, so sorted */
    PetscInt *next = (PetscInt *)malloc((size_t)(c->nloc > 0 ? c->nloc : 1) * sizeof *next);
    if (next == NULL) return SUNLS_MEM_FAIL;
    memcpy(next, c->ia, (size_t)c->nloc * sizeof *next);
    for (k = 0; k < N; k++)
      for (p = ptr[k]; p < ptr[k + 1]; p++)
        if (ind[p] >= r0 && ind[p] < r1) {
          const PetscInt q = next[ind[p] - r0]++;
          c->ja[q]         = (PetscInt)k;
          c->perm[q]       = p;
        }
    free(next);
  }
  for (i = 0; i < c->nloc; i++) SortRow(c->ja, c->perm, c->ia[i], c->ia[i + 1]);
  return SUNLS_SUCCESS;
}

/* Subdomain mode: the global (row, column) of each stored entry of A, in
 * the order of A's data: entry (i, j) of A is entry (gidx[i], gidx[j]) of
 * this rank's contribution P_r^T A P_r to the global matrix. */
static int BuildCoo(PetscLUContent *c, SUNMatrix A)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
  const int csr = SUNSparseMatrix_SparseType(A) == CSR_MAT;
  sunindextype k, p;
  c->coo_i = (PetscInt *)malloc((size_t)(c->nnz > 0 ? c->nnz : 1) * sizeof *c->coo_i);
  c->coo_j = (PetscInt *)malloc((size_t)(c->nnz > 0 ? c->nnz : 1) * sizeof *c->coo_j);
  if (c->coo_i == NULL || c->coo_j == NULL) return SUNLS_MEM_FAIL;
  for (k = 0; k < np; k++) /* k: row (CSR) or column (CSC) of A */
    for (p = ptr[k]; p < ptr[k + 1]; p++) {
      c->coo_i[p] = c->gidx[csr ? k : ind[p]];
      c->coo_j[p] = c->gidx[csr ? ind[p] : k];
    }
  return SUNLS_SUCCESS;
}

/* A's new pattern, checked and copied, and what the mode builds from it.
 * Local. Returns SUNLS_SUCCESS, SUNLS_ILL_INPUT or SUNLS_MEM_FAIL (then no
 * pattern). */
static int BuildPattern(PetscLUContent *c, SUNMatrix A)
{
  int flag;
  FreePattern(c);
  flag = CheckIndices(c, A);
  if (flag == SUNLS_SUCCESS) flag = CopyPattern(c, A);
  if (flag == SUNLS_SUCCESS) flag = c->subdomain ? BuildCoo(c, A) : BuildLocalCSR(c, A);
  if (flag != SUNLS_SUCCESS) FreePattern(c);
  return flag;
}

/* A new PETSc matrix of the mode's layout, and its vectors. Collective. */
static PetscErrorCode NewMatrix(PetscLUContent *c)
{
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->ksp));
  PetscCall(MatDestroy(&c->P));
  PetscCall(VecDestroy(&c->pb));
  PetscCall(VecDestroy(&c->px));
  PetscCall(MatCreate(c->comm, &c->P));
  PetscCall(MatSetSizes(c->P, c->nloc, c->nloc, (PetscInt)c->N, (PetscInt)c->N));
  PetscCall(MatSetType(c->P, MATAIJ));
  if (c->subdomain) {
    /* entries of rows owned elsewhere go to their owner; repeated ones are
     * summed (PETSc may change the arrays: freed right after) */
    PetscCall(MatSetPreallocationCOO(c->P, (PetscCount)c->nnz, c->coo_i, c->coo_j));
    FreeCoo(c);
  } else {
    /* both are called, the one of the other type does nothing */
    PetscCall(MatSeqAIJSetPreallocationCSR(c->P, c->ia, c->ja, NULL));
    PetscCall(MatMPIAIJSetPreallocationCSR(c->P, c->ia, c->ja, NULL));
    PetscCall(MatSetOption(c->P, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  }
  PetscCall(MatCreateVecs(c->P, &c->px, &c->pb));
  PetscFunctionReturn(0);
}

/* A new KSP (LU by MUMPS) for c->P: the analysis is redone at the next
 * factorisation. Collective on c->P's communicator. */
static PetscErrorCode NewKsp(PetscLUContent *c)
{
  PC pc;
  Mat F;
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->ksp));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)c->P), &c->ksp));
  PetscCall(KSPSetOptionsPrefix(c->ksp, "lgn_"));
  PetscCall(KSPSetType(c->ksp, KSPPREONLY));
  PetscCall(KSPGetPC(c->ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(c->ksp));
  PetscCall(KSPSetOperators(c->ksp, c->P, c->P));
  PetscCall(PCFactorSetUpMatSolverType(pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatMumpsSetIcntl(F, 24, 1));  /* null pivot detection */
  PetscCall(MatMumpsSetIcntl(F, 13, 1));  /* as PETSc does with it */
  PetscCall(MatMumpsSetCntl(F, 3, LGN_PETSC_NULL_PIVOT_TOL));
  /* the workspace: more than MUMPS' 20 % by default, since the pivots of
   * a saddle-point matrix (its zero block) are often delayed */
  if (c->icntl14 > 0) PetscCall(MatMumpsSetIcntl(F, 14, c->icntl14));
  PetscFunctionReturn(0);
}

/* This setup's values into PETSc's matrix. Collective. */
static PetscErrorCode SetValues(PetscLUContent *c, SUNMatrix A)
{
  const sunrealtype *data = SUNSparseMatrix_Data(A);
  PetscInt i, k;
  PetscFunctionBeginUser;
  if (c->subdomain) {
    /* INSERT_VALUES: the sum of all ranks' contributions replaces the
     * value of the last setup (no assembly calls needed) */
    PetscCall(MatSetValuesCOO(c->P, data, INSERT_VALUES));
    PetscFunctionReturn(0);
  }
  for (k = 0; k < c->ia[c->nloc]; k++) c->va[k] = data[c->perm[k]];
  for (i = 0; i < c->nloc; i++) {
    const PetscInt row = c->rstart + i;
    PetscCall(MatSetValues(c->P, 1, &row, c->ia[i + 1] - c->ia[i], c->ja + c->ia[i],
                           c->va + c->ia[i], INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(c->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(c->P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The factorisation (KSPSetUp), and how it went: *nnull null pivots
 * (INFOG(28)), *infog MUMPS' INFOG(1), *failed when MUMPS or PETSc reports
 * a failure. */
static PetscErrorCode Factor(PetscLUContent *c, PetscInt *nnull, PetscInt *infog,
                             PetscBool *failed)
{
  PC pc;
  Mat F;
  PCFailedReason reason;
  MatFactorError ferr;
  PetscInt infog1 = 0;
  PetscFunctionBeginUser;
  /* new values: KSPSetUp refactors only after KSPSetOperators, and PCSetUp
   * then sees the matrix's unchanged nonzero state (SAME_NONZERO_PATTERN:
   * numerical factorisation only) */
  PetscCall(KSPSetOperators(c->ksp, c->P, c->P));
  PetscCall(KSPSetUp(c->ksp));
  PetscCall(KSPGetPC(c->ksp, &pc));
  PetscCall(PCGetFailedReason(pc, &reason));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatFactorGetError(F, &ferr));
  PetscCall(MatMumpsGetInfog(F, 1, &infog1));
  PetscCall(MatMumpsGetInfog(F, 28, nnull));
  *infog = infog1;
  *failed = reason != PC_NOERROR || ferr != MAT_FACTOR_NOERROR || infog1 < 0 ? PETSC_TRUE
                                                                            : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* With null pivots: MUMPS' first null-space vector (one solve with
 * ICNTL(25) = 1) and the global index of its largest entry into *col. */
static PetscErrorCode NullColumn(PetscLUContent *c, PetscInt *col)
{
  PC pc;
  Mat F;
  PetscReal vmax;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(c->ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(VecSet(c->pb, 0.0));
  PetscCall(MatMumpsSetIcntl(F, 25, 1));
  PetscCall(MatSolve(F, c->pb, c->px));
  PetscCall(MatMumpsSetIcntl(F, 25, 0));
  PetscCall(VecMax(c->px, col, &vmax));
  {
    PetscInt cmin;
    PetscReal vmin;
    PetscCall(VecMin(c->px, &cmin, &vmin));
    if (-vmin > vmax) *col = cmin;
  }
  PetscFunctionReturn(0);
}

/* The null column of a sequential matrix seq->P (vectors seq->pb, px):
 * a KSP of its own, the factorisation, and the column when it has null
 * pivots; -1 otherwise or when a PETSc call fails. Frees seq's KSP. */
static PetscInt SeqNullColumn(PetscLUContent *seq)
{
  PetscInt col = -1, nnull = 0, infog = 0;
  PetscBool failed = PETSC_TRUE;
  if (NewKsp(seq) == 0 && Factor(seq, &nnull, &infog, &failed) == 0 && nnull > 0 &&
      !failed && NullColumn(seq, &col) != 0)
    col = -1;
  (void)KSPDestroy(&seq->ksp);
  return nnull > 0 && !failed ? col : -1;
}

/* A content for a sequential copy of c's global matrix on PETSC_COMM_SELF. */
static void InitSeqContent(PetscLUContent *seq, const PetscLUContent *c)
{
  memset(seq, 0, sizeof *seq);
  seq->comm       = PETSC_COMM_SELF;
  seq->size       = 1;
  seq->N          = c->N;
  seq->nA         = c->N;
  seq->nloc       = (PetscInt)c->N;
  seq->sparsetype = -1;
  seq->icntl14    = c->icntl14;
}

/* Full mode, after null pivots on several ranks: MUMPS computes null-space
 * vectors only with a centralised solution (INFOG(1) = -37 with PETSc's
 * distributed one), so each rank factors its own full copy of A on
 * PETSC_COMM_SELF (the same on every rank) and takes the column there.
 * Only on this failure path; PETSc's error messages are silenced (the
 * column is then unknown, -1). */
static PetscInt NullColumnOnEveryRank(const PetscLUContent *c, SUNMatrix A)
{
  PetscLUContent seq;
  PetscInt col = -1;
  InitSeqContent(&seq, c);
  if (PetscPushErrorHandler(PetscReturnErrorHandler, NULL) != 0) return -1;
  if (BuildPattern(&seq, A) == SUNLS_SUCCESS && NewMatrix(&seq) == 0 &&
      SetValues(&seq, A) == 0)
    col = SeqNullColumn(&seq);
  (void)PetscPopErrorHandler();
  (void)MatDestroy(&seq.P);
  (void)VecDestroy(&seq.pb);
  (void)VecDestroy(&seq.px);
  FreePattern(&seq);
  return col;
}

/* Subdomain mode, after null pivots on several ranks: no rank holds the
 * global matrix, so rank 0 gathers it from PETSc's (MatCreateSubMatrices
 * of all rows and columns there, of none elsewhere), factors it on
 * PETSC_COMM_SELF and broadcasts the column. Collective; only on this
 * failure path; -1 when unknown. */
static PetscInt NullColumnGathered(const PetscLUContent *c)
{
  PetscLUContent seq;
  PetscInt col = -1;
  long long lcol;
  IS all = NULL;
  Mat *sub = NULL;
  const int silenced = PetscPushErrorHandler(PetscReturnErrorHandler, NULL) == 0;
  int ok;
  InitSeqContent(&seq, c);
  /* the index set is local: agreed on before the collective gather */
  ok = ISCreateStride(PETSC_COMM_SELF, c->rank == 0 ? (PetscInt)c->N : 0, 0, 1, &all) == 0;
  if (AgreeFlag(c->comm, ok ? SUNLS_SUCCESS : SUNLS_MEM_FAIL, NULL) == SUNLS_SUCCESS &&
      MatCreateSubMatrices(c->P, 1, &all, &all, MAT_INITIAL_MATRIX, &sub) == 0 &&
      c->rank == 0) {
    seq.P = sub[0]; /* borrowed: MatDestroySubMatrices frees it */
    if (MatCreateVecs(seq.P, &seq.px, &seq.pb) == 0) col = SeqNullColumn(&seq);
    seq.P = NULL;
  }
  if (sub != NULL) (void)MatDestroySubMatrices(1, &sub);
  (void)ISDestroy(&all);
  (void)VecDestroy(&seq.pb);
  (void)VecDestroy(&seq.px);
  if (silenced) (void)PetscPopErrorHandler();
  lcol = (long long)col;
  if (MPI_Bcast(&lcol, 1, MPI_LONG_LONG, 0, c->comm) != MPI_SUCCESS) return -1;
  return (PetscInt)lcol;
}

/* The global column of a null pivot found by this setup's factorisation
 * (-1 when unknown). Collective. */
static PetscInt NullPivotColumn(PetscLUContent *c, SUNMatrix A)
{
  PetscInt col = -1;
  if (c->size == 1) return NullColumn(c, &col) == 0 ? col : -1;
  return c->subdomain ? NullColumnGathered(c) : NullColumnOnEveryRank(c, A);
}

/* =============================================================================
 * The SUNLinearSolver operations
 * ===========================================================================*/

static SUNLinearSolver_Type GetType(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID GetID(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_CUSTOM;
}

static int Initialize(SUNLinearSolver S)
{
  if (S == NULL || S->content == NULL) return SUNLS_MEM_NULL;
  CONTENT(S)->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

/* A sparse nA x nA matrix? (this rank only) */
static int CheckMatrix(const PetscLUContent *c, SUNMatrix A)
{
  if (A == NULL) return SUNLS_MEM_NULL;
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE || SUNSparseMatrix_Rows(A) != c->nA ||
      SUNSparseMatrix_Columns(A) != c->nA)
    return SUNLS_ILL_INPUT;
  return SUNLS_SUCCESS;
}

/* A failed setup: no pattern kept (a new one at the next setup). */
static int SetupFailed(PetscLUContent *c, int flag)
{
  FreePattern(c);
  c->last_flag = flag;
  return flag;
}

/* A new pattern on every rank: built (locally), agreed on, then PETSc's
 * matrix and KSP. Collective. */
static int NewPattern(PetscLUContent *c, SUNMatrix A)
{
  int flag = AgreeFlag(c->comm, BuildPattern(c, A), NULL);
  if (flag != SUNLS_SUCCESS) return flag;
  if (NewMatrix(c) != 0 || NewKsp(c) != 0) return SUNLS_PACKAGE_FAIL_UNREC;
  return SUNLS_SUCCESS;
}

static int PetscLUSetup(SUNLinearSolver S, SUNMatrix A)
{
  PetscLUContent *c;
  int flag, newpat = 0;
  PetscInt nnull = 0, col = -1, infog = 0;
  PetscBool failed = PETSC_FALSE;
  if (S == NULL || S->content == NULL) return SUNLS_MEM_NULL;
  c           = CONTENT(S);
  c->factored = SUNFALSE;
  /* one reduction: a bad matrix on any rank, a new pattern on any rank */
  flag = CheckMatrix(c, A);
  if (flag == SUNLS_SUCCESS) newpat = !SamePattern(c, A);
  flag = AgreeFlag(c->comm, flag, &newpat);
  if (flag != SUNLS_SUCCESS) {
    c->last_flag = flag;
    return flag;
  }
  if (newpat) {
    flag = NewPattern(c, A);
    if (flag != SUNLS_SUCCESS) return SetupFailed(c, flag);
  }
  for (;;) {
    if (SetValues(c, A) != 0 || Factor(c, &nnull, &infog, &failed) != 0)
      return SetupFailed(c, SUNLS_PACKAGE_FAIL_UNREC);
    /* MUMPS ran short of workspace (-8, -9, -11 .. -15: more pivots were
     * delayed than its analysis estimated): twice the increase, with a
     * new analysis, up to LGN_PETSC_ICNTL14_MAX % */
    if (!(infog == -8 || infog == -9 || (infog <= -11 && infog >= -15)) ||
        2 * c->icntl14 > LGN_PETSC_ICNTL14_MAX)
      break;
    c->icntl14 *= 2;
    if (NewKsp(c) != 0) return SetupFailed(c, SUNLS_PACKAGE_FAIL_UNREC);
  }
  if (nnull > 0 && !failed) col = NullPivotColumn(c, A);
  if (nnull > 0 || failed) {
    c->last_flag = col >= 0 ? (sunindextype)col + 1 : 0;
    return SUNLS_LUFACT_FAIL;
  }
  c->last_flag = SUNLS_SUCCESS;
  c->factored  = SUNTRUE;
  return SUNLS_SUCCESS;
}

/* Is v an owned part: an N_Vector_Parallel or MPIPlusX? */
static int IsOwnedPartType(N_Vector v)
{
  const N_Vector_ID id = N_VGetVectorID(v);
  return id == SUNDIALS_NVEC_PARALLEL || id == SUNDIALS_NVEC_MPIPLUSX;
}

/* Are x and b vectors of the mode's kind (full: length N; subdomain:
 * owned parts of length nloc, N over all ranks) with arrays? This rank
 * only. */
static int CheckSolveVectors(const PetscLUContent *c, N_Vector x, N_Vector b)
{
  N_Vector v[2];
  int k;
  v[0] = x;
  v[1] = b;
  for (k = 0; k < 2; k++) {
    if (v[k] == NULL) return SUNLS_MEM_NULL;
    if (N_VGetLength(v[k]) != c->N) return SUNLS_ILL_INPUT;
    if (c->subdomain &&
        (!IsOwnedPartType(v[k]) || LocalLength(v[k]) != (sunindextype)c->nloc))
      return SUNLS_ILL_INPUT;
    if (N_VGetArrayPointer(v[k]) == NULL && (!c->subdomain || c->nloc > 0))
      return SUNLS_MEM_FAIL;
  }
  return SUNLS_SUCCESS;
}

/* PETSc's solution into x: full, the parts gathered to every rank;
 * subdomain, this rank's part. Collective. */
static int SolutionOut(const PetscLUContent *c, const PetscScalar *xv, sunrealtype *xd)
{
  if (c->subdomain || c->size == 1) {
    if (c->nloc > 0) memcpy(xd, xv, (size_t)c->nloc * sizeof *xd);
    return SUNLS_SUCCESS;
  }
  return MPI_Allgatherv(xv, c->counts[c->rank], MPI_DOUBLE, xd, c->counts, c->displs,
                        MPI_DOUBLE, c->comm) == MPI_SUCCESS
             ? SUNLS_SUCCESS
             : SUNLS_PACKAGE_FAIL_UNREC;
}

static int PetscLUSolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                        sunrealtype tol)
{
  PetscLUContent *c;
  sunrealtype *xd, *bd;
  PetscScalar *pv;
  const PetscScalar *xv;
  KSPConvergedReason reason;
  int flag;
  (void)tol;
  if (S == NULL || S->content == NULL) return SUNLS_MEM_NULL;
  c    = CONTENT(S);
  flag = CheckMatrix(c, A);
  if (flag == SUNLS_SUCCESS) flag = CheckSolveVectors(c, x, b);
  if (flag == SUNLS_SUCCESS && !c->factored) flag = SUNLS_ILL_INPUT;
  flag = AgreeFlag(c->comm, flag, NULL); /* KSPSolve is collective */
  if (flag != SUNLS_SUCCESS) {
    c->last_flag = flag;
    return flag;
  }
  xd = N_VGetArrayPointer(x);
  bd = N_VGetArrayPointer(b);
  if (VecGetArray(c->pb, &pv) != 0) goto petsc_fail;
  if (c->nloc > 0) memcpy(pv, bd + (c->subdomain ? 0 : c->rstart), (size_t)c->nloc * sizeof *pv);
  if (VecRestoreArray(c->pb, &pv) != 0) goto petsc_fail;
  if (KSPSolve(c->ksp, c->pb, c->px) != 0) goto petsc_fail;
  if (KSPGetConvergedReason(c->ksp, &reason) != 0 || reason < 0) goto petsc_fail;
  if (VecGetArrayRead(c->px, &xv) != 0) goto petsc_fail;
  flag = SolutionOut(c, xv, xd);
  if (VecRestoreArrayRead(c->px, &xv) != 0) goto petsc_fail;
  c->last_flag = flag;
  return flag;
petsc_fail:
  c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  return SUNLS_PACKAGE_FAIL_UNREC;
}

static sunindextype LastFlag(SUNLinearSolver S)
{
  if (S == NULL || S->content == NULL) return -1;
  return CONTENT(S)->last_flag;
}

/* Lignum's own arrays (PETSc's and MUMPS' memory is not counted): the
 * pattern copies, local CSR and global indices as integers, the local
 * values as reals. */
static int Space(SUNLinearSolver S, long int *lenrw, long int *leniw)
{
  const PetscLUContent *c;
  long int nl;
  if (S == NULL || S->content == NULL || lenrw == NULL || leniw == NULL)
    return SUNLS_MEM_NULL;
  c      = CONTENT(S);
  nl     = c->ia != NULL ? (long int)c->ia[c->nloc] : 0;
  *lenrw = nl;
  *leniw = (long int)(c->nA + 1 + c->nnz) + (c->ia != NULL ? (long int)c->nloc + 1 : 0) +
           2 * nl + (c->counts != NULL ? 2L * c->size : 0) +
           (c->gidx != NULL ? (long int)c->nA : 0);
  return SUNLS_SUCCESS;
}

/* =============================================================================
 * PETSc's initialisation, the solver's shell, Free
 * ===========================================================================*/

/* PETSc initialised (by Lignum if nobody did; collective over
 * PETSC_COMM_WORLD then), and the solver counted. MPI must be initialised.
 * Returns 0, or reports and returns -1 (nothing counted). */
static int AcquirePetsc(const char *func)
{
  int mpi_init = 0;
  PetscBool done = PETSC_FALSE;
  if (MPI_Initialized(&mpi_init) != MPI_SUCCESS || !mpi_init) {
    Report(func,
              "MPI is not initialised: call MPI_Init before creating the solver.");
    return -1;
  }
  if (PetscInitialized(&done) != 0) done = PETSC_FALSE;
  if (!done) {
    /* PETSc's signal handler would take over the application's */
    if (PetscOptionsSetValue(NULL, "-no_signal_handler", NULL) != 0 ||
        PetscInitializeNoArguments() != 0) {
      Report(func, "PETSc could not be initialised.");
      return -1;
    }
    lgn_petsc_initialised_here = 1;
  }
  lgn_petsc_nsolvers++;
  return 0;
}

/* One solver fewer: the last one finalises PETSc if Lignum initialised it. */
static void ReleasePetsc(void)
{
  if (--lgn_petsc_nsolvers == 0 && lgn_petsc_initialised_here) {
    (void)PetscFinalize();
    lgn_petsc_initialised_here = 0;
  }
}

static int Free(SUNLinearSolver S);

/* The solver with its operations and an empty content (the defaults of
 * both modes), or NULL (reported) when memory is refused. Local. */
static SUNLinearSolver NewSolver(SUNContext sunctx, const char *func)
{
  SUNLinearSolver S = SUNLinSolNewEmpty(sunctx);
  PetscLUContent *c;
  if (S == NULL) {
    Report(func, MSG_MEM_FAIL);
    return NULL;
  }
  S->ops->gettype    = GetType;
  S->ops->getid      = GetID;
  S->ops->initialize = Initialize;
  S->ops->setup      = PetscLUSetup;
  S->ops->solve      = PetscLUSolve;
  S->ops->lastflag   = LastFlag;
  S->ops->space      = Space;
  S->ops->free       = Free;
  c = (PetscLUContent *)calloc(1, sizeof *c);
  if (c == NULL) {
    SUNLinSolFreeEmpty(S);
    Report(func, MSG_MEM_FAIL);
    return NULL;
  }
  S->content    = c;
  c->comm       = MPI_COMM_NULL;
  c->sparsetype = -1;
  c->last_flag  = SUNLS_SUCCESS;
  c->icntl14    = LGN_PETSC_ICNTL14_FIRST;
  return S;
}

static int Free(SUNLinearSolver S)
{
  if (S == NULL) return SUNLS_SUCCESS;
  if (S->content != NULL) {
    PetscLUContent *c = CONTENT(S);
    (void)KSPDestroy(&c->ksp);
    (void)MatDestroy(&c->P);
    (void)VecDestroy(&c->pb);
    (void)VecDestroy(&c->px);
    FreePattern(c);
    free(c->counts);
    free(c->displs);
    free(c->gidx);
    if (c->owns_comm) (void)MPI_Comm_free(&c->comm);
    free(c);
    S->content = NULL;
    ReleasePetsc();
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

/* =============================================================================
 * Constructors
 * ===========================================================================*/

SUNLinearSolver LGNLinSol_PETSc(N_Vector y, SUNMatrix A, MPI_Comm comm, SUNContext sunctx)
{
  SUNLinearSolver S;
  PetscLUContent *c;
  sunindextype n;
  N_Vector_ID id;
  PetscInt nloc = PETSC_DECIDE, nglob;
  int rank = 0, size = 1, r, nl;

  if (y == NULL || A == NULL || sunctx == NULL) {
    Report(__func__, "%s = NULL illegal.",
              y == NULL ? "y" : A == NULL ? "A" : "sunctx");
    return NULL;
  }
  if (comm == MPI_COMM_NULL) {
    Report(__func__, "comm = MPI_COMM_NULL illegal.");
    return NULL;
  }
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE) {
    Report(__func__,
              "A must be a SUNSparseMatrix (its matrix ID is %d).", (int)SUNMatGetID(A));
    return NULL;
  }
  n = SUNSparseMatrix_Rows(A);
  if (SUNSparseMatrix_Columns(A) != n || n < 1) {
    Report(__func__,
              "A must be square and not empty (it is %lld x %lld).", (long long)n,
              (long long)SUNSparseMatrix_Columns(A));
    return NULL;
  }
  if (n > (sunindextype)PETSC_MAX_INT) {
    Report(__func__,
              "A is %lld x %lld, beyond PETSc's index range (PetscInt).", (long long)n,
              (long long)n);
    return NULL;
  }
  id = N_VGetVectorID(y);
  if (id != SUNDIALS_NVEC_SERIAL && id != SUNDIALS_NVEC_OPENMP &&
      id != SUNDIALS_NVEC_PTHREADS) {
    Report(__func__,
              "y must be a serial, OpenMP or Pthreads vector (its vector ID is %d).", (int)id);
    return NULL;
  }
  if (N_VGetLength(y) != n) {
    Report(__func__, "y has length %lld but A is %lld x %lld.",
              (long long)N_VGetLength(y), (long long)n, (long long)n);
    return NULL;
  }
  if (AcquirePetsc(__func__) != 0) return NULL;
  S = NewSolver(sunctx, __func__);
  if (S == NULL) {
    ReleasePetsc();
    return NULL;
  }
  c       = CONTENT(S); /* Free releases whatever follows */
  c->comm = comm;
  c->N    = n;
  c->nA   = n;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  c->rank   = rank;
  c->size   = size;
  nglob     = (PetscInt)n;
  c->counts = (int *)calloc((size_t)size, sizeof *c->counts);
  c->displs = (int *)calloc((size_t)size, sizeof *c->displs);
  if (c->counts == NULL || c->displs == NULL ||
      PetscSplitOwnership(comm, &nloc, &nglob) != 0) {
    Free(S);
    Report(__func__, MSG_MEM_FAIL);
    return NULL;
  }
  nl = (int)nloc;
  MPI_Allgather(&nl, 1, MPI_INT, c->counts, 1, MPI_INT, comm);
  for (r = 1; r < size; r++) c->displs[r] = c->displs[r - 1] + c->counts[r - 1];
  c->nloc   = nloc;
  c->rstart = (PetscInt)c->displs[rank];
  return S;
}

/* y's communicator: y must be an N_Vector_Parallel or MPIPlusX. Local
 * (a rank without such a y has no communicator to tell the others on):
 * 0, or reported and -1. */
static int OwnedPartComm(N_Vector y, const char *func, MPI_Comm *comm)
{
  N_Vector_ID id;
  void *pc;
  int mpi_init = 0;
  if (y == NULL) {
    Report(func, "y = NULL illegal.");
    return -1;
  }
  id = N_VGetVectorID(y);
  if (!IsOwnedPartType(y)) {
    Report(func,
           "y must be an N_Vector_Parallel or MPIPlusX vector of this rank's owned part (its "
           "vector ID is %d%s); LGNLinSol_PETSc takes a serial y and a whole matrix.",
           (int)id, id == SUNDIALS_NVEC_SERIAL ? ", serial" : "");
    return -1;
  }
  if (MPI_Initialized(&mpi_init) != MPI_SUCCESS || !mpi_init) {
    Report(func, "MPI is not initialised: call MPI_Init before creating the solver.");
    return -1;
  }
  pc = N_VGetCommunicator(y);
  if (pc == NULL || *(MPI_Comm *)pc == MPI_COMM_NULL) {
    Report(func, "y has no communicator.");
    return -1;
  }
  *comm = *(MPI_Comm *)pc;
  return 0;
}

/* The arguments that can be checked on this rank alone: 1 if fine, else
 * reported and 0. */
static int SubdomainArgsOk(N_Vector y, SUNMatrix A, const sunindextype *global_index,
                           SUNContext sunctx, const char *func)
{
  const sunindextype n_own = LocalLength(y);
  sunindextype n_loc;
  if (A == NULL || global_index == NULL || sunctx == NULL) {
    Report(func, "%s = NULL illegal.",
           A == NULL ? "A" : global_index == NULL ? "global_index" : "sunctx");
    return 0;
  }
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE) {
    Report(func, "A must be a SUNSparseMatrix (its matrix ID is %d).", (int)SUNMatGetID(A));
    return 0;
  }
  n_loc = SUNSparseMatrix_Rows(A);
  if (SUNSparseMatrix_Columns(A) != n_loc || n_loc < 1 || n_loc < n_own) {
    Report(func,
           "A must be square, n_loc x n_loc with n_loc >= 1 and n_loc >= n_own = %lld, the "
           "local length of y (it is %lld x %lld).",
           (long long)n_own, (long long)n_loc, (long long)SUNSparseMatrix_Columns(A));
    return 0;
  }
  if (n_loc > (sunindextype)PETSC_MAX_INT) {
    Report(func, "A is %lld x %lld, beyond PETSc's index range (PetscInt).", (long long)n_loc,
           (long long)n_loc);
    return 0;
  }
  if (n_own > 0 && N_VGetArrayPointer(y) == NULL) {
    Report(func, "y has no array on this rank (N_VGetArrayPointer is NULL).");
    return 0;
  }
  return 1;
}

/* lo = the first global index this rank owns (the exclusive prefix sum of
 * n_own over the ranks), N = the sum. Collective; 0, or -1 (reported). */
static int OwnedRange(MPI_Comm comm, sunindextype n_own, sunindextype *lo, sunindextype *N,
                      const char *func)
{
  long long own = (long long)n_own, first = 0, all = 0;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (MPI_Exscan(&own, &first, 1, MPI_LONG_LONG, MPI_SUM, comm) != MPI_SUCCESS ||
      MPI_Allreduce(&own, &all, 1, MPI_LONG_LONG, MPI_SUM, comm) != MPI_SUCCESS) {
    Report(func, "MPI_Exscan or MPI_Allreduce failed.");
    return -1;
  }
  *lo = rank == 0 ? 0 : (sunindextype)first; /* MPI_Exscan leaves rank 0's alone */
  *N  = (sunindextype)all;
  return 0;
}

/* global_index: each owned index lo ... lo + n_own - 1 once (anywhere),
 * the others (ghosts) in [0, N) outside the owned range. This rank's
 * entries; 1 if fine, else reported and 0. */
static int GlobalIndexOk(const sunindextype *gi, sunindextype n_own, sunindextype n_loc,
                         sunindextype lo, sunindextype N, const char *func)
{
  sunindextype k, seen = 0;
  char *mark;
  if (N < 1 || N > (sunindextype)PETSC_MAX_INT) {
    Report(func, "The ranks own %lld unknowns in all (y's local lengths): 1 to %lld needed.",
           (long long)N, (long long)PETSC_MAX_INT);
    return 0;
  }
  mark = (char *)calloc((size_t)(n_own > 0 ? n_own : 1), 1);
  if (mark == NULL) {
    Report(func, "A memory request failed.");
    return 0;
  }
  for (k = 0; k < n_loc; k++) {
    if (gi[k] < 0 || gi[k] >= N) {
      Report(func, "global_index[%lld] = %lld is outside [0, %lld).", (long long)k,
             (long long)gi[k], (long long)N);
      break;
    }
    if (gi[k] >= lo && gi[k] < lo + n_own) {
      if (mark[gi[k] - lo]) {
        Report(func, "global_index[%lld] = %lld: an owned index given twice.", (long long)k,
               (long long)gi[k]);
        break;
      }
      mark[gi[k] - lo] = 1;
      seen++;
    }
  }
  free(mark);
  if (k < n_loc) return 0;
  if (seen != n_own) {
    Report(func,
           "global_index holds %lld of this rank's %lld owned unknowns %lld .. %lld (the "
           "owned lengths of the ranks before it, summed): each must appear once.",
           (long long)seen, (long long)n_own, (long long)lo, (long long)(lo + n_own - 1));
    return 0;
  }
  return 1;
}

/* The subdomain solver's content: comm (taken over), sizes, global_index
 * copied. Local; 1, or reported and 0. */
static int SubdomainContent(PetscLUContent *c, MPI_Comm comm, sunindextype n_own,
                            sunindextype n_loc, sunindextype lo, sunindextype N,
                            const sunindextype *global_index, const char *func)
{
  sunindextype k;
  c->comm      = comm;
  c->owns_comm = 1;
  c->subdomain = 1;
  MPI_Comm_rank(comm, &c->rank);
  MPI_Comm_size(comm, &c->size);
  c->N      = N;
  c->nA     = n_loc;
  c->rstart = (PetscInt)lo;
  c->nloc   = (PetscInt)n_own;
  c->gidx   = (PetscInt *)malloc((size_t)n_loc * sizeof *c->gidx);
  if (c->gidx == NULL) {
    Report(func, MSG_MEM_FAIL);
    return 0;
  }
  for (k = 0; k < n_loc; k++) c->gidx[k] = (PetscInt)global_index[k];
  return 1;
}

SUNLinearSolver LGNLinSol_PETScSubdomain(N_Vector y, SUNMatrix A,
                                         const sunindextype *global_index, SUNContext sunctx)
{
  SUNLinearSolver S = NULL;
  MPI_Comm ycomm, comm = MPI_COMM_NULL;
  sunindextype n_own, n_loc, lo = 0, N = 0;
  int ok, petsc = 0;

  if (OwnedPartComm(y, __func__, &ycomm) != 0) return NULL;
  /* from here on every failure is agreed on over y's communicator */
  ok = SubdomainArgsOk(y, A, global_index, sunctx, __func__);
  if (!AllOk(ycomm, ok, __func__)) return NULL;
  n_own = LocalLength(y);
  n_loc = SUNSparseMatrix_Rows(A);
  if (OwnedRange(ycomm, n_own, &lo, &N, __func__) != 0) return NULL;
  ok = GlobalIndexOk(global_index, n_own, n_loc, lo, N, __func__);
  if (!AllOk(ycomm, ok, __func__)) return NULL;

  if (MPI_Comm_dup(ycomm, &comm) != MPI_SUCCESS) {
    Report(__func__, "MPI_Comm_dup failed.");
    return NULL;
  }
  petsc = AcquirePetsc(__func__) == 0;
  if (petsc) S = NewSolver(sunctx, __func__);
  ok = S != NULL &&
       SubdomainContent(CONTENT(S), comm, n_own, n_loc, lo, N, global_index, __func__);
  if (AllOk(comm, ok, __func__)) return S;
  /* refused on some rank: every rank undoes what it did (Free frees the
   * communicator once the content has it, and releases PETSc) */
  if (S == NULL || !CONTENT(S)->owns_comm) (void)MPI_Comm_free(&comm);
  if (S != NULL) Free(S);
  else if (petsc) ReleasePetsc();
  return NULL;
}
