! -----------------------------------------------------------------------------
! Lignum Fortran study tool: the N-body spherical pendulum chain with KLU, the
! Fortran counterpart of `chain` (bench/tools/chain.c; model in chain_model.f90):
!
!   chain_f [--n N] [--solver klu|klu-csr] [--formulation r3so3]
!           [--method newmark|genalpha] [--rho-inf R] [--beta B --gamma G]
!           [--kinematics simplified|exact] [--constraints index3|index2]
!           [--jacobian analytic|dq] [--h H] [--t-end T] [--outputs K]
!           [--rtol R] [--atol A] [--compare C_OUTPUT]
!
! Same options, same defaults (N = 10, KLU CSC, generalized-alpha
! rho_inf = 0.9, simplified kinematics, index 3, analytic tangents,
! h = 1e-3, t_end = 1, 100 outputs), same calls in the same order as the C
! program (rigid_run of models/rigid_bodies.c) on the product group
! (R^3 x SO(3))^N, with the joints of flignum_joints_mod and the sparse
! matrices written through flignum_klu_mod. Reports, like the C program,
! the work counters, the energy drift max |E(t) - E(0)| and the largest
! constraint violation over the outputs, and the free end with 17 digits.
!
! It fails (exit status 1) unless the run succeeds with max |Phi| at
! round-off level (1e-9 N at index 3, 1e-4 at index 2). With --compare FILE
! (the output of the C program at the same options) it also checks, against
! the C values: the free end to 1e-12 (absolute), the number of steps and
! the nnz of the iteration matrix exactly, Newton/step and E(t_end) to the
! digits C prints.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program chain_f
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod
  use flignum_joints_mod
  use flignum_sundials_mod
  use chain_model
  use fexample_util
  implicit none

  real(c_double), parameter :: compare_tol = 1.0e-12_c_double

  ! options, defaults as rigid_default_run_options + chain.c
  integer :: n = 10, outputs = 100
  logical :: csr = .false., newmark = .false., analytic = .true.
  real(c_double) :: rho_inf = 0.9_c_double, beta = 0.25_c_double, gamma = 0.5_c_double
  real(c_double) :: h = 1.0e-3_c_double, t_end = 1.0_c_double
  real(c_double) :: rtol = 0.0_c_double, atol = 0.0_c_double
  integer(c_int) :: constraints = LGN_CONSTR_INDEX3
  integer(c_int) :: kinematics = LGN_KINEMATICS_SIMPLIFIED
  character(len=:), allocatable :: compare_path

  type(chain_data), target :: sys
  type(c_ptr) :: ctx, mem, qv, vv, phiv, y, A, LS
  real(c_double), pointer :: q(:), v(:), phi(:)
  real(c_double) :: t, tout, energy0, energy, max_drift, max_phi, cpu, c0, c1
  real(c_double) :: tip(3)
  integer(c_long) :: nsteps, nni, ndq, nanalyses, nnz, lenrw, leniw
  integer(c_int64_t) :: nq, nv, m, nsys
  integer(c_int) :: flag
  integer :: k, status

  call parse_options()
  call check(FSUNContext_Create(ctx), "SUNContext_Create")
  call check(chain_create(sys, n, ctx), "chain_create")
  nq = 7_c_int64_t * n
  nv = 6_c_int64_t * n
  m = LGNJoints_NumConstraints(sys%joints)
  nsys = nv + m

  write (*, "(a, i0, a, a, a, a, a, i0, a, es9.3, a, a, a)") "chain of ", n, &
    " rods on (R^3 x SO(3))^N, Fortran, ", &
    trim(merge("Newmark          ", "generalized-alpha", newmark)), ", ", &
    trim(merge("exact     ", "simplified", kinematics == LGN_KINEMATICS_EXACT)), &
    " kinematics, index ", constraints, ", h = ", h, ", t in [0, ", fixed(t_end, 3), "]"

  ! --- the run of rigid_run (models/rigid_bodies.c), call by call -------
  mem = LGNCreate(ctx)
  qv = N_VNew_Serial(nq, ctx)
  vv = N_VNew_Serial(nv, ctx)
  phiv = N_VNew_Serial(m, ctx)
  y = N_VNew_Serial(nsys, ctx)      ! template of the (nv + m) unknowns
  A = SUNSparseMatrix(nsys, nsys, 30 * nsys, merge(CSR_MAT, CSC_MAT, csr), ctx)
  LS = SUNLinSol_KLU(y, A, ctx)
  ! AMD ordering, as the C tool: the iteration matrix's pattern is symmetric
  if (c_associated(LS)) then
    if (SUNLinSol_KLUSetOrdering(LS, 0_c_int) /= 0) call check(LGN_MEM_FAIL, "KLU ordering")
  end if
  call N_VDestroy(y)
  if (.not. (c_associated(mem) .and. c_associated(qv) .and. c_associated(vv) .and. &
             c_associated(phiv) .and. c_associated(A) .and. c_associated(LS))) &
    call check(LGN_MEM_FAIL, "allocation")
  q => FN_VGetArray(qv)
  v => FN_VGetArray(vv)
  phi => FN_VGetArray(phiv)

  call check(LGNSetGroup(mem, sys%G), "LGNSetGroup")
  call check(LGNInit(mem, 0.0_c_double, sys%q0, sys%v0), "LGNInit")
  call check(LGNSetUserData(mem, c_loc(sys)), "LGNSetUserData")
  call check(LGNSetMassFn(mem, c_funloc(chain_mass)), "LGNSetMassFn")
  call check(LGNSetForceFn(mem, c_funloc(chain_force)), "LGNSetForceFn")
  call check(LGNSetConstraints(mem, m, c_funloc(chain_constr), c_funloc(chain_constr_jac)), &
             "LGNSetConstraints")
  if (analytic) then
    call check(LGNSetStiffnessFn(mem, c_funloc(chain_stiffness)), "LGNSetStiffnessFn")
    call check(LGNSetDampingFn(mem, c_funloc(chain_damping)), "LGNSetDampingFn")
    call check(LGNSetCurvatureFn(mem, c_funloc(chain_curvature)), "LGNSetCurvatureFn")
  end if
  call check(LGNSetLinearSolver(mem, LS, A), "LGNSetLinearSolver")
  ! Lignum's solves on a copy of KLU's factors (off by default), opted in as
  ! rigid_run does; KLU's own solves if the versions are not the copy's
  flag = LGNSetOwnKLUSolves(mem, 1_c_int)
  if (flag /= LGN_ILL_INPUT) call check(flag, "LGNSetOwnKLUSolves")
  call check(LGNSetStepSize(mem, h), "LGNSetStepSize")
  if (newmark) then
    call check(LGNSetNewmark(mem, beta, gamma), "LGNSetNewmark")
  else
    call check(LGNSetGenAlpha(mem, rho_inf), "LGNSetGenAlpha")
  end if
  call check(LGNSetKinematics(mem, kinematics), "LGNSetKinematics")
  call check(LGNSetConstraintIndex(mem, constraints), "LGNSetConstraintIndex")
  if (rtol > 0) call check(LGNSStolerances(mem, rtol, atol), "LGNSStolerances")

  ! --- integrate, sampling energy and constraints at the outputs ------------------
  energy0 = chain_energy(sys, FN_VGetArray(sys%q0), FN_VGetArray(sys%v0))
  energy = energy0
  max_drift = 0.0_c_double
  call check(LGNJoints_Residual(sys%joints, 0.0_c_double, sys%q0, phiv), "LGNJoints_Residual")
  max_phi = maxval(abs(phi))
  cpu = 0.0_c_double
  t = 0.0_c_double
  flag = LGN_SUCCESS
  do k = 1, outputs
    tout = t_end * real(k, c_double) / real(outputs, c_double)
    call cpu_time(c0)
    flag = LGNSolve(mem, tout, t, qv, vv, LGN_NORMAL)
    call cpu_time(c1)
    cpu = cpu + (c1 - c0)
    if (flag /= LGN_SUCCESS) exit
    energy = chain_energy(sys, q, v)
    max_drift = max(max_drift, abs(energy - energy0))
    call check(LGNJoints_Residual(sys%joints, t, qv, phiv), "LGNJoints_Residual")
    max_phi = max(max_phi, maxval(abs(phi)))
  end do
  call check(LGNGetNumSteps(mem, nsteps), "LGNGetNumSteps")
  call check(LGNGetNumNewtonIters(mem, nni), "LGNGetNumNewtonIters")
  call check(LGNGetNumDQEvals(mem, ndq), "LGNGetNumDQEvals")
  call check(LGNGetNumSparsityAnalyses(mem, nanalyses), "LGNGetNumSparsityAnalyses")
  call check(LGNGetIterationMatrixNnz(mem, nnz), "LGNGetIterationMatrixNnz")
  call check(LGNGetWorkSpace(mem, lenrw, leniw), "LGNGetWorkSpace")
  tip = chain_free_end(sys, q)

  ! --- report (the lines of chain.c) -------------------------------------------------
  write (*, "(a, 1x, a, a, a, a, i0, a, a, a, i0, a, i0, a, i0, a, a, a, es9.3, a)") &
    merge("klu-csr ", "klu     ", csr), merge("analytic ", "dq       ", analytic), &
    " t = ", fixed(t, 3), "  steps ", nsteps, "  Newton/step ", &
    fixed(per_step(real(nni, c_double)), 2), "  DQ evals ", ndq, "  analyses ", nanalyses, &
    "  nnz ", nnz, "  cpu ", fixed(cpu, 3), " s (", per_step(1.0e3_c_double * cpu), " ms/step)"
  write (*, "(a, es17.10, a, es17.10, a, es9.3, a, es9.3, a)") &
    "         energy E0 = ", energy0, "  E(t_end) = ", energy, "  max |E - E0| = ", &
    max_drift, " (relative to the potential scale N^2 m g L/2: ", &
    max_drift / (0.5_c_double * 9.81_c_double * n * n), ")"
  write (*, "(a, es9.3, a, i0, a, i0, a, i0, a)") "         max |Phi| = ", max_phi, &
    "   work space ", lenrw, " reals + ", leniw, " integers (", &
    nint((8.0_c_double * lenrw + 8.0_c_double * leniw) / n), " bytes/body)"
  call print_values("         free end", tip)

  ! --- own checks (those of chain.c), then the comparison with C -----------------------
  status = 0
  if (flag /= LGN_SUCCESS .or. max_phi > merge(1.0e-9_c_double * n, 1.0e-4_c_double, &
                                               constraints == LGN_CONSTR_INDEX3)) then
    write (*, "(a, a, a, es9.3)") "FAILED: flag ", FLGNGetReturnFlagName(flag), &
      ", max |Phi| = ", max_phi
    status = 1
  end if
  if (allocated(compare_path)) call compare_with_c()
  write (*, "(a)") merge("PASSED", "FAILED", status == 0)

  call LGNFree(mem)
  call check(SUNLinSolFree(LS), "SUNLinSolFree")
  call SUNMatDestroy(A)
  call N_VDestroy(qv)
  call N_VDestroy(vv)
  call N_VDestroy(phiv)
  call chain_free(sys)
  call check(SUNContext_Free(ctx), "SUNContext_Free")
  ! variables of the main program are never deallocated automatically
  if (allocated(compare_path)) deallocate (compare_path)

  if (status /= 0) error stop 1

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

  !> Compare with the C program's output file (the lines of its Report).
  subroutine compare_with_c()
    real(c_double) :: ref_tip(3), ref(1), diff
    logical :: found
    integer :: nfail

    nfail = 0
    ! the free end, printed by C with %.17g: read back exactly
    call reference_after(compare_path, "free end", ref_tip, found)
    if (found) then
      diff = maxval(abs(tip - ref_tip))
      write (*, "(a, es9.3, a, es9.3, a)") "compare: free end |F - C|_max = ", diff, &
        " (must be <= ", compare_tol, ")"
      if (.not. (diff <= compare_tol)) nfail = nfail + 1
    else
      nfail = nfail + 1
    end if
    call reference_after(compare_path, "steps ", ref, found)
    call compare_count("steps", nsteps, ref(1), found, nfail)
    call reference_after(compare_path, "nnz ", ref, found)
    call compare_count("nnz of the iteration matrix", nnz, ref(1), found, nfail)
    ! %.2f and %.10g: equal to the printed digits
    call reference_after(compare_path, "Newton/step ", ref, found)
    call compare_printed("Newton/step", per_step(real(nni, c_double)), ref(1), &
                         0.005_c_double, found, nfail)
    call reference_after(compare_path, "E(t_end) = ", ref, found)
    call compare_printed("E(t_end)", energy, ref(1), 5.0e-10_c_double * abs(ref(1)), &
                         found, nfail)
    if (nfail > 0) then
      write (error_unit, "(a, i0, a, a)") "comparison with C: ", nfail, &
        " failure(s), reference file ", compare_path
      status = 1
    end if
  end subroutine compare_with_c

  !> x per step (0 before the first step).
  function per_step(x) result(y)
    real(c_double), intent(in) :: x
    real(c_double) :: y

    y = 0.0_c_double
    if (nsteps > 0) y = x / real(nsteps, c_double)
  end function per_step

  !> A count equal to the C one.
  subroutine compare_count(name, mine, ref, found, nfail)
    character(len=*), intent(in) :: name
    integer(c_long), intent(in) :: mine
    real(c_double), intent(in) :: ref
    logical, intent(in) :: found
    integer, intent(inout) :: nfail

    if (found .and. mine == nint(ref, c_long)) then
      write (*, "(a, a, a, i0, a)") "compare: ", name, " ", mine, " as in C"
    else
      write (error_unit, "(a, a, a, i0, a, f0.0)") "compare: ", name, " ", mine, &
        " DIFFERS from C: ", ref
      nfail = nfail + 1
    end if
  end subroutine compare_count

  !> A value equal to the C one up to the precision C printed it with.
  subroutine compare_printed(name, mine, ref, tol, found, nfail)
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: mine, ref, tol
    logical, intent(in) :: found
    integer, intent(inout) :: nfail

    if (found .and. abs(mine - ref) <= tol) then
      write (*, "(a, a, a, es24.16, a, es9.3, a)") "compare: ", name, " ", mine, &
        " as in C (to the printed ", tol, ")"
    else
      write (error_unit, "(a, a, a, es24.16, a, es24.16)") "compare: ", name, " ", &
        mine, " DIFFERS from C: ", ref
      nfail = nfail + 1
    end if
  end subroutine compare_printed

  !> Parse the command line (the options of chain.c for KLU on (R^3 x SO(3))^N).
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
      case ("--n")
        call parse_int(val, n, ok)
        ok = ok .and. n >= 1
      case ("--solver")
        ok = val == "klu" .or. val == "klu-csr"
        csr = val == "klu-csr"
      case ("--formulation")
        ok = val == "r3so3"
      case ("--method")
        ok = val == "newmark" .or. val == "genalpha"
        newmark = val == "newmark"
      case ("--kinematics")
        select case (val)
        case ("simplified"); kinematics = LGN_KINEMATICS_SIMPLIFIED
        case ("exact"); kinematics = LGN_KINEMATICS_EXACT
        case default; ok = .false.
        end select
      case ("--constraints")
        select case (val)
        case ("index3"); constraints = LGN_CONSTR_INDEX3
        case ("index2"); constraints = LGN_CONSTR_INDEX2
        case default; ok = .false.
        end select
      case ("--jacobian")
        ok = val == "analytic" .or. val == "dq"
        analytic = val == "analytic"
      case ("--rho-inf"); call parse_real(val, rho_inf, ok)
      case ("--beta"); call parse_real(val, beta, ok)
      case ("--gamma"); call parse_real(val, gamma, ok)
      case ("--h")
        call parse_real(val, h, ok)
        ok = ok .and. h > 0
      case ("--t-end")
        call parse_real(val, t_end, ok)
        ok = ok .and. t_end > 0
      case ("--outputs")
        call parse_int(val, outputs, ok)
        ok = ok .and. outputs >= 1
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

    write (error_unit, "(a, a)") "chain_f: ", msg
    write (error_unit, "(a)") &
      "usage: chain_f [--n N] [--solver klu|klu-csr] [--formulation r3so3]", &
      "         [--method newmark|genalpha] [--rho-inf R] [--beta B --gamma G]", &
      "         [--kinematics simplified|exact] [--constraints index3|index2]", &
      "         [--jacobian analytic|dq] [--h H] [--t-end T] [--outputs K]", &
      "         [--rtol R] [--atol A] [--compare C_OUTPUT]"
    error stop 2
  end subroutine usage

end program chain_f
