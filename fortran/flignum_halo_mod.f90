! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_halo_mod (built with LGN_ENABLE_MPI): hand-written ISO_C_BINDING
! interface to the ghost bodies of runs across MPI ranks,
! include/lignum/lignum_halo.h.
!
! Names are the C names, types as in flignum_mod:
!   LGNHalo, LGNGroup, the memory block -> type(c_ptr), value
!   LGNHalo *H (LGNHalo_Destroy)       -> type(c_ptr), by reference (set to c_null_ptr)
!   const long int *global_id          -> integer(c_long) :: global_id(*)
!   const int *ghost_owner             -> type(c_ptr), value: c_loc of an
!                                         integer(c_int) array, or c_null_ptr
!   sunindextype                       -> integer(c_int64_t)
! The communicator: LGNHalo_Create takes a C MPI_Comm, which has no portable
! Fortran type (Open MPI's is a pointer, MPICH's an int). FLGNHalo_Create
! takes the Fortran handle instead (the integer of the mpi module, or the
! MPI_VAL component of mpi_f08's type(MPI_Comm)) and converts it with
! MPI_Comm_f2c (fortran/flignum_mpi_shim.c).
! ---------------------------------------------------------------------------
module flignum_halo_mod
  use, intrinsic :: iso_c_binding
  implicit none

  !> LGNHalo_UpdateGhosts: nq reals per body (a configuration).
  integer(c_int), parameter :: LGN_HALO_CONFIGURATION = 0
  !> LGNHalo_UpdateGhosts: nv reals per body (a velocity-type vector).
  integer(c_int), parameter :: LGN_HALO_VELOCITY = 1

  interface
    !> LGNHalo_Create with a Fortran communicator handle fcomm (collective).
    type(c_ptr) function FLGNHalo_Create(fcomm, G, nowned, global_id, ghost_owner) &
        bind(c, name="FLGNHalo_Create")
      import :: c_ptr, c_int, c_long
      integer(c_int), value :: fcomm
      type(c_ptr), value :: G
      integer(c_int), value :: nowned
      integer(c_long), intent(in) :: global_id(*)
      type(c_ptr), value :: ghost_owner
    end function FLGNHalo_Create

    !> Free a halo (collective); H becomes c_null_ptr.
    subroutine LGNHalo_Destroy(H) bind(c, name="LGNHalo_Destroy")
      import :: c_ptr
      type(c_ptr) :: H
    end subroutine LGNHalo_Destroy

    !> Number of this rank's own bodies.
    integer(c_int) function LGNHalo_NumOwned(H) bind(c, name="LGNHalo_NumOwned")
      import :: c_int, c_ptr
      type(c_ptr), value :: H
    end function LGNHalo_NumOwned

    !> Number of ghost bodies on this rank.
    integer(c_int) function LGNHalo_NumGhosts(H) bind(c, name="LGNHalo_NumGhosts")
      import :: c_int, c_ptr
      type(c_ptr), value :: H
    end function LGNHalo_NumGhosts

    !> The ranks this rank exchanges ghosts with.
    integer(c_int) function LGNHalo_NumNeighbours(H) bind(c, name="LGNHalo_NumNeighbours")
      import :: c_int, c_ptr
      type(c_ptr), value :: H
    end function LGNHalo_NumNeighbours

    !> Fill the ghosts' entries of x from their owners (collective).
    integer(c_int) function LGNHalo_UpdateGhosts(H, kind, x) bind(c, name="LGNHalo_UpdateGhosts")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: H
      integer(c_int), value :: kind
      real(c_double), intent(inout) :: x(*)
    end function LGNHalo_UpdateGhosts

    !> Couple the integrator's ranks through the halo H.
    integer(c_int) function LGNSetHalo(lgn_mem, H) bind(c, name="LGNSetHalo")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, H
    end function LGNSetHalo

    !> The size of this rank's subdomain iteration matrix.
    integer(c_int) function LGNGetSubdomainSize(lgn_mem, n) bind(c, name="LGNGetSubdomainSize")
      import :: c_int, c_ptr, c_int64_t
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), intent(out) :: n
    end function LGNGetSubdomainSize

    !> The global index of each unknown of the subdomain matrix (collective).
    integer(c_int) function LGNGetGlobalIndices(lgn_mem, idx) bind(c, name="LGNGetGlobalIndices")
      import :: c_int, c_ptr, c_int64_t
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), intent(out) :: idx(*)
    end function LGNGetGlobalIndices
  end interface

end module flignum_halo_mod
