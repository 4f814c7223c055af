! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_planar_mod: hand-written ISO_C_BINDING interface to
! include/lignum/lignum_planar.h: the planar groups SE(2) and R^2 x SO(2)
! (q = (x, y, theta), the angle unwrapped) and the planar elements of the
! body and joint sets created on them (flignum_bodies_mod,
! flignum_joints_mod evaluate them).
!
! Names are the C names, types as in flignum_bodies_mod:
!   LGNGroup, LGNBodies, LGNJoints -> type(c_ptr), value
!   LGNDriveFn                     -> type(c_funptr), value
!   int (body indices, flags)      -> integer(c_int)
!   sunrealtype                    -> real(c_double), value
!   const sunrealtype[2]           -> real(c_double) :: x(2)
! Body indices are 0-based; LGN_GROUND is the one of flignum_joints_mod.
! The body set's second body is bb (Fortran does not tell B from b).
! ---------------------------------------------------------------------------
module flignum_planar_mod
  use, intrinsic :: iso_c_binding
  implicit none

  interface
    !> SE(2): q = (x, y, theta), v = (U body-fixed, omega).
    type(c_ptr) function LGNGroup_SE2() bind(c, name="LGNGroup_SE2")
      import :: c_ptr
    end function LGNGroup_SE2

    !> R^2 x SO(2): q = (x, y, theta), v = (u inertial, omega); T = I.
    type(c_ptr) function LGNGroup_R2xSO2() bind(c, name="LGNGroup_R2xSO2")
      import :: c_ptr
    end function LGNGroup_R2xSO2

    !> Mass m > 0 and moment of inertia J > 0 of planar body k.
    integer(c_int) function LGNBodies_SetPlanarMass(B, k, m, J) &
        bind(c, name="LGNBodies_SetPlanarMass")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: B
      integer(c_int), value :: k
      real(c_double), value :: m, J
    end function LGNBodies_SetPlanarMass

    !> Spring-damper between points sa of a and sb of b (2-vectors).
    integer(c_int) function LGNBodies_AddPlanarSpringDamper(B, a, sa, bb, sb, k, c, L0) &
        bind(c, name="LGNBodies_AddPlanarSpringDamper")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: B
      integer(c_int), value :: a, bb
      real(c_double), intent(in) :: sa(2), sb(2)
      real(c_double), value :: k, c, L0
    end function LGNBodies_AddPlanarSpringDamper

    !> Rotational spring-damper: torque -kr (theta_b - theta_a - theta0)
    !! - cr (omega_b - omega_a) on b.
    integer(c_int) function LGNBodies_AddPlanarRotationalSpringDamper(B, a, bb, kr, cr, &
        theta0) bind(c, name="LGNBodies_AddPlanarRotationalSpringDamper")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: B
      integer(c_int), value :: a, bb
      real(c_double), value :: kr, cr, theta0
    end function LGNBodies_AddPlanarRotationalSpringDamper

    !> Planar revolute joint (2 rows): p_a - p_b = 0.
    integer(c_int) function LGNJoints_AddPlanarRevolute(J, a, sa, b, sb) &
        bind(c, name="LGNJoints_AddPlanarRevolute")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(2), sb(2)
    end function LGNJoints_AddPlanarRevolute

    !> Planar prismatic joint (2 rows): sb on the line through sa along
    !! axis_a, theta_b - theta_a = theta0.
    integer(c_int) function LGNJoints_AddPlanarPrismatic(J, a, sa, axis_a, b, sb, theta0) &
        bind(c, name="LGNJoints_AddPlanarPrismatic")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(2), axis_a(2), sb(2)
      real(c_double), value :: theta0
    end function LGNJoints_AddPlanarPrismatic

    !> Planar rotation driver (1 row): theta_b - theta_a = f(t).
    integer(c_int) function LGNJoints_AddPlanarRotationDriver(J, a, b, f, drive_data) &
        bind(c, name="LGNJoints_AddPlanarRotationDriver")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      type(c_funptr), value :: f
      type(c_ptr), value :: drive_data
    end function LGNJoints_AddPlanarRotationDriver

    !> Planar translation driver (1 row): (R_a e).(p_b - p_a) = f(t).
    integer(c_int) function LGNJoints_AddPlanarTranslationDriver(J, a, sa, axis_a, b, sb, f, &
        drive_data) bind(c, name="LGNJoints_AddPlanarTranslationDriver")
      import :: c_int, c_ptr, c_double, c_funptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(2), axis_a(2), sb(2)
      type(c_funptr), value :: f
      type(c_ptr), value :: drive_data
    end function LGNJoints_AddPlanarTranslationDriver
  end interface
end module flignum_planar_mod
