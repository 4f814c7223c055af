! -----------------------------------------------------------------------------
! Lignum Fortran study tool: the heavy top (Brüls and Cardona 2010) on R^3 x SO(3),
! the Fortran counterpart of `heavy_top --formulation lie` (bench/tools/heavy_top.c):
!
!   heavy_top_f [--formulation lie] [--method newmark|genalpha] [--rho-inf R]
!               [--beta B --gamma G] [--constraints index3|index2]
!               [--kinematics simplified|exact|sigma] [--jacobian analytic|dq]
!               [--predictor zero|extrapolate] [--h H] [--t-end T]
!               [--rtol R] [--atol A] [--compare C_OUTPUT]
!
! Same options, same defaults, same calls in the same order as the C
! program; prints the final state in its format ("com_final x y z", 17
! digits). With --compare FILE (the output of the C program at the same
! options) it checks its final centre of mass, quaternion, angular velocity
! and multiplier against the C values to 1e-12 (relative to max(1, |value|))
! and exits nonzero on a mismatch. Without it, it checks that the run
! succeeded and the joint stayed closed (|Phi| <= 1e-10 at index 3, the
! drift <= 1e-2 at index 2).
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program heavy_top_f
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod
  use flignum_sundials_mod
  use heavy_top_model
  use fexample_util
  implicit none

  real(c_double), parameter :: compare_tol = 1.0e-12_c_double

  ! options, defaults as heavy_top_default_options (models/heavy_top.c)
  logical :: newmark = .false., analytic = .true.
  real(c_double) :: rho_inf = 0.9_c_double, beta = 0.25_c_double, gamma = 0.5_c_double
  real(c_double) :: h = 1.0e-3_c_double, t_end = 1.0_c_double
  real(c_double) :: rtol = 0.0_c_double, atol = 0.0_c_double
  integer(c_int) :: constraints = LGN_CONSTR_INDEX3
  integer(c_int) :: kinematics = LGN_KINEMATICS_SIMPLIFIED
  integer(c_int) :: predictor = LGN_PREDICTOR_ZERO
  character(len=:), allocatable :: compare_path

  type(heavy_top_data), target :: model
  type(c_ptr) :: ctx, G, qvec, vvec, lvec, tmpl, A, LS, mem
  real(c_double), pointer :: q(:), v(:), lambda(:)
  real(c_double) :: t, tout, max_phi, nrm, sgn
  real(c_double) :: com(3), quat(4), omega(3), lam(3)
  integer(c_long) :: k, nsteps
  integer :: nfail

  call parse_options()

  ! --- SUNDIALS objects and the group -----------------------------------------
  call check(FSUNContext_Create(ctx), "SUNContext_Create")
  G = LGNGroup_R3xSO3()
  qvec = N_VNew_Serial(7_c_int64_t, ctx)
  vvec = N_VNew_Serial(6_c_int64_t, ctx)
  lvec = N_VNew_Serial(3_c_int64_t, ctx)
  A = SUNDenseMatrix(9_c_int64_t, 9_c_int64_t, ctx)   ! (nv + m) x (nv + m)
  tmpl = N_VNew_Serial(9_c_int64_t, ctx)               ! template of the solver
  LS = SUNLinSol_Dense(tmpl, A, ctx)
  mem = LGNCreate(ctx)
  if (.not. (c_associated(G) .and. c_associated(qvec) .and. c_associated(vvec) &
             .and. c_associated(lvec) .and. c_associated(LS) .and. c_associated(mem))) &
    call check(LGN_MEM_FAIL, "allocation")
  q => FN_VGetArray(qvec)
  v => FN_VGetArray(vvec)
  lambda => FN_VGetArray(lvec)
  call heavy_top_initial_state(model, q, v)

  ! --- model: callbacks written in Fortran, model data as user data --------------
  call check(LGNSetGroup(mem, G), "LGNSetGroup")
  call check(LGNSetUserData(mem, c_loc(model)), "LGNSetUserData")
  call check(LGNSetMassFn(mem, c_funloc(ht_mass)), "LGNSetMassFn")
  call check(LGNSetForceFn(mem, c_funloc(ht_force)), "LGNSetForceFn")
  call check(LGNSetConstraints(mem, 3_c_int64_t, c_funloc(ht_constr), &
                               c_funloc(ht_constr_jac)), "LGNSetConstraints")
  if (analytic) then
    call check(LGNSetStiffnessFn(mem, c_funloc(ht_stiffness)), "LGNSetStiffnessFn")
    call check(LGNSetDampingFn(mem, c_funloc(ht_damping)), "LGNSetDampingFn")
    call check(LGNSetCurvatureFn(mem, c_funloc(ht_curvature)), "LGNSetCurvatureFn")
  end if

  ! --- method and solver (the order of heavy_top.c) -----------------------------
  call check(LGNInit(mem, 0.0_c_double, qvec, vvec), "LGNInit")
  call check(LGNSetLinearSolver(mem, LS, A), "LGNSetLinearSolver")
  if (newmark) then
    call check(LGNSetNewmark(mem, beta, gamma), "LGNSetNewmark")
  else
    call check(LGNSetGenAlpha(mem, rho_inf), "LGNSetGenAlpha")
  end if
  call check(LGNSetConstraintIndex(mem, constraints), "LGNSetConstraintIndex")
  call check(LGNSetKinematics(mem, kinematics), "LGNSetKinematics")
  call check(LGNSetStepSize(mem, h), "LGNSetStepSize")
  if (rtol > 0.0_c_double .or. atol > 0.0_c_double) &
    call check(LGNSStolerances(mem, rtol, atol), "LGNSStolerances")
  ! the step's own values, as the C model (models/heavy_top.c)
  call check(LGNSetConsistentOutputs(mem, 0_c_int), "LGNSetConsistentOutputs")
  call check(LGNSetProjectOutputs(mem, LGN_PROJECT_NONE), "LGNSetProjectOutputs")
  call check(LGNSetPredictor(mem, predictor), "LGNSetPredictor")

  ! --- integrate: consistent initial values, then output at t_k = k h -------------
  write (*, "(a)") "Heavy top (Brüls-Cardona 2010), Fortran, R^3 x SO(3) formulation"
  write (*, "(a, es10.3, a, es10.3, a, l1)") "h = ", h, ", t_end = ", t_end, &
    ", analytic Jacobians: ", analytic
  nsteps = ceiling(t_end / h - 1.0e-9_c_double, kind=c_long)
  t = 0.0_c_double
  call check(LGNSolve(mem, 0.0_c_double, t, qvec, vvec, LGN_NORMAL), "LGNSolve")
  max_phi = ht_joint_violation(model, q)
  do k = 1, nsteps
    tout = min(real(k, c_double) * h, t_end)
    call check(LGNSolve(mem, tout, t, qvec, vvec, LGN_NORMAL), "LGNSolve")
    max_phi = max(max_phi, ht_joint_violation(model, q))
  end do
  call check(LGNGetMultipliers(mem, lvec), "LGNGetMultipliers")

  ! --- final state in the variables of heavy_top.c (quaternion with w >= 0) --------
  com = q(1:3)
  nrm = sqrt(q(4) * q(4) + q(5) * q(5) + q(6) * q(6) + q(7) * q(7))
  sgn = merge(1.0_c_double, -1.0_c_double, q(4) >= 0.0_c_double)
  quat = sgn * q(4:7) / nrm
  omega = v(4:6)
  lam = lambda(1:3)

  write (*, "(/, a, a)") "status     ", FLGNGetReturnFlagName(LGN_SUCCESS)
  call print_values("t_final", [t])
  call print_values("com_final", com)
  call print_values("quat_final", quat)
  call print_values("omega_final", omega)
  call print_values("lambda_final", lam)
  write (*, "(a, es10.3, /)") "max_phi    ", max_phi
  call check(FLGNPrintAllStats(mem, SUN_OUTPUTFORMAT_TABLE), "LGNPrintAllStats")

  ! --- own checks ------------------------------------------------------------------
  nfail = 0
  if (allocated(compare_path)) then
    call compare_with_c()
  else if (max_phi > merge(1.0e-10_c_double, 1.0e-2_c_double, &
                           constraints == LGN_CONSTR_INDEX3)) then
    ! index 3 keeps Phi = 0 to the Newton tolerance; index 2 drifts
    write (error_unit, "(a, es10.3)") "joint violation too large: ", max_phi
    nfail = 1
  end if

  call LGNFree(mem)
  call check(SUNLinSolFree(LS), "SUNLinSolFree")
  call SUNMatDestroy(A)
  call N_VDestroy(qvec)
  call N_VDestroy(vvec)
  call N_VDestroy(lvec)
  call N_VDestroy(tmpl)
  call LGNGroup_Destroy(G)
  call check(SUNContext_Free(ctx), "SUNContext_Free")
  ! variables of the main program are never deallocated automatically
  if (allocated(compare_path)) deallocate (compare_path)

  if (nfail > 0) error stop 1

contains

  !> Stop with the flag's name unless flag is LGN_SUCCESS (0).
  subroutine check(flag, what)
    integer(c_int), intent(in) :: flag
    character(len=*), intent(in) :: what

    if (flag /= LGN_SUCCESS) then
      write (error_unit, "(a, a, a, a, i0, a)") what, " failed: ", &
        FLGNGetReturnFlagName(flag), " (", flag, ")"
      error stop 1
    end if
  end subroutine check

  !> Compare the final state with the C program's output file.
  subroutine compare_with_c()
    real(c_double) :: ref3(3), ref4(4), ref1(1)
    logical :: found

    call reference_values(compare_path, "t_final", ref1, found)
    if (found) call check_close("t_final", [t], ref1, compare_tol, nfail)
    if (.not. found) nfail = nfail + 1
    call reference_values(compare_path, "com_final", ref3, found)
    if (found) call check_close("com_final", com, ref3, compare_tol, nfail)
    if (.not. found) nfail = nfail + 1
    call reference_values(compare_path, "quat_final", ref4, found)
    if (found) call check_close("quat_final", quat, ref4, compare_tol, nfail)
    if (.not. found) nfail = nfail + 1
    call reference_values(compare_path, "omega_final", ref3, found)
    if (found) call check_close("omega_final", omega, ref3, compare_tol, nfail)
    if (.not. found) nfail = nfail + 1
    call reference_values(compare_path, "lambda_final", ref3, found)
    if (found) call check_close("lambda_final", lam, ref3, compare_tol, nfail)
    if (.not. found) nfail = nfail + 1
    if (nfail > 0) write (error_unit, "(a, i0, a, a)") "comparison with C: ", nfail, &
      " failure(s), reference file ", compare_path
  end subroutine compare_with_c

  !> Parse the command line (options of heavy_top.c that apply to R^3 x SO(3)).
  subroutine parse_options()
    character(len=:), allocatable :: key, val
    integer :: i, nargs
    logical :: ok

    nargs = command_argument_count()
    i = 1
    do while (i <= nargs)
      key = get_arg(i)
      if (i + 1 > nargs) call usage("missing value of "//key)
      val = get_arg(i + 1)
      ok = .true.
      select case (key)
      case ("--formulation")
        ok = val == "lie"
      case ("--method")
        ok = val == "newmark" .or. val == "genalpha"
        newmark = val == "newmark"
      case ("--constraints")
        select case (val)
        case ("index3"); constraints = LGN_CONSTR_INDEX3
        case ("index2"); constraints = LGN_CONSTR_INDEX2
        case default; ok = .false.
        end select
      case ("--kinematics")
        select case (val)
        case ("simplified"); kinematics = LGN_KINEMATICS_SIMPLIFIED
        case ("exact"); kinematics = LGN_KINEMATICS_EXACT
        case ("sigma"); kinematics = LGN_KINEMATICS_SIGMA
        case default; ok = .false.
        end select
      case ("--jacobian")
        ok = val == "analytic" .or. val == "dq"
        analytic = val == "analytic"
      case ("--predictor")
        select case (val)
        case ("zero"); predictor = LGN_PREDICTOR_ZERO
        case ("extrapolate"); predictor = LGN_PREDICTOR_EXTRAPOLATE
        case default; ok = .false.
        end select
      case ("--rho-inf"); call parse_real(val, rho_inf, ok)
      case ("--beta"); call parse_real(val, beta, ok)
      case ("--gamma"); call parse_real(val, gamma, ok)
      case ("--h"); call parse_real(val, h, ok); ok = ok .and. h > 0
      case ("--t-end"); call parse_real(val, t_end, ok); ok = ok .and. t_end > 0
      case ("--rtol"); call parse_real(val, rtol, ok); ok = ok .and. rtol >= 0
      case ("--atol"); call parse_real(val, atol, ok); ok = ok .and. atol >= 0
      case ("--compare"); compare_path = val
      case default; ok = .false.
      end select
      if (.not. ok) call usage("bad option or value: "//key//" "//val)
      i = i + 2
    end do
  end subroutine parse_options

  !> Print the usage and stop with status 2.
  subroutine usage(msg)
    character(len=*), intent(in) :: msg

    write (error_unit, "(a, a)") "heavy_top_f: ", msg
    write (error_unit, "(a)") &
      "usage: heavy_top_f [--formulation lie] [--method newmark|genalpha] [--rho-inf R]", &
      "         [--beta B --gamma G] [--constraints index3|index2]", &
      "         [--kinematics simplified|exact|sigma] [--jacobian analytic|dq]", &
      "         [--predictor zero|extrapolate] [--h H] [--t-end T]", &
      "         [--rtol R] [--atol A] [--compare C_OUTPUT]"
    error stop 2
  end subroutine usage

end program heavy_top_f
