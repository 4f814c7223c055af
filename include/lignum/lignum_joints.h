/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Joint constraints between rigid bodies, ready to call from the constraint
 * callbacks: Phi(q), B(q) (dense or sparse, with its pattern), the
 * constraint forces B(q)^T lambda, the curvature term Z(q)(v, v) of the
 * consistent initial values, and the geometric stiffness
 * d/dq (B(q)^T lambda) for an analytic K_t.
 *
 * The bodies are the leaves of the configuration group: a single R^3 x SO(3)
 * or SE(3) factor, or a product of them (body k = factor k, products of
 * products flattened in order). Body points and axes are given in the body
 * frame; for LGN_GROUND they are fixed inertial vectors. B is the derivative
 * along the group, B(q) w = d/de Phi(q o exp(e w)) at e = 0
 * (doc/theory.md): with R^3 x SO(3), dx = w_x and dR = R w_theta~; with
 * SE(3), dx = R w_U.
 *
 *   spherical:  x_a + R_a s_a - x_b - R_b s_b = 0                     (3 rows)
 *   revolute:   spherical and (R_a e_i) . (R_b c) = 0, i = 1, 2, with
 *               e_1, e_2 perpendicular to axis_a, c = axis_b          (5 rows)
 *   universal:  spherical and (R_a axis_a) . (R_b axis_b) = 0         (4 rows)
 *   prismatic:  relative rotation locked, R_a^T R_b = R0 (3 rows), and
 *               (R_a e_i) . (p_b - p_a) = 0, i = 1, 2 (p = x + R s, e_i
 *               perpendicular to axis_a: sb on the line through sa along
 *               axis_a)                                               (5 rows)
 *   cylindrical: axes parallel as in the revolute joint (2 rows) and sb on
 *               the line as in the prismatic joint (2 rows)           (4 rows)
 *   rotation driver: the angle theta of body b about axis_a of body a is
 *               f(t): (R_a e(t)) . (R_b c) = sin(theta - f(t))        (1 row)
 *   translation driver: (R_a n) . (p_b - p_a) - f(t), n = axis_a    (1 row)
 *
 * Drivers (prescribed motion) make Phi depend on t: every evaluation takes
 * the time t of the callback it is called from, and a model with drivers
 * gives Lignum Phi_t with LGNJoints_TimeDerivative (LGNSetConstraintTimeFn);
 * LGNJoints_Curvature includes their time terms. Without drivers t is not
 * used.
 *
 * A joint set keeps workspace for its evaluations (the bodies' rotations, the
 * pattern of the sparse B): evaluate one set from one thread at a time.
 *
 * Errors: the functions returning a flag return LGN_SUCCESS, LGN_ILL_INPUT
 * (bad argument, named in the message) or LGN_MEM_FAIL, and report the
 * failure through the joint set's own error handler (stderr by default;
 * LGNJoints_SetErrHandlerFn, LGNJoints_SetErrFile). A joint set does not
 * refer to any integrator memory. With J = NULL there is no handler to find:
 * the message goes to stderr.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_JOINTS_H
#define LIGNUM_JOINTS_H

#include <lignum/lignum.h>
#include <lignum/lignum_export.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Body index of the fixed inertial frame. */
#define LGN_GROUND (-1)

/** A set of joints between the bodies of one configuration group. */
typedef struct LGNJointsRec *LGNJoints;

/** Time law of a driver: f[0] = f(t), f[1] = f'(t), f[2] = f''(t) (radians
 *  or lengths and their rates). Return 0 on success, nonzero on failure
 *  (the evaluation then fails with LGN_CONSTR_FAIL); the values must be
 *  finite. */
typedef int (*LGNDriveFn)(sunrealtype t, sunrealtype f[3], void *drive_data);

/**
 * Create an empty joint set for the bodies of G. The set reports bad input
 * of every LGNJoints function itself, through its own error handler
 * (LGNJoints_SetErrHandlerFn, LGNJoints_SetErrFile; default: stderr, in the
 * format of the integrator's messages). It holds no integrator memory, so
 * it may outlive any integrator it is used with.
 * @param G R^3 x SO(3), SE(3) or a product of them; referenced, must
 *          outlive the joint set
 * @return the joint set, or NULL (message on stderr) if G is NULL, has
 *         another leaf group, or memory ran out.
 */
LGN_EXPORT LGNJoints LGNJoints_Create(LGNGroup G);

/**
 * Replace the error handler of a joint set (NULL restores the default,
 * which writes to the stream of LGNJoints_SetErrFile). The handler gets the
 * public function that failed (e.g. "LGNJoints_AddSpherical") and a
 * message naming the bad argument.
 * @return LGN_SUCCESS, or LGN_ILL_INPUT if J is NULL (message on stderr).
 */
LGN_EXPORT int LGNJoints_SetErrHandlerFn(LGNJoints J, LGNErrHandlerFn ehfun, void *eh_data);

/**
 * Set the stream of the joint set's default error handler (stderr at
 * creation; NULL silences it). Not used while a handler of
 * LGNJoints_SetErrHandlerFn is set.
 * @return LGN_SUCCESS, or LGN_ILL_INPUT if J is NULL (message on stderr).
 */
LGN_EXPORT int LGNJoints_SetErrFile(LGNJoints J, FILE *errfp);

/** Free a joint set and set *J to NULL; NULL is allowed. */
LGN_EXPORT void LGNJoints_Destroy(LGNJoints *J);

/** Number of bodies (leaves of G); 0 for J = NULL. */
LGN_EXPORT int LGNJoints_NumBodies(LGNJoints J);

/**
 * Spherical joint: point sa of body a coincides with point sb of body b.
 * Its three multipliers lambda are the joint force in the inertial frame
 * acting on body b (body a feels -lambda); doc/conventions.md gives the
 * signs of every joint.
 * @param J     the joint set
 * @param a, b  body indices (0-based leaves of G) or LGN_GROUND, a != b
 * @param sa, sb points in the body frames (inertial for LGN_GROUND)
 * @return LGN_SUCCESS, LGN_ILL_INPUT (bad body index or NULL point) or
 *         LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddSpherical(LGNJoints J, int a,
                                      const sunrealtype sa[3], int b,
                                      const sunrealtype sb[3]);

/** Revolute joint: spherical at (sa, sb) and body axes axis_a, axis_b
 *  (nonzero, need not be unit) kept parallel. Five constraints. */
LGN_EXPORT int LGNJoints_AddRevolute(LGNJoints J, int a,
                                     const sunrealtype sa[3],
                                     const sunrealtype axis_a[3], int b,
                                     const sunrealtype sb[3],
                                     const sunrealtype axis_b[3]);

/** Universal (Cardan) joint: spherical at (sa, sb) and body axes axis_a,
 *  axis_b kept perpendicular (they must be perpendicular in the initial
 *  configuration for it to be satisfied). Four constraints. */
LGN_EXPORT int LGNJoints_AddUniversal(LGNJoints J, int a,
                                      const sunrealtype sa[3],
                                      const sunrealtype axis_a[3], int b,
                                      const sunrealtype sb[3],
                                      const sunrealtype axis_b[3]);

/**
 * Prismatic (sliding) joint: point sb of body b stays on the line through
 * point sa of body a along axis_a, and the relative rotation is locked at
 * R_a^T R_b = R0, the smallest rotation taking axis_b to axis_a (the
 * identity when axis_b = axis_a: the body frames keep the relative
 * orientation they have when aligned). Rows: (R_a R0 d_1).(R_b c),
 * (R_a R0 d_2).(R_b c), (R_a R0 d_1).(R_b d_2) with c = axis_b / |axis_b|
 * and d_1, d_2 perpendicular to it, then (R_a R0 d_i).(p_b - p_a), i = 1, 2.
 * Five constraints; the configuration must satisfy them at the start.
 * @param J     the joint set
 * @param a, b  the bodies (0-based leaves of G, or LGN_GROUND), a != b
 * @param sa, sb points in the body frames (inertial for LGN_GROUND)
 * @param axis_a, axis_b nonzero (need not be unit)
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPrismatic(LGNJoints J, int a,
                                      const sunrealtype sa[3],
                                      const sunrealtype axis_a[3], int b,
                                      const sunrealtype sb[3],
                                      const sunrealtype axis_b[3]);

/**
 * Cylindrical joint: axis_a and axis_b kept parallel (the revolute joint's
 * two rows) and point sb of body b on the line through sa along axis_a
 * (the prismatic joint's two rows): rotation about and sliding along the
 * axis are free. Four constraints.
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddCylindrical(LGNJoints J, int a,
                                        const sunrealtype sa[3],
                                        const sunrealtype axis_a[3], int b,
                                        const sunrealtype sb[3],
                                        const sunrealtype axis_b[3]);

/**
 * Prismatic joint with the locked relative rotation given by two joint
 * frames: the frame [axis_a, ref_a, axis_a x ref_a] of body a and the frame
 * [axis_b, ref_b, axis_b x ref_b] of body b stay aligned (R_a^T R_b = R0
 * with R0 axis_b = axis_a and R0 ref_b = ref_a), and point sb of body b stays
 * on the line through sa along axis_a. The same five rows as
 * LGNJoints_AddPrismatic, which picks R0 itself (the smallest rotation
 * taking axis_b to axis_a).
 * @param J     the joint set
 * @param a, b  the bodies (0-based leaves of G, or LGN_GROUND), a != b
 * @param sa, sb points in the body frames (inertial for LGN_GROUND)
 * @param axis_a, axis_b the sliding axis in each body, nonzero
 * @param ref_a, ref_b a direction in each body not parallel to its axis
 *              (its part perpendicular to the axis is used)
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPrismaticFrames(LGNJoints J, int a,
                                            const sunrealtype sa[3],
                                            const sunrealtype axis_a[3],
                                            const sunrealtype ref_a[3], int b,
                                            const sunrealtype sb[3],
                                            const sunrealtype axis_b[3],
                                            const sunrealtype ref_b[3]);

/**
 * Rotation driver: the angle theta of body b relative to body a about
 * axis_a is prescribed, theta = f(t). theta is measured in a's frame from
 * ref_a to the direction ref_b of body b, positive about axis_a. One row,
 *   Phi = (R_a e(t)) . (R_b c),  e(t) = cos f (n x r) - sin f r,
 * with n = axis_a, r = ref_a (its part perpendicular to n) and c = ref_b,
 * all normalised: Phi = sin(theta - f(t)) when c is perpendicular to the
 * axis. Use it with a revolute joint about the same axis (a motor).
 * Phi also vanishes at theta = f + pi: start within a quarter turn of
 * f(t0) (Newton then stays on theta = f as long as the steps do not turn
 * the body by a quarter turn, which error control ensures).
 * @param J      the joint set
 * @param a, b   the bodies (0-based leaves of G, or LGN_GROUND), a != b
 * @param axis_a the axis in body a, nonzero
 * @param ref_a  the zero-angle direction in body a, not parallel to axis_a
 * @param ref_b  the direction of body b whose angle is prescribed
 * @param f      the time law (LGNDriveFn), not NULL
 * @param drive_data passed to f
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddRotationDriver(LGNJoints J, int a,
                                           const sunrealtype axis_a[3],
                                           const sunrealtype ref_a[3], int b,
                                           const sunrealtype ref_b[3],
                                           LGNDriveFn f, void *drive_data);

/**
 * Translation driver: the distance of point sb of body b from point sa of
 * body a along axis_a is prescribed: (R_a n) . (p_b - p_a) = f(t), with
 * n = axis_a / |axis_a| and p = x + R s. One row. Use it with a prismatic
 * or cylindrical joint along the same axis (an actuator).
 * @param J      the joint set
 * @param a, b   the bodies (0-based leaves of G, or LGN_GROUND), a != b
 * @param sa, sb points in the body frames (inertial for LGN_GROUND)
 * @param axis_a the axis in body a, nonzero
 * @param f      the time law (LGNDriveFn), not NULL
 * @param drive_data passed to f
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddTranslationDriver(LGNJoints J, int a,
                                              const sunrealtype sa[3],
                                              const sunrealtype axis_a[3], int b,
                                              const sunrealtype sb[3],
                                              LGNDriveFn f, void *drive_data);

/** Number of drivers in the set (0 for J = NULL). With drivers, give Lignum
 *  Phi_t (LGNSetConstraintTimeFn with LGNJoints_TimeDerivative). */
LGN_EXPORT int LGNJoints_NumDrivers(LGNJoints J);

/**
 * Describe constraint row `row` (0-based, as in Phi and B and in
 * LGNGetRedundantConstraints): its joint, kind and bodies, e.g.
 * "revolute joint 2 (body 1 - body 2), its constraint 4 of 5".
 * @param J         the joint set
 * @param row       the constraint row
 * @param buf, len  the text (truncated to len - 1 characters)
 * @return LGN_SUCCESS, or LGN_ILL_INPUT (J NULL, buf NULL, len 0, row out
 *         of range).
 */
LGN_EXPORT int LGNJoints_DescribeConstraint(LGNJoints J, sunindextype row,
                                            char *buf, size_t len);

/** Number of constraints m of all joints added so far (rows of Phi and B). */
LGN_EXPORT sunindextype LGNJoints_NumConstraints(LGNJoints J);

/** Number of stored entries of the sparse B written by LGNJoints_Jacobian
 *  (explicit zeros included; the pattern does not depend on q). A point
 *  row stores 6 entries at an SE(3) body and 4 at an R^3 x SO(3) body,
 *  whose translation part is +-I; a perpendicularity row 3 per body, a
 *  point-on-line row (prismatic, cylindrical) 6 per body. */
LGN_EXPORT sunindextype LGNJoints_JacobianNnz(LGNJoints J);

/** Number of stored entries of the sparse K written by LGNJoints_Stiffness. */
LGN_EXPORT sunindextype LGNJoints_StiffnessNnz(LGNJoints J);

/** phi = Phi(q, t), length m. For use in an LGNConstrFn (t is used by
 *  drivers only). Returns LGN_SUCCESS, LGN_ILL_INPUT, or LGN_CONSTR_FAIL
 *  when a driver's time law fails. */
LGN_EXPORT int LGNJoints_Residual(LGNJoints J, sunrealtype t, N_Vector q,
                                  N_Vector phi);

/**
 * B = B(q, t), m x nv (t is used by rotation drivers only). A dense B is overwritten entry by entry (entries outside
 * the joints' columns are left alone, so zero it first: Lignum does before
 * calling an LGNConstrJacFn). A sparse B (CSC or CSR) is overwritten with
 * the whole pattern, reallocated if it has fewer than
 * LGNJoints_JacobianNnz(J) entries. The pattern is built on the first sparse
 * call and kept in J (built again after a joint is added or when B's format
 * differs from the last one); every call copies it into B and writes the
 * values in place.
 */
LGN_EXPORT int LGNJoints_Jacobian(LGNJoints J, sunrealtype t, N_Vector q,
                                  SUNMatrix B);

/**
 * f = B(q)^T lambda, length nv: the joints' constraint forces, without
 * forming B. For use in an LGNConstrForceFn. f is overwritten entirely:
 * the entries of bodies in no joint become 0. Equals B(q)^T lambda of
 * LGNJoints_Jacobian to round-off. With no joints (m = 0), lambda is not
 * read and f = 0. The joint forces and motor torques at an output of
 * LGNSolve: t, q as returned and lambda from LGNGetMultipliers (by default
 * the consistent multipliers at that (t, q, v), LGNSetConsistentOutputs),
 * so that M vdot + g + f = 0 holds there with vdot from
 * LGNGetAcceleration: the joints act on the bodies with -f (a driver's
 * body b feels -lambda_i times its axis: lambda_i is minus the motor
 * torque or actuator force, doc/conventions.md).
 */
LGN_EXPORT int LGNJoints_ConstraintForce(LGNJoints J, sunrealtype t,
                                         N_Vector q, N_Vector lambda,
                                         N_Vector f);

/** z = d/dt(B v + Phi_t) - B vdot, length m: without drivers
 *  Z(q)(v, v) = D_q(B(q) v).(q v~), i.e. d/dt(B v) = B vdot + Z(q)(v, v)
 *  (doc/theory.md); a driver adds its time terms. The curvature term of the
 *  consistent initial accelerations (LGNCurvatureFn). */
LGN_EXPORT int LGNJoints_Curvature(LGNJoints J, sunrealtype t, N_Vector q,
                                   N_Vector v, N_Vector z);

/** phit = dPhi/dt(q, t) at fixed q, length m: -f'(t) in a translation
 *  driver's row, (R_a e'(t)) . (R_b c) in a rotation driver's, 0 in the
 *  joints' rows. For an LGNConstrTimeFn (LGNSetConstraintTimeFn). */
LGN_EXPORT int LGNJoints_TimeDerivative(LGNJoints J, sunrealtype t, N_Vector q,
                                        N_Vector phit);

/**
 * K = d/dq (B(q)^T lambda), nv x nv: the joints' part of the tangent
 * stiffness K_t (the geometric stiffness), ADDED to what K holds, dense or
 * sparse, by the body helpers' rule (lignum_bodies.h, "Matrices"), so that
 * this and LGNBodies_Stiffness sum in one K in either order. Its sparse
 * pattern: the blocks of the bodies and
 * of pairs coupled by a revolute, universal, prismatic or cylindrical
 * joint, in their rotation columns only (B^T lambda of the point and
 * perpendicularity rows does not depend on the translations) and their
 * rotation rows, plus the translation rows of an SE(3) body's own block;
 * a block with a body in a prismatic or cylindrical joint is stored whole
 * (6 x 6: the point-on-line rows depend on the translations).
 */
LGN_EXPORT int LGNJoints_Stiffness(LGNJoints J, sunrealtype t, N_Vector q,
                                   N_Vector lambda, SUNMatrix K);

/**
 * A contact of point s of body b (body frame) with the plane n . p = d
 * (inertial; n need not be unit: the gap is then scaled by |n|), for the
 * contact rows G of LGNApplyImpact: *gap = n . (x_b + R_b s) - d (> 0:
 * apart) and row (length nv, overwritten) its derivative along the group,
 * zero except at body b's six velocities: [n^T P, (s x R_b^T n)^T] with
 * P = I on R^3 x SO(3), R_b on SE(3). Copy the row into a dense or sparse
 * G; a root function of LGNRootInit can return *gap.
 * @return LGN_SUCCESS, LGN_ILL_INPUT (bad body, NULL or non-finite
 *         argument, n = 0, q of the wrong length).
 */
LGN_EXPORT int LGNJoints_PointPlaneContact(LGNJoints J, N_Vector q, int b,
                                           const sunrealtype s[3],
                                           const sunrealtype n[3], sunrealtype d,
                                           sunrealtype *gap, sunrealtype *row);

#ifdef __cplusplus
}
#endif

#endif
