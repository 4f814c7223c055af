/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The direct solve through PETSc (LGNLinSol_PETSc, lignum_petsc.h): a
 * SUNLinearSolver over a KSP of type KSPPREONLY with PCLU and
 * MATSOLVERMUMPS, for a SUNSparseMatrix (CSR or CSC) held identically on
 * every rank of a communicator.
 *
 *   - Pattern. At each setup A's format and index arrays are compared with
 *     a copy of those of the last setup (collectively: a new pattern on
 *     any rank is a new pattern on all). A new pattern makes this rank's
 *     rows of A in CSR, columns sorted, with the position of each entry in
 *     A's data (perm: the transposition of a CSC matrix is done once per
 *     pattern), a new MATAIJ (MATSEQAIJ on one rank, MATMPIAIJ with PETSc's
 *     split of the rows on several) preallocated from them, and a new KSP:
 *     MUMPS analyses the pattern at the next factorisation.
 *   - Values. Every setup gathers this rank's values through perm and
 *     inserts them row by row (MatSetValues, INSERT_VALUES, with
 *     MAT_NEW_NONZERO_LOCATION_ERR set); the pattern is then the same, and
 *     PCSetUp does only MUMPS' numerical factorisation
 *     (SAME_NONZERO_PATTERN: the analysis is reused).
 *   - Singular matrices: null pivot detection (ICNTL(24) = 1, ICNTL(13) =
 *     1 as PETSc sets it with -mat_mumps_icntl_24, CNTL(3) the relative
 *     threshold). Null pivots (INFOG(28) > 0) or a failed factorisation
 *     (PCGetFailedReason, INFOG(1) < 0) make the setup return
 *     SUNLS_LUFACT_FAIL. With null pivots, one solve with ICNTL(25) = 1
 *     returns MUMPS' first null-space vector; 1 + the index of its largest
 *     entry is the last flag (the unknown Lignum's diagnostics name).
 *   - Solve: this rank's part of b into PETSc's vector, KSPSolve, and the
 *     parts of the solution gathered to every rank (MPI_Allgatherv).
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
  MPI_Comm comm;          /* the user's communicator (not duplicated: PETSc
                             duplicates it for its objects)                 */
  int rank, size;
  sunindextype N;
  /* the pattern of the last setup: format, nnz, copies of A's arrays */
  int sparsetype;         /* CSR_MAT or CSC_MAT; -1: none yet              */
  sunindextype nnz;
  sunindextype *ptr, *ind;
  /* this rank's rows rstart .. rstart+nloc-1 in CSR, columns sorted */
  PetscInt rstart, nloc;
  PetscInt *ia, *ja;      /* local row pointers (nloc+1), columns          */
  sunindextype *perm;     /* position in A's data of each local entry      */
  PetscScalar *va;        /* the local values of this setup                */
  int *counts, *displs;   /* rows of each rank (MPI_Allgatherv)            */
  Mat P;                  /* PETSc's copy of A                             */
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

static void FreePattern(PetscLUContent *c)
{
  free(c->ptr);
  free(c->ind);
  free(c->ia);
  free(c->ja);
  free(c->perm);
  free(c->va);
  c->ptr = c->ind = c->perm = NULL;
  c->ia = c->ja = NULL;
  c->va         = NULL;
  c->sparsetype = -1;
  c->nnz        = 0;
}

/* The local CSR of A's new pattern (this rank's rows), and copies of A's
 * index arrays. Returns SUNLS_SUCCESS or SUNLS_MEM_FAIL (then no pattern). */
static int BuildPattern(PetscLUContent *c, SUNMatrix A)
{
  const sunindextype N = c->N, np = SUNSparseMatrix_NP(A);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
  const sunindextype nnz = ptr[np];
  const sunindextype r0 = c->rstart, r1 = c->rstart + c->nloc;
  sunindextype i, k, p, nl = 0;

  FreePattern(c);
  c->ptr = (sunindextype *)malloc((size_t)(np + 1) * sizeof *c->ptr);
  c->ind = (sunindextype *)malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *c->ind);
  c->ia  = (PetscInt *)calloc((size_t)c->nloc + 1, sizeof *c->ia);
  if (c->ptr == NULL || c->ind == NULL || c->ia == NULL) goto fail;
  memcpy(c->ptr, ptr, (size_t)(np + 1) * sizeof *ptr);
  memcpy(c->ind, ind, (size_t)nnz * sizeof *ind);

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
  if (c->ja == NULL || c->perm == NULL || c->va == NULL) goto fail;

  if (SUNSparseMatrix_SparseType(A) == CSR_MAT) {
    for (i = r0; i < r1; i++)
      for (p = ptr[i], k = c->ia[i - r0]; p < ptr[i + 1]; p++, k++) {
        c->ja[k]   = (PetscInt)ind[p];
        c->perm[k] = p;
      }
  } else { /* the transpose of the local rows: column by column, so sorted */
    PetscInt *next = (PetscInt *)malloc((size_t)(c->nloc > 0 ? c->nloc : 1) * sizeof *next);
    if (next == NULL) goto fail;
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
  c->sparsetype = (int)SUNSparseMatrix_SparseType(A);
  c->nnz        = nnz;
  return SUNLS_SUCCESS;
fail:
  FreePattern(c);
  return SUNLS_MEM_FAIL;
}

/* A new PETSc matrix for the local CSR, and a new KSP for it (the analysis
 * is redone at the next factorisation). */
static PetscErrorCode NewPetscObjects(PetscLUContent *c)
{
  PC pc;
  Mat F;
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->ksp));
  PetscCall(MatDestroy(&c->P));
  PetscCall(VecDestroy(&c->pb));
  PetscCall(VecDestroy(&c->px));
  PetscCall(MatCreate(c->comm, &c->P));
  PetscCall(MatSetSizes(c->P, c->nloc, c->nloc, (PetscInt)c->N, (PetscInt)c->N));
  PetscCall(MatSetType(c->P, MATAIJ));
  /* both are called, the one of the other type does nothing */
  PetscCall(MatSeqAIJSetPreallocationCSR(c->P, c->ia, c->ja, NULL));
  PetscCall(MatMPIAIJSetPreallocationCSR(c->P, c->ia, c->ja, NULL));
  PetscCall(MatSetOption(c->P, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(MatCreateVecs(c->P, &c->px, &c->pb));

  PetscCall(KSPCreate(c->comm, &c->ksp));
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

/* This setup's values into PETSc's matrix, row by row. */
static PetscErrorCode SetValues(PetscLUContent *c, SUNMatrix A)
{
  const sunrealtype *data = SUNSparseMatrix_Data(A);
  PetscInt i, k;
  PetscFunctionBeginUser;
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

/* After null pivots on several ranks: MUMPS computes null-space vectors
 * only with a centralised solution (INFOG(1) = -37 with PETSc's
 * distributed one), so each rank factors its own full copy of A on
 * PETSC_COMM_SELF (the same on every rank) and takes the column there.
 * Only on this failure path; PETSc's error messages are silenced (the
 * column is then unknown, -1). */
static PetscInt NullColumnOnOneRank(const PetscLUContent *c, SUNMatrix A)
{
  PetscLUContent seq;
  PetscInt col = -1, nnull = 0, infog = 0;
  PetscBool failed = PETSC_TRUE;
  memset(&seq, 0, sizeof seq);
  seq.comm       = PETSC_COMM_SELF;
  seq.size       = 1;
  seq.N          = c->N;
  seq.nloc       = (PetscInt)c->N;
  seq.sparsetype = -1;
  seq.icntl14    = c->icntl14;
  if (PetscPushErrorHandler(PetscReturnErrorHandler, NULL) != 0) return -1;
  if (BuildPattern(&seq, A) == SUNLS_SUCCESS && NewPetscObjects(&seq) == 0 &&
      SetValues(&seq, A) == 0 && Factor(&seq, &nnull, &infog, &failed) == 0 && nnull > 0 &&
      !failed && NullColumn(&seq, &col) != 0)
    col = -1;
  (void)PetscPopErrorHandler();
  (void)KSPDestroy(&seq.ksp);
  (void)MatDestroy(&seq.P);
  (void)VecDestroy(&seq.pb);
  (void)VecDestroy(&seq.px);
  FreePattern(&seq);
  return nnull > 0 && !failed ? col : -1;
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

static int CheckMatrix(const PetscLUContent *c, SUNMatrix A)
{
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE || SUNSparseMatrix_Rows(A) != c->N ||
      SUNSparseMatrix_Columns(A) != c->N)
    return SUNLS_ILL_INPUT;
  return SUNLS_SUCCESS;
}

static int PetscLUSetup(SUNLinearSolver S, SUNMatrix A)
{
  PetscLUContent *c;
  int flag, newpat, anynew;
  PetscInt nnull = 0, col = -1, infog = 0;
  PetscBool failed = PETSC_FALSE;
  if (S == NULL || S->content == NULL || A == NULL) return SUNLS_MEM_NULL;
  c           = CONTENT(S);
  c->factored = SUNFALSE;
  flag        = CheckMatrix(c, A);
  if (flag != SUNLS_SUCCESS) {
    c->last_flag = flag;
    return flag;
  }
  newpat = !SamePattern(c, A);
  if (MPI_Allreduce(&newpat, &anynew, 1, MPI_INT, MPI_LOR, c->comm) != MPI_SUCCESS) {
    c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (anynew) {
    flag = BuildPattern(c, A);
    if (flag == SUNLS_SUCCESS && NewPetscObjects(c) != 0) flag = SUNLS_PACKAGE_FAIL_UNREC;
    if (flag != SUNLS_SUCCESS) {
      FreePattern(c); /* a new pattern at the next setup */
      c->last_flag = flag;
      return flag;
    }
  }
  for (;;) {
    if (SetValues(c, A) != 0 || Factor(c, &nnull, &infog, &failed) != 0) {
      FreePattern(c);
      c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
    /* MUMPS ran short of workspace (-8, -9, -11 .. -15: more pivots were
     * delayed than its analysis estimated): twice the increase, with a
     * new analysis, up to LGN_PETSC_ICNTL14_MAX % */
    if (!(infog == -8 || infog == -9 || (infog <= -11 && infog >= -15)) ||
        2 * c->icntl14 > LGN_PETSC_ICNTL14_MAX)
      break;
    c->icntl14 *= 2;
    if (NewPetscObjects(c) != 0) {
      FreePattern(c);
      c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
  }
  if (nnull > 0 && !failed) {
    if (c->size == 1) {
      if (NullColumn(c, &col) != 0) col = -1;
    } else {
      col = NullColumnOnOneRank(c, A);
    }
  }
  if (nnull > 0 || failed) {
    c->last_flag = col >= 0 ? (sunindextype)col + 1 : 0;
    return SUNLS_LUFACT_FAIL;
  }
  c->last_flag = SUNLS_SUCCESS;
  c->factored  = SUNTRUE;
  return SUNLS_SUCCESS;
}

static int PetscLUSolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                        sunrealtype tol)
{
  PetscLUContent *c;
  sunrealtype *xd, *bd;
  PetscScalar *pv;
  const PetscScalar *xv;
  KSPConvergedReason reason;
  int flag = SUNLS_SUCCESS;
  (void)tol;
  if (S == NULL || S->content == NULL || A == NULL || x == NULL || b == NULL)
    return SUNLS_MEM_NULL;
  c = CONTENT(S);
  if (CheckMatrix(c, A) != SUNLS_SUCCESS || !c->factored || N_VGetLength(x) != c->N ||
      N_VGetLength(b) != c->N)
    flag = SUNLS_ILL_INPUT;
  xd = N_VGetArrayPointer(x);
  bd = N_VGetArrayPointer(b);
  if (flag == SUNLS_SUCCESS && (xd == NULL || bd == NULL)) flag = SUNLS_MEM_FAIL;
  if (flag != SUNLS_SUCCESS) {
    c->last_flag = flag;
    return flag;
  }
  if (VecGetArray(c->pb, &pv) != 0) goto petsc_fail;
  memcpy(pv, bd + c->rstart, (size_t)c->nloc * sizeof *pv);
  if (VecRestoreArray(c->pb, &pv) != 0) goto petsc_fail;
  if (KSPSolve(c->ksp, c->pb, c->px) != 0) goto petsc_fail;
  if (KSPGetConvergedReason(c->ksp, &reason) != 0 || reason < 0) goto petsc_fail;
  if (VecGetArrayRead(c->px, &xv) != 0) goto petsc_fail;
  if (c->size == 1)
    memcpy(xd, xv, (size_t)c->N * sizeof *xd);
  else
    flag = MPI_Allgatherv(xv, c->counts[c->rank], MPI_DOUBLE, xd, c->counts, c->displs,
                          MPI_DOUBLE, c->comm) == MPI_SUCCESS
               ? SUNLS_SUCCESS
               : SUNLS_PACKAGE_FAIL_UNREC;
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
 * pattern copies and local CSR as integers, the local values as reals. */
static int Space(SUNLinearSolver S, long int *lenrw, long int *leniw)
{
  const PetscLUContent *c;
  long int nl;
  if (S == NULL || S->content == NULL || lenrw == NULL || leniw == NULL)
    return SUNLS_MEM_NULL;
  c      = CONTENT(S);
  nl     = c->ia != NULL ? (long int)c->ia[c->nloc] : 0;
  *lenrw = nl;
  *leniw = (long int)(c->N + 1 + c->nnz) + (long int)c->nloc + 1 + 2 * nl +
           2L * c->size;
  return SUNLS_SUCCESS;
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
    free(c);
    S->content = NULL;
    if (--lgn_petsc_nsolvers == 0 && lgn_petsc_initialised_here) {
      (void)PetscFinalize();
      lgn_petsc_initialised_here = 0;
    }
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

/* =============================================================================
 * Constructor
 * ===========================================================================*/

/* PETSc initialised (by Lignum if nobody did); MPI must be. Returns 0 or
 * reports and returns -1. */
static int EnsurePetsc(const char *func)
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
  return 0;
}

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
  if (EnsurePetsc(__func__) != 0) return NULL;
  lgn_petsc_nsolvers++; /* from here on, Free balances it */

  S = SUNLinSolNewEmpty(sunctx);
  if (S == NULL) {
    Report(__func__, MSG_MEM_FAIL);
    if (--lgn_petsc_nsolvers == 0 && lgn_petsc_initialised_here) {
      (void)PetscFinalize();
      lgn_petsc_initialised_here = 0;
    }
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
    Report(__func__, MSG_MEM_FAIL);
    if (--lgn_petsc_nsolvers == 0 && lgn_petsc_initialised_here) {
      (void)PetscFinalize();
      lgn_petsc_initialised_here = 0;
    }
    return NULL;
  }
  S->content    = c; /* Free releases whatever follows */
  c->comm       = comm;
  c->N          = n;
  c->sparsetype = -1;
  c->last_flag  = SUNLS_SUCCESS;
  c->icntl14    = LGN_PETSC_ICNTL14_FIRST;
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
