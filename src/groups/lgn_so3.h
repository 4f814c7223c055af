/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private SO(3) math shared by the built-in groups (doc/theory.md §1.1): the scalar coefficients of the tangent operator with their
 * small-angle series, T, T^{-1}, Tdot and D^2T applied with cross products,
 * T and DT as dense blocks, and the quaternion exponential.
 *
 * With x a rotation vector, phi = |x| and x~ y = x cross y:
 *   T(x)      = I + a x~ + b x~^2                           (§4.1)
 *   T(x)^{-1} = I + x~/2 + d x~^2                           (§4.1)
 *   Tdot(x,xd)= a xd~ + b (xd~ x~ + x~ xd~)
 *             + (x.xd)(c1 x~ + c2 x~^2)                     (§4.1)
 *   D^2T(x)[U,W]  as in §4.3 (needs c3 = c1'/phi, c4 = c2'/phi).
 * Matrices in this header are column-major with leading dimension ld
 * (element (i,j) at M[i + j*ld]) unless stated otherwise.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_SO3_H
#define LGN_SO3_H

#include <lignum/lignum_group.h>

/* Below these angles the Taylor series of doc/theory.md §1.1 are used. */
#define LGN_SO3_THR_SINC SUN_RCONST(0.05) /* sin(phi)/phi        */
#define LGN_SO3_THR_CC   SUN_RCONST(0.05) /* (1-cos(phi))/phi^2  */
#define LGN_SO3_THR_A    SUN_RCONST(0.1)
#define LGN_SO3_THR_B    SUN_RCONST(0.1)
#define LGN_SO3_THR_D    SUN_RCONST(0.1)
#define LGN_SO3_THR_C1   SUN_RCONST(0.2)
#define LGN_SO3_THR_C2   SUN_RCONST(0.3)
#define LGN_SO3_THR_C3   SUN_RCONST(0.4)
#define LGN_SO3_THR_C4   SUN_RCONST(0.5)
#define LGN_SO3_THR_C5   SUN_RCONST(1.5) /* series to phi^14: both forms */
#define LGN_SO3_THR_C6   SUN_RCONST(1.8) /* within ~1e-12 relative       */

/* Bits selecting which coefficients lgnSO3_Coefs computes. */
#define LGN_SO3_SINC (1u << 0)
#define LGN_SO3_CC   (1u << 1)
#define LGN_SO3_A    (1u << 2)
#define LGN_SO3_B    (1u << 3)
#define LGN_SO3_D    (1u << 4)
#define LGN_SO3_C1   (1u << 5)
#define LGN_SO3_C2   (1u << 6)
#define LGN_SO3_C3   (1u << 7)
#define LGN_SO3_C4   (1u << 8)
#define LGN_SO3_C5   (1u << 9)
#define LGN_SO3_C6   (1u << 10)
#define LGN_SO3_ALL  (0x7FFu)
/* what T, Tdot and D^2T need; with C5, C6 also D^3T */
#define LGN_SO3_D2T  (LGN_SO3_A | LGN_SO3_B | LGN_SO3_C1 | LGN_SO3_C2 | \
                      LGN_SO3_C3 | LGN_SO3_C4)
#define LGN_SO3_D3T  (LGN_SO3_D2T | LGN_SO3_C5 | LGN_SO3_C6)

/* Coefficients at one angle phi (doc/theory.md §1.1; those not requested are
 * left unset):
 *   sinc = sin(phi)/phi          cc = (1-cos phi)/phi^2
 *   a    = (cos phi - 1)/phi^2   b  = (phi - sin phi)/phi^3
 *   d    = (1 - (phi/2)cot(phi/2))/phi^2
 *   c1   = (2 - 2cos phi - phi sin phi)/phi^4
 *   c2   = (3 sin phi - 2 phi - phi cos phi)/phi^5
 *   c3   = c1'(phi)/phi          c4 = c2'(phi)/phi
 *   c5   = c3'(phi)/phi          c6 = c4'(phi)/phi   (D^3T only)
 * (c1 = a'/phi, c2 = b'/phi: each derivative of T with respect to x
 * brings one such step, d/dx f(|x|) = (f'/phi) x^T.)                       */
typedef struct {
  sunrealtype sinc, cc, a, b, d, c1, c2, c3, c4, c5, c6;
} lgnSO3_Coef;

/* Fill the coefficients selected by the bit mask `need` at angle phi >= 0. */
void lgnSO3_Coefs(sunrealtype phi, unsigned need, lgnSO3_Coef *c);

/* The coefficients `need` at phi = |x| and p = expq(x) (as lgnSO3_ExpQuat)
 * from one sine and cosine of phi/2: what one iterate of the exact
 * kinematics needs (exp, T, Tdot, and for the iteration matrix their
 * derivatives), bit for bit what lgnSO3_Coefs(lgnSO3_Norm(x), ..) and
 * lgnSO3_ExpQuat give separately. p may be NULL. */
void lgnSO3_CoefsExp(const sunrealtype x[3], unsigned need, lgnSO3_Coef *c,
                     sunrealtype p[4]);

/* Euclidean norm of a 3-vector. */
sunrealtype lgnSO3_Norm(const sunrealtype x[3]);

/* M = x~ as a row-major 3x3 matrix, M[3*i+j]. */
void lgnSO3_Tilde(const sunrealtype x[3], sunrealtype M[9]);

/* y = T(x) v, T^{-1}(x) v, Tdot(x,xd) v; y must not alias the inputs.
 * The *C variants take coefficients computed at phi = |x| by the caller
 * (T needs A|B, T^{-1} needs D, Tdot needs A|B|C1|C2). */
void lgnSO3_TApply(const sunrealtype x[3], const sunrealtype v[3],
                   sunrealtype y[3]);
void lgnSO3_TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                    const sunrealtype v[3], sunrealtype y[3]);
void lgnSO3_TInvApply(const sunrealtype x[3], const sunrealtype v[3],
                      sunrealtype y[3]);
void lgnSO3_TInvApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype v[3], sunrealtype y[3]);
void lgnSO3_TDotApply(const sunrealtype x[3], const sunrealtype xd[3],
                      const sunrealtype v[3], sunrealtype y[3]);
void lgnSO3_TDotApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype xd[3], const sunrealtype v[3],
                       sunrealtype y[3]);

/* y = D^2T(x)[U,W] v (the second derivative of T(x)), coefficients A|B|C1|C2|C3|C4 at |x|. */
void lgnSO3_D2TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype U[3], const sunrealtype W[3],
                      const sunrealtype v[3], sunrealtype y[3]);

/* y = D^3T(x)[U,W,V] v (the third derivative of T(x), symmetric in U, W,
 * V), coefficients LGN_SO3_D3T at |x|. */
void lgnSO3_D3TApplyC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype U[3], const sunrealtype W[3],
                      const sunrealtype V[3], const sunrealtype v[3],
                      sunrealtype y[3]);

/* The derivatives of the exact kinematics as 3x3 column-major blocks
 * (leading dimension ld), linear in the direction u of x:
 *   lgnSO3_DTMatrixC:  M u = DT(x)[u] v        = Tdot(x, u) v
 *                      (coefficients A|B|C1|C2)
 *   lgnSO3_D2TMatrixC: M u = D^2T(x)[u, w] v   (coefficients LGN_SO3_D2T)
 *   lgnSO3_D3TMatrixC: M u = D^3T(x)[u, U, W] v (coefficients LGN_SO3_D3T)
 * With add, M += instead of M =. */
void lgnSO3_DTMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                      const sunrealtype v[3], sunrealtype *M, sunindextype ld,
                      sunbooleantype add);
void lgnSO3_D2TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype w[3], const sunrealtype v[3],
                       sunrealtype *M, sunindextype ld, sunbooleantype add);
void lgnSO3_D3TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                       const sunrealtype U[3], const sunrealtype W[3],
                       const sunrealtype v[3], sunrealtype *M, sunindextype ld,
                       sunbooleantype add);

/* The rotation blocks of the exact kinematics' derivatives (lgn_tangent.c)
 * at x with xd = sigma_dot, xdd = sigma_ddot of that rotation and T = T(x)
 * (leading dimension ld for T, Tv and Ta):
 *   Tv = T + DT[.] xd / gamma'
 *   Ta = T + (gamma'/beta') (DT[.] xd + Tdot(x, xd))
 *          + (DT[.] xdd + D^2T[., xd] xd) / beta'
 * (DT[u] y = Tdot(x, u) y). Coefficients LGN_SO3_D2T at |x|. */
void lgnSO3_ExactBlocks(const lgnSO3_Coef *c, const sunrealtype x[3],
                        const sunrealtype xd[3], const sunrealtype xdd[3],
                        sunrealtype gamma_p, sunrealtype beta_p,
                        const sunrealtype *T, sunrealtype *Tv, sunrealtype *Ta,
                        sunindextype ld);

/* M = T(x) as a 3x3 column-major block with leading dimension ld. */
void lgnSO3_TMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                     sunrealtype *M, sunindextype ld);
void lgnSO3_TMatrix(const sunrealtype x[3], sunrealtype *M, sunindextype ld);

/* M = Tdot(x, xd) (= DT(x)[xd]) as a 3x3 column-major block, coefficients
 * A|B|C1|C2 at |x|. */
void lgnSO3_TDotMatrixC(const lgnSO3_Coef *c, const sunrealtype x[3],
                        const sunrealtype xd[3], sunrealtype *M,
                        sunindextype ld);

/* Small 3-vector kernels, shared by the groups and the joint and body sets
 * (3x3 matrices row-major, as LGNQuaternionToRotation writes them). */

/* z = x . y */
static inline sunrealtype lgnVec3Dot(const sunrealtype x[3], const sunrealtype y[3])
{
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

/* z = x cross y (z may alias neither argument) */
static inline void lgnVec3Cross(const sunrealtype x[3], const sunrealtype y[3],
                                sunrealtype z[3])
{
  z[0] = x[1] * y[2] - x[2] * y[1];
  z[1] = x[2] * y[0] - x[0] * y[2];
  z[2] = x[0] * y[1] - x[1] * y[0];
}

/* y = A x and y = A^T x (y may not alias x) */
static inline void lgnMat3Apply(const sunrealtype A[9], const sunrealtype x[3],
                                sunrealtype y[3])
{
  int i;
  for (i = 0; i < 3; i++) y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}

static inline void lgnMat3ApplyT(const sunrealtype A[9], const sunrealtype x[3],
                                 sunrealtype y[3])
{
  int i;
  for (i = 0; i < 3; i++) y[i] = A[i] * x[0] + A[3 + i] * x[1] + A[6 + i] * x[2];
}

/* r = p1 (x) p2, the Hamilton product (r may alias p1 or p2: all inputs are
 * read first): inline, since
 * the composition p (x) expq(w) runs for every body at every iterate;
 * LGNQuaternionMultiply is this. */
static inline void lgnSO3_QuatMultiply(const sunrealtype p1[4],
                                       const sunrealtype p2[4], sunrealtype r[4])
{
  /* (w1,v1)(w2,v2) = (w1w2 - v1.v2, w1 v2 + w2 v1 + v1 x v2) */
  const sunrealtype w1 = p1[0], x1 = p1[1], y1 = p1[2], z1 = p1[3];
  const sunrealtype w2 = p2[0], x2 = p2[1], y2 = p2[2], z2 = p2[3];
  r[0] = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2;
  r[1] = w1 * x2 + w2 * x1 + y1 * z2 - z1 * y2;
  r[2] = w1 * y2 + w2 * y1 + z1 * x2 - x1 * z2;
  r[3] = w1 * z2 + w2 * z1 + x1 * y2 - y1 * x2;
}

/* p = (cos(phi/2), sin(phi/2) x/phi), the unit quaternion of exp(x~). */
void lgnSO3_ExpQuat(const sunrealtype x[3], sunrealtype p[4]);

/* p_out = p (x) e for a unit quaternion e (lgnSO3_CoefsExp's), renormalised
 * as lgnSO3_QuatComposeExp does; p_out may alias p. */
void lgnSO3_QuatComposeQuat(const sunrealtype p[4], const sunrealtype e[4],
                            sunrealtype p_out[4]);

/* p_out = p (x) expq(w), renormalised; p_out may alias p. */
void lgnSO3_QuatComposeExp(const sunrealtype p[4], const sunrealtype w[3],
                           sunrealtype p_out[4]);

/* Below this ratio r = |v|/w = tan(angle/2) of a quaternion (w, v), w >= 0,
 * the logarithm uses the series of atan(r)/r (to r^12: truncation below
 * r^14/15 < 5e-20 there) instead of atan2: the same increments that take
 * the series branch of expq (angle/2 < 0.05) take it here. */
#define LGN_SO3_THR_LOG SUN_RCONST(0.05)

/* phi = log(p), the rotation vector of the rotation of p, |phi| <= pi.
 * p and -p give the same phi: the sign is chosen with w >= 0 and, at w = 0
 * (angle pi), with the first nonzero entry of (x, y, z) positive.
 * Scale-invariant: any nonzero multiple of a unit quaternion (a quaternion
 * unnormalised by roundoff, say) gives the log of p/|p|. Relative accuracy
 * down to the smallest normal angles (no squares that underflow decide a
 * branch). Returns 0, or -1 (phi = 0) when p is zero or not finite. */
int lgnSO3_LogQuat(const sunrealtype p[4], sunrealtype phi[3]);

/* phi = log(conj(p1) (x) p2), the body-fixed rotation vector with
 * p2 = p1 (x) expq(phi) (the inverse of lgnSO3_QuatComposeExp); phi must
 * not alias p1 or p2. Returns lgnSO3_LogQuat's flag. */
int lgnSO3_QuatComposeLog(const sunrealtype p1[4], const sunrealtype p2[4],
                          sunrealtype phi[3]);

/* Scale p to unit length (left unchanged if p = 0). */
int lgnSO3_QuatNormalize(sunrealtype p[4]); /* -1: zero or not finite */

/* y = R(p) v for a unit quaternion p; y may alias v. */
void lgnSO3_QuatRotate(const sunrealtype p[4], const sunrealtype v[3],
                       sunrealtype y[3]);

#endif
