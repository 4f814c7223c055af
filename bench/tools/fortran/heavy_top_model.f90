! -----------------------------------------------------------------------------
! Lignum Fortran study tool: the heavy top (Brüls and Cardona 2010) on R^3 x SO(3),
! the callbacks of models/heavy_top.c (formulation HT_LIE) written
! as bind(C) Fortran functions. The model data reach them as user data:
! LGNSetUserData(mem, c_loc(model)), c_f_pointer(user_data, model) inside.
!
!   q = (x, p), v = (u, Omega), spherical joint at 0, centre of mass X (body):
!     M = diag(m I, J),  g = [-m gamma_g ; Omega x J Omega],
!     Phi = X - R^T x,   B = [-R^T, -X~]           (Brüls-Cardona, Klemps (2.21)-(2.26))
!     K_t = [[0, R lambda~], [0, 0]],  C_t = [[0, 0], [0, Omega~ J - (J Omega)~]],
!     Z(q)(v, v) = Omega x (R^T u).
!
! The arithmetic follows the C model operation by operation, so that both
! produce the same numbers (the test tool_fortran_heavy_top_* compares).
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
module heavy_top_model
  use, intrinsic :: iso_c_binding
  use flignum_mod, only: LGNQuaternionToRotation
  use flignum_sundials_mod, only: FN_VGetArray, FSUNDenseMatrix_Array
  implicit none
  private

  public :: heavy_top_data, heavy_top_initial_state
  public :: ht_mass, ht_force, ht_constr, ht_constr_jac
  public :: ht_stiffness, ht_damping, ht_curvature, ht_joint_violation

  !> Data of the benchmark (Brüls and Cardona 2010), passed as user data.
  type :: heavy_top_data
    real(c_double) :: mass = 15.0_c_double
    real(c_double) :: J(3) = [0.234375_c_double, 0.46875_c_double, 0.234375_c_double]
    real(c_double) :: X(3) = [0.0_c_double, 1.0_c_double, 0.0_c_double] !< centre of mass
    real(c_double) :: gravity(3) = [0.0_c_double, 0.0_c_double, -9.81_c_double]
    real(c_double) :: Omega0(3) = [0.0_c_double, 150.0_c_double, -4.61538_c_double]
  end type heavy_top_data

contains

  ! ===========================================================================
  ! Small vector helpers (as in the C model)
  ! ===========================================================================

  !> c = a x b
  pure function cross(a, b) result(c)
    real(c_double), intent(in) :: a(3), b(3)
    real(c_double) :: c(3)

    c(1) = a(2) * b(3) - a(3) * b(2)
    c(2) = a(3) * b(1) - a(1) * b(3)
    c(3) = a(1) * b(2) - a(2) * b(1)
  end function cross

  !> a~ as a Fortran 3x3 matrix, so that matmul(tilde(a), b) = a x b
  pure function tilde(a) result(T)
    real(c_double), intent(in) :: a(3)
    real(c_double) :: T(3, 3)

    T(1, :) = [0.0_c_double, -a(3), a(2)]
    T(2, :) = [a(3), 0.0_c_double, -a(1)]
    T(3, :) = [-a(2), a(1), 0.0_c_double]
  end function tilde

  !> R(i, j) of the unit quaternion p (LGNQuaternionToRotation is row-major).
  function rotation(p) result(R)
    real(c_double), intent(in) :: p(4)
    real(c_double) :: R(3, 3), Rrow(9)

    call LGNQuaternionToRotation(p, Rrow)
    R = transpose(reshape(Rrow, [3, 3]))
  end function rotation

  !> y = R^T x, summed in the order of the C model
  pure function mat_t_vec(R, x) result(y)
    real(c_double), intent(in) :: R(3, 3), x(3)
    real(c_double) :: y(3)
    integer :: i

    do i = 1, 3
      y(i) = R(1, i) * x(1) + R(2, i) * x(2) + R(3, i) * x(3)
    end do
  end function mat_t_vec

  !> The model data behind the user data pointer.
  function model_of(user_data) result(d)
    type(c_ptr), intent(in) :: user_data
    type(heavy_top_data), pointer :: d

    call c_f_pointer(user_data, d)
  end function model_of

  ! ===========================================================================
  ! Initial state: R0 = I, x0 = X, u0 = Omega0 x X, p0 = (1, 0, 0, 0)
  ! ===========================================================================

  !> Fill q (7) and v (6) with the initial state of the benchmark.
  subroutine heavy_top_initial_state(d, q, v)
    type(heavy_top_data), intent(in) :: d
    real(c_double), intent(out) :: q(7), v(6)

    q = 0.0_c_double
    q(1:3) = d%X
    q(4) = 1.0_c_double
    v(1:3) = cross(d%Omega0, d%X)
    v(4:6) = d%Omega0
  end subroutine heavy_top_initial_state

  !> |X - R^T x|_inf of the raw state q (unnormalised quaternion, as in Phi).
  function ht_joint_violation(d, q) result(viol)
    type(heavy_top_data), intent(in) :: d
    real(c_double), intent(in) :: q(7)
    real(c_double) :: viol

    viol = maxval(abs(d%X - mat_t_vec(rotation(q(4:7)), q(1:3))))
  end function ht_joint_violation

  ! ===========================================================================
  ! Callbacks (flignum_mod abstract interfaces LGNMassFn, ...)
  ! ===========================================================================

  !> M = diag(m I, J) (LGNMassFn).
  integer(c_int) function ht_mass(t, q, Mmat, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, Mmat, user_data
    type(heavy_top_data), pointer :: d
    real(c_double), pointer :: M(:, :)
    integer :: i

    d => model_of(user_data)
    M => FSUNDenseMatrix_Array(Mmat)
    do i = 1, 3
      M(i, i) = d%mass
      M(3 + i, 3 + i) = d%J(i)
    end do
    ierr = 0
  end function ht_mass

  !> g = [-m gamma_g ; Omega x J Omega] (LGNForceFn).
  integer(c_int) function ht_force(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    type(heavy_top_data), pointer :: d
    real(c_double), pointer :: vv(:), gg(:)

    d => model_of(user_data)
    vv => FN_VGetArray(v)
    gg => FN_VGetArray(g)
    gg(1:3) = -d%mass * d%gravity
    gg(4:6) = cross(vv(4:6), d%J * vv(4:6))
    ierr = 0
  end function ht_force

  !> Phi = X - R^T x (LGNConstrFn).
  integer(c_int) function ht_constr(t, q, phi, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, phi, user_data
    type(heavy_top_data), pointer :: d
    real(c_double), pointer :: qq(:), ph(:)

    d => model_of(user_data)
    qq => FN_VGetArray(q)
    ph => FN_VGetArray(phi)
    ph = d%X - mat_t_vec(rotation(qq(4:7)), qq(1:3))
    ierr = 0
  end function ht_constr

  !> B = [-R^T, -X~] (LGNConstrJacFn).
  integer(c_int) function ht_constr_jac(t, q, Bmat, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, Bmat, user_data
    type(heavy_top_data), pointer :: d
    real(c_double), pointer :: qq(:), B(:, :)

    d => model_of(user_data)
    qq => FN_VGetArray(q)
    B => FSUNDenseMatrix_Array(Bmat)
    B(1:3, 1:3) = -transpose(rotation(qq(4:7)))
    B(1:3, 4:6) = -tilde(d%X)
    ierr = 0
  end function ht_constr_jac

  !> K_t = [[0, R lambda~], [0, 0]] (LGNStiffnessFn).
  integer(c_int) function ht_stiffness(t, q, v, vdot, lambda, Kmat, user_data) &
      result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, vdot, lambda, Kmat, user_data
    real(c_double), pointer :: qq(:), l(:), Kt(:, :)
    real(c_double) :: R(3, 3), lt(3, 3), s
    integer :: i, j, k

    qq => FN_VGetArray(q)
    l => FN_VGetArray(lambda)
    Kt => FSUNDenseMatrix_Array(Kmat)
    R = rotation(qq(4:7))
    lt = tilde(l(1:3))
    do i = 1, 3
      do j = 1, 3
        s = 0.0_c_double
        do k = 1, 3
          s = s + R(i, k) * lt(k, j)
        end do
        Kt(i, 3 + j) = s
      end do
    end do
    ierr = 0
  end function ht_stiffness

  !> C_t = [[0, 0], [0, Omega~ J - (J Omega)~]] (LGNDampingFn).
  integer(c_int) function ht_damping(t, q, v, Cmat, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, Cmat, user_data
    type(heavy_top_data), pointer :: d
    real(c_double), pointer :: vv(:), C(:, :)
    real(c_double) :: W(3), JW(3)

    d => model_of(user_data)
    vv => FN_VGetArray(v)
    C => FSUNDenseMatrix_Array(Cmat)
    W = vv(4:6)
    JW = d%J * W
    C(4, 5) = -W(3) * d%J(2) + JW(3)
    C(4, 6) = W(2) * d%J(3) - JW(2)
    C(5, 4) = W(3) * d%J(1) - JW(3)
    C(5, 6) = -W(1) * d%J(3) + JW(1)
    C(6, 4) = -W(2) * d%J(1) + JW(2)
    C(6, 5) = W(1) * d%J(2) - JW(1)
    ierr = 0
  end function ht_damping

  !> Z(q)(v, v) = Omega x (R^T u) (LGNCurvatureFn).
  integer(c_int) function ht_curvature(t, q, v, z, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, z, user_data
    real(c_double), pointer :: qq(:), vv(:), zz(:)

    qq => FN_VGetArray(q)
    vv => FN_VGetArray(v)
    zz => FN_VGetArray(z)
    zz = cross(vv(4:6), mat_t_vec(rotation(qq(4:7)), vv(1:3)))
    ierr = 0
  end function ht_curvature

end module heavy_top_model
