/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Planar mechanisms: the planar groups and the planar elements of the body
 * and joint sets.
 *
 * A planar body moves in the x-y plane: q = (x, y, theta), nq = nv = 3,
 * with the angle theta stored as a real number (it counts turns: the
 * logarithm of LGNGroup_ComposeLog is theta2 - theta1 without wrapping).
 *   SE(2):        v = (U body-fixed, omega), xdot = R(theta) U,
 *                 q o exp(U, omega) = (x + R(theta) V(omega) U, theta + omega)
 *   R^2 x SO(2):  v = (u inertial, omega), q o exp(w) = q + w, T = I
 * (doc/theory.md gives T, T^{-1} and Tdot of SE(2)). Near a nonzero
 * multiple of a full turn, omega = 2 pi n, SE(2)'s exp maps every U to
 * nearly the same point: its log and T^{-1} fail there (LGN_GROUP_FAIL from
 * LGNGroup_ComposeLog) where (sin(omega/2)/(omega/2))^2 < 1e-16; a step
 * never turns a body that far. Products of these
 * groups (LGNGroup_Product) hold several bodies.
 *
 * The body and joint sets of lignum_bodies.h and lignum_joints.h created on
 * a planar group (LGNBodies_Create(G), LGNJoints_Create(G)) are planar sets:
 * every evaluation (M, g, K_t, C_t, energies; Phi, B, B^T lambda, the
 * curvature, Phi_t, the geometric stiffness, the constraint descriptions;
 * dense and sparse) works on them. The settings take planar arguments:
 *   LGNBodies_SetPlanarMass (or LGNBodies_SetMass / SetPrincipalInertia,
 *     which use the inertia about z: inertia[8], J[2]);
 *   LGNBodies_SetGravity (gravity[2] must be 0);
 *   LGNBodies_AddPlanarSpringDamper (or LGNBodies_AddSpringDamper with
 *     points at z = 0);
 *   LGNBodies_AddPlanarRotationalSpringDamper (or the spatial one with a
 *     rest rotation about z, or NULL);
 *   LGNJoints_AddPlanarRevolute (or LGNJoints_AddRevolute with both axes
 *     along z and points at z = 0), LGNJoints_AddPlanarPrismatic,
 *     LGNJoints_AddPlanarRotationDriver, LGNJoints_AddPlanarTranslationDriver.
 * The other spatial joints and LGNBodies_SetGhosts are refused on a planar
 * set, and the planar functions on a spatial set, with LGN_ILL_INPUT.
 *
 * Rows and multipliers (p = x + R s a body point, s in body axes):
 *   revolute:    p_a - p_b = 0 (2 rows); lambda is the joint force on b
 *                (inertial), as for the spatial spherical joint
 *   prismatic:   (R_a n) . (p_b - p_a) = 0 with n perpendicular to axis_a
 *                (sb on the line through sa along axis_a), and
 *                theta_b - theta_a - theta0 = 0 (2 rows)
 *   rotation driver:    theta_b - theta_a - f(t) = 0 (1 row)
 *   translation driver: (R_a e) . (p_b - p_a) - f(t) = 0, e = axis_a/|axis_a|
 * Force elements (g holds minus the applied forces):
 *   spring-damper between points: tension k (L - L0) + c dL/dt;
 *   rotational spring-damper: torque -kr (theta_b - theta_a - theta0)
 *     - cr (omega_b - omega_a) on b, the reaction on a.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_PLANAR_H
#define LIGNUM_PLANAR_H

#include <lignum/lignum_bodies.h>
#include <lignum/lignum_export.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>

#ifdef __cplusplus
extern "C" {
#endif

/** SE(2): q = (x, y, theta), v = (U, omega) with U body-fixed (see the top
 *  of lignum_planar.h). @return the group, or NULL if allocation failed. */
LGN_EXPORT LGNGroup LGNGroup_SE2(void);

/** R^2 x SO(2): q = (x, y, theta), v = (u, omega) with u inertial;
 *  q o exp(w) = q + w and T = I. @return the group, or NULL if allocation
 *  failed. */
LGN_EXPORT LGNGroup LGNGroup_R2xSO2(void);

/**
 * Mass and moment of inertia of planar body k.
 * @param B the body set (on a planar group)
 * @param k the body (0-based)
 * @param m the mass, > 0
 * @param J the moment of inertia about the centre of mass (normal to the
 *          plane), > 0
 * @return LGN_SUCCESS or LGN_ILL_INPUT.
 */
LGN_EXPORT int LGNBodies_SetPlanarMass(LGNBodies B, int k, sunrealtype m, sunrealtype J);

/**
 * Translational spring-damper between point sa of planar body a and point
 * sb of body b (body frames; inertial for LGN_GROUND): tension k (L - L0)
 * + c dL/dt. Undefined at L = 0 (the evaluations refuse a vanishing length).
 * @param B     the body set (on a planar group)
 * @param a, b  the bodies (0-based, or LGN_GROUND), a != b
 * @param sa, sb the points (2-vectors)
 * @param k, c, L0 stiffness, damping, rest length, >= 0
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNBodies_AddPlanarSpringDamper(LGNBodies B, int a, const sunrealtype sa[2],
                                               int b, const sunrealtype sb[2],
                                               sunrealtype k, sunrealtype c,
                                               sunrealtype L0);

/**
 * Rotational spring-damper between planar bodies a and b (one may be
 * LGN_GROUND): torque -kr (theta_b - theta_a - theta0) - cr (omega_b -
 * omega_a) on b, the reaction on a; potential kr (theta_b - theta_a -
 * theta0)^2 / 2 (the angles count turns).
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNBodies_AddPlanarRotationalSpringDamper(LGNBodies B, int a, int b,
                                                         sunrealtype kr, sunrealtype cr,
                                                         sunrealtype theta0);

/**
 * Planar revolute joint: point sa of body a coincides with point sb of
 * body b (2 rows, p_a - p_b; lambda the joint force on b, inertial).
 * @param J     the joint set (on a planar group)
 * @param a, b  the bodies (0-based, or LGN_GROUND), a != b
 * @param sa, sb the points in the bodies' frames (2-vectors)
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPlanarRevolute(LGNJoints J, int a, const sunrealtype sa[2],
                                           int b, const sunrealtype sb[2]);

/**
 * Planar prismatic joint: point sb of body b slides on the line through
 * point sa of body a along axis_a (body a's frame, nonzero), and the
 * relative angle is locked, theta_b - theta_a = theta0 (2 rows).
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPlanarPrismatic(LGNJoints J, int a, const sunrealtype sa[2],
                                            const sunrealtype axis_a[2], int b,
                                            const sunrealtype sb[2], sunrealtype theta0);

/**
 * Planar rotation driver: theta_b - theta_a = f(t) (1 row; f from the time
 * law, lignum_joints.h). Give Lignum Phi_t with LGNJoints_TimeDerivative.
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPlanarRotationDriver(LGNJoints J, int a, int b, LGNDriveFn f,
                                                 void *drive_data);

/**
 * Planar translation driver: (R_a e) . (p_b - p_a) = f(t) with e =
 * axis_a / |axis_a| (body a's frame), p_a, p_b the points sa, sb (1 row).
 * @return LGN_SUCCESS, LGN_ILL_INPUT or LGN_MEM_FAIL.
 */
LGN_EXPORT int LGNJoints_AddPlanarTranslationDriver(LGNJoints J, int a,
                                                    const sunrealtype sa[2],
                                                    const sunrealtype axis_a[2], int b,
                                                    const sunrealtype sb[2], LGNDriveFn f,
                                                    void *drive_data);

#ifdef __cplusplus
}
#endif

#endif
