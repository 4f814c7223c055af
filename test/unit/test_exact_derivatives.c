/* -----------------------------------------------------------------------------
 * Lignum unit test: the closed-form derivatives of the exact kinematics
 * (lgn_group_impl.h: lgnGroup*ExactDerivatives) and the fused map
 * (lgnGroup*ExactMap).
 *
 * The map of the exact kinematics at a correction delta of sigma,
 *   v(delta)    = T(s) (sd + gamma' delta)
 *   vdot(delta) = T(s) (sdd + beta' delta) + Tdot(s, sd + gamma' delta)(sd + gamma' delta),
 * s = sigma + delta, is differentiated by central differences of the
 * group's public ops (Richardson-extrapolated, step 1e-3 and 5e-4 times
 * max(1, |sigma|)), and Tv = (dv/ddelta)/gamma', Ta = (dvdot/ddelta)/beta'
 * must agree with the closed forms to 1e-8 relative to max(1, |matrix|),
 * with the method's gamma', beta' and with gamma' = beta' = 1 (where the
 * derivative terms, not T, make the matrices).
 * Groups: SO(3), R^3 x SO(3), SE(3), and a product R^2 x SO(3) x
 * R^3 x SO(3) x SE(3) (its difference quotient must be block diagonal and
 * each leaf's block the leaf's closed form). Angles: 0, 1e-9, 0.03 (the
 * series), 0.7, 2.5 (closed forms), with sigma_dot, sigma_ddot of
 * integration size and large. The fused map must equal compose_exp,
 * tangent_apply, tangent_dot_apply and tangent_matrix bit for bit.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum_group.h>

#include "groups/lgn_group_impl.h"
#include "groups/lgn_so3.h"

#define NMAX 32
#define TOL  1.0e-8

static int failures = 0;

typedef int (*DerivFn)(LGNGroup, const sunrealtype *, const sunrealtype *,
                       const sunrealtype *, sunrealtype, sunrealtype,
                       const sunrealtype *, sunrealtype *, sunrealtype *);
typedef int (*MapFn)(LGNGroup, const sunrealtype *, const sunrealtype *,
                     const sunrealtype *, const sunrealtype *, sunrealtype *,
                     sunrealtype *, sunrealtype *, sunrealtype *);

/* v, vdot of the exact kinematics at sigma + delta (public ops) */
static void KinMap(LGNGroup G, const double *sigma, const double *sd,
                   const double *sdd, double gp, double bp, const double *delta,
                   double *v, double *vdot)
{
  const sunindextype n = G->nv;
  double s[NMAX] = {0}, d1[NMAX] = {0}, d2[NMAX] = {0}, t[NMAX] = {0};
  sunindextype i;
  for (i = 0; i < n; i++) {
    s[i]  = sigma[i] + delta[i];
    d1[i] = sd[i] + gp * delta[i];
    d2[i] = sdd[i] + bp * delta[i];
  }
  G->ops.tangent_apply(G, s, d1, v);
  G->ops.tangent_apply(G, s, d2, vdot);
  G->ops.tangent_dot_apply(G, s, d1, d1, t);
  for (i = 0; i < n; i++) vdot[i] += t[i];
}

/* Tv, Ta (n x n, column-major) by Richardson-extrapolated central
 * differences of KinMap */
static void DiffQuot(LGNGroup G, const double *sigma, const double *sd,
                     const double *sdd, double gp, double bp, double *Tv,
                     double *Ta)
{
  const sunindextype n = G->nv;
  double nrm = 0, delta[NMAX] = {0}, vp[NMAX] = {0}, vm[NMAX] = {0};
  double ap[NMAX] = {0}, am[NMAX] = {0}, dv1[NMAX] = {0}, da1[NMAX] = {0}, e, ee;
  sunindextype i, j;
  int r;
  for (i = 0; i < n; i++) nrm = fmax(nrm, fabs(sigma[i]));
  for (j = 0; j < n; j++) {
    for (r = 0; r < 2; r++) {
      e = (r == 0 ? 1.0e-3 : 5.0e-4) * fmax(1.0, nrm);
      memset(delta, 0, sizeof delta);
      delta[j] = e;
      KinMap(G, sigma, sd, sdd, gp, bp, delta, vp, ap);
      delta[j] = -e;
      KinMap(G, sigma, sd, sdd, gp, bp, delta, vm, am);
      for (i = 0; i < n; i++) {
        const double dv = (vp[i] - vm[i]) / (2 * e), da = (ap[i] - am[i]) / (2 * e);
        if (r == 0) {
          dv1[i] = dv;
          da1[i] = da;
        } else { /* (4 D(e/2) - D(e)) / 3: error O(e^4) */
          ee = (4 * dv - dv1[i]) / 3;
          Tv[i + j * n] = ee / gp;
          ee = (4 * da - da1[i]) / 3;
          Ta[i + j * n] = ee / bp;
        }
      }
    }
  }
}

/* relative difference of two n x n blocks (leading dimensions la, lb) */
static double BlockDiff(const double *a, sunindextype la, const double *b,
                        sunindextype lb, sunindextype n)
{
  double d = 0, m = 1;
  sunindextype i, j;
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++) {
      d = fmax(d, fabs(a[i + j * la] - b[i + j * lb]));
      m = fmax(m, fabs(b[i + j * lb]));
    }
  return d / m;
}

static void Check(const char *what, double err, double tol)
{
  if (!(err <= tol)) {
    printf("FAIL %s: %.3e > %.1e\n", what, err, tol);
    failures++;
  }
}

/* A state of size n: each rotation part (SO(3): the last 3 of a leaf; in
 * R^n anything) scaled to angle phi, sigma_dot of size vs, sigma_ddot of
 * size as */
static void State(sunindextype n, double phi, double vs, double as, int seed,
                  double *sigma, double *sd, double *sdd)
{
  sunindextype i;
  for (i = 0; i < n; i++) {
    const double k = (double)(i + 1 + seed);
    sigma[i] = sin(1.3 * k + 0.2) * phi / sqrt(3.0);
    sd[i]    = vs * cos(0.7 * k - 0.4);
    sdd[i]   = as * sin(2.1 * k + 1.0);
  }
}

/* stands in for a user's replacement of an op */
static int OtherDot(LGNGroup G, const sunrealtype *w, const sunrealtype *wd,
                    const sunrealtype *x, sunrealtype *y)
{
  return G->ops.tangent_dot_apply == OtherDot ? lgnSO3_TDotApply(w, wd, x, y), 0 : -1;
}

/* One leaf: closed form against difference quotients, and the fused map
 * against the ops. */
static void CheckLeaf(const char *name, LGNGroup G, DerivFn deriv, MapFn map,
                      double phi, double vs, double as, double gp, double bp)
{
  const sunindextype n = G->nv;
  double sigma[NMAX] = {0}, sd[NMAX] = {0}, sdd[NMAX] = {0};
  double Tm[NMAX * NMAX] = {0}, Tv[NMAX * NMAX] = {0};
  double Ta[NMAX * NMAX] = {0}, Fv[NMAX * NMAX] = {0}, Fa[NMAX * NMAX] = {0};
  double q[NMAX] = {0}, q1[NMAX] = {0}, q1o[NMAX] = {0}, v[NMAX] = {0};
  double vo[NMAX] = {0}, vd[NMAX] = {0}, vdo[NMAX] = {0};
  double T2[NMAX * NMAX] = {0}, t[NMAX] = {0}, zero[NMAX] = {0};
  char what[160];
  sunindextype i;
  State(n, phi, vs, as, 0, sigma, sd, sdd);
  G->ops.tangent_matrix(G, sigma, Tm, n);
  if (deriv(G, sigma, sd, sdd, gp, bp, Tm, Tv, Ta) != 0) {
    printf("FAIL %s: closed form refused\n", name);
    failures++;
    return;
  }
  DiffQuot(G, sigma, sd, sdd, gp, bp, Fv, Fa);
  snprintf(what, sizeof what, "%s Tv, phi = %g, |sd| ~ %g", name, phi, vs);
  Check(what, BlockDiff(Tv, n, Fv, n, n), TOL);
  snprintf(what, sizeof what, "%s Ta, phi = %g, |sd| ~ %g, |sdd| ~ %g", name, phi, vs, as);
  Check(what, BlockDiff(Ta, n, Fa, n, n), TOL);

  /* the fused map: bit for bit the ops */
  State(G->nq, 1.0, 1.0, 1.0, 3, q, t, t);
  G->ops.compose_exp(G, q, zero, q); /* a valid element: normalised */
  if (G->ops.normalize != NULL) G->ops.normalize(G, q);
  map(G, q, sigma, sd, sdd, q1, v, vd, T2);
  G->ops.compose_exp(G, q, sigma, q1o);
  G->ops.tangent_apply(G, sigma, sd, vo);
  G->ops.tangent_apply(G, sigma, sdd, vdo);
  G->ops.tangent_dot_apply(G, sigma, sd, sd, t);
  for (i = 0; i < n; i++) vdo[i] += t[i];
  snprintf(what, sizeof what, "%s fused map, phi = %g", name, phi);
  Check(what,
        (memcmp(q1, q1o, (size_t)G->nq * sizeof(double)) == 0 &&
         memcmp(v, vo, (size_t)n * sizeof(double)) == 0 &&
         memcmp(vd, vdo, (size_t)n * sizeof(double)) == 0 &&
         memcmp(T2, Tm, (size_t)(n * n) * sizeof(double)) == 0) ? 0.0 : 1.0,
        0.0);
}

/* A product: the difference quotient of the whole map is block diagonal
 * with each leaf's closed form (I for R^n) on the diagonal. */
static void CheckProduct(LGNGroup P, double phi, double vs, double as,
                         double gp, double bp)
{
  const sunindextype n = P->nv;
  double sigma[NMAX] = {0}, sd[NMAX] = {0}, sdd[NMAX] = {0};
  double Fv[NMAX * NMAX] = {0}, Fa[NMAX * NMAX] = {0}, Tm[NMAX * NMAX] = {0};
  double Tv[NMAX * NMAX] = {0}, Ta[NMAX * NMAX] = {0}, off = 0, scale = 1;
  const LGNGroup *f;
  const sunindextype *qo, *vo;
  char what[160];
  sunindextype i, j, o, m;
  int nf, k, ret;
  State(n, phi, vs, as, 1, sigma, sd, sdd);
  DiffQuot(P, sigma, sd, sdd, gp, bp, Fv, Fa);
  lgnGroupProductFactors(P, &nf, &f, &qo, &vo);
  for (k = 0; k < nf; k++) {
    o = vo[k];
    m = f[k]->nv;
    f[k]->ops.tangent_matrix(f[k], sigma + o, Tm, m);
    switch (f[k]->kind) {
    case LGN_GROUP_SO3:
      ret = lgnGroupSO3ExactDerivatives(f[k], sigma + o, sd + o, sdd + o, gp, bp, Tm, Tv, Ta);
      break;
    case LGN_GROUP_R3XSO3:
      ret = lgnGroupR3xSO3ExactDerivatives(f[k], sigma + o, sd + o, sdd + o, gp, bp, Tm, Tv, Ta);
      break;
    case LGN_GROUP_SE3:
      ret = lgnGroupSE3ExactDerivatives(f[k], sigma + o, sd + o, sdd + o, gp, bp, Tm, Tv, Ta);
      break;
    default: /* R^n: Tv = Ta = I */
      ret = 0;
      for (j = 0; j < m; j++)
        for (i = 0; i < m; i++) Tv[i + j * m] = Ta[i + j * m] = (i == j);
    }
    if (ret != 0) {
      printf("FAIL product: closed form of factor %d refused\n", k);
      failures++;
      continue;
    }
    snprintf(what, sizeof what, "product factor %d Tv, phi = %g", k, phi);
    Check(what, BlockDiff(Tv, m, Fv + o + o * n, n, m), TOL);
    snprintf(what, sizeof what, "product factor %d Ta, phi = %g", k, phi);
    Check(what, BlockDiff(Ta, m, Fa + o + o * n, n, m), TOL);
  }
  /* block diagonal */
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++) {
      int bi = 0, bj = 0;
      for (k = 0; k < nf; k++) {
        if (i >= vo[k]) bi = k;
        if (j >= vo[k]) bj = k;
      }
      scale = fmax(scale, fmax(fabs(Fv[i + j * n]), fabs(Fa[i + j * n])));
      if (bi != bj) off = fmax(off, fmax(fabs(Fv[i + j * n]), fabs(Fa[i + j * n])));
    }
  snprintf(what, sizeof what, "product off-diagonal blocks, phi = %g", phi);
  Check(what, off / scale, TOL);
}

/* D^3T against a central difference of D^2T, and the matrix forms of DT,
 * D^2T against the apply kernels */
static void CheckKernels(double phi)
{
  double x[3], U[3], W[3], V[3], v[3], y[3], yp[3], ym[3], xp[3], xm[3], M[9], y2[3];
  double e[3], d = 0, m = 1, dm = 0;
  lgnSO3_Coef c, cp, cm;
  const double h = 1.0e-4 * fmax(1.0, phi);
  char what[120];
  int i, j;
  State(3, phi, 1.0, 1.0, 5, x, U, W);
  State(3, 1.0, 1.3, 0.8, 7, V, v, e);
  lgnSO3_Coefs(lgnSO3_Norm(x), LGN_SO3_ALL, &c);
  lgnSO3_D3TApplyC(&c, x, U, W, V, v, y);
  for (i = 0; i < 3; i++) {
    xp[i] = x[i] + h * V[i];
    xm[i] = x[i] - h * V[i];
  }
  lgnSO3_Coefs(lgnSO3_Norm(xp), LGN_SO3_ALL, &cp);
  lgnSO3_Coefs(lgnSO3_Norm(xm), LGN_SO3_ALL, &cm);
  lgnSO3_D2TApplyC(&cp, xp, U, W, v, yp);
  lgnSO3_D2TApplyC(&cm, xm, U, W, v, ym);
  for (i = 0; i < 3; i++) {
    d = fmax(d, fabs(y[i] - (yp[i] - ym[i]) / (2 * h)));
    m = fmax(m, fabs(y[i]));
  }
  snprintf(what, sizeof what, "D^3T vs difference of D^2T, phi = %g", phi);
  Check(what, d / m, 1.0e-6);
  /* matrix forms against the apply kernels, column by column */
  for (j = 0; j < 3; j++) {
    memset(e, 0, sizeof e);
    e[j] = 1;
    lgnSO3_DTMatrixC(&c, x, v, M, 3, SUNFALSE);
    lgnSO3_TDotApplyC(&c, x, e, v, y2);
    for (i = 0; i < 3; i++) dm = fmax(dm, fabs(M[i + 3 * j] - y2[i]) / fmax(1.0, fabs(y2[i])));
    lgnSO3_D2TMatrixC(&c, x, W, v, M, 3, SUNFALSE);
    lgnSO3_D2TApplyC(&c, x, e, W, v, y2);
    for (i = 0; i < 3; i++) dm = fmax(dm, fabs(M[i + 3 * j] - y2[i]) / fmax(1.0, fabs(y2[i])));
  }
  snprintf(what, sizeof what, "DT, D^2T matrices vs apply kernels, phi = %g", phi);
  Check(what, dm, 1.0e-13);
}

int main(void)
{
  static const double angles[] = {0.0, 1.0e-9, 0.03, 0.7, 2.5};
  LGNGroup so3 = LGNGroup_SO3(), r3 = LGNGroup_R3xSO3(), se3 = LGNGroup_SE3();
  LGNGroup r2 = LGNGroup_Rn(2), P;
  LGNGroup fac[4];
  size_t a;
  fac[0] = r2;
  fac[1] = so3;
  fac[2] = r3;
  fac[3] = se3;
  P = LGNGroup_Product(4, fac);
  for (a = 0; a < sizeof angles / sizeof angles[0]; a++) {
    const double phi = angles[a];
    /* integration size (h = 1e-3, Newmark: gamma' = 2/h, beta' = 4/h^2,
     * |sd| ~ 10, |sdd| ~ 100), and gamma' = beta' = 1 with large sd, sdd,
     * where the derivative terms dominate T and are tested on their own */
    const double gh = 2.0 / 0.001, bh = 1.0 / (0.25 * 0.001 * 0.001);
    CheckLeaf("SO(3)", so3, lgnGroupSO3ExactDerivatives, lgnGroupSO3ExactMap, phi, 10, 100, gh, bh);
    CheckLeaf("SO(3)", so3, lgnGroupSO3ExactDerivatives, lgnGroupSO3ExactMap, phi, 30, 1e3, 1, 1);
    CheckLeaf("R3xSO(3)", r3, lgnGroupR3xSO3ExactDerivatives, lgnGroupR3xSO3ExactMap, phi, 10, 100, gh, bh);
    CheckLeaf("R3xSO(3)", r3, lgnGroupR3xSO3ExactDerivatives, lgnGroupR3xSO3ExactMap, phi, 30, 1e3, 1, 1);
    CheckLeaf("SE(3)", se3, lgnGroupSE3ExactDerivatives, lgnGroupSE3ExactMap, phi, 10, 100, gh, bh);
    CheckLeaf("SE(3)", se3, lgnGroupSE3ExactDerivatives, lgnGroupSE3ExactMap, phi, 30, 1e3, 1, 1);
    CheckProduct(P, phi, 10, 100, gh, bh);
    CheckProduct(P, phi, 30, 1e3, 1, 1);
    CheckKernels(phi);
  }
  /* a user's replacement of an op turns the closed forms off */
  {
    LGNGroup G = LGNGroup_SO3();
    double w[3] = {0.1, 0.2, 0.3}, T[9], Tv[9], Ta[9];
    G->ops.tangent_dot_apply = OtherDot;
    if (lgnGroupSO3ExactDerivatives(G, w, w, w, 1, 1, T, Tv, Ta) != 1 ||
        lgnGroupSO3ExactMap(G, w, w, w, w, T, Tv, Ta, NULL) != 1) {
      printf("FAIL closed forms used for replaced ops\n");
      failures++;
    }
    LGNGroup_Destroy(G);
  }
  LGNGroup_Destroy(P);
  LGNGroup_Destroy(r2);
  LGNGroup_Destroy(se3);
  LGNGroup_Destroy(r3);
  LGNGroup_Destroy(so3);
  if (failures == 0) printf("test_exact_derivatives: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
