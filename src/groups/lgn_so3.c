/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private SO(3) math (doc/theory.md §1.1): coefficients of the
 * tangent operator with small-angle series, operators applied with cross
 * products (x~ y = x cross y), dense blocks, quaternion exponential.
 *
 * Functions: lgnSO3_Coefs, lgnSO3_Norm, lgnSO3_Tilde, lgnSO3_TApply[C],
 * lgnSO3_TInvApply[C], lgnSO3_TDotApply[C], lgnSO3_D2TApplyC,
 * lgnSO3_TMatrix[C], lgnSO3_TDotMatrixC, lgnSO3_ExpQuat,
 * lgnSO3_QuatComposeExp, lgnSO3_QuatNormalize, lgnSO3_QuatRotate,
 * lgnSO3_LogQuat, lgnSO3_QuatComposeLog.
 * None of them allocates.
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_so3.h"

#define ONE  SUN_RCONST(1.0)
#define TWO  SUN_RCONST(2.0)
#define HALF SUN_RCONST(0.5)

/* =============================================================================
 * Small helpers
 * ===========================================================================*/

sunrealtype lgnSO3_Norm(const sunrealtype x[3])
{
  return sqrt(lgnVec3Dot(x, x));
}

void lgnSO3_Tilde(const sunrealtype x[3], sunrealtype M[9])
{
  /* x~ = [[0,-x3,x2],[x3,0,-x1],[-x2,x1,0]]  (the hat map) */
  M[0] = 0;     M[1] = -x[2]; M[2] = x[1];
  M[3] = x[2];  M[4] = 0;     M[5] = -x[0];
  M[6] = -x[1]; M[7] = x[0];  M[8] = 0;
}

/* =============================================================================
 * Coefficients (doc/theory.md §1.1): series below the threshold, closed form
 * above. The closed forms use the half angle, 1 - cos(phi) = 2 sin^2(phi/2),
 * which removes one cancellation.
 * ===========================================================================*/

void lgnSO3_Coefs(sunrealtype phi, unsigned need, lgnSO3_Coef *c)
{
  const sunrealtype p2 = phi * phi;
  sunrealtype sh = 0, ch = ONE, s = 0, omc = 0, cs = ONE;

  if (phi >= LGN_SO3_THR_SINC) {
    sh  = sin(HALF * phi);
    ch  = cos(HALF * phi);
    s   = TWO * sh * ch;       /* sin(phi)     */
    omc = TWO * sh * sh;       /* 1 - cos(phi) */
    cs  = ONE - omc;           /* cos(phi)     */
  }

  /* below the thresholds: Taylor series in phi^2, Horner form; the last
   * coefficient is a product with 1/k!-like constants folded at compile
   * time, not a division (a division costs several multiplications) */
  if (need & LGN_SO3_SINC) {
    c->sinc = (phi < LGN_SO3_THR_SINC)
      ? ONE + p2 * (-ONE / 6 + p2 * (ONE / 120 - p2 * (ONE / 5040)))
      : s / phi;
  }
  if (need & LGN_SO3_CC) {
    c->cc = (phi < LGN_SO3_THR_CC)
      ? HALF + p2 * (-ONE / 24 + p2 * (ONE / 720 - p2 * (ONE / 40320)))
      : omc / p2;
  }
  if (need & LGN_SO3_A) {
    c->a = (phi < LGN_SO3_THR_A)
      ? -HALF + p2 * (ONE / 24 + p2 * (-ONE / 720 + p2 * (ONE / 40320)))
      : -omc / p2;
  }
  if (need & LGN_SO3_B) {
    c->b = (phi < LGN_SO3_THR_B)
      ? ONE / 6 + p2 * (-ONE / 120 + p2 * (ONE / 5040 - p2 * (ONE / 362880)))
      : (phi - s) / (p2 * phi);
  }
  if (need & LGN_SO3_D) {
    c->d = (phi < LGN_SO3_THR_D)
      ? ONE / 12 + p2 * (ONE / 720 + p2 * (ONE / 30240 + p2 * (ONE / 1209600)))
      : (ONE - HALF * phi * ch / sh) / p2;
  }
  if (need & LGN_SO3_C1) {
    c->c1 = (phi < LGN_SO3_THR_C1)
      ? ONE / 12 + p2 * (-ONE / 180 + p2 * (ONE / 6720 - p2 * (ONE / 453600)))
      : (TWO * omc - phi * s) / (p2 * p2);
  }
  if (need & LGN_SO3_C2) {
    c->c2 = (phi < LGN_SO3_THR_C2)
      ? -ONE / 60 + p2 * (ONE / 1260 + p2 * (-ONE / 60480 + p2 * (ONE / 4989600
                                              - p2 * (ONE / 622702080))))
      : (3 * s - TWO * phi - phi * cs) / (p2 * p2 * phi);
  }
  if (need & LGN_SO3_C3) {
    /* c3 = (8cos - 8 + 5 phi sin - phi^2 cos)/phi^6 */
    c->c3 = (phi < LGN_SO3_THR_C3)
      ? -ONE / 90 + p2 * (ONE / 1680 + p2 * (-ONE / 75600 + p2 * (ONE / 5987520
                                              - p2 * (ONE / 726485760))))
      : (-8 * omc + 5 * phi * s - p2 * cs) / (p2 * p2 * p2);
  }
  if (need & LGN_SO3_C4) {
    /* c4 = (phi^2 sin + 7 phi cos + 8 phi - 15 sin)/phi^7 */
    c->c4 = (phi < LGN_SO3_THR_C4)
      ? ONE / 630 + p2 * (-ONE / 15120 + p2 * (ONE / 831600 + p2 * (
            -ONE / 77837760 + p2 * (ONE / SUN_RCONST(10897286400.0)))))
      : (p2 * s + 7 * phi * cs + 8 * phi - 15 * s) / (p2 * p2 * p2 * phi);
  }
}

/* =============================================================================
 * Operators applied with cross products
 * ===========================================================================*/

void lgnSO3_TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                    const sunrealtype v[3], sunrealtype y[3])
{
  /* T v = v + a x~v + b x~x~v  (doc/theory.md §1.1) */
  sunrealtype xv[3], xxv[3];
  int i;
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  for (i = 0; i < 3; i++) y[i] = v[i] + c->a * xv[i] + c->b * xxv[i];
}

void lgnSO3_TApply(const sunrealtype x[3], const sunrealtype v[3],
                   sunrealtype y[3])
{
  lgnSO3_Coef c;
  lgnSO3_Coefs(lgnSO3_Norm(x), LGN_SO3_A | LGN_SO3_B, &c);
  lgnSO3_TApplyC(&c, x, v, y);
}

void lgnSO3_TInvApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype v[3], sunrealtype y[3])
{
  /* T^{-1} v = v + x~v/2 + d x~x~v  (doc/theory.md §1.1) */
  sunrealtype xv[3], xxv[3];
  int i;
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  for (i = 0; i < 3; i++) y[i] = v[i] + HALF * xv[i] + c->d * xxv[i];
}

void lgnSO3_TInvApply(const sunrealtype x[3], const sunrealtype v[3],
                      sunrealtype y[3])
{
  lgnSO3_Coef c;
  lgnSO3_Coefs(lgnSO3_Norm(x), LGN_SO3_D, &c);
  lgnSO3_TInvApplyC(&c, x, v, y);
}

void lgnSO3_TDotApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype xd[3], const sunrealtype v[3],
                       sunrealtype y[3])
{
  /* Tdot v = a xd~v + b(xd~x~v + x~xd~v) + (x.xd)(c1 x~v + c2 x~x~v) (§4.1) */
  sunrealtype xv[3], xxv[3], dv[3], dxv[3], xdv[3];
  const sunrealtype s = lgnVec3Dot(x, xd);
  int i;
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  lgnVec3Cross(xd, v, dv);
  lgnVec3Cross(xd, xv, dxv);
  lgnVec3Cross(x, dv, xdv);
  for (i = 0; i < 3; i++)
    y[i] = c->a * dv[i] + c->b * (dxv[i] + xdv[i])
         + s * (c->c1 * xv[i] + c->c2 * xxv[i]);
}

void lgnSO3_TDotApply(const sunrealtype x[3], const sunrealtype xd[3],
                      const sunrealtype v[3], sunrealtype y[3])
{
  lgnSO3_Coef c;
  lgnSO3_Coefs(lgnSO3_Norm(x),
               LGN_SO3_A | LGN_SO3_B | LGN_SO3_C1 | LGN_SO3_C2, &c);
  lgnSO3_TDotApplyC(&c, x, xd, v, y);
}

void lgnSO3_D2TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype U[3], const sunrealtype W[3],
                      const sunrealtype v[3], sunrealtype y[3])
{
  /* D^2T(x)[U,W] v (the second derivative of T(x)):
   *   (c3 (x.W)(x.U) + c1 (W.U)) x~v + c1 ((x.U) W~v + (x.W) U~v)
   * + (c4 (x.W)(x.U) + c2 (W.U)) x~x~v
   * + c2 ((x.U)(W~x~ + x~W~)v + (x.W)(U~x~ + x~U~)v) + b (U~W~ + W~U~)v  */
  sunrealtype xv[3], xxv[3], Wv[3], Uv[3], Wxv[3], xWv[3], Uxv[3], xUv[3];
  sunrealtype UWv[3], WUv[3];
  const sunrealtype ou = lgnVec3Dot(x, U), ow = lgnVec3Dot(x, W), wu = lgnVec3Dot(W, U);
  const sunrealtype k1 = c->c3 * ow * ou + c->c1 * wu;
  const sunrealtype k2 = c->c4 * ow * ou + c->c2 * wu;
  int i;
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  lgnVec3Cross(W, v, Wv);
  lgnVec3Cross(U, v, Uv);
  lgnVec3Cross(W, xv, Wxv);
  lgnVec3Cross(x, Wv, xWv);
  lgnVec3Cross(U, xv, Uxv);
  lgnVec3Cross(x, Uv, xUv);
  lgnVec3Cross(U, Wv, UWv);
  lgnVec3Cross(W, Uv, WUv);
  for (i = 0; i < 3; i++)
    y[i] = k1 * xv[i] + c->c1 * (ou * Wv[i] + ow * Uv[i]) + k2 * xxv[i]
         + c->c2 * (ou * (Wxv[i] + xWv[i]) + ow * (Uxv[i] + xUv[i]))
         + c->b * (UWv[i] + WUv[i]);
}

/* =============================================================================
 * Dense blocks (column-major, leading dimension ld)
 * ===========================================================================*/

void lgnSO3_TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                     sunrealtype *M, sunindextype ld)
{
  /* T = I + a x~ + b x~^2 with x~^2 = x x^T - |x|^2 I */
  sunrealtype X[9];
  const sunrealtype p2 = lgnVec3Dot(x, x);
  int i, j;
  lgnSO3_Tilde(x, X);
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++)
      M[i + j * ld] = (i == j ? ONE - c->b * p2 : 0)
                    + c->b * x[i] * x[j] + c->a * X[3 * i + j];
}

void lgnSO3_TMatrix(const sunrealtype x[3], sunrealtype *M, sunindextype ld)
{
  lgnSO3_Coef c;
  lgnSO3_Coefs(lgnSO3_Norm(x), LGN_SO3_A | LGN_SO3_B, &c);
  lgnSO3_TMatrixC(&c, x, M, ld);
}

void lgnSO3_TDotMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                        const sunrealtype xd[3], sunrealtype *M,
                        sunindextype ld)
{
  /* Tdot = a xd~ + b(x xd^T + xd x^T - 2(x.xd) I)
   *      + (x.xd)(c1 x~ + c2 (x x^T - |x|^2 I)),
   * using xd~x~ + x~xd~ = x xd^T + xd x^T - 2 (x.xd) I. */
  sunrealtype X[9], D[9];
  const sunrealtype s = lgnVec3Dot(x, xd), p2 = lgnVec3Dot(x, x);
  int i, j;
  lgnSO3_Tilde(x, X);
  lgnSO3_Tilde(xd, D);
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++)
      M[i + j * ld] = c->a * D[3 * i + j]
                    + c->b * (x[i] * xd[j] + xd[i] * x[j])
                    + s * (c->c1 * X[3 * i + j] + c->c2 * x[i] * x[j])
                    - (i == j ? TWO * c->b * s + s * c->c2 * p2 : 0);
}

/* =============================================================================
 * Quaternions (p = (w, x, y, z), Hamilton product)
 * ===========================================================================*/

static inline void ExpQuat(const sunrealtype x[3], sunrealtype p[4])
{
  /* expq(x) = (cos(h), sin(h)/phi x), h = phi/2. Below the threshold both
   * come from series in h^2 (no square root, sine or cosine): sin(h)/phi =
   * sinc(h)/2 (the sin(phi)/phi row of the §4.1 table) and cos(h) to h^8,
   * whose first omitted term, h^10/10!, is below 3e-20 there. The step
   * increments and Newton corrections of a time integration are this small. */
  const sunrealtype h2 = lgnVec3Dot(x, x) / 4;
  sunrealtype k, c;
  if (h2 < LGN_SO3_THR_SINC * LGN_SO3_THR_SINC) {
    k = HALF * (ONE + h2 * (-ONE / 6 + h2 * (ONE / 120 - h2 * (ONE / 5040))));
    c = ONE + h2 * (-HALF + h2 * (ONE / 24 + h2 * (-ONE / 720 + h2 * (ONE / 40320))));
  } else {
    const sunrealtype h = sqrt(h2);
    k = sin(h) / (2 * h);
    c = cos(h);
  }
  p[0] = c;
  p[1] = k * x[0];
  p[2] = k * x[1];
  p[3] = k * x[2];
}

void lgnSO3_ExpQuat(const sunrealtype x[3], sunrealtype p[4])
{
  ExpQuat(x, p);
}

/* 1/|p|: for |p|^2 = 1 + d with |d| <= 1e-8, as after composing unit
 * quaternions, 1 - d/2 is 1/sqrt(1 + d) to 3 d^2/8 < 4e-17, so neither a
 * square root nor a division is needed. 0 for p = 0. */
static inline sunrealtype InverseNorm(const sunrealtype p[4])
{
  const sunrealtype n2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
  const sunrealtype d  = n2 - ONE;
  if (fabs(d) <= SUN_RCONST(1.0e-8)) return ONE - HALF * d;
  return n2 > 0 ? ONE / sqrt(n2) : 0;
}

int lgnSO3_QuatNormalize(sunrealtype p[4])
{
  const sunrealtype r = InverseNorm(p);
  if (!(r > 0) || !isfinite(r)) return -1; /* zero or not finite: no rotation */
  p[0] *= r; p[1] *= r; p[2] *= r; p[3] *= r;
  return 0;
}

void lgnSO3_QuatComposeExp(const sunrealtype p[4], const sunrealtype w[3],
                           sunrealtype p_out[4])
{
  /* p_out = p (x) expq(w), renormalised to stop drift; computed in locals
   * and stored once (storing, then reloading to normalise, stalls on
   * store-to-load forwarding) */
  sunrealtype e[4], r[4], s;
  ExpQuat(w, e);
  lgnSO3_QuatMultiply(p, e, r);
  s = InverseNorm(r);
  if (s == 0) s = ONE;
  p_out[0] = s * r[0]; p_out[1] = s * r[1]; p_out[2] = s * r[2]; p_out[3] = s * r[3];
}

void lgnSO3_QuatRotate(const sunrealtype p[4], const sunrealtype v[3],
                       sunrealtype y[3])
{
  /* R(p) v = v + w t + q x t with t = 2 q x v, q = (p1,p2,p3) */
  sunrealtype t[3], qt[3];
  const sunrealtype *q = p + 1;
  int i;
  lgnVec3Cross(q, v, t);
  for (i = 0; i < 3; i++) t[i] *= TWO;
  lgnVec3Cross(q, t, qt);
  for (i = 0; i < 3; i++) y[i] = v[i] + p[0] * t[i] + qt[i];
}

/* =============================================================================
 * Quaternion logarithm (the inverse of expq and of the composition above)
 * ===========================================================================*/

/* |p|^2 outside [LOG_TINY, LOG_HUGE]: rescale before squaring (far from a
 * unit quaternion, zero, or not finite). */
#define LOG_TINY SUN_RCONST(1.0e-200)
#define LOG_HUGE SUN_RCONST(1.0e200)

int lgnSO3_LogQuat(const sunrealtype p[4], sunrealtype phi[3])
{
  /* p = (w, v) = s (cos(h), sin(h) u), h = angle/2 in [0, pi/2] once w >= 0:
   * phi = 2 h u = k v with k = 2 atan2(|v|, w) / |v|. atan2, not acos(w) or
   * asin(|v|), keeps full relative accuracy at both ends (acos loses half
   * the digits near 0, asin near pi). For r = |v|/w < LGN_SO3_THR_LOG,
   * k = (2/w) atan(r)/r by its series in r^2, which needs no square root
   * and stays exact when |v|^2 underflows (angles below 1e-154). */
  sunrealtype w = p[0], x = p[1], y = p[2], z = p[3], n2, w2, k;

  /* p and -p are the same rotation: w >= 0; at w = 0 (angle pi) the first
   * nonzero of (x, y, z) positive, so that log(-p) = log(p) there too */
  if (w < 0 || (w == 0 && (x < 0 || (x == 0 && (y < 0 || (y == 0 && z < 0)))))) {
    w = -w; x = -x; y = -y; z = -z;
  }
  n2 = x * x + y * y + z * z;
  w2 = w * w;
  if (!(n2 + w2 >= LOG_TINY && n2 + w2 <= LOG_HUGE)) {
    const sunrealtype m = fmax(fmax(w, fabs(x)), fmax(fabs(y), fabs(z)));
    if (!isfinite(w + x + y + z) || !(m > 0)) {
      phi[0] = phi[1] = phi[2] = 0;
      return -1; /* zero or not finite: no rotation */
    }
    w /= m; x /= m; y /= m; z /= m;
    n2 = x * x + y * y + z * z;
    w2 = w * w;
  }
  if (n2 < (LGN_SO3_THR_LOG * LGN_SO3_THR_LOG) * w2) {
    /* atan(r)/r = 1 - r^2/3 + r^4/5 - ... - r^10/11 + r^12/13 */
    const sunrealtype r2 = n2 / w2;
    k = (TWO / w)
      * (ONE + r2 * (-ONE / 3 + r2 * (ONE / 5 + r2 * (-ONE / 7 + r2 * (ONE / 9
          + r2 * (-ONE / 11 + r2 * (ONE / 13)))))));
  } else {
    const sunrealtype n = sqrt(n2);
    k = TWO * atan2(n, w) / n;
  }
  phi[0] = k * x;
  phi[1] = k * y;
  phi[2] = k * z;
  return 0;
}

int lgnSO3_QuatComposeLog(const sunrealtype p1[4], const sunrealtype p2[4],
                          sunrealtype phi[3])
{
  /* conj(p1) is p1^{-1} up to the factor |p1|^2, which the log ignores */
  const sunrealtype c[4] = {p1[0], -p1[1], -p1[2], -p1[3]};
  sunrealtype r[4];
  lgnSO3_QuatMultiply(c, p2, r);
  return lgnSO3_LogQuat(r, phi);
}
