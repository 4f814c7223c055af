! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_joints_mod: hand-written ISO_C_BINDING interface to the joint
! helpers of include/lignum/lignum_joints.h (spherical, revolute, universal,
! prismatic and cylindrical joints, rotation and translation drivers, between rigid bodies on R^3 x SO(3) or SE(3) leaves of the
! configuration group: Phi, B, the constraint forces B^T lambda, the
! curvature Z(q)(v, v) and the geometric stiffness d/dq (B^T lambda), ready
! to call from the constraint callbacks).
!
! Names are the C names, types as in flignum_mod:
!   LGNJoints, LGNGroup, N_Vector, SUNMatrix, FILE *
!                          -> type(c_ptr), value
!   LGNErrHandlerFn        -> type(c_funptr), value
!   LGNJoints *J (LGNJoints_Destroy)
!                          -> type(c_ptr), by reference (set to c_null_ptr)
!   int (body indices, flags) -> integer(c_int)
!   sunindextype           -> integer(c_int64_t)
!   const sunrealtype[3]   -> real(c_double) :: x(3)
!
! Body indices are the C ones: 0-based (body k is leaf k of the group, in
! the order of the product's factors, products of products flattened), or
! LGN_GROUND for the fixed inertial frame. Rows of Phi and B and columns of
! B are 0-based in C; through FN_VGetArray, FSUNDenseMatrix_Array and the
! sparse helpers of flignum_klu_mod they are 1-based Fortran arrays.
! ---------------------------------------------------------------------------
module flignum_joints_mod
  use, intrinsic :: iso_c_binding
  implicit none

  !> Body index of the fixed inertial frame.
  integer(c_int), parameter :: LGN_GROUND = -1

  abstract interface
    !> Time law of a driver: f(1) = f(t), f(2) = f'(t), f(3) = f''(t);
    !! return 0 on success.
    integer(c_int) function LGNDriveFn(t, f, drive_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      real(c_double), intent(out) :: f(3)
      type(c_ptr), value :: drive_data
    end function LGNDriveFn
  end interface

  interface
    ! =========================================================================
    ! Construction
    ! =========================================================================

    !> Create an empty joint set for the bodies of G (R^3 x SO(3), SE(3) or
    !! a product of them; G is referenced and must outlive the set). The set
    !! reports bad input of every LGNJoints function through its own error
    !! handler (LGNJoints_SetErrHandlerFn, LGNJoints_SetErrFile; default:
    !! stderr) and holds no integrator memory. Returns c_null_ptr (message
    !! on stderr) if G is c_null_ptr, has another leaf group or memory ran
    !! out.
    type(c_ptr) function LGNJoints_Create(G) bind(c, name="LGNJoints_Create")
      import :: c_ptr
      type(c_ptr), value :: G
    end function LGNJoints_Create

    !> Error handler of the joint set (an LGNErrHandlerFn of flignum_mod:
    !! c_funloc of a bind(c) subroutine); c_null_funptr restores the
    !! default. LGN_ILL_INPUT for J = c_null_ptr.
    integer(c_int) function LGNJoints_SetErrHandlerFn(J, ehfun, eh_data) &
        bind(c, name="LGNJoints_SetErrHandlerFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: J
      type(c_funptr), value :: ehfun
      type(c_ptr), value :: eh_data
    end function LGNJoints_SetErrHandlerFn

    !> Stream of the joint set's default error handler (a C FILE *:
    !! FLGNStderr(), FLGNFopen(...) of flignum_mod); c_null_ptr silences it.
    !! LGN_ILL_INPUT for J = c_null_ptr.
    integer(c_int) function LGNJoints_SetErrFile(J, errfp) &
        bind(c, name="LGNJoints_SetErrFile")
      import :: c_int, c_ptr
      type(c_ptr), value :: J, errfp
    end function LGNJoints_SetErrFile

    !> Free a joint set and set J = c_null_ptr; c_null_ptr is allowed.
    subroutine LGNJoints_Destroy(J) bind(c, name="LGNJoints_Destroy")
      import :: c_ptr
      type(c_ptr), intent(inout) :: J
    end subroutine LGNJoints_Destroy

    !> Number of bodies (leaves of G); 0 for c_null_ptr.
    integer(c_int) function LGNJoints_NumBodies(J) bind(c, name="LGNJoints_NumBodies")
      import :: c_int, c_ptr
      type(c_ptr), value :: J
    end function LGNJoints_NumBodies

    !> Spherical joint (3 rows): point sa of body a coincides with point sb
    !! of body b; a, b 0-based or LGN_GROUND, a /= b; points in the body
    !! frames (inertial for LGN_GROUND). LGN_SUCCESS, LGN_ILL_INPUT (bad body
    !! index) or LGN_MEM_FAIL.
    integer(c_int) function LGNJoints_AddSpherical(J, a, sa, b, sb) &
        bind(c, name="LGNJoints_AddSpherical")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), sb(3)
    end function LGNJoints_AddSpherical

    !> Revolute joint (5 rows): spherical at (sa, sb) and the body axes
    !! axis_a, axis_b (nonzero, need not be unit) kept parallel.
    integer(c_int) function LGNJoints_AddRevolute(J, a, sa, axis_a, b, sb, axis_b) &
        bind(c, name="LGNJoints_AddRevolute")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), sb(3), axis_b(3)
    end function LGNJoints_AddRevolute

    !> Universal (Cardan) joint (4 rows): spherical at (sa, sb) and the body
    !! axes axis_a, axis_b kept perpendicular (they must be perpendicular
    !! initially for the joint to be satisfied).
    integer(c_int) function LGNJoints_AddUniversal(J, a, sa, axis_a, b, sb, axis_b) &
        bind(c, name="LGNJoints_AddUniversal")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), sb(3), axis_b(3)
    end function LGNJoints_AddUniversal

    !> Prismatic joint (5 rows): sb of body b on the line through sa of
    !! body a along axis_a, the relative rotation locked at R_a^T R_b = R0,
    !! the smallest rotation taking axis_b to axis_a.
    integer(c_int) function LGNJoints_AddPrismatic(J, a, sa, axis_a, b, sb, axis_b) &
        bind(c, name="LGNJoints_AddPrismatic")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), sb(3), axis_b(3)
    end function LGNJoints_AddPrismatic

    !> Cylindrical joint (4 rows): axis_a, axis_b kept parallel and sb on
    !! the line through sa along axis_a.
    integer(c_int) function LGNJoints_AddCylindrical(J, a, sa, axis_a, b, sb, axis_b) &
        bind(c, name="LGNJoints_AddCylindrical")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), sb(3), axis_b(3)
    end function LGNJoints_AddCylindrical

    !> Prismatic joint (5 rows) locked where the frames [axis_a, ref_a,
    !! axis_a x ref_a] of a and [axis_b, ref_b, axis_b x ref_b] of b align.
    integer(c_int) function LGNJoints_AddPrismaticFrames(J, a, sa, axis_a, ref_a, b, sb, &
        axis_b, ref_b) bind(c, name="LGNJoints_AddPrismaticFrames")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), ref_a(3), sb(3), axis_b(3), ref_b(3)
    end function LGNJoints_AddPrismaticFrames

    !> Rotation driver (1 row): the angle of ref_b (body b) about axis_a,
    !! from ref_a (body a), is f(t) (time law f: LGNDriveFn, c_funloc).
    integer(c_int) function LGNJoints_AddRotationDriver(J, a, axis_a, ref_a, b, ref_b, f, &
        drive_data) bind(c, name="LGNJoints_AddRotationDriver")
      import :: c_int, c_double, c_ptr, c_funptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: axis_a(3), ref_a(3), ref_b(3)
      type(c_funptr), value :: f
      type(c_ptr), value :: drive_data
    end function LGNJoints_AddRotationDriver

    !> Translation driver (1 row): (R_a axis_a).(p_b - p_a) = f(t).
    integer(c_int) function LGNJoints_AddTranslationDriver(J, a, sa, axis_a, b, sb, f, &
        drive_data) bind(c, name="LGNJoints_AddTranslationDriver")
      import :: c_int, c_double, c_ptr, c_funptr
      type(c_ptr), value :: J
      integer(c_int), value :: a, b
      real(c_double), intent(in) :: sa(3), axis_a(3), sb(3)
      type(c_funptr), value :: f
      type(c_ptr), value :: drive_data
    end function LGNJoints_AddTranslationDriver

    !> Number of drivers in the set.
    integer(c_int) function LGNJoints_NumDrivers(J) bind(c, name="LGNJoints_NumDrivers")
      import :: c_int, c_ptr
      type(c_ptr), value :: J
    end function LGNJoints_NumDrivers

    ! =========================================================================
    ! Sizes
    ! =========================================================================

    !> Describe constraint row (0-based): its joint, kind and bodies, into
    !! the C string buf of length len (character(kind=c_char) array).
    integer(c_int) function LGNJoints_DescribeConstraint(J, row, buf, len) &
        bind(c, name="LGNJoints_DescribeConstraint")
      import :: c_int, c_int64_t, c_ptr, c_char, c_size_t
      type(c_ptr), value :: J
      integer(c_int64_t), value :: row
      character(kind=c_char), dimension(*), intent(out) :: buf
      integer(c_size_t), value :: len
    end function LGNJoints_DescribeConstraint

    !> Number of constraints m of all joints added so far (rows of Phi, B).
    integer(c_int64_t) function LGNJoints_NumConstraints(J) &
        bind(c, name="LGNJoints_NumConstraints")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: J
    end function LGNJoints_NumConstraints

    !> Stored entries of a sparse B written by LGNJoints_Jacobian (explicit
    !! zeros included; the pattern does not depend on q).
    integer(c_int64_t) function LGNJoints_JacobianNnz(J) &
        bind(c, name="LGNJoints_JacobianNnz")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: J
    end function LGNJoints_JacobianNnz

    !> Stored entries of a sparse K written by LGNJoints_Stiffness.
    integer(c_int64_t) function LGNJoints_StiffnessNnz(J) &
        bind(c, name="LGNJoints_StiffnessNnz")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: J
    end function LGNJoints_StiffnessNnz

    ! =========================================================================
    ! Evaluation, for the callbacks (vectors: serial N_Vectors)
    ! =========================================================================

    !> phi = Phi(q, t), length m (for an LGNConstrFn; t is read by drivers only).
    integer(c_int) function LGNJoints_Residual(J, t, q, phi) bind(c, name="LGNJoints_Residual")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, phi
    end function LGNJoints_Residual

    !> B = B(q), m x nv (for an LGNConstrJacFn). A dense B is written entry
    !! by entry (zero it first; Lignum does before the callback); a sparse B
    !! (CSC or CSR) gets the whole structure, reallocated if it has fewer
    !! than LGNJoints_JacobianNnz(J) entries.
    integer(c_int) function LGNJoints_Jacobian(J, t, q, B) bind(c, name="LGNJoints_Jacobian")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, B
    end function LGNJoints_Jacobian

    !> f = B(q)^T lambda, length nv: the joints' constraint forces, without
    !! forming B (for an LGNConstrForceFn). f is overwritten entirely: the
    !! entries of bodies in no joint become 0. Equals B(q)^T lambda of
    !! LGNJoints_Jacobian to round-off; with no joints (m = 0), f = 0.
    integer(c_int) function LGNJoints_ConstraintForce(J, t, q, lambda, f) &
        bind(c, name="LGNJoints_ConstraintForce")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, lambda, f
    end function LGNJoints_ConstraintForce

    !> z = d/dt(B v + Phi_t) - B vdot, length m (Z(q)(v, v) without drivers):
    !! the curvature term of the consistent initial accelerations (for an
    !! LGNCurvatureFn).
    integer(c_int) function LGNJoints_Curvature(J, t, q, v, z) &
        bind(c, name="LGNJoints_Curvature")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, v, z
    end function LGNJoints_Curvature

    !> A point s of body b against the plane n . p = d: gap = n . (x_b + R_b s) - d
    !! and row (length nv) its derivative along the group (LGNApplyImpact's G).
    integer(c_int) function LGNJoints_PointPlaneContact(J, q, b, s, n, d, gap, row) &
        bind(c, name="LGNJoints_PointPlaneContact")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J, q
      integer(c_int), value :: b
      real(c_double), intent(in) :: s(3), n(3)
      real(c_double), value :: d
      real(c_double), intent(out) :: gap
      real(c_double), intent(out) :: row(*)
    end function LGNJoints_PointPlaneContact

    !> phit = dPhi/dt(q, t), length m: the drivers' rows (for an LGNConstrTimeFn).
    integer(c_int) function LGNJoints_TimeDerivative(J, t, q, phit) &
        bind(c, name="LGNJoints_TimeDerivative")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, phit
    end function LGNJoints_TimeDerivative

    !> K = d/dq (B(q)^T lambda), nv x nv: the joints' part of K_t (for an
    !! LGNStiffnessFn). Added to a dense K; a sparse K is overwritten with
    !! its pattern (blocks of the bodies and of the pairs coupled by a
    !! revolute, universal, prismatic or cylindrical joint).
    integer(c_int) function LGNJoints_Stiffness(J, t, q, lambda, K) &
        bind(c, name="LGNJoints_Stiffness")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: J
      real(c_double), value :: t
      type(c_ptr), value :: q, lambda, K
    end function LGNJoints_Stiffness
  end interface

end module flignum_joints_mod
