! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! Fortran 2003 interface to the multibody model object (lignum_model.h):
! a body set, a joint set and a user force installed on an integrator with
! one call, LGNModel_Attach. Argument mapping as in flignum_bodies_mod:
!   LGNModel, LGNBodies, LGNJoints, void *, FILE * -> type(c_ptr), value
!   LGNModel *model (LGNModel_Destroy) -> type(c_ptr), by reference
!   callbacks (LGNForceFn, LGNStiffnessFn, LGNDampingFn, LGNErrHandlerFn)
!                                   -> type(c_funptr), value (c_funloc of a
!                                      bind(c) procedure with the abstract
!                                      interfaces of flignum_mod)
!   int (flags)                     -> integer(c_int)
!   sunindextype                    -> integer(c_int64_t)
! The model becomes the integrator's user data: a root function set on the
! integrator receives the model and finds the user's pointer with
! LGNModel_GetUserData. Free with LGNFree first, then LGNModel_Destroy.
! ---------------------------------------------------------------------------
module flignum_model_mod
  use, intrinsic :: iso_c_binding
  implicit none

  interface

    !> A model of the bodies of `bodies` joined by `joints` (c_null_ptr: no
    !! constraints); c_null_ptr if bodies is null or the sets' groups differ.
    type(c_ptr) function LGNModel_Create(bodies, joints) bind(c, name="LGNModel_Create")
      import :: c_ptr
      type(c_ptr), value :: bodies, joints
    end function LGNModel_Create

    !> Error handler of the model (c_null_funptr: the default).
    integer(c_int) function LGNModel_SetErrHandlerFn(model, ehfun, eh_data) &
        bind(c, name="LGNModel_SetErrHandlerFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: model
      type(c_funptr), value :: ehfun
      type(c_ptr), value :: eh_data
    end function LGNModel_SetErrHandlerFn

    !> Stream of the default error handler (c_null_ptr silences it).
    integer(c_int) function LGNModel_SetErrFile(model, errfp) &
        bind(c, name="LGNModel_SetErrFile")
      import :: c_int, c_ptr
      type(c_ptr), value :: model, errfp
    end function LGNModel_SetErrFile

    !> Free a model (not its sets) and set model = c_null_ptr.
    subroutine LGNModel_Destroy(model) bind(c, name="LGNModel_Destroy")
      import :: c_ptr
      type(c_ptr), intent(inout) :: model
    end subroutine LGNModel_Destroy

    !> A user force added to the bodies' g, with its K and C (each may be
    !! c_null_funptr: then Lignum's difference quotients give K_t or C_t).
    integer(c_int) function LGNModel_SetUserForce(model, force, K, C) &
        bind(c, name="LGNModel_SetUserForce")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: model
      type(c_funptr), value :: force, K, C
    end function LGNModel_SetUserForce

    !> The pointer passed to the user force callbacks.
    integer(c_int) function LGNModel_SetUserData(model, user_data) &
        bind(c, name="LGNModel_SetUserData")
      import :: c_int, c_ptr
      type(c_ptr), value :: model, user_data
    end function LGNModel_SetUserData

    !> The pointer of LGNModel_SetUserData.
    type(c_ptr) function LGNModel_GetUserData(model) bind(c, name="LGNModel_GetUserData")
      import :: c_ptr
      type(c_ptr), value :: model
    end function LGNModel_GetUserData

    !> The model's body set.
    type(c_ptr) function LGNModel_GetBodies(model) bind(c, name="LGNModel_GetBodies")
      import :: c_ptr
      type(c_ptr), value :: model
    end function LGNModel_GetBodies

    !> The model's joint set (c_null_ptr without constraints).
    type(c_ptr) function LGNModel_GetJoints(model) bind(c, name="LGNModel_GetJoints")
      import :: c_ptr
      type(c_ptr), value :: model
    end function LGNModel_GetJoints

    !> Number of constraints m of the model's joints.
    integer(c_int64_t) function LGNModel_NumConstraints(model) &
        bind(c, name="LGNModel_NumConstraints")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: model
    end function LGNModel_NumConstraints

    !> Install the model on an integrator: group, user data and every model
    !! callback (M, g, Phi, B, curvature, Phi_t, K_t, C_t).
    integer(c_int) function LGNModel_Attach(model, lgn_mem) bind(c, name="LGNModel_Attach")
      import :: c_int, c_ptr
      type(c_ptr), value :: model, lgn_mem
    end function LGNModel_Attach

  end interface

end module flignum_model_mod
