! -----------------------------------------------------------------------------
! Lignum teaching example (Fortran twin of ../pendulum_so3.c): a physical
! pendulum on SO(3), through the Fortran modules flignum_mod and
! flignum_sundials_mod.
!
! One rigid body turns about a fixed pivot: the group SO(3) (q = unit
! quaternion, v = Omega body), no constraints,
!
!   J_O Omegadot + Omega x J_O Omega - s x (R^T m gvec) = 0,
!
! J_O the inertia about the pivot, s the centre of mass (body frame). The
! callbacks are bind(c) functions (LGNMassFn, LGNForceFn) reading the
! N_Vectors through FN_VGetArray and the dense matrix through
! FSUNDenseMatrix_Array (1-based, no copy). Generalized-alpha (0.9),
! h = 1e-3, t in [0, 2]. It prints the table of pendulum_so3.c (same answer
! file): t, the centre of mass R s, |Omega|, the energy.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
module pendulum_model
  use, intrinsic :: iso_c_binding
  use flignum_mod, only: LGNQuaternionToRotation
  use flignum_sundials_mod, only: FN_VGetArray, FSUNDenseMatrix_Array
  implicit none

  real(c_double), parameter :: mass = 1.0_c_double
  real(c_double), parameter :: s(3) = [0.0_c_double, 0.0_c_double, -0.5_c_double]
  real(c_double), parameter :: jo(3) = [0.35_c_double, 0.37_c_double, 0.02_c_double]
  real(c_double), parameter :: gvec(3) = [0.0_c_double, 0.0_c_double, -9.81_c_double]

contains

  pure function cross(a, b) result(c)
    real(c_double), intent(in) :: a(3), b(3)
    real(c_double) :: c(3)

    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  !> R as a Fortran matrix (LGNQuaternionToRotation writes it row-major)
  function rotation(q) result(R)
    real(c_double), intent(in) :: q(4)
    real(c_double) :: R(3, 3), rm(9)

    call LGNQuaternionToRotation(q, rm)
    R = transpose(reshape(rm, [3, 3]))
  end function rotation

  !> M = J_O (LGNMassFn)
  integer(c_int) function mass_fn(t, q, M, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, M, user_data
    real(c_double), pointer :: a(:, :)
    integer :: i

    a => FSUNDenseMatrix_Array(M)
    do i = 1, 3
      a(i, i) = jo(i)
    end do
    ierr = 0
  end function mass_fn

  !> g = Omega x J_O Omega - s x (R^T m gvec) (LGNForceFn)
  integer(c_int) function force_fn(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    real(c_double), pointer :: qq(:), w(:), gg(:)
    real(c_double) :: R(3, 3)

    qq => FN_VGetArray(q)
    w => FN_VGetArray(v)
    gg => FN_VGetArray(g)
    R = rotation(qq)
    gg = cross(w, jo * w) - cross(s, matmul(transpose(R), mass * gvec))
    ierr = 0
  end function force_fn

  !> print t, R s, |Omega|, energy
  subroutine print_row(t, q, v)
    real(c_double), intent(in) :: t
    type(c_ptr), intent(in) :: q, v
    real(c_double), pointer :: qq(:), w(:)
    real(c_double) :: x(3), energy

    qq => FN_VGetArray(q)
    w => FN_VGetArray(v)
    x = matmul(rotation(qq), s)
    energy = 0.5_c_double * sum(jo * w * w) - mass * dot_product(gvec, x)
    write (*, "(f6.2, 4(1x, f12.6), 1x, f14.8)") t, x, norm2(w), energy
  end subroutine print_row

end module pendulum_model

program pendulum_so3_f
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod
  use flignum_sundials_mod
  use pendulum_model
  implicit none

  real(c_double), parameter :: psi0(3) = [0.6_c_double, 0.2_c_double, 0.0_c_double]
  real(c_double), parameter :: omega0(3) = [0.0_c_double, 1.0_c_double, 3.0_c_double]
  real(c_double), parameter :: h = 1.0e-3_c_double, dtout = 0.25_c_double, tend = 2.0_c_double
  type(c_ptr) :: ctx, G, q, v, A, LS, mem
  real(c_double), pointer :: qq(:), vv(:)
  real(c_double) :: t, tout
  integer(c_long) :: nst, nni
  integer(c_int) :: flag

  ! context and group
  if (FSUNContext_Create(ctx) /= 0) error stop 1
  G = LGNGroup_SO3() ! nq = 4, nv = 3

  ! initial state
  q = N_VNew_Serial(4_c_int64_t, ctx)
  v = N_VNew_Serial(3_c_int64_t, ctx)
  qq => FN_VGetArray(q)
  vv => FN_VGetArray(v)
  call LGNQuaternionFromRotationVector(psi0, qq)
  vv = omega0

  ! integrator, model, initial values
  mem = LGNCreate(ctx)
  flag = LGNSetGroup(mem, G)
  if (flag == LGN_SUCCESS) flag = LGNSetMassFn(mem, c_funloc(mass_fn))
  if (flag == LGN_SUCCESS) flag = LGNSetForceFn(mem, c_funloc(force_fn))
  if (flag == LGN_SUCCESS) flag = LGNSetMassConstant(mem, 1_c_int)
  if (flag == LGN_SUCCESS) flag = LGNInit(mem, 0.0_c_double, q, v)

  ! dense linear solver, nv x nv (no constraints)
  A = SUNDenseMatrix(3_c_int64_t, 3_c_int64_t, ctx)
  LS = LGNLinSol_Dense(v, A, ctx)
  if (flag == LGN_SUCCESS) flag = LGNSetLinearSolver(mem, LS, A)

  ! generalized-alpha, fixed step
  if (flag == LGN_SUCCESS) flag = LGNSetGenAlpha(mem, 0.9_c_double)
  if (flag == LGN_SUCCESS) flag = LGNSetStepSize(mem, h)

  write (*, "(a)") "Physical pendulum on SO(3): generalized-alpha(0.9), h = 1e-03"
  write (*, "(a)") ""
  write (*, "(a6, 4(1x, a12), 1x, a14)") "t", "x_cm", "y_cm", "z_cm", "|Omega|", "energy"
  t = 0.0_c_double
  call print_row(t, q, v)
  tout = dtout
  do while (flag == LGN_SUCCESS .and. tout <= tend + 0.5_c_double * dtout)
    flag = LGNSolve(mem, tout, t, q, v, LGN_NORMAL)
    if (flag /= LGN_SUCCESS) exit
    call print_row(t, q, v)
    tout = tout + dtout
  end do
  if (flag /= LGN_SUCCESS) write (error_unit, "(2a)") "pendulum_so3_f: ", FLGNGetReturnFlagName(flag)

  if (LGNGetNumSteps(mem, nst) /= LGN_SUCCESS) nst = -1
  if (LGNGetNumNewtonIters(mem, nni) /= LGN_SUCCESS) nni = -1
  write (*, "(a)") ""
  write (*, "(a, i0, a, i0)") "steps = ", nst, "   Newton iterations = ", nni

  call LGNFree(mem)
  if (SUNLinSolFree(LS) /= 0) flag = -1
  call SUNMatDestroy(A)
  call N_VDestroy(q)
  call N_VDestroy(v)
  call LGNGroup_Destroy(G)
  if (SUNContext_Free(ctx) /= 0) flag = -1
  if (flag /= LGN_SUCCESS) error stop 1
end program pendulum_so3_f
