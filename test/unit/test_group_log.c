/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the logarithm of the built-in groups, LGNGroup_ComposeLog
 * (w = log(q1^{-1} q2), the inverse of LGNGroup_ComposeExp), for R^n,
 * SO(3), R^3 x SO(3), SE(3) and a product of all of them:
 *  - round trips log(q, exp(q, w)) = w (angles in (0, pi)) and
 *    exp(q1, log(q1, q2)) = q2 (as rotations: p and -p are one rotation);
 *  - against a long double reference computed from the same stored q1, q2;
 *  - tiny angles (1e-4 ... 1e-300, 0) with relative accuracy where the base
 *    point's rotation is exact (identity and +-basis quaternions), and the
 *    absolute accuracy a few eps that the rounding of a general q1 allows;
 *  - near pi (pi - 1e-3 ... pi - 1e-15) and at pi exactly (w = 0 in the
 *    quaternion): |log| = pi, one choice for p and -p;
 *  - sign flips of q1 and q2 give the same w bit for bit;
 *  - quaternions unnormalised by roundoff (and any scale) give the same w;
 *  - log(q2, q1) = -log(q1, q2);
 *  - the derivative: d/de log(q1^{-1} q2 o exp(e d)) at e = 0 equals
 *    T(w)^{-1} d (the library's T: d/dt exp(w) = exp(w) (T(w) wdot)^),
 *    by Richardson-extrapolated central differences;
 *  - bad input: flags and the messages naming the argument or the op.
 * A summary table (check, count, max error, tolerance) is printed; the exit
 * status is nonzero if any check failed.
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L /* dup, dup2, fileno */

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>

#define GROUP_TEST_SEED 0x2545F4914F6CDD1DULL
#include "group_test_util.h"

#define MAXF 8  /* max factors of a test group */
#define MAXV 32 /* max nv of a test group      */
#define MAXQ 40 /* max nq of a test group      */

static const double PI = 3.141592653589793238462643383279502884;

/* =============================================================================
 * Test groups: the factor kinds, for building q and w and for the references
 * ===========================================================================*/

typedef struct {
  const char *name;
  LGNGroup G;
  int nf;
  LGNGroupKind kind[MAXF];
  int n[MAXF]; /* size of R^n factors */
} TG;

static int FacNq(const TG *t, int k)
{
  return t->kind[k] == LGN_GROUP_RN ? t->n[k] : t->kind[k] == LGN_GROUP_SO3 ? 4 : 7;
}

static int FacNv(const TG *t, int k)
{
  return t->kind[k] == LGN_GROUP_RN ? t->n[k] : t->kind[k] == LGN_GROUP_SO3 ? 3 : 6;
}

/* offset of the quaternion in factor k's q (-1: none), of the rotation in v */
static int QuatOff(const TG *t, int k)
{
  return t->kind[k] == LGN_GROUP_RN ? -1 : t->kind[k] == LGN_GROUP_SO3 ? 0 : 3;
}

/* random w whose rotation parts have angle phi; translations in [-1, 1] */
static void MakeW(const TG *t, double phi, RT *w)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    RT d[3];
    int r = QuatOff(t, k);
    if (r < 0) {
      for (i = 0; i < t->n[k]; i++) w[o + i] = Rand();
    } else {
      for (i = 0; i < r; i++) w[o + i] = Rand();
      RandDir(d);
      for (i = 0; i < 3; i++) w[o + r + i] = phi * d[i];
    }
    o += FacNv(t, k);
  }
}

/* random group element; exact != 0: translations 0 and each quaternion one
 * of +-1, +-i, +-j, +-k (so that composing with it is exact) */
static void MakeQ(const TG *t, RT *q, int exact)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    int r = QuatOff(t, k), nt = r < 0 ? t->n[k] : r;
    for (i = 0; i < nt; i++) q[o + i] = exact ? 0 : 2 * Rand();
    if (r >= 0) {
      RT *p = q + o + r;
      if (exact) {
        int j = (int)((Rand() + 1) * 2) & 3;
        for (i = 0; i < 4; i++) p[i] = 0;
        p[j] = Rand() < 0 ? -1 : 1;
      } else {
        double n = 0;
        for (i = 0; i < 4; i++) { p[i] = Rand(); n += p[i] * p[i]; }
        for (i = 0; i < 4; i++) p[i] /= sqrt(n);
      }
    }
    o += FacNq(t, k);
  }
}

/* the largest error of a rotation part relative to that part's max norm
 * (0/0 = 0: an exact zero stays exact) and of the other entries relative
 * to max(1, |w|) */
static double BlockRelErr(const TG *t, const RT *w, const RT *wref)
{
  int k, o = 0;
  double err = 0, big = fmax(1.0, MaxAbs(wref, (int)t->G->nv));
  for (k = 0; k < t->nf; k++) {
    int r = QuatOff(t, k), nt = r < 0 ? t->n[k] : r;
    err = fmax(err, MaxDiff(w + o, wref + o, nt) / big);
    if (r >= 0) {
      const RT *a = w + o + r, *b = wref + o + r;
      double nb = MaxAbs(b, 3); /* no squares: angles down to 1e-300 */
      double d = MaxDiff(a, b, 3);
      err = fmax(err, nb > 0 ? d / nb : (d == 0 ? 0 : INFINITY));
    }
    o += FacNv(t, k);
  }
  return err;
}

/* q2 vs q3 as group elements: quaternions up to sign, the rest relative
 * to 1 + |entry| */
static double GroupDiff(const TG *t, const RT *qa, const RT *qb)
{
  int k, i, o = 0;
  double err = 0;
  for (k = 0; k < t->nf; k++) {
    int r = QuatOff(t, k), nt = r < 0 ? t->n[k] : r;
    for (i = 0; i < nt; i++)
      err = fmax(err, fabs(qa[o + i] - qb[o + i]) / (1 + fabs(qb[o + i])));
    if (r >= 0) {
      double ep = 0, em = 0;
      for (i = 0; i < 4; i++) {
        ep = fmax(ep, fabs(qa[o + r + i] - qb[o + r + i]));
        em = fmax(em, fabs(qa[o + r + i] + qb[o + r + i]));
      }
      err = fmax(err, fmin(ep, em));
    }
    o += FacNq(t, k);
  }
  return err;
}

/* the quaternions of q scaled by s */
static void ScaleQuats(const TG *t, RT *q, double s)
{
  int k, i, o = 0;
  for (k = 0; k < t->nf; k++) {
    int r = QuatOff(t, k);
    if (r >= 0)
      for (i = 0; i < 4; i++) q[o + r + i] *= s;
    o += FacNq(t, k);
  }
}

/* =============================================================================
 * Long double reference: log(q1^{-1} q2) from the stored q1, q2
 * ===========================================================================*/

/* d(phi) = (1 - (phi/2) cot(phi/2)) / phi^2 of T^{-1} */
static LD CoefDL(LD phi)
{
  LD p2 = phi * phi;
  if (phi < 0.05L)
    return 1.0L / 12 + p2 * (1.0L / 720 + p2 * (1.0L / 30240 + p2 * (1.0L / 1209600)));
  return (1.0L - 0.5L * phi / tanl(0.5L * phi)) / p2;
}

static void LogRefL(const TG *t, const RT *q1, const RT *q2, LD *out)
{
  int k, i, oq = 0, ov = 0;
  for (k = 0; k < t->nf; k++) {
    const RT *a = q1 + oq, *b = q2 + oq;
    int r = QuatOff(t, k);
    if (r < 0) {
      for (i = 0; i < t->n[k]; i++) out[ov + i] = (LD)b[i] - (LD)a[i];
    } else {
      LD pa[4], pb[4], pr[4], s, n, kk, *om = out + ov + r;
      pa[0] = a[r]; pb[0] = b[r];
      for (i = 1; i < 4; i++) { pa[i] = -(LD)a[r + i]; pb[i] = b[r + i]; }
      QMulL(pa, pb, pr);
      s = (pr[0] < 0) ? -1.0L : 1.0L;
      n = sqrtl(pr[1] * pr[1] + pr[2] * pr[2] + pr[3] * pr[3]);
      kk = (n == 0) ? 2.0L / (s * pr[0]) : 2.0L * atan2l(n, s * pr[0]) / n;
      for (i = 0; i < 3; i++) om[i] = s * kk * pr[i + 1];
      if (r == 3) {
        for (i = 0; i < 3; i++) out[ov + i] = (LD)b[i] - (LD)a[i];
      }
      if (t->kind[k] == LGN_GROUP_SE3) {
        /* U = T(-Om)^{-1} R(p1)^T (x2 - x1); R(p1)^T = R(conj p1) */
        LD nn = pa[0] * pa[0] + pa[1] * pa[1] + pa[2] * pa[2] + pa[3] * pa[3];
        LD w = pa[0], x = pa[1], y = pa[2], z = pa[3], sc = 2.0L / nn;
        LD Rt[9], dx[3], xr[3], mo[3], ox[3], oox[3], d;
        Rt[0] = 1 - sc * (y * y + z * z); Rt[1] = sc * (x * y - w * z);
        Rt[2] = sc * (x * z + w * y);     Rt[3] = sc * (x * y + w * z);
        Rt[4] = 1 - sc * (x * x + z * z); Rt[5] = sc * (y * z - w * x);
        Rt[6] = sc * (x * z - w * y);     Rt[7] = sc * (y * z + w * x);
        Rt[8] = 1 - sc * (x * x + y * y);
        for (i = 0; i < 3; i++) dx[i] = (LD)b[i] - (LD)a[i];
        for (i = 0; i < 3; i++)
          xr[i] = Rt[3 * i] * dx[0] + Rt[3 * i + 1] * dx[1] + Rt[3 * i + 2] * dx[2];
        for (i = 0; i < 3; i++) mo[i] = -om[i];
        d = CoefDL(sqrtl(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]));
        CrossL(mo, xr, ox);
        CrossL(mo, ox, oox);
        for (i = 0; i < 3; i++) out[ov + i] = xr[i] + 0.5L * ox[i] + d * oox[i];
      }
    }
    oq += FacNq(t, k);
    ov += FacNv(t, k);
  }
}

/* =============================================================================
 * Checks on one group
 * ===========================================================================*/

static int Log(const TG *t, const RT *q1, const RT *q2, RT *w)
{
  int flag = LGNGroup_ComposeLog(t->G, q1, q2, w);
  if (flag != LGN_SUCCESS) Check("LGNGroup_ComposeLog returns LGN_SUCCESS", 1, 0, t->name);
  return flag;
}

/* round trips, reference, antisymmetry, sign flips, scaling at one (q1, w) */
static void CheckAt(const TG *t, const RT *q1, const RT *w, int exact, double phi,
                    const char *ctx)
{
  const int nq = (int)t->G->nq, nv = (int)t->G->nv;
  RT q2[MAXQ], q3[MAXQ], qs1[MAXQ], qs2[MAXQ], wl[MAXV], wb[MAXV], wr[MAXV];
  LD ref[MAXV];
  int i;
  double err;

  LGNGroup_ComposeExp(t->G, q1, w, q2);
  Log(t, q1, q2, wl);
  err = BlockRelErr(t, wl, w);
  if (exact && phi < 3)
    Check("log(q, exp(q, w)) = w, q exact, angle 0, 1e-300..0.11 (rel/block)",
          err, 6e-16, ctx);
  else if (exact)
    Check("log(q, exp(q, w)) = w, q exact, angle pi-1e-6..pi-1e-15 (rel)",
          err, 6e-16, ctx);
  else if (phi > PI - 2e-3)
    Check("log(q, exp(q, w)) = w, random q, angle pi-1e-3..pi-1e-12 (rel)",
          err, 1e-14, ctx);
  else if (phi >= 0.1)
    Check("log(q, exp(q, w)) = w, random q, angle in [0.1, pi) (rel)",
          err, 1e-14, ctx);
  else
    Check("log(q, exp(q, w)) = w, random q, angle < 0.1 (abs, max(1,|w|))",
          MaxDiff(wl, w, nv) / fmax(1, MaxAbs(w, nv)), 4e-15, ctx);

  /* exp(q1, log(q1, q2)) = q2 as group elements */
  LGNGroup_ComposeExp(t->G, q1, wl, q3);
  Check("exp(q1, log(q1, q2)) = q2 (quaternions up to sign)",
        GroupDiff(t, q3, q2), 1e-15, ctx);

  /* the long double log of the same stored q1, q2 */
  LogRefL(t, q1, q2, ref);
  err = 0;
  for (i = 0; i < nv; i++) {
    wr[i] = (RT)ref[i];
  }
  if (exact)
    Check("log vs long double log of the same q1, q2, q exact (rel per block)",
          BlockRelErr(t, wl, wr), ldx ? 4e-16 : 1e-15, ctx);
  else
    Check("log vs long double log of the same q1, q2 (abs, max(1,|w|))",
          MaxDiff(wl, wr, nv) / fmax(1, MaxAbs(wr, nv)), ldx ? 2e-15 : 4e-15, ctx);

  /* log(q2, q1) = -log(q1, q2) */
  Log(t, q2, q1, wb);
  for (i = 0; i < nv; i++) wb[i] = -wb[i];
  Check("log(q2, q1) = -log(q1, q2) (abs, max(1,|w|))",
        MaxDiff(wb, wl, nv) / fmax(1, MaxAbs(wl, nv)), 4e-15, ctx);

  /* -p for p: the same w, bit for bit */
  memcpy(qs1, q1, (size_t)nq * sizeof(RT));
  memcpy(qs2, q2, (size_t)nq * sizeof(RT));
  ScaleQuats(t, qs2, -1);
  Log(t, q1, qs2, wb);
  err = MaxDiff(wb, wl, nv);
  ScaleQuats(t, qs1, -1);
  Log(t, qs1, q2, wb);
  err = fmax(err, MaxDiff(wb, wl, nv));
  Log(t, qs1, qs2, wb);
  err = fmax(err, MaxDiff(wb, wl, nv));
  Check("sign flips q1 -> -q1, q2 -> -q2 give the same w (bit for bit)", err, 0, ctx);

  /* quaternions unnormalised by roundoff (and by any scale) */
  {
    static const double sc[] = {1 + 2.2e-16, 1 - 1.1e-16, 1 + 1e-13, 1 - 3e-12,
                                1 + 1e-8, 3.7, 0.01};
    int m;
    err = 0;
    for (m = 0; m < (int)(sizeof sc / sizeof sc[0]); m++) {
      memcpy(qs1, q1, (size_t)nq * sizeof(RT));
      memcpy(qs2, q2, (size_t)nq * sizeof(RT));
      ScaleQuats(t, qs1, sc[m]);
      ScaleQuats(t, qs2, 1 / sc[(m + 3) % 7]);
      Log(t, qs1, qs2, wb);
      err = fmax(err, exact ? BlockRelErr(t, wb, wl)
                            : MaxDiff(wb, wl, nv) / fmax(1, MaxAbs(wl, nv)));
    }
    Check(exact ? "quaternions scaled (1+-1e-16 .. 3.7): same w, q exact (rel)"
                : "quaternions scaled (1+-1e-16 .. 3.7): same w (abs, max(1,|w|))",
          err, exact ? 1e-15 : 4e-15, ctx);
  }
}

/* d/de log(q1^{-1} q2 o exp(e d)) at e = 0 = T(w)^{-1} d, w = log(q1^{-1} q2):
 * Richardson-extrapolated central differences */
static void CheckDerivative(const TG *t, const RT *q1, const RT *w, const char *ctx)
{
  const int nv = (int)t->G->nv;
  RT q2[MAXQ], qe[MAXQ], wl[MAXV], d[MAXV], ed[MAXV], g[4][MAXV], fd[MAXV], ti[MAXV];
  const double e = 1e-3, ss[4] = {1e-3, -1e-3, 5e-4, -5e-4};
  int i, k;
  LGNGroup_ComposeExp(t->G, q1, w, q2);
  Log(t, q1, q2, wl);
  for (i = 0; i < nv; i++) d[i] = Rand();
  for (k = 0; k < 4; k++) {
    for (i = 0; i < nv; i++) ed[i] = ss[k] * d[i];
    LGNGroup_ComposeExp(t->G, q2, ed, qe);
    Log(t, q1, qe, g[k]);
  }
  for (i = 0; i < nv; i++) {
    LD D1 = ((LD)g[0][i] - g[1][i]) / (2 * (LD)e);
    LD D2 = ((LD)g[2][i] - g[3][i]) / (LD)e;
    fd[i] = (RT)((4 * D2 - D1) / 3);
  }
  LGNGroup_TangentInverseApply(t->G, wl, d, ti);
  Check("d/de log(q1^-1 q2 exp(e d)) = T(w)^-1 d  [FD, rel]",
        MaxDiff(fd, ti, nv) / (1 + MaxAbs(ti, nv)), 1e-9, ctx);
}

static void RunGroup(const TG *t)
{
  static const double tiny[] = {0, 1e-300, 1e-200, 1e-154, 1e-100, 1e-12, 1e-8,
                                1e-4, 0.0499, 0.0501, 0.09, 0.11};
  static const double nearpi[] = {1e-3, 1e-6, 1e-9, 1e-12};
  static const double nearpi_exact[] = {1e-6, 1e-9, 1e-12, 1e-15};
  RT q1[MAXQ], w[MAXV];
  char ctx[160];
  int k, m;

  printf("--- %s: nq=%ld nv=%ld\n", t->name, (long)t->G->nq, (long)t->G->nv);
  for (m = 0; m < 200; m++) { /* random angles in (0, pi) */
    double phi = PI * (0.5 * (Rand() + 1)) * (1 - 1e-9);
    snprintf(ctx, sizeof ctx, "%s angle %.6g random #%d", t->name, phi, m);
    MakeQ(t, q1, 0);
    MakeW(t, phi, w);
    CheckAt(t, q1, w, 0, phi, ctx);
    if (phi < PI - 0.05) CheckDerivative(t, q1, w, ctx);
  }
  for (k = 0; k < (int)(sizeof tiny / sizeof tiny[0]); k++)
    for (m = 0; m < 8; m++) {
      snprintf(ctx, sizeof ctx, "%s angle %.4g #%d", t->name, tiny[k], m);
      MakeQ(t, q1, 1);
      MakeW(t, tiny[k], w);
      CheckAt(t, q1, w, 1, tiny[k], ctx);
      MakeQ(t, q1, 0);
      CheckAt(t, q1, w, 0, tiny[k], ctx);
      CheckDerivative(t, q1, w, ctx);
    }
  for (k = 0; k < (int)(sizeof nearpi / sizeof nearpi[0]); k++)
    for (m = 0; m < 8; m++) {
      snprintf(ctx, sizeof ctx, "%s angle pi-%.1e #%d", t->name, nearpi[k], m);
      MakeQ(t, q1, 0);
      MakeW(t, PI - nearpi[k], w);
      CheckAt(t, q1, w, 0, PI - nearpi[k], ctx);
    }
  for (k = 0; k < (int)(sizeof nearpi_exact / sizeof nearpi_exact[0]); k++)
    for (m = 0; m < 8; m++) {
      snprintf(ctx, sizeof ctx, "%s angle pi-%.1e exact q #%d", t->name,
               nearpi_exact[k], m);
      MakeQ(t, q1, 1);
      MakeW(t, PI - nearpi_exact[k], w);
      CheckAt(t, q1, w, 1, PI - nearpi_exact[k], ctx);
    }
  /* beyond pi and around the pi of double (rounding decides the side):
   * the log is the other vector of the rotation, |angle| <= pi */
  for (m = 0; m < 16; m++) {
    static const double beyond[] = {0, 1e-15, 1e-9, 1e-3, 0.5, 2, 3, -1e-15};
    RT q2[MAXQ], q3[MAXQ], wl[MAXV];
    int o = 0;
    double phi = PI + beyond[m % 8];
    snprintf(ctx, sizeof ctx, "%s angle pi%+.1e #%d", t->name, beyond[m % 8], m);
    MakeQ(t, q1, m < 8);
    MakeW(t, phi, w);
    LGNGroup_ComposeExp(t->G, q1, w, q2);
    Log(t, q1, q2, wl);
    LGNGroup_ComposeExp(t->G, q1, wl, q3);
    Check("beyond pi: exp(q1, log(q1, q2)) = q2 (up to sign)", GroupDiff(t, q3, q2),
          1e-15, ctx);
    for (k = 0; k < t->nf; k++) {
      int r = QuatOff(t, k);
      if (r >= 0) {
        const RT *a = wl + o + r;
        Check("beyond pi: |log| <= pi (+ 4 eps)",
              fmax(0, sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) - PI), 9e-16, ctx);
      }
      o += FacNv(t, k);
    }
  }
}

/* =============================================================================
 * SO(3) at angle pi exactly (a quaternion with w = +-0) and the kernel's
 * relative accuracy from the identity
 * ===========================================================================*/

static void RunSO3Special(LGNGroup so3)
{
  static const RT pis[][4] = {
    {0, 0.6, 0.8, 0}, {0, -0.6, 0.8, 0}, {0, 0, -1, 0}, {0, 0, 0, -1},
    {-0.0, 0, 0.6, -0.8}, {0, -0.0, -0.0, 1}, {-0.0, 0.48, -0.6, 0.64},
    {0, 1e-300, -1, 0}};
  const RT id[4] = {1, 0, 0, 0};
  RT p[4], mp[4], w1[3], w2[3], p3[4];
  double err = 0, errn = 0, erre = 0;
  int k, i;
  printf("--- SO(3) at angle pi exactly, and from the identity vs long double\n");
  for (k = 0; k < (int)(sizeof pis / sizeof pis[0]); k++) {
    memcpy(p, pis[k], sizeof p);
    for (i = 0; i < 4; i++) mp[i] = -p[i];
    LGNGroup_ComposeLog(so3, id, p, w1);
    LGNGroup_ComposeLog(so3, id, mp, w2);
    err = fmax(err, MaxDiff(w1, w2, 3));
    errn = fmax(errn, fabs(sqrt(w1[0] * w1[0] + w1[1] * w1[1] + w1[2] * w1[2]) - PI) / PI);
    LGNGroup_ComposeExp(so3, id, w1, p3);
    for (i = 0; i < 4; i++)
      erre = fmax(erre, fmin(fabs(p3[i] - p[i]), fabs(p3[i] + p[i])));
    /* the choice: the first nonzero entry of w positive */
    for (i = 0; i < 3 && w1[i] == 0; i++) {}
    if (i == 3 || !(w1[i] > 0)) err = 1;
  }
  Check("angle pi exactly: log(p) = log(-p), first nonzero entry > 0", err, 0, "pi");
  Check("angle pi exactly: |log(p)| = pi (rel)", errn, 3e-16, "pi");
  Check("angle pi exactly: exp(log(p)) = p (up to sign)", erre, 4e-16, "pi");

  /* from the identity: relative accuracy against atan2l for angles from
   * 1e-300 to pi - 1e-15, through the series/atan2 switch */
  err = 0;
  for (k = 0; k < 4000; k++) {
    double phi = k < 3000 ? pow(10.0, -300.0 * (k % 1000) / 999.0) * (k < 1000 ? 1 : k < 2000 ? 0.3 : 0.0997)
                          : PI * (k - 2999) / 1001.0;
    RT d[3], pp[4];
    LD pl[4], n, kk, ref[3];
    RandDir(d);
    for (i = 0; i < 3; i++) w1[i] = phi * d[i];
    LGNQuaternionFromRotationVector(w1, pp);
    for (i = 0; i < 4; i++) pl[i] = pp[i];
    n = sqrtl(pl[1] * pl[1] + pl[2] * pl[2] + pl[3] * pl[3]);
    kk = (n < 1e-150L) ? 2.0L / pl[0] : 2.0L * atan2l(n, pl[0]) / n;
    for (i = 0; i < 3; i++) ref[i] = kk * pl[i + 1];
    LGNGroup_ComposeLog(so3, id, pp, w2);
    for (i = 0; i < 3; i++) {
      double e = (double)(fabsl((LD)w2[i] - ref[i]) / sqrtl(ref[0] * ref[0] + ref[1] * ref[1]
                                                          + ref[2] * ref[2]));
      if (e > err || e != e) err = e;
    }
  }
  Check("SO(3) log from the identity vs long double atan2 (rel, 1e-300..pi)", err,
        ldx ? 3e-16 : 1e-15, "identity");
}

/* =============================================================================
 * Bad input and user-supplied groups
 * ===========================================================================*/

/* capture what is written to stderr between Begin and End */
typedef struct { FILE *tmp; int saved; char text[4096]; } Capture;

static int CaptureBegin(Capture *c)
{
  fflush(stderr);
  c->tmp = tmpfile();
  c->saved = dup(fileno(stderr));
  if (c->tmp == NULL || c->saved < 0 || dup2(fileno(c->tmp), fileno(stderr)) < 0) return -1;
  return 0;
}

static void CaptureEnd(Capture *c)
{
  size_t n;
  fflush(stderr);
  dup2(c->saved, fileno(stderr));
  close(c->saved);
  rewind(c->tmp);
  n = fread(c->text, 1, sizeof c->text - 1, c->tmp);
  c->text[n] = '\0';
  fclose(c->tmp);
}

static int FailingLog(LGNGroup G, const RT *q1, const RT *q2, RT *w)
{
  (void)G; (void)q1; (void)q2; (void)w;
  return 5;
}

static int UserLog(LGNGroup G, const RT *q1, const RT *q2, RT *w)
{
  sunindextype i;
  for (i = 0; i < G->nv; i++) w[i] = 2 * (q2[i] - q1[i]);
  return 0;
}

/* flag and message of one call: the flag wanted and the words the message
 * must hold */
static void ExpectMsg(int flag, int want, const Capture *c, const char *w1,
                      const char *w2, const char *what)
{
  int ok = flag == want && strstr(c->text, "LGNGroup_ComposeLog") != NULL &&
           strstr(c->text, w1) != NULL && (w2 == NULL || strstr(c->text, w2) != NULL);
  if (!ok) printf("    %s: flag %d (want %d), message \"%s\"\n", what, flag, want, c->text);
  Check("bad input: flag and a message naming the argument or op", ok ? 0 : 1, 0, what);
}

static void RunBadInput(LGNGroup so3)
{
  LGNGroup empty = LGNGroup_NewEmpty(2, 2), fac[2], P;
  RT q[8] = {1, 0, 0, 0, 1, 0, 0, 0}, w[8], z[4] = {0, 0, 0, 0};
  RT nanq[4] = {1, 0, 0, 0};
  Capture c;
  int flag;

  printf("--- bad input to LGNGroup_ComposeLog\n");
  nanq[2] = NAN;
  if (empty == NULL || CaptureBegin(&c) != 0) {
    Check("set-up of the bad-input checks", 1, 0, "setup");
    return;
  }
  flag = LGNGroup_ComposeLog(NULL, q, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_ILL_INPUT, &c, "G = NULL", NULL, "G = NULL");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, NULL, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_ILL_INPUT, &c, "q1 = NULL", NULL, "q1 = NULL");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, q, NULL, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_ILL_INPUT, &c, "q2 = NULL", NULL, "q2 = NULL");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, q, q, NULL);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_ILL_INPUT, &c, "w = NULL", NULL, "w = NULL");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(empty, q, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_ILL_INPUT, &c, "compose_log", "NULL",
            "user-supplied group without compose_log");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, q, z, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_GROUP_FAIL, &c, "compose_log", "quaternion", "zero quaternion q2");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, z, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_GROUP_FAIL, &c, "compose_log", "quaternion", "zero quaternion q1");
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(so3, q, nanq, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_GROUP_FAIL, &c, "compose_log", "not finite", "NaN in q2");

  /* a product with a factor lacking the op: the product's op fails */
  fac[0] = so3; fac[1] = empty;
  P = LGNGroup_Product(2, fac);
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(P, q, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_GROUP_FAIL, &c, "compose_log", "factor", "product, factor without op");

  /* a user op that fails, then one that works (and is really called) */
  empty->ops.compose_log = FailingLog;
  CaptureBegin(&c);
  flag = LGNGroup_ComposeLog(empty, q, q, w);
  CaptureEnd(&c);
  ExpectMsg(flag, LGN_GROUP_FAIL, &c, "flag 5", NULL, "user op returning 5");
  empty->ops.compose_log = UserLog;
  {
    RT a[2] = {1, 2}, b[2] = {4, 0}, v[2];
    CaptureBegin(&c);
    flag = LGNGroup_ComposeLog(empty, a, b, v);
    CaptureEnd(&c);
    Check("user-supplied compose_log is called; success is silent",
          (flag == LGN_SUCCESS && v[0] == 6 && v[1] == -4 && c.text[0] == '\0') ? 0 : 1,
          0, "user op");
    /* and the product now works with it, factor by factor */
    {
      RT qq[6] = {1, 0, 0, 0, 1, 2}, q2[6] = {0, 1, 0, 0, 4, 0}, ww[5];
      flag = LGNGroup_ComposeLog(P, qq, q2, ww);
      Check("product with a user factor: factor by factor",
            (flag == LGN_SUCCESS && fabs(ww[0] - PI) < 1e-15 && ww[1] == 0 && ww[2] == 0 &&
             ww[3] == 6 && ww[4] == -4) ? 0 : 1, 0, "user factor");
    }
  }
  LGNGroup_Destroy(P);
  LGNGroup_Destroy(empty);
}

int main(void)
{
  LGNGroup rn = LGNGroup_Rn(3), so3 = LGNGroup_SO3(), r3 = LGNGroup_R3xSO3();
  LGNGroup se3 = LGNGroup_SE3(), r2 = LGNGroup_Rn(2), fac[4], prod, fac2[2], nest;
  TG t;
  int nfail;

  printf("Lignum unit test: the logarithm of the built-in Lie groups\n");
  {
    volatile LD one = 1, tiny = LDBL_EPSILON;
    ldx = (LDBL_MANT_DIG > 53) && ((one + tiny) - one == tiny);
  }
  fac[0] = r2; fac[1] = so3; fac[2] = r3; fac[3] = se3;
  prod = LGNGroup_Product(4, fac);
  fac2[0] = prod; fac2[1] = so3;
  nest = LGNGroup_Product(2, fac2);
  if (!rn || !so3 || !r3 || !se3 || !r2 || !prod || !nest) {
    printf("FAIL  a constructor returned NULL\n");
    return 1;
  }

  memset(&t, 0, sizeof t);
  t.nf = 1;
  t.name = "R^3"; t.G = rn; t.kind[0] = LGN_GROUP_RN; t.n[0] = 3;
  RunGroup(&t);
  t.name = "SO(3)"; t.G = so3; t.kind[0] = LGN_GROUP_SO3;
  RunGroup(&t);
  t.name = "R^3xSO(3)"; t.G = r3; t.kind[0] = LGN_GROUP_R3XSO3;
  RunGroup(&t);
  t.name = "SE(3)"; t.G = se3; t.kind[0] = LGN_GROUP_SE3;
  RunGroup(&t);
  memset(&t, 0, sizeof t);
  t.name = "R^2 x SO(3) x R^3xSO(3) x SE(3)"; t.G = prod; t.nf = 4;
  t.kind[0] = LGN_GROUP_RN; t.n[0] = 2; t.kind[1] = LGN_GROUP_SO3;
  t.kind[2] = LGN_GROUP_R3XSO3; t.kind[3] = LGN_GROUP_SE3;
  RunGroup(&t);
  t.name = "(R^2 x SO(3) x R^3xSO(3) x SE(3)) x SO(3) (nested)"; t.G = nest; t.nf = 5;
  t.kind[4] = LGN_GROUP_SO3;
  RunGroup(&t);

  RunSO3Special(so3);
  RunBadInput(so3);

  nfail = CheckSummary(66);

  LGNGroup_Destroy(nest);
  LGNGroup_Destroy(prod);
  LGNGroup_Destroy(rn); LGNGroup_Destroy(so3); LGNGroup_Destroy(r3);
  LGNGroup_Destroy(se3); LGNGroup_Destroy(r2);
  return nfail ? 1 : 0;
}
