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
#include "lgn_group_impl.h"

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

/* The library's own R^3 x SO(3) ops (not replaced by the user)? */
static sunbooleantype OwnOps(LGNGroup G)
{
  return G->kind == LGN_GROUP_R3XSO3 && G->ops.compose_exp == R3SO3ComposeExp &&
         G->ops.tangent_apply == R3SO3TangentApply &&
         G->ops.tangent_dot_apply == R3SO3TangentDotApply &&
         G->ops.tangent_matrix == R3SO3TangentMatrix;
}

int lgnGroupR3xSO3ExactMap(LGNGroup G, const sunrealtype *q,
                           const sunrealtype *w, const sunrealtype *wd,
                           const sunrealtype *wdd, sunrealtype *q1,
                           sunrealtype *v, sunrealtype *vdot, sunrealtype *Tm)
{
  lgnSO3_Coef c;
  sunrealtype e[4], t[3];
  int i, j;
  if (!OwnOps(G)) return 1;
  lgnSO3_CoefsExp(w + 3, LGN_SO3_A | LGN_SO3_B | LGN_SO3_C1 | LGN_SO3_C2, &c, e);
  for (i = 0; i < 3; i++) {
    q1[i]   = q[i] + w[i];
    v[i]    = wd[i];  /* T = diag(I3, T_SO3), Tdot = diag(0, Tdot_SO3) */
    vdot[i] = wdd[i];
  }
  lgnSO3_QuatComposeQuat(q + 3, e, q1 + 3);
  if (Tm != NULL) {
    for (j = 0; j < 6; j++)
      for (i = 0; i < 6; i++) Tm[i + j * 6] = (i == j && i < 3) ? 1 : 0;
    lgnSO3_TMatrixC(&c, w + 3, Tm + 3 + 3 * 6, 6);
  }
  lgnSO3_TApplyC(&c, w + 3, wd + 3, v + 3);
  lgnSO3_TApplyC(&c, w + 3, wdd + 3, vdot + 3);
  lgnSO3_TDotApplyC(&c, w + 3, wd + 3, wd + 3, t);
  vdot[3] += t[0];
  vdot[4] += t[1];
  vdot[5] += t[2];
  return 0;
}

int lgnGroupR3xSO3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                   const sunrealtype *wd,
                                   const sunrealtype *wdd, sunrealtype gamma_p,
                                   sunrealtype beta_p, const sunrealtype *Tm,
                                   sunrealtype *Tv, sunrealtype *Ta)
{
  /* diag(I3, rotation blocks): the translation's kinematics are exact */
  lgnSO3_Coef c;
  int i, j;
  if (!OwnOps(G)) return 1;
  for (j = 0; j < 6; j++)
    for (i = 0; i < 6; i++)
      if (i < 3 || j < 3) Tv[i + j * 6] = Ta[i + j * 6] = (i == j) ? 1 : 0;
  lgnSO3_Coefs(lgnSO3_Norm(w + 3), LGN_SO3_D2T, &c);
  lgnSO3_ExactBlocks(&c, w + 3, wd + 3, wdd + 3, gamma_p, beta_p,
                     Tm + 3 + 3 * 6, Tv + 3 + 3 * 6, Ta + 3 + 3 * 6, 6);
  return 0;
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
