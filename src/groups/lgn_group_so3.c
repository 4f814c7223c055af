/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * SO(3) with unit-quaternion storage p = (w, x, y, z), body angular
 * velocity, q o exp(w) = p (x) expq(w) (renormalised), log(q1^{-1} q2) =
 * the rotation vector of conj(p1) (x) p2. Operators of doc/theory.md §1.1
 * through lgn_so3.h.
 * ---------------------------------------------------------------------------*/

#include <stddef.h>

#include "lgn_so3.h"
#include "lgn_group_impl.h"

static int SO3ComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                         sunrealtype *q_out)
{
  (void)G;
  lgnSO3_QuatComposeExp(q, w, q_out);
  return 0;
}

static int SO3ComposeLog(LGNGroup G, const sunrealtype *q1,
                         const sunrealtype *q2, sunrealtype *w)
{
  (void)G;
  return lgnSO3_QuatComposeLog(q1, q2, w);
}

static int SO3TangentApply(LGNGroup G, const sunrealtype *w,
                           const sunrealtype *x, sunrealtype *y)
{
  (void)G;
  lgnSO3_TApply(w, x, y);
  return 0;
}

static int SO3TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                  const sunrealtype *x, sunrealtype *y)
{
  (void)G;
  lgnSO3_TInvApply(w, x, y);
  return 0;
}

static int SO3TangentDotApply(LGNGroup G, const sunrealtype *w,
                              const sunrealtype *wdot, const sunrealtype *x,
                              sunrealtype *y)
{
  (void)G;
  lgnSO3_TDotApply(w, wdot, x, y);
  return 0;
}

static int SO3TangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                            sunindextype ld)
{
  (void)G;
  if (ld < 3) return -1;
  lgnSO3_TMatrix(w, Tm, ld);
  return 0;
}

static int SO3Identity(LGNGroup G, sunrealtype *q)
{
  (void)G;
  q[0] = 1;
  q[1] = q[2] = q[3] = 0;
  return 0;
}

static int SO3Normalize(LGNGroup G, sunrealtype *q)
{
  (void)G;
  return lgnSO3_QuatNormalize(q);
}

/* The library's own SO(3) ops (not replaced by the user)? */
static sunbooleantype OwnOps(LGNGroup G)
{
  return G->kind == LGN_GROUP_SO3 && G->ops.compose_exp == SO3ComposeExp &&
         G->ops.tangent_apply == SO3TangentApply &&
         G->ops.tangent_dot_apply == SO3TangentDotApply &&
         G->ops.tangent_matrix == SO3TangentMatrix;
}

int lgnGroupSO3ExactMap(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        const sunrealtype *wd, const sunrealtype *wdd,
                        sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                        sunrealtype *Tm)
{
  lgnSO3_Coef c;
  sunrealtype e[4], t[3];
  if (!OwnOps(G)) return 1;
  lgnSO3_CoefsExp(w, LGN_SO3_A | LGN_SO3_B | LGN_SO3_C1 | LGN_SO3_C2, &c, e);
  lgnSO3_QuatComposeQuat(q, e, q1);
  if (Tm != NULL) lgnSO3_TMatrixC(&c, w, Tm, 3);
  lgnSO3_TApplyC(&c, w, wd, v);
  lgnSO3_TApplyC(&c, w, wdd, vdot);
  lgnSO3_TDotApplyC(&c, w, wd, wd, t);
  vdot[0] += t[0];
  vdot[1] += t[1];
  vdot[2] += t[2];
  return 0;
}

int lgnGroupSO3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wd, const sunrealtype *wdd,
                                sunrealtype gamma_p, sunrealtype beta_p,
                                const sunrealtype *Tm, sunrealtype *Tv,
                                sunrealtype *Ta)
{
  lgnSO3_Coef c;
  if (!OwnOps(G)) return 1;
  lgnSO3_Coefs(lgnSO3_Norm(w), LGN_SO3_D2T, &c);
  lgnSO3_ExactBlocks(&c, w, wd, wdd, gamma_p, beta_p, Tm, Tv, Ta, 3);
  return 0;
}

LGNGroup LGNGroup_SO3(void)
{
  LGNGroup G = LGNGroup_NewEmpty(4, 3);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_SO3;
  G->ops.compose_exp           = SO3ComposeExp;
  G->ops.tangent_apply         = SO3TangentApply;
  G->ops.tangent_inverse_apply = SO3TangentInverseApply;
  G->ops.tangent_dot_apply     = SO3TangentDotApply;
  G->ops.tangent_matrix        = SO3TangentMatrix;
  G->ops.identity              = SO3Identity;
  G->ops.normalize             = SO3Normalize;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = SO3ComposeLog;
  return G;
}
