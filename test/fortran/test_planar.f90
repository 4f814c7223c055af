! -----------------------------------------------------------------------------
! Lignum Fortran test: the planar groups and elements (lignum_planar.h)
! through flignum_planar_mod: a pendulum of one R^2 x SO(2) body on a
! planar revolute joint, with a prismatic slider, both drivers, the
! spring-dampers; the row counts, Phi = 0 where the joints hold, g of the
! spring and gravity written out here, bad input refused.
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------
program test_planar
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_joints_mod
  use flignum_bodies_mod
  use flignum_planar_mod
  use flignum_sundials_mod
  use ftest_util
  implicit none

  type(c_ptr) :: ctx, body, slider, G, J, B, qv, vv, gv, phiv
  type(c_ptr), target :: factors(2)
  real(c_double), pointer :: q(:), v(:), gf(:), phi(:)
  real(c_double), parameter :: m = 2.0d0, grav(3) = [0.0d0, -9.81d0, 0.0d0]
  real(c_double) :: th

  call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
  body = LGNGroup_R2xSO2()
  slider = LGNGroup_SE2()
  factors = [body, slider]
  G = LGNGroup_Product(2_c_int, factors)
  J = LGNJoints_Create(G)
  B = LGNBodies_Create(G)
  call expect(c_associated(J) .and. c_associated(B), "planar sets created")
  ! body 0: a rod pinned at its end (-0.5, 0) to the origin; body 1 slides on x
  call expect_flag(LGNJoints_AddPlanarRevolute(J, LGN_GROUND, [0.0d0, 0.0d0], 0_c_int, &
       [-0.5d0, 0.0d0]), LGN_SUCCESS, "LGN_SUCCESS", "revolute")
  call expect_flag(LGNJoints_AddPlanarPrismatic(J, LGN_GROUND, [0.0d0, 0.0d0], [1.0d0, 0.0d0], &
       1_c_int, [0.0d0, 0.0d0], 0.0d0), LGN_SUCCESS, "LGN_SUCCESS", "prismatic")
  call expect(LGNJoints_NumConstraints(J) == 4, "2 + 2 rows")
  call expect_flag(LGNJoints_AddPlanarRotationDriver(J, 0_c_int, 0_c_int, c_null_funptr, &
       c_null_ptr), LGN_ILL_INPUT, "LGN_ILL_INPUT", "a = b refused")
  call expect_flag(LGNJoints_AddPlanarTranslationDriver(J, 0_c_int, [0.0d0, 0.0d0], &
       [0.0d0, 0.0d0], 1_c_int, [0.0d0, 0.0d0], c_null_funptr, c_null_ptr), LGN_ILL_INPUT, &
       "LGN_ILL_INPUT", "zero axis refused")
  call expect_flag(LGNBodies_SetPlanarMass(B, 0_c_int, m, 0.2d0), LGN_SUCCESS, &
       "LGN_SUCCESS", "mass")
  call expect_flag(LGNBodies_SetPlanarMass(B, 5_c_int, m, 0.2d0), LGN_ILL_INPUT, &
       "LGN_ILL_INPUT", "body out of range refused")
  call expect_flag(LGNBodies_SetGravity(B, grav), LGN_SUCCESS, "LGN_SUCCESS", "gravity")
  call expect_flag(LGNBodies_AddPlanarSpringDamper(B, 0_c_int, [0.5d0, 0.0d0], 1_c_int, &
       [0.0d0, 0.0d0], 10.0d0, 0.0d0, 0.0d0), LGN_SUCCESS, "LGN_SUCCESS", &
       "spring")
  call expect_flag(LGNBodies_AddPlanarRotationalSpringDamper(B, LGN_GROUND, 0_c_int, 3.0d0, &
       0.0d0, 0.0d0), LGN_SUCCESS, "LGN_SUCCESS", "rot. spring")
  ! the rod at angle th (centre at 0.5 (cos th, sin th)), the slider at its tip
  th = 0.3d0
  qv = N_VNew_Serial(6_c_int64_t, ctx)
  vv = N_VNew_Serial(6_c_int64_t, ctx)
  gv = N_VNew_Serial(6_c_int64_t, ctx)
  phiv = N_VNew_Serial(4_c_int64_t, ctx)
  q => FN_VGetArray(qv)
  v => FN_VGetArray(vv)
  gf => FN_VGetArray(gv)
  phi => FN_VGetArray(phiv)
  q = [0.5d0 * cos(th), 0.5d0 * sin(th), th, 1.3d0, 0.0d0, 0.0d0]
  v = 0.0d0
  call expect_flag(LGNJoints_Residual(J, 0.0d0, qv, phiv), LGN_SUCCESS, "LGN_SUCCESS", &
       "Phi")
  call expect(maxval(abs(phi)) < 1d-15, "Phi = 0 where the joints hold")
  call expect_flag(LGNBodies_Force(B, qv, vv, gv), LGN_SUCCESS, "LGN_SUCCESS", "g")
  ! the spring from the rod's tip (cos th, sin th) to the slider (1.3, 0),
  ! tension 10 L pulling the tip along n; g = - gravity - spring force
  block
    real(c_double) :: d(2), L, n(2), gx(2)
    d = [1.3d0 - cos(th), -sin(th)]
    L = norm2(d)
    n = d / L
    gx = -m * grav(1:2) - 10.0d0 * L * n
    call expect_near(gf(1), gx(1), 1d-13, "g_x of the rod")
    call expect_near(gf(2), gx(2), 1d-13, "g_y of the rod")
    call expect_near(gf(3), -0.5d0 * (cos(th) * 10.0d0 * L * n(2) - sin(th) * 10.0d0 * L * n(1)) &
         + 3.0d0 * th, 1d-13, "g_theta of the rod")
  end block
  call N_VDestroy(qv)
  call N_VDestroy(vv)
  call N_VDestroy(gv)
  call N_VDestroy(phiv)
  call LGNBodies_Destroy(B)
  call LGNJoints_Destroy(J)
  call LGNGroup_Destroy(G)
  call LGNGroup_Destroy(body)
  call LGNGroup_Destroy(slider)
  call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  call ftest_finish("test_planar")
end program test_planar
