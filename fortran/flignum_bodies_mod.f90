! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_bodies_mod: hand-written ISO_C_BINDING interface to the body
! helpers of include/lignum/lignum_bodies.h (rigid bodies on R^3 x SO(3) or
! SE(3) leaves of the configuration group, gravity, translational and
! rotational spring-dampers: M, g, K_t = d/dq (M vdot + g), C_t = dg/dv and
! the energies, ready to call from the model callbacks, and the callbacks
! LGNBodies_MassFn, ... themselves, to pass with c_funloc and the body set
! as user data).
!
! Names are the C names, types as in flignum_mod and flignum_joints_mod:
!   LGNBodies, LGNGroup, N_Vector, SUNMatrix, FILE * -> type(c_ptr), value
!   LGNErrHandlerFn        -> type(c_funptr), value
!   LGNBodies *B (LGNBodies_Destroy) -> type(c_ptr), by reference
!   int (body indices, flags) -> integer(c_int)
!   sunindextype           -> integer(c_int64_t)
!   sunrealtype            -> real(c_double), value
!   const sunrealtype[n]   -> real(c_double) :: x(n); the 3x3 inertia is
!                             row-major in C: symmetric, so either order
! Body indices are 0-based; LGN_GROUND is the one of flignum_joints_mod.
! ---------------------------------------------------------------------------
module flignum_bodies_mod
  use, intrinsic :: iso_c_binding
  implicit none

  interface
    !> Create the body set of G (R^3 x SO(3), SE(3) or a product of them;
    !! referenced, must outlive the set): masses 1, inertias I, gravity 0,
    !! no force elements. c_null_ptr (message on stderr) on bad G or no
    !! memory.
    type(c_ptr) function LGNBodies_Create(G) bind(c, name="LGNBodies_Create")
      import :: c_ptr
      type(c_ptr), value :: G
    end function LGNBodies_Create

    !> Error handler of the body set (c_null_funptr: the default).
    integer(c_int) function LGNBodies_SetErrHandlerFn(B, ehfun, eh_data) &
        bind(c, name="LGNBodies_SetErrHandlerFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: B
      type(c_funptr), value :: ehfun
      type(c_ptr), value :: eh_data
    end function LGNBodies_SetErrHandlerFn

    !> Stream of the default error handler (c_null_ptr silences it).
    integer(c_int) function LGNBodies_SetErrFile(B, errfp) &
        bind(c, name="LGNBodies_SetErrFile")
      import :: c_int, c_ptr
      type(c_ptr), value :: B, errfp
    end function LGNBodies_SetErrFile

    !> Free a body set and set B = c_null_ptr; c_null_ptr is allowed.
    subroutine LGNBodies_Destroy(B) bind(c, name="LGNBodies_Destroy")
      import :: c_ptr
      type(c_ptr), intent(inout) :: B
    end subroutine LGNBodies_Destroy

    !> Number of bodies; 0 for c_null_ptr.
    integer(c_int) function LGNBodies_NumBodies(B) bind(c, name="LGNBodies_NumBodies")
      import :: c_int, c_ptr
      type(c_ptr), value :: B
    end function LGNBodies_NumBodies

    !> Bodies first_ghost ... (0-based) are ghosts of other MPI ranks' bodies:
    !! no mass, inertia or weight here.
    integer(c_int) function LGNBodies_SetGhosts(B, first_ghost) &
        bind(c, name="LGNBodies_SetGhosts")
      import :: c_int, c_ptr
      type(c_ptr), value :: B
      integer(c_int), value :: first_ghost
    end function LGNBodies_SetGhosts

    !> Number of bodies that are not ghosts; 0 for c_null_ptr.
    integer(c_int) function LGNBodies_NumOwnedBodies(B) bind(c, name="LGNBodies_NumOwnedBodies")
      import :: c_int, c_ptr
      type(c_ptr), value :: B
    end function LGNBodies_NumOwnedBodies

    !> Mass m > 0 and inertia (3x3 about the centre of mass in body axes,
    !! symmetric positive definite) of body k (0-based).
    integer(c_int) function LGNBodies_SetMass(B, k, m, inertia) &
        bind(c, name="LGNBodies_SetMass")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B
      integer(c_int), value :: k
      real(c_double), value :: m
      real(c_double), intent(in) :: inertia(9)
    end function LGNBodies_SetMass

    !> Mass m > 0 and principal moments J(3) > 0 of body k.
    integer(c_int) function LGNBodies_SetPrincipalInertia(B, k, m, J) &
        bind(c, name="LGNBodies_SetPrincipalInertia")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B
      integer(c_int), value :: k
      real(c_double), value :: m
      real(c_double), intent(in) :: J(3)
    end function LGNBodies_SetPrincipalInertia

    !> Acceleration of gravity (inertial), shared by all bodies.
    integer(c_int) function LGNBodies_SetGravity(B, gravity) &
        bind(c, name="LGNBodies_SetGravity")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B
      real(c_double), intent(in) :: gravity(3)
    end function LGNBodies_SetGravity

    !> Translational spring-damper between point sa of body a and sb of
    !! body b (LGN_GROUND: inertial point): k, c, L0 >= 0.
    integer(c_int) function LGNBodies_AddSpringDamper(B, a, sa, bb, sb, k, c, L0) &
        bind(c, name="LGNBodies_AddSpringDamper")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B
      integer(c_int), value :: a, bb
      real(c_double), intent(in) :: sa(3), sb(3)
      real(c_double), value :: k, c, L0
    end function LGNBodies_AddSpringDamper

    !> Rotational spring-damper between bodies a and b: torque
    !! -kr theta - cr omega_rel on b, theta = log(R0^T R_a^T R_b), with R0
    !! the rest relative rotation given by the unit quaternion rest:
    !! c_loc(p0) of a real(c_double), target :: p0(4), or c_null_ptr for R0 = I.
    integer(c_int) function LGNBodies_AddRotationalSpringDamper(B, a, bb, kr, cr, rest) &
        bind(c, name="LGNBodies_AddRotationalSpringDamper")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B
      integer(c_int), value :: a, bb
      real(c_double), value :: kr, cr
      type(c_ptr), value :: rest
    end function LGNBodies_AddRotationalSpringDamper

    !> Stored entries of a sparse M (12 per body).
    integer(c_int64_t) function LGNBodies_MassNnz(B) bind(c, name="LGNBodies_MassNnz")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: B
    end function LGNBodies_MassNnz

    !> Stored entries of a sparse K_t or C_t (full 6x6 blocks of the bodies
    !! and of the pairs joined by a force element).
    integer(c_int64_t) function LGNBodies_TangentNnz(B) bind(c, name="LGNBodies_TangentNnz")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: B
    end function LGNBodies_TangentNnz

    !> M (dense: added; sparse: overwritten with its pattern).
    integer(c_int) function LGNBodies_Mass(B, q, M) bind(c, name="LGNBodies_Mass")
      import :: c_int, c_ptr
      type(c_ptr), value :: B, q, M
    end function LGNBodies_Mass

    !> g(q, v): gyroscopic terms, gravity and force elements, minus the
    !! applied forces (overwritten).
    integer(c_int) function LGNBodies_Force(B, q, v, g) bind(c, name="LGNBodies_Force")
      import :: c_int, c_ptr
      type(c_ptr), value :: B, q, v, g
    end function LGNBodies_Force

    !> K = d/dq (M vdot + g) along the group (dense: added; sparse:
    !! overwritten).
    integer(c_int) function LGNBodies_Stiffness(B, q, v, K) bind(c, name="LGNBodies_Stiffness")
      import :: c_int, c_ptr
      type(c_ptr), value :: B, q, v, K
    end function LGNBodies_Stiffness

    !> C = dg/dv (dense: added; sparse: overwritten).
    integer(c_int) function LGNBodies_Damping(B, q, v, C) bind(c, name="LGNBodies_Damping")
      import :: c_int, c_ptr
      type(c_ptr), value :: B, q, v, C
    end function LGNBodies_Damping

    !> Kinetic and potential energy (either argument may be c_null_ptr in
    !! C; here both are required).
    integer(c_int) function LGNBodies_Energy(B, q, v, kinetic, potential) &
        bind(c, name="LGNBodies_Energy")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: B, q, v
      real(c_double), intent(out) :: kinetic, potential
    end function LGNBodies_Energy

    !> An LGNMassFn with the body set as user_data (pass c_funloc of it).
    integer(c_int) function LGNBodies_MassFn(t, q, M, user_data) &
        bind(c, name="LGNBodies_MassFn")
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, M, user_data
    end function LGNBodies_MassFn

    !> An LGNForceFn with the body set as user_data.
    integer(c_int) function LGNBodies_ForceFn(t, q, v, g, user_data) &
        bind(c, name="LGNBodies_ForceFn")
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, g, user_data
    end function LGNBodies_ForceFn

    !> An LGNStiffnessFn with the body set as user_data (no constraints).
    integer(c_int) function LGNBodies_StiffnessFn(t, q, v, vdot, lambda, K, user_data) &
        bind(c, name="LGNBodies_StiffnessFn")
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, vdot, lambda, K, user_data
    end function LGNBodies_StiffnessFn

    !> An LGNDampingFn with the body set as user_data.
    integer(c_int) function LGNBodies_DampingFn(t, q, v, C, user_data) &
        bind(c, name="LGNBodies_DampingFn")
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, C, user_data
    end function LGNBodies_DampingFn
  end interface

end module flignum_bodies_mod
