! -----------------------------------------------------------------------------
! Lignum Fortran study tools: command-line parsing and the comparison with the
! output of the C counterpart of a tool. The test scripts run the C
! program first and pass its output file with --compare FILE; the Fortran
! program then checks its own final values against the lines
! "<key> v1 v2 ..." of that file (printed by C with %.17g).
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
module fexample_util
  use, intrinsic :: iso_c_binding, only: c_double
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private

  public :: get_arg, parse_real, parse_int, reference_values, reference_after
  public :: check_close, print_values, fixed

contains

  !> The i-th command-line argument as an allocatable string.
  function get_arg(i) result(arg)
    integer, intent(in) :: i
    character(len=:), allocatable :: arg
    integer :: n

    call get_command_argument(i, length=n)
    allocate (character(len=n) :: arg)
    if (n > 0) call get_command_argument(i, arg)
  end function get_arg

  !> Read a real from a string; ok = .false. if it is not one.
  subroutine parse_real(str, x, ok)
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    character(len=*), intent(in) :: str
    real(c_double), intent(out) :: x
    logical, intent(out) :: ok
    integer :: ios

    read (str, *, iostat=ios) x
    ! a finite number
    ok = ios == 0
    if (ok) ok = ieee_is_finite(x)
  end subroutine parse_real

  !> Read an integer from a string; ok = .false. if it is not one.
  subroutine parse_int(str, n, ok)
    character(len=*), intent(in) :: str
    integer, intent(out) :: n
    logical, intent(out) :: ok
    integer :: ios

    read (str, *, iostat=ios) n
    ok = ios == 0 .and. verify(trim(adjustl(str)), "+-0123456789") == 0
  end subroutine parse_int

  !> Values that follow the text marker in the first line containing it,
  !! e.g. marker "E(t_end) =" in "energy E0 = -196.1  E(t_end) = -196.2  ...".
  !! @param path   file written by the C tool
  !! @param marker text in the line, right before the values
  !! @param vals   on return, as many values as vals holds
  !! @param found  .true. if the marker was found and all values read
  subroutine reference_after(path, marker, vals, found)
    character(len=*), intent(in) :: path, marker
    real(c_double), intent(out) :: vals(:)
    logical, intent(out) :: found
    character(len=1024) :: line
    integer :: unit, ios, pos

    found = .false.
    vals = 0.0_c_double
    open (newunit=unit, file=path, status="old", action="read", iostat=ios)
    if (ios /= 0) return
    do
      read (unit, "(a)", iostat=ios) line
      if (ios /= 0) exit
      pos = index(line, marker)
      if (pos > 0) then
        read (line(pos + len(marker):), *, iostat=ios) vals
        found = ios == 0
        exit
      end if
    end do
    close (unit)
  end subroutine reference_after

  !> Values of the first line "<key> v1 v2 ..." of a text file.
  !! @param path  file written by the C tool
  !! @param key   first word of the line, e.g. "com_final"
  !! @param vals  on return, as many values as vals holds
  !! @param found .true. if the line was found and all values read
  subroutine reference_values(path, key, vals, found)
    character(len=*), intent(in) :: path, key
    real(c_double), intent(out) :: vals(:)
    logical, intent(out) :: found
    character(len=1024) :: line
    integer :: unit, ios

    found = .false.
    vals = 0.0_c_double
    open (newunit=unit, file=path, status="old", action="read", iostat=ios)
    if (ios /= 0) return
    do
      read (unit, "(a)", iostat=ios) line
      if (ios /= 0) exit
      line = adjustl(line)
      if (index(line, key//" ") == 1) then
        read (line(len(key) + 1:), *, iostat=ios) vals
        found = ios == 0
        exit
      end if
    end do
    close (unit)
  end subroutine reference_values

  !> Compare x with the reference xref: |x - xref| <= tol max(1, |xref|)
  !! entry by entry; prints the largest difference, counts failures.
  subroutine check_close(name, x, xref, tol, nfail)
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: x(:), xref(:), tol
    integer, intent(inout) :: nfail
    real(c_double) :: diff

    diff = maxval(abs(x - xref) / max(1.0_c_double, abs(xref)))
    if (diff <= tol) then
      write (*, "(a, a, es10.3)") name, ": matches C, max rel. difference ", diff
    else
      write (error_unit, "(a, a, es10.3, a, es10.3)") name, &
        ": DIFFERS from C, max rel. difference ", diff, " > ", tol
      nfail = nfail + 1
    end if
  end subroutine check_close

  !> x with d decimals and no padding, as C's %.<d>f (gfortran's F0.d
  !! drops the zero before the decimal point: ".5" -> "0.5").
  function fixed(x, d) result(str)
    real(c_double), intent(in) :: x
    integer, intent(in) :: d
    character(len=:), allocatable :: str
    character(len=64) :: buf, fmt

    write (fmt, "(a, i0, a)") "(f0.", d, ")"
    write (buf, fmt) x
    str = trim(buf)
    if (str(1:1) == ".") str = "0"//str
    if (len(str) > 1) then
      if (str(1:2) == "-.") str = "-0"//str(2:)
    end if
  end function fixed

  !> One line "<key> v1 v2 ..." with 17 significant digits (as C's %.17g).
  subroutine print_values(key, vals)
    character(len=*), intent(in) :: key
    real(c_double), intent(in) :: vals(:)
    integer :: i

    write (*, "(a)", advance="no") key
    do i = 1, size(vals)
      write (*, "(1x, es24.16e3)", advance="no") vals(i)
    end do
    write (*, "(a)") ""
  end subroutine print_values

end module fexample_util
