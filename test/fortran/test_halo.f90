! Ghost bodies from Fortran (flignum_halo_mod; run on 1, 2 and 4 ranks):
! each rank owns one body (R^3 x SO(3)), global number = its rank, and on
! more than one rank holds the next rank's body as a ghost.
!  - FLGNHalo_Create on MPI_COMM_WORLD given as the Fortran handle of the
!    mpi module: the numbers of owned bodies, ghosts and neighbours;
!  - LGNHalo_UpdateGhosts fills the ghost's q (LGN_HALO_CONFIGURATION) and
!    v (LGN_HALO_VELOCITY) with its owner's values, the owned entries stay;
!  - a bad nowned (0) gives c_null_ptr on every rank; LGNHalo_Destroy
!    clears the pointer.
program test_halo
  use, intrinsic :: iso_c_binding
  use mpi
  use flignum_mod
  use flignum_halo_mod
  use ftest_util
  implicit none

  integer :: ierr, rank, nranks, nb
  type(c_ptr) :: body, G, H, bad
  type(c_ptr), target :: factors(2)
  integer(c_long) :: gid(2)
  integer(c_int), target :: owner(1)
  real(c_double), target :: q(14), v(12)

  call MPI_Init(ierr)
  call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
  call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
  nb = merge(2, 1, nranks > 1)
  body = LGNGroup_R3xSO3()
  factors = body
  G = LGNGroup_Product(int(nb, c_int), factors)
  gid(1) = int(rank, c_long)
  gid(2) = int(mod(rank + 1, nranks), c_long)
  owner(1) = int(mod(rank + 1, nranks), c_int)
  if (nranks > 1) then
    H = FLGNHalo_Create(int(MPI_COMM_WORLD, c_int), G, 1_c_int, gid, c_loc(owner))
  else
    H = FLGNHalo_Create(int(MPI_COMM_WORLD, c_int), G, 1_c_int, gid, c_null_ptr)
  end if
  call expect(c_associated(H), "FLGNHalo_Create")
  call expect(LGNHalo_NumOwned(H) == 1, "one owned body")
  call expect(LGNHalo_NumGhosts(H) == nb - 1, "the ghosts")
  ! the owner of the ghost (rank + 1) and the rank whose ghost is this
  ! rank's body (rank - 1): one rank on 2 ranks, two on more
  call expect(LGNHalo_NumNeighbours(H) == min(nranks - 1, 2), "the neighbours")

  ! the owned body at x = (rank + 1, 0, 0), the ghost's entries unknown
  q = 0.0_c_double
  v = -1.0_c_double
  q(1) = real(rank + 1, c_double)
  q(4) = 1.0_c_double
  v(1:6) = real(10 * (rank + 1), c_double)
  if (nb > 1) q(11) = 1.0_c_double
  call expect(LGNHalo_UpdateGhosts(H, LGN_HALO_CONFIGURATION, q) == 0, "UpdateGhosts(q)")
  call expect(LGNHalo_UpdateGhosts(H, LGN_HALO_VELOCITY, v) == 0, "UpdateGhosts(v)")
  call expect_near(q(1), real(rank + 1, c_double), 0.0_c_double, "the owned q is kept")
  if (nb > 1) then
    call expect_near(q(8), real(owner(1) + 1, c_double), 0.0_c_double, &
                     "the ghost's q is its owner's")
    call expect_near(maxval(abs(v(7:12) - real(10 * (owner(1) + 1), c_double))), &
                     0.0_c_double, 0.0_c_double, "the ghost's v is its owner's")
  end if

  bad = FLGNHalo_Create(int(MPI_COMM_WORLD, c_int), G, 0_c_int, gid, c_null_ptr)
  call expect(.not. c_associated(bad), "nowned = 0 refused on every rank")
  call LGNHalo_Destroy(H)
  call expect(.not. c_associated(H), "LGNHalo_Destroy clears the pointer")
  call LGNGroup_Destroy(G)
  call LGNGroup_Destroy(body)
  call ftest_finish("test_halo")
  call MPI_Finalize(ierr)
end program test_halo
