/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A multibody model: a body set (lignum_bodies.h: bodies, gravity, force
 * elements), a joint set (lignum_joints.h: joints and drivers) and an
 * optional user force for what the helpers lack, installed on an integrator
 * with one call, LGNModel_Attach, which sets every model callback:
 *
 *   M        LGNBodies_Mass (LGNSetMassConstant: M of rigid bodies is
 *            constant)
 *   g        LGNBodies_Force + the user force
 *   Phi, B   LGNJoints_Residual, LGNJoints_Jacobian (m rows)
 *   Z        LGNJoints_Curvature
 *   Phi_t    LGNJoints_TimeDerivative, when the joints have drivers
 *   K_t      LGNBodies_Stiffness + LGNJoints_Stiffness + the user's K
 *   C_t      LGNBodies_Damping + the user's C
 *
 * The matrices are those of the iteration matrix (LGNSetLinearSolver):
 * dense, or sparse (CSC or CSR) with the helpers' patterns; each term is
 * ADDED to what the matrix holds, by the same rule for dense and sparse
 * matrices (lignum_bodies.h, "Matrices"), so the sum is right for both.
 *
 * The model is generic over the group its sets were created on: it uses
 * nothing but the body and joint sets' functions, so it runs on every
 * group those support.
 *
 * Ownership: the model references the body and joint sets (it does not
 * copy or free them) and is referenced by the integrator it is attached
 * to (it becomes that integrator's user data, LGNSetUserData; a callback
 * the user sets on the integrator, e.g. a root function, receives the model
 * and finds the user's pointer with LGNModel_GetUserData). Destroy in
 * reverse order of creation: LGNFree first, then LGNModel_Destroy, then the
 * sets, then the group. The integrator keeps working as long as the model
 * and its sets live; destroying the model while an attached integrator is
 * still used is an error (its callbacks would read freed memory).
 *
 * Errors: the functions returning a flag return LGN_SUCCESS, LGN_MEM_NULL
 * (the integrator memory is NULL), LGN_ILL_INPUT (a bad argument, named in
 * the message) or LGN_MEM_FAIL, report through the model's own error
 * handler (stderr by default; LGNModel_SetErrHandlerFn, LGNModel_SetErrFile)
 * and change nothing when they fail. A model keeps work space (for the
 * user's K and C): evaluate one model from one thread at a time, as its
 * sets.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_MODEL_H
#define LIGNUM_MODEL_H

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_export.h>
#include <lignum/lignum_joints.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A multibody model: bodies, joints, force elements, a user force. */
typedef struct LGNModelRec *LGNModel;

/**
 * Create a model of the bodies of `bodies` joined by the joints of `joints`.
 * @param bodies the body set (not NULL); referenced, must outlive the model
 * @param joints the joint set, created on the same group as `bodies` (the
 *               same LGNGroup), or NULL for a model without constraints;
 *               referenced, must outlive the model
 * @return the model, or NULL (message on stderr) if bodies is NULL, the
 *         sets were created on different groups, or memory ran out.
 */
LGN_EXPORT LGNModel LGNModel_Create(LGNBodies bodies, LGNJoints joints);

/** Replace the error handler of a model (NULL restores the default).
 *  @return LGN_SUCCESS, or LGN_ILL_INPUT if model is NULL (message on
 *  stderr). */
LGN_EXPORT int LGNModel_SetErrHandlerFn(LGNModel model, LGNErrHandlerFn ehfun,
                                        void *eh_data);

/** Set the stream of the model's default error handler (stderr at
 *  creation; NULL silences it). @return LGN_SUCCESS, or LGN_ILL_INPUT if
 *  model is NULL. */
LGN_EXPORT int LGNModel_SetErrFile(LGNModel model, FILE *errfp);

/** Free a model (not its sets) and set *model to NULL; NULL is allowed.
 *  Call it after LGNFree of every integrator it is attached to. */
LGN_EXPORT void LGNModel_Destroy(LGNModel *model);

/**
 * Add a user force to the helpers' forces, for what the body set lacks
 * (e.g. a tyre, a magnetic field). force (an LGNForceFn) writes its g_u
 * (length nv, MINUS the applied forces, as g: it arrives zeroed) and the
 * model adds it to the bodies' g. Its tangent stiffness dg_u/dq along the
 * group (an LGNStiffnessFn, which gets vdot and lambda but should not need
 * them) and damping dg_u/dv (an LGNDampingFn) are optional: each writes
 * its own matrix, which arrives as Lignum's do (dense: zeroed; sparse:
 * empty, to be filled with the callback's pattern), and the model adds it.
 * Without K (or C) the model leaves all of K_t (or C_t) to Lignum's
 * difference quotients: a Jacobian missing a term would slow Newton down
 * silently. The callbacks get the pointer of LGNModel_SetUserData. Takes
 * effect at the next LGNModel_Attach.
 * @param model the model
 * @param force the user force, or NULL (none: K and C must be NULL too)
 * @param K     dg_u/dq, or NULL
 * @param C     dg_u/dv, or NULL
 * @return LGN_SUCCESS or LGN_ILL_INPUT (model NULL, K or C without force).
 */
LGN_EXPORT int LGNModel_SetUserForce(LGNModel model, LGNForceFn force,
                                     LGNStiffnessFn K, LGNDampingFn C);

/** Set the pointer passed to the user force callbacks (NULL at creation).
 *  @return LGN_SUCCESS or LGN_ILL_INPUT (model NULL). */
LGN_EXPORT int LGNModel_SetUserData(LGNModel model, void *user_data);

/** The pointer of LGNModel_SetUserData; NULL for model = NULL. */
LGN_EXPORT void *LGNModel_GetUserData(LGNModel model);

/** The model's body set; NULL for model = NULL. */
LGN_EXPORT LGNBodies LGNModel_GetBodies(LGNModel model);

/** The model's joint set (NULL without constraints or for model = NULL). */
LGN_EXPORT LGNJoints LGNModel_GetJoints(LGNModel model);

/** Number of constraints m of the model's joints (0 without joints or for
 *  model = NULL). */
LGN_EXPORT sunindextype LGNModel_NumConstraints(LGNModel model);

/**
 * Install the model on an integrator, before or after LGNInit: its group
 * (LGNSetGroup), the user data (the model itself), and the callbacks of
 * the table at the top of this header (LGNSetMassFn, LGNSetMassConstant,
 * LGNSetForceFn, LGNSetConstraints with m = LGNModel_NumConstraints,
 * LGNSetCurvatureFn, LGNSetConstraintTimeFn (NULL without drivers),
 * LGNSetStiffnessFn, LGNSetDampingFn). Joints or force elements added
 * later are seen by the callbacks, but m is the one of this call: attach
 * again after adding joints. Set the linear solver, the method and the
 * tolerances as usual.
 * @param model   the model
 * @param lgn_mem an integrator memory from LGNCreate
 * @return LGN_SUCCESS; LGN_ILL_INPUT if model is NULL, or if lgn_mem was
 *         initialised (LGNInit) with sizes nq, nv other than those of the
 *         model's group (nothing changed then); LGN_MEM_NULL if lgn_mem is
 *         NULL.
 */
LGN_EXPORT int LGNModel_Attach(LGNModel model, void *lgn_mem);

#ifdef __cplusplus
}
#endif

#endif
