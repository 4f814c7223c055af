/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Planar rigid bodies and force elements (include/lignum/lignum_planar.h):
 * the part of a body set on SE(2) or R^2 x SO(2) bodies, q_k = (x, y,
 * theta), M = diag(m, m, J) and
 *   R^2 x SO(2), v = (u inertial, omega):  g = (-m gvec - F, -tau)
 *   SE(2), v = (U body, omega):  g = (m omega J U - R^T (m gvec + F), -tau)
 * (J = [[0, -1], [1, 0]]; (F, tau) the applied force and torque), so that
 * C_t = dg/dv has m omega J and m J U on SE(2), and K_t = dg/dq has the
 * column d/dtheta (-R^T m gvec) = J R^T m gvec.
 *
 * Translational spring-damper between points of a and b, d = p_b - p_a,
 * L = |d|, n = d / L: with the gradient gL = n^T Dd (Dd = [-H_a, H_b],
 * lgn_planar.h) and the tension f = k (L - L0) + c gL v, g += f gL (the
 * derivative of the potential k (L - L0)^2 / 2 plus the damping), so
 *   K_t += gL (k gL + c v^T HL) + f HL,   C_t += c gL gL^T,
 * HL = Dd^T (I - n n^T) Dd / L + n . (E_b - E_a) (the Hessian of L).
 * Rotational spring-damper: tau = kr (theta_b - theta_a - theta0)
 * + cr (omega_b - omega_a) on b (minus), the reaction on a.
 * ---------------------------------------------------------------------------*/

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "groups/lgn_group_impl.h"
#include "lgn_argcheck.h"
#include "lgn_matops.h"
#include "lgn_planar.h"

typedef enum { ELEM_SPRING = 0, ELEM_ROTSPRING } ElemKind;

typedef struct {
  ElemKind kind;
  int a, b;
  sunrealtype sa[2], sb[2];
  sunrealtype k, c, L0; /* L0: theta0 for the rotational spring */
} Element;

struct lgnPlanarBodiesRec {
  const LGNErrSink *err;
  LGNGroup G;
  int nb;
  sunindextype *qoff, *voff;
  sunbooleantype *se2;
  sunrealtype *mass, *inertia;
  sunrealtype gravity[2];
  Element *elem;
  int nelem, cap;
  lgnPlanarPattern patM, patK;
};

lgnPlanarBodies *lgnPlanarBodiesCreate(LGNGroup G, const LGNErrSink *err, const char *func)
{
  lgnPlanarBodies *P = (lgnPlanarBodies *)calloc(1, sizeof *P);
  const int nb = lgnGroupPlanarBodies(G, NULL, NULL, NULL);
  int k;
  if (P != NULL) {
    P->qoff    = (sunindextype *)malloc((size_t)nb * sizeof *P->qoff);
    P->voff    = (sunindextype *)malloc((size_t)nb * sizeof *P->voff);
    P->se2     = (sunbooleantype *)malloc((size_t)nb * sizeof *P->se2);
    P->mass    = (sunrealtype *)malloc((size_t)nb * sizeof *P->mass);
    P->inertia = (sunrealtype *)malloc((size_t)nb * sizeof *P->inertia);
  }
  if (P == NULL || P->qoff == NULL || P->voff == NULL || P->se2 == NULL ||
      P->mass == NULL || P->inertia == NULL) {
    lgnPlanarBodiesDestroy(P);
    lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
    return NULL;
  }
  P->err = err;
  P->G   = G;
  P->nb  = nb;
  lgnGroupPlanarBodies(G, P->qoff, P->voff, P->se2);
  for (k = 0; k < nb; k++) P->mass[k] = P->inertia[k] = 1;
  P->patM.fmt = P->patK.fmt = -1;
  return P;
}

void lgnPlanarBodiesDestroy(lgnPlanarBodies *P)
{
  if (P == NULL) return;
  free(P->qoff);
  free(P->voff);
  free(P->se2);
  free(P->mass);
  free(P->inertia);
  free(P->elem);
  lgnPlanarPatternFree(&P->patM);
  lgnPlanarPatternFree(&P->patK);
  free(P);
}

/* ---------------------------------------------------------------------------
 * Settings
 * ------------------------------------------------------------------------ */

static int CheckBody(const lgnPlanarBodies *P, int k, const char *func)
{
  if (k < 0 || k >= P->nb) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "k = %d illegal (0..%d).", k, P->nb - 1);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int lgnPlanarBodiesSetMass(lgnPlanarBodies *P, int k, sunrealtype m, sunrealtype Jz,
                           const char *func)
{
  if (CheckBody(P, k, func) != LGN_SUCCESS) return LGN_ILL_INPUT;
  if (!(m > 0) || !isfinite(m) || !(Jz > 0) || !isfinite(Jz)) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "m = %g, J = %g illegal: the mass and the inertia about the normal of "
              "the plane must be positive and finite.", (double)m, (double)Jz);
    return LGN_ILL_INPUT;
  }
  P->mass[k]    = m;
  P->inertia[k] = Jz;
  return LGN_SUCCESS;
}

int lgnPlanarBodiesSetGravity(lgnPlanarBodies *P, const sunrealtype gravity[3],
                              const char *func)
{
  if (lgnCheckVec3(P->err, gravity, "gravity", func) != LGN_SUCCESS) return LGN_ILL_INPUT;
  if (gravity[2] != 0) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "gravity[2] = %g illegal: planar bodies move in the x-y plane.",
              (double)gravity[2]);
    return LGN_ILL_INPUT;
  }
  P->gravity[0] = gravity[0];
  P->gravity[1] = gravity[1];
  return LGN_SUCCESS;
}

static int CheckPair(const lgnPlanarBodies *P, int a, int b, const char *func)
{
  if (a < LGN_GROUND || a >= P->nb || b < LGN_GROUND || b >= P->nb || a == b) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "bodies a = %d, b = %d illegal (0..%d or LGN_GROUND, a != b).", a, b,
              P->nb - 1);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static int CheckCoef(const lgnPlanarBodies *P, sunrealtype x, const char *name,
                     const char *func)
{
  if (!(x >= 0) || !isfinite(x)) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "%s = %g illegal: must be finite and >= 0.",
              name, (double)x);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static Element *NewElement(lgnPlanarBodies *P, const char *func)
{
  Element *e;
  if (P->nelem == P->cap) {
    const int cap = 2 * P->cap + 8;
    e = (Element *)realloc(P->elem, (size_t)cap * sizeof *e);
    if (e == NULL) {
      lgnReport(P->err, LGN_MEM_FAIL, func, "A memory request failed.");
      return NULL;
    }
    P->elem = e;
    P->cap  = cap;
  }
  e = P->elem + P->nelem++;
  memset(e, 0, sizeof *e);
  lgnPlanarPatternFree(&P->patK);
  return e;
}

static int AddSpring(lgnPlanarBodies *P, int a, const sunrealtype sa[2], int b,
                     const sunrealtype sb[2], sunrealtype k, sunrealtype c, sunrealtype L0,
                     const char *func)
{
  Element *e;
  if (CheckCoef(P, k, "k", func) != LGN_SUCCESS || CheckCoef(P, c, "c", func) != LGN_SUCCESS ||
      CheckCoef(P, L0, "L0", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((e = NewElement(P, func)) == NULL) return LGN_MEM_FAIL;
  e->kind  = ELEM_SPRING;
  e->a     = a;
  e->b     = b;
  e->sa[0] = sa[0];
  e->sa[1] = sa[1];
  e->sb[0] = sb[0];
  e->sb[1] = sb[1];
  e->k     = k;
  e->c     = c;
  e->L0    = L0;
  return LGN_SUCCESS;
}

static int CheckPoint2(const lgnPlanarBodies *P, const sunrealtype *x, const char *name,
                       const char *func)
{
  if (x == NULL || !isfinite(x[0]) || !isfinite(x[1])) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "%s illegal: NULL or not finite.", name);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int lgnPlanarBodiesAddSpring2(lgnPlanarBodies *P, int a, const sunrealtype sa[2], int b,
                              const sunrealtype sb[2], sunrealtype k, sunrealtype c,
                              sunrealtype L0, const char *func)
{
  if (CheckPair(P, a, b, func) != LGN_SUCCESS ||
      CheckPoint2(P, sa, "sa", func) != LGN_SUCCESS ||
      CheckPoint2(P, sb, "sb", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  return AddSpring(P, a, sa, b, sb, k, c, L0, func);
}

int lgnPlanarBodiesAddSpring3(lgnPlanarBodies *P, int a, const sunrealtype sa[3], int b,
                              const sunrealtype sb[3], sunrealtype k, sunrealtype c,
                              sunrealtype L0, const char *func)
{
  if (CheckPair(P, a, b, func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, sa, "sa", func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, sb, "sb", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (sa[2] != 0 || sb[2] != 0) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "sa[2] = %g, sb[2] = %g illegal: the points of a planar body lie in the "
              "plane (z = 0).", (double)sa[2], (double)sb[2]);
    return LGN_ILL_INPUT;
  }
  return AddSpring(P, a, sa, b, sb, k, c, L0, func);
}

static int AddRotSpring(lgnPlanarBodies *P, int a, int b, sunrealtype kr, sunrealtype cr,
                        sunrealtype theta0, const char *func)
{
  Element *e;
  if (CheckPair(P, a, b, func) != LGN_SUCCESS || CheckCoef(P, kr, "kr", func) != LGN_SUCCESS ||
      CheckCoef(P, cr, "cr", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (!isfinite(theta0)) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "theta0 = %g illegal: not finite.",
              (double)theta0);
    return LGN_ILL_INPUT;
  }
  if ((e = NewElement(P, func)) == NULL) return LGN_MEM_FAIL;
  e->kind = ELEM_ROTSPRING;
  e->a    = a;
  e->b    = b;
  e->k    = kr;
  e->c    = cr;
  e->L0   = theta0;
  return LGN_SUCCESS;
}

int lgnPlanarBodiesAddRotSpring(lgnPlanarBodies *P, int a, int b, sunrealtype kr,
                                sunrealtype cr, sunrealtype theta0, const char *func)
{
  return AddRotSpring(P, a, b, kr, cr, theta0, func);
}

int lgnPlanarBodiesAddRotSpringQuat(lgnPlanarBodies *P, int a, int b, sunrealtype kr,
                                    sunrealtype cr, const sunrealtype rest[4],
                                    const char *func)
{
  sunrealtype theta0 = 0;
  if (rest != NULL) {
    if (!isfinite(rest[0]) || !isfinite(rest[3]) || rest[1] != 0 || rest[2] != 0 ||
        (rest[0] == 0 && rest[3] == 0)) {
      lgnReport(P->err, LGN_ILL_INPUT, func,
                "rest = (%g, %g, %g, %g) illegal: on a planar group the rest rotation "
                "turns about the normal of the plane, (cos(a/2), 0, 0, sin(a/2)).",
                (double)rest[0], (double)rest[1], (double)rest[2], (double)rest[3]);
      return LGN_ILL_INPUT;
    }
    theta0 = 2 * atan2(rest[3], rest[0]);
  }
  return AddRotSpring(P, a, b, kr, cr, theta0, func);
}

/* ---------------------------------------------------------------------------
 * Evaluation
 * ------------------------------------------------------------------------ */

static void GetPose(const lgnPlanarBodies *P, int k, const sunrealtype *q,
                    const sunrealtype *v, lgnPlanarPose *X)
{
  memset(X, 0, sizeof *X);
  X->ground = k == LGN_GROUND;
  X->c      = 1;
  X->voff   = -1;
  if (X->ground) return;
  X->se2  = P->se2[k];
  X->x[0] = q[P->qoff[k]];
  X->x[1] = q[P->qoff[k] + 1];
  X->th   = q[P->qoff[k] + 2];
  X->c    = cos(X->th);
  X->s    = sin(X->th);
  X->voff = P->voff[k];
  if (v != NULL) {
    X->v[0] = v[X->voff];
    X->v[1] = v[X->voff + 1];
    X->v[2] = v[X->voff + 2];
  }
}

/* A spring's length L, gradient gL and (HL not NULL) Hessian HL on its two
 * bodies, its tension f (v not NULL); LGN_ILL_INPUT at a too short L. */
typedef struct {
  lgnPlanarPose A, B;
  sunrealtype L, f, gL[6], HL[36], vl[6];
} SpringLocal;

static int SpringEval(const lgnPlanarBodies *P, const Element *e, const sunrealtype *q,
                      const sunrealtype *v, SpringLocal *S, sunbooleantype hess,
                      const char *func)
{
  sunrealtype pa[2], pb[2], Ha[6], Hb[6], Dd[12], n[2], d[2], t[12];
  int i, j;
  GetPose(P, e->a, q, v, &S->A);
  GetPose(P, e->b, q, v, &S->B);
  lgnPlanarPoint(&S->A, e->sa, pa, Ha);
  lgnPlanarPoint(&S->B, e->sb, pb, Hb);
  d[0] = pb[0] - pa[0];
  d[1] = pb[1] - pa[1];
  S->L = hypot(d[0], d[1]);
  if (!(S->L > 100 * DBL_EPSILON * (1 + hypot(pa[0], pa[1]) + hypot(pb[0], pb[1])))) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "the spring-damper between bodies %d and %d has length %g: its direction is "
              "undefined.", e->a, e->b, (double)S->L);
    return LGN_ILL_INPUT;
  }
  n[0] = d[0] / S->L;
  n[1] = d[1] / S->L;
  for (i = 0; i < 3; i++) {
    Dd[i] = -Ha[i];
    Dd[6 + i] = -Ha[3 + i];
    Dd[3 + i] = Hb[i];
    Dd[9 + i] = Hb[3 + i];
    S->vl[i] = S->A.v[i];
    S->vl[3 + i] = S->B.v[i];
  }
  S->f = e->k * (S->L - e->L0);
  for (j = 0; j < 6; j++) {
    S->gL[j] = n[0] * Dd[j] + n[1] * Dd[6 + j];
    S->f += e->c * S->gL[j] * S->vl[j];
  }
  if (!hess) return LGN_SUCCESS;
  /* (I - n n^T) Dd / L, then HL = Dd^T that + n . E terms */
  for (j = 0; j < 6; j++) {
    const sunrealtype nd = n[0] * Dd[j] + n[1] * Dd[6 + j];
    t[j]     = (Dd[j] - n[0] * nd) / S->L;
    t[6 + j] = (Dd[6 + j] - n[1] * nd) / S->L;
  }
  for (i = 0; i < 6; i++)
    for (j = 0; j < 6; j++) S->HL[6 * i + j] = Dd[i] * t[j] + Dd[6 + i] * t[6 + j];
  lgnPlanarPointHessian(&S->A, e->sa, n, -1, 0, S->HL);
  lgnPlanarPointHessian(&S->B, e->sb, n, 1, 3, S->HL);
  return LGN_SUCCESS;
}

static int CheckVec(const lgnPlanarBodies *P, N_Vector x, sunindextype n, const char *name,
                    const char *func)
{
  return lgnCheckSerialVector(P->err, x, n, name, func);
}

int lgnPlanarBodiesForce(lgnPlanarBodies *P, N_Vector q, N_Vector v, N_Vector g,
                         const char *func)
{
  const sunrealtype *qd, *vd;
  sunrealtype *gd;
  SpringLocal S;
  int k, i, ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, v, P->G->nv, "v", func) != LGN_SUCCESS ||
      CheckVec(P, g, P->G->nv, "g", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  gd = lgnVecData(g);
  for (i = 0; i < P->G->nv; i++) gd[i] = 0;
  for (k = 0; k < P->nb; k++) {
    const sunindextype o = P->voff[k];
    const sunrealtype m = P->mass[k];
    const sunrealtype G0 = m * P->gravity[0], G1 = m * P->gravity[1];
    if (P->se2[k]) { /* m omega J U - R^T m gvec */
      const sunrealtype th = qd[P->qoff[k] + 2], c = cos(th), s = sin(th);
      gd[o]     = -m * vd[o + 2] * vd[o + 1] - (c * G0 + s * G1);
      gd[o + 1] = m * vd[o + 2] * vd[o] - (-s * G0 + c * G1);
    } else {
      gd[o]     = -G0;
      gd[o + 1] = -G1;
    }
  }
  for (k = 0; k < P->nelem; k++) {
    const Element *e = P->elem + k;
    if (e->kind == ELEM_SPRING) {
      if ((ret = SpringEval(P, e, qd, vd, &S, SUNFALSE, func)) != LGN_SUCCESS) return ret;
      for (i = 0; i < 3; i++) {
        if (!S.A.ground) gd[S.A.voff + i] += S.f * S.gL[i];
        if (!S.B.ground) gd[S.B.voff + i] += S.f * S.gL[3 + i];
      }
    } else {
      const sunrealtype tha = e->a == LGN_GROUND ? 0 : qd[P->qoff[e->a] + 2];
      const sunrealtype thb = e->b == LGN_GROUND ? 0 : qd[P->qoff[e->b] + 2];
      const sunrealtype wa = e->a == LGN_GROUND ? 0 : vd[P->voff[e->a] + 2];
      const sunrealtype wb = e->b == LGN_GROUND ? 0 : vd[P->voff[e->b] + 2];
      const sunrealtype tau = e->k * (thb - tha - e->L0) + e->c * (wb - wa);
      if (e->a != LGN_GROUND) gd[P->voff[e->a] + 2] -= tau;
      if (e->b != LGN_GROUND) gd[P->voff[e->b] + 2] += tau;
    }
  }
  return LGN_SUCCESS;
}

int lgnPlanarBodiesEnergy(lgnPlanarBodies *P, N_Vector q, N_Vector v, sunrealtype *kin,
                          sunrealtype *pot, const char *func)
{
  const sunrealtype *qd, *vd;
  sunrealtype T = 0, V = 0;
  SpringLocal S;
  int k, ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, v, P->G->nv, "v", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  for (k = 0; k < P->nb; k++) {
    const sunindextype o = P->voff[k], qo = P->qoff[k];
    T += P->mass[k] * (vd[o] * vd[o] + vd[o + 1] * vd[o + 1]) +
         P->inertia[k] * vd[o + 2] * vd[o + 2];
    V -= P->mass[k] * (P->gravity[0] * qd[qo] + P->gravity[1] * qd[qo + 1]);
  }
  for (k = 0; k < P->nelem; k++) {
    const Element *e = P->elem + k;
    if (e->kind == ELEM_SPRING) {
      if ((ret = SpringEval(P, e, qd, vd, &S, SUNFALSE, func)) != LGN_SUCCESS) return ret;
      V += e->k * (S.L - e->L0) * (S.L - e->L0) / 2;
    } else {
      const sunrealtype tha = e->a == LGN_GROUND ? 0 : qd[P->qoff[e->a] + 2];
      const sunrealtype thb = e->b == LGN_GROUND ? 0 : qd[P->qoff[e->b] + 2];
      V += e->k * (thb - tha - e->L0) * (thb - tha - e->L0) / 2;
    }
  }
  if (kin != NULL) *kin = T / 2;
  if (pot != NULL) *pot = V;
  return LGN_SUCCESS;
}

/* The matrices entry by entry (lgnPlanarWrite); q, v NULL in collect mode */
typedef struct {
  lgnPlanarBodies *P;
  const sunrealtype *q, *v;
  sunbooleantype damping;
  const char *func;
} GenCtx;

static int GenMass(void *vctx, lgnPlanarSink *s)
{
  const GenCtx *c = (const GenCtx *)vctx;
  int k;
  for (k = 0; k < c->P->nb; k++) {
    const sunindextype o = c->P->voff[k];
    lgnPlanarEmit(s, o, o, c->P->mass[k]);
    lgnPlanarEmit(s, o + 1, o + 1, c->P->mass[k]);
    lgnPlanarEmit(s, o + 2, o + 2, c->P->inertia[k]);
  }
  return LGN_SUCCESS;
}

/* the 3x3 blocks (a, b) x (a, b) of a local 6x6 matrix X (times f) */
static void EmitLocal(lgnPlanarSink *s, const lgnPlanarBodies *P, int a, int b,
                      const sunrealtype *X)
{
  const int body[2] = {a, b};
  int bi, bj, i, j;
  for (bj = 0; bj < 2; bj++)
    for (bi = 0; bi < 2; bi++) {
      if (body[bi] == LGN_GROUND || body[bj] == LGN_GROUND) continue;
      for (j = 0; j < 3; j++)
        for (i = 0; i < 3; i++)
          lgnPlanarEmit(s, P->voff[body[bi]] + i, P->voff[body[bj]] + j,
                        s->mode == LGN_PA_COLLECT ? 0 : X[6 * (3 * bi + i) + 3 * bj + j]);
    }
}

static int GenTangent(void *vctx, lgnPlanarSink *s)
{
  const GenCtx *c = (const GenCtx *)vctx;
  const lgnPlanarBodies *P = c->P;
  sunrealtype X[36];
  SpringLocal S;
  int k, i, j, ret;
  for (k = 0; k < P->nb; k++) { /* the bodies' own blocks (SE(2)) */
    const sunindextype o = P->voff[k];
    sunrealtype b0 = 0, b1 = 0, b2 = 0, b3 = 0;
    if (P->se2[k] && s->mode != LGN_PA_COLLECT) {
      const sunrealtype m = P->mass[k];
      if (c->damping) { /* d(m om J U)/d(U, om) */
        b0 = -m * c->v[o + 2];
        b1 = m * c->v[o + 2];
        b2 = -m * c->v[o + 1];
        b3 = m * c->v[o];
      } else { /* d/dtheta (-R^T m gvec) = J R^T m gvec */
        const sunrealtype th = c->q[P->qoff[k] + 2], cs = cos(th), sn = sin(th);
        const sunrealtype G0 = m * P->gravity[0], G1 = m * P->gravity[1];
        b2 = -(-sn * G0 + cs * G1);
        b3 = cs * G0 + sn * G1;
      }
    }
    if (!P->se2[k]) continue;
    lgnPlanarEmit(s, o, o + 1, b0);
    lgnPlanarEmit(s, o + 1, o, b1);
    lgnPlanarEmit(s, o, o + 2, b2);
    lgnPlanarEmit(s, o + 1, o + 2, b3);
  }
  for (k = 0; k < P->nelem; k++) {
    const Element *e = P->elem + k;
    for (i = 0; i < 36; i++) X[i] = 0;
    if (s->mode != LGN_PA_COLLECT) {
      if (e->kind == ELEM_SPRING) {
        if ((ret = SpringEval(P, e, c->q, c->v, &S, !c->damping, c->func)) != LGN_SUCCESS)
          return ret;
        if (c->damping) {
          for (i = 0; i < 6; i++)
            for (j = 0; j < 6; j++) X[6 * i + j] = e->c * S.gL[i] * S.gL[j];
        } else {
          sunrealtype df[6];
          for (j = 0; j < 6; j++) {
            df[j] = e->k * S.gL[j];
            for (i = 0; i < 6; i++) df[j] += e->c * S.vl[i] * S.HL[6 * i + j];
          }
          for (i = 0; i < 6; i++)
            for (j = 0; j < 6; j++) X[6 * i + j] = S.gL[i] * df[j] + S.f * S.HL[6 * i + j];
        }
      } else { /* k or c times g g^T, g = (0, 0, -1, 0, 0, 1) */
        const sunrealtype f = c->damping ? e->c : e->k;
        X[6 * 2 + 2] = X[6 * 5 + 5] = f;
        X[6 * 2 + 5] = X[6 * 5 + 2] = -f;
      }
    }
    EmitLocal(s, P, e->a, e->b, X);
  }
  return LGN_SUCCESS;
}

sunindextype lgnPlanarBodiesMassNnz(lgnPlanarBodies *P) { return 3 * (sunindextype)P->nb; }

sunindextype lgnPlanarBodiesTangentNnz(lgnPlanarBodies *P)
{
  GenCtx c = {P, NULL, NULL, SUNFALSE, NULL};
  lgnPlanarPattern pat;
  sunindextype n;
  memset(&pat, 0, sizeof pat);
  pat.fmt = -1;
  n = lgnPlanarCount(&pat, P->G->nv, GenTangent, &c);
  lgnPlanarPatternFree(&pat);
  return n;
}

int lgnPlanarBodiesMass(lgnPlanarBodies *P, N_Vector q, SUNMatrix M, const char *func)
{
  GenCtx c = {P, NULL, NULL, SUNFALSE, NULL};
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      lgnPlanarCheckMat(M, P->G->nv, P->G->nv, "M", P->err, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  c.func = func;
  return lgnPlanarWrite(&P->patM, M, SUNFALSE, GenMass, &c, P->err, func);
}

int lgnPlanarBodiesTangent(lgnPlanarBodies *P, N_Vector q, N_Vector v, SUNMatrix A,
                           sunbooleantype damping, const char *func)
{
  GenCtx c = {P, NULL, NULL, SUNFALSE, NULL};
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, v, P->G->nv, "v", func) != LGN_SUCCESS ||
      lgnPlanarCheckMat(A, P->G->nv, P->G->nv, damping ? "C" : "K", P->err, func) !=
          LGN_SUCCESS)
    return LGN_ILL_INPUT;
  c.q       = lgnVecData(q);
  c.v       = lgnVecData(v);
  c.damping = damping;
  c.func    = func;
  return lgnPlanarWrite(&P->patK, A, SUNFALSE, GenTangent, &c, P->err, func);
}
