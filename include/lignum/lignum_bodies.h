/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Rigid bodies and force elements, ready to call from the model callbacks:
 * the mass matrix M(q), the forces g(q, v) of M vdot + g + B^T lambda = 0,
 * their tangent stiffness K_t = d/dq (M vdot + g) and damping C_t = dg/dv
 * (dense or sparse, with their patterns), and the kinetic and potential
 * energy.
 *
 * The bodies are the leaves of the configuration group, as for the joint
 * helpers (lignum_joints.h): a single R^3 x SO(3) or SE(3) factor, or a
 * product of them (body k = factor k, products of products flattened in
 * order). The position x of a body is its centre of mass; its rotation R
 * (quaternion p) turns body axes into inertial ones.
 *
 *   R^3 x SO(3), v = (u inertial, Omega body):
 *     M = diag(m I, J),  g = (-m gvec - F, Omega x J Omega - T)
 *   SE(3), v = (U body, Omega body), xdot = R U:
 *     M = diag(m I, J),  g = (m Omega x U - R^T (m gvec + F), Omega x J Omega - T)
 *
 * with J the inertia about the centre of mass in body axes, gvec the
 * acceleration of gravity (shared by all bodies) and (F, T) the force
 * (inertial) and torque (body axes) of the force elements: g holds MINUS
 * the applied forces. M is constant, so K_t = dg/dq. Derivatives are along
 * the group, q o exp(e w) (lignum_group.h): dx = w_x (R^3 x SO(3)) or
 * R w_U (SE(3)), dR = R w_theta~.
 *
 * Force elements:
 *   translational spring-damper between point sa of body a and sb of body
 *     b (or an inertial point for LGN_GROUND): with d = p_b - p_a,
 *     L = |d|, n = d / L, the tension f = k (L - L0) + c dL/dt pulls a
 *     along +n and b along -n; potential k (L - L0)^2 / 2. Undefined at
 *     L = 0: the evaluations refuse L <= 100 eps (1 + |p_a| + |p_b|) with
 *     LGN_ILL_INPUT (and its stiffness grows as f / L near it).
 *   rotational spring-damper between bodies a and b (either LGN_GROUND):
 *     exact logarithm, theta = log(R_a^T R_b) (|theta| < pi; the spring is
 *     relaxed when the body frames are aligned), omega_rel = Omega_b -
 *     R_b^T R_a Omega_a; torque -k_r theta - c_r omega_rel on b (its axes),
 *     the opposite on a; potential k_r |theta|^2 / 2. At |theta| = pi the
 *     logarithm jumps to the other side.
 *
 * Matrices: one rule for dense and sparse M, K and C, here and in the
 * joint helpers (LGNJoints_Stiffness): the term is ADDED to what the matrix
 * holds, so that the bodies' and the joints' terms sum in one matrix in
 * either order. Start from an empty matrix: Lignum passes its callbacks a
 * dense matrix zeroed and a sparse one (CSC or CSR) without entries (index
 * pointers 0, as SUNSparseMatrix creates it); between own calls use
 * SUNMatZero. An empty sparse matrix gets the term's pattern (documented at
 * LGNBodies_MassNnz and LGNBodies_TangentNnz; reallocated if it has too few
 * entries); a sparse matrix holding entries gets the union of its pattern
 * and the term's (each column, or row, sorted by index; in place, without
 * reallocation, when the term's pattern lies within it).
 *
 * Errors: the functions returning a flag return LGN_SUCCESS, LGN_ILL_INPUT
 * (bad argument, named in the message) or LGN_MEM_FAIL, and report through
 * the set's own error handler (stderr by default; LGNBodies_SetErrHandlerFn,
 * LGNBodies_SetErrFile), as the joint sets do. A body set keeps work space:
 * evaluate one set from one thread at a time.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_BODIES_H
#define LIGNUM_BODIES_H

#include <lignum/lignum.h>
#include <lignum/lignum_export.h>
#include <lignum/lignum_joints.h> /* LGN_GROUND */

#ifdef __cplusplus
extern "C" {
#endif

/** The rigid bodies of one configuration group and their force elements. */
typedef struct LGNBodiesRec *LGNBodies;

/**
 * Create the body set of G: every body with mass 1 and inertia I, gravity
 * (0, 0, 0), no force elements.
 * @param G R^3 x SO(3), SE(3) or a product of them; referenced, must
 *          outlive the body set
 * @return the body set, or NULL (message on stderr) if G is NULL, has
 *         another leaf group, or memory ran out.
 */
LGN_EXPORT LGNBodies LGNBodies_Create(LGNGroup G);

/** Replace the error handler of a body set (NULL restores the default).
 *  @return LGN_SUCCESS, or LGN_ILL_INPUT if B is NULL (message on stderr). */
LGN_EXPORT int LGNBodies_SetErrHandlerFn(LGNBodies B, LGNErrHandlerFn ehfun,
                                         void *eh_data);

/** Set the stream of the default error handler (stderr at creation; NULL
 *  silences it). @return LGN_SUCCESS, or LGN_ILL_INPUT if B is NULL. */
LGN_EXPORT int LGNBodies_SetErrFile(LGNBodies B, FILE *errfp);

/** Free a body set and set *B to NULL; NULL is allowed. */
LGN_EXPORT void LGNBodies_Destroy(LGNBodies *B);

/** Number of bodies (leaves of G); 0 for B = NULL. */
LGN_EXPORT int LGNBodies_NumBodies(LGNBodies B);

/**
 * Mark bodies first_ghost ... (the last) as ghosts: copies of other MPI
 * ranks' bodies that this rank's force elements (and joints) touch
 * (lignum_halo.h). A ghost has no mass, inertia or weight here (its
 * owner's rank counts them): its rows of M and g hold only what this
 * rank's force elements put on it, and it adds nothing to the energies
 * but through them. LGNBodies_SetMass and LGNBodies_SetPrincipalInertia
 * refuse ghosts. Calling it again with a larger first_ghost gives the
 * bodies that are no longer ghosts mass 1 and inertia I.
 * @param B           the body set
 * @param first_ghost the first ghost, 1 ... LGNBodies_NumBodies(B) (that
 *                    number: no ghosts)
 * @return LGN_SUCCESS or LGN_ILL_INPUT.
 */
LGN_EXPORT int LGNBodies_SetGhosts(LGNBodies B, int first_ghost);

/** Number of bodies that are not ghosts (all of them unless
 *  LGNBodies_SetGhosts was called); 0 for B = NULL. */
LGN_EXPORT int LGNBodies_NumOwnedBodies(LGNBodies B);

/**
 * Mass and inertia of body k.
 * @param B      the body set
 * @param k      the body (0-based leaf of the group)
 * @param m      mass, > 0
 * @param inertia 3x3 inertia about the centre of mass in body axes
 *               (row-major), symmetric (to 1e-12 relative), positive
 *               definite, and its principal moments satisfy the triangle
 *               inequality J_i <= J_j + J_k (to 1e-12 relative), as a rigid
 *               body's do
 * @return LGN_SUCCESS or LGN_ILL_INPUT.
 */
LGN_EXPORT int LGNBodies_SetMass(LGNBodies B, int k, sunrealtype m,
                                 const sunrealtype inertia[9]);

/** Mass m > 0 and principal moments J[3] > 0 of body k (body axes along
 *  the principal axes): inertia diag(J). The moments must satisfy the
 *  triangle inequality J_i <= J_j + J_k (equality, a plate, within
 *  round-off), as a rigid body's do. @return LGN_SUCCESS or LGN_ILL_INPUT. */
LGN_EXPORT int LGNBodies_SetPrincipalInertia(LGNBodies B, int k, sunrealtype m,
                                             const sunrealtype J[3]);

/** The acceleration of gravity (inertial), shared by all bodies; finite. */
LGN_EXPORT int LGNBodies_SetGravity(LGNBodies B, const sunrealtype gravity[3]);

/**
 * Translational spring-damper between point sa of body a and point sb of
 * body b (body frames; inertial for LGN_GROUND).
 * @param B     the body set
 * @param a, b  the bodies (0-based leaves, or LGN_GROUND), a != b
 * @param sa, sb the points in the bodies' frames
 * @param k, c  stiffness and damping, >= 0
 * @param L0    rest length, >= 0
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNBodies_AddSpringDamper(LGNBodies B, int a,
                                         const sunrealtype sa[3], int b,
                                         const sunrealtype sb[3], sunrealtype k,
                                         sunrealtype c, sunrealtype L0);

/**
 * Rotational spring-damper between bodies a and b (one may be LGN_GROUND,
 * a != b): torque -kr theta - cr omega_rel on b (and the reaction on a),
 * theta = log(R0^T R_a^T R_b) the rotation vector of b relative to its rest
 * orientation (see the top of this header).
 * @param B      the body set
 * @param a, b   the bodies (0-based leaves, or LGN_GROUND), a != b
 * @param kr, cr rotational stiffness and damping, >= 0
 * @param rest   the unit quaternion of the rest relative rotation
 *               R0 = R_a^T R_b (scalar first; |rest| = 1 to 1e-10, it is
 *               normalised), or NULL for R0 = I (rest when the body frames
 *               are aligned)
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNBodies_AddRotationalSpringDamper(LGNBodies B, int a, int b,
                                                   sunrealtype kr,
                                                   sunrealtype cr,
                                                   const sunrealtype rest[4]);

/** Number of stored entries of a sparse M: 12 per body (m on the
 *  translation diagonal, the full 3x3 inertia block). */
LGN_EXPORT sunindextype LGNBodies_MassNnz(LGNBodies B);

/** Number of stored entries of a sparse K_t or C_t: full 6x6 blocks
 *  (explicit zeros included) for every body's own block and for the pairs
 *  of bodies joined by a force element (both blocks (a, b) and (b, a)). */
LGN_EXPORT sunindextype LGNBodies_TangentNnz(LGNBodies B);

/** M (nv x nv), added (see "Matrices" at the top; LGNBodies_MassNnz). */
LGN_EXPORT int LGNBodies_Mass(LGNBodies B, N_Vector q, SUNMatrix M);

/** g = g(q, v) (length nv, overwritten): gyroscopic terms, gravity and the
 *  force elements, minus the applied forces. */
LGN_EXPORT int LGNBodies_Force(LGNBodies B, N_Vector q, N_Vector v, N_Vector g);

/** K = d/dq (M vdot + g) (nv x nv) along the group, added (see "Matrices"
 *  at the top; LGNBodies_TangentNnz). The joints' part d/dq (B^T lambda)
 *  is LGNJoints_Stiffness, added to the same K. */
LGN_EXPORT int LGNBodies_Stiffness(LGNBodies B, N_Vector q, N_Vector v,
                                   SUNMatrix K);

/** C = dg/dv (nv x nv), added (see "Matrices" at the top;
 *  LGNBodies_TangentNnz). */
LGN_EXPORT int LGNBodies_Damping(LGNBodies B, N_Vector q, N_Vector v,
                                 SUNMatrix C);

/**
 * Energies: kinetic (m |u|^2 + Omega . J Omega) / 2 summed over the bodies,
 * potential -m gvec . x summed over the bodies plus the springs'
 * potentials. Either pointer may be NULL.
 */
LGN_EXPORT int LGNBodies_Energy(LGNBodies B, N_Vector q, N_Vector v,
                                sunrealtype *kinetic, sunrealtype *potential);

/** An LGNMassFn with the body set as user_data: LGNBodies_Mass; returns 0,
 *  or -1 after reporting through the set's handler. */
LGN_EXPORT int LGNBodies_MassFn(sunrealtype t, N_Vector q, SUNMatrix M,
                                void *user_data);

/** An LGNForceFn with the body set as user_data: LGNBodies_Force. */
LGN_EXPORT int LGNBodies_ForceFn(sunrealtype t, N_Vector q, N_Vector v,
                                 N_Vector g, void *user_data);

/** An LGNStiffnessFn with the body set as user_data, for models without
 *  constraints (lambda is not read): LGNBodies_Stiffness. */
LGN_EXPORT int LGNBodies_StiffnessFn(sunrealtype t, N_Vector q, N_Vector v,
                                     N_Vector vdot, N_Vector lambda,
                                     SUNMatrix K, void *user_data);

/** An LGNDampingFn with the body set as user_data: LGNBodies_Damping. */
LGN_EXPORT int LGNBodies_DampingFn(sunrealtype t, N_Vector q, N_Vector v,
                                   SUNMatrix C, void *user_data);

#ifdef __cplusplus
}
#endif

#endif
