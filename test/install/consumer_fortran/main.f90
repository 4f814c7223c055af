! -----------------------------------------------------------------------------
! Lignum install test: a Fortran program outside the source tree that uses
! the installed modules flignum_mod / flignum_sundials_mod /
! flignum_joints_mod and the library Lignum::lignum_fortran (found with
! find_package(Lignum COMPONENTS Fortran)). Integrates q'' = -q on R^1 with
! Fortran callbacks and checks q(1) = cos(1); adds a spherical joint to a
! rigid body (3 constraints).
!   lignum_consumer_fortran [expected version]
! Exits nonzero on any mismatch.
! ---------------------------------------------------------------------------
module consumer_model
  use, intrinsic :: iso_c_binding
  use flignum_sundials_mod, only: FN_VGetArray, FSUNDenseMatrix_Array
  implicit none

  !> Model data, passed as user data.
  type :: oscillator
    real(c_double) :: k = 1.0_c_double
  end type oscillator

contains

  !> M = 1 (LGNMassFn)
  integer(c_int) function mass(t, q, M, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, M, user_data
    real(c_double), pointer :: a(:, :)

    a => FSUNDenseMatrix_Array(M)
    a(1, 1) = 1.0_c_double
    ierr = 0
  end function mass

  !> g = k q (LGNForceFn)
  integer(c_int) function force(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    type(oscillator), pointer :: osc
    real(c_double), pointer :: qq(:), gg(:)

    call c_f_pointer(user_data, osc)
    qq => FN_VGetArray(q)
    gg => FN_VGetArray(g)
    gg(1) = osc%k * qq(1)
    ierr = 0
  end function force

end module consumer_model

program lignum_consumer_fortran
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod
  use flignum_joints_mod
  use flignum_sundials_mod
  use consumer_model
  implicit none

  type(oscillator), target :: osc
  type(c_ptr) :: ctx, G, q, v, A, tmpl, LS, mem, body, J
  real(c_double), pointer :: qq(:)
  real(c_double) :: t
  character(len=32) :: expected
  integer :: nfail = 0

  write (*, "(a, a)") "Lignum (Fortran) ", LGN_VERSION
  if (command_argument_count() >= 1) then
    call get_command_argument(1, expected)
    call expect(LGN_VERSION == trim(expected), "LGN_VERSION equals the package version")
  end if

  call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
  G = LGNGroup_Rn(1_c_int64_t)
  q = N_VNew_Serial(1_c_int64_t, ctx)
  v = N_VNew_Serial(1_c_int64_t, ctx)
  A = SUNDenseMatrix(1_c_int64_t, 1_c_int64_t, ctx)
  tmpl = N_VNew_Serial(1_c_int64_t, ctx)
  LS = SUNLinSol_Dense(tmpl, A, ctx)
  qq => FN_VGetArray(q)
  qq(1) = 1.0_c_double
  call N_VConst(0.0_c_double, v)

  mem = LGNCreate(ctx)
  call expect(LGNSetGroup(mem, G) == LGN_SUCCESS, "LGNSetGroup")
  call expect(LGNSetUserData(mem, c_loc(osc)) == LGN_SUCCESS, "LGNSetUserData")
  call expect(LGNSetMassFn(mem, c_funloc(mass)) == LGN_SUCCESS, "LGNSetMassFn")
  call expect(LGNSetForceFn(mem, c_funloc(force)) == LGN_SUCCESS, "LGNSetForceFn")
  call expect(LGNInit(mem, 0.0_c_double, q, v) == LGN_SUCCESS, "LGNInit")
  call expect(LGNSetLinearSolver(mem, LS, A) == LGN_SUCCESS, "LGNSetLinearSolver")
  call expect(LGNSetNewmark(mem, 0.25_c_double, 0.5_c_double) == LGN_SUCCESS, "LGNSetNewmark")
  call expect(LGNSetStepSize(mem, 1.0e-3_c_double) == LGN_SUCCESS, "LGNSetStepSize")
  call expect(LGNSolve(mem, 1.0_c_double, t, q, v, LGN_NORMAL) == LGN_SUCCESS, "LGNSolve")
  write (*, "(a, es24.16, a, es24.16)") "q(1) = ", qq(1), ", cos(1) = ", cos(1.0_c_double)
  call expect(abs(qq(1) - cos(1.0_c_double)) <= 1.0e-6_c_double, "q(1) = cos(1)")
  call expect(FLGNGetReturnFlagName(LGN_CONV_FAILURE) == "LGN_CONV_FAILURE", &
              "FLGNGetReturnFlagName(LGN_CONV_FAILURE)")

  call LGNFree(mem)
  call expect(.not. c_associated(mem), "LGNFree sets mem to c_null_ptr")
  call expect(SUNLinSolFree(LS) == 0, "SUNLinSolFree")
  call SUNMatDestroy(A)
  call N_VDestroy(q)
  call N_VDestroy(v)
  call N_VDestroy(tmpl)
  call LGNGroup_Destroy(G)

  ! the joint helpers: a rigid body hanging from the ground
  body = LGNGroup_R3xSO3()
  J = LGNJoints_Create(body)
  call expect(LGNJoints_NumBodies(J) == 1, "LGNJoints_NumBodies")
  call expect(LGNJoints_AddSpherical(J, LGN_GROUND, [0.0_c_double, 0.0_c_double, &
                                     0.0_c_double], 0_c_int, [0.0_c_double, 0.0_c_double, &
                                     0.5_c_double]) == LGN_SUCCESS, "LGNJoints_AddSpherical")
  call expect(LGNJoints_NumConstraints(J) == 3, "a spherical joint has 3 constraints")
  call LGNJoints_Destroy(J)
  call expect(.not. c_associated(J), "LGNJoints_Destroy sets J to c_null_ptr")
  call LGNGroup_Destroy(body)
  call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")

  if (nfail > 0) then
    write (error_unit, "(i0, a)") nfail, " check(s) failed"
    error stop 1
  end if
  write (*, "(a)") "install test (Fortran): all checks passed"

contains

  !> Count a failure unless ok.
  subroutine expect(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what

    if (.not. ok) then
      write (error_unit, "(a, a)") "FAILED: ", what
      nfail = nfail + 1
    end if
  end subroutine expect

end program lignum_consumer_fortran
