! -----------------------------------------------------------------------------
! Lignum Fortran test: the C API through flignum_mod, call by call.
!
!  - return flags seen from Fortran and their names (FLGNGetReturnFlagName):
!    NULL memory -> LGN_MEM_NULL, LGNSolve before LGNInit -> LGN_NO_MALLOC,
!    a negative step -> LGN_ILL_INPUT, tout behind -> LGN_BAD_TOUT, a failing
!    Fortran force callback -> LGN_FORCE_FAIL; every flag's name;
!  - a Fortran error handler (code, function name, message via FLGNString,
!    its data via c_loc/c_f_pointer); the error file and LGNPrintAllStats
!    on C streams opened from Fortran;
!  - built-in groups (FLGNGroup_Rec), products, the dispatchers and the
!    quaternion helpers; a group defined in Fortran (R^1 with bind(C) ops);
!  - a complete integration on that group: the oscillator q'' = -q with
!    Newmark (1/4, 1/2), exact kinematics, against cos(t); every setter and
!    getter of lignum.h is called once;
!  - the same oscillator with error control (LGN_STEP_ADAPTIVE): LGN_NORMAL
!    interpolating at tout, a stop time (LGN_TSTOP_RETURN), LGNGetDky and
!    the error-control setters and getters.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------

! Callbacks (bind(C) procedures must be module procedures).
module test_api_callbacks
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_sundials_mod
  implicit none

  !> Oscillator data (user data): stiffness, and a switch to make the force fail.
  type :: oscillator
    real(c_double) :: k = 1.0_c_double
    logical :: fail_force = .false.
  end type oscillator

contains

  ! --- R^n as a user-supplied group: exp(w) = w, T = I, Tdot = 0 ----------------

  !> LGNGroupComposeExpFn: q_out = q + w.
  integer(c_int) function rn_compose_exp(G, q, w, q_out) result(ierr) bind(c)
    type(c_ptr), value :: G
    real(c_double) :: q(*), w(*), q_out(*)
    integer(c_int64_t) :: n

    n = FLGNGroup_NQ(G)
    q_out(1:n) = q(1:n) + w(1:n)
    ierr = 0
  end function rn_compose_exp

  !> LGNGroupTangentApplyFn: y = T(w) x = x (also T^{-1}).
  integer(c_int) function rn_tangent_apply(G, w, x, y) result(ierr) bind(c)
    type(c_ptr), value :: G
    real(c_double), intent(in) :: w(*), x(*)
    real(c_double), intent(out) :: y(*)
    integer(c_int64_t) :: n

    n = FLGNGroup_NV(G)
    y(1:n) = x(1:n)
    ierr = 0
  end function rn_tangent_apply

  !> LGNGroupTangentDotApplyFn: y = Tdot x = 0.
  integer(c_int) function rn_tangent_dot_apply(G, w, wdot, x, y) result(ierr) bind(c)
    type(c_ptr), value :: G
    real(c_double), intent(in) :: w(*), wdot(*), x(*)
    real(c_double), intent(out) :: y(*)

    y(1:FLGNGroup_NV(G)) = 0.0_c_double
    ierr = 0
  end function rn_tangent_dot_apply

  !> LGNGroupTangentMatrixFn: Tm = I (column-major, leading dimension ld).
  integer(c_int) function rn_tangent_matrix(G, w, Tm, ld) result(ierr) bind(c)
    type(c_ptr), value :: G
    real(c_double), intent(in) :: w(*)
    real(c_double), intent(inout) :: Tm(*)
    integer(c_int64_t), value :: ld
    integer(c_int64_t) :: i, j, n

    n = FLGNGroup_NV(G)
    do j = 1, n
      do i = 1, n
        Tm(i + (j - 1) * ld) = merge(1.0_c_double, 0.0_c_double, i == j)
      end do
    end do
    ierr = 0
  end function rn_tangent_matrix

  !> LGNGroupIdentityFn: q = 0.
  integer(c_int) function rn_identity(G, q) result(ierr) bind(c)
    type(c_ptr), value :: G
    real(c_double), intent(inout) :: q(*)

    q(1:FLGNGroup_NQ(G)) = 0.0_c_double
    ierr = 0
  end function rn_identity

  ! --- the oscillator q'' + k q = 0 ---------------------------------------------

  !> LGNMassFn: M = 1.
  integer(c_int) function osc_mass(t, q, M, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, M, user_data
    real(c_double), pointer :: a(:, :)

    a => FSUNDenseMatrix_Array(M)
    a(1, 1) = 1.0_c_double
    ierr = 0
  end function osc_mass

  !> LGNForceFn: g = k q; fails (-1) when the user data say so.
  integer(c_int) function osc_force(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    type(oscillator), pointer :: osc
    real(c_double), pointer :: qq(:), gg(:)

    call c_f_pointer(user_data, osc)
    qq => FN_VGetArray(q)
    gg => FN_VGetArray(g)
    gg(1) = osc%k * qq(1)
    ierr = merge(-1_c_int, 0_c_int, osc%fail_force)
  end function osc_force

  !> LGNRootFn: g = (q, q - 1/2), events of the oscillator.
  integer(c_int) function osc_root(t, q, v, gout, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v
    real(c_double) :: gout(*)
    type(c_ptr), value :: user_data
    real(c_double), pointer :: qq(:)

    qq => FN_VGetArray(q)
    gout(1) = qq(1)
    gout(2) = qq(1) - 0.5_c_double
    ierr = 0
  end function osc_root

end module test_api_callbacks

program test_api
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_sundials_mod
  use test_api_callbacks
  use ftest_util
  implicit none

  call test_flag_names()
  call test_usage_errors()
  call test_groups()
  call test_parameter_map()
  call test_oscillator()
  call test_adaptive()
  call test_vtk()
  call ftest_finish("test_api")

contains

  !> Every flag's name, and the name of an unknown value.
  subroutine test_flag_names()
    call name_is(LGN_SUCCESS, "LGN_SUCCESS")
    call name_is(LGN_TOO_MUCH_WORK, "LGN_TOO_MUCH_WORK")
    call name_is(LGN_CONV_FAILURE, "LGN_CONV_FAILURE")
    call name_is(LGN_MASS_FAIL, "LGN_MASS_FAIL")
    call name_is(LGN_FORCE_FAIL, "LGN_FORCE_FAIL")
    call name_is(LGN_CONSTR_FAIL, "LGN_CONSTR_FAIL")
    call name_is(LGN_CONSTR_JAC_FAIL, "LGN_CONSTR_JAC_FAIL")
    call name_is(LGN_TANGENT_FAIL, "LGN_TANGENT_FAIL")
    call name_is(LGN_GROUP_FAIL, "LGN_GROUP_FAIL")
    call name_is(LGN_NONFINITE, "LGN_NONFINITE")
    call name_is(LGN_REPTD_CALLBACK_ERR, "LGN_REPTD_CALLBACK_ERR")
    call name_is(LGN_IC_FAIL, "LGN_IC_FAIL")
    call name_is(LGN_INCONSISTENT_IC, "LGN_INCONSISTENT_IC")
    call name_is(LGN_MEM_NULL, "LGN_MEM_NULL")
    call name_is(LGN_MEM_FAIL, "LGN_MEM_FAIL")
    call name_is(LGN_ILL_INPUT, "LGN_ILL_INPUT")
    call name_is(LGN_NO_MALLOC, "LGN_NO_MALLOC")
    call name_is(LGN_NO_LINSOL, "LGN_NO_LINSOL")
    call name_is(LGN_MISSING_FN, "LGN_MISSING_FN")
    call name_is(LGN_BAD_TOUT, "LGN_BAD_TOUT")
    call name_is(LGN_LINIT_FAIL, "LGN_LINIT_FAIL")
    call name_is(LGN_LSETUP_FAIL, "LGN_LSETUP_FAIL")
    call name_is(LGN_LSOLVE_FAIL, "LGN_LSOLVE_FAIL")
    call name_is(LGN_LS_MISMATCH, "LGN_LS_MISMATCH")
    call name_is(LGN_IO_FAIL, "LGN_IO_FAIL")
    call name_is(LGN_RESTART_BAD_FILE, "LGN_RESTART_BAD_FILE")
    call name_is(LGN_RESTART_MISMATCH, "LGN_RESTART_MISMATCH")
    call name_is(LGN_UNRECOGNIZED_ERR, "LGN_UNRECOGNIZED_ERR")
    call name_is(LGN_ROOT_RETURN, "LGN_ROOT_RETURN")
    call name_is(LGN_RTFUNC_FAIL, "LGN_RTFUNC_FAIL")
    call name_is(12345_c_int, "NONE")
    call expect(FLGNString(LGNGetReturnFlagName(-2_c_long)) == "LGN_CONV_FAILURE", &
                "LGNGetReturnFlagName(-2) through FLGNString")
    call expect(FLGNString(c_null_ptr) == "", "FLGNString(c_null_ptr) is empty")
  end subroutine test_flag_names

  !> FLGNGetReturnFlagName(flag) == name
  subroutine name_is(flag, name)
    integer(c_int), intent(in) :: flag
    character(len=*), intent(in) :: name

    call expect(FLGNGetReturnFlagName(flag) == name, &
                "FLGNGetReturnFlagName: "//FLGNGetReturnFlagName(flag)//" /= "//name)
  end subroutine name_is

  !> Flags of usage errors, the error handler and the error file.
  subroutine test_usage_errors()
    type(c_ptr) :: ctx, mem, q, v, fp
    integer(c_long) :: nnull
    type(error_record), target :: rec
    real(c_double) :: t
    integer(c_int) :: flag
    character(len=256) :: line
    integer :: unit, ios
    logical :: found

    call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
    q = N_VNew_Serial(7_c_int64_t, ctx)
    v = N_VNew_Serial(6_c_int64_t, ctx)

    ! NULL memory block (message on stderr, as documented)
    call expect_flag(LGNSetStepSize(c_null_ptr, 1.0e-3_c_double), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNSetStepSize(NULL)")
    call expect_flag(LGNSetOwnKLUSolves(c_null_ptr, 1_c_int), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNSetOwnKLUSolves(NULL)")
    call expect_flag(LGNGetNumOwnKLUSolves(c_null_ptr, nnull), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNGetNumOwnKLUSolves(NULL)")
    call expect_flag(LGNCalcIC(c_null_ptr, LGN_IC_PROJECT_QV), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNCalcIC(NULL)")
    call expect_flag(LGNGetConsistentIC(c_null_ptr, q, v), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNGetConsistentIC(NULL)")
    call expect_flag(LGNSetPerturbedStart(c_null_ptr, 1_c_int), LGN_MEM_NULL, &
                     "LGN_MEM_NULL", "LGNSetPerturbedStart(NULL)")

    mem = LGNCreate(ctx)
    call expect(c_associated(mem), "LGNCreate")

    ! a Fortran error handler with Fortran data
    call expect_flag(LGNSetErrHandlerFn(mem, c_funloc(record_error), c_loc(rec)), &
                     LGN_SUCCESS, "LGN_SUCCESS", "LGNSetErrHandlerFn")
    flag = LGNSetStepSize(mem, -1.0_c_double)
    call expect_flag(flag, LGN_ILL_INPUT, "LGN_ILL_INPUT", "LGNSetStepSize(-1)")
    call expect(rec%count == 1 .and. rec%code == LGN_ILL_INPUT, &
                "the error handler saw LGN_ILL_INPUT once")
    if (rec%count > 0) then
      call expect(rec%function_name == "LGNSetStepSize", &
                  "the error handler got the function name, not "//rec%function_name)
      call expect(len(rec%msg) > 0 .and. len(rec%module_name) > 0, &
                  "the error handler got a module name and a message")
    end if
    flag = LGNSolve(mem, 1.0_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_NO_MALLOC, "LGN_NO_MALLOC", "LGNSolve before LGNInit")
    call expect(rec%count == 2 .and. rec%code == LGN_NO_MALLOC, &
                "the error handler saw LGN_NO_MALLOC")

    ! the default handler on a C stream opened from Fortran
    call expect_flag(LGNSetErrHandlerFn(mem, c_null_funptr, c_null_ptr), LGN_SUCCESS, &
                     "LGN_SUCCESS", "LGNSetErrHandlerFn(NULL)")
    fp = FLGNFopen("test_api_errors.txt", "w")
    call expect(c_associated(fp), "FLGNFopen")
    call expect_flag(LGNSetErrFile(mem, fp), LGN_SUCCESS, "LGN_SUCCESS", "LGNSetErrFile")
    call expect_flag(LGNSetNewmark(mem, -1.0_c_double, 0.5_c_double), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "LGNSetNewmark(-1, 0.5)")
    call expect_flag(LGNSetErrFile(mem, c_null_ptr), LGN_SUCCESS, "LGN_SUCCESS", &
                     "LGNSetErrFile(NULL)")
    call expect_flag(LGNSetKinematics(mem, 99_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetKinematics(99), silenced")
    call expect(rec%count == 2, "the replaced handler is no longer called")
    call expect(FLGNFclose(fp) == 0, "FLGNFclose")
    found = .false.
    open (newunit=unit, file="test_api_errors.txt", status="old", action="read", iostat=ios)
    call expect(ios == 0, "the error file exists")
    do while (ios == 0)
      read (unit, "(a)", iostat=ios) line
      if (ios == 0) found = found .or. index(line, "LGNSetNewmark") > 0
      call expect(index(line, "LGNSetKinematics") == 0, "a silenced error was written")
    end do
    if (ios > 0) call expect(.false., "reading the error file")
    close (unit, status="delete")
    call expect(found, "the error file names LGNSetNewmark")

    call LGNFree(mem)
    call expect(.not. c_associated(mem), "LGNFree sets mem to c_null_ptr")
    call N_VDestroy(q)
    call N_VDestroy(v)
    call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
    call expect(.not. c_associated(ctx), "SUNContext_Free sets ctx to c_null_ptr")
  end subroutine test_usage_errors

  !> Built-in and Fortran-defined groups, dispatchers, quaternion helpers.
  subroutine test_groups()
    type(c_ptr) :: G, S, Rn, Pg, U
    type(c_ptr) :: factors(2)
    type(LGNGroupRec), pointer :: rec
    real(c_double) :: q7(7), w6(6), qo(7), x(6), y(6), Tm(6, 6)
    real(c_double) :: pq(4), pr(4), phi(3), R9(9), q2(2), w2(2), y2(2)
    real(c_double), parameter :: pi = acos(-1.0_c_double)

    ! R^3 x SO(3)
    G = LGNGroup_R3xSO3()
    rec => FLGNGroup_Rec(G)
    call expect(rec%kind == LGN_GROUP_R3XSO3 .and. rec%nq == 7 .and. rec%nv == 6, &
                "LGNGroup_R3xSO3: kind, nq = 7, nv = 6")
    call expect(LGNGroup_Identity(G, q7) == 0, "LGNGroup_Identity")
    call expect(maxval(abs(q7 - [0, 0, 0, 1, 0, 0, 0])) <= 0, "identity of R^3 x SO(3)")
    w6 = [1.0_c_double, 2.0_c_double, 3.0_c_double, 0.0_c_double, 0.0_c_double, pi / 2]
    call expect(LGNGroup_ComposeExp(G, q7, w6, qo) == 0, "LGNGroup_ComposeExp")
    call expect_near(qo(1) + qo(2) + qo(3), 6.0_c_double, 1.0e-15_c_double, "x + u")
    call expect_near(qo(4), cos(pi / 4), 1.0e-15_c_double, "p0 of exp(pi/2 e_z)")
    call expect_near(qo(7), sin(pi / 4), 1.0e-15_c_double, "p3 of exp(pi/2 e_z)")
    call expect(LGNGroup_Normalize(G, qo) == 0, "LGNGroup_Normalize")
    x = [1, 2, 3, 4, 5, 6]
    call expect(LGNGroup_TangentApply(G, w6, x, y) == 0, "LGNGroup_TangentApply")
    call expect(LGNGroup_TangentInverseApply(G, w6, y, qo) == 0, &
                "LGNGroup_TangentInverseApply")
    call expect(maxval(abs(qo(1:6) - x)) <= 1.0e-14_c_double, "T^{-1} T x = x")
    call expect(LGNGroup_TangentDotApply(G, w6, w6, x, y) == 0, "LGNGroup_TangentDotApply")
    call expect(LGNGroup_TangentMatrix(G, w6, Tm, 6_c_int64_t) == 0, "LGNGroup_TangentMatrix")
    call expect(LGNGroup_TangentApply(G, w6, x, y) == 0, "LGNGroup_TangentApply again")
    call expect(maxval(abs(matmul(Tm, x) - y)) <= 1.0e-14_c_double, &
                "T(w) as a column-major Fortran matrix")
    call expect(LGNGroup_TangentMatrix(G, w6, Tm, 5_c_int64_t) == -1, &
                "LGNGroup_TangentMatrix with ld < nv returns -1")
    ! the logarithm: log(q, exp(q, w)) = w, and the op in the record
    call expect(c_associated(rec%ops%compose_log), "R^3 x SO(3) has a compose_log op")
    call expect(LGNGroup_ComposeExp(G, q7, w6, qo) == 0, "LGNGroup_ComposeExp (for the log)")
    call expect(LGNGroup_ComposeLog(G, q7, qo, y) == LGN_SUCCESS, "LGNGroup_ComposeLog")
    call expect(maxval(abs(y - w6)) <= 1.0e-15_c_double, "log(q, exp(q, w)) = w")

    ! products of built-in groups
    S = LGNGroup_SO3()
    Rn = LGNGroup_Rn(2_c_int64_t)
    factors = [S, Rn]
    Pg = LGNGroup_Product(2_c_int, factors)
    call expect(c_associated(Pg), "LGNGroup_Product")
    rec => FLGNGroup_Rec(Pg)
    call expect(rec%kind == LGN_GROUP_PRODUCT .and. rec%nq == 6 .and. rec%nv == 5, &
                "SO(3) x R^2: kind, nq = 6, nv = 5")
    call expect(.not. c_associated(LGNGroup_Rn(0_c_int64_t)), "LGNGroup_Rn(0) is NULL")
    call LGNGroup_Destroy(Pg)
    call LGNGroup_Destroy(Rn)
    call LGNGroup_Destroy(S)
    call LGNGroup_Destroy(G)
    G = LGNGroup_SE3()
    rec => FLGNGroup_Rec(G)
    call expect(rec%kind == LGN_GROUP_SE3, "LGNGroup_SE3: kind")
    call expect(FLGNGroup_NQ(G) == 7, "LGNGroup_SE3: FLGNGroup_NQ")
    call expect(FLGNGroup_NV(G) == 6, "LGNGroup_SE3: FLGNGroup_NV")
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(c_null_ptr)

    ! a group defined in Fortran: R^2 with only compose_exp and identity
    U = LGNGroup_NewEmpty(2_c_int64_t, 2_c_int64_t)
    rec => FLGNGroup_Rec(U)
    call expect(rec%kind == LGN_GROUP_CUSTOM .and. rec%nq == 2 .and. rec%nv == 2, &
                "LGNGroup_NewEmpty(2, 2)")
    call expect(.not. c_associated(rec%ops%compose_exp), "NewEmpty: ops are NULL")
    rec%ops%compose_exp = c_funloc(rn_compose_exp)
    rec%ops%identity = c_funloc(rn_identity)
    q2 = [1.0_c_double, 2.0_c_double]
    w2 = [0.5_c_double, -1.0_c_double]
    call expect(LGNGroup_ComposeExp(U, q2, w2, y2) == 0, "ComposeExp of a Fortran group")
    call expect(maxval(abs(y2 - [1.5_c_double, 1.0_c_double])) <= 0, &
                "q o exp(w) = q + w in Fortran")
    call expect(LGNGroup_Identity(U, y2) == 0, "Identity of a Fortran group")
    call expect(maxval(abs(y2)) <= 0, "the identity is 0 in Fortran")
    call expect(LGNGroup_TangentApply(U, w2, q2, y2) == -1, "a missing op returns -1")
    call expect(LGNGroup_Normalize(U, q2) == 0, "Normalize without op is a no-op")
    call LGNGroup_Destroy(U)

    ! quaternion helpers: p = exp(pi/2 e_z); R row-major
    call LGNQuaternionFromRotationVector([0.0_c_double, 0.0_c_double, pi / 2], pq)
    call expect_near(pq(1), cos(pi / 4), 1.0e-15_c_double, "LGNQuaternionFromRotationVector w")
    call LGNQuaternionToRotation(pq, R9)
    call expect(maxval(abs(R9 - [0, -1, 0, 1, 0, 0, 0, 0, 1])) <= 1.0e-15_c_double, &
                "LGNQuaternionToRotation is row-major")
    call LGNRotationVectorFromQuaternion(pq, phi)
    call expect_near(phi(3), pi / 2, 1.0e-15_c_double, "LGNRotationVectorFromQuaternion")
    call LGNQuaternionMultiply(pq, pq, pr)
    call expect_near(pr(4), 1.0_c_double, 1.0e-15_c_double, "LGNQuaternionMultiply: p p = e_z")
  end subroutine test_groups

  !> LGNGenAlphaFromRhoInf(0.9) = (8/19, 9/19, 100/361, 21/38).
  subroutine test_parameter_map()
    real(c_double) :: am, af, beta, gamma

    call expect(LGNGenAlphaFromRhoInf(0.9_c_double, am, af, beta, gamma) == LGN_SUCCESS, &
                "LGNGenAlphaFromRhoInf(0.9)")
    call expect_near(am, 8.0_c_double / 19, 1.0e-15_c_double, "alpha_m")
    call expect_near(af, 9.0_c_double / 19, 1.0e-15_c_double, "alpha_f")
    call expect_near(beta, 100.0_c_double / 361, 1.0e-15_c_double, "beta")
    call expect_near(gamma, 21.0_c_double / 38, 1.0e-15_c_double, "gamma")
    call expect_flag(LGNGenAlphaFromRhoInf(2.0_c_double, am, af, beta, gamma), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "LGNGenAlphaFromRhoInf(2)")
  end subroutine test_parameter_map

  !> q'' = -q on R^1 defined in Fortran, q(0) = 1, v(0) = 0: q(1) = cos 1.
  subroutine test_oscillator()
    type(oscillator), target :: osc
    type(c_ptr) :: ctx, G, q, v, vdot, a, l0, A1, tmpl, LS, mem, fp
    type(LGNGroupRec), pointer :: rec
    real(c_double), pointer :: qq(:), vv(:), vd(:)
    real(c_double) :: t, am, af, beta, gamma, h
    integer(c_long) :: nsteps, nni, nncf, nsf, nres, ndq, nje, nls, nlsolves, lflag
    integer(c_long) :: nreuse, nrestart, nge
    integer(c_int) :: rootsfound(2)
    integer(c_long) :: ncopies, nvalues, nrefactors, nsolves, npivot, npattern, nnocopy
    integer(c_int) :: flag
    real(c_double), parameter :: tol = 1.0e-6_c_double

    call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
    G = LGNGroup_NewEmpty(1_c_int64_t, 1_c_int64_t)
    rec => FLGNGroup_Rec(G)
    rec%ops%compose_exp = c_funloc(rn_compose_exp)
    rec%ops%tangent_apply = c_funloc(rn_tangent_apply)
    rec%ops%tangent_inverse_apply = c_funloc(rn_tangent_apply)
    rec%ops%tangent_dot_apply = c_funloc(rn_tangent_dot_apply)
    rec%ops%tangent_matrix = c_funloc(rn_tangent_matrix)
    rec%ops%identity = c_funloc(rn_identity)
    q = N_VNew_Serial(1_c_int64_t, ctx)
    v = N_VNew_Serial(1_c_int64_t, ctx)
    vdot = N_VNew_Serial(1_c_int64_t, ctx)
    a = N_VNew_Serial(1_c_int64_t, ctx)
    A1 = SUNDenseMatrix(1_c_int64_t, 1_c_int64_t, ctx)
    call expect(SUNMatGetID(A1) == SUNMATRIX_DENSE, "SUNMatGetID of a dense matrix")
    call expect(SUNDenseMatrix_LData(A1) == 1, "SUNDenseMatrix_LData")
    tmpl = N_VNew_Serial(1_c_int64_t, ctx)
    LS = SUNLinSol_Dense(tmpl, A1, ctx)
    qq => FN_VGetArray(q)
    vv => FN_VGetArray(v)
    qq(1) = 1.0_c_double
    call N_VConst(0.0_c_double, v)
    call N_VConst(-1.0_c_double, vdot)   ! consistent: vdot0 = -k q0

    mem = LGNCreate(ctx)
    call expect(LGNSetGroup(mem, G) == 0, "LGNSetGroup")
    call expect(LGNSetUserData(mem, c_loc(osc)) == 0, "LGNSetUserData")
    call expect(LGNSetMassFn(mem, c_funloc(osc_mass)) == 0, "LGNSetMassFn")
    call expect(LGNSetForceFn(mem, c_funloc(osc_force)) == 0, "LGNSetForceFn")
    call expect(LGNSetConstraints(mem, 0_c_int64_t, c_null_funptr, c_null_funptr) == 0, &
                "LGNSetConstraints(m = 0)")
    call expect(LGNSetStiffnessFn(mem, c_null_funptr) == 0, "LGNSetStiffnessFn(NULL)")
    call expect(LGNSetDampingFn(mem, c_null_funptr) == 0, "LGNSetDampingFn(NULL)")
    call expect(LGNSetCurvatureFn(mem, c_null_funptr) == 0, "LGNSetCurvatureFn(NULL)")
    call expect(LGNSetConstraintForceFn(mem, c_null_funptr) == 0, "LGNSetConstraintForceFn(NULL)")
    call expect(LGNSetMassConstant(mem, 0_c_int) == 0, "LGNSetMassConstant(0)")
    call expect(LGNInit(mem, 0.0_c_double, q, v) == 0, "LGNInit")
    call expect(LGNSetLinearSolver(mem, LS, A1) == 0, "LGNSetLinearSolver")
    ! with a dense solver the switch is only recorded: off (the default)
    ! always; on where the copy of KLU's factors is available (else
    ! LGN_ILL_INPUT, built without KLU, and it stays off); then off again
    flag = LGNSetOwnKLUSolves(mem, 1_c_int)
    call expect(flag == 0 .or. flag == LGN_ILL_INPUT, &
                "LGNSetOwnKLUSolves(1): recorded, or refused (built without KLU)")
    call expect(LGNSetOwnKLUSolves(mem, 0_c_int) == 0, "LGNSetOwnKLUSolves(0)")
    call expect(LGNSetGenAlphaParams(mem, 0.0_c_double, 0.0_c_double, 0.3_c_double, &
                                     0.6_c_double) == 0, "LGNSetGenAlphaParams")
    call expect(LGNGetMethodParams(mem, am, af, beta, gamma) == 0, "LGNGetMethodParams")
    call expect_near(beta, 0.3_c_double, 0.0_c_double, "beta after LGNSetGenAlphaParams")
    call expect_near(gamma, 0.6_c_double, 0.0_c_double, "gamma after LGNSetGenAlphaParams")
    call expect(LGNSetNewmark(mem, 0.25_c_double, 0.5_c_double) == 0, "LGNSetNewmark")
    call expect(LGNSetKinematics(mem, LGN_KINEMATICS_EXACT) == 0, "LGNSetKinematics")
    call expect(LGNSetConstraintIndex(mem, LGN_CONSTR_INDEX3) == 0, "LGNSetConstraintIndex")
    call expect(LGNSetPredictor(mem, LGN_PREDICTOR_EXTRAPOLATE) == 0, "LGNSetPredictor")
    call expect_flag(LGNSetBDFForm(mem, 7_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetBDFForm(7)")
    call expect_flag(LGNSetBDFForm(mem, LGN_BDF_FIXED_LEADING), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetBDFForm under the Newmark family")
    call expect(LGNSStolerances(mem, 1.0e-10_c_double, 1.0e-12_c_double) == 0, &
                "LGNSStolerances")
    call expect(LGNSetMaxNewtonIters(mem, 10_c_int) == 0, "LGNSetMaxNewtonIters")
    call expect_flag(LGNSetNewtonMode(mem, 7_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetNewtonMode(7)")
    call expect(LGNSetNewtonMode(mem, LGN_NEWTON_MODIFIED) == 0, "LGNSetNewtonMode")
    call expect(LGNSetLSetupFrequency(mem, 50_c_long) == 0, "LGNSetLSetupFrequency")
    call expect(LGNSetMaxNumSteps(mem, 5000_c_long) == 0, "LGNSetMaxNumSteps")
    call expect(LGNSetStepSize(mem, 1.0e-3_c_double) == 0, "LGNSetStepSize")
    call expect(LGNSetInitialAcceleration(mem, vdot, c_null_ptr) == 0, &
                "LGNSetInitialAcceleration(vdot0, NULL)")
    call expect(LGNSetInitialAux(mem, vdot) == 0, "LGNSetInitialAux")
    call expect(LGNSetPerturbedStart(mem, 0_c_int) == 0, "LGNSetPerturbedStart(0)")
    call expect(LGNSetConsistentOutputs(mem, 1_c_int) == 0, "LGNSetConsistentOutputs(1)")
    call expect(LGNSetProjectOutputs(mem, LGN_PROJECT_INTERPOLATED) == 0, &
                "LGNSetProjectOutputs(LGN_PROJECT_INTERPOLATED)")
    call expect_flag(LGNSetProjectOutputs(mem, 7_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetProjectOutputs(7)")
    call expect_flag(LGNSetMultiplierErrorControl(mem, 1_c_int, 0.0_c_double), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "LGNSetMultiplierErrorControl(1, 0)")
    call expect(LGNSetMultiplierErrorControl(mem, 0_c_int, 0.0_c_double) == 0, &
                "LGNSetMultiplierErrorControl(0)")
    call expect(LGNGetNumOutputSolves(mem, nge) == 0 .and. nge == 0, &
                "LGNGetNumOutputSolves before a solve")
    call expect_flag(LGNCalcIC(mem, 9_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNCalcIC(icopt = 9)")
    call expect(LGNGetConsistentIC(mem, q, c_null_ptr) == 0, "LGNGetConsistentIC(q0, NULL)")

    ! one step, then to t = 1
    flag = LGNSolve(mem, 1.0_c_double, t, q, v, LGN_ONE_STEP)
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "LGNSolve(LGN_ONE_STEP)")
    call expect_near(t, 1.0e-3_c_double, 1.0e-15_c_double, "t after one step")
    call expect(LGNGetLastStep(mem, h) == 0, "LGNGetLastStep")
    call expect_near(h, 1.0e-3_c_double, 1.0e-15_c_double, "last step")
    flag = LGNSolve(mem, 1.0_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "LGNSolve(1)")
    call expect_near(t, 1.0_c_double, 1.0e-15_c_double, "t reached")
    call expect_near(qq(1), cos(1.0_c_double), tol, "q(1) = cos(1)")
    call expect_near(vv(1), -sin(1.0_c_double), tol, "v(1) = -sin(1)")
    call expect(LGNGetCurrentTime(mem, t) == 0, "LGNGetCurrentTime")
    call expect_near(t, 1.0_c_double, 1.0e-15_c_double, "current time")
    call expect(LGNGetAcceleration(mem, vdot) == 0, "LGNGetAcceleration")
    vd => FN_VGetArray(vdot)
    call expect_near(vd(1), -qq(1), 1.0e-8_c_double, "vdot = -q")
    call expect(LGNGetAuxAcceleration(mem, a) == 0, "LGNGetAuxAcceleration")
    l0 = N_VNew_Serial(0_c_int64_t, ctx)
    call expect(LGNGetMultipliers(mem, l0) == 0, "LGNGetMultipliers (m = 0, length 0)")
    call N_VDestroy(l0)
    ! the getters first, their values after (no order within an expression)
    call expect(LGNGetNumSteps(mem, nsteps) == 0, "LGNGetNumSteps")
    call expect(LGNGetNumNewtonIters(mem, nni) == 0, "LGNGetNumNewtonIters")
    call expect(LGNGetNumNewtonConvFails(mem, nncf) == 0, "LGNGetNumNewtonConvFails")
    call expect(LGNGetNumStepFails(mem, nsf) == 0, "LGNGetNumStepFails")
    call expect(LGNGetNumResEvals(mem, nres) == 0, "LGNGetNumResEvals")
    call expect(LGNGetNumDQEvals(mem, ndq) == 0, "LGNGetNumDQEvals")
    call expect(LGNGetNumJacEvals(mem, nje) == 0, "LGNGetNumJacEvals")
    call expect(LGNGetNumLinSolvSetups(mem, nls) == 0, "LGNGetNumLinSolvSetups")
    call expect(LGNGetNumLinSolves(mem, nlsolves) == 0, "LGNGetNumLinSolves")
    call expect(LGNGetLastLinFlag(mem, lflag) == 0, "LGNGetLastLinFlag")
    call expect(LGNGetNumMatrixReuses(mem, nreuse) == 0, "LGNGetNumMatrixReuses")
    call expect(LGNGetNumNewtonRestarts(mem, nrestart) == 0, "LGNGetNumNewtonRestarts")
    call expect(LGNGetNumKLUFactorCopies(mem, ncopies) == 0, "LGNGetNumKLUFactorCopies")
    call expect(LGNGetNumKLUValueCopies(mem, nvalues) == 0, "LGNGetNumKLUValueCopies")
    call expect(LGNGetNumOwnKLURefactors(mem, nrefactors) == 0, "LGNGetNumOwnKLURefactors")
    call expect(LGNGetNumOwnKLUSolves(mem, nsolves) == 0, "LGNGetNumOwnKLUSolves")
    call expect(LGNGetNumKLUFallbacks(mem, npivot, npattern, nnocopy) == 0, &
                "LGNGetNumKLUFallbacks")
    call expect(nsteps == 1000, "1000 steps")
    call expect(nni >= nsteps, "at least one Newton iteration per step")
    call expect(nncf == 0 .and. nsf == 0, "no Newton or step failures")
    call expect(nres > 0 .and. nje > 0 .and. nls > 0, "residuals, Jacobians, setups counted")
    call expect(ndq > 0, "no stiffness callback: difference quotients counted")
    call expect(nlsolves >= nni, "a linear solve per Newton iteration")
    call expect(nreuse > 0 .and. nls + nreuse >= nni .and. nls < nni, &
                "modified Newton: iterations with a reused matrix, fewer setups")
    call expect(nrestart >= 0, "Newton restarts counted")
    call expect(lflag == 0, "last linear solver flag 0")
    call expect(ncopies == 0 .and. nvalues == 0 .and. nrefactors == 0 .and. nsolves == 0 &
                .and. npivot == 0 .and. npattern == 0 .and. nnocopy == 0, &
                "dense: no copy of KLU's factors counted")

    ! statistics on C streams: CSV into a file, the table on stdout
    fp = FLGNFopen("test_api_stats.csv", "w")
    call expect(LGNPrintAllStats(mem, fp, SUN_OUTPUTFORMAT_CSV) == 0, "LGNPrintAllStats(CSV)")
    call expect(FLGNFclose(fp) == 0, "FLGNFclose")
    call expect(file_has("test_api_stats.csv", "Steps,1000"), "the CSV has Steps,1000")
    call expect(FLGNPrintAllStats(mem, SUN_OUTPUTFORMAT_TABLE) == 0, "FLGNPrintAllStats")
    call expect(LGNSetErrFile(mem, c_null_ptr) == 0, "LGNSetErrFile(NULL)")
    call expect_flag(LGNPrintAllStats(mem, c_null_ptr, SUN_OUTPUTFORMAT_TABLE), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "LGNPrintAllStats(NULL stream)")

    ! tout behind the current time
    flag = LGNSolve(mem, 0.5_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_BAD_TOUT, "LGN_BAD_TOUT", "LGNSolve(tout behind)")

    ! events through a Fortran root function: q = cos t falls through 1/2
    ! at pi/3 and through 0 at pi/2 (the first only counted decreasing)
    qq(1) = 1.0_c_double
    vv(1) = 0.0_c_double
    call expect(LGNReInit(mem, 0.0_c_double, q, v) == 0, "LGNReInit before the events")
    call expect(LGNRootInit(mem, 2_c_int, c_funloc(osc_root)) == 0, "LGNRootInit")
    call expect(LGNSetRootDirection(mem, [0_c_int, -1_c_int]) == 0, "LGNSetRootDirection")
    call expect(LGNSetNoInactiveRootWarn(mem) == 0, "LGNSetNoInactiveRootWarn")
    flag = LGNSolve(mem, 3.0_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_ROOT_RETURN, "LGN_ROOT_RETURN", "the first event")
    call expect_near(t, acos(0.5_c_double), 1.0e-5_c_double, "q = 1/2 at pi/3")
    call expect(LGNGetRootInfo(mem, rootsfound) == 0, "LGNGetRootInfo")
    call expect(rootsfound(1) == 0 .and. rootsfound(2) == -1, "rootsfound = (0, -1)")
    flag = LGNSolve(mem, 3.0_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_ROOT_RETURN, "LGN_ROOT_RETURN", "the second event")
    call expect_near(t, 2.0_c_double * atan(1.0_c_double), 1.0e-5_c_double, "q = 0 at pi/2")
    call expect_near(qq(1), 0.0_c_double, 1.0e-12_c_double, "q interpolated at the root")
    call expect(LGNGetRootInfo(mem, rootsfound) == 0, "LGNGetRootInfo")
    call expect(rootsfound(1) == -1 .and. rootsfound(2) == 0, "rootsfound = (-1, 0)")
    call expect(LGNGetNumGEvals(mem, nge) == 0, "LGNGetNumGEvals")
    call expect(nge > 2, "root function evaluations counted")
    call expect(LGNRootInit(mem, 0_c_int, c_null_funptr) == 0, "LGNRootInit(0): off")

    ! a failing Fortran callback, after a restart (LGNReInit)
    qq(1) = 1.0_c_double
    vv(1) = 0.0_c_double
    call expect(LGNReInit(mem, 0.0_c_double, q, v) == 0, "LGNReInit")
    osc%fail_force = .true.
    flag = LGNSolve(mem, 0.1_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_FORCE_FAIL, "LGN_FORCE_FAIL", "a force callback returning -1")

    call LGNFree(mem)
    call expect(SUNLinSolFree(LS) == 0, "SUNLinSolFree")
    call SUNMatDestroy(A1)
    call N_VDestroy(q)
    call N_VDestroy(v)
    call N_VDestroy(vdot)
    call N_VDestroy(a)
    call N_VDestroy(tmpl)
    call LGNGroup_Destroy(G)
    call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  end subroutine test_oscillator

  !> The oscillator q'' = -q with error control: every error-control setter
  !> and getter, output between steps, the stop time.
  subroutine test_adaptive()
    type(oscillator), target :: osc
    type(c_ptr) :: ctx, G, q, v, atolv, ele, ewt, dky, A1, A2, tmpl, LS, LS2, mem, mem2
    type(LGNGroupRec), pointer :: rec
    real(c_double), pointer :: qq(:), vv(:), pe(:), pw(:), pd(:)
    real(c_double) :: t, hcur, h0, hlast, errnorm, tm, q_ref, v_ref
    integer(c_long) :: nsteps, netf, nsteps2
    integer(c_int) :: flag
    real(c_double), parameter :: rtol = 1.0e-6_c_double, atol = 1.0e-8_c_double

    call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
    G = LGNGroup_NewEmpty(1_c_int64_t, 1_c_int64_t)
    rec => FLGNGroup_Rec(G)
    rec%ops%compose_exp = c_funloc(rn_compose_exp)
    rec%ops%tangent_apply = c_funloc(rn_tangent_apply)
    rec%ops%tangent_inverse_apply = c_funloc(rn_tangent_apply)
    rec%ops%tangent_dot_apply = c_funloc(rn_tangent_dot_apply)
    rec%ops%tangent_matrix = c_funloc(rn_tangent_matrix)
    rec%ops%identity = c_funloc(rn_identity)
    q = N_VNew_Serial(1_c_int64_t, ctx)
    v = N_VNew_Serial(1_c_int64_t, ctx)
    atolv = N_VNew_Serial(1_c_int64_t, ctx)
    ele = N_VNew_Serial(1_c_int64_t, ctx)
    ewt = N_VNew_Serial(1_c_int64_t, ctx)
    dky = N_VNew_Serial(1_c_int64_t, ctx)
    A1 = SUNDenseMatrix(1_c_int64_t, 1_c_int64_t, ctx)
    A2 = SUNDenseMatrix(1_c_int64_t, 1_c_int64_t, ctx)
    tmpl = N_VNew_Serial(1_c_int64_t, ctx)
    ! Lignum's dense LU in SUNLinSol_Dense's place (the oscillator above
    ! uses SUNDIALS'); a NULL argument gives a null pointer
    call expect(.not. c_associated(LGNLinSol_Dense(c_null_ptr, A1, ctx)), &
                "LGNLinSol_Dense(y = NULL) gives NULL")
    LS = LGNLinSol_Dense(tmpl, A1, ctx)
    call expect(c_associated(LS), "LGNLinSol_Dense")
    qq => FN_VGetArray(q)
    vv => FN_VGetArray(v)
    qq(1) = 1.0_c_double
    vv(1) = 0.0_c_double
    call N_VConst(atol, atolv)

    mem = LGNCreate(ctx)
    call expect(LGNSetGroup(mem, G) == 0, "LGNSetGroup")
    call expect(LGNSetUserData(mem, c_loc(osc)) == 0, "LGNSetUserData")
    call expect(LGNSetMassFn(mem, c_funloc(osc_mass)) == 0, "LGNSetMassFn")
    call expect(LGNSetForceFn(mem, c_funloc(osc_force)) == 0, "LGNSetForceFn")
    call expect(LGNSetConstraints(mem, 0_c_int64_t, c_null_funptr, c_null_funptr) == 0, &
                "LGNSetConstraints(m = 0)")
    call expect(LGNInit(mem, 0.0_c_double, q, v) == 0, "LGNInit")
    call expect(LGNSetLinearSolver(mem, LS, A1) == 0, "LGNSetLinearSolver")
    call expect(LGNSetGenAlpha(mem, 0.9_c_double) == 0, "LGNSetGenAlpha")
    call expect_flag(LGNSetStepControl(mem, 7_c_int), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetStepControl(7)")
    call expect(LGNSetStepControl(mem, LGN_STEP_FIXED) == 0, "LGNSetStepControl(FIXED)")
    call expect(LGNSetStepControl(mem, LGN_STEP_ADAPTIVE) == 0, "LGNSetStepControl(ADAPTIVE)")
    call expect(LGNSVtolerances(mem, rtol, atolv) == 0, "LGNSVtolerances")
    call expect_flag(LGNSetInitStep(mem, -1.0_c_double), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "LGNSetInitStep(-1)")
    call expect(LGNSetInitStep(mem, 1.0e-4_c_double) == 0, "LGNSetInitStep")
    call expect(LGNSetMinStep(mem, 1.0e-12_c_double) == 0, "LGNSetMinStep")
    call expect(LGNSetMaxStep(mem, 0.2_c_double) == 0, "LGNSetMaxStep")
    call expect(LGNSetMaxErrTestFails(mem, 0_c_int) == 0, "LGNSetMaxErrTestFails")
    call expect(LGNSetMaxConvFails(mem, 0_c_int) == 0, "LGNSetMaxConvFails")
    call expect_flag(LGNSetNonlinConvCoef(mem, 2.0_c_double), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "LGNSetNonlinConvCoef(2)")
    call expect(LGNSetNonlinConvCoef(mem, 0.0_c_double) == 0, "LGNSetNonlinConvCoef")
    call expect(LGNSetStopTime(mem, 0.5_c_double) == 0, "LGNSetStopTime(0.5)")
    call expect(LGNClearStopTime(mem) == 0, "LGNClearStopTime")

    ! no step yet: no interval to interpolate in
    call expect_flag(LGNGetDky(mem, 0.0_c_double, 0_c_int, dky), LGN_BAD_T, "LGN_BAD_T", &
                     "LGNGetDky before the first step")

    ! LGN_NORMAL steps past tout and interpolates there
    flag = LGNSolve(mem, 0.3_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "LGNSolve(0.3), adaptive")
    call expect_near(t, 0.3_c_double, 1.0e-15_c_double, "t = tout (interpolated)")
    call expect_near(qq(1), cos(0.3_c_double), 1.0e-4_c_double, "q(0.3) = cos(0.3)")
    call expect_near(vv(1), -sin(0.3_c_double), 1.0e-4_c_double, "v(0.3) = -sin(0.3)")
    call expect(LGNGetCurrentTime(mem, tm) == 0, "LGNGetCurrentTime")
    call expect(tm >= 0.3_c_double, "the integrator is at or past tout")

    ! a stop time: landed on exactly
    call expect(LGNSetStopTime(mem, 1.0_c_double) == 0, "LGNSetStopTime(1)")
    flag = LGNSolve(mem, 2.0_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_TSTOP_RETURN, "LGN_TSTOP_RETURN", "LGNSolve to the stop time")
    call expect_near(t, 1.0_c_double, 0.0_c_double, "t = tstop exactly")
    call expect_near(qq(1), cos(1.0_c_double), 1.0e-4_c_double, "q(1) = cos(1)")
    call expect_near(vv(1), -sin(1.0_c_double), 1.0e-4_c_double, "v(1) = -sin(1)")

    ! the getters
    call expect(LGNGetNumSteps(mem, nsteps) == 0, "LGNGetNumSteps")
    call expect(LGNGetNumErrTestFails(mem, netf) == 0, "LGNGetNumErrTestFails")
    call expect(LGNGetCurrentStep(mem, hcur) == 0, "LGNGetCurrentStep")
    call expect(LGNGetActualInitStep(mem, h0) == 0, "LGNGetActualInitStep")
    call expect(LGNGetLastStep(mem, hlast) == 0, "LGNGetLastStep")
    call expect(LGNGetLastErrNorm(mem, errnorm) == 0, "LGNGetLastErrNorm")
    call expect(LGNGetEstLocalErrors(mem, ele) == 0, "LGNGetEstLocalErrors")
    call expect(LGNGetErrWeights(mem, ewt) == 0, "LGNGetErrWeights")
    write (*, "(a, i0, a, i0, a, es10.3, a, es10.3, a, es10.3)") "adaptive: steps ", nsteps, &
        ", error-test failures ", netf, ", h0 ", h0, ", hcur ", hcur, ", |e| ", errnorm
    call expect(nsteps > 5 .and. nsteps < 1000, "far fewer steps than 1000 (h = 1e-3)")
    call expect(netf >= 0 .and. netf < nsteps, "error-test failures counted")
    call expect_near(h0, 1.0e-4_c_double, 0.0_c_double, "the initial step given")
    call expect(hcur > 0.0_c_double .and. hcur <= 0.2_c_double, "hcur within (0, hmax]")
    call expect(hlast > 0.0_c_double .and. hlast <= 0.2_c_double, "hlast within (0, hmax]")
    call expect(errnorm >= 0.0_c_double .and. errnorm <= 1.0_c_double, "accepted: |e| <= 1")
    pe => FN_VGetArray(ele)
    pw => FN_VGetArray(ewt)
    call expect(pw(1) > 0.0_c_double .and. pw(1) <= (1.0_c_double + 1.0e-12_c_double) / (hlast * atol), &
                "weight 1/(h atol + rtol |s|) <= 1/(h atol)")
    call expect_near(abs(pe(1) * pw(1)), errnorm, 1.0e-12_c_double, &
                     "|e| = |ele * ewt| (one component)")

    ! output between steps: q, v, vdot inside the last step
    tm = 1.0_c_double - 0.5_c_double * hlast
    call expect(LGNGetDky(mem, tm, 0_c_int, dky) == 0, "LGNGetDky(k = 0)")
    pd => FN_VGetArray(dky)
    call expect_near(pd(1), cos(tm), 1.0e-4_c_double, "dense q = cos(t)")
    call expect(LGNGetDky(mem, tm, 1_c_int, dky) == 0, "LGNGetDky(k = 1)")
    call expect_near(pd(1), -sin(tm), 1.0e-4_c_double, "dense v = -sin(t)")
    call expect(LGNGetDky(mem, tm, 2_c_int, dky) == 0, "LGNGetDky(k = 2)")
    call expect_near(pd(1), -cos(tm), 1.0e-2_c_double, "dense vdot = -cos(t)")
    call expect(LGNGetDky(mem, 1.0_c_double, 0_c_int, dky) == 0, "LGNGetDky at t_n")
    call expect_near(pd(1), qq(1), 0.0_c_double, "dense output at the step's end = q")
    call expect_flag(LGNGetDky(mem, tm, 3_c_int, dky), LGN_BAD_K, "LGN_BAD_K", "LGNGetDky(k = 3)")
    call expect_flag(LGNGetDky(mem, 1.5_c_double, 0_c_int, dky), LGN_BAD_T, "LGN_BAD_T", &
                     "LGNGetDky(t past the step)")
    call expect_flag(LGNGetDky(c_null_ptr, tm, 0_c_int, dky), LGN_MEM_NULL, "LGN_MEM_NULL", &
                     "LGNGetDky(NULL)")

    ! a restart file: written at t = 1, read into a new integrator made with
    ! the same settings; both go on to t = 1.7 and end bit for bit alike
    call expect(FLGNWriteRestart(mem, "ftest_restart.lgr") == 0, "FLGNWriteRestart")
    flag = LGNSolve(mem, 1.7_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "LGNSolve(1.7), uninterrupted")
    call expect(LGNGetNumSteps(mem, nsteps) == 0, "LGNGetNumSteps")
    q_ref = qq(1)
    v_ref = vv(1)
    mem2 = LGNCreate(ctx)
    call expect(LGNSetGroup(mem2, G) == 0, "LGNSetGroup (restart)")
    call expect(LGNSetUserData(mem2, c_loc(osc)) == 0, "LGNSetUserData (restart)")
    call expect(LGNSetMassFn(mem2, c_funloc(osc_mass)) == 0, "LGNSetMassFn (restart)")
    call expect(LGNSetForceFn(mem2, c_funloc(osc_force)) == 0, "LGNSetForceFn (restart)")
    call expect(LGNSetConstraints(mem2, 0_c_int64_t, c_null_funptr, c_null_funptr) == 0, &
                "LGNSetConstraints (restart)")
    call expect(LGNInit(mem2, 0.0_c_double, q, v) == 0, "LGNInit (restart)")
    LS2 = LGNLinSol_Dense(tmpl, A2, ctx)
    call expect(LGNSetLinearSolver(mem2, LS2, A2) == 0, "LGNSetLinearSolver (restart)")
    call expect(LGNSetGenAlpha(mem2, 0.9_c_double) == 0, "LGNSetGenAlpha (restart)")
    call expect(LGNSetStepControl(mem2, LGN_STEP_ADAPTIVE) == 0, "LGNSetStepControl (restart)")
    call expect(LGNSVtolerances(mem2, rtol, atolv) == 0, "LGNSVtolerances (restart)")
    call expect(LGNSetInitStep(mem2, 1.0e-4_c_double) == 0, "LGNSetInitStep (restart)")
    call expect(LGNSetMinStep(mem2, 1.0e-12_c_double) == 0, "LGNSetMinStep (restart)")
    ! a setting left out: refused, naming it
    call expect_flag(FLGNReadRestart(mem2, "ftest_restart.lgr"), LGN_RESTART_MISMATCH, &
                     "LGN_RESTART_MISMATCH", "FLGNReadRestart without LGNSetMaxStep")
    call expect(LGNSetMaxStep(mem2, 0.2_c_double) == 0, "LGNSetMaxStep (restart)")
    call expect(LGNSetMaxErrTestFails(mem2, 0_c_int) == 0, "LGNSetMaxErrTestFails (restart)")
    call expect(LGNSetMaxConvFails(mem2, 0_c_int) == 0, "LGNSetMaxConvFails (restart)")
    call expect(LGNSetNonlinConvCoef(mem2, 0.0_c_double) == 0, "LGNSetNonlinConvCoef (restart)")
    call expect_flag(FLGNReadRestart(mem2, "no-such-file.lgr"), LGN_IO_FAIL, "LGN_IO_FAIL", &
                     "FLGNReadRestart of a missing file")
    call expect(FLGNReadRestart(mem2, "ftest_restart.lgr") == 0, "FLGNReadRestart")
    flag = LGNSolve(mem2, 1.7_c_double, t, q, v, LGN_NORMAL)
    call expect_flag(flag, LGN_SUCCESS, "LGN_SUCCESS", "LGNSolve(1.7), restarted")
    call expect(LGNGetNumSteps(mem2, nsteps2) == 0, "LGNGetNumSteps (restart)")
    call expect(transfer(qq(1), 0_c_int64_t) == transfer(q_ref, 0_c_int64_t) .and. &
                transfer(vv(1), 0_c_int64_t) == transfer(v_ref, 0_c_int64_t) .and. &
                nsteps2 == nsteps, &
                "the restarted run equals the uninterrupted one bit for bit")
    call LGNFree(mem2)
    call expect(SUNLinSolFree(LS2) == 0, "SUNLinSolFree (restart)")

    call LGNFree(mem)
    call expect(SUNLinSolFree(LS) == 0, "SUNLinSolFree")
    call SUNMatDestroy(A1)
    call SUNMatDestroy(A2)
    call N_VDestroy(q)
    call N_VDestroy(v)
    call N_VDestroy(atolv)
    call N_VDestroy(ele)
    call N_VDestroy(ewt)
    call N_VDestroy(dky)
    call N_VDestroy(tmpl)
    call LGNGroup_Destroy(G)
    call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  end subroutine test_adaptive

  !> Trajectories for ParaView from Fortran (flignum_vtk_mod): a box and a
  !> frame on one R^3 x SO(3) body, two outputs; bad input refused.
  subroutine test_vtk()
    use flignum_vtk_mod
    type(c_ptr) :: ctx, G, q, w
    real(c_double), pointer :: qq(:)
    real(c_double) :: origin(3) = [0.0_c_double, 0.0_c_double, 0.5_c_double]
    integer(c_int) :: nb
    logical :: exists

    call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
    G = LGNGroup_R3xSO3()
    q = N_VNew_Serial(7_c_int64_t, ctx)
    qq => FN_VGetArray(q)
    call expect(LGNGroup_Identity(G, qq) == 0, "LGNGroup_Identity")
    w = FLGNVtk_Create(G, "ftest_vtk")
    call expect(c_associated(w), "FLGNVtk_Create")
    call expect(LGNVtk_GetNumBodies(w, nb) == 0 .and. nb == 1, "one body")
    call expect(LGNVtk_SetBox(w, 0_c_int, 0.2_c_double, 0.1_c_double, 1.0_c_double) == 0, &
                "LGNVtk_SetBox")
    call expect_flag(LGNVtk_SetSphere(w, 1_c_int, 0.1_c_double), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "LGNVtk_SetSphere(body 1 of 1)")
    call expect(LGNVtk_AddFrame(w, 0_c_int, origin, c_null_ptr, 0.1_c_double) == 0, &
                "LGNVtk_AddFrame")
    call expect(LGNVtk_Write(w, 0.0_c_double, q) == 0, "LGNVtk_Write(0)")
    qq(1) = 1.0_c_double
    call expect(LGNVtk_Write(w, 0.5_c_double, q) == 0, "LGNVtk_Write(0.5)")
    call LGNVtk_Destroy(w)
    call expect(.not. c_associated(w), "LGNVtk_Destroy clears the pointer")
    inquire (file="ftest_vtk_000001.vtp", exist=exists)
    call expect(exists, "ftest_vtk_000001.vtp written")
    inquire (file="ftest_vtk.pvd", exist=exists)
    call expect(exists, "ftest_vtk.pvd written")
    call N_VDestroy(q)
    call LGNGroup_Destroy(G)
    call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  end subroutine test_vtk

  !> .true. if a line of the file contains text; deletes the file.
  function file_has(path, text) result(found)
    character(len=*), intent(in) :: path, text
    logical :: found
    character(len=256) :: line
    integer :: unit, ios

    found = .false.
    open (newunit=unit, file=path, status="old", action="read", iostat=ios)
    if (ios /= 0) return
    do
      read (unit, "(a)", iostat=ios) line
      if (ios /= 0) exit
      found = found .or. index(line, text) > 0
    end do
    close (unit, status="delete")
  end function file_has

end program test_api
