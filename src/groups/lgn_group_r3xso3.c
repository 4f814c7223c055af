/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * R^3 x SO(3) (doc/theory.md §1.1): q = (x[3], p[4]), v = (u, Omega)
 * with u inertial and Omega body-fixed; q o exp(u, psi) = (x + u,
 * p (x) expq(psi)); log(q1^{-1} q2) = (x2 - x1, log(conj(p1) (x) p2));
 * T = diag(I3, T_SO3(psi)), Tdot = diag(0, Tdot_SO3).
 * ---------------------------------------------------------------------------*/

#include <stddef.h>

#include "lgn_so3.h"

static int R3SO3ComposeExp(LGNGroup G, const sunrealtype *q,
                           const sunrealtype *w, sunrealtype *q_out)
{
  (void)G;
  q_out[0] = q[0] + w[0];
  q_out[1] = q[1] + w[1];
  q_out[2] = q[2] + w[2];
  lgnSO3_QuatComposeExp(q + 3, w + 3, q_out + 3);
  return 0;
}

static int R3SO3ComposeLog(LGNGroup G, const sunrealtype *q1,
                           const sunrealtype *q2, sunrealtype *w)
{
  (void)G;
  w[0] = q2[0] - q1[0];
  w[1] = q2[1] - q1[1];
  w[2] = q2[2] - q1[2];
  return lgnSO3_QuatComposeLog(q1 + 3, q2 + 3, w + 3);
}

static int R3SO3TangentApply(LGNGroup G, const sunrealtype *w,
                             const sunrealtype *x, sunrealtype *y)
{
  (void)G;
  y[0] = x[0];
  y[1] = x[1];
  y[2] = x[2];
  lgnSO3_TApply(w + 3, x + 3, y + 3);
  return 0;
}

static int R3SO3TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                    const sunrealtype *x, sunrealtype *y)
{
  (void)G;
  y[0] = x[0];
  y[1] = x[1];
  y[2] = x[2];
  lgnSO3_TInvApply(w + 3, x + 3, y + 3);
  return 0;
}

static int R3SO3TangentDotApply(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wdot, const sunrealtype *x,
                                sunrealtype *y)
{
  (void)G;
  y[0] = y[1] = y[2] = 0;
  lgnSO3_TDotApply(w + 3, wdot + 3, x + 3, y + 3);
  return 0;
}

static int R3SO3TangentMatrix(LGNGroup G, const sunrealtype *w,
                              sunrealtype *Tm, sunindextype ld)
{
  int i, j;
  (void)G;
  if (ld < 6) return -1;
  /* identity and zero blocks, then T_SO3(psi) in the lower-right block */
  for (j = 0; j < 6; j++)
    for (i = 0; i < 6; i++) Tm[i + j * ld] = (i == j && i < 3) ? 1 : 0;
  lgnSO3_TMatrix(w + 3, Tm + 3 + 3 * ld, ld);
  return 0;
}

static int R3SO3Identity(LGNGroup G, sunrealtype *q)
{
  (void)G;
  q[0] = q[1] = q[2] = 0;
  q[3] = 1;
  q[4] = q[5] = q[6] = 0;
  return 0;
}

static int R3SO3Normalize(LGNGroup G, sunrealtype *q)
{
  (void)G;
  return lgnSO3_QuatNormalize(q + 3);
}

LGNGroup LGNGroup_R3xSO3(void)
{
  LGNGroup G = LGNGroup_NewEmpty(7, 6);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_R3XSO3;
  G->ops.compose_exp           = R3SO3ComposeExp;
  G->ops.tangent_apply         = R3SO3TangentApply;
  G->ops.tangent_inverse_apply = R3SO3TangentInverseApply;
  G->ops.tangent_dot_apply     = R3SO3TangentDotApply;
  G->ops.tangent_matrix        = R3SO3TangentMatrix;
  G->ops.identity              = R3SO3Identity;
  G->ops.normalize             = R3SO3Normalize;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = R3SO3ComposeLog;
  return G;
}
