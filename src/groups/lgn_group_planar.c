/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The planar groups (include/lignum/lignum_planar.h), q = (x, y, theta) with
 * the angle stored unwrapped (it counts turns), nq = nv = 3.
 *
 * R^2 x SO(2), v = (u inertial, omega): q o exp(w) = q + w, T = I, Tdot = 0.
 *
 * SE(2), v = (U body, omega), xdot = R(theta) U. With J = [[0,-1],[1,0]],
 * ad(U, om) = [[om J, -J U], [0, 0]] and T = sum (-1)^i/(i+1)! ad^i:
 *   T(w)   = [[A, c], [0, 1]],   A = s I - k J,   c = al U + be J U,
 *   s = sin(om)/om, k = (1 - cos om)/om, al = (om - sin om)/om^2,
 *   be = (1 - cos om)/om^2;
 *   exp(U, om) = (A^T U, om), so q o exp(w) = (x + R(theta) A^T U, theta + om);
 *   T^{-1} = [[A^{-1}, -A^{-1} c], [0, 1]], A^{-1} = A^T / (s^2 + k^2);
 *   Tdot(w, wd) = [[(s' I - k' J) omd, al' omd U + al Ud + be' omd J U
 *                   + be J Ud], [0, 0]]   (' = d/d om).
 * The coefficients are SO(3)'s at phi = |om| (lgn_so3.h, series at small
 * angles): s = sinc, be = cc, al = om b, k = om cc, s' = -2 om b - om^3 c2,
 * k' = cc - om^2 c1, al' = b + om^2 c2, be' = -om c1. SE(2) is the
 * subgroup of SE(3) of motions in the x-y plane: these are the SE(3)
 * formulas at Omega = (0, 0, om), U = (U1, U2, 0) (checked in test_planar_group).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stddef.h>

#include <lignum/lignum_planar.h>

#include "lgn_so3.h"
#include "lgn_group_impl.h"

/* ---------------------------------------------------------------------------
 * R^2 x SO(2)
 * ------------------------------------------------------------------------ */

static int R2SO2ComposeExp(LGNGroup G, const sunrealtype *q,
                           const sunrealtype *w, sunrealtype *q_out)
{
  (void)G;
  q_out[0] = q[0] + w[0];
  q_out[1] = q[1] + w[1];
  q_out[2] = q[2] + w[2];
  return 0;
}

static int R2SO2ComposeLog(LGNGroup G, const sunrealtype *q1,
                           const sunrealtype *q2, sunrealtype *w)
{
  (void)G;
  w[0] = q2[0] - q1[0];
  w[1] = q2[1] - q1[1];
  w[2] = q2[2] - q1[2];
  return 0;
}

static int R2SO2TangentApply(LGNGroup G, const sunrealtype *w,
                             const sunrealtype *x, sunrealtype *y)
{
  (void)G;
  (void)w;
  y[0] = x[0];
  y[1] = x[1];
  y[2] = x[2];
  return 0;
}

static int R2SO2TangentDotApply(LGNGroup G, const sunrealtype *w,
                                const sunrealtype *wdot, const sunrealtype *x,
                                sunrealtype *y)
{
  (void)G;
  (void)w;
  (void)wdot;
  (void)x;
  y[0] = y[1] = y[2] = 0;
  return 0;
}

static int R2SO2TangentMatrix(LGNGroup G, const sunrealtype *w,
                              sunrealtype *Tm, sunindextype ld)
{
  int i, j;
  (void)G;
  (void)w;
  if (ld < 3) return -1;
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) Tm[i + j * ld] = (i == j) ? 1 : 0;
  return 0;
}

static int PlanarIdentity(LGNGroup G, sunrealtype *q)
{
  (void)G;
  q[0] = q[1] = q[2] = 0;
  return 0;
}

LGNGroup LGNGroup_R2xSO2(void)
{
  LGNGroup G = LGNGroup_NewEmpty(3, 3);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_R2XSO2;
  G->ops.compose_exp           = R2SO2ComposeExp;
  G->ops.tangent_apply         = R2SO2TangentApply;
  G->ops.tangent_inverse_apply = R2SO2TangentApply;
  G->ops.tangent_dot_apply     = R2SO2TangentDotApply;
  G->ops.tangent_matrix        = R2SO2TangentMatrix;
  G->ops.identity              = PlanarIdentity;
  G->ops.normalize             = NULL;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = R2SO2ComposeLog;
  return G;
}

/* ---------------------------------------------------------------------------
 * SE(2)
 * ------------------------------------------------------------------------ */

/* The coefficients of T at the angle om (see the top of the file). */
typedef struct {
  sunrealtype s, k, al, be;     /* T                  */
  sunrealtype ds, dk, dal, dbe; /* their derivatives  */
} SE2Coef;

/* Below this s^2 + k^2 = (sin(om/2)/(om/2))^2, near om = 2 pi n (n != 0),
 * A is singular to working accuracy (condition above 1e8): exp maps every
 * U to (nearly) the same point, and the log and T^{-1} are refused. */
#define SE2_DET_MIN SUN_RCONST(1.0e-16)

static void SE2Coefs(sunrealtype om, sunbooleantype derivs, SE2Coef *c)
{
  lgnSO3_Coef sc;
  const sunrealtype o2 = om * om;
  unsigned need = LGN_SO3_SINC | LGN_SO3_CC | LGN_SO3_B;
  if (derivs) need |= LGN_SO3_C1 | LGN_SO3_C2;
  lgnSO3_Coefs(fabs(om), need, &sc);
  c->s  = sc.sinc;
  c->k  = om * sc.cc;
  c->al = om * sc.b;
  c->be = sc.cc;
  if (derivs) {
    c->ds  = -2 * om * sc.b - o2 * om * sc.c2;
    c->dk  = sc.cc - o2 * sc.c1;
    c->dal = sc.b + o2 * sc.c2;
    c->dbe = -om * sc.c1;
  } else {
    c->ds = c->dk = c->dal = c->dbe = 0;
  }
}

static int SE2ComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                         sunrealtype *q_out)
{
  /* x += R(theta) A^T U, A^T = s I + k J */
  SE2Coef c;
  sunrealtype d0, d1, cs, sn;
  (void)G;
  SE2Coefs(w[2], SUNFALSE, &c);
  d0 = c.s * w[0] - c.k * w[1];
  d1 = c.k * w[0] + c.s * w[1];
  cs = cos(q[2]);
  sn = sin(q[2]);
  q_out[0] = q[0] + cs * d0 - sn * d1;
  q_out[1] = q[1] + sn * d0 + cs * d1;
  q_out[2] = q[2] + w[2];
  return 0;
}

static int SE2ComposeLog(LGNGroup G, const sunrealtype *q1,
                         const sunrealtype *q2, sunrealtype *w)
{
  /* om = theta2 - theta1, U = A^{-T} R(theta1)^T (x2 - x1) */
  SE2Coef c;
  const sunrealtype cs = cos(q1[2]), sn = sin(q1[2]);
  const sunrealtype dx = q2[0] - q1[0], dy = q2[1] - q1[1];
  const sunrealtype r0 = cs * dx + sn * dy, r1 = -sn * dx + cs * dy;
  sunrealtype det;
  (void)G;
  w[2] = q2[2] - q1[2];
  SE2Coefs(w[2], SUNFALSE, &c);
  det = c.s * c.s + c.k * c.k; /* (sin(om/2)/(om/2))^2: 0 at om = 2 pi n */
  if (!(det > SE2_DET_MIN)) return -1;
  /* A^T = [[s, -k], [k, s]], its inverse [[s, k], [-k, s]] / det */
  w[0] = (c.s * r0 + c.k * r1) / det;
  w[1] = (-c.k * r0 + c.s * r1) / det;
  return 0;
}

/* y = T(w) x */
static void SE2TApplyC(const SE2Coef *c, const sunrealtype *w,
                       const sunrealtype *x, sunrealtype *y)
{
  /* A = [[s, k], [-k, s]], c = (al U1 - be U2, al U2 + be U1) */
  y[0] = c->s * x[0] + c->k * x[1] + (c->al * w[0] - c->be * w[1]) * x[2];
  y[1] = -c->k * x[0] + c->s * x[1] + (c->al * w[1] + c->be * w[0]) * x[2];
  y[2] = x[2];
}

static int SE2TangentApply(LGNGroup G, const sunrealtype *w,
                           const sunrealtype *x, sunrealtype *y)
{
  SE2Coef c;
  (void)G;
  SE2Coefs(w[2], SUNFALSE, &c);
  SE2TApplyC(&c, w, x, y);
  return 0;
}

static int SE2TangentInverseApply(LGNGroup G, const sunrealtype *w,
                                  const sunrealtype *x, sunrealtype *y)
{
  /* y_om = x_om, y_U = A^{-1} (x_U - c x_om), A^{-1} = A^T / (s^2 + k^2) */
  SE2Coef c;
  sunrealtype r0, r1, det;
  (void)G;
  SE2Coefs(w[2], SUNFALSE, &c);
  det = c.s * c.s + c.k * c.k;
  if (!(det > SE2_DET_MIN)) return -1;
  r0 = x[0] - (c.al * w[0] - c.be * w[1]) * x[2];
  r1 = x[1] - (c.al * w[1] + c.be * w[0]) * x[2];
  y[0] = (c.s * r0 - c.k * r1) / det;
  y[1] = (c.k * r0 + c.s * r1) / det;
  y[2] = x[2];
  return 0;
}

static int SE2TangentDotApply(LGNGroup G, const sunrealtype *w,
                              const sunrealtype *wdot, const sunrealtype *x,
                              sunrealtype *y)
{
  /* the om-derivative of A times omd, and d/dt c */
  SE2Coef c;
  const sunrealtype omd = wdot[2];
  sunrealtype c0, c1;
  (void)G;
  SE2Coefs(w[2], SUNTRUE, &c);
  c0 = (c.dal * w[0] - c.dbe * w[1]) * omd + c.al * wdot[0] - c.be * wdot[1];
  c1 = (c.dal * w[1] + c.dbe * w[0]) * omd + c.al * wdot[1] + c.be * wdot[0];
  y[0] = (c.ds * x[0] + c.dk * x[1]) * omd + c0 * x[2];
  y[1] = (-c.dk * x[0] + c.ds * x[1]) * omd + c1 * x[2];
  y[2] = 0;
  return 0;
}

static int SE2TangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                            sunindextype ld)
{
  SE2Coef c;
  (void)G;
  if (ld < 3) return -1;
  SE2Coefs(w[2], SUNFALSE, &c);
  Tm[0] = c.s;
  Tm[1] = -c.k;
  Tm[2] = 0;
  Tm[ld]     = c.k;
  Tm[ld + 1] = c.s;
  Tm[ld + 2] = 0;
  Tm[2 * ld]     = c.al * w[0] - c.be * w[1];
  Tm[2 * ld + 1] = c.al * w[1] + c.be * w[0];
  Tm[2 * ld + 2] = 1;
  return 0;
}

LGNGroup LGNGroup_SE2(void)
{
  LGNGroup G = LGNGroup_NewEmpty(3, 3);
  if (G == NULL) return NULL;
  G->kind                      = LGN_GROUP_SE2;
  G->ops.compose_exp           = SE2ComposeExp;
  G->ops.tangent_apply         = SE2TangentApply;
  G->ops.tangent_inverse_apply = SE2TangentInverseApply;
  G->ops.tangent_dot_apply     = SE2TangentDotApply;
  G->ops.tangent_matrix        = SE2TangentMatrix;
  G->ops.identity              = PlanarIdentity;
  G->ops.normalize             = NULL;
  G->ops.free_content          = NULL;
  G->ops.compose_log           = SE2ComposeLog;
  return G;
}

/* ---------------------------------------------------------------------------
 * The planar bodies of a group (lgn_group_impl.h)
 * ------------------------------------------------------------------------ */

static int Leaves(LGNGroup G, sunindextype q0, sunindextype v0, int n,
                  sunindextype *qoff, sunindextype *voff, sunbooleantype *se2)
{
  int nf, k;
  const LGNGroup *f;
  const sunindextype *qo, *vo;
  if (lgnGroupProductFactors(G, &nf, &f, &qo, &vo) == 0) {
    for (k = 0; k < nf; k++) {
      n = Leaves(f[k], q0 + qo[k], v0 + vo[k], n, qoff, voff, se2);
      if (n < 0) return -1;
    }
    return n;
  }
  if (G->kind != LGN_GROUP_SE2 && G->kind != LGN_GROUP_R2XSO2) return -1;
  if (qoff != NULL) {
    qoff[n] = q0;
    voff[n] = v0;
    se2[n]  = G->kind == LGN_GROUP_SE2;
  }
  return n + 1;
}

int lgnGroupPlanarBodies(LGNGroup G, sunindextype *qoff, sunindextype *voff,
                         sunbooleantype *se2)
{
  if (G == NULL) return -1;
  return Leaves(G, 0, 0, 0, qoff, voff, se2);
}
