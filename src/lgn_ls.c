/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The bridge to SUNDIALS' SUNLinearSolver: LGNSetLinearSolver,
 * LGNSetOwnKLUSolves, the check of matrix and solver against the problem
 * size, setup (factorisation) and solve. The iteration matrix is filled by
 * lgn_assemble.c (dense) or lgn_assemble_sparse.c (SUNSparseMatrix, CSC or
 * CSR, with SUNLinSol_KLU). With KLU, the solves use a copy of KLU's
 * factors (lgn_klu_solve.c), made when a factorisation is solved with a
 * second time, unless switched off.
 * ---------------------------------------------------------------------------*/

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"
#include "lgn_klu_solve.h"
#include "lgn_sparse.h"
#if defined(LGN_KLU_COPY)
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
  if (A == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "A = NULL illegal: Lignum needs a matrix-based (direct) solver.");
    return LGN_ILL_INPUT;
  }
  if (SUNLinSolGetType(LS) != SUNLINEARSOLVER_DIRECT) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The linear solver is not a direct (matrix-based) solver.");
    return LGN_LS_MISMATCH;
  }
  if (SUNMatGetID(A) == SUNMATRIX_SPARSE) {
#if defined(LGN_HAVE_KLU)
    if (SUNLinSolGetID(LS) != SUNLINEARSOLVER_KLU) {
      LGN_ERROR(mem, LGN_LS_MISMATCH,
                "A sparse matrix needs the KLU linear solver (SUNLinSol_KLU).");
      return LGN_LS_MISMATCH;
    }
#else
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "Sparse matrices need Lignum built with LGN_ENABLE_KLU=ON.");
    return LGN_LS_MISMATCH;
#endif
  } else if (SUNMatGetID(A) != SUNMATRIX_DENSE) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "Matrix type %d not supported: use a SUNDenseMatrix, or a "
              "SUNSparseMatrix with SUNLinSol_KLU.",
              (int)SUNMatGetID(A));
    return LGN_LS_MISMATCH;
  } else if (SUNLinSolGetID(LS) == SUNLINEARSOLVER_KLU) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "SUNLinSol_KLU needs a SUNSparseMatrix, not a dense one.");
    return LGN_LS_MISMATCH;
  }
  mem->LS = LS;
  mem->A  = A;
  /* the model matrices are reallocated for A's type at the next solve; the
   * copy of the old solver's factors goes with them */
  lgnInvalidate(mem, LGN_CHANGE_LINSOL);
  return LGN_SUCCESS;
}

int LGNSetOwnKLUSolves(void *lgn_mem, sunbooleantype own)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  mem->own_klu_solves = own ? SUNTRUE : SUNFALSE;
  if (!mem->own_klu_solves && mem->klu != NULL) {
    /* SUNLinSolSetup and SUNLinSolSolve from now on; the factors of the
     * matrix may be only in the copy (Lignum refactored), so the next
     * step sets the matrix up anew */
    lgnInvalidate(mem, LGN_CHANGE_MATRIX);
    lgnKluCopyFree(&mem->klu);
  } /* else the copy is made at the first solve after the next setup */
  return LGN_SUCCESS;
}

/* Before the first solve: the matrix must be (nv+m) x (nv+m). */
int lgnLsCheck(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->m;
  const sunbooleantype sparse = SUNMatGetID(mem->A) == SUNMATRIX_SPARSE;
  const sunindextype rows = sparse ? SUNSparseMatrix_Rows(mem->A) : SM_ROWS_D(mem->A);
  const sunindextype cols = sparse ? SUNSparseMatrix_Columns(mem->A) : SM_COLUMNS_D(mem->A);
  int ret;
  if (rows != n || cols != n) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The matrix A is %lld x %lld but the problem needs %lld x %lld "
              "(nv = %lld velocities + m = %lld constraints).",
              (long long)rows, (long long)cols,
              (long long)n, (long long)n, (long long)mem->nv,
              (long long)mem->m);
    return LGN_LS_MISMATCH;
  }
  if (!mem->ls_initialized) {
    ret = SUNLinSolInitialize(mem->LS);
    mem->last_lin_flag = ret;
    if (ret != 0) {
      LGN_ERROR(mem, LGN_LINIT_FAIL, "SUNLinSolInitialize failed (%d).", ret);
      return LGN_LINIT_FAIL;
    }
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
  int flag;
  if (!mem->own_klu_solves || SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_KLU ||
      mem->klu_nsolve != (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT ? 0 : 1))
    return;
  flag = lgnKluCopyRefresh(&mem->klu, mem->LS);
  mem->klu_valid = flag == LGN_SUCCESS ? SUNTRUE : SUNFALSE;
  if (flag != LGN_SUCCESS) lgnKluCopyFree(&mem->klu);
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
 * pivot that became too small, or anything else, KLU factors (and may
 * pivot anew), and its factors are copied again at the next solve. */
static sunbooleantype OwnRefactor(LGNMem mem)
{
#if defined(LGN_KLU_COPY)
  int flag;
  if (!mem->own_klu_solves || mem->klu == NULL || !mem->klu->rows ||
      mem->klu_pattern != PatternNumber(mem) ||
      SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_KLU)
    return SUNFALSE;
  flag = lgnKluCopyRefactor(mem->klu, mem->A, mem->klu_pattern,
                            SUNLinSol_KLUGetCommon(mem->LS)->scale);
  if (flag == LGN_MEM_FAIL) lgnKluCopyFree(&mem->klu);
  if (flag != LGN_SUCCESS) {
    mem->nklu_fallback++;
    return SUNFALSE;
  }
  mem->klu_valid = SUNTRUE; /* the factors are the copy's: nothing to copy */
  return SUNTRUE;
#else
  (void)mem;
  return SUNFALSE;
#endif
}

int lgnLsSetup(LGNMem mem)
{
  int ret;
  mem->nlsetup++;
  if (OwnRefactor(mem)) return LGN_SUCCESS;
  mem->klu_valid  = SUNFALSE; /* the factors in LS change (or are lost) */
  mem->klu_nsolve = 0;
  mem->klu_pattern = PatternNumber(mem);
  ret = SUNLinSolSetup(mem->LS, mem->A);
  mem->last_lin_flag = ret;
  if (ret != 0) {
    LGN_ERROR(mem, LGN_LSETUP_FAIL,
              MSG_TIME "the linear solver setup failed (%d%s).",
              (double)mem->tn, ret,
              ret > 0 ? ": the iteration matrix is singular" : "");
    return LGN_LSETUP_FAIL;
  }
  return LGN_SUCCESS;
}

int lgnLsSolve(LGNMem mem, N_Vector x, N_Vector b)
{
  int ret;
  if (!mem->klu_valid) CopyKLUFactors(mem);
  mem->klu_nsolve++;
  mem->nlsolve++;
  if (mem->klu_valid) { /* Lignum's solve on its copy of the factors */
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
