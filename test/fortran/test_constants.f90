! -----------------------------------------------------------------------------
! Lignum Fortran test: every constant of flignum_mod, flignum_joints_mod and
! flignum_sundials_mod equals its C value, and every C constant has been
! checked.
!
! The C side (lgn_c_constants.c, generated from the public headers at
! configure time) lists every LGN_ constant (numeric #defines and
! enumerators of lignum.h, lignum_group.h, lignum_joints.h, lignum_config.h)
! and the SUNDIALS constants the Fortran modules duplicate. This program
! compares each Fortran constant with the C entry of the same name and fails
! if a name is missing on either side: a constant added to a header without
! a Fortran binding fails the test, so does a value that drifts. Also
! checked: the version string and the layout of struct LGNGroupRec against
! the bind(C) type LGNGroupRec.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program test_constants
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_joints_mod
  use flignum_sundials_mod
  use ftest_util
  implicit none

  interface
    integer(c_int) function lgn_c_num_constants() bind(c)
      import :: c_int
    end function lgn_c_num_constants
    type(c_ptr) function lgn_c_constant_name(i) bind(c)
      import :: c_ptr, c_int
      integer(c_int), value :: i
    end function lgn_c_constant_name
    integer(c_long) function lgn_c_constant_value(i) bind(c)
      import :: c_long, c_int
      integer(c_int), value :: i
    end function lgn_c_constant_value
    type(c_ptr) function lgn_c_version() bind(c)
      import :: c_ptr
    end function lgn_c_version
    integer(c_size_t) function lgn_c_group_layout(which) bind(c)
      import :: c_size_t, c_int
      integer(c_int), value :: which
    end function lgn_c_group_layout
  end interface

  integer :: ncheck = 0, i, n
  logical, allocatable :: seen(:)
  type(LGNGroupRec), target :: rec

  n = lgn_c_num_constants()
  allocate (seen(0:n - 1))
  seen = .false.

  ! --- lignum.h: return flags -------------------------------------------------------
  call check("LGN_SUCCESS", LGN_SUCCESS)
  call check("LGN_TSTOP_RETURN", LGN_TSTOP_RETURN)
  call check("LGN_TOO_MUCH_WORK", LGN_TOO_MUCH_WORK)
  call check("LGN_CONV_FAILURE", LGN_CONV_FAILURE)
  call check("LGN_MASS_FAIL", LGN_MASS_FAIL)
  call check("LGN_FORCE_FAIL", LGN_FORCE_FAIL)
  call check("LGN_CONSTR_FAIL", LGN_CONSTR_FAIL)
  call check("LGN_CONSTR_JAC_FAIL", LGN_CONSTR_JAC_FAIL)
  call check("LGN_TANGENT_FAIL", LGN_TANGENT_FAIL)
  call check("LGN_GROUP_FAIL", LGN_GROUP_FAIL)
  call check("LGN_NONFINITE", LGN_NONFINITE)
  call check("LGN_REPTD_CALLBACK_ERR", LGN_REPTD_CALLBACK_ERR)
  call check("LGN_IC_FAIL", LGN_IC_FAIL)
  call check("LGN_ERR_FAILURE", LGN_ERR_FAILURE)
  call check("LGN_STEP_TOO_SMALL", LGN_STEP_TOO_SMALL)
  call check("LGN_INCONSISTENT_IC", LGN_INCONSISTENT_IC)
  call check("LGN_REDUNDANT_INCONSISTENT", LGN_REDUNDANT_INCONSISTENT)
  call check("LGN_REDUNDANT_ELIMINATE", LGN_REDUNDANT_ELIMINATE)
  call check("LGN_REDUNDANT_REFUSE", LGN_REDUNDANT_REFUSE)
  call check("LGN_MEM_NULL", LGN_MEM_NULL)
  call check("LGN_MEM_FAIL", LGN_MEM_FAIL)
  call check("LGN_ILL_INPUT", LGN_ILL_INPUT)
  call check("LGN_NO_MALLOC", LGN_NO_MALLOC)
  call check("LGN_NO_LINSOL", LGN_NO_LINSOL)
  call check("LGN_MISSING_FN", LGN_MISSING_FN)
  call check("LGN_BAD_TOUT", LGN_BAD_TOUT)
  call check("LGN_BAD_T", LGN_BAD_T)
  call check("LGN_BAD_K", LGN_BAD_K)
  call check("LGN_LINIT_FAIL", LGN_LINIT_FAIL)
  call check("LGN_LSETUP_FAIL", LGN_LSETUP_FAIL)
  call check("LGN_LSOLVE_FAIL", LGN_LSOLVE_FAIL)
  call check("LGN_LS_MISMATCH", LGN_LS_MISMATCH)
  call check("LGN_IO_FAIL", LGN_IO_FAIL)
  call check("LGN_RESTART_BAD_FILE", LGN_RESTART_BAD_FILE)
  call check("LGN_RESTART_MISMATCH", LGN_RESTART_MISMATCH)
  call check("LGN_UNRECOGNIZED_ERR", LGN_UNRECOGNIZED_ERR)
  ! events (root finding)
  call check("LGN_ROOT_RETURN", LGN_ROOT_RETURN)
  call check("LGN_RTFUNC_FAIL", LGN_RTFUNC_FAIL)
  call check("LGN_WARNING", LGN_WARNING)

  ! --- lignum.h: other constants ----------------------------------------------------
  call check("LGN_NORMAL", LGN_NORMAL)
  call check("LGN_ONE_STEP", LGN_ONE_STEP)
  call check("LGN_STEP_FIXED", LGN_STEP_FIXED)
  call check("LGN_STEP_ADAPTIVE", LGN_STEP_ADAPTIVE)
  call check("LGN_CONSTR_INDEX3", LGN_CONSTR_INDEX3)
  call check("LGN_CONSTR_INDEX2", LGN_CONSTR_INDEX2)
  call check("LGN_CONSTR_GGL", LGN_CONSTR_GGL)
  call check("LGN_KINEMATICS_SIMPLIFIED", LGN_KINEMATICS_SIMPLIFIED)
  call check("LGN_KINEMATICS_EXACT", LGN_KINEMATICS_EXACT)
  call check("LGN_KINEMATICS_SIGMA", LGN_KINEMATICS_SIGMA)
  call check("LGN_PREDICTOR_ZERO", LGN_PREDICTOR_ZERO)
  call check("LGN_PREDICTOR_EXTRAPOLATE", LGN_PREDICTOR_EXTRAPOLATE)
  call check("LGN_BDF_VARIABLE_COEFF", LGN_BDF_VARIABLE_COEFF)
  call check("LGN_BDF_FIXED_LEADING", LGN_BDF_FIXED_LEADING)
  call check("LGN_BDF_MAX_ORDER", LGN_BDF_MAX_ORDER)
  call check("LGN_NEWTON_FULL", LGN_NEWTON_FULL)
  call check("LGN_NEWTON_MODIFIED", LGN_NEWTON_MODIFIED)
  call check("LGN_IC_PROJECT_Q", LGN_IC_PROJECT_Q)
  call check("LGN_IC_PROJECT_V", LGN_IC_PROJECT_V)
  call check("LGN_IC_PROJECT_QV", LGN_IC_PROJECT_QV)
  call check("LGN_PROJECT_NONE", LGN_PROJECT_NONE)
  call check("LGN_PROJECT_INTERPOLATED", LGN_PROJECT_INTERPOLATED)
  call check("LGN_PROJECT_ALL", LGN_PROJECT_ALL)

  ! --- lignum_group.h: LGNGroupKind -------------------------------------------------
  call check("LGN_GROUP_CUSTOM", LGN_GROUP_CUSTOM)
  call check("LGN_GROUP_RN", LGN_GROUP_RN)
  call check("LGN_GROUP_SO3", LGN_GROUP_SO3)
  call check("LGN_GROUP_R3XSO3", LGN_GROUP_R3XSO3)
  call check("LGN_GROUP_SE3", LGN_GROUP_SE3)
  call check("LGN_GROUP_PRODUCT", LGN_GROUP_PRODUCT)

  ! --- lignum_joints.h (flignum_joints_mod) ------------------------------------------
  call check("LGN_GROUND", LGN_GROUND)

  ! --- lignum_config.h: version ------------------------------------------------------
  call check("LGN_VERSION_MAJOR", LGN_VERSION_MAJOR)
  call check("LGN_VERSION_MINOR", LGN_VERSION_MINOR)
  call check("LGN_VERSION_PATCH", LGN_VERSION_PATCH)
  call expect(LGN_VERSION == FLGNString(lgn_c_version()), &
              "LGN_VERSION = "//LGN_VERSION//", C: "//FLGNString(lgn_c_version()))

  ! --- SUNDIALS constants of flignum_sundials_mod -----------------------------------
  call check("SUN_OUTPUTFORMAT_TABLE", SUN_OUTPUTFORMAT_TABLE)
  call check("SUN_OUTPUTFORMAT_CSV", SUN_OUTPUTFORMAT_CSV)
  call check("SUNMATRIX_DENSE", SUNMATRIX_DENSE)
  call check("SUNMATRIX_MAGMADENSE", SUNMATRIX_MAGMADENSE)
  call check("SUNMATRIX_ONEMKLDENSE", SUNMATRIX_ONEMKLDENSE)
  call check("SUNMATRIX_BAND", SUNMATRIX_BAND)
  call check("SUNMATRIX_SPARSE", SUNMATRIX_SPARSE)
  call check("SUNMATRIX_SLUNRLOC", SUNMATRIX_SLUNRLOC)
  call check("SUNMATRIX_CUSPARSE", SUNMATRIX_CUSPARSE)
  call check("SUNMATRIX_GINKGO", SUNMATRIX_GINKGO)
  call check("SUNMATRIX_KOKKOSDENSE", SUNMATRIX_KOKKOSDENSE)
  call check("SUNMATRIX_CUSTOM", SUNMATRIX_CUSTOM)
  call check("CSC_MAT", CSC_MAT)
  call check("CSR_MAT", CSR_MAT)
  ! in the C table when SUNDIALS has KLU (target SUNDIALS::sunlinsolklu)
  call check("SUNKLU_REINIT_FULL", SUNKLU_REINIT_FULL, optional_in_c=.true.)
  call check("SUNKLU_REINIT_PARTIAL", SUNKLU_REINIT_PARTIAL, optional_in_c=.true.)

  ! --- every C constant has a Fortran counterpart -----------------------------------
  do i = 0, n - 1
    call expect(seen(i), "the C constant "//FLGNString(lgn_c_constant_name(int(i, c_int))) &
                //" has no Fortran counterpart in this test")
  end do

  ! --- struct LGNGroupRec = type(LGNGroupRec) ----------------------------------------
  call expect(c_sizeof(rec) == lgn_c_group_layout(0), "sizeof(struct LGNGroupRec)")
  call expect(offset(c_loc(rec%kind)) == lgn_c_group_layout(1), "offset of kind")
  call expect(offset(c_loc(rec%nq)) == lgn_c_group_layout(2), "offset of nq")
  call expect(offset(c_loc(rec%nv)) == lgn_c_group_layout(3), "offset of nv")
  call expect(offset(c_loc(rec%content)) == lgn_c_group_layout(4), "offset of content")
  call expect(offset(c_loc(rec%ops)) == lgn_c_group_layout(5), "offset of ops")
  call expect(c_sizeof(rec%ops) == lgn_c_group_layout(6), "sizeof(struct LGNGroupOpsRec)")
  call expect(offset(c_loc(rec%ops%free_content)) - offset(c_loc(rec%ops)) &
              == lgn_c_group_layout(7), "offset of ops.free_content")

  write (*, "(i0, a, i0, a)") ncheck, " constants checked against ", n, " C entries"
  deallocate (seen)   ! a main program's variables are never deallocated automatically
  call ftest_finish("test_constants")

contains

  !> Compare the Fortran constant fvalue with the C entry called name.
  subroutine check(name, fvalue, optional_in_c)
    character(len=*), intent(in) :: name
    integer(c_int), intent(in) :: fvalue
    logical, intent(in), optional :: optional_in_c
    integer :: j
    character(len=32) :: buf

    ncheck = ncheck + 1
    do j = 0, n - 1
      if (FLGNString(lgn_c_constant_name(int(j, c_int))) == name) then
        seen(j) = .true.
        write (buf, "(i0)") lgn_c_constant_value(int(j, c_int))
        call expect(int(fvalue, c_long) == lgn_c_constant_value(int(j, c_int)), &
                    name//" differs from C (C: "//trim(buf)//")")
        return
      end if
    end do
    if (present(optional_in_c)) then
      if (optional_in_c) return
    end if
    call expect(.false., name//" is not a C constant")
  end subroutine check

  !> Byte offset of an address from the start of rec.
  function offset(p) result(off)
    type(c_ptr), intent(in) :: p
    integer(c_size_t) :: off

    off = int(transfer(p, 0_c_intptr_t) - transfer(c_loc(rec), 0_c_intptr_t), c_size_t)
  end function offset

end program test_constants
