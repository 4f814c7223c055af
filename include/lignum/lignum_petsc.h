/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A direct solve through PETSc (built with LGN_ENABLE_PETSC): a
 * SUNLinearSolver over PETSc's KSP (KSPPREONLY + PCLU) with MUMPS, for
 * Lignum's sparse iteration matrix either held identically on every rank
 * of an MPI communicator (LGNLinSol_PETSc) or summed from the ranks'
 * subdomain matrices (LGNLinSol_PETScSubdomain). Include it after MPI's
 * <mpi.h> is on the include path (the CMake target Lignum::lignum brings
 * it).
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_PETSC_H
#define LIGNUM_PETSC_H

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>

#if !defined(LGN_HAVE_PETSC)
#error "This Lignum was built without PETSc (LGN_ENABLE_PETSC=OFF): LGNLinSol_PETSc is not available."
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Create a direct linear solver over PETSc: the SUNSparseMatrix A (N x N,
 *  CSR or CSC) is copied into a PETSc MATAIJ matrix at each setup and
 *  factored by MUMPS (KSPPREONLY, PCLU, MATSOLVERMUMPS); a solve returns
 *  the whole solution on every rank. Attach it with LGNSetLinearSolver(mem,
 *  LS, A) as SUNLinSol_KLU; any SUNDIALS package that drives a direct
 *  solver can use it too.
 *
 *  Distribution (this first version): A, y and the vectors of the solves
 *  are held identically, in full, on every rank of comm (each rank runs
 *  the same integration). On one rank the matrix is a MATSEQAIJ; on p
 *  ranks a MATMPIAIJ whose contiguous blocks of rows (PETSc's split) each
 *  rank fills from its own rows of A, and MUMPS factors in parallel. The
 *  solution is gathered to every rank (MPI_Allgatherv).
 *
 *  Symbolic reuse: while A's sparsity pattern (format, index arrays) is
 *  the one of the previous setup, only the values are copied and MUMPS
 *  factors numerically with the analysis it has (PETSc's
 *  SAME_NONZERO_PATTERN); a new pattern makes a new PETSc matrix and a new
 *  analysis. A CSC matrix is converted to rows through a permutation
 *  computed once per pattern (one gather of the values per setup).
 *
 *  Singular matrices: MUMPS' null pivot detection is on (ICNTL(24) = 1,
 *  threshold CNTL(3) = 1e-13 times the norm of the matrix MUMPS factors).
 *  A setup that finds null pivots (INFOG(28) > 0), or whose factorisation
 *  fails in MUMPS (INFOG(1) < 0, e.g. -10, numerically singular), returns
 *  SUNLS_LUFACT_FAIL (recoverable). SUNLinSolLastFlag then gives the
 *  1-based column of one unknown of the null space (the largest entry of
 *  MUMPS' first null-space vector, ICNTL(25) = 1) when null pivots were
 *  found, else 0. Lignum's diagnostics name that unknown and find the
 *  redundant constraints with their own rank-revealing QR of B.
 *
 *  PETSc's initialisation: MPI must be initialised (MPI_Init) before this
 *  call. If PETSc is not initialised, this call initialises it
 *  (PetscInitializeNoArguments, with PETSc's signal handler switched off)
 *  and the free of the last such solver finalises it (PetscFinalize, which
 *  leaves MPI alone since PETSc did not initialise MPI). An application
 *  that uses PETSc itself initialises PETSc first; Lignum then never
 *  finalises it. The count of solvers is not protected by a lock: create
 *  and free these solvers from one thread.
 *
 *  Options: the KSP has the options prefix "lgn_" (KSPSetFromOptions), so
 *  MUMPS can be tuned from PETSc's options database, e.g.
 *  -lgn_mat_mumps_icntl_14 50; ICNTL(24) and CNTL(3) are set by Lignum.
 *
 *  @param y      template vector of length N (serial, OpenMP or Pthreads),
 *                the same length on every rank
 *  @param A      the SUNSparseMatrix the solver will factor (square,
 *                N >= 1, CSR or CSC; its pattern may change between setups)
 *  @param comm   the communicator of the ranks that solve together (e.g.
 *                MPI_COMM_WORLD, or MPI_COMM_SELF for one rank); all its
 *                ranks call every operation of the solver (collective)
 *  @param sunctx SUNDIALS context
 *  @return the solver (free it with SUNLinSolFree, collectively), or NULL
 *          with a message naming the argument (on stderr) when y, A or
 *          sunctx is NULL, comm is MPI_COMM_NULL, A is not a square
 *          SUNSparseMatrix, y is not a serial-type vector of length N, MPI
 *          is not initialised, PETSc could not be initialised or was built
 *          without MUMPS, or memory was refused.
 *  Notes: SUNLinSolSetup returns SUNLS_SUCCESS, SUNLS_LUFACT_FAIL (singular,
 *  see above), SUNLS_ILL_INPUT for a matrix that is not sparse N x N or
 *  whose index arrays are invalid (reported), SUNLS_MEM_NULL,
 *  SUNLS_MEM_FAIL, or SUNLS_PACKAGE_FAIL_UNREC when a PETSc call fails
 *  (PETSc prints its own traceback). SUNLinSolSolve returns
 *  SUNLS_ILL_INPUT (and leaves x alone) before a successful setup or after
 *  a failed one, or for vectors of another length; x may be b. A failure
 *  found on some ranks only (a bad matrix or vector, memory) is agreed on
 *  with one MPI_Allreduce and returned on every rank, so that no rank
 *  waits for the others. */
LGN_EXPORT SUNLinearSolver LGNLinSol_PETSc(N_Vector y, SUNMatrix A, MPI_Comm comm,
                                           SUNContext sunctx);

/** Create a direct linear solver over PETSc for a matrix assembled from
 *  subdomain matrices: each rank holds a SUNSparseMatrix A_r over its
 *  local unknowns, its owned unknowns and ghost unknowns (owned by other
 *  ranks), and the global matrix is the sum over the ranks of
 *  P_r^T A_r P_r, where P_r maps local index k to the global index
 *  global_index[k] (additive, finite-element assembly: an entry in a
 *  ghost row is added to the owner's row, entries that meet at one global
 *  position are summed, also on one rank). The right-hand sides and
 *  solutions are the owned parts only: no rank holds or gathers the whole
 *  vector. Attach it with LGNSetLinearSolver(mem, LS, A) like
 *  LGNLinSol_PETSc.
 *
 *  Ownership: rank r owns the n_r = N_VGetLocalLength(y) global unknowns
 *  lo_r, ..., lo_r + n_r - 1, with lo_r = n_0 + ... + n_{r-1} (the ranks in
 *  the order of y's communicator); N = the sum of all n_r. PETSc's matrix
 *  is a MATAIJ (MATSEQAIJ on one rank, MATMPIAIJ on several) with those
 *  rows on rank r, assembled by PETSc's COO interface
 *  (MatSetPreallocationCOO once per pattern with the global row and
 *  column of every stored entry of A, MatSetValuesCOO with INSERT_VALUES
 *  at every setup, which sums the contributions of all ranks and replaces
 *  the values of the last setup), and factored by MUMPS (KSPPREONLY,
 *  PCLU, MATSOLVERMUMPS).
 *
 *  Symbolic reuse, singular matrices, options and PETSc's initialisation
 *  are those of LGNLinSol_PETSc: while A's pattern (format, index arrays)
 *  is that of the previous setup on every rank, only the values are sent
 *  and MUMPS refactors numerically with its analysis; a new pattern on
 *  any rank is a new preallocation and analysis on all. A setup that finds
 *  null pivots or whose factorisation fails returns SUNLS_LUFACT_FAIL on
 *  every rank; SUNLinSolLastFlag then gives, on every rank, the 1-based
 *  GLOBAL column of one unknown of the null space (found on rank 0 from a
 *  gathered copy of the global matrix: on this failure path only), else
 *  0. The KSP has the options prefix "lgn_".
 *
 *  Collective: every operation (creation, setup, solve, free) is
 *  collective over y's communicator, which the solver duplicates
 *  (MPI_Comm_dup) and frees at SUNLinSolFree. A failure that arises on
 *  some ranks only (an argument refused on one rank, memory) is agreed on
 *  with one MPI_Allreduce, so every rank returns NULL or the same failure
 *  flag and none waits for the others; a rank whose y is NULL or not an
 *  MPI vector has no communicator and returns NULL at once, so that must
 *  hold for all ranks alike. If PETSc is not initialised, the constructor
 *  initialises it, which is collective over MPI_COMM_WORLD.
 *
 *  @param y      template of this rank's owned part: an N_Vector_Parallel
 *                or MPIPlusX vector (over a serial, OpenMP or Pthreads
 *                local vector) of local length n_own >= 0 (a rank may own
 *                nothing; at least one rank owns an unknown); its
 *                communicator is the solver's
 *  @param A      this rank's subdomain SUNSparseMatrix, CSR or CSC, square
 *                n_loc x n_loc with n_loc >= n_own and n_loc >= 1; its
 *                rows and columns are the local unknowns (owned and
 *                ghosts, in any order); its pattern may change between
 *                setups
 *  @param global_index  array of n_loc global indices, the global unknown
 *                of each local row and column: each owned index lo_r,
 *                ..., lo_r + n_own - 1 exactly once, anywhere (checked
 *                collectively; Lignum's subdomain matrices hold the
 *                ghosts' velocities between the owned velocities and the
 *                multipliers, LGNGetGlobalIndices), the others (ghosts)
 *                indices in [0, N) outside that range, owned by other
 *                ranks. Copied: it may be freed after this call
 *  @param sunctx SUNDIALS context
 *  @return the solver (free it with SUNLinSolFree, collectively), or NULL
 *          on every rank, with a message naming the argument (on stderr,
 *          on the rank that refused it; the other ranks say that another
 *          rank refused), when y, A, global_index or sunctx is NULL, y is
 *          not an N_Vector_Parallel or MPIPlusX (a serial vector is
 *          refused: use LGNLinSol_PETSc), A is not a square
 *          SUNSparseMatrix of at least max(n_own, 1) rows, global_index
 *          misses one of this rank's owned indices, holds one twice, or
 *          has an index outside [0, N), N is 0 or beyond PETSc's index range, MPI is
 *          not initialised, PETSc could not be initialised, or memory was
 *          refused.
 *  Notes: SUNLinSolSetup(S, A) takes the rank's subdomain matrix (of the
 *  size given here) and returns SUNLS_SUCCESS, SUNLS_LUFACT_FAIL
 *  (singular), SUNLS_ILL_INPUT for a matrix that is not sparse n_loc x
 *  n_loc or whose index arrays are invalid on some rank (reported),
 *  SUNLS_MEM_NULL, SUNLS_MEM_FAIL, or SUNLS_PACKAGE_FAIL_UNREC when a PETSc
 *  call fails (PETSc prints its own traceback); the same flag on every
 *  rank. SUNLinSolSolve(S, A, x, b, tol) takes x and b of y's kind (local
 *  length n_own, global length N: this rank's part of the global solution
 *  and of the right-hand side, b summed over the ranks already) and
 *  returns SUNLS_ILL_INPUT on every rank (x left alone) before a
 *  successful setup or after a failed one, or for vectors of other
 *  lengths on any rank; x may be b. */
LGN_EXPORT SUNLinearSolver LGNLinSol_PETScSubdomain(N_Vector y, SUNMatrix A,
                                                    const sunindextype *global_index,
                                                    SUNContext sunctx);

#ifdef __cplusplus
}
#endif

#endif
