/* -----------------------------------------------------------------------------
 * The planar groups SE(2) and R^2 x SO(2) (lignum_planar.h): exp/log round
 * trips, T against central differences of exp (through the log), T^{-1} T
 * = I, Tdot against central differences of T, the tangent matrix against
 * T applied, SE(2) against SE(3) restricted to planar motions (exp, T,
 * T^{-1}, Tdot: the same formulas at Omega = (0, 0, om), U = (U1, U2, 0)),
 * products of planar factors, and bad input.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <lignum/lignum.h>
#include <lignum/lignum_planar.h>

static int fails = 0;

static void Check(const char *what, double err, double tol, double om)
{
  if (!(err <= tol)) {
    printf("FAIL  %-44s om = %-10.3g err = %.3e  tol = %.1e\n", what, om, err, tol);
    fails++;
  }
}

static double Rand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

static double MaxDiff(const double *a, const double *b, int n)
{
  double m = 0;
  int i;
  for (i = 0; i < n; i++) m = fmax(m, fabs(a[i] - b[i]));
  return m;
}

/* the angles tried: zero, tiny, around the series thresholds, large */
static const double OMEGAS[] = {0.0, 1e-12, -3e-9, 1e-4, 0.0499, 0.05, 0.0501, -0.1,
                                0.2999, 0.3, 0.7, -1.3, 2.5, 3.1, -4.0, 6.0};
#define NOM ((int)(sizeof OMEGAS / sizeof OMEGAS[0]))

static void GroupChecks(LGNGroup G, const char *name)
{
  int k, r, i, j;
  char what[128];
  for (k = 0; k < NOM; k++) {
    const double om = OMEGAS[k];
    for (r = 0; r < 4; r++) {
      double q[3] = {3 * Rand(), 3 * Rand(), 10 * Rand()}, w[3] = {2 * Rand(), 2 * Rand(), om};
      double q1[3], wl[3], d[3] = {Rand(), Rand(), Rand()}, wd[3] = {Rand(), Rand(), Rand()};
      double Td[3], Tfd[3], x[3], y[3], Tm[9], Ti[3], Tdot[3], Tdfd[3], e, qe[3], wp[3], wm[3],
          lp[3], lm[3], Tp[3], Tmn[3];
      /* exp/log round trip */
      LGNGroup_ComposeExp(G, q, w, q1);
      if (LGNGroup_ComposeLog(G, q, q1, wl) != LGN_SUCCESS) {
        printf("FAIL  %s log failed\n", name);
        fails++;
        continue;
      }
      snprintf(what, sizeof what, "%s log(q^-1 q exp(w)) = w", name);
      Check(what, MaxDiff(w, wl, 3) / (1 + fabs(q[0]) + fabs(q[1])), 1e-14 * (1 + fabs(om)), om);
      /* T against central differences of exp: exp(w + e d) = exp(w) exp(e T d) */
      e = 1e-5;
      for (i = 0; i < 3; i++) {
        wp[i] = w[i] + e * d[i];
        wm[i] = w[i] - e * d[i];
      }
      LGNGroup_ComposeExp(G, q, wp, qe);
      LGNGroup_ComposeLog(G, q1, qe, lp);
      LGNGroup_ComposeExp(G, q, wm, qe);
      LGNGroup_ComposeLog(G, q1, qe, lm);
      for (i = 0; i < 3; i++) Tfd[i] = (lp[i] - lm[i]) / (2 * e);
      LGNGroup_TangentApply(G, w, d, Td);
      snprintf(what, sizeof what, "%s T(w) d vs differences of exp", name);
      Check(what, MaxDiff(Td, Tfd, 3), 1e-8, om);
      /* T^{-1} T = I */
      LGNGroup_TangentInverseApply(G, w, Td, Ti);
      snprintf(what, sizeof what, "%s T^-1 T d = d", name);
      Check(what, MaxDiff(Ti, d, 3), 1e-14, om);
      /* tangent matrix = T applied to the unit vectors */
      LGNGroup_TangentMatrix(G, w, Tm, 3);
      for (j = 0; j < 3; j++) {
        x[0] = x[1] = x[2] = 0;
        x[j] = 1;
        LGNGroup_TangentApply(G, w, x, y);
        for (i = 0; i < 3; i++) x[i] = Tm[i + 3 * j];
        snprintf(what, sizeof what, "%s tangent matrix = T applied", name);
        Check(what, MaxDiff(x, y, 3), 0, om);
      }
      /* Tdot(w, wd) d against central differences of T along wd */
      LGNGroup_TangentDotApply(G, w, wd, d, Tdot);
      for (i = 0; i < 3; i++) {
        wp[i] = w[i] + e * wd[i];
        wm[i] = w[i] - e * wd[i];
      }
      LGNGroup_TangentApply(G, wp, d, Tp);
      LGNGroup_TangentApply(G, wm, d, Tmn);
      for (i = 0; i < 3; i++) Tdfd[i] = (Tp[i] - Tmn[i]) / (2 * e);
      snprintf(what, sizeof what, "%s Tdot vs differences of T", name);
      Check(what, MaxDiff(Tdot, Tdfd, 3), 1e-8, om);
    }
  }
}

/* SE(2) = the planar motions of SE(3) */
static void AgainstSE3(LGNGroup G2, LGNGroup G3)
{
  int k, r, i, j;
  const int idx[3] = {0, 1, 5};
  for (k = 0; k < NOM; k++) {
    const double om = OMEGAS[k];
    for (r = 0; r < 4; r++) {
      const double th = 4 * Rand();
      double q2[3] = {Rand(), Rand(), th}, w2[3] = {2 * Rand(), 2 * Rand(), om};
      double wd2[3] = {Rand(), Rand(), Rand()}, x2[3] = {Rand(), Rand(), Rand()};
      double q3[7] = {q2[0], q2[1], 0, cos(th / 2), 0, 0, sin(th / 2)};
      double w3[6] = {w2[0], w2[1], 0, 0, 0, om}, wd3[6] = {wd2[0], wd2[1], 0, 0, 0, wd2[2]};
      double x3[6] = {x2[0], x2[1], 0, 0, 0, x2[2]};
      double o2[3], o3[7], y2[3], y3[6], T2[9], T3[36], err = 0;
      LGNGroup_ComposeExp(G2, q2, w2, o2);
      LGNGroup_ComposeExp(G3, q3, w3, o3);
      err = fmax(fabs(o2[0] - o3[0]), fabs(o2[1] - o3[1]));
      err = fmax(err, fabs(cos(o2[2] / 2) * o3[6] - sin(o2[2] / 2) * o3[3])); /* same angle */
      Check("SE(2) exp = SE(3) exp of planar motion", err, 1e-14, om);
      LGNGroup_TangentMatrix(G2, w2, T2, 3);
      LGNGroup_TangentMatrix(G3, w3, T3, 6);
      err = 0;
      for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) err = fmax(err, fabs(T2[i + 3 * j] - T3[idx[i] + 6 * idx[j]]));
      Check("SE(2) T = SE(3) T restricted", err, 1e-15, om);
      LGNGroup_TangentInverseApply(G2, w2, x2, y2);
      LGNGroup_TangentInverseApply(G3, w3, x3, y3);
      err = 0;
      for (i = 0; i < 3; i++) err = fmax(err, fabs(y2[i] - y3[idx[i]]));
      Check("SE(2) T^-1 = SE(3) T^-1 restricted", err, 1e-14, om);
      LGNGroup_TangentDotApply(G2, w2, wd2, x2, y2);
      LGNGroup_TangentDotApply(G3, w3, wd3, x3, y3);
      err = 0;
      for (i = 0; i < 3; i++) err = fmax(err, fabs(y2[i] - y3[idx[i]]));
      Check("SE(2) Tdot = SE(3) Tdot restricted", err, 1e-14, om);
    }
  }
}

int main(void)
{
  LGNGroup se2 = LGNGroup_SE2(), r2 = LGNGroup_R2xSO2(), se3 = LGNGroup_SE3();
  LGNGroup fac[3], prod;
  double q[9], w[9], q1[9], ql[9], id[3];
  int i;
  srand(12345);
  if (se2 == NULL || r2 == NULL || se3 == NULL) return 1;
  if (se2->nq != 3 || se2->nv != 3 || r2->nq != 3 || r2->nv != 3 ||
      se2->kind != LGN_GROUP_SE2 || r2->kind != LGN_GROUP_R2XSO2) {
    printf("FAIL  sizes or kinds\n");
    fails++;
  }
  GroupChecks(se2, "SE(2)");
  GroupChecks(r2, "R2xSO(2)");
  AgainstSE3(se2, se3);
  /* the angle is stored unwrapped: exp over several turns, log back */
  {
    double qa[3] = {0, 0, 0}, wa[3] = {1, 0, 20.0}, qb[3], wb[3];
    LGNGroup_ComposeExp(r2, qa, wa, qb);
    LGNGroup_ComposeLog(r2, qa, qb, wb);
    Check("R2xSO(2) angle counts turns", fabs(qb[2] - 20.0) + fabs(wb[2] - 20.0), 0, 20);
  }
  /* the identity */
  LGNGroup_Identity(se2, id);
  Check("SE(2) identity", fabs(id[0]) + fabs(id[1]) + fabs(id[2]), 0, 0);
  /* a product of planar factors: factor by factor */
  fac[0] = se2;
  fac[1] = r2;
  fac[2] = se2;
  prod = LGNGroup_Product(3, fac);
  for (i = 0; i < 9; i++) {
    q[i] = Rand();
    w[i] = Rand();
  }
  LGNGroup_ComposeExp(prod, q, w, q1);
  for (i = 0; i < 3; i++) LGNGroup_ComposeExp(fac[i], q + 3 * i, w + 3 * i, ql + 3 * i);
  Check("product of planar factors: exp factor-wise", MaxDiff(q1, ql, 9), 0, 0);
  /* bad input: the log reports, a full turn of SE(2) has no log */
  {
    double qa[3] = {0, 0, 0}, qb[3] = {1, 0, 2 * 3.14159265358979323846}, wb[3];
    Check("SE(2) log at a full turn refused",
          LGNGroup_ComposeLog(se2, qa, qb, wb) == LGN_GROUP_FAIL ? 0 : 1, 0, 2 * 3.14159265358979323846);
    Check("log with NULL refused", LGNGroup_ComposeLog(se2, NULL, qb, wb) == LGN_ILL_INPUT ? 0 : 1,
          0, 0);
  }
  LGNGroup_Destroy(prod);
  LGNGroup_Destroy(se2);
  LGNGroup_Destroy(r2);
  LGNGroup_Destroy(se3);
  printf("%s: %d failure(s)\n", fails ? "FAILED" : "PASSED", fails);
  return fails ? 1 : 0;
}
