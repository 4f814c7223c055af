! -----------------------------------------------------------------------------
! Lignum Fortran study tool: the N-body spherical pendulum chain of
! models/chain.{h,c} on (R^3 x SO(3))^N, with the callbacks of
! models/rigid_bodies.c (formulation RB_R3XSO3, analytic tangents)
! written as bind(C) Fortran functions for sparse matrices.
!
! N identical rods (solid cylinders, length 1 m, mass 1 kg, radius 0.02 m,
! axis = body z) joined by spherical joints, the top of rod 0 to the ground
! at the origin, under gravity g = (0, 0, -9.81). Initial configuration, at
! rest: rod k (k = 0..N-1) points from its top to its bottom along
!   d_k = (sin th_k cos ph_k, sin th_k sin ph_k, -cos th_k),
!   th_k = (pi/2)(1 - k/N),   ph_k = 0.3 k/N,
! i.e. the chain starts horizontal at the support and bends down towards the
! vertical, slightly twisted out of the x-z plane so the motion is spatial.
!
! Body k: q = (x, p), v = (u inertial, Omega body),
!   M = diag(m I, J),  g = [-m g ; Omega x J Omega],
!   C_t: Omega block Omega~ J - (J Omega)~,
! and the joints (Phi, B, Z and the geometric stiffness K_t) come from the
! joint helpers (flignum_joints_mod). With KLU Lignum hands M and C_t to the
! callbacks as empty sparse matrices (CSC or CSR, as A): they are written
! through the pointer views of flignum_klu_mod, M with its 6 N diagonal
! entries, C_t with the 3x3 Omega blocks (9 N entries, zeros included),
! exactly the patterns of the C model.
!
! The arithmetic follows the C model operation by operation, so that both
! produce the same numbers (the tests tool_fortran_chain_* compare).
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
module chain_model
  use, intrinsic :: iso_c_binding
  use flignum_mod, only: LGNGroup_R3xSO3, LGNGroup_Product, LGNGroup_Identity, &
                         LGNGroup_Destroy, LGNQuaternionToRotation, &
                         LGNQuaternionFromRotationVector, LGN_SUCCESS, LGN_MEM_FAIL
  use flignum_joints_mod
  use flignum_sundials_mod, only: N_VNew_Serial, N_VDestroy, N_VConst, FN_VGetArray, &
                                  SUNMatGetID, SUNMATRIX_SPARSE, &
                                  SUNSparseMatrix_SparseType, CSC_MAT
  use flignum_klu_mod
  implicit none
  private

  public :: chain_data, chain_create, chain_free, chain_energy, chain_free_end
  public :: chain_mass, chain_force, chain_damping, chain_stiffness
  public :: chain_constr, chain_constr_jac, chain_curvature

  !> The chain (user data of every callback).
  type :: chain_data
    integer :: n = 0                            !< bodies
    real(c_double), allocatable :: mass(:)      !< mass(k), k = 1..n
    real(c_double), allocatable :: inertia(:, :) !< principal moments (1:3, k)
    real(c_double) :: gravity(3) = [0.0_c_double, 0.0_c_double, -9.81_c_double]
    type(c_ptr) :: body = c_null_ptr            !< the leaf R^3 x SO(3)
    type(c_ptr) :: G = c_null_ptr               !< the product (R^3 x SO(3))^n
    type(c_ptr) :: joints = c_null_ptr          !< LGNJoints
    type(c_ptr) :: q0 = c_null_ptr, v0 = c_null_ptr !< initial state
  end type chain_data

contains

  ! ===========================================================================
  ! Set-up (chain_create of chain.c, rigid_create/_set_cylinder/_place of
  ! rigid_bodies.c)
  ! ===========================================================================

  !> Build the chain of n rods: group, joints, initial state.
  !! @param sys the chain (free it with chain_free)
  !! @param n   number of rods (>= 1)
  !! @param ctx SUNDIALS context
  !! @return    LGN_SUCCESS or LGN_MEM_FAIL
  function chain_create(sys, n, ctx) result(flag)
    type(chain_data), intent(inout) :: sys
    integer, intent(in) :: n
    type(c_ptr), intent(in) :: ctx
    integer(c_int) :: flag
    real(c_double), parameter :: L = 1.0_c_double, rod_mass = 1.0_c_double
    real(c_double), parameter :: radius = 0.02_c_double
    real(c_double), parameter :: top(3) = [0.0_c_double, 0.0_c_double, 0.5_c_double * L]
    real(c_double), parameter :: bottom(3) = [0.0_c_double, 0.0_c_double, -0.5_c_double * L]
    real(c_double), parameter :: origin(3) = 0.0_c_double
    type(c_ptr), allocatable :: factors(:)
    real(c_double), pointer :: q(:)
    real(c_double) :: pi, joint(3), th, ph, d(0:2), e1(0:2), e2(0:2), e3(0:2), R(0:8)
    real(c_double) :: x(0:2), nrm
    integer :: k, i

    flag = LGN_MEM_FAIL
    sys%n = n
    allocate (sys%mass(n), sys%inertia(3, n), factors(n))
    sys%mass = 1.0_c_double
    sys%inertia = 1.0_c_double
    sys%body = LGNGroup_R3xSO3()
    factors = sys%body
    sys%G = LGNGroup_Product(int(n, c_int), factors)
    deallocate (factors)
    if (.not. c_associated(sys%G)) return
    sys%joints = LGNJoints_Create(sys%G)
    sys%q0 = N_VNew_Serial(7_c_int64_t * n, ctx)
    sys%v0 = N_VNew_Serial(6_c_int64_t * n, ctx)
    if (.not. (c_associated(sys%joints) .and. c_associated(sys%q0) &
               .and. c_associated(sys%v0))) return
    call N_VConst(0.0_c_double, sys%v0)
    q => FN_VGetArray(sys%q0)
    do k = 0, n - 1
      if (LGNGroup_Identity(sys%body, q(7 * k + 1:7 * k + 7)) /= 0) return
    end do

    pi = acos(-1.0_c_double)
    joint = 0.0_c_double
    do k = 0, n - 1
      th = 0.5_c_double * pi * (1.0_c_double - real(k, c_double) / n)
      ph = 0.3_c_double * real(k, c_double) / n
      d(0) = sin(th) * cos(ph)
      d(1) = sin(th) * sin(ph)
      d(2) = -cos(th)
      ! body frame: e3 = -d (bottom to top), e1 horizontal, e2 = e3 x e1
      e3 = -d
      e1(0) = -sin(ph)
      e1(1) = cos(ph)
      e1(2) = 0.0_c_double
      e2(0) = e3(1) * e1(2) - e3(2) * e1(1)
      e2(1) = e3(2) * e1(0) - e3(0) * e1(2)
      e2(2) = e3(0) * e1(1) - e3(1) * e1(0)
      nrm = sqrt(e2(0) * e2(0) + e2(1) * e2(1) + e2(2) * e2(2))
      do i = 0, 2
        e2(i) = e2(i) / nrm
        R(3 * i) = e1(i)       ! R row-major (as in C), columns e1, e2, e3
        R(3 * i + 1) = e2(i)
        R(3 * i + 2) = e3(i)
        x(i) = joint(i + 1) + 0.5_c_double * L * d(i)
      end do
      call set_cylinder(sys, k + 1, L, rod_mass, radius)
      call place(q(7 * k + 1:7 * k + 7), x, R)
      if (k == 0) then
        flag = LGNJoints_AddSpherical(sys%joints, LGN_GROUND, origin, 0_c_int, top)
      else
        flag = LGNJoints_AddSpherical(sys%joints, int(k - 1, c_int), bottom, &
                                      int(k, c_int), top)
      end if
      if (flag /= LGN_SUCCESS) return
      do i = 0, 2
        joint(i + 1) = joint(i + 1) + L * d(i)
      end do
    end do
  end function chain_create

  !> Body k (1-based): solid cylinder of length L, mass m, radius r, axis = body z.
  subroutine set_cylinder(sys, k, L, m, r)
    type(chain_data), intent(inout) :: sys
    integer, intent(in) :: k
    real(c_double), intent(in) :: L, m, r

    sys%mass(k) = m
    sys%inertia(1, k) = m * (3.0_c_double * r * r + L * L) / 12.0_c_double
    sys%inertia(2, k) = sys%inertia(1, k)
    sys%inertia(3, k) = 0.5_c_double * m * r * r
  end subroutine set_cylinder

  !> q of one body from its centre of mass x and its rotation R (row-major,
  !! R(3 i + j) = R_ij): the rotation vector of R (angle < pi), then the
  !! quaternion.
  subroutine place(q, x, R)
    real(c_double), intent(inout) :: q(7)
    real(c_double), intent(in) :: x(0:2), R(0:8)
    real(c_double) :: rv(3), c, s, tr, angle, f

    tr = R(0) + R(4) + R(8)
    c = 0.5_c_double * (tr - 1.0_c_double)
    s = 0.5_c_double * sqrt((R(7) - R(5)) * (R(7) - R(5)) + (R(2) - R(6)) * (R(2) - R(6)) + &
                            (R(3) - R(1)) * (R(3) - R(1)))
    angle = atan2(s, c)
    if (s > 1.0e-12_c_double) then
      f = angle / (2.0_c_double * s)
    else
      f = 0.5_c_double
    end if
    rv(1) = f * (R(7) - R(5))
    rv(2) = f * (R(2) - R(6))
    rv(3) = f * (R(3) - R(1))
    q(1:3) = x
    call LGNQuaternionFromRotationVector(rv, q(4:7))
  end subroutine place

  !> Free what chain_create made.
  subroutine chain_free(sys)
    type(chain_data), intent(inout) :: sys

    call LGNJoints_Destroy(sys%joints)
    if (c_associated(sys%q0)) call N_VDestroy(sys%q0)
    if (c_associated(sys%v0)) call N_VDestroy(sys%v0)
    call LGNGroup_Destroy(sys%G)
    call LGNGroup_Destroy(sys%body)
    sys%q0 = c_null_ptr
    sys%v0 = c_null_ptr
    sys%G = c_null_ptr
    sys%body = c_null_ptr
    if (allocated(sys%mass)) deallocate (sys%mass)
    if (allocated(sys%inertia)) deallocate (sys%inertia)
  end subroutine chain_free

  ! ===========================================================================
  ! Outputs
  ! ===========================================================================

  !> Total energy: kinetic + gravitational potential (zero at the origin).
  function chain_energy(sys, q, v) result(E)
    type(chain_data), intent(in) :: sys
    real(c_double), intent(in) :: q(:), v(:)
    real(c_double) :: E
    integer :: k, i, o

    E = 0.0_c_double
    do k = 1, sys%n
      o = 6 * (k - 1)
      do i = 1, 3
        E = E + 0.5_c_double * (sys%mass(k) * v(o + i) * v(o + i) + &
                                sys%inertia(i, k) * v(o + 3 + i) * v(o + 3 + i))
      end do
      do i = 1, 3
        E = E - sys%mass(k) * sys%gravity(i) * q(7 * (k - 1) + i)
      end do
    end do
  end function chain_energy

  !> Position of the free end (bottom of the last rod): x - (L/2) R e3.
  function chain_free_end(sys, q) result(tip)
    type(chain_data), intent(in) :: sys
    real(c_double), intent(in) :: q(:)
    real(c_double) :: tip(3), R(0:8)
    integer :: o, i

    o = 7 * (sys%n - 1)
    call LGNQuaternionToRotation(q(o + 4:o + 7), R)
    do i = 0, 2
      tip(i + 1) = q(o + i + 1) - 0.5_c_double * R(3 * i + 2)
    end do
  end function chain_free_end

  ! ===========================================================================
  ! Callbacks (Lignum zeroes or empties the matrices before each call)
  ! ===========================================================================

  !> c = a x b (as Cross of rigid_bodies.c)
  pure function cross(a, b) result(c)
    real(c_double), intent(in) :: a(3), b(3)
    real(c_double) :: c(3)

    c(1) = a(2) * b(3) - a(3) * b(2)
    c(2) = a(3) * b(1) - a(1) * b(3)
    c(3) = a(1) * b(2) - a(2) * b(1)
  end function cross

  !> The 6x6 mass block of body k: diag(m, m, m, J1, J2, J3).
  pure function mass_block(sys, k) result(blk)
    type(chain_data), intent(in) :: sys
    integer, intent(in) :: k
    real(c_double) :: blk(6, 6)
    integer :: i

    blk = 0.0_c_double
    do i = 1, 3
      blk(i, i) = sys%mass(k)
      blk(3 + i, 3 + i) = sys%inertia(i, k)
    end do
  end function mass_block

  !> The 6x6 damping block of body k: d(Omega x J Omega)/dOmega
  !! = Omega~ J - (J Omega)~ in the Omega block (DampingBlock of C).
  pure function damping_block(sys, k, v) result(blk)
    type(chain_data), intent(in) :: sys
    integer, intent(in) :: k
    real(c_double), intent(in) :: v(:)
    real(c_double) :: blk(6, 6), w(3), Jw(3), e(3), c1(3)
    integer :: i, j

    blk = 0.0_c_double
    w = v(6 * (k - 1) + 4:6 * (k - 1) + 6)
    do i = 1, 3
      Jw(i) = sys%inertia(i, k) * w(i)
    end do
    do j = 1, 3
      e = 0.0_c_double
      e(j) = sys%inertia(j, k)
      c1 = cross(w, e)
      do i = 1, 3
        blk(3 + i, 3 + j) = blk(3 + i, 3 + j) + c1(i)
      end do
    end do
    ! += -(J w)~ (AddSkew of C with f = -1)
    blk(5, 4) = blk(5, 4) + (-1.0_c_double) * Jw(3)
    blk(6, 4) = blk(6, 4) - (-1.0_c_double) * Jw(2)
    blk(4, 5) = blk(4, 5) - (-1.0_c_double) * Jw(3)
    blk(6, 5) = blk(6, 5) + (-1.0_c_double) * Jw(1)
    blk(4, 6) = blk(4, 6) + (-1.0_c_double) * Jw(2)
    blk(5, 6) = blk(5, 6) - (-1.0_c_double) * Jw(1)
  end function damping_block

  !> Write a block-diagonal matrix with 6x6 blocks into the empty sparse A
  !! (CSC or CSR): the 9 entries of each block's Omega part, or only its
  !! diagonal.
  !! @param v velocities (for the damping blocks; unused for the mass)
  !! @return  0, or -1 if A is not sparse or cannot be enlarged
  function write_block_diagonal(sys, A, damping, v) result(ierr)
    type(chain_data), intent(in) :: sys
    type(c_ptr), intent(in) :: A
    logical, intent(in) :: damping
    real(c_double), intent(in) :: v(:)
    integer(c_int) :: ierr
    real(c_double), pointer :: val(:)
    integer(c_int64_t), pointer :: ind(:), ptr(:)
    real(c_double) :: blk(6, 6)
    integer(c_int64_t) :: p
    integer :: per, k, r, c
    logical :: csc

    ierr = -1
    if (SUNMatGetID(A) /= SUNMATRIX_SPARSE) return
    per = merge(9, 6, damping)                         ! entries per body
    csc = SUNSparseMatrix_SparseType(A) == CSC_MAT
    if (FSUNSparseMatrix_Reserve(A, int(per * sys%n, c_int64_t)) /= 0) return
    val => FSUNSparseMatrix_Data(A)
    ind => FSUNSparseMatrix_IndexValues(A)
    ptr => FSUNSparseMatrix_IndexPointers(A)
    p = 0
    ptr(1) = 0
    do k = 1, sys%n
      if (damping) then
        blk = damping_block(sys, k, v)
      else
        blk = mass_block(sys, k)
      end if
      do c = 1, 6
        do r = 1, 6
          if (.not. damping .and. r /= c) cycle
          if (damping .and. (r <= 3 .or. c <= 3)) cycle
          p = p + 1
          ind(p) = 6 * (k - 1) + r - 1                 ! 0-based row (CSC) / column (CSR)
          val(p) = merge(blk(r, c), blk(c, r), csc)
        end do
        ptr(6 * (k - 1) + c + 1) = p                   ! 0-based end of column/row
      end do
    end do
    ierr = 0
  end function write_block_diagonal

  !> LGNMassFn: M = diag(m I, J) per body, sparse.
  integer(c_int) function chain_mass(t, q, M, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, M, user_data
    type(chain_data), pointer :: sys
    real(c_double) :: none(0)

    call c_f_pointer(user_data, sys)
    ierr = write_block_diagonal(sys, M, .false., none)
  end function chain_mass

  !> LGNForceFn: g = [-m g ; Omega x J Omega] per body.
  integer(c_int) function chain_force(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    type(chain_data), pointer :: sys
    real(c_double), pointer :: vv(:), gg(:)
    real(c_double) :: w(3), Jw(3)
    integer :: k, i, o

    call c_f_pointer(user_data, sys)
    vv => FN_VGetArray(v)
    gg => FN_VGetArray(g)
    do k = 1, sys%n
      o = 6 * (k - 1)
      w = vv(o + 4:o + 6)
      do i = 1, 3
        Jw(i) = sys%inertia(i, k) * w(i)
      end do
      gg(o + 4:o + 6) = cross(w, Jw)
      do i = 1, 3
        gg(o + i) = -sys%mass(k) * sys%gravity(i)
      end do
    end do
    ierr = 0
  end function chain_force

  !> LGNDampingFn: C_t = dg/dv, the 6x6 blocks of the bodies, sparse.
  integer(c_int) function chain_damping(t, q, v, C, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, C, user_data
    type(chain_data), pointer :: sys

    call c_f_pointer(user_data, sys)
    ierr = write_block_diagonal(sys, C, .true., FN_VGetArray(v))
  end function chain_damping

  !> LGNStiffnessFn: K_t = the joints' geometric stiffness d/dq (B^T lambda).
  integer(c_int) function chain_stiffness(t, q, v, vdot, lambda, K, user_data) &
      result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, vdot, lambda, K, user_data
    type(chain_data), pointer :: sys

    call c_f_pointer(user_data, sys)
    ierr = merge(0_c_int, -1_c_int, LGNJoints_Stiffness(sys%joints, t, q, lambda, K) == 0)
  end function chain_stiffness

  !> LGNConstrFn: phi = Phi(q) of the joints.
  integer(c_int) function chain_constr(t, q, phi, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, phi, user_data
    type(chain_data), pointer :: sys

    call c_f_pointer(user_data, sys)
    ierr = merge(0_c_int, -1_c_int, LGNJoints_Residual(sys%joints, t, q, phi) == 0)
  end function chain_constr

  !> LGNConstrJacFn: B = B(q) of the joints (sparse, the whole pattern).
  integer(c_int) function chain_constr_jac(t, q, B, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, B, user_data
    type(chain_data), pointer :: sys

    call c_f_pointer(user_data, sys)
    ierr = merge(0_c_int, -1_c_int, LGNJoints_Jacobian(sys%joints, t, q, B) == 0)
  end function chain_constr_jac

  !> LGNCurvatureFn: z = Z(q)(v, v) of the joints.
  integer(c_int) function chain_curvature(t, q, v, z, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, z, user_data
    type(chain_data), pointer :: sys

    call c_f_pointer(user_data, sys)
    ierr = merge(0_c_int, -1_c_int, LGNJoints_Curvature(sys%joints, t, q, v, z) == 0)
  end function chain_curvature

end module chain_model
