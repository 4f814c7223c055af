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
 * lgnSO3_D3TApplyC, lgnSO3_TMatrix[C], lgnSO3_TDotMatrixC,
 * lgnSO3_DTMatrixC, lgnSO3_D2TMatrixC, lgnSO3_D3TMatrixC, lgnSO3_ExactBlocks,
 * lgnSO3_CoefsExp,
 * lgnSO3_ExpQuat, lgnSO3_QuatComposeQuat, lgnSO3_QuatComposeExp, lgnSO3_QuatNormalize, lgnSO3_QuatRotate,
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

/* The coefficients from sh = sin(phi/2), ch = cos(phi/2) (used only for
 * phi >= LGN_SO3_THR_SINC, where every closed form is taken). */
static void CoefsSC(sunrealtype phi, unsigned need, lgnSO3_Coef *c,
                    sunrealtype sh, sunrealtype ch)
{
  const sunrealtype p2 = phi * phi;
  sunrealtype s = 0, omc = 0, cs = ONE;

  if (phi >= LGN_SO3_THR_SINC) {
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
  /* c5, c6: only the third derivative of T (SE(3)'s iteration matrix). The
   * closed forms cancel like phi^-6 and phi^-8, so the series (to phi^14,
   * coefficients 8 (m+1)(m+2)(m+3) (-1)^m / (2m+8)! and -../(2m+9)!) run
   * to larger angles; both are within ~1.5e-12 relative everywhere. */
  if (need & LGN_SO3_C5) {
    /* c5 = (48 (1 - cos) - 33 phi sin + 9 phi^2 cos + phi^3 sin)/phi^8 */
    c->c5 = (phi < LGN_SO3_THR_C5)
      ? ONE / 840 + p2 * (-ONE / 18900 + p2 * (ONE / 997920 + p2 * (
            -ONE / 90810720 + p2 * (ONE / SUN_RCONST(12454041600.0) + p2 * (
            -ONE / SUN_RCONST(2381835456000.0) + p2 * (
            ONE / SUN_RCONST(603398315520000.0) - p2 * (
            ONE / SUN_RCONST(1.95139015239168e17))))))))
      : (48 * omc - 33 * phi * s + 9 * p2 * cs + p2 * phi * s)
            / (p2 * p2 * p2 * p2);
  }
  if (need & LGN_SO3_C6) {
    /* c6 = (phi^3 cos - 12 phi^2 sin - 57 phi cos - 48 phi + 105 sin)/phi^9 */
    c->c6 = (phi < LGN_SO3_THR_C6)
      ? -ONE / 7560 + p2 * (ONE / 207900 + p2 * (-ONE / 12972960 + p2 * (
            ONE / SUN_RCONST(1362160800.0) + p2 * (
            -ONE / SUN_RCONST(211718707200.0) + p2 * (
            ONE / SUN_RCONST(45254873664000.0) + p2 * (
            -ONE / SUN_RCONST(1.267136462592e16) + p2 * (
            ONE / SUN_RCONST(4.48819735050086e18))))))))
      : (p2 * phi * cs - 12 * p2 * s - 57 * phi * cs - 48 * phi + 105 * s)
            / (p2 * p2 * p2 * p2 * phi);
  }
}

void lgnSO3_Coefs(sunrealtype phi, unsigned need, lgnSO3_Coef *c)
{
  sunrealtype sh = 0, ch = ONE;
  if (phi >= LGN_SO3_THR_SINC) {
    sh = sin(HALF * phi);
    ch = cos(HALF * phi);
  }
  CoefsSC(phi, need, c, sh, ch);
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

void lgnSO3_D3TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype U[3], const sunrealtype W[3],
                      const sunrealtype V[3], const sunrealtype v[3],
                      sunrealtype y[3])
{
  /* D^3T(x)[U,W,V] v, the derivative of D^2T[U,W] along V (d/dx of a
   * coefficient f(|x|) is (f'/phi) x^T: c1 -> c3 -> c5, c2 -> c4 -> c6):
   *   k1 x~v + k2 x~x~v  with k1 = c3 ((x.U)(W.V) + (x.W)(U.V) + (x.V)(U.W))
   *                            + c5 (x.U)(x.W)(x.V), k2 likewise (c4, c6)
   * + sum over the three directions Y of U, W, V, (Z, Z') the other two:
   *     (c1 (Z.Z') + c3 (x.Z)(x.Z')) Y~v
   *   + (c2 (Z.Z') + c4 (x.Z)(x.Z')) (Y~x~ + x~Y~) v
   *   + c2 (x.Y) (Z~Z'~ + Z'~Z~) v                                         */
  const sunrealtype *Y[3] = {U, W, V};
  sunrealtype ox[3], dd[3], xv[3], xxv[3], t1[3], t2[3], t3[3], t4[3];
  sunrealtype k1, k2, al, be;
  int i, k;
  for (k = 0; k < 3; k++) ox[k] = lgnVec3Dot(x, Y[k]);
  dd[0] = lgnVec3Dot(W, V); /* pairs opposite U, W, V */
  dd[1] = lgnVec3Dot(U, V);
  dd[2] = lgnVec3Dot(U, W);
  k1 = c->c3 * (ox[0] * dd[0] + ox[1] * dd[1] + ox[2] * dd[2])
     + c->c5 * ox[0] * ox[1] * ox[2];
  k2 = c->c4 * (ox[0] * dd[0] + ox[1] * dd[1] + ox[2] * dd[2])
     + c->c6 * ox[0] * ox[1] * ox[2];
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  for (i = 0; i < 3; i++) y[i] = k1 * xv[i] + k2 * xxv[i];
  for (k = 0; k < 3; k++) {
    const sunrealtype *Z = Y[(k + 1) % 3], *Zp = Y[(k + 2) % 3];
    const sunrealtype oo = ox[(k + 1) % 3] * ox[(k + 2) % 3];
    al = c->c1 * dd[k] + c->c3 * oo;
    be = c->c2 * dd[k] + c->c4 * oo;
    lgnVec3Cross(Y[k], v, t1);  /* Y~v      */
    lgnVec3Cross(Y[k], xv, t2); /* Y~x~v    */
    lgnVec3Cross(x, t1, t3);    /* x~Y~v    */
    for (i = 0; i < 3; i++) y[i] += al * t1[i] + be * (t2[i] + t3[i]);
    lgnVec3Cross(Zp, v, t1);    /* Z'~v     */
    lgnVec3Cross(Z, t1, t2);    /* Z~Z'~v   */
    lgnVec3Cross(Z, v, t3);     /* Z~v      */
    lgnVec3Cross(Zp, t3, t4);   /* Z'~Z~v   */
    for (i = 0; i < 3; i++) y[i] += c->c2 * ox[k] * (t2[i] + t4[i]);
  }
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

/* J with J u = DT(x)[u] v = a u~v + b (u~x~ + x~u~) v + (x.u)(c1 x~v + c2 x~x~v):
 * with u~y = -y~u, x~v~ = v x^T - (x.v) I and (x~v)~ = v x^T - x v^T,
 *   J = -a v~ - b (2 v x^T - x v^T - (x.v) I) + (c1 x~v + c2 x~x~v) x^T. */
void lgnSO3_DTMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype v[3], sunrealtype *M, sunindextype ld,
                      sunbooleantype add)
{
  sunrealtype V[9], xv[3], xxv[3], g[3], m;
  const sunrealtype s = lgnVec3Dot(x, v);
  int i, j;
  lgnSO3_Tilde(v, V);
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  for (i = 0; i < 3; i++) g[i] = c->c1 * xv[i] + c->c2 * xxv[i];
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) {
      m = -c->a * V[3 * i + j]
        - c->b * (TWO * v[i] * x[j] - x[i] * v[j] - (i == j ? s : 0))
        + g[i] * x[j];
      M[i + j * ld] = add ? M[i + j * ld] + m : m;
    }
}

/* K with K u = D^2T(x)[u, w] v (lgnSO3_D2TApplyC with U = u, W = w):
 *   K = x~v (c3 (x.w) x + c1 w)^T + x~x~v (c4 (x.w) x + c2 w)^T
 *     + (c1 w~v + c2 (w~x~ + x~w~) v) x^T
 *     - c1 (x.w) v~ - c2 (x.w) (2 v x^T - x v^T - (x.v) I)
 *     - b (2 v w^T - w v^T - (w.v) I)                                      */
void lgnSO3_D2TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype w[3], const sunrealtype v[3],
                       sunrealtype *M, sunindextype ld, sunbooleantype add)
{
  sunrealtype V[9], xv[3], xxv[3], wv[3], wxv[3], xwv[3], f1[3], f2[3], g[3], m;
  const sunrealtype ow = lgnVec3Dot(x, w), xv_ = lgnVec3Dot(x, v);
  const sunrealtype wv_ = lgnVec3Dot(w, v);
  int i, j;
  lgnSO3_Tilde(v, V);
  lgnVec3Cross(x, v, xv);
  lgnVec3Cross(x, xv, xxv);
  lgnVec3Cross(w, v, wv);
  lgnVec3Cross(w, xv, wxv);
  lgnVec3Cross(x, wv, xwv);
  for (i = 0; i < 3; i++) {
    f1[i] = c->c3 * ow * x[i] + c->c1 * w[i];
    f2[i] = c->c4 * ow * x[i] + c->c2 * w[i];
    g[i]  = c->c1 * wv[i] + c->c2 * (wxv[i] + xwv[i]);
  }
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) {
      m = xv[i] * f1[j] + xxv[i] * f2[j] + g[i] * x[j]
        - c->c1 * ow * V[3 * i + j]
        - c->c2 * ow * (TWO * v[i] * x[j] - x[i] * v[j] - (i == j ? xv_ : 0))
        - c->b * (TWO * v[i] * w[j] - w[i] * v[j] - (i == j ? wv_ : 0));
      M[i + j * ld] = add ? M[i + j * ld] + m : m;
    }
}

/* L with L u = D^3T(x)[u, U, W] v, column by column (SE(3) only). */
void lgnSO3_D3TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype U[3], const sunrealtype W[3],
                       const sunrealtype v[3], sunrealtype *M, sunindextype ld,
                       sunbooleantype add)
{
  sunrealtype e[3] = {0, 0, 0}, y[3];
  int i, j;
  for (j = 0; j < 3; j++) {
    e[j] = ONE;
    lgnSO3_D3TApplyC(c, x, e, U, W, v, y);
    e[j] = 0;
    for (i = 0; i < 3; i++) M[i + j * ld] = add ? M[i + j * ld] + y[i] : y[i];
  }
}

void lgnSO3_ExactBlocks(const lgnSO3_Coef *c, const sunrealtype x[3],
                        const sunrealtype xd[3], const sunrealtype xdd[3],
                        sunrealtype gamma_p, sunrealtype beta_p,
                        const sunrealtype *T, sunrealtype *Tv, sunrealtype *Ta,
                        sunindextype ld)
{
  sunrealtype P[9], D[9], Q[9];
  const sunrealtype ratio = gamma_p / beta_p;
  int i, j;
  lgnSO3_DTMatrixC(c, x, xd, P, 3, SUNFALSE);        /* DT[.] xd       */
  lgnSO3_TDotMatrixC(c, x, xd, D, 3);                /* Tdot(x, xd)    */
  lgnSO3_DTMatrixC(c, x, xdd, Q, 3, SUNFALSE);       /* DT[.] xdd      */
  lgnSO3_D2TMatrixC(c, x, xd, xd, Q, 3, SUNTRUE);    /* + D^2T[., xd] xd */
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) {
      const sunrealtype t = T[i + j * ld], p = P[i + 3 * j];
      Tv[i + j * ld] = t + p / gamma_p;
      Ta[i + j * ld] = t + ratio * (p + D[i + 3 * j]) + Q[i + 3 * j] / beta_p;
    }
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

void lgnSO3_QuatComposeQuat(const sunrealtype p[4], const sunrealtype e[4],
                            sunrealtype p_out[4])
{
  /* p_out = p (x) e, renormalised to stop drift; computed in locals and
   * stored once (storing, then reloading to normalise, stalls on
   * store-to-load forwarding) */
  sunrealtype r[4], s;
  lgnSO3_QuatMultiply(p, e, r);
  s = InverseNorm(r);
  if (s == 0) s = ONE;
  p_out[0] = s * r[0]; p_out[1] = s * r[1]; p_out[2] = s * r[2]; p_out[3] = s * r[3];
}

void lgnSO3_QuatComposeExp(const sunrealtype p[4], const sunrealtype w[3],
                           sunrealtype p_out[4])
{
  sunrealtype e[4];
  ExpQuat(w, e);
  lgnSO3_QuatComposeQuat(p, e, p_out);
}

void lgnSO3_CoefsExp(const sunrealtype x[3], unsigned need, lgnSO3_Coef *c,
                     sunrealtype p[4])
{
  /* one sine and cosine of h = phi/2 for both: sqrt(|x|^2/4) = sqrt(|x|^2)/2
   * exactly, so h, sin(h) and cos(h) are ExpQuat's and lgnSO3_Coefs' own;
   * the branches are theirs too (ExpQuat's closed form, h^2 >= THR^2, lies
   * inside Coefs' phi >= THR) */
  const sunrealtype x2 = lgnVec3Dot(x, x), phi = sqrt(x2);
  sunrealtype sh = 0, ch = ONE;
  if (phi >= LGN_SO3_THR_SINC) {
    sh = sin(HALF * phi);
    ch = cos(HALF * phi);
  }
  CoefsSC(phi, need, c, sh, ch);
  if (p == NULL) return;
  {
    const sunrealtype h2 = x2 / 4;
    sunrealtype k, cq;
    if (h2 < LGN_SO3_THR_SINC * LGN_SO3_THR_SINC) {
      k  = HALF * (ONE + h2 * (-ONE / 6 + h2 * (ONE / 120 - h2 * (ONE / 5040))));
      cq = ONE + h2 * (-HALF + h2 * (ONE / 24 + h2 * (-ONE / 720 + h2 * (ONE / 40320))));
    } else {
      const sunrealtype h = sqrt(h2);
      k  = sh / (2 * h);
      cq = ch;
    }
    p[0] = cq;
    p[1] = k * x[0];
    p[2] = k * x[1];
    p[3] = k * x[2];
  }
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
