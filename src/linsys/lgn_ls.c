/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The bridge to SUNDIALS' SUNLinearSolver: LGNSetLinearSolver,
 * LGNSetOwnKLUSolves and the getters of its counters, the check of matrix
 * and solver against the problem size, setup (factorisation) and solve.
 * The iteration matrix is filled by lgn_assemble.c (dense) or
 * lgn_assemble_sparse.c (SUNSparseMatrix, CSC or CSR, with SUNLinSol_KLU).
 * With KLU, and when switched on (off by default: it reads layouts that
 * KLU and SUNDIALS do not publish, so only the versions of
 * lgnKluCopySupported are accepted), the solves use a copy of KLU's
 * factors (lgn_klu_solve.c), into which Lignum also refactors (CSC).
 * Lignum's own dense LU (LGNLinSol_Dense, lgn_dense_lu.c) is checked
 * against the problem size as SUNLinSol_Dense is. A sparse matrix goes with
 * SUNLinSol_KLU or a custom direct solver (LGNLinSol_PETSc, lgn_petsc.c in
 * the library lignum_petsc), which checks the size at its setup.
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include <sundials/sundials_version.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_dense_lu.h"
#include "lgn_impl.h"
#include "lgn_klu_solve.h"
#include "lgn_sparse.h"
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

int LGNSetLinearSolver(void *lgn_mem, SUNLinearSolver LS, SUNMatrix A)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (LS == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "LS = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (SUNLinSolGetType(LS) == SUNLINEARSOLVER_ITERATIVE) {
    if (A != NULL) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "A matrix-free iterative solver takes A = NULL: Lignum applies "
                "the iteration matrix itself (its own assembled copy).");
      return LGN_ILL_INPUT;
    }
    return lgnKrylovAttach(mem, LS);
  }
  if (SUNLinSolGetType(LS) != SUNLINEARSOLVER_DIRECT) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The linear solver is neither direct (matrix-based) nor "
              "matrix-free iterative (SUNLINEARSOLVER_ITERATIVE: SPGMR, "
              "SPFGMR, SPBCGS, SPTFQMR); matrix-embedded and matrix-based "
              "iterative solvers are not supported.");
    return LGN_LS_MISMATCH;
  }
  if (A == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "A = NULL illegal with a direct linear solver: pass the "
              "SUNDenseMatrix or SUNSparseMatrix it factors (only matrix-free "
              "iterative solvers such as SUNLinSol_SPGMR take A = NULL).");
    return LGN_ILL_INPUT;
  }
  if (lgnMatID(A) == SUNMATRIX_SPARSE) {
    /* another direct solver of sparse matrices, such as LGNLinSol_PETSc
     * (library lignum_petsc): a custom one that is not Lignum's dense LU */
    if (SUNLinSolGetID(LS) != SUNLINEARSOLVER_CUSTOM || lgnDenseLUSize(LS) >= 0) {
#if defined(LGN_HAVE_KLU)
      if (SUNLinSolGetID(LS) != SUNLINEARSOLVER_KLU) {
        LGN_ERROR(mem, LGN_LS_MISMATCH,
                  "A sparse matrix needs the KLU linear solver (SUNLinSol_KLU)"
                  " or a custom direct sparse solver such as LGNLinSol_PETSc.");
        return LGN_LS_MISMATCH;
      }
#else
      LGN_ERROR(mem, LGN_LS_MISMATCH,
                "Sparse matrices need Lignum built with LGN_ENABLE_KLU=ON "
                "(SUNLinSol_KLU), or a custom direct sparse solver such as "
                "LGNLinSol_PETSc.");
      return LGN_LS_MISMATCH;
#endif
    }
  } else if (lgnMatID(A) != SUNMATRIX_DENSE) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "Matrix type %d not supported: use a SUNDenseMatrix, or a "
              "SUNSparseMatrix with SUNLinSol_KLU.",
              (int)lgnMatID(A));
    return LGN_LS_MISMATCH;
  } else if (SUNLinSolGetID(LS) == SUNLINEARSOLVER_KLU) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "SUNLinSol_KLU needs a SUNSparseMatrix, not a dense one.");
    return LGN_LS_MISMATCH;
  }
  if (mem->krylov) lgnFreeKrylov(mem, SUNFALSE); /* Lignum's A, vectors */
  mem->krylov = SUNFALSE;
  lgnFreeRedundancySolver(mem); /* a stand-in for the old solver */
  mem->LS = LS;
  mem->A  = A;
  /* the model matrices are reallocated for A's type at the next solve; the
   * copy of the old solver's factors goes with them */
  lgnInvalidate(mem, LGN_CHANGE_LINSOL);
  return LGN_SUCCESS;
}

#define LGN_STR_(x) #x
#define LGN_STR(x)  LGN_STR_(x)

/* Exactly the versions of lgn_klu_solve.h's LGN_KLU_COPY_* (the reason
 * names the first library whose version differs). */
int lgnKluCopySupported(int klu_major, int klu_minor, int sun_major,
                        int sun_minor, const char **why)
{
  const char *reason = NULL;
  if (klu_major != LGN_KLU_COPY_KLU_MAJOR || klu_minor != LGN_KLU_COPY_KLU_MINOR)
    reason = "KLU's internal factor layout (klu_l_numeric, klu_l_symbolic, "
             "the packed columns) is known for KLU "
             LGN_STR(LGN_KLU_COPY_KLU_MAJOR) "." LGN_STR(LGN_KLU_COPY_KLU_MINOR)
             " only";
  else if (sun_major != LGN_KLU_COPY_SUN_MAJOR ||
           sun_minor != LGN_KLU_COPY_SUN_MINOR)
    reason = "SUNLinSol_KLU's private content (its klu_solver) is known for "
             "SUNDIALS " LGN_STR(LGN_KLU_COPY_SUN_MAJOR) "."
             LGN_STR(LGN_KLU_COPY_SUN_MINOR) " only";
  if (why != NULL) *why = reason != NULL ? reason : "supported";
  return reason == NULL;
}

/* Whether the copy of KLU's factors can be switched on: Lignum built with
 * KLU, SUNDIALS with 64-bit indices (klu_l_*), and lgnKluCopySupported for
 * the KLU compiled against (KLU has no version call) with the SUNDIALS
 * found at run time and the one compiled against. Else reports why, with
 * the versions found and those supported, and returns LGN_ILL_INPUT. */
static int KluCopyAvailable(LGNMem mem)
{
#if defined(LGN_KLU_COPY)
  int major = -1, minor = -1, patch = -1;
  char label[64];
  const char *why = NULL;
  if (SUNDIALSGetVersionNumber(&major, &minor, &patch, label,
                               (int)sizeof label) != 0)
    major = minor = patch = -1;
  if (lgnKluCopySupported(KLU_MAIN_VERSION, KLU_SUB_VERSION, major, minor,
                          &why) &&
      lgnKluCopySupported(KLU_MAIN_VERSION, KLU_SUB_VERSION,
                          SUNDIALS_VERSION_MAJOR, SUNDIALS_VERSION_MINOR, &why))
    return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "Lignum's solves on a copy of KLU's factors read layouts that "
            "KLU and SUNDIALS do not publish, and %s: found KLU %d.%d.%d "
            "(compiled against) with SUNDIALS %d.%d.%d (run time; compiled "
            "against %d.%d.%d); supported: KLU %d.%d.x with SUNDIALS %d.%d.x. "
            "The setting stays off (KLU's own solves).",
            why, KLU_MAIN_VERSION, KLU_SUB_VERSION, KLU_SUBSUB_VERSION, major,
            minor, patch, SUNDIALS_VERSION_MAJOR, SUNDIALS_VERSION_MINOR,
            SUNDIALS_VERSION_PATCH, LGN_KLU_COPY_KLU_MAJOR,
            LGN_KLU_COPY_KLU_MINOR, LGN_KLU_COPY_SUN_MAJOR,
            LGN_KLU_COPY_SUN_MINOR);
  return LGN_ILL_INPUT;
#elif defined(LGN_HAVE_KLU)
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "Lignum's solves on a copy of KLU's factors need SUNDIALS with "
            "64-bit indices (KLU's klu_l_* interface); this SUNDIALS has "
            "%d-bit sunindextype. The setting stays off (KLU's own solves).",
            (int)(8 * sizeof(sunindextype)));
  return LGN_ILL_INPUT;
#else
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "Lignum was built without KLU (LGN_ENABLE_KLU=OFF): there are no "
            "KLU factors to copy. The setting stays off.");
  return LGN_ILL_INPUT;
#endif
}

int LGNSetOwnKLUSolves(void *lgn_mem, sunbooleantype own)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (own) flag = KluCopyAvailable(mem);
  mem->own_klu_solves = own && flag == LGN_SUCCESS ? SUNTRUE : SUNFALSE;
  if (!mem->own_klu_solves && mem->klu != NULL) {
    /* SUNLinSolSetup and SUNLinSolSolve from now on; the factors of the
     * matrix may be only in the copy (Lignum refactored), so the next
     * step sets the matrix up anew */
    lgnInvalidate(mem, LGN_CHANGE_MATRIX);
    lgnKluCopyFree(&mem->klu);
  } /* else the copy is made at the first solve after the next setup */
  return flag;
}

/* The common part of the getters below: the memory block, and the output
 * argument `name` (out) not NULL. */
static int KluGetter(void *lgn_mem, const char *func, const long int *out,
                     const char *name, LGNMem *mem)
{
  int flag = lgnAccessMem(lgn_mem, func, mem);
  if (flag != LGN_SUCCESS) return flag;
  if (out == NULL) {
    lgnProcessError(*mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNGetNumKLUFactorCopies(void *lgn_mem, long int *ncopies)
{
  LGNMem mem;
  int flag = KluGetter(lgn_mem, __func__, ncopies, "ncopies", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *ncopies = mem->nklu_copy;
  return LGN_SUCCESS;
}

int LGNGetNumKLUValueCopies(void *lgn_mem, long int *nvalues)
{
  LGNMem mem;
  int flag = KluGetter(lgn_mem, __func__, nvalues, "nvalues", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nvalues = mem->nklu_values;
  return LGN_SUCCESS;
}

int LGNGetNumOwnKLURefactors(void *lgn_mem, long int *nrefactors)
{
  LGNMem mem;
  int flag = KluGetter(lgn_mem, __func__, nrefactors, "nrefactors", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nrefactors = mem->nklu_refactor;
  return LGN_SUCCESS;
}

int LGNGetNumOwnKLUSolves(void *lgn_mem, long int *nsolves)
{
  LGNMem mem;
  int flag = KluGetter(lgn_mem, __func__, nsolves, "nsolves", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nsolves = mem->nklu_solve;
  return LGN_SUCCESS;
}

int LGNGetNumKLUFallbacks(void *lgn_mem, long int *npivot, long int *npattern,
                          long int *nnocopy)
{
  LGNMem mem;
  int flag = KluGetter(lgn_mem, __func__, npivot, "npivot", &mem);
  if (flag == LGN_SUCCESS)
    flag = KluGetter(lgn_mem, __func__, npattern, "npattern", &mem);
  if (flag == LGN_SUCCESS)
    flag = KluGetter(lgn_mem, __func__, nnocopy, "nnocopy", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *npivot   = mem->nklu_fallback;
  *npattern = mem->nklu_newpattern;
  *nnocopy  = mem->nklu_nocopy;
  return LGN_SUCCESS;
}

/* GGL (LGN_CONSTR_GGL) is implemented for the BDF family and for the
 * Newmark family with simplified or exact kinematics, with a dense matrix
 * A, without ghost bodies: its iteration matrix has products of M, C_t and
 * B with B^T in the column of the kinematic multiplier, which only the
 * dense assembly forms (lgn_matrix.c), and the ghost bodies' and Krylov
 * paths size their unknowns nv + m. The sigma variant is not derived for
 * it: its corrections are composed on q1 along the Newton path, and where
 * the multiplier's correction would enter that path is a method of its own. */
static int CheckGGL(LGNMem mem)
{
  const char *why = NULL;
  if (mem->constr_index != LGN_CONSTR_GGL || mem->m == 0) return LGN_SUCCESS;
  if (mem->family == LGN_FAMILY_NEWMARK && mem->kinematics == LGN_KINEMATICS_SIGMA)
    why = "the BDF family and the Newmark family with simplified or exact kinematics, "
          "not the sigma variant (LGN_KINEMATICS_SIGMA: its Newton corrections are "
          "composed on the configuration, and the stabilised form is not derived "
          "for that)";
  else if (mem->krylov)
    why = "a dense matrix A only, not a Krylov solver (the column of the kinematic "
          "multiplier holds products of M, C_t and B with B^T, which only the dense "
          "assembly forms)";
  else if (mem->halo != NULL)
    why = "a rank's own bodies only, not with ghost bodies (LGNSetHalo)";
  else if (lgnMatID(mem->A) != SUNMATRIX_DENSE)
    why = "a dense matrix A only (SUNDenseMatrix of nv + 2m rows), not a sparse one "
          "(the column of the kinematic multiplier holds products of M, C_t and B "
          "with B^T, which only the dense assembly forms)";
  if (why == NULL) return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "index = LGN_CONSTR_GGL (LGNSetConstraintIndex) is implemented for %s; "
            "use LGN_CONSTR_INDEX3 or LGN_CONSTR_INDEX2 here.", why);
  return LGN_ILL_INPUT;
}

/* Rows left out as redundant (lgn_redundancy.c): the user's direct solver
 * was made for nv + all m_user rows; a stand-in of its kind is made for
 * the kept rows (and dropped when nothing is left out any more). A matrix
 * of another size is left to the check below. */
static int FitKeptRows(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->nalg;
  const sunindextype nuser = mem->nv + (mem->nalg > mem->m ? 2 : 1) * mem->m_user;
  sunindextype rows;
  if (mem->krylov || mem->A == NULL) return LGN_SUCCESS;
  rows = lgnMatID(mem->A) == SUNMATRIX_SPARSE ? SUNSparseMatrix_Rows(mem->A) : SM_ROWS_D(mem->A);
  if (mem->red_LS != NULL) {
    if (mem->red_nout > 0 && rows == n) return LGN_SUCCESS;
    lgnFreeRedundancySolver(mem);
    rows = lgnMatID(mem->A) == SUNMATRIX_SPARSE ? SUNSparseMatrix_Rows(mem->A) : SM_ROWS_D(mem->A);
  }
  if (mem->red_nout == 0 || rows == n || rows != nuser) return LGN_SUCCESS;
  return lgnAllocRedundancySolver(mem, n);
}

/* Before the first solve: the matrix must be (nv + nalg) x (nv + nalg),
 * nalg = m, or 2m under GGL. */
/* The linear solver and A fit the problem (on this rank). */
static int CheckLinearSolver(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->nalg;
  sunbooleantype sparse;
  sunindextype rows, cols;
  int ret = CheckGGL(mem);
  if (ret != LGN_SUCCESS) return ret;
  if (mem->krylov) { /* Lignum's own A, made for the sizes */
    ret = lgnKrylovCheck(mem);
    if (ret != LGN_SUCCESS) return ret;
  }
  ret = FitKeptRows(mem);
  if (ret != LGN_SUCCESS) return ret;
  sparse = lgnMatID(mem->A) == SUNMATRIX_SPARSE;
  if (mem->halo != NULL && !mem->krylov &&
      (!sparse || SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_CUSTOM)) {
    /* a rank's matrix is its part of a sum: only a solver across ranks
     * can solve with the sum */
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "Ghost bodies (LGNSetHalo) couple the ranks' matrices: use a Krylov "
              "solver (LGNSetLinearSolver(mem, LS, NULL)) or LGNLinSol_PETScSubdomain "
              "with a sparse matrix, not a solver of one rank's matrix.");
    return LGN_LS_MISMATCH;
  }
  rows = sparse ? SUNSparseMatrix_Rows(mem->A) : SM_ROWS_D(mem->A);
  cols = sparse ? SUNSparseMatrix_Columns(mem->A) : SM_COLUMNS_D(mem->A);
  if (rows != n || cols != n) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The matrix A is %lld x %lld but the problem needs %lld x %lld "
              "(nv = %lld velocities + %s%lld constraints%s).",
              (long long)rows, (long long)cols,
              (long long)n, (long long)n, (long long)mem->nv,
              mem->nalg > mem->m ? "2 m = 2 x " : "m = ", (long long)mem->m,
              mem->nalg > mem->m ? ": LGN_CONSTR_GGL has the multipliers lambda and mu" : "");
    return LGN_LS_MISMATCH;
  }
  if (SUNLinSolGetID(mem->LS) == SUNLINEARSOLVER_DENSE &&
      ((SUNLinearSolverContent_Dense)mem->LS->content)->N != n) {
    /* it would factor A with a pivot array of its own size */
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The dense linear solver was created for %lld x %lld matrices, "
              "but A is %lld x %lld: create it with SUNLinSol_Dense(y, A, ctx) "
              "for this A.",
              (long long)((SUNLinearSolverContent_Dense)mem->LS->content)->N,
              (long long)((SUNLinearSolverContent_Dense)mem->LS->content)->N, (long long)n, (long long)n);
    return LGN_LS_MISMATCH;
  }
  if (lgnDenseLUSize(mem->LS) >= 0 && lgnDenseLUSize(mem->LS) != n) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The dense linear solver was created for %lld x %lld matrices, "
              "but A is %lld x %lld: create it with LGNLinSol_Dense(y, A, ctx) "
              "for this A.",
              (long long)lgnDenseLUSize(mem->LS),
              (long long)lgnDenseLUSize(mem->LS), (long long)n, (long long)n);
    return LGN_LS_MISMATCH;
  }
  return LGN_SUCCESS;
}

int lgnLsCheck(LGNMem mem)
{
  int ret;
  /* across ranks: agreed before SUNLinSolInitialize (collective for a
   * Krylov solver over MPI vectors: it clones its basis) */
  int flag = lgnAgree(mem, CheckLinearSolver(mem));
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->ls_initialized) {
    ret = SUNLinSolInitialize(mem->LS);
    mem->last_lin_flag = ret;
    if (ret != 0) LGN_ERROR(mem, LGN_LINIT_FAIL, "SUNLinSolInitialize failed (%d).", ret);
    flag = lgnAgree(mem, ret != 0 ? LGN_LINIT_FAIL : LGN_SUCCESS);
    if (flag != LGN_SUCCESS) return flag;
    mem->ls_initialized = SUNTRUE;
  }
  return LGN_SUCCESS;
}

/* Copy the factors of SUNLinSol_KLU for lgnLsSolve. For a CSC matrix the
 * copy holds L and U by rows, and Lignum refactors into it (OwnRefactor):
 * it is made at the first solve with a factorisation by KLU, which then
 * factors again only when the pattern changes or a pivot becomes too small.
 * For a CSR matrix (a copy by columns, refactored by KLU) it is made at
 * the second solve: a copy costs more than one solve saves, so
 * factorisations solved with once (full Newton) are not copied. When they cannot
 * be copied (indices beyond 32 bits, or memory refused), the solves fall
 * back to SUNLinSolSolve and the setups to SUNLinSolSetup: the
 * integration goes on, only slower, and the copy's memory is released. */
static void CopyKLUFactors(LGNMem mem)
{
  long int nfull = 0, nvalues = 0;
  int flag;
  if (!mem->own_klu_solves || SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_KLU ||
      mem->klu_nsolve != (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT ? 0 : 1))
    return;
  if (mem->klu != NULL) {
    nfull   = mem->klu->nfull;
    nvalues = mem->klu->nvalues;
  }
  flag = lgnKluCopyRefresh(&mem->klu, mem->LS);
  mem->klu_valid = flag == LGN_SUCCESS ? SUNTRUE : SUNFALSE;
  if (flag == LGN_SUCCESS) {
    mem->nklu_copy   += mem->klu->nfull - nfull;
    mem->nklu_values += mem->klu->nvalues - nvalues;
  } else {
    mem->nklu_nocopy++;
    lgnKluCopyFree(&mem->klu);
  }
}

/* The number of A's sparsity pattern (changes when the assembly builds a
 * new one, and with it KLU's analysis). */
static long int PatternNumber(LGNMem mem)
{
  return mem->sp != NULL ? mem->sp->npattern : -1L;
}

/* Lignum's refactorisation of A into the copy of KLU's factors, with KLU's
 * pivots and scaling (lgnKluCopyRefactor), while the copy is of A's
 * pattern. Returns SUNTRUE when it took the place of SUNLinSolSetup; on a
 * new pattern, a pivot that became too small, or anything else (counted
 * by cause), KLU factors (and may pivot anew), and its factors are copied
 * again at the next solve. */
static sunbooleantype OwnRefactor(LGNMem mem)
{
#if defined(LGN_KLU_COPY)
  int flag;
  if (!mem->own_klu_solves || mem->klu == NULL || !mem->klu->rows ||
      SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_KLU)
    return SUNFALSE;
  if (mem->klu_pattern != PatternNumber(mem)) {
    mem->nklu_newpattern++;
    return SUNFALSE;
  }
  flag = lgnKluCopyRefactor(mem->klu, mem->A, mem->klu_pattern,
                            SUNLinSol_KLUGetCommon(mem->LS)->scale);
  if (flag == LGN_MEM_FAIL) lgnKluCopyFree(&mem->klu);
  if (flag != LGN_SUCCESS) {
    if (flag == LGN_KLU_PIVOT) mem->nklu_fallback++;
    else mem->nklu_nocopy++;
    return SUNFALSE;
  }
  mem->nklu_refactor++;
  mem->klu_valid = SUNTRUE; /* the factors are the copy's: nothing to copy */
  return SUNTRUE;
#else
  (void)mem;
  return SUNFALSE;
#endif
}

/* After a failed setup, or when A's pattern was dropped, the solver starts
 * clean: KLU's numeric object may be gone, hold a factorisation of a
 * non-finite or singular matrix, or belong to another pattern, and
 * refactoring it would fail for good or write past its factors; a new
 * analysis and factorisation at the next setup (dense LU keeps no state
 * between setups). */
static void ResetSolver(LGNMem mem)
{
#if defined(LGN_HAVE_KLU)
  if (SUNLinSolGetID(mem->LS) == SUNLINEARSOLVER_KLU)
    SUNLinSol_KLUReInit(mem->LS, mem->A, SUNSparseMatrix_NNZ(mem->A),
                        SUNKLU_REINIT_PARTIAL);
#endif
  lgnKluCopyFree(&mem->klu);
  mem->ls_restart = SUNFALSE;
}

/* SUNDIALS' dense LU stops only at an exact zero pivot; a matrix whose
 * pivots span more than 1/DENSE_RCOND_MIN (rounding turned a zero pivot of
 * a singular matrix into ~eps) is singular to working precision, and its
 * solves would be noise. Then 1 + the column of the smallest pivot, as the
 * LU's own flag; else 0. KLU checks its rcond itself (SUNLinSolSetup). */
#define DENSE_RCOND_MIN SUN_RCONST(1.0e-13)
static int DenseNearlySingular(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->nalg;
  sunrealtype umin = SUN_BIG_REAL, umax = SUN_RCONST(0.0), u;
  sunindextype k, kmin = 0;
  if (lgnMatID(mem->A) != SUNMATRIX_DENSE) return 0;
  for (k = 0; k < n; k++) { /* the LU factors are in A */
    u = fabs(SM_ELEMENT_D(mem->A, k, k));
    if (u < umin) {
      umin = u;
      kmin = k;
    }
    umax = SUNMAX(umax, u);
  }
  return umin < DENSE_RCOND_MIN * umax ? (int)(kmin + 1) : 0;
}

int lgnLsSetup(LGNMem mem)
{
  int ret;
  mem->nlsetup++;
  if (mem->krylov) return lgnKrylovSetup(mem);
  if (OwnRefactor(mem)) return LGN_SUCCESS;
  mem->klu_valid  = SUNFALSE; /* the factors in LS change (or are lost) */
  mem->klu_nsolve = 0;
  mem->klu_pattern = PatternNumber(mem);
  if (mem->ls_restart) ResetSolver(mem);
  ret = SUNLinSolSetup(mem->LS, mem->A);
  mem->last_lin_flag = ret;
  mem->ls_restart = ret != 0 ? SUNTRUE : SUNFALSE;
  if (ret == 0) ret = DenseNearlySingular(mem);
  if (ret != 0) {
    lgnDiagnoseSingular(mem, ret, mem->diag_text, sizeof mem->diag_text);
    /* singular at this step size: the caller retries a smaller one */
    if (mem->lsetup_recoverable && (ret > 0 || mem->diag_pivot >= 0)) return LGN_RECOVERABLE;
    LGN_ERROR(mem, LGN_LSETUP_FAIL,
              MSG_TIME "the linear solver setup failed (%d%s).%s",
              (double)mem->tn, ret,
              ret > 0 || mem->diag_pivot >= 0 ? ": the matrix is singular" : "",
              mem->diag_text);
    return LGN_LSETUP_FAIL;
  }
  return LGN_SUCCESS;
}

/* With ghost bodies: b's rows folded to the owned unknowns, the solve
 * across ranks, and x's ghost entries from their owners (lgn_ghosts.c). */
static int SolveWithGhosts(LGNMem mem, N_Vector x, N_Vector b)
{
  int ret;
  lgnGhostsFold(mem, lgnData(b), lgnData(mem->hx_b));
  if (mem->krylov) {
    ret = lgnKrylovSolve(mem, mem->hx_x, mem->hx_b);
  } else {
    ret = SUNLinSolSolve(mem->LS, mem->A, mem->hx_x, mem->hx_b, SUN_RCONST(0.0));
    mem->last_lin_flag = ret;
    if (ret != 0) {
      LGN_ERROR(mem, LGN_LSOLVE_FAIL, MSG_TIME "the linear solve failed (%d).",
                (double)mem->tn, ret);
      ret = LGN_LSOLVE_FAIL;
    }
  }
  /* the expansion is collective: every rank takes part, whatever failed */
  ret = lgnAgree(mem, ret);
  if (ret == LGN_SUCCESS) lgnGhostsExpand(mem, lgnData(mem->hx_x), lgnData(x));
  return ret;
}

int lgnLsSolve(LGNMem mem, N_Vector x, N_Vector b)
{
  int ret;
  if (mem->halo != NULL) {
    mem->nlsolve++;
    return SolveWithGhosts(mem, x, b);
  }
  if (mem->krylov) {
    mem->nlsolve++;
    return lgnKrylovSolve(mem, x, b);
  }
  if (!mem->klu_valid) CopyKLUFactors(mem);
  mem->klu_nsolve++;
  mem->nlsolve++;
  if (mem->klu_valid) { /* Lignum's solve on its copy of the factors */
    mem->nklu_solve++;
    lgnKluCopySolve(mem->klu, lgnData(b), lgnData(x));
    mem->last_lin_flag = 0;
    return LGN_SUCCESS;
  }
  ret = SUNLinSolSolve(mem->LS, mem->A, x, b, SUN_RCONST(0.0));
  mem->last_lin_flag = ret;
  if (ret != 0) {
    LGN_ERROR(mem, LGN_LSOLVE_FAIL, MSG_TIME "the linear solve failed (%d).",
              (double)mem->tn, ret);
    return LGN_LSOLVE_FAIL;
  }
  return LGN_SUCCESS;
}
