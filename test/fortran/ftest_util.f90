! -----------------------------------------------------------------------------
! Lignum Fortran tests: the shared checking routines. Every check that fails
! prints "FAILED: <what>" to standard error and is counted; ftest_finish
! ends the test program with the count (error stop 1 if any failed).
!
!   use ftest_util
!   call expect(ok, "what is checked")
!   call expect_flag(flag, LGN_ILL_INPUT, "LGN_ILL_INPUT", "LGNSetStepSize(-1)")
!   call expect_near(x, 1.0_c_double, 1.0e-15_c_double, "x")
!   call ftest_finish("test_name")
!
! and an error handler that records what Lignum reported:
!   type(error_record), target :: rec
!   flag = LGNSetErrHandlerFn(mem, c_funloc(record_error), c_loc(rec))
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
module ftest_util
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_f_pointer
  use, intrinsic :: iso_fortran_env, only: error_unit
  use flignum_mod, only: FLGNGetReturnFlagName, FLGNString
  implicit none
  private

  !> Number of failed checks so far.
  integer, public, protected :: ftest_nfail = 0

  !> What the error handler record_error saw (its eh_data).
  type, public :: error_record
    integer :: count = 0                 !< errors reported
    integer(c_int) :: code = 0           !< flag of the last one
    character(len=:), allocatable :: module_name, function_name, msg
  end type error_record

  public :: expect, expect_flag, expect_near, ftest_finish, record_error

contains

  !> Record a failure unless ok.
  subroutine expect(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what

    if (.not. ok) then
      write (error_unit, "(a, a)") "FAILED: ", what
      ftest_nfail = ftest_nfail + 1
    end if
  end subroutine expect

  !> flag == expected, and its name is the expected constant's name.
  subroutine expect_flag(flag, expected, name, what)
    integer(c_int), intent(in) :: flag, expected
    character(len=*), intent(in) :: name, what

    call expect(flag == expected, what//" returns "//name//", got " &
                //FLGNGetReturnFlagName(flag))
    call expect(FLGNGetReturnFlagName(flag) == name, &
                what//": the name of the flag is "//FLGNGetReturnFlagName(flag))
  end subroutine expect_flag

  !> |x - y| <= tol
  subroutine expect_near(x, y, tol, what)
    real(c_double), intent(in) :: x, y, tol
    character(len=*), intent(in) :: what
    character(len=80) :: buf

    write (buf, "(a, es24.16, a, es24.16)") " = ", x, ", expected ", y
    call expect(abs(x - y) <= tol, what//trim(buf))
  end subroutine expect_near

  !> LGNErrHandlerFn recording the last error in the error_record eh_data.
  subroutine record_error(error_code, module_name, function_name, msg, eh_data) bind(c)
    integer(c_int), value :: error_code
    type(c_ptr), value :: module_name, function_name, msg, eh_data
    type(error_record), pointer :: rec

    call c_f_pointer(eh_data, rec)
    rec%count = rec%count + 1
    rec%code = error_code
    rec%module_name = FLGNString(module_name)
    rec%function_name = FLGNString(function_name)
    rec%msg = FLGNString(msg)
  end subroutine record_error

  !> End the test: error stop 1 if a check failed, else report success.
  subroutine ftest_finish(name)
    character(len=*), intent(in) :: name

    if (ftest_nfail > 0) then
      write (error_unit, "(a, a, i0, a)") name, ": ", ftest_nfail, " check(s) failed"
      error stop 1
    end if
    write (*, "(a, a)") name, ": all checks passed"
  end subroutine ftest_finish

end module ftest_util
