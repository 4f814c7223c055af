! -----------------------------------------------------------------------------
! Lignum teaching example (Fortran twin of ../heavy_top.c): the heavy top
! with error control, through flignum_mod, flignum_bodies_mod,
! flignum_joints_mod, flignum_model_mod and flignum_sundials_mod.
!
! One body on R^3 x SO(3) (mass 15, J = diag(0.234375, 0.46875, 0.234375),
! centre of mass X = (0, 1, 0) in the body frame), its point -X held at the
! origin by a spherical joint, gravity (0, 0, -9.81); R = I and
! Omega = (0, 150, -4.61538) at the start. The model object (LGNModel_Create,
! LGNModel_Attach) gives Lignum every callback from the body set and the
! joint set. Generalized-alpha (0.9), error control with rtol = atol = 1e-6.
! It prints the table of heavy_top.c (same answer file).
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
program heavy_top_f
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod
  use flignum_bodies_mod
  use flignum_joints_mod
  use flignum_model_mod
  use flignum_sundials_mod
  implicit none

  real(c_double), parameter :: X(3) = [0.0_c_double, 1.0_c_double, 0.0_c_double]
  real(c_double), parameter :: J(3) = [0.234375_c_double, 0.46875_c_double, 0.234375_c_double]
  real(c_double), parameter :: gvec(3) = [0.0_c_double, 0.0_c_double, -9.81_c_double]
  real(c_double), parameter :: omega0(3) = [0.0_c_double, 150.0_c_double, -4.61538_c_double]
  real(c_double), parameter :: rtol = 1.0e-6_c_double, atol = 1.0e-6_c_double
  real(c_double), parameter :: dtout = 0.1_c_double, tend = 1.0_c_double
  type(c_ptr) :: ctx, G, bodies, joints, model, q, v, phi, y, A, LS, mem
  real(c_double), pointer :: qq(:), vv(:)
  real(c_double) :: t, tout
  integer(c_int64_t) :: m
  integer(c_long) :: nst, nni, netf
  integer(c_int) :: flag

  if (FSUNContext_Create(ctx) /= 0) error stop 1
  G = LGNGroup_R3xSO3() ! q = (x, p): nq = 7, v = (u, Omega): nv = 6

  ! the model: one body, gravity, a spherical joint to the ground
  bodies = LGNBodies_Create(G)
  joints = LGNJoints_Create(G)
  flag = LGNBodies_SetPrincipalInertia(bodies, 0_c_int, 15.0_c_double, J)
  if (flag == LGN_SUCCESS) flag = LGNBodies_SetGravity(bodies, gvec)
  if (flag == LGN_SUCCESS) flag = LGNJoints_AddSpherical(joints, LGN_GROUND, &
                                    [0.0_c_double, 0.0_c_double, 0.0_c_double], 0_c_int, -X)
  model = LGNModel_Create(bodies, joints)
  m = LGNModel_NumConstraints(model) ! 3

  ! initial state: x = X, p = identity, u = Omega x X (R = I)
  q = N_VNew_Serial(7_c_int64_t, ctx)
  v = N_VNew_Serial(6_c_int64_t, ctx)
  phi = N_VNew_Serial(m, ctx)
  qq => FN_VGetArray(q)
  vv => FN_VGetArray(v)
  qq = [X, 1.0_c_double, 0.0_c_double, 0.0_c_double, 0.0_c_double]
  vv(1:3) = [omega0(2) * X(3) - omega0(3) * X(2), omega0(3) * X(1) - omega0(1) * X(3), &
             omega0(1) * X(2) - omega0(2) * X(1)]
  vv(4:6) = omega0

  mem = LGNCreate(ctx)
  if (flag == LGN_SUCCESS) flag = LGNModel_Attach(model, mem) ! every callback
  if (flag == LGN_SUCCESS) flag = LGNInit(mem, 0.0_c_double, q, v)

  ! dense linear solver on the (nv + m) x (nv + m) iteration matrix
  y = N_VNew_Serial(6_c_int64_t + m, ctx)
  A = SUNDenseMatrix(6_c_int64_t + m, 6_c_int64_t + m, ctx)
  LS = LGNLinSol_Dense(y, A, ctx)
  if (flag == LGN_SUCCESS) flag = LGNSetLinearSolver(mem, LS, A)

  ! generalized-alpha with error control (the step size is the first tried)
  if (flag == LGN_SUCCESS) flag = LGNSetGenAlpha(mem, 0.9_c_double)
  if (flag == LGN_SUCCESS) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE)
  if (flag == LGN_SUCCESS) flag = LGNSStolerances(mem, rtol, atol)
  if (flag == LGN_SUCCESS) flag = LGNSetStepSize(mem, 1.0e-3_c_double)
  if (flag == LGN_SUCCESS) flag = LGNSetMaxNumSteps(mem, 100000_c_long)

  write (*, "(a)") "Heavy top on R^3 x SO(3), spherical joint, generalized-alpha(0.9),"
  write (*, "(a)") "error control with rtol = atol = 1e-06"
  write (*, "(a)") ""
  write (*, "(a5, 3(1x, a12), 1x, a14, 1x, a10)") "t", "x", "y", "z", "energy", "|Phi|"
  t = 0.0_c_double
  if (flag == LGN_SUCCESS) call print_row()
  tout = dtout
  do while (flag == LGN_SUCCESS .and. tout <= tend + 0.5_c_double * dtout)
    flag = LGNSolve(mem, tout, t, q, v, LGN_NORMAL)
    if (flag /= LGN_SUCCESS) exit
    call print_row()
    tout = tout + dtout
  end do
  if (flag /= LGN_SUCCESS) write (error_unit, "(2a)") "heavy_top_f: ", FLGNGetReturnFlagName(flag)

  if (LGNGetNumSteps(mem, nst) /= LGN_SUCCESS) nst = -1
  if (LGNGetNumNewtonIters(mem, nni) /= LGN_SUCCESS) nni = -1
  if (LGNGetNumErrTestFails(mem, netf) /= LGN_SUCCESS) netf = -1
  write (*, "(a)") ""
  write (*, "(a, i0, a, i0, a, i0)") "steps = ", nst, "   Newton iterations = ", nni, &
    "   error test failures = ", netf

  call LGNFree(mem)
  if (SUNLinSolFree(LS) /= 0) flag = -1
  call SUNMatDestroy(A)
  call N_VDestroy(y)
  call N_VDestroy(phi)
  call N_VDestroy(q)
  call N_VDestroy(v)
  call LGNModel_Destroy(model) ! after LGNFree
  call LGNJoints_Destroy(joints)
  call LGNBodies_Destroy(bodies)
  call LGNGroup_Destroy(G)
  if (SUNContext_Free(ctx) /= 0) flag = -1
  if (flag /= LGN_SUCCESS) error stop 1

contains

  !> t, the centre of mass, the energy and |Phi|_2
  subroutine print_row()
    real(c_double) :: kin, pot
    real(c_double), pointer :: ph(:)

    if (LGNBodies_Energy(bodies, q, v, kin, pot) /= 0) error stop 1
    if (LGNJoints_Residual(joints, t, q, phi) /= 0) error stop 1
    ph => FN_VGetArray(phi)
    write (*, "(f5.2, 3(1x, f12.6), 1x, f14.6, 1x, es10.1)") t, qq(1:3), kin + pot, norm2(ph)
  end subroutine print_row

end program heavy_top_f
