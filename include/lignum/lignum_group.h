/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The Lie group object LGNGroup: a configuration space G with its Lie algebra
 * identified with R^nv, carried around like an N_Vector carries its ops.
 *
 * Conventions (doc/theory.md, doc/conventions.md):
 *  - velocities are left-invariant (body-fixed), exp is composed on the RIGHT:
 *    q_{n+1} = q_n o exp(w);
 *  - T(w) = sum_i (-1)^i/(i+1)! ad(w)^i  (= dexp_{-w}), so that
 *    d/dt exp(w(t)) = exp(w(t)) (T(w) wdot)~ ;
 *  - Tdot(w, wdot) = d/dt T(w(t)) for w' = wdot.
 *
 * Storage of group elements (nq reals each):
 *  - R^n:        q = (x_1..x_n),            nq = nv = n;
 *  - SO(3):      q = unit quaternion (w, x, y, z) with scalar first, nq = 4,
 *                nv = 3 (body angular velocity);
 *  - R^3xSO(3):  q = (x[3], p[4]),          nq = 7, nv = 6 (u inertial, Omega body);
 *  - products:   the factors' coordinates concatenated in order.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_GROUP_H
#define LIGNUM_GROUP_H

#include <stdio.h>
#include <sundials/sundials_types.h>

#include <lignum/lignum_export.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct LGNGroupRec *LGNGroup;

/** Group kinds of the built-in groups; LGN_GROUP_CUSTOM for user-supplied ones.
 *  LGN_GROUP_SE2 and LGN_GROUP_R2XSO2 are the planar groups (lignum_planar.h). */
typedef enum {
  LGN_GROUP_CUSTOM = 0,
  LGN_GROUP_RN,
  LGN_GROUP_SO3,
  LGN_GROUP_R3XSO3,
  LGN_GROUP_SE3,
  LGN_GROUP_PRODUCT,
  LGN_GROUP_SE2,
  LGN_GROUP_R2XSO2
} LGNGroupKind;

/**
 * Operations of a Lie group. All arrays are plain contiguous sunrealtype
 * arrays; matrices are dense column-major with leading dimension ld.
 * Every op returns 0 on success and a nonzero value on failure (custom groups).
 */
typedef struct LGNGroupOpsRec {
  /** q_out = q o exp(w); q_out may alias q. */
  int (*compose_exp)(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                     sunrealtype *q_out);
  /** y = T(w) x; y may not alias x. */
  int (*tangent_apply)(LGNGroup G, const sunrealtype *w, const sunrealtype *x,
                       sunrealtype *y);
  /** y = T(w)^{-1} x; y may not alias x. */
  int (*tangent_inverse_apply)(LGNGroup G, const sunrealtype *w,
                               const sunrealtype *x, sunrealtype *y);
  /** y = Tdot(w, wdot) x; y may not alias x. */
  int (*tangent_dot_apply)(LGNGroup G, const sunrealtype *w,
                           const sunrealtype *wdot, const sunrealtype *x,
                           sunrealtype *y);
  /** Tm = T(w), written as a dense nv x nv block (column-major, leading
   *  dimension ld). Entries outside the nonzero pattern are set to zero. */
  int (*tangent_matrix)(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                        sunindextype ld);
  /** q = identity element. */
  int (*identity)(LGNGroup G, sunrealtype *q);
  /** Project q back onto the group (e.g. renormalise a quaternion). May be NULL. */
  int (*normalize)(LGNGroup G, sunrealtype *q);
  /** Free the content (not the LGNGroup itself). May be NULL. */
  void (*free_content)(LGNGroup G);
  /** w = log(q1^{-1} q2) in R^nv, the inverse of compose_exp:
   *  q1 o exp(w) = q2 (for SO(3) parts the rotation vector with angle in
   *  [0, pi]). w may not alias q1 or q2. May be NULL in a user-supplied
   *  group; then LGNGroup_ComposeLog reports LGN_ILL_INPUT. (Last in the
   *  record so that the earlier fields keep their offsets.) */
  int (*compose_log)(LGNGroup G, const sunrealtype *q1, const sunrealtype *q2,
                     sunrealtype *w);
} *LGNGroupOps;

/** The group object. Built-in constructors fill it; a user-supplied group
 *  is made with LGNGroup_NewEmpty and its ops filled in by the user. */
struct LGNGroupRec {
  LGNGroupKind kind;    /**< which built-in group, or LGN_GROUP_CUSTOM   */
  sunindextype nq;      /**< number of reals storing one group element    */
  sunindextype nv;      /**< dimension of the Lie algebra (velocity size) */
  void *content;        /**< implementation data                          */
  struct LGNGroupOpsRec ops;
};

/* -------------------------------------------------------------------------
 * Constructors and destructor
 * ---------------------------------------------------------------------- */

/** Vector space R^n as an (additive) Lie group: exp(w) = w, T = I, Tdot = 0.
 *  @return the group, or NULL if n < 1 or allocation failed. */
LGN_EXPORT LGNGroup LGNGroup_Rn(sunindextype n);

/** SO(3) with unit-quaternion storage (w, x, y, z). */
LGN_EXPORT LGNGroup LGNGroup_SO3(void);

/** R^3 x SO(3): q = (x, p), v = (u, Omega) with u inertial and Omega body-fixed. */
LGN_EXPORT LGNGroup LGNGroup_R3xSO3(void);

/** SE(3): q = (x, p), v = (U, Omega), both body-fixed; xdot = R U.
 *  q o exp(U, Omega) = (x + R(p) T_SO3(Omega)^T U, p * expq(Omega)); in the
 *  ordering (U, Omega), T = [[T_SO3(Omega), Tdot_SO3(Omega, U)],
 *  [0, T_SO3(Omega)]], with T^{-1} and Tdot in closed form (doc/theory.md).
 *  @return the group, or NULL if allocation failed. */
LGN_EXPORT LGNGroup LGNGroup_SE3(void);

/**
 * Direct product G_1 x ... x G_n. The factors are referenced, not copied or
 * owned: they must outlive the product, and the same factor may appear
 * several times (e.g. a chain of identical bodies).
 * @param nfactors number of factors (>= 1)
 * @param factors  array of nfactors groups
 * @return the product group, or NULL on bad input or allocation failure.
 */
LGN_EXPORT LGNGroup LGNGroup_Product(int nfactors, const LGNGroup *factors);

/** A group with dimensions set and all ops NULL, for user-supplied groups. */
LGN_EXPORT LGNGroup LGNGroup_NewEmpty(sunindextype nq, sunindextype nv);

/** Free a group made by any constructor above; NULL is allowed. */
LGN_EXPORT void LGNGroup_Destroy(LGNGroup G);

/* -------------------------------------------------------------------------
 * Dispatchers (call the op, return its flag; -1 if the op is missing;
 * LGNGroup_ComposeLog checks its arguments and returns LGN_* flags)
 * ---------------------------------------------------------------------- */

/** q_out = q o exp(w). */
LGN_EXPORT int LGNGroup_ComposeExp(LGNGroup G, const sunrealtype *q,
                                   const sunrealtype *w, sunrealtype *q_out);
/**
 * The local chart at q1: w = log(q1^{-1} q2) in R^nv, the inverse of
 * LGNGroup_ComposeExp (q1 o exp(w) = q2 and log(q1^{-1} (q1 o exp(w))) = w
 * while every rotation angle of w is below pi).
 *
 * Per built-in group (doc/theory.md §1.1): R^n: w = q2 - q1; SO(3): the
 * rotation vector of conj(p1) (x) p2, angle in [0, pi], the same for p2
 * and -p2 (at angle pi the vector whose first nonzero entry is positive);
 * R^3 x SO(3): (x2 - x1, SO(3) part); SE(3): Omega as for SO(3) and
 * U = T_SO3(Omega)^{-T} R(p1)^T (x2 - x1), inverting compose_exp's
 * x + R T_SO3(Omega)^T U; products: factor by factor. Quaternions need not
 * be exactly unit (the log of p/|p| is taken). Small angles keep their
 * relative accuracy (tiny or zero angles included) when q1's rotation is
 * exact, e.g. the identity; otherwise the rounding of q1 and q2 limits w
 * to an absolute accuracy of a few eps.
 *
 * Derivative: d/de log(q1^{-1} q2 o exp(e d)) at e = 0 is T(w)^{-1} d.
 *
 * @param G  the group
 * @param q1 the base point (nq reals)
 * @param q2 the point to chart (nq reals)
 * @param w  out: nv reals; must not alias q1 or q2
 * @return LGN_SUCCESS; LGN_ILL_INPUT (G, q1, q2 or w NULL, or the group has
 *         no compose_log op: a user-supplied group that did not set it);
 *         LGN_GROUP_FAIL (the op failed: for a built-in group a zero or
 *         not finite quaternion, or a product factor without the op).
 *         Errors are reported, naming the argument or the op, on stderr
 *         (a group has no error handler of its own). Unlike the other
 *         dispatchers it returns these flags, not -1 or the op's flag.
 */
LGN_EXPORT int LGNGroup_ComposeLog(LGNGroup G, const sunrealtype *q1,
                                   const sunrealtype *q2, sunrealtype *w);
/** y = T(w) x. */
LGN_EXPORT int LGNGroup_TangentApply(LGNGroup G, const sunrealtype *w,
                                     const sunrealtype *x, sunrealtype *y);
/** y = T(w)^{-1} x. */
LGN_EXPORT int LGNGroup_TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                            const sunrealtype *x,
                                            sunrealtype *y);
/** y = Tdot(w, wdot) x. */
LGN_EXPORT int LGNGroup_TangentDotApply(LGNGroup G, const sunrealtype *w,
                                        const sunrealtype *wdot,
                                        const sunrealtype *x, sunrealtype *y);
/** Tm = T(w) as a dense column-major nv x nv matrix with leading dimension ld.
 *  Returns -1 (without calling the op) if ld < nv. */
LGN_EXPORT int LGNGroup_TangentMatrix(LGNGroup G, const sunrealtype *w,
                                      sunrealtype *Tm, sunindextype ld);
/** q = identity element. */
LGN_EXPORT int LGNGroup_Identity(LGNGroup G, sunrealtype *q);
/** Project q onto the group (no-op when the group has no normalize op). */
LGN_EXPORT int LGNGroup_Normalize(LGNGroup G, sunrealtype *q);

/* -------------------------------------------------------------------------
 * Rotation helpers for model code (quaternion p = (w, x, y, z))
 * ---------------------------------------------------------------------- */

/** R (row-major 3x3, R[3*i+j]) of the unit quaternion p. */
LGN_EXPORT void LGNQuaternionToRotation(const sunrealtype p[4],
                                        sunrealtype R[9]);

/** Unit quaternion p = exp of the rotation vector phi (numerically safe). */
LGN_EXPORT void LGNQuaternionFromRotationVector(const sunrealtype phi[3],
                                                sunrealtype p[4]);

/** Rotation vector phi = log(p), |phi| <= pi (numerically safe). */
LGN_EXPORT void LGNRotationVectorFromQuaternion(const sunrealtype p[4],
                                                sunrealtype phi[3]);

/** r = p1 * p2 (Hamilton product). r may alias p1 or p2. */
LGN_EXPORT void LGNQuaternionMultiply(const sunrealtype p1[4],
                                      const sunrealtype p2[4],
                                      sunrealtype r[4]);

#ifdef __cplusplus
}
#endif

#endif
