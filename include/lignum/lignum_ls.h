/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The linear solver interface (included by lignum.h): attaching a SUNDIALS
 * linear solver and matrix, Lignum's solves with a copy of KLU's factors,
 * the sparsity pattern of the iteration matrix, and the linear solver's
 * statistics.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_LS_H
#define LIGNUM_LS_H

#include <lignum/lignum.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Attach a linear solver and the iteration matrix A ((nv+m) x (nv+m);
 *  (nv+2m) x (nv+2m) under LGN_CONSTR_GGL, dense only).
 *  - Direct (SUNLINEARSOLVER_DIRECT): a SUNDenseMatrix with SUNLinSol_Dense
 *    (or another direct solver on a dense matrix), or a SUNSparseMatrix
 *    (CSC or CSR; any initial nnz, Lignum sizes it) with SUNLinSol_KLU when
 *    Lignum was built with KLU (LGN_ENABLE_KLU). The model's matrices handed
 *    to the callbacks are then of the same type and format.
 *  - Matrix-free iterative (SUNLINEARSOLVER_ITERATIVE: SUNLinSol_SPGMR,
 *    SUNLinSol_SPFGMR, SUNLinSol_SPBCGS, SUNLinSol_SPTFQMR) with A = NULL.
 *    Lignum supplies the products with the scaled iteration matrix
 *    (SUNLinSolSetATimes): it assembles the matrix from the model's
 *    matrices (M, K_t, C_t, B: callbacks or difference quotients) into a
 *    compressed-column matrix of its own, at the same points where a
 *    direct solver would factor it, and multiplies with it. The model's
 *    matrices handed to the callbacks are then SUNSparseMatrix CSC, as with
 *    KLU. A preconditioner is optional (LGNSetPreconditioner,
 *    LGNSetBlockPreconditioner); with one, create SPGMR, SPBCGS or SPTFQMR
 *    with PREC_LEFT (SPFGMR: PREC_RIGHT). The linear tolerance is tied to
 *    Newton's (LGNSetEpsLin). SUNLinSol_PCG is refused: the saddle-point
 *    matrix is indefinite.
 *  Lignum does not take ownership.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, LGN_ILL_INPUT (LS = NULL; A = NULL
 *          with a direct solver; A given with a matrix-free one), or
 *          LGN_LS_MISMATCH (matrix and solver do not fit: the message says
 *          which combinations work). */
LGN_EXPORT int LGNSetLinearSolver(void *lgn_mem, SUNLinearSolver LS,
                                  SUNMatrix A);

/** Create Lignum's dense LU linear solver for the SUNDenseMatrix A (N x N):
 *  a direct solver (SUNLINEARSOLVER_DIRECT; its ID is
 *  SUNLINEARSOLVER_CUSTOM) that takes SUNLinSol_Dense's place, for Lignum
 *  (LGNSetLinearSolver) or any SUNDIALS package. SUNLinSolSetup factors A
 *  in place (LU with partial pivoting, the pivots kept by the solver),
 *  SUNLinSolSolve does the row swaps and the two triangular solves (x may
 *  be b). It does what SUNLinSol_Dense does, in the same order of
 *  operations (the same pivots, factors and solutions; to roundoff where
 *  the compiler fuses multiply-adds), but is compiled with Lignum's flags:
 *  with Debian's SUNDIALS (built at -O0) a setup and solve of a 9 x 9
 *  matrix is 2.3 times, of a 100 x 100 one 8 times faster than
 *  SUNLinSol_Dense's (bench/dense_lu.c; doc/user-guide.md, section 7,
 *  "Dense matrices").
 *  @param y      template vector of length N: serial, OpenMP or Pthreads
 *  @param A      the SUNDenseMatrix the solver will factor (square, N >= 1)
 *  @param sunctx SUNDIALS context
 *  @return the solver (free it with SUNLinSolFree), or NULL with a message
 *          naming the argument (on stderr, or to the default handler) when
 *          y, A or sunctx is NULL, A is not a square SUNDenseMatrix, y is
 *          not a serial-type vector or its length is not N, or memory was
 *          refused.
 *  Notes: SUNLinSolSetup returns SUNLS_SUCCESS, SUNLS_LUFACT_FAIL on a
 *  zero pivot (SUNLinSolLastFlag then gives 1 + the column of that pivot,
 *  as SUNLinSol_Dense: Lignum's diagnostics name the unknown),
 *  SUNLS_ILL_INPUT for a matrix that is not dense N x N, or
 *  SUNLS_MEM_NULL. SUNLinSolSolve returns SUNLS_ILL_INPUT (and leaves x
 *  alone) before a successful setup, after a failed one, or for a matrix
 *  or vectors of another size. */
LGN_EXPORT SUNLinearSolver LGNLinSol_Dense(N_Vector y, SUNMatrix A,
                                           SUNContext sunctx);

/** Solve with Lignum's own triangular solves on a copy of KLU's factors
 *  (SUNLinSol_KLU only). Off by default: opt in with own = SUNTRUE.
 *  Lignum copies L, U, the off-diagonal BTF blocks, the permutations and
 *  the row scaling out of KLU (klu_l_extract) with 32-bit indices and
 *  solves with the copy instead of calling SUNLinSolSolve: 12 instead of
 *  16 bytes per entry to read and a shorter chain of dependences make a
 *  solve about twice as fast.
 *  - CSC matrix: the copy holds L and U by rows and is made at the first
 *    solve after KLU's factorisation. From then on Lignum also refactors
 *    in its place: each row of Rs^{-1} A(P, Q) is eliminated against the
 *    rows of U with KLU's pivots, blocks, pattern and row scaling
 *    (klu_common.scale), which gives KLU's factors up to roundoff without
 *    klu_l_refactor and without copying them out again. As SUNLinSolSetup
 *    does, it checks KLU's cheap rcond, min |U(i,i)| / max |U(i,i)|: below
 *    eps^(2/3), and after a change of A's pattern, KLU factors (and may
 *    pivot anew) and its factors are copied again.
 *  - CSR matrix: the copy holds the columns of KLU's factors and is made
 *    at the second solve with a factorisation (so never with full Newton);
 *    after klu_l_refactor only the new values are taken.
 *  By columns (CSR) the solves do KLU's operations in KLU's order: the
 *  results agree with SUNLinSolSolve to the last bit without fused
 *  multiply-add. By rows (CSC) U's rows are kept divided by U's diagonal,
 *  which takes the division off the solve's chain of dependences, and
 *  Lignum refactors: the results agree with SUNLinSolSolve to roundoff
 *  (backward errors within a small factor of KLU's: at most 2.5 times in
 *  the tests, which allow 10). The copy takes 12 bytes per
 *  entry of L + U, 56 per row, 8 per entry of A for the refactorisation's
 *  maps, and 8 per entry of the larger factor for the extraction (counted
 *  in LGNGetWorkSpace; doc/user-guide.md, section 7). Factors beyond 32-bit
 *  indices, or memory refused, make Lignum fall back to SUNLinSolSetup and
 *  SUNLinSolSolve (LGNGetNumKLUFallbacks).
 *  What it buys (bench/chain_scaling, the 1000- and 10000-body chains,
 *  KLU CSC, CPU ms per step, copy off -> on): full Newton 3.16 -> 2.60
 *  and 33.2 -> 20.8, modified Newton 0.608 -> 0.397 and 8.49 -> 4.61
 *  (1.2 to 1.8 times faster; doc/user-guide.md, section 7), for 3.2 kB
 *  more memory per body (16.8 instead of 13.6 kB with KLU's).
 *  Why it is off by default: it reads KLU's Numeric and Symbolic objects
 *  and packed columns and SUNLinSol_KLU's private content, layouts that
 *  neither library publishes. So it accepts only the versions it was
 *  written and tested against: KLU 1.3 (SuiteSparse 5; the version
 *  compiled against) with SUNDIALS 6.4 (the version found at run time and
 *  the one compiled against).
 *  @param lgn_mem memory block
 *  @param own     SUNTRUE: Lignum's solves (and, CSC, its
 *                 refactorisations); SUNFALSE (default): SUNLinSolSetup and
 *                 SUNLinSolSolve, a copy is freed and the next step sets
 *                 the matrix up anew. With a dense solver the setting is
 *                 only recorded.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT for own = SUNTRUE
 *          when the copy is not available: other versions of KLU or
 *          SUNDIALS (the message names those found and those supported),
 *          SUNDIALS with 32-bit indices, or Lignum built without KLU
 *          (LGN_ENABLE_KLU=OFF); the setting then stays off. */
LGN_EXPORT int LGNSetOwnKLUSolves(void *lgn_mem, sunbooleantype own);

/** Number of whole copies of KLU's factors (klu_l_extract) made for
 *  Lignum's solves (LGNSetOwnKLUSolves): after each factorisation by KLU
 *  with new pivots or a new pattern. Counted from LGNInit / LGNReInit, as
 *  all counters; 0 with the copy off.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (ncopies = NULL). */
LGN_EXPORT int LGNGetNumKLUFactorCopies(void *lgn_mem, long int *ncopies);

/** Number of copies of the values only of KLU's factors, after
 *  klu_l_refactor kept the pattern (CSR matrices: KLU refactors).
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nvalues = NULL). */
LGN_EXPORT int LGNGetNumKLUValueCopies(void *lgn_mem, long int *nvalues);

/** Number of Lignum's refactorisations into the copy that took the place
 *  of SUNLinSolSetup (CSC matrices). LGNGetNumLinSolvSetups counts these
 *  and KLU's factorisations together.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nrefactors = NULL). */
LGN_EXPORT int LGNGetNumOwnKLURefactors(void *lgn_mem, long int *nrefactors);

/** Number of linear solves with the copy instead of SUNLinSolSolve (of
 *  LGNGetNumLinSolves, which counts both).
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nsolves = NULL). */
LGN_EXPORT int LGNGetNumOwnKLUSolves(void *lgn_mem, long int *nsolves);

/** Number of times KLU factored where Lignum would have refactored into the
 *  copy, or its factors could not be copied, by cause:
 *  @param lgn_mem  memory block
 *  @param npivot   Lignum's refactorisation left a pivot below SUNDIALS'
 *                  rcond threshold (its work is spent; KLU may pivot anew)
 *  @param npattern A's sparsity pattern changed (a new symbolic analysis)
 *  @param nnocopy  the factors could not be copied or A did not fit the
 *                  copy (sizes beyond 32-bit indices, memory refused):
 *                  KLU's setups and solves until the next factorisation
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (an output NULL,
 *          named in the message). */
LGN_EXPORT int LGNGetNumKLUFallbacks(void *lgn_mem, long int *npivot, long int *npattern,
                          long int *nnocopy);

/** Tell Lignum that the sparsity pattern of M, B, K_t or C_t has changed:
 *  at the next assembly the pattern of the iteration matrix and the column
 *  colouring of the difference quotients are rebuilt, and KLU analyses the
 *  new pattern. Without this call the pattern found at the first assembly is
 *  kept (KLU only refactors); entries outside it extend it automatically.
 *  A no-op for dense matrices. */
LGN_EXPORT int LGNResetSparsityPattern(void *lgn_mem);

/** Number of patterns of the sparse iteration matrix built (each followed
 *  by a symbolic analysis in KLU); 0 for dense matrices. */
LGN_EXPORT int LGNGetNumSparsityAnalyses(void *lgn_mem, long int *nanalyses);

/** Number of stored entries of the iteration matrix: its pattern's size for
 *  sparse matrices (0 before the first assembly), (nv + m)^2 for dense ones. */
LGN_EXPORT int LGNGetIterationMatrixNnz(void *lgn_mem, long int *nnz);

/** Number of displaced evaluations per difference-quotient stiffness matrix:
 *  the number of column colours (sparse) or nv (dense); 0 before the first
 *  assembly of a sparse matrix. */
LGN_EXPORT int LGNGetNumDQColors(void *lgn_mem, long int *ncolors);

/* =============================================================================
 * Krylov solvers and preconditioners (doc/user-guide.md, section 7)
 * ===========================================================================*/

/** Preconditioner setup: prepare P ~ the scaled iteration matrix
 *
 *    A = [[ cM M + cC C_t + cK K_t ,  B^T ],
 *         [ B                      ,  0   ]]
 *
 *  at the iterate (t, q, v) (Lignum's A carries besides the tangent
 *  factors T of the kinematics variant, close to I for small steps; the
 *  index-2 row has a term cK/cC D_q(B v)). cM, cC, cK are the scalings of
 *  the current matrix: (beta h^2 beta', beta h^2 gamma', beta h^2) in a
 *  step, (1, 0, 0) for the consistent initial values. Called where a
 *  direct solver would factor A: every Newton iteration (full Newton), or
 *  when the matrix is rebuilt (modified Newton).
 *  @return 0 on success, > 0 for a recoverable failure (the step is
 *          retried smaller with error control), < 0 unrecoverable. */
typedef int (*LGNPrecSetupFn)(sunrealtype t, N_Vector q, N_Vector v,
                              sunrealtype cM, sunrealtype cC, sunrealtype cK,
                              void *user_data);

/** Preconditioner solve: z ~ A^{-1} r (r, z of length nv + m: the velocity
 *  part, then the constraint rows; with ghost bodies, LGNSetHalo, the owned
 *  bodies' velocities then the rank's constraint rows), with the arguments
 *  of the last setup and the Krylov solver's tolerance delta for this
 *  solve.
 *  @return 0 on success, > 0 recoverable, < 0 unrecoverable. */
typedef int (*LGNPrecSolveFn)(sunrealtype t, N_Vector q, N_Vector v,
                              N_Vector r, N_Vector z, sunrealtype cM,
                              sunrealtype cC, sunrealtype cK,
                              sunrealtype delta, void *user_data);

/** Attach a user preconditioner for a matrix-free Krylov solver (as
 *  IDASetPreconditioner). It takes the place of a block preconditioner.
 *  @param lgn_mem memory block
 *  @param psetup  the setup (may be NULL when psolve needs none)
 *  @param psolve  the solve; psetup = psolve = NULL switches the
 *                 preconditioner off
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (psolve = NULL with
 *          psetup given).
 *  Notes: the solver must be created with PREC_LEFT (SPFGMR: PREC_RIGHT);
 *  LGNSolve refuses PREC_NONE with a preconditioner (LGN_LS_MISMATCH).
 *  user_data is the one of LGNSetUserData. */
LGN_EXPORT int LGNSetPreconditioner(void *lgn_mem, LGNPrecSetupFn psetup,
                                    LGNPrecSolveFn psolve);

/** Attach Lignum's block-Jacobi preconditioner for a matrix-free Krylov
 *  solver. The bodies (the leaves of the Lie group, in order) are split
 *  into nblocks contiguous blocks; block b holds the velocities of its
 *  bodies and the constraint rows whose first body (the lowest velocity
 *  column of the row in B) lies in it; a row with no column in any block
 *  is in none (left as it is). With ghost bodies (LGNSetHalo) the blocks
 *  split the rank's owned bodies and the ghosts are in no block: a block's
 *  constraints must then be independent on its owned bodies (a singular
 *  block is reported as such). Each block's restriction of the
 *  scaled iteration matrix (a saddle-point matrix itself) is factored with
 *  KLU at each matrix setup; the coupling between blocks (the joints at the
 *  block boundaries) is left to the Krylov iteration. nblocks = 1 is the
 *  whole matrix: the Krylov solver then converges in one or two
 *  iterations. This is the per-process block of the distributed design,
 *  with several blocks on one process.
 *  @param lgn_mem    memory block
 *  @param nblocks    number of blocks (>= 1); 0 switches it off
 *  @param body_start nblocks + 1 increasing body indices, body_start[0] = 0
 *                    and body_start[nblocks] = the number of bodies (owned
 *                    bodies with ghosts): block
 *                    b holds the bodies body_start[b] ... body_start[b+1]-1.
 *                    NULL: nblocks blocks of (nearly) equal numbers of
 *                    bodies. Copied.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, LGN_MEM_FAIL, or LGN_ILL_INPUT
 *          (nblocks < 0, a partition not increasing or not starting at 0,
 *          or Lignum built without KLU). A partition that does not end at
 *          the number of bodies, or more blocks than bodies, is refused by
 *          LGNSolve (LGN_ILL_INPUT).
 *  Notes: it takes the place of a user preconditioner (LGNSetPreconditioner).
 *  The solver must be created with PREC_LEFT (SPFGMR: PREC_RIGHT). */
LGN_EXPORT int LGNSetBlockPreconditioner(void *lgn_mem, int nblocks,
                                         const long int *body_start);

/** The linear tolerance as a fraction of Newton's (IDASetEpsLin). A Newton
 *  correction has converged when its weighted RMS norm (weights 1/(atol +
 *  rtol |x|) on (sigma/h, h lambda), LGNSStolerances) is <= 1; the Krylov
 *  solver stops when the weighted 2-norm of its (left-preconditioned)
 *  residual is <= eplifac sqrt(nv + m), i.e. its weighted RMS norm is
 *  <= eplifac. With a left preconditioner close to A this residual is the
 *  error of the correction, so the linear error stays eplifac of Newton's
 *  tolerance. 0 restores the default 0.05.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (eplifac < 0). */
LGN_EXPORT int LGNSetEpsLin(void *lgn_mem, sunrealtype eplifac);

/** Number of Krylov iterations (all linear solves). */
LGN_EXPORT int LGNGetNumLinIters(void *lgn_mem, long int *nliters);

/** Number of preconditioner setups (user's or block). */
LGN_EXPORT int LGNGetNumPrecEvals(void *lgn_mem, long int *npevals);

/** Number of preconditioner solves. */
LGN_EXPORT int LGNGetNumPrecSolves(void *lgn_mem, long int *npsolves);

/** Number of products with the iteration matrix (ATimes). */
LGN_EXPORT int LGNGetNumJtimesEvals(void *lgn_mem, long int *njvevals);

/** Number of linear solves that stopped short of their tolerance (the
 *  Krylov solver's SUNLS_RES_REDUCED in a Newton iteration, whose
 *  correction is used, and its other recoverable failures). */
LGN_EXPORT int LGNGetNumLinConvFails(void *lgn_mem, long int *nlcfails);

/** Number of linear solver setups (factorisations). */
LGN_EXPORT int LGNGetNumLinSolvSetups(void *lgn_mem, long int *nlsetups);

/** Number of linear solves. */
LGN_EXPORT int LGNGetNumLinSolves(void *lgn_mem, long int *nlsolves);

/** Return flag of the last linear solver call. */
LGN_EXPORT int LGNGetLastLinFlag(void *lgn_mem, long int *flag);

#ifdef __cplusplus
}
#endif

#endif
