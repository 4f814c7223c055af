/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The C side of flignum_petsc_mod (library lignum_petsc_fortran):
 * LGNLinSol_PETSc with a Fortran communicator handle (MPI_Comm_f2c; a C
 * MPI_Comm has no portable Fortran type).
 * ---------------------------------------------------------------------------*/

#include <mpi.h>

#include <lignum/lignum_petsc.h>

SUNLinearSolver FLGNLinSol_PETSc(N_Vector y, SUNMatrix A, MPI_Fint fcomm, SUNContext sunctx);

_Static_assert(sizeof(MPI_Fint) == sizeof(int), "the Fortran modules bind MPI_Fint as integer(c_int)");

/* LGNLinSol_PETSc on the communicator of the Fortran handle fcomm. */
SUNLinearSolver FLGNLinSol_PETSc(N_Vector y, SUNMatrix A, MPI_Fint fcomm, SUNContext sunctx)
{
  return LGNLinSol_PETSc(y, A, MPI_Comm_f2c(fcomm), sunctx);
}
