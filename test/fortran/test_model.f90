! -----------------------------------------------------------------------------
! The multibody model object from Fortran (flignum_model_mod).
!
! A rod (mass 1, length 1, radius 0.02, axis z) hangs from the origin by a
! spherical joint at its end and swings in the x-z plane from theta0 = 0.01
! rad at rest. Installed with LGNModel_Attach, integrated with error control
! (generalized-alpha 0.9, rtol = atol = 1e-10) to t = 1, its angle follows
! the small-amplitude solution theta0 cos(omega t), omega^2 = m g d /
! (J_yy + m d^2), d = 0.5: asserted to 1e-6 rad at t = 0.5 and 1 (the
! amplitude's own correction, theta0^3 omega t / 16, is 2.4e-7; an inertia
! off by the rod's radius term would miss by 5e-6). The same pendulum with
! gravity given as a user force (LGNModel_SetUserForce, its data through
! LGNModel_SetUserData, no K or C: difference quotients) agrees to 1e-8.
! Bad input: a null body set, a null integrator memory, K without a force.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
module model_test_force
  use, intrinsic :: iso_c_binding
  use flignum_sundials_mod, only: FN_VGetArray
  implicit none
contains
  !> g_u = -m gvec: the weight of the rod as a user force (g holds MINUS the
  !! applied forces); the mass arrives as user data
  integer(c_int) function weight_fn(t, q, v, g, ud) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, ud
    real(c_double), pointer :: gg(:), mass

    call c_f_pointer(ud, mass)
    gg => FN_VGetArray(g)
    gg(3) = gg(3) + mass * 9.81_c_double
    ierr = 0
  end function weight_fn
end module model_test_force

program test_model
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_bodies_mod
  use flignum_joints_mod
  use flignum_model_mod
  use flignum_sundials_mod
  use ftest_util
  use model_test_force
  implicit none

  real(c_double), parameter :: theta0 = 0.01_c_double, d = 0.5_c_double, r = 0.02_c_double
  real(c_double), target :: mass = 1.0_c_double
  real(c_double) :: J(3), omega, theta_a(2), theta_b(2)
  type(c_ptr) :: ctx, G
  integer(c_int) :: flag
  type(error_record), target :: rec

  if (FSUNContext_Create(ctx) /= 0) error stop 1
  G = LGNGroup_R3xSO3()
  J = [mass * (3.0_c_double * r**2 + 1.0_c_double) / 12.0_c_double, &
       mass * (3.0_c_double * r**2 + 1.0_c_double) / 12.0_c_double, 0.5_c_double * mass * r**2]
  omega = sqrt(mass * 9.81_c_double * d / (J(2) + mass * d**2))

  call swing(.false., theta_a)
  call expect_near(theta_a(1), theta0 * cos(0.5_c_double * omega), 1.0e-6_c_double, &
                   "model: theta(0.5) against theta0 cos(omega t)")
  call expect_near(theta_a(2), theta0 * cos(omega), 1.0e-6_c_double, &
                   "model: theta(1) against theta0 cos(omega t)")
  call swing(.true., theta_b)
  call expect_near(theta_b(1), theta_a(1), 1.0e-8_c_double, "user-force weight: theta(0.5)")
  call expect_near(theta_b(2), theta_a(2), 1.0e-8_c_double, "user-force weight: theta(1)")
  call bad_input()

  call LGNGroup_Destroy(G)
  flag = SUNContext_Free(ctx)
  call ftest_finish("test_model")

contains

  !> theta at t = 0.5 and 1, gravity from the body set or as a user force
  subroutine swing(user_weight, theta)
    logical, intent(in) :: user_weight
    real(c_double), intent(out) :: theta(2)
    type(c_ptr) :: bodies, joints, model, mem, q, v, y, A, LS
    real(c_double), pointer :: qq(:), vv(:)
    real(c_double) :: t
    integer(c_int64_t) :: m
    integer :: k

    theta = huge(1.0_c_double)
    bodies = LGNBodies_Create(G)
    joints = LGNJoints_Create(G)
    flag = LGNBodies_SetPrincipalInertia(bodies, 0_c_int, mass, J)
    if (.not. user_weight .and. flag == LGN_SUCCESS) &
      flag = LGNBodies_SetGravity(bodies, [0.0_c_double, 0.0_c_double, -9.81_c_double])
    if (flag == LGN_SUCCESS) flag = LGNJoints_AddSpherical(joints, LGN_GROUND, &
      [0.0_c_double, 0.0_c_double, 0.0_c_double], 0_c_int, [0.0_c_double, 0.0_c_double, d])
    model = LGNModel_Create(bodies, joints)
    call expect(c_associated(model), "LGNModel_Create")
    if (user_weight) then
      if (flag == LGN_SUCCESS) flag = LGNModel_SetUserForce(model, c_funloc(weight_fn), &
                                                            c_null_funptr, c_null_funptr)
      if (flag == LGN_SUCCESS) flag = LGNModel_SetUserData(model, c_loc(mass))
      call expect(c_associated(LGNModel_GetUserData(model), c_loc(mass)), "user data kept")
    end if
    m = LGNModel_NumConstraints(model)
    call expect(m == 3_c_int64_t, "m = 3")
    call expect(c_associated(LGNModel_GetBodies(model), bodies), "the model's bodies")
    call expect(c_associated(LGNModel_GetJoints(model), joints), "the model's joints")

    ! tilted by theta0 about y, the joint point (0, 0, d) at the origin
    q = N_VNew_Serial(7_c_int64_t, ctx)
    v = N_VNew_Serial(6_c_int64_t, ctx)
    qq => FN_VGetArray(q)
    vv => FN_VGetArray(v)
    qq = [-d * sin(theta0), 0.0_c_double, -d * cos(theta0), cos(0.5_c_double * theta0), &
          0.0_c_double, sin(0.5_c_double * theta0), 0.0_c_double]
    vv = 0.0_c_double

    mem = LGNCreate(ctx)
    if (flag == LGN_SUCCESS) flag = LGNModel_Attach(model, mem)
    if (flag == LGN_SUCCESS) flag = LGNInit(mem, 0.0_c_double, q, v)
    y = N_VNew_Serial(6_c_int64_t + m, ctx)
    A = SUNDenseMatrix(6_c_int64_t + m, 6_c_int64_t + m, ctx)
    LS = LGNLinSol_Dense(y, A, ctx)
    if (flag == LGN_SUCCESS) flag = LGNSetLinearSolver(mem, LS, A)
    if (flag == LGN_SUCCESS) flag = LGNSetGenAlpha(mem, 0.9_c_double)
    if (flag == LGN_SUCCESS) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE)
    if (flag == LGN_SUCCESS) flag = LGNSStolerances(mem, 1.0e-10_c_double, 1.0e-10_c_double)
    if (flag == LGN_SUCCESS) flag = LGNSetMaxNumSteps(mem, 100000_c_long)
    do k = 1, 2
      if (flag == LGN_SUCCESS) flag = LGNSolve(mem, 0.5_c_double * k, t, q, v, LGN_NORMAL)
      if (flag == LGN_SUCCESS) theta(k) = atan2(-qq(1), -qq(3))
    end do
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "the swing")

    call LGNFree(mem)
    call LGNModel_Destroy(model) ! after LGNFree
    call expect(.not. c_associated(model), "LGNModel_Destroy sets model to c_null_ptr")
    if (SUNLinSolFree(LS) /= 0) flag = -1
    call SUNMatDestroy(A)
    call N_VDestroy(y)
    call N_VDestroy(q)
    call N_VDestroy(v)
    call LGNJoints_Destroy(joints)
    call LGNBodies_Destroy(bodies)
  end subroutine swing

  subroutine bad_input()
    type(c_ptr) :: bodies, model

    bodies = LGNBodies_Create(G)
    call expect(.not. c_associated(LGNModel_Create(c_null_ptr, c_null_ptr)), &
                "LGNModel_Create(null bodies) refused")
    model = LGNModel_Create(bodies, c_null_ptr)
    call expect(LGNModel_NumConstraints(model) == 0_c_int64_t, "no joints: m = 0")
    flag = LGNModel_SetErrHandlerFn(model, c_funloc(record_error), c_loc(rec))
    call expect_flag(LGNModel_Attach(model, c_null_ptr), LGN_MEM_NULL, "LGN_MEM_NULL", &
                     "LGNModel_Attach(null memory)")
    call expect(rec%count == 1, "one message")
    if (rec%count == 1) call expect(index(rec%msg, "lgn_mem") > 0, "the message names lgn_mem")
    call expect_flag(LGNModel_SetUserForce(model, c_null_funptr, c_null_funptr, &
                     c_funloc(weight_fn)), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNModel_SetUserForce(C without a force)")
    call expect(LGNModel_SetErrFile(model, c_null_ptr) == LGN_SUCCESS, "SetErrFile")
    call LGNModel_Destroy(model)
    call LGNBodies_Destroy(bodies)
  end subroutine bad_input

end program test_model
