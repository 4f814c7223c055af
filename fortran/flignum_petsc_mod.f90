! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_petsc_mod (library lignum_petsc_fortran, built with
! LGN_ENABLE_PETSC): hand-written ISO_C_BINDING interface to the direct
! solves through PETSc and MUMPS, include/lignum/lignum_petsc.h.
!
!   N_Vector, SUNMatrix, SUNContext, SUNLinearSolver -> type(c_ptr), value
!   const sunindextype *global_index               -> integer(c_int64_t) :: global_index(*)
! LGNLinSol_PETSc takes a C MPI_Comm, which has no portable Fortran type:
! FLGNLinSol_PETSc takes the Fortran handle (the integer of the mpi module,
! or mpi_f08's MPI_Comm%MPI_VAL) and converts it with MPI_Comm_f2c
! (fortran/flignum_petsc_shim.c).
! ---------------------------------------------------------------------------
module flignum_petsc_mod
  use, intrinsic :: iso_c_binding
  implicit none

  interface
    !> LGNLinSol_PETSc with a Fortran communicator handle fcomm.
    type(c_ptr) function FLGNLinSol_PETSc(y, A, fcomm, sunctx) bind(c, name="FLGNLinSol_PETSc")
      import :: c_ptr, c_int
      type(c_ptr), value :: y, A
      integer(c_int), value :: fcomm
      type(c_ptr), value :: sunctx
    end function FLGNLinSol_PETSc

    !> A direct solver by PETSc and MUMPS for the sum of the ranks' subdomain
    !! matrices (owned and ghost unknowns, global numbers global_index, e.g.
    !! from LGNGetGlobalIndices), owned parts in and out.
    type(c_ptr) function LGNLinSol_PETScSubdomain(y, A, global_index, sunctx) &
        bind(c, name="LGNLinSol_PETScSubdomain")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: y, A
      integer(c_int64_t), intent(in) :: global_index(*)
      type(c_ptr), value :: sunctx
    end function LGNLinSol_PETScSubdomain
  end interface

end module flignum_petsc_mod
