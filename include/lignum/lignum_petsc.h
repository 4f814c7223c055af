/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A direct solve through PETSc (built with LGN_ENABLE_PETSC): a
 * SUNLinearSolver over PETSc's KSP (KSPPREONLY + PCLU) with MUMPS, for
 * Lignum's sparse iteration matrix held identically on every rank of an
 * MPI communicator. Include it after MPI's <mpi.h> is on the include path
 * (the CMake target Lignum::lignum brings it).
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
 *  see above), SUNLS_ILL_INPUT for a matrix that is not sparse N x N,
 *  SUNLS_MEM_NULL, or SUNLS_PACKAGE_FAIL_UNREC when a PETSc call fails
 *  (PETSc prints its own traceback). SUNLinSolSolve returns
 *  SUNLS_ILL_INPUT (and leaves x alone) before a successful setup or after
 *  a failed one, or for vectors of another length; x may be b. */
LGN_EXPORT SUNLinearSolver LGNLinSol_PETSc(N_Vector y, SUNMatrix A, MPI_Comm comm,
                                           SUNContext sunctx);

#ifdef __cplusplus
}
#endif

#endif
