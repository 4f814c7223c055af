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
