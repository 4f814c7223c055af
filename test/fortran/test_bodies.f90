! -----------------------------------------------------------------------------
! Lignum Fortran test: the body helpers (lignum_bodies.h) through
! flignum_bodies_mod, and the prismatic and cylindrical joints through
! flignum_joints_mod.
!
!  - one SE(3) body with principal inertia and gravity: M (a dense matrix
!    seen as a Fortran array) = diag(m, m, m, J), g = (m Omega x U - R^T m
!    gvec, Omega x J Omega) written out here in Fortran, the same through
!    the callback LGNBodies_ForceFn with the set as user data, the kinetic
!    and potential energy; a spring to the ground adds k (L - L0) and its
!    potential; the sizes of the sparse patterns;
!  - a prismatic and a cylindrical joint: 5 and 4 rows;
!  - bad input (a non-positive mass) reported through the set's handler.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program test_bodies
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_joints_mod
  use flignum_bodies_mod
  use flignum_sundials_mod
  use ftest_util
  implicit none

  type(c_ptr) :: ctx

  call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
  call test_body()
  call test_joints()
  call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  call ftest_finish("test_bodies")

contains

  function cross(a, b) result(c)
    real(c_double), intent(in) :: a(3), b(3)
    real(c_double) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  subroutine test_body()
    real(c_double), parameter :: mass = 2.5_c_double
    real(c_double), parameter :: Jp(3) = [0.3_c_double, 0.5_c_double, 0.7_c_double]
    real(c_double), parameter :: grav(3) = [0.2_c_double, -1.0_c_double, -9.81_c_double]
    real(c_double), parameter :: rv(3) = [0.4_c_double, -0.3_c_double, 0.9_c_double]
    real(c_double), parameter :: origin(3) = 0.0_c_double
    type(c_ptr) :: grp, B, qv, vv, gv, g2v, Mm
    real(c_double), pointer :: q(:), v(:), gf(:), g2(:), Ma(:, :)
    real(c_double) :: R9(9), R(3, 3), expect_g(6), Tkin, Vpot, L
    type(error_record), target :: rec
    integer :: i

    grp = LGNGroup_SE3()
    B = LGNBodies_Create(grp)
    call expect(c_associated(B), "LGNBodies_Create on SE(3)")
    call expect(LGNBodies_NumBodies(B) == 1, "NumBodies = 1")
    call expect_flag(LGNBodies_SetPrincipalInertia(B, 0_c_int, mass, Jp), LGN_SUCCESS, &
                     "LGN_SUCCESS", "SetPrincipalInertia")
    call expect_flag(LGNBodies_SetGravity(B, grav), LGN_SUCCESS, "LGN_SUCCESS", "SetGravity")
    qv = N_VNew_Serial(7_c_int64_t, ctx)
    vv = N_VNew_Serial(6_c_int64_t, ctx)
    gv = N_VNew_Serial(6_c_int64_t, ctx)
    g2v = N_VNew_Serial(6_c_int64_t, ctx)
    q => FN_VGetArray(qv)
    v => FN_VGetArray(vv)
    gf => FN_VGetArray(gv)
    g2 => FN_VGetArray(g2v)
    q(1:3) = [0.1_c_double, 0.2_c_double, 1.5_c_double]
    call LGNQuaternionFromRotationVector(rv, q(4:7))
    v = [1.0_c_double, -0.5_c_double, 0.3_c_double, 2.0_c_double, 0.4_c_double, -1.0_c_double]

    Mm = SUNDenseMatrix(6_c_int64_t, 6_c_int64_t, ctx)
    call expect(SUNMatZero(Mm) == 0, "SUNMatZero")
    call expect_flag(LGNBodies_Mass(B, qv, Mm), LGN_SUCCESS, "LGN_SUCCESS", "LGNBodies_Mass")
    Ma => FSUNDenseMatrix_Array(Mm)
    do i = 1, 3
      call expect_near(Ma(i, i), mass, 0.0_c_double, "M: mass on the diagonal")
      call expect_near(Ma(3 + i, 3 + i), Jp(i), 0.0_c_double, "M: principal moments")
    end do
    call expect_near(sum(abs(Ma)), 3 * mass + sum(Jp), 1.0e-15_c_double, "M: nothing else")

    call LGNQuaternionToRotation(q(4:7), R9)
    R = transpose(reshape(R9, [3, 3]))
    expect_g(1:3) = mass * cross(v(4:6), v(1:3)) - matmul(transpose(R), mass * grav)
    expect_g(4:6) = cross(v(4:6), Jp * v(4:6))
    call expect_flag(LGNBodies_Force(B, qv, vv, gv), LGN_SUCCESS, "LGN_SUCCESS", "LGNBodies_Force")
    call expect_near(maxval(abs(gf - expect_g)), 0.0_c_double, 1.0e-14_c_double, &
                     "g = (m Omega x U - R^T m gvec, Omega x J Omega)")
    call expect(LGNBodies_ForceFn(0.0_c_double, qv, vv, g2v, B) == 0, "LGNBodies_ForceFn")
    call expect_near(maxval(abs(g2 - gf)), 0.0_c_double, 0.0_c_double, "callback = LGNBodies_Force")

    call expect_flag(LGNBodies_Energy(B, qv, vv, Tkin, Vpot), LGN_SUCCESS, "LGN_SUCCESS", "Energy")
    call expect_near(Tkin, 0.5_c_double * (mass * sum(v(1:3)**2) + sum(Jp * v(4:6)**2)), &
                     1.0e-14_c_double, "kinetic energy")
    call expect_near(Vpot, -mass * dot_product(grav, q(1:3)), 1.0e-14_c_double, "potential energy")

    ! a spring from the ground's origin to the centre of mass: V += k (L - L0)^2 / 2
    call expect_flag(LGNBodies_AddSpringDamper(B, LGN_GROUND, origin, 0_c_int, origin, &
                     10.0_c_double, 0.0_c_double, 0.5_c_double), LGN_SUCCESS, "LGN_SUCCESS", &
                     "AddSpringDamper")
    call expect_flag(LGNBodies_AddRotationalSpringDamper(B, 0_c_int, LGN_GROUND, &
                     0.0_c_double, 0.0_c_double, c_null_ptr), LGN_SUCCESS, "LGN_SUCCESS", &
                     "AddRotationalSpringDamper (zero: no effect)")
    L = sqrt(sum(q(1:3)**2))
    call expect(LGNBodies_Energy(B, qv, vv, Tkin, Vpot) == LGN_SUCCESS, "Energy with a spring")
    call expect_near(Vpot, -mass * dot_product(grav, q(1:3)) + 5.0_c_double * (L - 0.5_c_double)**2, &
                     1.0e-13_c_double, "potential energy with the spring")
    call expect(LGNBodies_MassNnz(B) == 12, "MassNnz = 12")
    call expect(LGNBodies_TangentNnz(B) == 36, "TangentNnz = 36 (no pair of bodies)")

    ! bad input: through the set's own handler
    call expect(LGNBodies_SetErrHandlerFn(B, c_funloc(record_error), c_loc(rec)) == LGN_SUCCESS, &
                "SetErrHandlerFn")
    call expect_flag(LGNBodies_SetPrincipalInertia(B, 0_c_int, -1.0_c_double, Jp), &
                     LGN_ILL_INPUT, "LGN_ILL_INPUT", "a negative mass")
    call expect(rec%count == 1, "one message through the set's handler")
    if (rec%count == 1) call expect(rec%function_name == "LGNBodies_SetPrincipalInertia", &
                                    "reported under the public name")
    call expect(LGNBodies_SetErrFile(B, c_null_ptr) == LGN_SUCCESS, "SetErrFile")

    call SUNMatDestroy(Mm)
    call N_VDestroy(qv)
    call N_VDestroy(vv)
    call N_VDestroy(gv)
    call N_VDestroy(g2v)
    call LGNBodies_Destroy(B)
    call expect(.not. c_associated(B), "LGNBodies_Destroy sets B to c_null_ptr")
    call LGNGroup_Destroy(grp)
  end subroutine test_body

  subroutine test_joints()
    real(c_double), parameter :: o(3) = 0.0_c_double
    real(c_double), parameter :: ax(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
    type(c_ptr) :: body, G, J
    type(c_ptr) :: factors(2)

    body = LGNGroup_R3xSO3()
    factors = [body, body]
    G = LGNGroup_Product(2_c_int, factors)
    J = LGNJoints_Create(G)
    call expect_flag(LGNJoints_AddPrismatic(J, LGN_GROUND, o, ax, 0_c_int, o, ax), &
                     LGN_SUCCESS, "LGN_SUCCESS", "AddPrismatic")
    call expect(LGNJoints_NumConstraints(J) == 5, "prismatic: 5 rows")
    call expect_flag(LGNJoints_AddCylindrical(J, 0_c_int, o, ax, 1_c_int, o, ax), &
                     LGN_SUCCESS, "LGN_SUCCESS", "AddCylindrical")
    call expect(LGNJoints_NumConstraints(J) == 9, "cylindrical: 4 more rows")
    call LGNJoints_Destroy(J)
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(body)
  end subroutine test_joints

end program test_bodies
