/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The vector space R^n as an additive Lie group (doc/theory.md §1.1):
 * q o exp(w) = q + w, log(q1^{-1} q2) = q2 - q1, T = T^{-1} = I, Tdot = 0.
 * No content: n = G->nv.
 * ---------------------------------------------------------------------------*/

#include <stddef.h>

#include "lgn_so3.h"

/* q_out = q + w (q_out may alias q) */
static int RnComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        sunrealtype *q_out)
{
  sunindextype i;
  for (i = 0; i < G->nv; i++) q_out[i] = q[i] + w[i];
  return 0;
}

/* w = q2 - q1 */
static int RnComposeLog(LGNGroup G, const sunrealtype *q1,
                        const sunrealtype *q2, sunrealtype *w)
{
  sunindextype i;
  for (i = 0; i < G->nv; i++) w[i] = q2[i] - q1[i];
  return 0;
}

/* y = T(w) x = x, also used for T^{-1} */
static int RnTangentApply(LGNGroup G, const sunrealtype *w,
                          const sunrealtype *x, sunrealtype *y)
{
  sunindextype i;
  (void)w;
  for (i = 0; i < G->nv; i++) y[i] = x[i];
  return 0;
}

/* y = Tdot x = 0 */
static int RnTangentDotApply(LGNGroup G, const sunrealtype *w,
                             const sunrealtype *wdot, const sunrealtype *x,
                             sunrealtype *y)
{
  sunindextype i;
  (void)w;
  (void)wdot;
  (void)x;
  for (i = 0; i < G->nv; i++) y[i] = 0;
  return 0;
}

/* Tm = I */
static int RnTangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                           sunindextype ld)
{
  sunindextype i, j;
  (void)w;
  if (ld < G->nv) return -1;
  for (j = 0; j < G->nv; j++)
    for (i = 0; i < G->nv; i++) Tm[i + j * ld] = (i == j) ? 1 : 0;
  return 0;
}

static int RnIdentity(LGNGroup G, sunrealtype *q)
{
  sunindextype i;
  for (i = 0; i < G->nq; i++) q[i] = 0;
  return 0;
}

LGNGroup LGNGroup_Rn(sunindextype n)
{
  LGNGroup G = LGNGroup_NewEmpty(n, n);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_RN;
  G->ops.compose_exp           = RnComposeExp;
  G->ops.tangent_apply         = RnTangentApply;
  G->ops.tangent_inverse_apply = RnTangentApply;
  G->ops.tangent_dot_apply     = RnTangentDotApply;
  G->ops.tangent_matrix        = RnTangentMatrix;
  G->ops.identity              = RnIdentity;
  G->ops.normalize             = NULL;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = RnComposeLog;
  return G;
}
