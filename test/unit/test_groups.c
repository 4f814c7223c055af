/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the built-in Lie groups (R^n, SO(3), R^3xSO(3), SE(3),
 * products) and of the private SO(3) math (doc/theory.md §1.1).
 *
 * Every check records its worst error against a tolerance; a summary table
 * (check, count, max error, tolerance) is printed at the end and the exit
 * status is nonzero if any check failed. References are computed
 * independently in long double (series and closed forms of the
 * coefficients, quaternion log, 4x4 matrix exponential by scaled Taylor
 * series) or by central finite differences with Richardson extrapolation.
 * ---------------------------------------------------------------------------*/

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum_group.h>

#include "groups/lgn_so3.h"

#define GROUP_TEST_SEED 0x9E3779B97F4A7C15ULL
#include "group_test_util.h"

#define MAXF 8    /* max factors of a test group */
#define MAXV 64   /* max nv of a test group      */
#define MAXQ 80   /* max nq of a test group      */

static double MaxDiffL(const LD *x, const RT *y, int n)
{
  double m = 0;
  int i;
  for (i = 0; i < n; i++) {
    double d = (double)fabsl(x[i] - (LD)y[i]);
    if (d > m || d != d) m = d;
  }
  return m;
}

/* =============================================================================
 * Long double references: coefficients
 * ===========================================================================*/

/* A numerator as a sum of coef * phi^m * {1, sin phi, cos phi}; the
 * coefficient is numerator / phi^n. */
typedef struct { int type; LD coef; int m; } Term; /* type 0:1, 1:sin, 2:cos */

typedef struct {
  const char *name;
  unsigned bit;
  double thr;
  double stol;       /* series branch: truncation at thr (§4.1) + rounding */
  const char *cname; /* check name of the closed branch               */
  double ctol;       /* its tolerance: rounding in the cancellation   */
  int n;
  int nterms;
  Term t[4];
} CoefDef;

/* The closed forms lose digits to cancellation just above the threshold
 * (relative error ~ eps * (largest term) / (value)); measured worst cases on
 * [thr, 3): sinc, cc, a ~4e-16; b, d, c1 ~1e-13; c2, c3 ~5e-12; c4 ~1.5e-10. */
#define CN_A "closed branch vs LD ref: sinc, cc, a (rel)"
#define CN_B "closed branch vs LD ref: b, d, c1 (rel)"
#define CN_C "closed branch vs LD ref: c2, c3 (rel)"
#define CN_D "closed branch vs LD ref: c4 (rel)"

static const CoefDef coefdefs[] = {
  {"sinc", LGN_SO3_SINC, 0.05, 1e-15, CN_A, 2e-15, 1, 1, {{1, 1, 0}}},
  {"cc",   LGN_SO3_CC,   0.05, 1e-15, CN_A, 2e-15, 2, 2, {{0, 1, 0}, {2, -1, 0}}},
  {"a",    LGN_SO3_A,    0.1, 1.5e-14, CN_A, 2e-15, 2, 2, {{2, 1, 0}, {0, -1, 0}}},
  {"b",    LGN_SO3_B,    0.1, 5e-15, CN_B, 3e-13, 3, 2, {{0, 1, 1}, {1, -1, 0}}},
  {"d",    LGN_SO3_D,    0.1, 6e-15, CN_B, 3e-13, 2, 0, {{0, 0, 0}}},  /* special: cot */
  {"c1",   LGN_SO3_C1,   0.2, 1e-12, CN_B, 3e-13, 4, 3, {{0, 2, 0}, {2, -2, 0}, {1, -1, 1}}},
  {"c2",   LGN_SO3_C2,   0.3, 1e-14, CN_C, 2e-11, 5, 3, {{1, 3, 0}, {0, -2, 1}, {2, -1, 1}}},
  {"c3",   LGN_SO3_C3,   0.4, 2e-13, CN_C, 2e-11, 6, 4, {{2, 8, 0}, {0, -8, 0}, {1, 5, 1},
                                        {2, -1, 2}}},
  {"c4",   LGN_SO3_C4,   0.5, 6e-13, CN_D, 5e-10, 7, 4, {{1, 1, 2}, {2, 7, 1}, {0, 8, 1},
                                        {1, -15, 0}}},
};
#define NCOEF ((int)(sizeof coefdefs / sizeof coefdefs[0]))

static RT CoefPick(const lgnSO3_Coef *c, unsigned bit)
{
  switch (bit) {
  case LGN_SO3_SINC: return c->sinc;
  case LGN_SO3_CC:   return c->cc;
  case LGN_SO3_A:    return c->a;
  case LGN_SO3_B:    return c->b;
  case LGN_SO3_D:    return c->d;
  case LGN_SO3_C1:   return c->c1;
  case LGN_SO3_C2:   return c->c2;
  case LGN_SO3_C3:   return c->c3;
  default:           return c->c4;
  }
}

static RT LibCoef(unsigned bit, RT phi)
{
  lgnSO3_Coef c;
  memset(&c, 0, sizeof c);
  lgnSO3_Coefs(phi, bit, &c);
  return CoefPick(&c, bit);
}

/* closed form in long double */
static LD CoefClosedL(const CoefDef *cd, LD phi)
{
  LD num = 0;
  int k;
  if (cd->bit == LGN_SO3_D)
    return (1.0L - 0.5L * phi / tanl(0.5L * phi)) / (phi * phi);
  for (k = 0; k < cd->nterms; k++) {
    const Term *t = &cd->t[k];
    LD f = (t->type == 0) ? 1.0L : (t->type == 1) ? sinl(phi) : cosl(phi);
    num += t->coef * powl(phi, (LD)t->m) * f;
  }
  return num / powl(phi, (LD)cd->n);
}

/* Taylor series in long double (40 terms; the known-zero low-order
 * coefficients of the numerator are dropped exactly). */
static LD CoefSeriesL(const CoefDef *cd, LD phi)
{
  LD N[64], fact[64], s = 0;
  int k, j;
  fact[0] = 1;
  for (k = 1; k < 64; k++) fact[k] = fact[k - 1] * k;
  if (cd->bit == LGN_SO3_D) {
    /* d = sum_{k>=1} |B_2k| phi^(2k-2) / (2k)! */
    static const LD B[] = {1.0L / 6, 1.0L / 30, 1.0L / 42, 1.0L / 30,
                           5.0L / 66, 691.0L / 2730, 7.0L / 6,
                           3617.0L / 510, 43867.0L / 798};
    for (k = 8; k >= 0; k--) s = s * phi * phi + B[k] / fact[2 * k + 2];
    return s;
  }
  for (k = 0; k < 64; k++) N[k] = 0;
  for (j = 0; j < cd->nterms; j++) {
    const Term *t = &cd->t[j];
    for (k = 0; k + t->m < 64; k++) {
      LD a = 0;
      if (t->type == 0) a = (k == 0) ? 1 : 0;
      else if (t->type == 1) a = (k % 2 == 1) ? ((k / 2) % 2 ? -1 : 1) / fact[k] : 0;
      else a = (k % 2 == 0) ? ((k / 2) % 2 ? -1 : 1) / fact[k] : 0;
      N[k + t->m] += t->coef * a;
    }
  }
  for (k = 63; k >= cd->n; k--) s = s * phi + N[k];
  return s;
}

static LD CoefRefL(const CoefDef *cd, LD phi)
{
  return (phi <= 1.0L) ? CoefSeriesL(cd, phi) : CoefClosedL(cd, phi);
}

/* =============================================================================
 * Long double references: rotations
 * ===========================================================================*/

/* rotation vector of a (not necessarily unit) quaternion */
static void QLogL(const LD p[4], LD phi[3])
{
  LD s = (p[0] < 0) ? -1.0L : 1.0L;
  LD n = sqrtl(p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
  LD k = (n == 0) ? 0 : 2.0L * atan2l(n, s * p[0]) / n;
  int i;
  for (i = 0; i < 3; i++) phi[i] = s * k * p[i + 1];
}

static void QRotL(const LD p0[4], LD R[9])
{
  LD n = sqrtl(p0[0] * p0[0] + p0[1] * p0[1] + p0[2] * p0[2] + p0[3] * p0[3]);
  LD w = p0[0] / n, x = p0[1] / n, y = p0[2] / n, z = p0[3] / n;
  R[0] = 1 - 2 * (y * y + z * z); R[1] = 2 * (x * y - w * z);
  R[2] = 2 * (x * z + w * y);     R[3] = 2 * (x * y + w * z);
  R[4] = 1 - 2 * (x * x + z * z); R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y);     R[7] = 2 * (y * z + w * x);
  R[8] = 1 - 2 * (x * x + y * y);
}

/* E = expm(A) for a 4x4 row-major A: scaling, Taylor (30 terms), squaring */
static void Expm4L(const LD A0[16], LD E[16])
{
  LD A[16], T[16], S[16], P[16], nrm = 0;
  int i, j, k, s = 0, it;
  for (i = 0; i < 4; i++) {
    LD r = 0;
    for (j = 0; j < 4; j++) r += fabsl(A0[4 * i + j]);
    if (r > nrm) nrm = r;
  }
  while (nrm > 0.125L) { nrm *= 0.5L; s++; }
  for (i = 0; i < 16; i++) A[i] = ldexpl(A0[i], -s);
  for (i = 0; i < 16; i++) { S[i] = (i % 5 == 0) ? 1 : 0; T[i] = S[i]; }
  for (it = 1; it <= 30; it++) {
    for (i = 0; i < 4; i++)
      for (j = 0; j < 4; j++) {
        LD v = 0;
        for (k = 0; k < 4; k++) v += T[4 * i + k] * A[4 * k + j];
        P[4 * i + j] = v / it;
      }
    memcpy(T, P, sizeof T);
    for (i = 0; i < 16; i++) S[i] += T[i];
  }
  for (it = 0; it < s; it++) {
    for (i = 0; i < 4; i++)
      for (j = 0; j < 4; j++) {
        LD v = 0;
        for (k = 0; k < 4; k++) v += S[4 * i + k] * S[4 * k + j];
        P[4 * i + j] = v;
      }
    memcpy(S, P, sizeof S);
  }
  memcpy(E, S, sizeof S);
}

/* 4x4 twist [[Om~, U], [0, 0]] */
static void TwistL(const RT U[3], const RT Om[3], LD A[16])
{
  memset(A, 0, 16 * sizeof(LD));
  A[1] = -Om[2]; A[2] = Om[1];
  A[4] = Om[2];  A[6] = -Om[0];
  A[8] = -Om[1]; A[9] = Om[0];
  A[3] = U[0]; A[7] = U[1]; A[11] = U[2];
}

/* =============================================================================
 * Test groups: a flattened list of factor kinds, for the test-side log
 * ===========================================================================*/

typedef struct {
  const char *name;
  LGNGroup G;
  int nf;
  LGNGroupKind kind[MAXF];
  int n[MAXF]; /* nv of R^n factors */
} TG;

static int FacNq(const TG *t, int k)
{
  switch (t->kind[k]) {
  case LGN_GROUP_RN:  return t->n[k];
  case LGN_GROUP_SO3: return 4;
  default:            return 7;
  }
}

static int FacNv(const TG *t, int k)
{
  switch (t->kind[k]) {
  case LGN_GROUP_RN:  return t->n[k];
  case LGN_GROUP_SO3: return 3;
  default:            return 6;
  }
}

/* random w whose rotational parts have norm phi */
static void MakeW(const TG *t, double phi, RT *w)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    RT d[3];
    switch (t->kind[k]) {
    case LGN_GROUP_RN:
      for (i = 0; i < t->n[k]; i++) w[o + i] = Rand();
      break;
    case LGN_GROUP_SO3:
      RandDir(d);
      for (i = 0; i < 3; i++) w[o + i] = phi * d[i];
      break;
    default:
      RandDir(d);
      for (i = 0; i < 3; i++) { w[o + i] = Rand(); w[o + 3 + i] = phi * d[i]; }
      break;
    }
    o += FacNv(t, k);
  }
}

/* random group element */
static void MakeQ(const TG *t, RT *q)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    RT *p = q + o;
    double n = 0;
    if (t->kind[k] == LGN_GROUP_RN) {
      for (i = 0; i < t->n[k]; i++) q[o + i] = Rand();
    } else {
      if (t->kind[k] != LGN_GROUP_SO3) {
        for (i = 0; i < 3; i++) q[o + i] = 2 * Rand();
        p = q + o + 3;
      }
      for (i = 0; i < 4; i++) { p[i] = Rand(); n += p[i] * p[i]; }
      for (i = 0; i < 4; i++) p[i] /= sqrt(n);
    }
    o += FacNq(t, k);
  }
}

/* out = log(qa^{-1} qb), left-trivialised difference, in long double */
static void LogDiff(const TG *t, const RT *qa, const RT *qb, LD *out)
{
  int k, i, oq = 0, ov = 0;
  for (k = 0; k < t->nf; k++) {
    const RT *a = qa + oq, *b = qb + oq;
    LD pa[4], pb[4], pr[4], om[3];
    if (t->kind[k] == LGN_GROUP_RN) {
      for (i = 0; i < t->n[k]; i++) out[ov + i] = (LD)b[i] - (LD)a[i];
    } else {
      int r = (t->kind[k] == LGN_GROUP_SO3) ? 0 : 3;
      pa[0] = a[r]; pb[0] = b[r];
      for (i = 1; i < 4; i++) { pa[i] = -(LD)a[r + i]; pb[i] = b[r + i]; }
      QMulL(pa, pb, pr);
      QLogL(pr, om);
      for (i = 0; i < 3; i++) out[ov + r + i] = om[i];
      if (t->kind[k] == LGN_GROUP_R3XSO3) {
        for (i = 0; i < 3; i++) out[ov + i] = (LD)b[i] - (LD)a[i];
      } else if (t->kind[k] == LGN_GROUP_SE3) {
        /* relative (Ra^T (xb - xa), Ra^T Rb); U = T(Om)^{-T} x (§1, §4.3) */
        LD Ra[9], dx[3], xr[3], phi, d, ox[3], oox[3];
        QRotL(pa, Ra); /* pa holds conj(pa): Ra = R(pa)^T */
        for (i = 0; i < 3; i++) dx[i] = (LD)b[i] - (LD)a[i];
        for (i = 0; i < 3; i++)
          xr[i] = Ra[3 * i] * dx[0] + Ra[3 * i + 1] * dx[1] + Ra[3 * i + 2] * dx[2];
        phi = sqrtl(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]);
        d = (phi < 0.5L) ? CoefSeriesL(&coefdefs[4], phi)
                         : CoefClosedL(&coefdefs[4], phi);
        CrossL(om, xr, ox);
        CrossL(om, ox, oox);
        for (i = 0; i < 3; i++) out[ov + i] = xr[i] - 0.5L * ox[i] + d * oox[i];
      }
    }
    oq += FacNq(t, k);
    ov += FacNv(t, k);
  }
}

/* y = ad(xi) x per factor (doc/theory.md §1.1): so3: Om x; R3xSO3: diag(0, Om~);
 * SE3: [[Om~, U~], [0, Om~]] */
static void AdApply(const TG *t, const RT *xi, const RT *x, RT *y)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    LD a[3], b[3], r[3], r2[3];
    switch (t->kind[k]) {
    case LGN_GROUP_RN:
      for (i = 0; i < t->n[k]; i++) y[o + i] = 0;
      break;
    case LGN_GROUP_SO3:
      for (i = 0; i < 3; i++) { a[i] = xi[o + i]; b[i] = x[o + i]; }
      CrossL(a, b, r);
      for (i = 0; i < 3; i++) y[o + i] = (RT)r[i];
      break;
    case LGN_GROUP_R3XSO3:
      for (i = 0; i < 3; i++) { a[i] = xi[o + 3 + i]; b[i] = x[o + 3 + i]; }
      CrossL(a, b, r);
      for (i = 0; i < 3; i++) { y[o + i] = 0; y[o + 3 + i] = (RT)r[i]; }
      break;
    default:
      for (i = 0; i < 3; i++) { a[i] = xi[o + 3 + i]; b[i] = x[o + i]; }
      CrossL(a, b, r);                   /* Om x x_U */
      for (i = 0; i < 3; i++) { a[i] = xi[o + i]; b[i] = x[o + 3 + i]; }
      CrossL(a, b, r2);                  /* U x x_Om */
      for (i = 0; i < 3; i++) y[o + i] = (RT)(r[i] + r2[i]);
      for (i = 0; i < 3; i++) a[i] = xi[o + 3 + i];
      CrossL(a, b, r);                   /* Om x x_Om */
      for (i = 0; i < 3; i++) y[o + 3 + i] = (RT)r[i];
      break;
    }
    o += FacNv(t, k);
  }
}

/* =============================================================================
 * Group checks
 * ===========================================================================*/

/* q(s) = q0 o exp(w0 + s w1 + s^2 w2): Richardson-extrapolated central
 * difference of log(q(0)^{-1} q(s)) vs T(w0) w1 (the defining property of T) */
static void CheckDefining(const TG *t, const RT *q0, const RT *w0, const RT *w1,
                          const RT *w2, const char *ctx)
{
  LGNGroup G = t->G;
  const sunindextype nv = G->nv;
  RT q[MAXQ], qs[MAXQ], ws[MAXV], Tw1[MAXV], fd[MAXV];
  LD g[4][MAXV];
  const double e = 1e-3;
  const double ss[4] = {e, -e, e / 2, -e / 2};
  sunindextype i;
  int k;
  LGNGroup_ComposeExp(G, q0, w0, q);
  for (k = 0; k < 4; k++) {
    for (i = 0; i < nv; i++) ws[i] = w0[i] + ss[k] * w1[i] + ss[k] * ss[k] * w2[i];
    LGNGroup_ComposeExp(G, q0, ws, qs);
    LogDiff(t, q, qs, g[k]);
  }
  for (i = 0; i < nv; i++) {
    LD D1 = (g[0][i] - g[1][i]) / (2 * (LD)e);
    LD D2 = (g[2][i] - g[3][i]) / (LD)e;
    fd[i] = (RT)((4 * D2 - D1) / 3);
  }
  LGNGroup_TangentApply(G, w0, w1, Tw1);
  Check("d/dt exp(w) = exp(w)(T(w)wdot)~  [FD]",
        MaxDiff(fd, Tw1, nv) / (1 + MaxAbs(Tw1, nv)), 1e-9, ctx);
}

/* Tdot(w0, w1) x vs Richardson central difference of T(w0 + s w1) x */
static void CheckTdot(const TG *t, const RT *w0, const RT *w1, const RT *x,
                      const char *ctx)
{
  LGNGroup G = t->G;
  const sunindextype nv = G->nv;
  RT ws[MAXV], y[4][MAXV], fd[MAXV], td[MAXV];
  const double e = 1e-3;
  const double ss[4] = {e, -e, e / 2, -e / 2};
  sunindextype i;
  int k;
  for (k = 0; k < 4; k++) {
    for (i = 0; i < nv; i++) ws[i] = w0[i] + ss[k] * w1[i];
    LGNGroup_TangentApply(G, ws, x, y[k]);
  }
  for (i = 0; i < nv; i++) {
    LD D1 = ((LD)y[0][i] - y[1][i]) / (2 * (LD)e);
    LD D2 = ((LD)y[2][i] - y[3][i]) / (LD)e;
    fd[i] = (RT)((4 * D2 - D1) / 3);
  }
  LGNGroup_TangentDotApply(G, w0, w1, x, td);
  Check("Tdot(w,wd)x vs FD of T(w+s wd)x",
        MaxDiff(fd, td, nv) / (1 + MaxAbs(td, nv)), 1e-9, ctx);
}

/* algebraic checks at one w */
static void CheckAlgebra(const TG *t, const RT *w, const char *ctx)
{
  LGNGroup G = t->G;
  const sunindextype nv = G->nv, ldm = nv + 2;
  RT x[MAXV], y[MAXV], z[MAXV], e[MAXV], col[MAXV];
  static RT M[(MAXV + 2) * MAXV];
  double errm = 0, errpad = 0, errz = 0;
  sunindextype i, j;

  for (i = 0; i < nv; i++) x[i] = Rand();
  /* T T^{-1} x = x and T^{-1} T x = x */
  LGNGroup_TangentInverseApply(G, w, x, y);
  LGNGroup_TangentApply(G, w, y, z);
  Check("T(w) T^{-1}(w) x = x", MaxDiff(z, x, nv) / MaxAbs(x, nv), 1e-13, ctx);
  LGNGroup_TangentApply(G, w, x, y);
  LGNGroup_TangentInverseApply(G, w, y, z);
  Check("T^{-1}(w) T(w) x = x", MaxDiff(z, x, nv) / MaxAbs(x, nv), 1e-13, ctx);
  /* T(w) w = w since ad_w w = 0 */
  LGNGroup_TangentApply(G, w, w, y);
  Check("T(w) w = w", MaxDiff(y, w, nv) / (1 + MaxAbs(w, nv)), 1e-14, ctx);

  /* tangent_matrix vs tangent_apply; padding rows untouched; entries where
   * the apply gives an exact zero (outside the block pattern) exactly 0 */
  for (i = 0; i < ldm * nv; i++) M[i] = 12345.0;
  if (LGNGroup_TangentMatrix(G, w, M, ldm) != 0) Check("tangent_matrix returns 0", 1, 0, ctx);
  for (j = 0; j < nv; j++) {
    for (i = 0; i < nv; i++) e[i] = (i == j) ? 1 : 0;
    LGNGroup_TangentApply(G, w, e, col);
    for (i = 0; i < nv; i++) {
      double dd = fabs(M[i + j * ldm] - col[i]) / (1 + fabs(col[i]));
      if (dd > errm) errm = dd;
      if (col[i] == 0 && M[i + j * ldm] != 0) errz = 1;
    }
    for (i = nv; i < ldm; i++)
      if (M[i + j * ldm] != 12345.0) errpad = 1;
  }
  Check("tangent_matrix(w) = columns of tangent_apply(w, e_j)", errm, 1e-14, ctx);
  Check("tangent_matrix: exact zeros outside block pattern", errz, 0, ctx);
  Check("tangent_matrix: rows nv..ld-1 untouched", errpad, 0, ctx);
}

/* exp / compose checks at one w */
static void CheckCompose(const TG *t, const RT *q0, const RT *w, const char *ctx)
{
  LGNGroup G = t->G;
  const sunindextype nq = G->nq, nv = G->nv;
  RT q1[MAXQ], q2[MAXQ], qa[MAXQ], mw[MAXV], id[MAXQ];
  int k, i, j, oq = 0, ov = 0;
  double err = 0;

  for (i = 0; i < nv; i++) mw[i] = -w[i];
  LGNGroup_ComposeExp(G, q0, w, q1);
  LGNGroup_ComposeExp(G, q1, mw, q2);
  Check("q o exp(w) o exp(-w) = q", MaxDiff(q2, q0, nq) / (1 + MaxAbs(q0, nq)),
        2e-15 * (1 + MaxAbs(w, nv)), ctx);
  memcpy(qa, q0, (size_t)nq * sizeof(RT));
  LGNGroup_ComposeExp(G, qa, w, qa);
  Check("compose_exp with q_out aliasing q", MaxDiff(qa, q1, nq), 0, ctx);

  /* factorwise against independent long double formulas */
  LGNGroup_Identity(G, id);
  for (k = 0; k < t->nf; k++) {
    const RT *a = q0 + oq, *b = q1 + oq, *wk = w + ov;
    if (t->kind[k] == LGN_GROUP_RN) {
      for (i = 0; i < t->n[k]; i++) {
        double dd = fabs(b[i] - (a[i] + wk[i]));
        if (dd > err) err = dd;
        if (id[oq + i] != 0) err = 1;
      }
    } else {
      /* q0 and q1 as 4x4 homogeneous matrices */
      int r = (t->kind[k] == LGN_GROUP_SO3) ? 0 : 3;
      LD pa[4], Ra[9], A[16], E[16], H[16];
      RT Rb[9], z3[3] = {0, 0, 0};
      const RT *Om = wk + r;
      for (i = 0; i < 4; i++) pa[i] = a[r + i];
      QRotL(pa, Ra);
      LGNQuaternionToRotation(b + r, Rb);
      TwistL(t->kind[k] == LGN_GROUP_SE3 ? wk : z3, Om, A);
      Expm4L(A, E);
      /* H = [Ra, xa; 0 1] * E */
      for (i = 0; i < 3; i++)
        for (j = 0; j < 4; j++) {
          LD v = (j == 3 && r) ? (LD)a[i] : 0;
          v += Ra[3 * i] * E[j] + Ra[3 * i + 1] * E[4 + j] + Ra[3 * i + 2] * E[8 + j];
          H[4 * i + j] = v;
        }
      if (t->kind[k] == LGN_GROUP_R3XSO3)
        for (i = 0; i < 3; i++) H[4 * i + 3] = (LD)a[i] + wk[i];
      for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
          double dd = (double)fabsl(H[4 * i + j] - Rb[3 * i + j]);
          if (dd > err) err = dd;
        }
      if (r)
        for (i = 0; i < 3; i++) {
          double dd = (double)fabsl(H[4 * i + 3] - b[i]) / (1 + fabs(b[i]));
          if (dd > err) err = dd;
        }
      if (fabs(b[r] * b[r] + b[r + 1] * b[r + 1] + b[r + 2] * b[r + 2]
               + b[r + 3] * b[r + 3] - 1) > 1e-15)
        err = 1; /* compose_exp must renormalise */
      if (id[oq + r] != 1 || id[oq + r + 1] != 0 || id[oq + r + 2] != 0
          || id[oq + r + 3] != 0 || (r && (id[oq] != 0 || id[oq + 1] != 0
                                           || id[oq + 2] != 0)))
        err = 1;
    }
    oq += FacNq(t, k);
    ov += FacNv(t, k);
  }
  Check("compose_exp vs long double expm of the twist (x, R)", err,
        4e-15 * (1 + MaxAbs(w, nv)), ctx);
}

/* T(0) = I, Tdot(0,xd) = -ad(xd)/2 so Tdot(0,xd) xd = 0 (doc/theory.md §1.1) */
static void CheckAtZero(const TG *t)
{
  LGNGroup G = t->G;
  const sunindextype nv = G->nv;
  RT w[MAXV], xd[MAXV], x[MAXV], y[MAXV], ad[MAXV];
  static RT M[MAXV * MAXV];
  double err = 0;
  sunindextype i, j;
  for (i = 0; i < nv; i++) { w[i] = 0; xd[i] = Rand(); x[i] = Rand(); }
  LGNGroup_TangentMatrix(G, w, M, nv);
  for (j = 0; j < nv; j++)
    for (i = 0; i < nv; i++)
      err = fmax(err, fabs(M[i + j * nv] - (i == j ? 1.0 : 0.0)));
  Check("T(0) = I (exact)", err, 0, t->name);
  LGNGroup_TangentDotApply(G, w, xd, xd, y);
  Check("Tdot(0,xd) xd = 0", MaxAbs(y, nv), 1e-15, t->name);
  LGNGroup_TangentDotApply(G, w, xd, x, y);
  AdApply(t, xd, x, ad);
  for (i = 0; i < nv; i++) ad[i] *= -0.5;
  Check("Tdot(0,xd) x = -ad(xd) x / 2", MaxDiff(y, ad, nv), 1e-15, t->name);
}

static void RunGroup(const TG *t)
{
  static const double thr[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5};
  double phis[64];
  int np = 0, k, m;
  RT q0[MAXQ], w0[MAXV], w1[MAXV], w2[MAXV], x[MAXV];
  char ctx[160];
  sunindextype i;

  phis[np++] = 0; phis[np++] = 1e-9; phis[np++] = 1e-5; phis[np++] = 1e-3;
  for (k = 0; k < 6; k++) {
    phis[np++] = thr[k] * (1 - 1e-7);
    phis[np++] = thr[k];
    phis[np++] = thr[k] * (1 + 1e-7);
  }
  phis[np++] = 1; phis[np++] = 2.5; phis[np++] = 3.1; phis[np++] = 5;

  printf("--- %s: nq=%ld nv=%ld kind=%d\n", t->name, (long)t->G->nq,
         (long)t->G->nv, (int)t->G->kind);
  for (k = 0; k < np; k++)
    for (m = 0; m < 3; m++) { /* three random directions per angle */
      snprintf(ctx, sizeof ctx, "%s |w_rot|=%.9g #%d", t->name, phis[k], m);
      MakeQ(t, q0);
      MakeW(t, phis[k], w0);
      for (i = 0; i < t->G->nv; i++) {
        w1[i] = Rand(); w2[i] = Rand(); x[i] = Rand();
      }
      CheckDefining(t, q0, w0, w1, w2, ctx);
      CheckTdot(t, w0, w1, x, ctx);
      /* a slow curve stays on one side of a threshold */
      for (i = 0; i < t->G->nv; i++) w1[i] *= 1e-4;
      CheckTdot(t, w0, w1, x, ctx);
      CheckAlgebra(t, w0, ctx);
      CheckCompose(t, q0, w0, ctx);
    }
  CheckAtZero(t);
}

/* =============================================================================
 * Coefficients, spec check value, quaternion helpers, products, dispatchers
 * ===========================================================================*/

static void RunCoefficients(void)
{
  int k, j;
  char ctx[96];
  printf("--- SO(3) coefficients (long double mantissa %d bits, %s at run time)\n",
         LDBL_MANT_DIG, ldx ? "extended" : "NOT extended");
  if (!ldx)
    printf("NOTE: long double is not wider than double at run time (valgrind?):\n"
           "      only the reference-free continuity check is run for the coefficients.\n");
  for (k = 0; k < NCOEF; k++) {
    const CoefDef *cd = &coefdefs[k];
    const RT thr = (RT)cd->thr, below = nextafter(thr, 0.0);
    RT sb = LibCoef(cd->bit, below), ca = LibCoef(cd->bit, thr);
    LD rb = CoefClosedL(cd, below), ra = CoefClosedL(cd, thr);
    LD rs = CoefSeriesL(cd, below);
    snprintf(ctx, sizeof ctx, "%s at %.17g", cd->name, (double)thr);
    /* jump = series truncation (doc/theory.md §1.1) + closed-form rounding */
    Check("continuity across threshold: rel jump / (series + closed tol)",
          fabs((ca - sb) / sb) / (cd->stol + cd->ctol), 1, ctx);
    if (!ldx) continue;
    Check("series branch at threshold vs LD closed form: err/tol",
          (double)fabsl(((LD)sb - rb) / rb) / cd->stol, 1, ctx);
    Check("LD closed form vs LD 40-term series at threshold (ref)",
          (double)fabsl((rs - rb) / rb), 1e-13, ctx);
    Check(cd->cname, (double)fabsl(((LD)ca - ra) / ra), cd->ctol, ctx);
    Check("series at phi=0 is the constant term (rel, 1 ulp)",
          fabs(LibCoef(cd->bit, 0) / (RT)CoefSeriesL(cd, 0) - 1), 2.3e-16, ctx);
    /* whole range against the reference */
    for (j = 0; j <= 400; j++) {
      RT phi = (j < 100) ? cd->thr * j / 100.0 : 0.01 * (j - 100) + 0.005;
      LD r;
      if (cd->bit == LGN_SO3_D && phi > 5.5) continue; /* pole at 2 pi */
      r = CoefRefL(cd, phi);
      snprintf(ctx, sizeof ctx, "%s at %.6g", cd->name, (double)phi);
      if (phi < thr)
        Check("series branch vs LD reference on [0,thr): err/tol",
              (double)fabsl(((LD)LibCoef(cd->bit, phi) - r) / r) / cd->stol, 1, ctx);
      else
        Check(cd->cname, (double)fabsl(((LD)LibCoef(cd->bit, phi) - r) / r),
              cd->ctol, ctx);
    }
  }
}

static void RunSpecValue(void)
{
  static const double Tref[9] = {-0.0687127, 0.5555528, -0.0141310,
                                 -0.2267182, 0.1779133, 0.6236305,
                                 0.5073830, 0.3628735, 0.5889567};
  RT x[3] = {1, 2, 3}, M[9], e[3], y[3];
  double err = 0, erra = 0;
  int i, j;
  LGNGroup G = LGNGroup_SO3();
  LGNGroup_TangentMatrix(G, x, M, 3);
  for (j = 0; j < 3; j++) {
    for (i = 0; i < 3; i++) e[i] = (i == j);
    LGNGroup_TangentApply(G, x, e, y);
    for (i = 0; i < 3; i++) {
      err = fmax(err, fabs(M[i + 3 * j] - Tref[3 * i + j]));
      erra = fmax(erra, fabs(y[i] - Tref[3 * i + j]));
    }
  }
  printf("--- spec check value T((1,2,3))\n");
  Check("spec value T((1,2,3)) rows, tangent_matrix", err, 6e-7, "SO3");
  Check("spec value T((1,2,3)) rows, tangent_apply", erra, 6e-7, "SO3");
  LGNGroup_Destroy(G);
}

static void RunQuaternions(void)
{
  static const double ang[] = {0, 1e-15, 1e-12, 1e-8, 1e-4, 1e-3, 0.01,
                               0.09999999, 0.1, 0.10000001,
                               0.5, 1, 2, 3, 3.14159, 3.141592653589793 - 1e-7};
  const double PI = 3.141592653589793238462643383279502884;
  RT d[3], phi[3], p[4], mp[4], phi2[3], R[9], p1[4], p2[4], p12[4], R1[9],
     R2[9], R12[9];
  LD A[16], E[16];
  char ctx[96];
  int k, i, j, m;
  printf("--- quaternion helpers\n");
  for (k = 0; k < (int)(sizeof ang / sizeof ang[0]); k++)
    for (m = 0; m < 4; m++) {
      RandDir(d);
      for (i = 0; i < 3; i++) phi[i] = ang[k] * d[i];
      snprintf(ctx, sizeof ctx, "angle %.17g", ang[k]);
      LGNQuaternionFromRotationVector(phi, p);
      Check("quaternion from rotation vector is unit",
            fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1), 1e-15, ctx);
      {
        /* expq(phi) = (cos(h), sin(h)/|phi| phi), h = |phi|/2, in long double */
        LD h = 0.5L * (LD)ang[k], kk = (ang[k] > 0) ? sinl(h) / (LD)ang[k] : 0.5L;
        LD pr[4];
        pr[0] = cosl(h);
        for (i = 0; i < 3; i++) pr[i + 1] = kk * ang[k] * d[i];
        Check("quaternion from rotation vector vs long double (rel)",
              MaxDiffL(pr, p, 4) / (double)fmaxl(fabsl(pr[0]), sinl(h)), 3e-16, ctx);
      }
      LGNRotationVectorFromQuaternion(p, phi2);
      Check("rotvec -> quat -> rotvec round trip",
            MaxDiff(phi, phi2, 3) / fmax(1e-300, ang[k] > 0 ? ang[k] : 1), 4e-16, ctx);
      for (i = 0; i < 4; i++) mp[i] = -3.7 * p[i];
      LGNRotationVectorFromQuaternion(mp, phi2);
      Check("log(-3.7 p) = log(p) (sign w >= 0, scale free)",
            MaxDiff(phi, phi2, 3) / fmax(1e-300, ang[k] > 0 ? ang[k] : 1), 4e-16, ctx);
      /* R(expq(phi)) = expm(phi~) */
      LGNQuaternionToRotation(p, R);
      TwistL(d, phi, A); /* translation part unused */
      Expm4L(A, E);
      for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) A[3 * i + j] = E[4 * i + j];
      Check("R(quat(phi)) = expm(phi~) [long double]", MaxDiffL(A, R, 9),
            ldx ? 1e-15 : 2e-14, ctx);
    }
  /* renormalisation: the cheap branch (|p|^2 within 1e-8 of 1) and the
   * exact one agree with p/|p| in long double; zero stays zero */
  {
    static const double scale[] = {1, 1 + 1e-16, 1 - 3e-13, 1 + 4.9e-9, 1 - 4.9e-9,
                                   1 + 5.1e-9, 1 + 1e-6, 0.25, 3.5};
    for (k = 0; k < (int)(sizeof scale / sizeof scale[0]); k++)
      for (m = 0; m < 4; m++) {
        LD n2 = 0, pr[4];
        RandDir(d);
        LGNQuaternionFromRotationVector(d, p);
        for (i = 0; i < 4; i++) { p[i] *= scale[k]; n2 += (LD)p[i] * p[i]; }
        for (i = 0; i < 4; i++) pr[i] = p[i] / sqrtl(n2);
        lgnSO3_QuatNormalize(p);
        snprintf(ctx, sizeof ctx, "|p| = %.17g", scale[k]);
        Check("quaternion renormalisation vs p/|p| [long double]", MaxDiffL(pr, p, 4),
              ldx ? 3e-16 : 5e-16, ctx);
      }
    for (i = 0; i < 4; i++) p[i] = 0;
    lgnSO3_QuatNormalize(p);
    Check("renormalising the zero quaternion leaves it zero",
          fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + fabs(p[3]), 0, "zero");
  }
  /* just beyond pi: the log picks the equivalent vector of angle 2pi - |phi| */
  for (m = 0; m < 4; m++) {
    double a = PI + (m == 0 ? 1e-9 : m == 1 ? 1e-6 : m == 2 ? 1e-3 : 1.0);
    RT ex[3];
    RandDir(d);
    for (i = 0; i < 3; i++) { phi[i] = a * d[i]; ex[i] = -(2 * PI - a) * d[i]; }
    LGNQuaternionFromRotationVector(phi, p);
    LGNRotationVectorFromQuaternion(p, phi2);
    snprintf(ctx, sizeof ctx, "angle pi+%.1e", a - PI);
    Check("log of angle > pi returns the vector with |phi| <= pi",
          MaxDiff(ex, phi2, 3), 4e-15, ctx);
  }
  /* Hamilton product: R(p1 p2) = R(p1) R(p2); aliasing */
  for (m = 0; m < 20; m++) {
    double n1 = 0, n2 = 0, err = 0;
    for (i = 0; i < 4; i++) { p1[i] = Rand(); p2[i] = Rand(); n1 += p1[i] * p1[i]; n2 += p2[i] * p2[i]; }
    for (i = 0; i < 4; i++) { p1[i] /= sqrt(n1); p2[i] /= sqrt(n2); }
    LGNQuaternionMultiply(p1, p2, p12);
    LGNQuaternionToRotation(p1, R1);
    LGNQuaternionToRotation(p2, R2);
    LGNQuaternionToRotation(p12, R12);
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++) {
        double v = 0;
        for (k = 0; k < 3; k++) v += R1[3 * i + k] * R2[3 * k + j];
        err = fmax(err, fabs(v - R12[3 * i + j]));
      }
    Check("R(p1 (x) p2) = R(p1) R(p2)", err, 1e-15, "random");
    memcpy(p, p1, sizeof p);
    LGNQuaternionMultiply(p, p2, p);
    err = MaxDiff(p, p12, 4);
    memcpy(p, p2, sizeof p);
    LGNQuaternionMultiply(p1, p, p);
    err = fmax(err, MaxDiff(p, p12, 4));
    Check("quaternion multiply with r aliasing p1 / p2", err, 0, "random");
    /* orthogonality and det of R */
    err = 0;
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++) {
        double v = 0;
        for (k = 0; k < 3; k++) v += R12[3 * k + i] * R12[3 * k + j];
        err = fmax(err, fabs(v - (i == j)));
      }
    err = fmax(err, fabs(R12[0] * (R12[4] * R12[8] - R12[5] * R12[7])
                         - R12[1] * (R12[3] * R12[8] - R12[5] * R12[6])
                         + R12[2] * (R12[3] * R12[7] - R12[4] * R12[6]) - 1));
    Check("R(p) orthogonal with det 1", err, 1e-15, "random");
  }
}

/* a user-style custom group with no ops, and an always-failing op */
static int FailingCompose(LGNGroup G, const RT *q, const RT *w, RT *q_out)
{
  (void)G; (void)q; (void)w; (void)q_out;
  return 7;
}

static void RunApiAndProducts(void)
{
  LGNGroup so3 = LGNGroup_SO3(), rn = LGNGroup_Rn(2), r3 = LGNGroup_R3xSO3();
  LGNGroup se3 = LGNGroup_SE3(), empty = LGNGroup_NewEmpty(3, 2);
  LGNGroup bad[3], chain, P, P2;
  static LGNGroup many[10000];
  RT q[8] = {0}, w[8] = {0}, y[8];
  double err;
  int i, flag;

  printf("--- constructors, dispatchers, products\n");
  Check("constructors return groups of the right kind and size",
        (so3 && so3->kind == LGN_GROUP_SO3 && so3->nq == 4 && so3->nv == 3 &&
         rn && rn->kind == LGN_GROUP_RN && rn->nq == 2 && rn->nv == 2 &&
         r3 && r3->kind == LGN_GROUP_R3XSO3 && r3->nq == 7 && r3->nv == 6 &&
         se3 && se3->kind == LGN_GROUP_SE3 && se3->nq == 7 && se3->nv == 6 &&
         empty && empty->kind == LGN_GROUP_CUSTOM && empty->nq == 3 &&
         empty->nv == 2) ? 0 : 1, 0, "kinds");
  Check("bad dimensions give NULL (Rn(0), NewEmpty(0,1), NewEmpty(1,0))",
        (LGNGroup_Rn(0) == NULL && LGNGroup_NewEmpty(0, 1) == NULL &&
         LGNGroup_NewEmpty(1, 0) == NULL) ? 0 : 1, 0, "dims");

  /* dispatchers: -1 for a NULL group or a missing op */
  flag = (LGNGroup_ComposeExp(NULL, q, w, y) == -1)
       + (LGNGroup_TangentApply(NULL, w, q, y) == -1)
       + (LGNGroup_TangentInverseApply(NULL, w, q, y) == -1)
       + (LGNGroup_TangentDotApply(NULL, w, w, q, y) == -1)
       + (LGNGroup_TangentMatrix(NULL, w, y, 2) == -1)
       + (LGNGroup_Identity(NULL, q) == -1)
       + (LGNGroup_Normalize(NULL, q) == -1);
  Check("dispatchers return -1 for G == NULL (7 ops)", 7 - flag, 0, "NULL");
  flag = (LGNGroup_ComposeExp(empty, q, w, y) == -1)
       + (LGNGroup_TangentApply(empty, w, q, y) == -1)
       + (LGNGroup_TangentInverseApply(empty, w, q, y) == -1)
       + (LGNGroup_TangentDotApply(empty, w, w, q, y) == -1)
       + (LGNGroup_TangentMatrix(empty, w, y, 2) == -1)
       + (LGNGroup_Identity(empty, q) == -1)
       + (LGNGroup_Normalize(empty, q) == 0);
  Check("missing op: -1 (normalize: documented no-op, 0)", 7 - flag, 0, "empty");
  Check("TangentMatrix with ld < nv returns -1",
        LGNGroup_TangentMatrix(so3, w, y, 2) == -1 ? 0 : 1, 0, "ld");
  empty->ops.compose_exp = FailingCompose;
  Check("dispatcher passes the op's flag through",
        LGNGroup_ComposeExp(empty, q, w, y) == 7 ? 0 : 1, 0, "flag");

  /* product input validation */
  bad[0] = so3; bad[1] = NULL; bad[2] = rn;
  Check("Product rejects nfactors<1, factors==NULL, a NULL factor",
        (LGNGroup_Product(0, bad) == NULL && LGNGroup_Product(-1, bad) == NULL &&
         LGNGroup_Product(2, NULL) == NULL && LGNGroup_Product(3, bad) == NULL)
        ? 0 : 1, 0, "bad input");
  /* a product with a factor whose op is missing or fails */
  bad[0] = so3; bad[1] = empty;
  P = LGNGroup_Product(2, bad);
  Check("product: failing/missing factor op propagates (7 / -1)",
        (P != NULL && LGNGroup_ComposeExp(P, q, w, y) == 7 &&
         LGNGroup_TangentApply(P, w, w, y) == -1) ? 0 : 1, 0, "custom factor");
  /* normalize: a zero quaternion is no rotation (-1, from the SO(3)
   * factor); a nonzero one is scaled, the factor without the op skipped */
  Check("product: normalize fails on a zero quaternion, succeeds on (2, 0, 0, 0)",
        (LGNGroup_Normalize(P, q) == -1 && (q[0] = 2.0, LGNGroup_Normalize(P, q) == 0) &&
         q[0] == 1.0) ? 0 : 1, 0, "custom factor");
  LGNGroup_Destroy(P);

  /* a chain of 10000 identical bodies: one factor referenced 10000 times */
  {
    const int nb = 10000;
    RT *qq, *ww, *xx, *yy, *zz, *q1, *T1, *w1;
    clock_t c0;
    double secs;
    for (i = 0; i < nb; i++) many[i] = r3;
    c0 = clock();
    chain = LGNGroup_Product(nb, many);
    Check("chain of 10000 R3xSO3: nq = 70000, nv = 60000, kind product",
          (chain && chain->nq == 7 * nb && chain->nv == 6 * nb &&
           chain->kind == LGN_GROUP_PRODUCT) ? 0 : 1, 0, "chain");
    qq = malloc(sizeof(RT) * 7 * nb); q1 = malloc(sizeof(RT) * 7);
    ww = malloc(sizeof(RT) * 6 * nb); xx = malloc(sizeof(RT) * 6 * nb);
    yy = malloc(sizeof(RT) * 6 * nb); zz = malloc(sizeof(RT) * 6 * nb);
    T1 = malloc(sizeof(RT) * 6); w1 = malloc(sizeof(RT) * 6);
    if (!qq || !q1 || !ww || !xx || !yy || !zz || !T1 || !w1) exit(3);
    for (i = 0; i < 6 * nb; i++) { ww[i] = Rand(); xx[i] = Rand(); }
    LGNGroup_Identity(chain, qq);
    for (i = 0; i < 10; i++) {
      LGNGroup_ComposeExp(chain, qq, ww, qq);
      LGNGroup_TangentApply(chain, ww, xx, yy);
      LGNGroup_TangentInverseApply(chain, ww, yy, zz);
      LGNGroup_TangentDotApply(chain, ww, xx, xx, yy);
      LGNGroup_Normalize(chain, qq);
    }
    secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
    printf("    chain of %d bodies: build + 10 x (compose, T, T^-1, Tdot) "
           "in %.3f s\n", nb, secs);
    Check("chain: T^{-1} T x = x over all 60000 entries",
          MaxDiff(zz, xx, 6 * nb) / MaxAbs(xx, 6 * nb), 1e-13, "chain");
    /* body 7777 against the factor itself */
    err = 0;
    LGNGroup_Identity(r3, q1);
    for (i = 0; i < 10; i++) {
      LGNGroup_ComposeExp(r3, q1, ww + 6 * 7777, q1);
      LGNGroup_Normalize(r3, q1);
    }
    err = fmax(err, MaxDiff(q1, qq + 7 * 7777, 7));
    LGNGroup_TangentDotApply(r3, ww + 6 * 7777, xx + 6 * 7777, xx + 6 * 7777, T1);
    err = fmax(err, MaxDiff(T1, yy + 6 * 7777, 6));
    Check("chain: body 7777 equals the factor's own ops (offsets)", err, 0, "chain");
    Check("chain build + 40 ops over 10000 bodies under 10 s", secs, 10.0, "chain");
    free(qq); free(q1); free(ww); free(xx); free(yy); free(zz); free(T1); free(w1);
    LGNGroup_Destroy(chain);
  }

  /* nested product: (R3xSO3 x SO3) x SE3 x R^2 */
  bad[0] = r3; bad[1] = so3;
  P = LGNGroup_Product(2, bad);
  bad[0] = P; bad[1] = se3; bad[2] = rn;
  P2 = LGNGroup_Product(3, bad);
  {
    TG t;
    memset(&t, 0, sizeof t);
    t.name = "(R3xSO3 x SO3) x SE3 x R^2 (nested)"; t.G = P2; t.nf = 4;
    t.kind[0] = LGN_GROUP_R3XSO3; t.kind[1] = LGN_GROUP_SO3;
    t.kind[2] = LGN_GROUP_SE3; t.kind[3] = LGN_GROUP_RN; t.n[3] = 2;
    Check("nested product sizes nq=20 nv=17", (P2 && P2->nq == 20 && P2->nv == 17)
          ? 0 : 1, 0, "nested");
    if (P2) RunGroup(&t);
  }
  LGNGroup_Destroy(P2);
  LGNGroup_Destroy(P);
  LGNGroup_Destroy(so3); LGNGroup_Destroy(rn); LGNGroup_Destroy(r3);
  LGNGroup_Destroy(se3); LGNGroup_Destroy(empty);
  LGNGroup_Destroy(NULL);
}

int main(void)
{
  LGNGroup rn5 = LGNGroup_Rn(5), so3 = LGNGroup_SO3(), r3 = LGNGroup_R3xSO3();
  LGNGroup se3 = LGNGroup_SE3(), r2 = LGNGroup_Rn(2), prod;
  LGNGroup fac[3];
  TG t;
  int nfail;

  printf("Lignum unit test: built-in Lie groups (doc/theory.md §1.1)\n");
  {
    volatile LD one = 1, tiny = LDBL_EPSILON;
    ldx = (LDBL_MANT_DIG > 53) && ((one + tiny) - one == tiny);
  }
  if (!rn5 || !so3 || !r3 || !se3 || !r2) {
    printf("FAIL  a built-in constructor returned NULL\n");
    return 1;
  }
  fac[0] = r3; fac[1] = so3; fac[2] = r2;
  prod = LGNGroup_Product(3, fac);

  RunCoefficients();
  RunSpecValue();
  RunQuaternions();

  memset(&t, 0, sizeof t);
  t.name = "R^5"; t.G = rn5; t.nf = 1; t.kind[0] = LGN_GROUP_RN; t.n[0] = 5;
  RunGroup(&t);
  t.name = "SO(3)"; t.G = so3; t.kind[0] = LGN_GROUP_SO3;
  RunGroup(&t);
  t.name = "R^3xSO(3)"; t.G = r3; t.kind[0] = LGN_GROUP_R3XSO3;
  RunGroup(&t);
  t.name = "SE(3)"; t.G = se3; t.kind[0] = LGN_GROUP_SE3;
  RunGroup(&t);
  memset(&t, 0, sizeof t);
  t.name = "R3xSO3 x SO3 x R^2"; t.G = prod; t.nf = 3;
  t.kind[0] = LGN_GROUP_R3XSO3; t.kind[1] = LGN_GROUP_SO3;
  t.kind[2] = LGN_GROUP_RN; t.n[2] = 2;
  if (prod == NULL) Check("product constructor", 1, 0, "R3xSO3 x SO3 x R^2");
  else RunGroup(&t);

  RunApiAndProducts();

  nfail = CheckSummary(60);

  LGNGroup_Destroy(prod);
  LGNGroup_Destroy(rn5); LGNGroup_Destroy(so3); LGNGroup_Destroy(r3);
  LGNGroup_Destroy(se3); LGNGroup_Destroy(r2);
  return nfail ? 1 : 0;
}
