/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * SE(3) (doc/theory.md §1.1): q = (x[3], p[4]), v = (U, Omega), both
 * body-fixed (xdot = R U). (x1,R1) o (x2,R2) = (x1 + R1 x2, R1 R2) and
 * exp(U, Omega) = (T_SO3(Omega)^T U, exp Omega~), so
 *   q o exp(U, Omega) = (x + R(p) T(Omega)^T U, p (x) expq(Omega)),
 * and its inverse, the log in the chart at q1 = (x1, p1):
 *   log(q1^{-1} q2) = (T(Omega)^{-T} R(p1)^T (x2 - x1), Omega),
 *   Omega = log(conj(p1) (x) p2),   T(Omega)^{-T} = T(-Omega)^{-1}.
 * With DT(Omega)[U] := Tdot_SO3(Omega, U) (§4.3):
 *   T      = [[T, DT[U]], [0, T]]
 *   T^{-1} = [[T^{-1}, -T^{-1} DT[U] T^{-1}], [0, T^{-1}]]
 *   Tdot   = [[DT[Wd], D^2T[U,Wd] + DT[Ud]], [0, DT[Wd]]],  wdot = (Ud, Wd).
 * ---------------------------------------------------------------------------*/

#include <stddef.h>

#include "lgn_so3.h"
#include "lgn_group_impl.h"

#define SE3_NEED_T (LGN_SO3_A | LGN_SO3_B | LGN_SO3_C1 | LGN_SO3_C2)

/* q_out = q o exp(w) with the coefficients (A|B) at |Omega| and
 * e = expq(Omega) given */
static void ComposeExpC(const lgnSO3_Coef *c, const sunrealtype *q,
                        const sunrealtype *w, const sunrealtype e[4],
                        sunrealtype *q_out)
{
  /* T(Omega)^T = T(-Omega) since x~ is skew and x~^2 symmetric */
  sunrealtype mOm[3], VU[3], R[9];
  int i;
  mOm[0] = -w[3];
  mOm[1] = -w[4];
  mOm[2] = -w[5];
  lgnSO3_TApplyC(c, mOm, w, VU);
  LGNQuaternionToRotation(q + 3, R);
  for (i = 0; i < 3; i++)
    q_out[i] = q[i] + R[3 * i] * VU[0] + R[3 * i + 1] * VU[1]
             + R[3 * i + 2] * VU[2];
  lgnSO3_QuatComposeQuat(q + 3, e, q_out + 3);
}

static int SE3ComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                         sunrealtype *q_out)
{
  lgnSO3_Coef c;
  sunrealtype e[4];
  (void)G;
  lgnSO3_CoefsExp(w + 3, LGN_SO3_A | LGN_SO3_B, &c, e);
  ComposeExpC(&c, q, w, e, q_out);
  return 0;
}

static int SE3ComposeLog(LGNGroup G, const sunrealtype *q1,
                         const sunrealtype *q2, sunrealtype *w)
{
  /* undo compose_exp step by step with the same R(p1): xr = R^T (x2 - x1)
   * = T(Omega)^T U, so U = T(-Omega)^{-1} xr */
  sunrealtype R[9], dx[3], xr[3], mOm[3];
  int flag;
  (void)G;
  flag = lgnSO3_QuatComposeLog(q1 + 3, q2 + 3, w + 3);
  if (flag != 0) return flag;
  LGNQuaternionToRotation(q1 + 3, R);
  dx[0] = q2[0] - q1[0];
  dx[1] = q2[1] - q1[1];
  dx[2] = q2[2] - q1[2];
  lgnMat3ApplyT(R, dx, xr);
  mOm[0] = -w[3];
  mOm[1] = -w[4];
  mOm[2] = -w[5];
  lgnSO3_TInvApply(mOm, xr, w);
  return 0;
}

/* y = T(w) x, coefficients SE3_NEED_T at |Omega| */
static void TangentApplyC(const lgnSO3_Coef *c, const sunrealtype *w,
                          const sunrealtype *x, sunrealtype *y)
{
  /* y_U = T x_U + DT[U] x_Om,  y_Om = T x_Om */
  sunrealtype t[3];
  lgnSO3_TApplyC(c, w + 3, x, y);
  lgnSO3_TDotApplyC(c, w + 3, w, x + 3, t);
  y[0] += t[0];
  y[1] += t[1];
  y[2] += t[2];
  lgnSO3_TApplyC(c, w + 3, x + 3, y + 3);
}

static int SE3TangentApply(LGNGroup G, const sunrealtype *w,
                           const sunrealtype *x, sunrealtype *y)
{
  lgnSO3_Coef c;
  (void)G;
  lgnSO3_Coefs(lgnSO3_Norm(w + 3), SE3_NEED_T, &c);
  TangentApplyC(&c, w, x, y);
  return 0;
}

static int SE3TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                  const sunrealtype *x, sunrealtype *y)
{
  /* y_Om = T^{-1} x_Om,  y_U = T^{-1}(x_U - DT[U] y_Om) */
  lgnSO3_Coef c;
  sunrealtype t[3];
  (void)G;
  lgnSO3_Coefs(lgnSO3_Norm(w + 3), SE3_NEED_T | LGN_SO3_D, &c);
  lgnSO3_TInvApplyC(&c, w + 3, x + 3, y + 3);
  lgnSO3_TDotApplyC(&c, w + 3, w, y + 3, t);
  t[0] = x[0] - t[0];
  t[1] = x[1] - t[1];
  t[2] = x[2] - t[2];
  lgnSO3_TInvApplyC(&c, w + 3, t, y);
  return 0;
}

/* y = Tdot(w, wdot) x, coefficients LGN_SO3_D2T at |Omega| */
static void TangentDotApplyC(const lgnSO3_Coef *c, const sunrealtype *w,
                             const sunrealtype *wdot, const sunrealtype *x,
                             sunrealtype *y)
{
  /* y_U  = DT[Wd] x_U + D^2T[U,Wd] x_Om + DT[Ud] x_Om,  y_Om = DT[Wd] x_Om */
  sunrealtype t1[3], t2[3];
  lgnSO3_TDotApplyC(c, w + 3, wdot + 3, x, y);
  lgnSO3_D2TApplyC(c, w + 3, w, wdot + 3, x + 3, t1);
  lgnSO3_TDotApplyC(c, w + 3, wdot, x + 3, t2);
  y[0] += t1[0] + t2[0];
  y[1] += t1[1] + t2[1];
  y[2] += t1[2] + t2[2];
  lgnSO3_TDotApplyC(c, w + 3, wdot + 3, x + 3, y + 3);
}

static int SE3TangentDotApply(LGNGroup G, const sunrealtype *w,
                              const sunrealtype *wdot, const sunrealtype *x,
                              sunrealtype *y)
{
  lgnSO3_Coef c;
  (void)G;
  lgnSO3_Coefs(lgnSO3_Norm(w + 3), LGN_SO3_D2T, &c);
  TangentDotApplyC(&c, w, wdot, x, y);
  return 0;
}

/* Tm = T(w) (leading dimension ld), coefficients SE3_NEED_T at |Omega| */
static void TangentMatrixC(const lgnSO3_Coef *c, const sunrealtype *w,
                           sunrealtype *Tm, sunindextype ld)
{
  int i, j;
  lgnSO3_TMatrixC(c, w + 3, Tm, ld);                /* (U,U)   block */
  lgnSO3_TDotMatrixC(c, w + 3, w, Tm + 3 * ld, ld); /* (U,Om)  block */
  for (j = 0; j < 3; j++)                           /* (Om,U)  block */
    for (i = 3; i < 6; i++) Tm[i + j * ld] = 0;
  lgnSO3_TMatrixC(c, w + 3, Tm + 3 + 3 * ld, ld);   /* (Om,Om) block */
}

static int SE3TangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                            sunindextype ld)
{
  lgnSO3_Coef c;
  (void)G;
  if (ld < 6) return -1;
  lgnSO3_Coefs(lgnSO3_Norm(w + 3), SE3_NEED_T, &c);
  TangentMatrixC(&c, w, Tm, ld);
  return 0;
}

static int SE3Identity(LGNGroup G, sunrealtype *q)
{
  (void)G;
  q[0] = q[1] = q[2] = 0;
  q[3] = 1;
  q[4] = q[5] = q[6] = 0;
  return 0;
}

static int SE3Normalize(LGNGroup G, sunrealtype *q)
{
  (void)G;
  return lgnSO3_QuatNormalize(q + 3);
}

/* The library's own SE(3) ops (not replaced by the user)? */
static sunbooleantype OwnOps(LGNGroup G)
{
  return G->kind == LGN_GROUP_SE3 && G->ops.compose_exp == SE3ComposeExp &&
         G->ops.tangent_apply == SE3TangentApply &&
         G->ops.tangent_dot_apply == SE3TangentDotApply &&
         G->ops.tangent_matrix == SE3TangentMatrix;
}

int lgnGroupSE3ExactMap(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                        const sunrealtype *wd, const sunrealtype *wdd,
                        sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                        sunrealtype *Tm)
{
  lgnSO3_Coef c;
  sunrealtype e[4], t[6];
  int i;
  if (!OwnOps(G)) return 1;
  lgnSO3_CoefsExp(w + 3, LGN_SO3_D2T, &c, e);
  ComposeExpC(&c, q, w, e, q1);
  if (Tm != NULL) TangentMatrixC(&c, w, Tm, 6);
  TangentApplyC(&c, w, wd, v);
  TangentApplyC(&c, w, wdd, vdot);
  TangentDotApplyC(&c, w, wd, wd, t);
  for (i = 0; i < 6; i++) vdot[i] += t[i];
  return 0;
}

/* In blocks (rows U, Omega; columns the directions of U and Omega), with
 * x = Omega, (Ud, Wd) = wd, (Udd, Wdd) = wdd, J(y) u = DT[u] y,
 * K(z, y) u = D^2T[u, z] y, L(U, z, y) u = D^3T[u, U, z] y:
 *   D_w[T(w) y]          = [[J(y_Om), J(y_U) + K(U, y_Om)], [0, J(y_Om)]]
 *   Tdot(w, wd)          = [[Tdot(Wd), D^2T[U, Wd] + Tdot(Ud)], [0, Tdot(Wd)]]
 *   D_w[Tdot(w, wd) wd]  = [[K(Wd, Wd), K(Wd, Ud) + K(Ud, Wd) + L(U, Wd, Wd)],
 *                           [0, K(Wd, Wd)]]
 * so the diagonal blocks are SO(3)'s (lgnSO3_ExactBlocks with Wd, Wdd) and
 * the (U, Omega) block is assembled here. */
int lgnGroupSE3ExactDerivatives(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wd, const sunrealtype *wdd,
                                sunrealtype gamma_p, sunrealtype beta_p,
                                const sunrealtype *Tm, sunrealtype *Tv,
                                sunrealtype *Ta)
{
  lgnSO3_Coef c;
  const sunrealtype *x = w + 3, *U = w, *Ud = wd, *Wd = wd + 3;
  const sunrealtype *Udd = wdd, *Wdd = wdd + 3;
  const sunrealtype ratio = gamma_p / beta_p;
  sunrealtype P[9], D[9], Q[9], e[3] = {0, 0, 0}, col[3];
  int i, j;
  if (!OwnOps(G)) return 1;
  lgnSO3_Coefs(lgnSO3_Norm(x), LGN_SO3_D3T, &c);
  /* diagonal blocks */
  lgnSO3_ExactBlocks(&c, x, Wd, Wdd, gamma_p, beta_p, Tm, Tv, Ta, 6);
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) {
      Tv[3 + i + (3 + j) * 6] = Tv[i + j * 6];
      Ta[3 + i + (3 + j) * 6] = Ta[i + j * 6];
      Tv[3 + i + j * 6] = Ta[3 + i + j * 6] = 0;
    }
  /* (U, Omega): P = J(Ud) + K(U, Wd) */
  lgnSO3_DTMatrixC(&c, x, Ud, P, 3, SUNFALSE);
  lgnSO3_D2TMatrixC(&c, x, U, Wd, P, 3, SUNTRUE);
  /* D = D^2T[U, Wd] + Tdot(Ud), the first by columns */
  lgnSO3_TDotMatrixC(&c, x, Ud, D, 3);
  for (j = 0; j < 3; j++) {
    e[j] = 1;
    lgnSO3_D2TApplyC(&c, x, U, Wd, e, col);
    e[j] = 0;
    for (i = 0; i < 3; i++) D[i + 3 * j] += col[i];
  }
  /* Q = J(Udd) + K(U, Wdd) + K(Wd, Ud) + K(Ud, Wd) + L(U, Wd, Wd) */
  lgnSO3_DTMatrixC(&c, x, Udd, Q, 3, SUNFALSE);
  lgnSO3_D2TMatrixC(&c, x, U, Wdd, Q, 3, SUNTRUE);
  lgnSO3_D2TMatrixC(&c, x, Wd, Ud, Q, 3, SUNTRUE);
  lgnSO3_D2TMatrixC(&c, x, Ud, Wd, Q, 3, SUNTRUE);
  lgnSO3_D3TMatrixC(&c, x, U, Wd, Wd, Q, 3, SUNTRUE);
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) {
      const sunrealtype t = Tm[i + (3 + j) * 6], p = P[i + 3 * j];
      Tv[i + (3 + j) * 6] = t + p / gamma_p;
      Ta[i + (3 + j) * 6] = t + ratio * (p + D[i + 3 * j]) + Q[i + 3 * j] / beta_p;
    }
  return 0;
}

LGNGroup LGNGroup_SE3(void)
{
  LGNGroup G = LGNGroup_NewEmpty(7, 6);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_SE3;
  G->ops.compose_exp           = SE3ComposeExp;
  G->ops.tangent_apply         = SE3TangentApply;
  G->ops.tangent_inverse_apply = SE3TangentInverseApply;
  G->ops.tangent_dot_apply     = SE3TangentDotApply;
  G->ops.tangent_matrix        = SE3TangentMatrix;
  G->ops.identity              = SE3Identity;
  G->ops.normalize             = SE3Normalize;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = SE3ComposeLog;
  return G;
}
