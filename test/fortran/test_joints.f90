! -----------------------------------------------------------------------------
! Lignum Fortran test: the joint helpers (lignum_joints.h) through
! flignum_joints_mod, with dense matrices seen as Fortran arrays.
!
!  - a 2-body spherical chain on (R^3 x SO(3))^2 (ground - rod 0 - rod 1):
!    NumBodies, NumConstraints, JacobianNnz and StiffnessNnz (counted from
!    the joint rows and the bodies' rotation blocks), Phi = 0 at a closed configuration
!    and nonzero when a body is moved, the known translation columns of B
!    (+I, -I, none for the ground);
!  - on R^3 x SO(3) x SE(3) with a revolute and a universal joint: B, the
!    curvature Z and the stiffness K against central differences along the
!    group (LGNGroup_ComposeExp), i.e. from Phi alone:
!      B w        = d/de Phi(q o exp(e w))
!      Z(q)(v, v) = d/de B(q o exp(e v)) v
!      K w        = d/de B(q o exp(e w))^T lambda
!    and the constraint forces f = B^T lambda (computed without B) against
!    the dense B as a Fortran array, to round-off;
!  - bad input: an out-of-range body, a == b, a zero axis, vectors and
!    matrices of the wrong size, a group without rigid bodies; each returns
!    LGN_ILL_INPUT (or c_null_ptr) and is reported to the joint set's own
!    error handler (LGNJoints_SetErrHandlerFn), also after the integrator
!    it was used with is freed, under the public function's name; the
!    handler and stream setters refuse c_null_ptr, LGNJoints_SetErrFile
!    with c_null_ptr silences; Destroy nulls the handle.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program test_joints
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_joints_mod
  use flignum_sundials_mod
  use ftest_util
  implicit none

  type(c_ptr) :: ctx

  call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
  call test_chain()
  call test_derivatives()
  call test_bad_input()
  call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  call ftest_finish("test_joints")

contains

  !> Place a body: q(1:3) = x, q(4:7) = exp of the rotation vector rv.
  subroutine place(q, x, rv)
    real(c_double), intent(inout) :: q(7)
    real(c_double), intent(in) :: x(3), rv(3)

    q(1:3) = x
    call LGNQuaternionFromRotationVector(rv, q(4:7))
  end subroutine place

  !> R of body q as a Fortran matrix (LGNQuaternionToRotation is row-major).
  function rotation(q) result(R)
    real(c_double), intent(in) :: q(7)
    real(c_double) :: R(3, 3), R9(9)

    call LGNQuaternionToRotation(q(4:7), R9)
    R = transpose(reshape(R9, [3, 3]))
  end function rotation

  !> Ground - rod 0 - rod 1, spherical joints at the rod ends (+-1/2 e_z).
  subroutine test_chain()
    real(c_double), parameter :: top(3) = [0.0_c_double, 0.0_c_double, 0.5_c_double]
    real(c_double), parameter :: bottom(3) = -top, origin(3) = 0.0_c_double
    type(c_ptr) :: body, G, J, qv, phiv, B
    type(c_ptr) :: factors(2)
    real(c_double), pointer :: q(:), phi(:), Bm(:, :)
    real(c_double) :: joint(3), R(3, 3), eye(3, 3)
    integer :: i

    body = LGNGroup_R3xSO3()
    factors = [body, body]
    G = LGNGroup_Product(2_c_int, factors)
    J = LGNJoints_Create(G)
    call expect(c_associated(J), "LGNJoints_Create on (R^3 x SO(3))^2")
    call expect(LGNJoints_NumBodies(J) == 2, "NumBodies = 2")
    call expect(LGNJoints_NumConstraints(J) == 0, "no constraints before a joint")
    call expect_flag(LGNJoints_AddSpherical(J, LGN_GROUND, origin, 0_c_int, top), &
                     LGN_SUCCESS, "LGN_SUCCESS", "AddSpherical(ground, 0)")
    call expect_flag(LGNJoints_AddSpherical(J, 0_c_int, bottom, 1_c_int, top), &
                     LGN_SUCCESS, "LGN_SUCCESS", "AddSpherical(0, 1)")
    call expect(LGNJoints_NumConstraints(J) == 6, "two spherical joints: m = 6")
    ! B: 3 rows x (1 translation + 3 rotation) columns per body a joint
    ! touches (1 + 2 bodies)
    call expect(LGNJoints_JacobianNnz(J) == 3 * 4 * (1 + 2), "JacobianNnz = 36")
    ! K: the 3x3 rotation block of each body (no revolute/universal coupling)
    call expect(LGNJoints_StiffnessNnz(J) == 2 * 9, "StiffnessNnz = 18")

    ! closed configuration: rod k hangs from the previous joint, rotated
    qv = N_VNew_Serial(14_c_int64_t, ctx)
    phiv = N_VNew_Serial(6_c_int64_t, ctx)
    q => FN_VGetArray(qv)
    phi => FN_VGetArray(phiv)
    call place(q(1:7), [0.0_c_double, 0.0_c_double, 0.0_c_double], &
               [0.3_c_double, -0.2_c_double, 0.1_c_double])
    R = rotation(q(1:7))
    q(1:3) = origin - matmul(R, top)        ! top of rod 0 at the origin
    joint = q(1:3) + matmul(R, bottom)
    call place(q(8:14), [0.0_c_double, 0.0_c_double, 0.0_c_double], &
               [-0.5_c_double, 0.4_c_double, 0.7_c_double])
    R = rotation(q(8:14))
    q(8:10) = joint - matmul(R, top)        ! top of rod 1 at the bottom of rod 0
    call expect_flag(LGNJoints_Residual(J, 0.0_c_double, qv, phiv), LGN_SUCCESS, "LGN_SUCCESS", &
                     "LGNJoints_Residual")
    call expect_near(maxval(abs(phi)), 0.0_c_double, 1.0e-15_c_double, &
                     "max |Phi| at a closed configuration")
    q(10) = q(10) + 1.0e-3_c_double          ! lift rod 1: only the second joint opens
    call expect(LGNJoints_Residual(J, 0.0_c_double, qv, phiv) == LGN_SUCCESS, "LGNJoints_Residual, moved")
    call expect_near(maxval(abs(phi(1:3))), 0.0_c_double, 1.0e-15_c_double, &
                     "first joint still closed")
    call expect_near(phi(6), -1.0e-3_c_double, 1.0e-15_c_double, &
                     "Phi(6) = x_0 + R_0 s_0 - x_1 - R_1 s_1 = -dz")

    ! B dense, as a Fortran array B(1:6, 1:12): translation columns +I, -I
    B = SUNDenseMatrix(6_c_int64_t, 12_c_int64_t, ctx)
    call expect(SUNMatZero(B) == 0, "SUNMatZero")
    call expect_flag(LGNJoints_Jacobian(J, 0.0_c_double, qv, B), LGN_SUCCESS, "LGN_SUCCESS", &
                     "LGNJoints_Jacobian (dense)")
    Bm => FSUNDenseMatrix_Array(B)
    eye = 0
    do i = 1, 3
      eye(i, i) = 1
    end do
    ! Phi = x_a + R_a s_a - x_b - R_b s_b: +I for body a, -I for body b
    call expect(maxval(abs(Bm(1:3, 1:3) + eye)) <= 0, &
                "ground joint (rod 0 is b): -I in the x columns of rod 0")
    call expect(maxval(abs(Bm(4:6, 1:3) - eye)) <= 0, &
                "joint 0-1: +I in the x columns of rod 0")
    call expect(maxval(abs(Bm(4:6, 7:9) + eye)) <= 0, &
                "joint 0-1: -I in the x columns of rod 1")
    call expect(maxval(abs(Bm(1:3, 7:12))) <= 0, &
                "the ground joint has no entries in the columns of rod 1")
    call expect(count(abs(Bm) > 0) <= LGNJoints_JacobianNnz(J), "entries of B <= JacobianNnz")

    call SUNMatDestroy(B)
    call N_VDestroy(qv)
    call N_VDestroy(phiv)
    call LGNJoints_Destroy(J)
    call expect(.not. c_associated(J), "LGNJoints_Destroy sets J to c_null_ptr")
    call LGNJoints_Destroy(J)                ! c_null_ptr is allowed
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(body)
  end subroutine test_chain

  !> B, Z and K against central differences along the group.
  subroutine test_derivatives()
    real(c_double), parameter :: eps = 1.0e-5_c_double
    real(c_double), parameter :: pa(3) = [0.1_c_double, -0.2_c_double, 0.5_c_double]
    real(c_double), parameter :: pb(3) = [-0.3_c_double, 0.2_c_double, -0.4_c_double]
    real(c_double), parameter :: ax(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
    real(c_double), parameter :: axy(3) = [1.0_c_double, 1.0_c_double, 0.5_c_double]
    type(c_ptr) :: b1, b2, G, J, qv, qpv, qmv, vv, lv, zv, phipv, phimv, fv, B, Bp, Bm, K
    type(c_ptr) :: factors(2)
    real(c_double), pointer :: q(:), qp(:), qm(:), v(:), lam(:), z(:), phip(:), phim(:), f(:)
    real(c_double), pointer :: Ba(:, :), Bpa(:, :), Bma(:, :), Ka(:, :)
    real(c_double) :: w(12), scale
    integer(c_int64_t) :: m
    integer :: i

    b1 = LGNGroup_R3xSO3()
    b2 = LGNGroup_SE3()
    factors = [b1, b2]
    G = LGNGroup_Product(2_c_int, factors)
    J = LGNJoints_Create(G)
    call expect(LGNJoints_AddRevolute(J, 0_c_int, pa, axy, 1_c_int, pb, ax) == LGN_SUCCESS, &
                "AddRevolute(0, 1)")
    call expect(LGNJoints_AddUniversal(J, LGN_GROUND, pb, ax, 1_c_int, pa, axy) &
                == LGN_SUCCESS, "AddUniversal(ground, 1)")
    m = LGNJoints_NumConstraints(J)
    call expect(m == 5 + 4, "revolute (5) + universal (4): m = 9")
    ! B per body: point rows 3 x 4 (R^3 x SO(3): translation +-I) or 3 x 6
    ! (SE(3)), perpendicularity rows 1 x 3 (rotations)
    call expect(LGNJoints_JacobianNnz(J) == (12 + 3 + 3) + (18 + 3 + 3) + (18 + 3), &
                "JacobianNnz of a revolute and a universal joint")
    ! K, rotation columns: diagonal blocks (3 x 3 for R^3 x SO(3), 6 x 3 for
    ! SE(3)) and the 3 x 3 blocks (0,1), (1,0) of the revolute's coupling
    call expect(LGNJoints_StiffnessNnz(J) == 9 + 18 + 2 * 9, "StiffnessNnz with a coupling = 45")

    qv = N_VNew_Serial(14_c_int64_t, ctx)
    qpv = N_VNew_Serial(14_c_int64_t, ctx)
    qmv = N_VNew_Serial(14_c_int64_t, ctx)
    vv = N_VNew_Serial(12_c_int64_t, ctx)
    lv = N_VNew_Serial(m, ctx)
    zv = N_VNew_Serial(m, ctx)
    phipv = N_VNew_Serial(m, ctx)
    phimv = N_VNew_Serial(m, ctx)
    fv = N_VNew_Serial(12_c_int64_t, ctx)
    q => FN_VGetArray(qv)
    qp => FN_VGetArray(qpv)
    qm => FN_VGetArray(qmv)
    v => FN_VGetArray(vv)
    lam => FN_VGetArray(lv)
    z => FN_VGetArray(zv)
    phip => FN_VGetArray(phipv)
    phim => FN_VGetArray(phimv)
    f => FN_VGetArray(fv)
    B = SUNDenseMatrix(m, 12_c_int64_t, ctx)
    Bp = SUNDenseMatrix(m, 12_c_int64_t, ctx)
    Bm = SUNDenseMatrix(m, 12_c_int64_t, ctx)
    K = SUNDenseMatrix(12_c_int64_t, 12_c_int64_t, ctx)
    Ba => FSUNDenseMatrix_Array(B)
    Bpa => FSUNDenseMatrix_Array(Bp)
    Bma => FSUNDenseMatrix_Array(Bm)
    Ka => FSUNDenseMatrix_Array(K)

    ! a general configuration, velocity, direction and multipliers
    call place(q(1:7), [0.2_c_double, -0.1_c_double, 0.4_c_double], &
               [0.3_c_double, -0.7_c_double, 0.2_c_double])
    call place(q(8:14), [-0.3_c_double, 0.5_c_double, 0.1_c_double], &
               [-0.6_c_double, 0.1_c_double, 1.1_c_double])
    do i = 1, 12
      w(i) = sin(1.3_c_double * i)
      v(i) = 3 * cos(0.7_c_double * i)
    end do
    do i = 1, int(m)
      lam(i) = 10 * sin(2.1_c_double * i + 0.3_c_double)
    end do

    ! B w = d/de Phi(q o exp(e w))
    Ba = 0
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qv, B) == LGN_SUCCESS, "Jacobian at q")
    call expect(LGNGroup_ComposeExp(G, q, eps * w, qp) == 0, "q o exp(eps w)")
    call expect(LGNGroup_ComposeExp(G, q, -eps * w, qm) == 0, "q o exp(-eps w)")
    call expect(LGNJoints_Residual(J, 0.0_c_double, qpv, phipv) == LGN_SUCCESS, "Residual at q+")
    call expect(LGNJoints_Residual(J, 0.0_c_double, qmv, phimv) == LGN_SUCCESS, "Residual at q-")
    call expect_near(maxval(abs(matmul(Ba, w) - (phip - phim) / (2 * eps))), &
                     0.0_c_double, 1.0e-8_c_double, "max |B w - central difference of Phi|")

    ! f = B^T lambda without B (f is overwritten entirely: garble it first)
    f = huge(1.0_c_double)
    call expect_flag(LGNJoints_ConstraintForce(J, 0.0_c_double, qv, lv, fv), LGN_SUCCESS, "LGN_SUCCESS", &
                     "ConstraintForce at q")
    scale = maxval(abs(matmul(lam, Ba)))
    call expect(scale > 1, "B^T lambda is not small")
    call expect_near(maxval(abs(f - matmul(lam, Ba))) / scale, 0.0_c_double, 1.0e-14_c_double, &
                     "max |f - B^T lambda of the dense B| (relative)")

    ! K w = d/de B(q o exp(e w))^T lambda (K gets the term added: zero it)
    Ka = 0
    Bpa = 0
    Bma = 0
    call expect(LGNJoints_Stiffness(J, 0.0_c_double, qv, lv, K) == LGN_SUCCESS, "Stiffness at q")
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qpv, Bp) == LGN_SUCCESS, "Jacobian at q+")
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qmv, Bm) == LGN_SUCCESS, "Jacobian at q-")
    scale = maxval(abs(matmul(lam, Bpa)))
    call expect(scale > 1, "B^T lambda is not small")
    call expect_near(maxval(abs(matmul(Ka, w) - matmul(lam, Bpa - Bma) / (2 * eps))) / scale, &
                     0.0_c_double, 1.0e-8_c_double, &
                     "max |K w - central difference of B^T lambda| (relative)")

    ! Z(q)(v, v) = d/de B(q o exp(e v)) v
    call expect(LGNGroup_ComposeExp(G, q, eps * v, qp) == 0, "q o exp(eps v)")
    call expect(LGNGroup_ComposeExp(G, q, -eps * v, qm) == 0, "q o exp(-eps v)")
    Bpa = 0
    Bma = 0
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qpv, Bp) == LGN_SUCCESS, "Jacobian at q + eps v")
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qmv, Bm) == LGN_SUCCESS, "Jacobian at q - eps v")
    call expect(LGNJoints_Curvature(J, 0.0_c_double, qv, vv, zv) == LGN_SUCCESS, "Curvature")
    scale = maxval(abs(v))**2
    call expect(maxval(abs(z)) > 1.0e-2_c_double * scale, "Z(v, v) is not small")
    call expect_near(maxval(abs(z - matmul(Bpa - Bma, v) / (2 * eps))) / scale, &
                     0.0_c_double, 1.0e-8_c_double, &
                     "max |Z(v, v) - central difference of B v| / |v|^2")

    call SUNMatDestroy(B)
    call SUNMatDestroy(Bp)
    call SUNMatDestroy(Bm)
    call SUNMatDestroy(K)
    call N_VDestroy(qv)
    call N_VDestroy(qpv)
    call N_VDestroy(qmv)
    call N_VDestroy(vv)
    call N_VDestroy(lv)
    call N_VDestroy(zv)
    call N_VDestroy(phipv)
    call N_VDestroy(phimv)
    call N_VDestroy(fv)
    call LGNJoints_Destroy(J)
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(b1)
    call LGNGroup_Destroy(b2)
  end subroutine test_derivatives

  !> Bad input: LGN_ILL_INPUT or c_null_ptr, reported to the joint set's
  !! own error handler (the integrator's sees nothing, and may be freed).
  subroutine test_bad_input()
    real(c_double), parameter :: s(3) = [0.0_c_double, 0.0_c_double, 0.5_c_double]
    real(c_double), parameter :: zero(3) = 0.0_c_double
    type(error_record), target :: rec, mem_rec
    type(c_ptr) :: mem, body, Rn, G, J, JR, qv, phiv, lv, B
    type(c_ptr) :: factors(2)
    integer :: nerr

    mem = LGNCreate(ctx)
    call expect(LGNSetErrHandlerFn(mem, c_funloc(record_error), c_loc(mem_rec)) == 0, &
                "LGNSetErrHandlerFn")
    body = LGNGroup_R3xSO3()
    factors = [body, body]
    G = LGNGroup_Product(2_c_int, factors)
    J = LGNJoints_Create(G)
    call expect(c_associated(J), "LGNJoints_Create")
    call expect_flag(LGNJoints_SetErrHandlerFn(J, c_funloc(record_error), c_loc(rec)), &
                     LGN_SUCCESS, "LGN_SUCCESS", "LGNJoints_SetErrHandlerFn")
    call expect_flag(LGNJoints_SetErrHandlerFn(c_null_ptr, c_funloc(record_error), c_loc(rec)), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "LGNJoints_SetErrHandlerFn(c_null_ptr, ...)")
    call expect_flag(LGNJoints_SetErrFile(c_null_ptr, FLGNStderr()), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "LGNJoints_SetErrFile(c_null_ptr, ...)")
    call expect(rec%count == 0, "a refused setter does not call the joint set's handler")
    ! the integrator is gone: the joint set reports without it
    call LGNFree(mem)

    call expect_flag(LGNJoints_AddSpherical(J, 2_c_int, s, 0_c_int, s), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "AddSpherical with body 2 of 0..1")
    call expect(rec%count == 1 .and. rec%code == LGN_ILL_INPUT, &
                "the joint set's error handler saw LGN_ILL_INPUT")
    if (rec%count > 0) &
      call expect(rec%function_name == "LGNJoints_AddSpherical" .and. &
                  index(rec%msg, "a = 2") > 0 .and. index(rec%msg, "b = 0") > 0, &
                  "the message names the function and the bodies: "//rec%function_name// &
                  ": "//rec%msg)
    call expect(mem_rec%count == 0, "the integrator's handler saw none of it")
    call expect_flag(LGNJoints_AddSpherical(J, -2_c_int, s, 0_c_int, s), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "AddSpherical with body -2")
    call expect_flag(LGNJoints_AddSpherical(J, 1_c_int, s, 1_c_int, s), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "AddSpherical with a = b")
    call expect_flag(LGNJoints_AddRevolute(J, 0_c_int, s, zero, 1_c_int, s, s), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "AddRevolute with a zero axis")
    call expect_flag(LGNJoints_AddUniversal(J, 0_c_int, s, s, 3_c_int, s, s), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "AddUniversal with body 3")
    call expect(rec%count == 5, "each refused joint was reported")
    if (rec%count > 0) &
      call expect(rec%function_name == "LGNJoints_AddUniversal" .and. index(rec%msg, "a = 0") > 0, &
                  "the last message names LGNJoints_AddUniversal: "//rec%function_name)
    call expect(LGNJoints_NumConstraints(J) == 0, "refused joints add no constraint")

    ! vectors and matrices of the wrong size
    call expect(LGNJoints_AddSpherical(J, 0_c_int, s, 1_c_int, -s) == LGN_SUCCESS, &
                "AddSpherical(0, 1)")
    qv = N_VNew_Serial(14_c_int64_t, ctx)
    phiv = N_VNew_Serial(4_c_int64_t, ctx)
    call N_VConst(0.0_c_double, qv)
    nerr = rec%count
    call expect_flag(LGNJoints_Residual(J, 0.0_c_double, qv, phiv), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "Residual into phi of length 4 /= m = 3")
    call expect(rec%count == nerr + 1 .and. index(rec%msg, "phi") > 0, &
                "the message names phi: "//rec%msg)
    if (rec%count > 0) &
      call expect(rec%function_name == "LGNJoints_Residual", &
                  "reported under LGNJoints_Residual: "//rec%function_name)
    B = SUNDenseMatrix(3_c_int64_t, 6_c_int64_t, ctx)
    call expect_flag(LGNJoints_Jacobian(J, 0.0_c_double, qv, B), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "Jacobian into a 3 x 6 matrix (nv = 12)")
    call expect_flag(LGNJoints_Stiffness(J, 0.0_c_double, qv, phiv, B), LGN_ILL_INPUT, "LGN_ILL_INPUT", &
                     "Stiffness with lambda of length 4 /= m = 3")
    call expect_flag(LGNJoints_Residual(c_null_ptr, 0.0_c_double, qv, phiv), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "Residual of c_null_ptr")
    lv = N_VNew_Serial(3_c_int64_t, ctx)
    call expect_flag(LGNJoints_ConstraintForce(J, 0.0_c_double, qv, phiv, qv), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "ConstraintForce with lambda of length 4 /= m = 3")
    call expect_flag(LGNJoints_ConstraintForce(J, 0.0_c_double, qv, lv, qv), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "ConstraintForce into f of length 14 /= nv = 12")
    call expect_flag(LGNJoints_ConstraintForce(c_null_ptr, 0.0_c_double, qv, lv, qv), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "ConstraintForce of c_null_ptr")
    call expect(LGNJoints_NumBodies(c_null_ptr) == 0, "NumBodies(c_null_ptr) = 0")
    call expect(LGNJoints_NumConstraints(c_null_ptr) == 0, "NumConstraints(c_null_ptr) = 0")
    call expect(LGNJoints_JacobianNnz(c_null_ptr) == 0, "JacobianNnz(c_null_ptr) = 0")
    call expect(LGNJoints_StiffnessNnz(c_null_ptr) == 0, "StiffnessNnz(c_null_ptr) = 0")

    ! c_null_ptr silences the default handler; c_null_funptr restores it
    call expect_flag(LGNJoints_SetErrFile(J, c_null_ptr), LGN_SUCCESS, "LGN_SUCCESS", &
                     "LGNJoints_SetErrFile(J, c_null_ptr)")
    call expect_flag(LGNJoints_SetErrHandlerFn(J, c_null_funptr, c_null_ptr), LGN_SUCCESS, &
                     "LGN_SUCCESS", "LGNJoints_SetErrHandlerFn(J, c_null_funptr)")
    nerr = rec%count
    call expect_flag(LGNJoints_AddSpherical(J, 5_c_int, s, 0_c_int, s), LGN_ILL_INPUT, &
                     "LGN_ILL_INPUT", "AddSpherical with body 5, silenced")
    call expect(rec%count == nerr, "the replaced handler is not called")

    ! a group without rigid bodies, no group (reported on stderr)
    Rn = LGNGroup_Rn(3_c_int64_t)
    JR = LGNJoints_Create(Rn)
    call expect(.not. c_associated(JR), "LGNJoints_Create on R^3 returns c_null_ptr")
    call expect(.not. c_associated(LGNJoints_Create(c_null_ptr)), &
                "LGNJoints_Create(c_null_ptr) returns c_null_ptr")

    call SUNMatDestroy(B)
    call N_VDestroy(qv)
    call N_VDestroy(phiv)
    call N_VDestroy(lv)
    call LGNJoints_Destroy(J)
    call LGNGroup_Destroy(Rn)
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(body)
  end subroutine test_bad_input

end program test_joints
