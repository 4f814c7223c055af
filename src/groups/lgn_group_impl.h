/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: what the integrator and the joint and body helpers may
 * know about the built-in groups beyond their public ops.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_GROUP_IMPL_H
#define LGN_GROUP_IMPL_H

#include <lignum/lignum_group.h>

/* The factors of a product group and their offsets in q and v (not copies).
 * Returns 0 when G is a product, -1 otherwise. */
int lgnGroupProductFactors(LGNGroup G, int *nf, const LGNGroup **factors,
                           const sunindextype **qoff, const sunindextype **voff);

/* The rigid bodies of G: its leaves in order, each R^3 x SO(3) or SE(3)
 * (a product of products is flattened). With qoff, voff and se3 not NULL
 * (room for the count), also each body's offsets in q and v and whether it
 * is an SE(3) body. Returns the count, or -1 if a leaf is another group.
 * Shared by the joint and the body helpers. */
int lgnGroupRigidBodies(LGNGroup G, sunindextype *qoff, sunindextype *voff,
                        sunbooleantype *se3);

/* The planar bodies of G (lignum_planar.h): its leaves in order, each
 * SE(2) or R^2 x SO(2), as lgnGroupRigidBodies (se2: an SE(2) body).
 * Returns the count, or -1 if a leaf is another group. */
int lgnGroupPlanarBodies(LGNGroup G, sunindextype *qoff, sunindextype *voff,
                         sunbooleantype *se2);

/* Fused operations of the built-in leaves for the exact kinematics
 * (lgn_tangent.c), one sine and cosine per rotation for all of them
 * (lgnSO3_CoefsExp). Each returns 1, doing nothing, when G is not that
 * built-in group with its own ops (a user replaced one): the caller then
 * uses the public ops.
 *
 * ExactMap: q1 = q o exp(w), v = T(w) wd, vdot = T(w) wdd + Tdot(w, wd) wd
 * and, with Tm not NULL, Tm = T(w) (nv x nv, leading dimension nv): bit for
 * bit what compose_exp, tangent_apply, tangent_dot_apply and
 * tangent_matrix give.
 *
 * ExactDerivatives: the normalised derivatives of v and vdot with respect
 * to the correction of w (lgnExactKinematicsDerivatives), in closed form,
 * with Tm = T(w) given: Tv = Tm + (D_w[T(w) wd])/gamma',
 * Ta = Tm + (gamma'/beta') (D_w[T(w) wd] + Tdot(w, wd))
 *         + (D_w[T(w) wdd] + D_w[Tdot(w, wd) wd])/beta'. */
int lgnGroupSO3ExactMap(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        const sunrealtype *wd, const sunrealtype *wdd,
                        sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                        sunrealtype *Tm);
int lgnGroupSO3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wd, const sunrealtype *wdd,
                                sunrealtype gamma_p, sunrealtype beta_p,
                                const sunrealtype *Tm, sunrealtype *Tv,
                                sunrealtype *Ta);
int lgnGroupR3xSO3ExactMap(LGNGroup G, const sunrealtype *q,
                           const sunrealtype *w, const sunrealtype *wd,
                           const sunrealtype *wdd, sunrealtype *q1,
                           sunrealtype *v, sunrealtype *vdot, sunrealtype *Tm);
int lgnGroupR3xSO3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                   const sunrealtype *wd,
                                   const sunrealtype *wdd, sunrealtype gamma_p,
                                   sunrealtype beta_p, const sunrealtype *Tm,
                                   sunrealtype *Tv, sunrealtype *Ta);
int lgnGroupSE3ExactMap(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        const sunrealtype *wd, const sunrealtype *wdd,
                        sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                        sunrealtype *Tm);
int lgnGroupSE3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wd, const sunrealtype *wdd,
                                sunrealtype gamma_p, sunrealtype beta_p,
                                const sunrealtype *Tm, sunrealtype *Tv,
                                sunrealtype *Ta);

#endif
