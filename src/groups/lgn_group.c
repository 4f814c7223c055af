/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The generic LGNGroup object: LGNGroup_NewEmpty, LGNGroup_Destroy, the
 * LGNGroup_* dispatchers (each returns the op's flag, or -1 when G or the op
 * is NULL; LGNGroup_ComposeLog checks its arguments, reports on stderr and
 * returns LGN_* flags), and the public quaternion helpers LGNQuaternionToRotation,
 * LGNQuaternionFromRotationVector, LGNRotationVectorFromQuaternion,
 * LGNQuaternionMultiply (p = (w, x, y, z), Hamilton product).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>

#include "lgn_err.h"
#include "lgn_so3.h"

#define ONE SUN_RCONST(1.0)
#define TWO SUN_RCONST(2.0)

/* =============================================================================
 * Constructor / destructor
 * ===========================================================================*/

LGNGroup LGNGroup_NewEmpty(sunindextype nq, sunindextype nv)
{
  LGNGroup G;
  if (nq < 1 || nv < 1) return NULL;
  G = (LGNGroup)calloc(1, sizeof *G);
  if (G == NULL) return NULL;
  G->kind    = LGN_GROUP_CUSTOM;
  G->nq      = nq;
  G->nv      = nv;
  G->content = NULL;
  /* calloc leaves every op NULL */
  return G;
}

void LGNGroup_Destroy(LGNGroup G)
{
  if (G == NULL) return;
  if (G->ops.free_content != NULL) G->ops.free_content(G);
  free(G);
}

/* =============================================================================
 * Dispatchers
 * ===========================================================================*/

int LGNGroup_ComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        sunrealtype *q_out)
{
  if (G == NULL || G->ops.compose_exp == NULL) return -1;
  return G->ops.compose_exp(G, q, w, q_out);
}

int LGNGroup_ComposeLog(LGNGroup G, const sunrealtype *q1,
                        const sunrealtype *q2, sunrealtype *w)
{
  int flag;
  if (G == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "G = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (q1 == NULL || q2 == NULL || w == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "%s = NULL illegal.",
              q1 == NULL ? "q1" : q2 == NULL ? "q2" : "w");
    return LGN_ILL_INPUT;
  }
  if (G->ops.compose_log == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__,
              "The group has no compose_log op (G->ops.compose_log = NULL): "
              "a user-supplied group must set it to use the logarithm.");
    return LGN_ILL_INPUT;
  }
  flag = G->ops.compose_log(G, q1, q2, w);
  if (flag != 0) {
    lgnReport(NULL, LGN_GROUP_FAIL, __func__,
              "The group's compose_log op failed (flag %d): a zero or not "
              "finite quaternion, a product factor without compose_log, or "
              "the failure of a user-supplied op.", flag);
    return LGN_GROUP_FAIL;
  }
  return LGN_SUCCESS;
}

int LGNGroup_TangentApply(LGNGroup G, const sunrealtype *w,
                          const sunrealtype *x, sunrealtype *y)
{
  if (G == NULL || G->ops.tangent_apply == NULL) return -1;
  return G->ops.tangent_apply(G, w, x, y);
}

int LGNGroup_TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                 const sunrealtype *x, sunrealtype *y)
{
  if (G == NULL || G->ops.tangent_inverse_apply == NULL) return -1;
  return G->ops.tangent_inverse_apply(G, w, x, y);
}

int LGNGroup_TangentDotApply(LGNGroup G, const sunrealtype *w,
                             const sunrealtype *wdot, const sunrealtype *x,
                             sunrealtype *y)
{
  if (G == NULL || G->ops.tangent_dot_apply == NULL) return -1;
  return G->ops.tangent_dot_apply(G, w, wdot, x, y);
}

int LGNGroup_TangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                           sunindextype ld)
{
  if (G == NULL || G->ops.tangent_matrix == NULL) return -1;
  if (ld < G->nv) return -1;
  return G->ops.tangent_matrix(G, w, Tm, ld);
}

int LGNGroup_Identity(LGNGroup G, sunrealtype *q)
{
  if (G == NULL || G->ops.identity == NULL) return -1;
  return G->ops.identity(G, q);
}

int LGNGroup_Normalize(LGNGroup G, sunrealtype *q)
{
  if (G == NULL) return -1;
  if (G->ops.normalize == NULL) return 0; /* documented no-op */
  return G->ops.normalize(G, q);
}

/* =============================================================================
 * Quaternion helpers
 * ===========================================================================*/

void LGNQuaternionToRotation(const sunrealtype p[4], sunrealtype R[9])
{
  /* Standard Hamilton formula with s = 2/|p|^2, so R is orthogonal even for
   * a slightly non-unit p; p = 0 gives the identity. */
  const sunrealtype w = p[0], x = p[1], y = p[2], z = p[3];
  const sunrealtype n2 = w * w + x * x + y * y + z * z;
  const sunrealtype s = (n2 > 0) ? TWO / n2 : 0;
  R[0] = ONE - s * (y * y + z * z);
  R[1] = s * (x * y - w * z);
  R[2] = s * (x * z + w * y);
  R[3] = s * (x * y + w * z);
  R[4] = ONE - s * (x * x + z * z);
  R[5] = s * (y * z - w * x);
  R[6] = s * (x * z - w * y);
  R[7] = s * (y * z + w * x);
  R[8] = ONE - s * (x * x + y * y);
}

void LGNQuaternionFromRotationVector(const sunrealtype phi[3], sunrealtype p[4])
{
  lgnSO3_ExpQuat(phi, p);
}

void LGNRotationVectorFromQuaternion(const sunrealtype p[4], sunrealtype phi[3])
{
  /* With w >= 0 (p and -p are the same rotation): angle = 2 atan2(|v|, w)
   * in [0, pi], phi = angle v/|v|. For |v| << w use the series
   * atan(r)/r = 1 - r^2/3 + r^4/5 - r^6/7, r = |v|/w. Scale-invariant, so a
   * non-unit p gives the log of p/|p|. */
  const sunrealtype sg = (p[0] < 0) ? -ONE : ONE;
  const sunrealtype w = sg * p[0];
  const sunrealtype v[3] = {sg * p[1], sg * p[2], sg * p[3]};
  const sunrealtype n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  sunrealtype k;

  if (n == 0) {
    k = 0;
  } else if (n < SUN_RCONST(1.0e-3) * w) {
    const sunrealtype r2 = (n / w) * (n / w);
    k = (TWO / w) * (ONE + r2 * (-ONE / 3 + r2 * (ONE / 5 - r2 * (ONE / 7))));
  } else {
    k = TWO * atan2(n, w) / n;
  }
  phi[0] = k * v[0];
  phi[1] = k * v[1];
  phi[2] = k * v[2];
}

void LGNQuaternionMultiply(const sunrealtype p1[4], const sunrealtype p2[4],
                           sunrealtype r[4])
{
  lgnSO3_QuatMultiply(p1, p2, r);
}
