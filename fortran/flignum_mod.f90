! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_mod: hand-written ISO_C_BINDING interface to the whole public C API
! of Lignum (include/lignum/lignum.h and include/lignum/lignum_group.h).
! The joint helpers (lignum_joints.h) are in flignum_joints_mod, the SUNDIALS
! calls a Fortran program needs in flignum_sundials_mod.
!
! Names are the C names. Types (style.md §4):
!   void *, N_Vector, SUNMatrix, SUNLinearSolver, SUNContext, LGNGroup, FILE *
!                          -> type(c_ptr), value
!   void **lgn_mem (LGNFree), out-arguments
!                          -> passed by reference (type(c_ptr), real(c_double),
!                             integer(c_long))
!   sunrealtype            -> real(c_double)
!   sunindextype           -> integer(c_int64_t)
!   int, long int          -> integer(c_int), integer(c_long)
!   const sunrealtype *    -> real(c_double) array, by reference
!   callbacks              -> type(c_funptr), value, made with c_funloc(f) of a
!                             bind(C) procedure f matching an abstract
!                             interface below (LGNMassFn, ...)
!   user_data              -> type(c_ptr): c_loc(obj) in, c_f_pointer out
!
! Helpers that exist only in Fortran carry the prefix FLGN:
! FLGNGetReturnFlagName, FLGNString, FLGNStdout/FLGNStderr, FLGNFopen,
! FLGNFclose, FLGNFflush, FLGNPrintAllStats, FLGNGroup_Rec, FLGNGroup_NQ,
! FLGNGroup_NV.
! ---------------------------------------------------------------------------
module flignum_mod
  use, intrinsic :: iso_c_binding
  implicit none

  ! Lignum version (generated from the CMake project version).
  include "flignum_config.inc"

  ! ===========================================================================
  ! Return flags: one flat, non-overlapping space (names: LGNGetReturnFlagName)
  ! ===========================================================================
  integer(c_int), parameter :: LGN_SUCCESS = 0
  integer(c_int), parameter :: LGN_TSTOP_RETURN = 1

  ! solver failures -1 .. -19
  integer(c_int), parameter :: LGN_TOO_MUCH_WORK = -1
  integer(c_int), parameter :: LGN_CONV_FAILURE = -2
  integer(c_int), parameter :: LGN_MASS_FAIL = -3
  integer(c_int), parameter :: LGN_FORCE_FAIL = -4
  integer(c_int), parameter :: LGN_CONSTR_FAIL = -5
  integer(c_int), parameter :: LGN_CONSTR_JAC_FAIL = -6
  integer(c_int), parameter :: LGN_TANGENT_FAIL = -7
  integer(c_int), parameter :: LGN_GROUP_FAIL = -8
  integer(c_int), parameter :: LGN_NONFINITE = -9
  integer(c_int), parameter :: LGN_REPTD_CALLBACK_ERR = -10
  integer(c_int), parameter :: LGN_IC_FAIL = -11
  integer(c_int), parameter :: LGN_ERR_FAILURE = -12
  integer(c_int), parameter :: LGN_STEP_TOO_SMALL = -15
  integer(c_int), parameter :: LGN_INCONSISTENT_IC = -14
  integer(c_int), parameter :: LGN_REDUNDANT_INCONSISTENT = -16

  ! usage errors -20 .. -29
  integer(c_int), parameter :: LGN_MEM_NULL = -20
  integer(c_int), parameter :: LGN_MEM_FAIL = -21
  integer(c_int), parameter :: LGN_ILL_INPUT = -22
  integer(c_int), parameter :: LGN_NO_MALLOC = -23
  integer(c_int), parameter :: LGN_NO_LINSOL = -24
  integer(c_int), parameter :: LGN_MISSING_FN = -25
  integer(c_int), parameter :: LGN_BAD_TOUT = -26
  integer(c_int), parameter :: LGN_BAD_T = -27
  integer(c_int), parameter :: LGN_BAD_K = -28

  ! linear solver interface -30 .. -39
  integer(c_int), parameter :: LGN_LINIT_FAIL = -30
  integer(c_int), parameter :: LGN_LSETUP_FAIL = -31
  integer(c_int), parameter :: LGN_LSOLVE_FAIL = -32
  integer(c_int), parameter :: LGN_LS_MISMATCH = -33

  ! files -50 .. -59 (restart files, VTK output)
  integer(c_int), parameter :: LGN_IO_FAIL = -50
  integer(c_int), parameter :: LGN_RESTART_BAD_FILE = -51
  integer(c_int), parameter :: LGN_RESTART_MISMATCH = -52

  integer(c_int), parameter :: LGN_UNRECOGNIZED_ERR = -99

  ! ===========================================================================
  ! Other constants
  ! ===========================================================================
  ! itask of LGNSolve
  integer(c_int), parameter :: LGN_NORMAL = 1
  integer(c_int), parameter :: LGN_ONE_STEP = 2
  ! step size control (LGNSetStepControl)
  integer(c_int), parameter :: LGN_STEP_FIXED = 150
  integer(c_int), parameter :: LGN_STEP_ADAPTIVE = 151
  ! constraint formulation
  integer(c_int), parameter :: LGN_CONSTR_INDEX3 = 133
  integer(c_int), parameter :: LGN_CONSTR_INDEX2 = 132
  integer(c_int), parameter :: LGN_CONSTR_GGL = 134
  ! redundant constraints (LGNSetRedundantConstraints)
  integer(c_int), parameter :: LGN_REDUNDANT_ELIMINATE = 170
  integer(c_int), parameter :: LGN_REDUNDANT_REFUSE = 171
  ! kinematics
  integer(c_int), parameter :: LGN_KINEMATICS_SIMPLIFIED = 100
  integer(c_int), parameter :: LGN_KINEMATICS_EXACT = 101
  integer(c_int), parameter :: LGN_KINEMATICS_SIGMA = 102
  ! Newton predictor
  integer(c_int), parameter :: LGN_PREDICTOR_ZERO = 120
  integer(c_int), parameter :: LGN_PREDICTOR_EXTRAPOLATE = 121
  ! BDF form (LGNSetBDFForm)
  integer(c_int), parameter :: LGN_BDF_VARIABLE_COEFF = 160
  integer(c_int), parameter :: LGN_BDF_FIXED_LEADING = 161
  ! the highest BDF order (LGNSetBDF, LGNGetNumStepsAtOrder)
  integer(c_int), parameter :: LGN_BDF_MAX_ORDER = 5

  ! Newton variants
  integer(c_int), parameter :: LGN_NEWTON_FULL     = 110
  integer(c_int), parameter :: LGN_NEWTON_MODIFIED = 111

  ! icopt of LGNCalcIC
  integer(c_int), parameter :: LGN_IC_PROJECT_Q  = 141
  integer(c_int), parameter :: LGN_IC_PROJECT_V  = 142
  integer(c_int), parameter :: LGN_IC_PROJECT_QV = 143
  ! LGNSetProjectOutputs
  integer(c_int), parameter :: LGN_PROJECT_NONE = 0
  integer(c_int), parameter :: LGN_PROJECT_INTERPOLATED = 1
  integer(c_int), parameter :: LGN_PROJECT_ALL = 2

  ! LGNGroupKind
  enum, bind(c)
    enumerator :: LGN_GROUP_CUSTOM = 0
    enumerator :: LGN_GROUP_RN, LGN_GROUP_SO3, LGN_GROUP_R3XSO3
    enumerator :: LGN_GROUP_SE3, LGN_GROUP_PRODUCT
  end enum

  ! ===========================================================================
  ! The group object (struct LGNGroupRec, lignum_group.h). A Fortran program
  ! reaches it with FLGNGroup_Rec(G) (or c_f_pointer), e.g. to read nq and nv
  ! or to fill the ops of a group made with LGNGroup_NewEmpty using c_funloc
  ! of procedures matching the LGNGroup* abstract interfaces below.
  ! ===========================================================================
  type, bind(c) :: LGNGroupOpsRec
    type(c_funptr) :: compose_exp           !< LGNGroupComposeExpFn
    type(c_funptr) :: tangent_apply         !< LGNGroupTangentApplyFn
    type(c_funptr) :: tangent_inverse_apply !< LGNGroupTangentApplyFn
    type(c_funptr) :: tangent_dot_apply     !< LGNGroupTangentDotApplyFn
    type(c_funptr) :: tangent_matrix        !< LGNGroupTangentMatrixFn
    type(c_funptr) :: identity              !< LGNGroupIdentityFn
    type(c_funptr) :: normalize             !< LGNGroupIdentityFn (may be null)
    type(c_funptr) :: free_content          !< LGNGroupFreeContentFn (may be null)
    type(c_funptr) :: compose_log           !< LGNGroupComposeLogFn (may be null)
  end type LGNGroupOpsRec

  type, bind(c) :: LGNGroupRec
    integer(c_int) :: kind          !< LGN_GROUP_* (enum LGNGroupKind)
    integer(c_int64_t) :: nq        !< reals storing one group element
    integer(c_int64_t) :: nv        !< dimension of the Lie algebra
    type(c_ptr) :: content          !< implementation data
    type(LGNGroupOpsRec) :: ops
  end type LGNGroupRec

  ! ===========================================================================
  ! Callback types: write the callback as a bind(C) procedure with exactly
  ! this signature, pass c_funloc(callback). Return 0 on success, > 0 for a
  ! recoverable failure, < 0 for an unrecoverable one. Matrices are zeroed
  ! before the call; N_Vector/SUNMatrix data via flignum_sundials_mod
  ! (FN_VGetArray, FSUNDenseMatrix_Array).
  ! ===========================================================================
  abstract interface
    !> Mass matrix M = M(q, t), nv x nv.
    integer(c_int) function LGNMassFn(t, q, M, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, M, user_data
    end function LGNMassFn

    !> Forces g = g(q, v, t), so that M vdot + g + B^T lambda = 0.
    integer(c_int) function LGNForceFn(t, q, v, g, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, g, user_data
    end function LGNForceFn

    !> Constraints phi = Phi(q, t), length m.
    integer(c_int) function LGNConstrFn(t, q, phi, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, phi, user_data
    end function LGNConstrFn

    !> Constraint Jacobian B(q) in Lie algebra directions, m x nv.
    integer(c_int) function LGNConstrJacFn(t, q, B, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, B, user_data
    end function LGNConstrJacFn

    !> Contact rows G(q), nc x nv, of the model matrices' type (LGNApplyImpact).
    integer(c_int) function LGNContactJacFn(t, q, G, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, G, user_data
    end function LGNContactJacFn

    !> Tangent stiffness K_t: D_q[M vdot + g + B^T lambda].(q w~) = K_t w.
    integer(c_int) function LGNStiffnessFn(t, q, v, vdot, lambda, K, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, vdot, lambda, K, user_data
    end function LGNStiffnessFn

    !> Tangent damping C_t = dg/dv, nv x nv.
    integer(c_int) function LGNDampingFn(t, q, v, C, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, C, user_data
    end function LGNDampingFn

    !> Constraint curvature z = Z(q)(v, v), d/dt(B v) = B vdot + Z(q)(v, v).
    integer(c_int) function LGNCurvatureFn(t, q, v, z, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, z, user_data
    end function LGNCurvatureFn

    !> Explicit time derivative of the constraints phit = dPhi/dt(q, t), length m.
    integer(c_int) function LGNConstrTimeFn(t, q, phit, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, phit, user_data
    end function LGNConstrTimeFn

    !> Constraint forces f = B(q)^T lambda (length nv), without forming B.
    integer(c_int) function LGNConstrForceFn(t, q, lambda, f, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, lambda, f, user_data
    end function LGNConstrForceFn

    !> Error handler; module, function and msg are NUL-terminated C strings
    !! (convert with FLGNString). Valid only during the call.
    subroutine LGNErrHandlerFn(error_code, module_name, function_name, msg, eh_data) &
        bind(c)
      import :: c_int, c_ptr
      integer(c_int), value :: error_code
      type(c_ptr), value :: module_name, function_name, msg, eh_data
    end subroutine LGNErrHandlerFn

    ! --- ops of a user-supplied group (struct LGNGroupOpsRec) -----------------

    !> q_out = q o exp(w). Lignum may pass q_out aliasing q: read all of q
    !! before writing q_out.
    integer(c_int) function LGNGroupComposeExpFn(G, q, w, q_out) bind(c)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double) :: q(*), w(*), q_out(*)
    end function LGNGroupComposeExpFn

    !> w = log(q1^{-1} q2), the inverse of compose_exp (q1 o exp(w) = q2).
    integer(c_int) function LGNGroupComposeLogFn(G, q1, q2, w) bind(c)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: q1(*), q2(*)
      real(c_double), intent(out) :: w(*)
    end function LGNGroupComposeLogFn

    !> y = T(w) x (tangent_apply) or y = T(w)^{-1} x (tangent_inverse_apply).
    integer(c_int) function LGNGroupTangentApplyFn(G, w, x, y) bind(c)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*), x(*)
      real(c_double), intent(out) :: y(*)
    end function LGNGroupTangentApplyFn

    !> y = Tdot(w, wdot) x.
    integer(c_int) function LGNGroupTangentDotApplyFn(G, w, wdot, x, y) bind(c)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*), wdot(*), x(*)
      real(c_double), intent(out) :: y(*)
    end function LGNGroupTangentDotApplyFn

    !> Tm = T(w), dense nv x nv, column-major with leading dimension ld.
    integer(c_int) function LGNGroupTangentMatrixFn(G, w, Tm, ld) bind(c)
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*)
      real(c_double), intent(inout) :: Tm(*)
      integer(c_int64_t), value :: ld
    end function LGNGroupTangentMatrixFn

    !> q = identity element (identity), or project q onto the group (normalize).
    integer(c_int) function LGNGroupIdentityFn(G, q) bind(c)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(inout) :: q(*)
    end function LGNGroupIdentityFn

    !> Free the content (not the LGNGroup itself).
    subroutine LGNGroupFreeContentFn(G) bind(c)
      import :: c_ptr
      type(c_ptr), value :: G
    end subroutine LGNGroupFreeContentFn

    !> Preconditioner setup (LGNSetPreconditioner): prepare P ~ the scaled
    !! iteration matrix [[cM M + cC C_t + cK K_t, B^T], [B, 0]] at (t, q, v).
    integer(c_int) function LGNPrecSetupFn(t, q, v, cM, cC, cK, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v
      real(c_double), value :: cM, cC, cK
      type(c_ptr), value :: user_data
    end function LGNPrecSetupFn

    !> Preconditioner solve: z ~ P^{-1} r (N_Vectors of length nv + m),
    !! delta: the Krylov solver's tolerance for this solve.
    integer(c_int) function LGNPrecSolveFn(t, q, v, r, z, cM, cC, cK, delta, &
        user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v, r, z
      real(c_double), value :: cM, cC, cK, delta
      type(c_ptr), value :: user_data
    end function LGNPrecSolveFn
  end interface

  ! ===========================================================================
  ! lignum.h: lifecycle
  ! ===========================================================================
  interface
    !> Create an integrator memory block (c_null_ptr on failure).
    type(c_ptr) function LGNCreate(sunctx) bind(c, name="LGNCreate")
      import :: c_ptr
      type(c_ptr), value :: sunctx
    end function LGNCreate

    !> Initial state; allocates the state vectors. Group must be set.
    integer(c_int) function LGNInit(lgn_mem, t0, q0, v0) bind(c, name="LGNInit")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem, q0, v0
      real(c_double), value :: t0
    end function LGNInit

    !> Restart from a new initial state, keeping all settings.
    integer(c_int) function LGNReInit(lgn_mem, t0, q0, v0) bind(c, name="LGNReInit")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem, q0, v0
      real(c_double), value :: t0
    end function LGNReInit

    !> Advance to tout (LGN_NORMAL) or by one step (LGN_ONE_STEP).
    integer(c_int) function LGNSolve(lgn_mem, tout, tret, q, v, itask) &
        bind(c, name="LGNSolve")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem, q, v
      real(c_double), value :: tout
      real(c_double), intent(out) :: tret
      integer(c_int), value :: itask
    end function LGNSolve

    !> Free the memory block; sets lgn_mem = c_null_ptr.
    subroutine LGNFree(lgn_mem) bind(c, name="LGNFree")
      import :: c_ptr
      type(c_ptr), intent(inout) :: lgn_mem
    end subroutine LGNFree

    ! =========================================================================
    ! lignum.h: model description
    ! =========================================================================

    !> Set the Lie group (referenced, must outlive the memory block).
    integer(c_int) function LGNSetGroup(lgn_mem, G) bind(c, name="LGNSetGroup")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, G
    end function LGNSetGroup

    !> Set the pointer passed to every callback (e.g. c_loc(model)).
    integer(c_int) function LGNSetUserData(lgn_mem, user_data) &
        bind(c, name="LGNSetUserData")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, user_data
    end function LGNSetUserData

    !> Mass matrix callback (LGNMassFn), required.
    integer(c_int) function LGNSetMassFn(lgn_mem, mass) bind(c, name="LGNSetMassFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: mass
    end function LGNSetMassFn

    !> Force callback (LGNForceFn), required.
    integer(c_int) function LGNSetForceFn(lgn_mem, force) bind(c, name="LGNSetForceFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: force
    end function LGNSetForceFn

    !> Number of constraints m and callbacks Phi (LGNConstrFn), B (LGNConstrJacFn).
    integer(c_int) function LGNSetConstraints(lgn_mem, m, phi, B) &
        bind(c, name="LGNSetConstraints")
      import :: c_int, c_int64_t, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), value :: m
      type(c_funptr), value :: phi, B
    end function LGNSetConstraints

    !> Tangent stiffness (LGNStiffnessFn); c_null_funptr: difference quotients.
    integer(c_int) function LGNSetStiffnessFn(lgn_mem, K) bind(c, name="LGNSetStiffnessFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: K
    end function LGNSetStiffnessFn

    !> Tangent damping (LGNDampingFn); c_null_funptr: difference quotients.
    integer(c_int) function LGNSetDampingFn(lgn_mem, C) bind(c, name="LGNSetDampingFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: C
    end function LGNSetDampingFn

    !> Constraint curvature (LGNCurvatureFn); c_null_funptr: difference quotients.
    integer(c_int) function LGNSetCurvatureFn(lgn_mem, Z) bind(c, name="LGNSetCurvatureFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: Z
    end function LGNSetCurvatureFn

    !> Rheonomic constraints: their time derivative Phi_t (LGNConstrTimeFn);
    !> c_null_funptr (default): Phi does not depend on t explicitly.
    integer(c_int) function LGNSetConstraintTimeFn(lgn_mem, phit) bind(c, name="LGNSetConstraintTimeFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: phit
    end function LGNSetConstraintTimeFn

    !> Constraint forces f = B(q)^T lambda (LGNConstrForceFn); c_null_funptr:
    !! from B.
    integer(c_int) function LGNSetConstraintForceFn(lgn_mem, F) &
        bind(c, name="LGNSetConstraintForceFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: F
    end function LGNSetConstraintForceFn

    !> Declare the mass matrix constant (independent of q and t): evaluated
    !! once per LGNInit / LGNReInit. constant: 0 or 1 (sunbooleantype).
    integer(c_int) function LGNSetMassConstant(lgn_mem, constant) &
        bind(c, name="LGNSetMassConstant")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: constant
    end function LGNSetMassConstant

    ! =========================================================================
    ! lignum.h: method and solver settings
    ! =========================================================================

    !> Linear solver and iteration matrix ((nv+m) x (nv+m)); not owned.
    integer(c_int) function LGNSetLinearSolver(lgn_mem, LS, A) &
        bind(c, name="LGNSetLinearSolver")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, LS, A
    end function LGNSetLinearSolver

    !> Lignum's dense LU linear solver for the dense N x N matrix A (y a
    !! template vector of length N), in SUNLinSol_Dense's place; free it
    !! with SUNLinSolFree. c_null_ptr (with a message naming the argument)
    !! for a NULL argument, a matrix that is not square dense, or a y of
    !! another length.
    type(c_ptr) function LGNLinSol_Dense(y, A, sunctx) bind(c, name="LGNLinSol_Dense")
      import :: c_ptr
      type(c_ptr), value :: y, A, sunctx
    end function LGNLinSol_Dense

    !> With SUNLinSol_KLU: solve with Lignum's own triangular solves on a
    !! copy of KLU's factors (own = 1) or with SUNLinSolSolve (own = 0,
    !! default). own: 0 or 1 (sunbooleantype). own = 1 gives LGN_ILL_INPUT
    !! (and the setting stays off) for versions of KLU and SUNDIALS other
    !! than KLU 1.3 with SUNDIALS 6.4, or without KLU.
    integer(c_int) function LGNSetOwnKLUSolves(lgn_mem, own) &
        bind(c, name="LGNSetOwnKLUSolves")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: own
    end function LGNSetOwnKLUSolves

    !> Whole copies of KLU's factors (LGNSetOwnKLUSolves).
    integer(c_int) function LGNGetNumKLUFactorCopies(lgn_mem, ncopies) &
        bind(c, name="LGNGetNumKLUFactorCopies")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: ncopies
    end function LGNGetNumKLUFactorCopies

    !> Copies of the values only of KLU's factors (after klu_l_refactor).
    integer(c_int) function LGNGetNumKLUValueCopies(lgn_mem, nvalues) &
        bind(c, name="LGNGetNumKLUValueCopies")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nvalues
    end function LGNGetNumKLUValueCopies

    !> Lignum's refactorisations into the copy in place of KLU's (CSC).
    integer(c_int) function LGNGetNumOwnKLURefactors(lgn_mem, nrefactors) &
        bind(c, name="LGNGetNumOwnKLURefactors")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nrefactors
    end function LGNGetNumOwnKLURefactors

    !> Linear solves with the copy instead of SUNLinSolSolve.
    integer(c_int) function LGNGetNumOwnKLUSolves(lgn_mem, nsolves) &
        bind(c, name="LGNGetNumOwnKLUSolves")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nsolves
    end function LGNGetNumOwnKLUSolves

    !> KLU factored in the copy's place, by cause: a pivot below the rcond
    !! threshold, a new pattern of A, no copy possible.
    integer(c_int) function LGNGetNumKLUFallbacks(lgn_mem, npivot, npattern, nnocopy) &
        bind(c, name="LGNGetNumKLUFallbacks")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: npivot, npattern, nnocopy
    end function LGNGetNumKLUFallbacks

    !> Fixed step size h > 0 (required).
    integer(c_int) function LGNSetStepSize(lgn_mem, h) bind(c, name="LGNSetStepSize")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: h
    end function LGNSetStepSize

    !> Newmark method with beta, gamma.
    integer(c_int) function LGNSetNewmark(lgn_mem, beta, gamma) &
        bind(c, name="LGNSetNewmark")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: beta, gamma
    end function LGNSetNewmark

    !> Generalized-alpha (Chung-Hulbert) from rho_inf in [0, 1].
    integer(c_int) function LGNSetGenAlpha(lgn_mem, rho_inf) bind(c, name="LGNSetGenAlpha")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: rho_inf
    end function LGNSetGenAlpha

    !> Generalized-alpha with all four parameters.
    integer(c_int) function LGNSetGenAlphaParams(lgn_mem, alpha_m, alpha_f, beta, gamma) &
        bind(c, name="LGNSetGenAlphaParams")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: alpha_m, alpha_f, beta, gamma
    end function LGNSetGenAlphaParams

    !> LGN_CONSTR_INDEX3 (default), LGN_CONSTR_INDEX2 or LGN_CONSTR_GGL
    !> (stabilised index 2: BDF, or Newmark / generalized-alpha with
    !> simplified or exact kinematics; dense A of nv + 2m rows).
    integer(c_int) function LGNSetConstraintIndex(lgn_mem, index) &
        bind(c, name="LGNSetConstraintIndex")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: index
    end function LGNSetConstraintIndex

    !> LGN_REDUNDANT_ELIMINATE (default: dependent constraint rows are left
    !> out, with a warning, and checked after every step) or
    !> LGN_REDUNDANT_REFUSE (a singular matrix naming them).
    integer(c_int) function LGNSetRedundantConstraints(lgn_mem, mode) &
        bind(c, name="LGNSetRedundantConstraints")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: mode
    end function LGNSetRedundantConstraints

    !> LGN_KINEMATICS_SIMPLIFIED (default), _EXACT or _SIGMA.
    integer(c_int) function LGNSetKinematics(lgn_mem, kinematics) &
        bind(c, name="LGNSetKinematics")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: kinematics
    end function LGNSetKinematics

    !> LGN_PREDICTOR_ZERO (default) or LGN_PREDICTOR_EXTRAPOLATE.
    integer(c_int) function LGNSetPredictor(lgn_mem, predictor) &
        bind(c, name="LGNSetPredictor")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: predictor
    end function LGNSetPredictor

    !> Newton stop test tolerances (0 restores the defaults 1e-8).
    integer(c_int) function LGNSStolerances(lgn_mem, rtol, atol) &
        bind(c, name="LGNSStolerances")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: rtol, atol
    end function LGNSStolerances

    ! =========================================================================
    ! lignum.h: error control (adaptive steps, stop time, output between steps)
    ! =========================================================================

    !> LGN_STEP_FIXED (default) or LGN_STEP_ADAPTIVE (the local error of
    !> every step kept within the tolerances of LGNSStolerances /
    !> LGNSVtolerances; LGN_NORMAL then interpolates at tout).
    integer(c_int) function LGNSetStepControl(lgn_mem, control) &
        bind(c, name="LGNSetStepControl")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: control
    end function LGNSetStepControl

    !> Tolerances with a vector of absolute tolerances (N_Vector, length nv,
    !> each > 0); copied.
    integer(c_int) function LGNSVtolerances(lgn_mem, rtol, atol) &
        bind(c, name="LGNSVtolerances")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: rtol
      type(c_ptr), value :: atol
    end function LGNSVtolerances

    !> First step size of error control (0: estimated, the default).
    integer(c_int) function LGNSetInitStep(lgn_mem, h0) bind(c, name="LGNSetInitStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: h0
    end function LGNSetInitStep

    !> Smallest step size of error control (default 0).
    integer(c_int) function LGNSetMinStep(lgn_mem, hmin) bind(c, name="LGNSetMinStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: hmin
    end function LGNSetMinStep

    !> Largest step size of error control (0: no limit, the default).
    integer(c_int) function LGNSetMaxStep(lgn_mem, hmax) bind(c, name="LGNSetMaxStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: hmax
    end function LGNSetMaxStep

    !> Error-test failures allowed in one step (0: the default 10).
    integer(c_int) function LGNSetMaxErrTestFails(lgn_mem, maxnef) &
        bind(c, name="LGNSetMaxErrTestFails")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: maxnef
    end function LGNSetMaxErrTestFails

    !> Newton (and recoverable callback) failures allowed in one step
    !> (0: the default 10).
    integer(c_int) function LGNSetMaxConvFails(lgn_mem, maxncf) &
        bind(c, name="LGNSetMaxConvFails")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: maxncf
    end function LGNSetMaxConvFails

    !> Ratio of Newton's tolerances to the error test's (0: the default 0.33).
    integer(c_int) function LGNSetNonlinConvCoef(lgn_mem, epcon) &
        bind(c, name="LGNSetNonlinConvCoef")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: epcon
    end function LGNSetNonlinConvCoef

    !> Write the state to a restart file (filename NUL-terminated: use
    !! FLGNWriteRestart with a Fortran string).
    integer(c_int) function LGNWriteRestart(lgn_mem, filename) bind(c, name="LGNWriteRestart")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: lgn_mem
      character(kind=c_char), intent(in) :: filename(*)
    end function LGNWriteRestart

    !> Read a restart file into an integrator of the same problem and
    !! settings (filename NUL-terminated: use FLGNReadRestart).
    integer(c_int) function LGNReadRestart(lgn_mem, filename) bind(c, name="LGNReadRestart")
      import :: c_int, c_ptr, c_char
      type(c_ptr), value :: lgn_mem
      character(kind=c_char), intent(in) :: filename(*)
    end function LGNReadRestart

    !> A time not to step past: LGNSolve lands on it, returns LGN_TSTOP_RETURN.
    integer(c_int) function LGNSetStopTime(lgn_mem, tstop) bind(c, name="LGNSetStopTime")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: tstop
    end function LGNSetStopTime

    !> Forget the stop time.
    integer(c_int) function LGNClearStopTime(lgn_mem) bind(c, name="LGNClearStopTime")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
    end function LGNClearStopTime

    !> q (k = 0, length nq), v (k = 1) or vdot (k = 2, length nv) at t in
    !> the last step, from the dense output (dky: an N_Vector), projected
    !> and consistent as LGNSolve's outputs are.
    integer(c_int) function LGNGetDky(lgn_mem, t, k, dky) bind(c, name="LGNGetDky")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: t
      integer(c_int), value :: k
      type(c_ptr), value :: dky
    end function LGNGetDky

    !> Consistent outputs on (SUNTRUE = 1, the default: vdot and lambda of
    !> the index-1 system at every output) or off (0: the step's own).
    integer(c_int) function LGNSetConsistentOutputs(lgn_mem, on) &
        bind(c, name="LGNSetConsistentOutputs")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: on
    end function LGNSetConsistentOutputs

    !> Which outputs are projected onto Phi = 0 and B v + Phi_t = 0:
    !> LGN_PROJECT_NONE, LGN_PROJECT_INTERPOLATED, LGN_PROJECT_ALL (default).
    integer(c_int) function LGNSetProjectOutputs(lgn_mem, which) &
        bind(c, name="LGNSetProjectOutputs")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: which
    end function LGNSetProjectOutputs

    !> The multipliers in the error test on (1, with their absolute
    !> tolerance atol_lambda > 0) or off (0, the default).
    integer(c_int) function LGNSetMultiplierErrorControl(lgn_mem, on, atol_lambda) &
        bind(c, name="LGNSetMultiplierErrorControl")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: on
      real(c_double), value :: atol_lambda
    end function LGNSetMultiplierErrorControl

    !> The number of outputs made consistent or projected.
    integer(c_int) function LGNGetNumOutputSolves(lgn_mem, nout) &
        bind(c, name="LGNGetNumOutputSolves")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nout
    end function LGNGetNumOutputSolves

    !> The step size to be tried next (error control) or the fixed h.
    integer(c_int) function LGNGetCurrentStep(lgn_mem, hcur) &
        bind(c, name="LGNGetCurrentStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: hcur
    end function LGNGetCurrentStep

    !> The first step size tried (error control) or the fixed h.
    integer(c_int) function LGNGetActualInitStep(lgn_mem, hinused) &
        bind(c, name="LGNGetActualInitStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: hinused
    end function LGNGetActualInitStep

    !> Steps rejected by the error test.
    integer(c_int) function LGNGetNumErrTestFails(lgn_mem, netfails) &
        bind(c, name="LGNGetNumErrTestFails")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: netfails
    end function LGNGetNumErrTestFails

    !> Aggregate statistics (as IDAGetIntegratorStats).
    integer(c_int) function LGNGetIntegratorStats(lgn_mem, nsteps, nrevals, nlinsetups, &
        netfails, hinused, hlast, hcur, tcur) bind(c, name="LGNGetIntegratorStats")
      import :: c_int, c_long, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nsteps, nrevals, nlinsetups, netfails
      real(c_double), intent(out) :: hinused, hlast, hcur, tcur
    end function LGNGetIntegratorStats

    !> Newton iterations and convergence failures.
    integer(c_int) function LGNGetNewtonStats(lgn_mem, nniters, nncfails) &
        bind(c, name="LGNGetNewtonStats")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nniters, nncfails
    end function LGNGetNewtonStats

    !> The fixed step size of LGNSetStepSize.
    integer(c_int) function LGNGetStepSize(lgn_mem, h) bind(c, name="LGNGetStepSize")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: h
    end function LGNGetStepSize

    !> The kinematics variant in use.
    integer(c_int) function LGNGetKinematics(lgn_mem, kinematics) &
        bind(c, name="LGNGetKinematics")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: kinematics
    end function LGNGetKinematics

    !> The constraint formulation in use.
    integer(c_int) function LGNGetConstraintIndex(lgn_mem, index) &
        bind(c, name="LGNGetConstraintIndex")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: index
    end function LGNGetConstraintIndex

    !> The Newton mode in use.
    integer(c_int) function LGNGetNewtonMode(lgn_mem, mode) bind(c, name="LGNGetNewtonMode")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: mode
    end function LGNGetNewtonMode

    !> The step size control in use.
    integer(c_int) function LGNGetStepControl(lgn_mem, control) &
        bind(c, name="LGNGetStepControl")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: control
    end function LGNGetStepControl

    !> The tolerances in use.
    integer(c_int) function LGNGetTolerances(lgn_mem, rtol, atol) &
        bind(c, name="LGNGetTolerances")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: rtol, atol
    end function LGNGetTolerances

    !> Whether Newton may stop with stalled multipliers (default .true.).
    integer(c_int) function LGNSetAcceptStalls(lgn_mem, accept) &
        bind(c, name="LGNSetAcceptStalls")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: accept
    end function LGNSetAcceptStalls

    !> After a singular matrix: the number of redundant constraints and, if
    !! rows is not c_null_ptr, their 0-based indices (an int64 array of
    !! length m, ascending).
    integer(c_int) function LGNGetRedundantConstraints(lgn_mem, nred, rows) &
        bind(c, name="LGNGetRedundantConstraints")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), intent(out) :: nred
      type(c_ptr), value :: rows
    end function LGNGetRedundantConstraints

    !> After a singular matrix: the unknown with a zero pivot (0-based; nv
    !! and above: a constraint's multiplier), or -1.
    integer(c_int) function LGNGetZeroPivot(lgn_mem, unknown) &
        bind(c, name="LGNGetZeroPivot")
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), intent(out) :: unknown
    end function LGNGetZeroPivot

    !> The local error estimate of the last step attempted (N_Vector, nv).
    integer(c_int) function LGNGetEstLocalErrors(lgn_mem, ele) &
        bind(c, name="LGNGetEstLocalErrors")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, ele
    end function LGNGetEstLocalErrors

    !> The error weights 1/(atol_i + rtol |s_i|) of the last step attempted.
    integer(c_int) function LGNGetErrWeights(lgn_mem, eweight) &
        bind(c, name="LGNGetErrWeights")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, eweight
    end function LGNGetErrWeights

    !> The error test's norm of the last step attempted (<= 1: accepted).
    integer(c_int) function LGNGetLastErrNorm(lgn_mem, errnorm) &
        bind(c, name="LGNGetLastErrNorm")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: errnorm
    end function LGNGetLastErrNorm

    !> Maximum Newton iterations per step (0: default 20).
    integer(c_int) function LGNSetMaxNewtonIters(lgn_mem, maxiters) &
        bind(c, name="LGNSetMaxNewtonIters")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: maxiters
    end function LGNSetMaxNewtonIters

    !> LGN_NEWTON_FULL (default) or LGN_NEWTON_MODIFIED (reuse the factorised
    !> iteration matrix while the iteration contracts fast).
    integer(c_int) function LGNSetNewtonMode(lgn_mem, mode) &
        bind(c, name="LGNSetNewtonMode")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: mode
    end function LGNSetNewtonMode

    !> Modified Newton: max steps between matrix setups (0: default 10, < 0: no limit).
    integer(c_int) function LGNSetLSetupFrequency(lgn_mem, msbp) &
        bind(c, name="LGNSetLSetupFrequency")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), value :: msbp
    end function LGNSetLSetupFrequency

    !> Maximum steps per LGNSolve call (0: default, < 0: no limit).
    integer(c_int) function LGNSetMaxNumSteps(lgn_mem, mxsteps) &
        bind(c, name="LGNSetMaxNumSteps")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), value :: mxsteps
    end function LGNSetMaxNumSteps

    !> Consistent vdot0 and lambda0 (c_null_ptr when m = 0); after LGNInit.
    integer(c_int) function LGNSetInitialAcceleration(lgn_mem, vdot0, lambda0) &
        bind(c, name="LGNSetInitialAcceleration")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, vdot0, lambda0
    end function LGNSetInitialAcceleration

    !> Initial algorithmic acceleration a_0; after LGNInit.
    integer(c_int) function LGNSetInitialAux(lgn_mem, a0) bind(c, name="LGNSetInitialAux")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, a0
    end function LGNSetInitialAux

    !> Error handler (LGNErrHandlerFn); c_null_funptr restores the default.
    integer(c_int) function LGNSetErrHandlerFn(lgn_mem, ehfun, eh_data) &
        bind(c, name="LGNSetErrHandlerFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: ehfun
      type(c_ptr), value :: eh_data
    end function LGNSetErrHandlerFn

    !> Stream of the default error handler (a C FILE *: FLGNStderr(),
    !! FLGNFopen(...)); c_null_ptr silences it.
    integer(c_int) function LGNSetErrFile(lgn_mem, errfp) bind(c, name="LGNSetErrFile")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, errfp
    end function LGNSetErrFile

    !> The sparsity pattern of M, B, K_t or C_t changed: rebuild it.
    integer(c_int) function LGNResetSparsityPattern(lgn_mem) &
        bind(c, name="LGNResetSparsityPattern")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
    end function LGNResetSparsityPattern

    !> Steps accepted with the multipliers stalled at roundoff level.
    integer(c_int) function LGNGetNumNewtonStalls(lgn_mem, nstalls) &
        bind(c, name="LGNGetNumNewtonStalls")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nstalls
    end function LGNGetNumNewtonStalls

    !> Patterns of the sparse iteration matrix built (KLU analyses).
    integer(c_int) function LGNGetNumSparsityAnalyses(lgn_mem, nanalyses) &
        bind(c, name="LGNGetNumSparsityAnalyses")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nanalyses
    end function LGNGetNumSparsityAnalyses

    !> Stored entries of the iteration matrix.
    integer(c_int) function LGNGetIterationMatrixNnz(lgn_mem, nnz) &
        bind(c, name="LGNGetIterationMatrixNnz")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nnz
    end function LGNGetIterationMatrixNnz

    !> Displaced evaluations per difference-quotient stiffness matrix.
    integer(c_int) function LGNGetNumDQColors(lgn_mem, ncolors) &
        bind(c, name="LGNGetNumDQColors")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: ncolors
    end function LGNGetNumDQColors

    !> Work space of the integrator: lenrw reals and leniw integers.
    integer(c_int) function LGNGetWorkSpace(lgn_mem, lenrw, leniw) &
        bind(c, name="LGNGetWorkSpace")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: lenrw, leniw
    end function LGNGetWorkSpace

    ! =========================================================================
    ! lignum.h: parameter maps
    ! =========================================================================

    !> Chung-Hulbert parameters from rho_inf in [0, 1].
    integer(c_int) function LGNGenAlphaFromRhoInf(rho_inf, alpha_m, alpha_f, beta, gamma) &
        bind(c, name="LGNGenAlphaFromRhoInf")
      import :: c_int, c_double
      real(c_double), value :: rho_inf
      real(c_double), intent(out) :: alpha_m, alpha_f, beta, gamma
    end function LGNGenAlphaFromRhoInf

    ! =========================================================================
    ! lignum.h: outputs
    ! =========================================================================

    !> Acceleration vdot at the current time (length nv).
    integer(c_int) function LGNGetAcceleration(lgn_mem, vdot) &
        bind(c, name="LGNGetAcceleration")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, vdot
    end function LGNGetAcceleration

    !> Multipliers lambda at the current time (length m).
    integer(c_int) function LGNGetMultipliers(lgn_mem, lambda) &
        bind(c, name="LGNGetMultipliers")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, lambda
    end function LGNGetMultipliers

    !> Algorithmic acceleration a at the current time (length nv).
    integer(c_int) function LGNGetAuxAcceleration(lgn_mem, a) &
        bind(c, name="LGNGetAuxAcceleration")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, a
    end function LGNGetAuxAcceleration

    !> Current time.
    integer(c_int) function LGNGetCurrentTime(lgn_mem, tcur) bind(c, name="LGNGetCurrentTime")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: tcur
    end function LGNGetCurrentTime

    !> Size of the last step taken.
    integer(c_int) function LGNGetLastStep(lgn_mem, hlast) bind(c, name="LGNGetLastStep")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: hlast
    end function LGNGetLastStep

    !> Method parameters in use.
    integer(c_int) function LGNGetMethodParams(lgn_mem, alpha_m, alpha_f, beta, gamma) &
        bind(c, name="LGNGetMethodParams")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), intent(out) :: alpha_m, alpha_f, beta, gamma
    end function LGNGetMethodParams

    !> BDF: the order of the next step (2 for the Newmark family).
    integer(c_int) function LGNGetCurrentOrder(lgn_mem, order) bind(c, name="LGNGetCurrentOrder")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: order
    end function LGNGetCurrentOrder

    !> BDF: the order of the last step taken (2 for the Newmark family).
    integer(c_int) function LGNGetLastOrder(lgn_mem, order) bind(c, name="LGNGetLastOrder")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(out) :: order
    end function LGNGetLastOrder

    !> BDF: steps taken at each order, nsteps(k + 1) for order k = 1 ... 5.
    integer(c_int) function LGNGetNumStepsAtOrder(lgn_mem, nsteps) &
        bind(c, name="LGNGetNumStepsAtOrder")
      import :: c_int, c_long, c_ptr, LGN_BDF_MAX_ORDER
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nsteps(LGN_BDF_MAX_ORDER + 1)
    end function LGNGetNumStepsAtOrder

    !> Select the BDF family of variable order 1 ... maxord (maxord <= 5).
    integer(c_int) function LGNSetBDF(lgn_mem, maxord) bind(c, name="LGNSetBDF")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: maxord
    end function LGNSetBDF

    !> The form of the BDF formulas on non-uniform steps:
    !> LGN_BDF_VARIABLE_COEFF or LGN_BDF_FIXED_LEADING.
    integer(c_int) function LGNSetBDFForm(lgn_mem, form) bind(c, name="LGNSetBDFForm")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: form
    end function LGNSetBDFForm

    !> Number of steps taken.
    integer(c_int) function LGNGetNumSteps(lgn_mem, nsteps) bind(c, name="LGNGetNumSteps")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nsteps
    end function LGNGetNumSteps

    !> Number of Newton iterations.
    integer(c_int) function LGNGetNumNewtonIters(lgn_mem, nniters) &
        bind(c, name="LGNGetNumNewtonIters")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nniters
    end function LGNGetNumNewtonIters

    !> Number of Newton convergence failures.
    integer(c_int) function LGNGetNumNewtonConvFails(lgn_mem, nncfails) &
        bind(c, name="LGNGetNumNewtonConvFails")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nncfails
    end function LGNGetNumNewtonConvFails

    !> Number of failed step attempts.
    integer(c_int) function LGNGetNumStepFails(lgn_mem, nfails) &
        bind(c, name="LGNGetNumStepFails")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nfails
    end function LGNGetNumStepFails

    !> Number of residual evaluations in Newton.
    integer(c_int) function LGNGetNumResEvals(lgn_mem, nres) bind(c, name="LGNGetNumResEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nres
    end function LGNGetNumResEvals

    !> Number of residual-type evaluations in difference quotients.
    integer(c_int) function LGNGetNumDQEvals(lgn_mem, ndq) bind(c, name="LGNGetNumDQEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: ndq
    end function LGNGetNumDQEvals

    !> Number of iteration matrix evaluations.
    integer(c_int) function LGNGetNumJacEvals(lgn_mem, njevals) bind(c, name="LGNGetNumJacEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: njevals
    end function LGNGetNumJacEvals

    !> Number of linear solver setups.
    integer(c_int) function LGNGetNumLinSolvSetups(lgn_mem, nlsetups) &
        bind(c, name="LGNGetNumLinSolvSetups")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nlsetups
    end function LGNGetNumLinSolvSetups

    !> Number of linear solves.
    integer(c_int) function LGNGetNumLinSolves(lgn_mem, nlsolves) &
        bind(c, name="LGNGetNumLinSolves")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nlsolves
    end function LGNGetNumLinSolves

    !> Newton iterations solved with a reused iteration matrix.
    integer(c_int) function LGNGetNumMatrixReuses(lgn_mem, nreuses) &
        bind(c, name="LGNGetNumMatrixReuses")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nreuses
    end function LGNGetNumMatrixReuses

    !> Steps whose modified Newton iteration restarted with a fresh matrix.
    integer(c_int) function LGNGetNumNewtonRestarts(lgn_mem, nrestarts) &
        bind(c, name="LGNGetNumNewtonRestarts")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nrestarts
    end function LGNGetNumNewtonRestarts

    !> Return flag of the last linear solver call.
    integer(c_int) function LGNGetLastLinFlag(lgn_mem, flag) bind(c, name="LGNGetLastLinFlag")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: flag
    end function LGNGetLastLinFlag

    !> Attach a user preconditioner for a matrix-free Krylov solver
    !! (c_funloc of LGNPrecSetupFn / LGNPrecSolveFn procedures; c_null_funptr
    !! for both: none).
    integer(c_int) function LGNSetPreconditioner(lgn_mem, psetup, psolve) &
        bind(c, name="LGNSetPreconditioner")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      type(c_funptr), value :: psetup, psolve
    end function LGNSetPreconditioner

    !> Lignum's block-Jacobi preconditioner: nblocks blocks of bodies;
    !! body_start (nblocks + 1 body indices from 0) or c_null_ptr for equal
    !! blocks (pass c_loc of an integer(c_long) array).
    integer(c_int) function LGNSetBlockPreconditioner(lgn_mem, nblocks, body_start) &
        bind(c, name="LGNSetBlockPreconditioner")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: nblocks
      type(c_ptr), value :: body_start
    end function LGNSetBlockPreconditioner

    !> The linear tolerance as a fraction of Newton's (0: default 0.05).
    integer(c_int) function LGNSetEpsLin(lgn_mem, eplifac) bind(c, name="LGNSetEpsLin")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: lgn_mem
      real(c_double), value :: eplifac
    end function LGNSetEpsLin

    !> Krylov iterations.
    integer(c_int) function LGNGetNumLinIters(lgn_mem, nliters) bind(c, name="LGNGetNumLinIters")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nliters
    end function LGNGetNumLinIters

    !> Preconditioner setups.
    integer(c_int) function LGNGetNumPrecEvals(lgn_mem, npevals) bind(c, name="LGNGetNumPrecEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: npevals
    end function LGNGetNumPrecEvals

    !> Preconditioner solves.
    integer(c_int) function LGNGetNumPrecSolves(lgn_mem, npsolves) bind(c, name="LGNGetNumPrecSolves")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: npsolves
    end function LGNGetNumPrecSolves

    !> Products with the iteration matrix (ATimes).
    integer(c_int) function LGNGetNumJtimesEvals(lgn_mem, njvevals) bind(c, name="LGNGetNumJtimesEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: njvevals
    end function LGNGetNumJtimesEvals

    !> Linear solves short of their tolerance.
    integer(c_int) function LGNGetNumLinConvFails(lgn_mem, nlcfails) bind(c, name="LGNGetNumLinConvFails")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: nlcfails
    end function LGNGetNumLinConvFails

    !> Print all counters to a C stream (FLGNStdout(), FLGNFopen(...)); fmt is
    !! SUN_OUTPUTFORMAT_TABLE or SUN_OUTPUTFORMAT_CSV (flignum_sundials_mod).
    !! See FLGNPrintAllStats for standard output.
    integer(c_int) function LGNPrintAllStats(lgn_mem, outfile, fmt) &
        bind(c, name="LGNPrintAllStats")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, outfile
      integer(c_int), value :: fmt
    end function LGNPrintAllStats

    !> Name of a return flag as a static C string; FLGNGetReturnFlagName
    !! returns it as a Fortran string.
    type(c_ptr) function LGNGetReturnFlagName(flag) bind(c, name="LGNGetReturnFlagName")
      import :: c_ptr, c_long
      integer(c_long), value :: flag
    end function LGNGetReturnFlagName

    ! =========================================================================
    ! lignum_group.h: constructors and destructor
    ! =========================================================================

    !> R^n as an additive Lie group (c_null_ptr if n < 1).
    type(c_ptr) function LGNGroup_Rn(n) bind(c, name="LGNGroup_Rn")
      import :: c_ptr, c_int64_t
      integer(c_int64_t), value :: n
    end function LGNGroup_Rn

    !> SO(3), unit quaternion storage (w, x, y, z).
    type(c_ptr) function LGNGroup_SO3() bind(c, name="LGNGroup_SO3")
      import :: c_ptr
    end function LGNGroup_SO3

    !> R^3 x SO(3): q = (x, p), v = (u inertial, Omega body).
    type(c_ptr) function LGNGroup_R3xSO3() bind(c, name="LGNGroup_R3xSO3")
      import :: c_ptr
    end function LGNGroup_R3xSO3

    !> SE(3): q = (x, p), v = (U, Omega) both body-fixed.
    type(c_ptr) function LGNGroup_SE3() bind(c, name="LGNGroup_SE3")
      import :: c_ptr
    end function LGNGroup_SE3

    !> Direct product of nfactors groups (referenced, not owned).
    type(c_ptr) function LGNGroup_Product(nfactors, factors) bind(c, name="LGNGroup_Product")
      import :: c_ptr, c_int
      integer(c_int), value :: nfactors
      type(c_ptr), intent(in) :: factors(*)
    end function LGNGroup_Product

    !> A group with dimensions set and all ops null (fill via FLGNGroup_Rec).
    type(c_ptr) function LGNGroup_NewEmpty(nq, nv) bind(c, name="LGNGroup_NewEmpty")
      import :: c_ptr, c_int64_t
      integer(c_int64_t), value :: nq, nv
    end function LGNGroup_NewEmpty

    !> Free a group made by any constructor; c_null_ptr is allowed.
    subroutine LGNGroup_Destroy(G) bind(c, name="LGNGroup_Destroy")
      import :: c_ptr
      type(c_ptr), value :: G
    end subroutine LGNGroup_Destroy

    ! =========================================================================
    ! lignum_group.h: dispatchers (flag of the op; -1 if the op is missing)
    ! =========================================================================

    !> q_out = q o exp(w).
    integer(c_int) function LGNGroup_ComposeExp(G, q, w, q_out) &
        bind(c, name="LGNGroup_ComposeExp")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: q(*), w(*)
      real(c_double), intent(out) :: q_out(*)
    end function LGNGroup_ComposeExp

    !> w = log(q1^{-1} q2) in R^nv, the inverse of LGNGroup_ComposeExp.
    !! Returns LGN_SUCCESS, LGN_ILL_INPUT (a null argument, or no
    !! compose_log op) or LGN_GROUP_FAIL (the op failed), with a message.
    integer(c_int) function LGNGroup_ComposeLog(G, q1, q2, w) &
        bind(c, name="LGNGroup_ComposeLog")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: q1(*), q2(*)
      real(c_double), intent(out) :: w(*)
    end function LGNGroup_ComposeLog

    !> y = T(w) x.
    integer(c_int) function LGNGroup_TangentApply(G, w, x, y) &
        bind(c, name="LGNGroup_TangentApply")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*), x(*)
      real(c_double), intent(out) :: y(*)
    end function LGNGroup_TangentApply

    !> y = T(w)^{-1} x.
    integer(c_int) function LGNGroup_TangentInverseApply(G, w, x, y) &
        bind(c, name="LGNGroup_TangentInverseApply")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*), x(*)
      real(c_double), intent(out) :: y(*)
    end function LGNGroup_TangentInverseApply

    !> y = Tdot(w, wdot) x.
    integer(c_int) function LGNGroup_TangentDotApply(G, w, wdot, x, y) &
        bind(c, name="LGNGroup_TangentDotApply")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*), wdot(*), x(*)
      real(c_double), intent(out) :: y(*)
    end function LGNGroup_TangentDotApply

    !> Tm = T(w), column-major nv x nv with leading dimension ld (Tm(ld, nv)).
    integer(c_int) function LGNGroup_TangentMatrix(G, w, Tm, ld) &
        bind(c, name="LGNGroup_TangentMatrix")
      import :: c_int, c_int64_t, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(in) :: w(*)
      real(c_double), intent(inout) :: Tm(*)
      integer(c_int64_t), value :: ld
    end function LGNGroup_TangentMatrix

    !> q = identity element.
    integer(c_int) function LGNGroup_Identity(G, q) bind(c, name="LGNGroup_Identity")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(out) :: q(*)
    end function LGNGroup_Identity

    !> Project q onto the group.
    integer(c_int) function LGNGroup_Normalize(G, q) bind(c, name="LGNGroup_Normalize")
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: G
      real(c_double), intent(inout) :: q(*)
    end function LGNGroup_Normalize

    ! =========================================================================
    ! lignum_group.h: rotation helpers, quaternion p = (w, x, y, z)
    ! =========================================================================

    !> R of the unit quaternion p, ROW-major: R(3*i+j+1) = R_ij (i, j from 0),
    !! so reshape(R, [3, 3]) is the transpose R^T.
    subroutine LGNQuaternionToRotation(p, R) bind(c, name="LGNQuaternionToRotation")
      import :: c_double
      real(c_double), intent(in) :: p(4)
      real(c_double), intent(out) :: R(9)
    end subroutine LGNQuaternionToRotation

    !> Unit quaternion p = exp of the rotation vector phi.
    subroutine LGNQuaternionFromRotationVector(phi, p) &
        bind(c, name="LGNQuaternionFromRotationVector")
      import :: c_double
      real(c_double), intent(in) :: phi(3)
      real(c_double), intent(out) :: p(4)
    end subroutine LGNQuaternionFromRotationVector

    !> Rotation vector phi = log(p), |phi| <= pi.
    subroutine LGNRotationVectorFromQuaternion(p, phi) &
        bind(c, name="LGNRotationVectorFromQuaternion")
      import :: c_double
      real(c_double), intent(in) :: p(4)
      real(c_double), intent(out) :: phi(3)
    end subroutine LGNRotationVectorFromQuaternion

    !> r = p1 * p2 (Hamilton product); in C r may alias p1 or p2, in
    !! Fortran pass distinct actual arguments.
    subroutine LGNQuaternionMultiply(p1, p2, r) bind(c, name="LGNQuaternionMultiply")
      import :: c_double
      real(c_double), intent(in) :: p1(4), p2(4)
      real(c_double), intent(out) :: r(4)
    end subroutine LGNQuaternionMultiply

    ! =========================================================================
    ! C streams for LGNSetErrFile and LGNPrintAllStats (fortran/flignum_cshim.c
    ! for stdout/stderr, the C library for the rest)
    ! =========================================================================

    !> The C stream stdout.
    type(c_ptr) function FLGNStdout() bind(c, name="FLGNStdout")
      import :: c_ptr
    end function FLGNStdout

    !> The C stream stderr.
    type(c_ptr) function FLGNStderr() bind(c, name="FLGNStderr")
      import :: c_ptr
    end function FLGNStderr

    !> fflush(fp) of the C library; c_null_ptr flushes all C streams.
    integer(c_int) function FLGNFflush(fp) bind(c, name="fflush")
      import :: c_int, c_ptr
      type(c_ptr), value :: fp
    end function FLGNFflush

    !> fclose(fp) of the C library.
    integer(c_int) function FLGNFclose(fp) bind(c, name="fclose")
      import :: c_int, c_ptr
      type(c_ptr), value :: fp
    end function FLGNFclose

    ! =========================================================================
    ! lignum.h: consistent initial values
    ! =========================================================================

    !> Project the initial state onto the constraints (icopt LGN_IC_PROJECT_Q,
    !> _V or _QV), then compute vdot_0, lambda_0 (IDACalcIC-like).
    integer(c_int) function LGNCalcIC(lgn_mem, icopt) bind(c, name="LGNCalcIC")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: icopt
    end function LGNCalcIC

    !> An impact at the current state: contact rows G (LGNContactJacFn, nc
    !> of them), restitution e in [0, 1]; v+ from the impulse saddle-point
    !> problem, then a restart; v (length nv) receives v+, P (length nc) the
    !> impulses (either may be c_null_ptr).
    integer(c_int) function LGNApplyImpact(lgn_mem, nc, G, e, v, P) &
        bind(c, name="LGNApplyImpact")
      import :: c_int, c_int64_t, c_double, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      integer(c_int64_t), value :: nc
      type(c_funptr), value :: G
      real(c_double), value :: e
      type(c_ptr), value :: v, P
    end function LGNApplyImpact

    !> The corrected q0 (length nq), v0 (length nv); either may be c_null_ptr.
    !> Only before the first step.
    integer(c_int) function LGNGetConsistentIC(lgn_mem, q0, v0) &
        bind(c, name="LGNGetConsistentIC")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem, q0, v0
    end function LGNGetConsistentIC

    !> Perturbed starting values on (SUNTRUE = 1) or off (SUNFALSE = 0, the
    !> default).
    integer(c_int) function LGNSetPerturbedStart(lgn_mem, on) &
        bind(c, name="LGNSetPerturbedStart")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: on
    end function LGNSetPerturbedStart
  end interface

  ! ===========================================================================
  ! lignum.h: events (root finding)
  ! ===========================================================================
  integer(c_int), parameter :: LGN_ROOT_RETURN = 2    !< LGNSolve returned at a root
  integer(c_int), parameter :: LGN_RTFUNC_FAIL = -13  !< the root function failed
  integer(c_int), parameter :: LGN_WARNING = 99       !< error_code of a warning

  abstract interface
    !> Root functions: gout(1:nrtfn) = g(t, q, v). q and v (N_Vector) hold
    !! the solution at t. Return 0; anything else stops LGNSolve with
    !! LGN_RTFUNC_FAIL.
    integer(c_int) function LGNRootFn(t, q, v, gout, user_data) bind(c)
      import :: c_int, c_double, c_ptr
      real(c_double), value :: t
      type(c_ptr), value :: q, v
      real(c_double) :: gout(*)
      type(c_ptr), value :: user_data
    end function LGNRootFn
  end interface

  interface
    !> Root finding on nrtfn functions g (c_funloc of an LGNRootFn); after
    !! LGNInit. LGNSolve returns LGN_ROOT_RETURN at each root, in order;
    !! nrtfn = 0 turns root finding off.
    integer(c_int) function LGNRootInit(lgn_mem, nrtfn, g) bind(c, name="LGNRootInit")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), value :: nrtfn
      type(c_funptr), value :: g
    end function LGNRootInit

    !> Directions: rootdir(i) = +1 increasing, -1 decreasing, 0 both.
    integer(c_int) function LGNSetRootDirection(lgn_mem, rootdir) &
        bind(c, name="LGNSetRootDirection")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(in) :: rootdir(*)
    end function LGNSetRootDirection

    !> No warning for a g_i still exactly 0 after the first step.
    integer(c_int) function LGNSetNoInactiveRootWarn(lgn_mem) &
        bind(c, name="LGNSetNoInactiveRootWarn")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
    end function LGNSetNoInactiveRootWarn

    !> After LGN_ROOT_RETURN: rootsfound(i) = +1 / -1 (direction) or 0.
    integer(c_int) function LGNGetRootInfo(lgn_mem, rootsfound) &
        bind(c, name="LGNGetRootInfo")
      import :: c_int, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_int), intent(inout) :: rootsfound(*)
    end function LGNGetRootInfo

    !> Root function evaluations (since LGNInit / LGNReInit).
    integer(c_int) function LGNGetNumGEvals(lgn_mem, ngevals) &
        bind(c, name="LGNGetNumGEvals")
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: lgn_mem
      integer(c_long), intent(out) :: ngevals
    end function LGNGetNumGEvals
  end interface

contains

  !> Copy a NUL-terminated C string into a Fortran string ("" for c_null_ptr).
  !! @param cstr the C string (const char *)
  !! @return     its characters, without the terminating NUL
  function FLGNString(cstr) result(str)
    type(c_ptr), intent(in) :: cstr
    character(len=:), allocatable :: str
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    interface
      integer(c_size_t) function c_strlen(s) bind(c, name="strlen")
        import :: c_size_t, c_ptr
        type(c_ptr), value :: s
      end function c_strlen
    end interface

    if (.not. c_associated(cstr)) then
      str = ""
      return
    end if
    n = int(c_strlen(cstr))
    call c_f_pointer(cstr, chars, [n])
    allocate (character(len=n) :: str)
    do i = 1, n
      str(i:i) = chars(i)
    end do
  end function FLGNString

  !> Name of a Lignum return flag, e.g. "LGN_CONV_FAILURE".
  !! @param flag a value returned by a Lignum function
  !! @return     the name (as LGNGetReturnFlagName)
  function FLGNGetReturnFlagName(flag) result(name)
    integer(c_int), intent(in) :: flag
    character(len=:), allocatable :: name

    name = FLGNString(LGNGetReturnFlagName(int(flag, c_long)))
  end function FLGNGetReturnFlagName

  !> LGNWriteRestart with a Fortran file name (trailing blanks ignored).
  !! @param lgn_mem  memory block
  !! @param filename the restart file (one per MPI rank)
  !! @return         the flag of LGNWriteRestart
  function FLGNWriteRestart(lgn_mem, filename) result(flag)
    type(c_ptr), intent(in) :: lgn_mem
    character(len=*), intent(in) :: filename
    integer(c_int) :: flag

    flag = LGNWriteRestart(lgn_mem, trim(filename)//c_null_char)
  end function FLGNWriteRestart

  !> LGNReadRestart with a Fortran file name (trailing blanks ignored).
  !! @param lgn_mem  memory block (after LGNInit, settings as the writer's)
  !! @param filename the restart file
  !! @return         the flag of LGNReadRestart
  function FLGNReadRestart(lgn_mem, filename) result(flag)
    type(c_ptr), intent(in) :: lgn_mem
    character(len=*), intent(in) :: filename
    integer(c_int) :: flag

    flag = LGNReadRestart(lgn_mem, trim(filename)//c_null_char)
  end function FLGNReadRestart

  !> Open a C stream (fopen) for LGNSetErrFile or LGNPrintAllStats.
  !! @param path file name (trailing blanks are ignored)
  !! @param mode fopen mode, e.g. "w"
  !! @return     the FILE *, c_null_ptr on failure; close it with FLGNFclose
  function FLGNFopen(path, mode) result(fp)
    character(len=*), intent(in) :: path, mode
    type(c_ptr) :: fp
    interface
      type(c_ptr) function c_fopen(cpath, cmode) bind(c, name="fopen")
        import :: c_ptr, c_char
        character(kind=c_char), intent(in) :: cpath(*), cmode(*)
      end function c_fopen
    end interface

    fp = c_fopen(trim(path)//c_null_char, trim(mode)//c_null_char)
  end function FLGNFopen

  !> LGNPrintAllStats on standard output, in order with Fortran output:
  !! flushes the Fortran unit output_unit first and the C stdout after.
  !! @param lgn_mem memory block
  !! @param fmt     SUN_OUTPUTFORMAT_TABLE or SUN_OUTPUTFORMAT_CSV
  !! @return        the flag of LGNPrintAllStats
  function FLGNPrintAllStats(lgn_mem, fmt) result(flag)
    use, intrinsic :: iso_fortran_env, only: output_unit
    type(c_ptr), intent(in) :: lgn_mem
    integer(c_int), intent(in) :: fmt
    integer(c_int) :: flag, ierr

    flush (output_unit)
    flag = LGNPrintAllStats(lgn_mem, FLGNStdout(), fmt)
    ierr = FLGNFflush(FLGNStdout())
    if (ierr /= 0 .and. flag == LGN_SUCCESS) flag = LGN_UNRECOGNIZED_ERR
  end function FLGNPrintAllStats

  !> The group record behind an LGNGroup (nq, nv, kind, content, ops).
  !! @param G a group (not c_null_ptr)
  !! @return  pointer to its struct LGNGroupRec
  function FLGNGroup_Rec(G) result(rec)
    type(c_ptr), intent(in) :: G
    type(LGNGroupRec), pointer :: rec

    call c_f_pointer(G, rec)
  end function FLGNGroup_Rec

  !> Number of reals storing one element of G (G->nq).
  !! @param G a group (not c_null_ptr)
  function FLGNGroup_NQ(G) result(nq)
    type(c_ptr), intent(in) :: G
    integer(c_int64_t) :: nq
    type(LGNGroupRec), pointer :: rec

    call c_f_pointer(G, rec)
    nq = rec%nq
  end function FLGNGroup_NQ

  !> Dimension of the Lie algebra of G (G->nv).
  !! @param G a group (not c_null_ptr)
  function FLGNGroup_NV(G) result(nv)
    type(c_ptr), intent(in) :: G
    integer(c_int64_t) :: nv
    type(LGNGroupRec), pointer :: rec

    call c_f_pointer(G, rec)
    nv = rec%nv
  end function FLGNGroup_NV

end module flignum_mod
