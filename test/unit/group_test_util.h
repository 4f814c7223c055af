/* -----------------------------------------------------------------------------
 * Shared by the group tests (test_groups.c, test_group_log.c): the check
 * bookkeeping (every check records its worst error against its tolerance,
 * a summary table at the end), a reproducible random generator, and small
 * double and long-double vector helpers. Define GROUP_TEST_SEED (the
 * generator's seed) before including it.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_GROUP_TEST_UTIL_H
#define LGN_GROUP_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_types.h>

typedef long double LD;
typedef sunrealtype RT;

/* ---- check bookkeeping ---------------------------------------------------- */

typedef struct {
  const char *name;
  double tol, maxerr;
  long count, fails;
} CheckRec;

static CheckRec checks[128];
static int nchecks = 0;

/* 1 if long double arithmetic really is wider than double at run time
 * (valgrind, for one, computes x87 long double in double precision). */
static int ldx = 0;

/* Record err <= tol under `name`; print the first few failures with ctx. */
static int Check(const char *name, double err, double tol, const char *ctx)
{
  CheckRec *c = NULL;
  int k;
  for (k = 0; k < nchecks; k++)
    if (strcmp(checks[k].name, name) == 0) { c = &checks[k]; break; }
  if (c == NULL) {
    if (nchecks == (int)(sizeof checks / sizeof checks[0])) {
      fprintf(stderr, "too many checks\n");
      exit(2);
    }
    c = &checks[nchecks++];
    c->name = name; c->tol = tol; c->maxerr = 0; c->count = 0; c->fails = 0;
  }
  c->count++;
  if (!(err <= tol)) { /* also catches NaN */
    c->fails++;
    if (c->fails <= 5)
      printf("FAIL  %-62s err=%.3e tol=%.1e  [%s]\n", name, err, tol, ctx);
  }
  if (err > c->maxerr || err != err) c->maxerr = err;
  return err <= tol;
}

/* The summary table (names padded to width); returns the failed checks. */
static int CheckSummary(int width)
{
  int k, nfail = 0;
  printf("\n%-*s %7s %10s %8s  %s\n", width, "check", "count", "max err", "tol", "result");
  for (k = 0; k < nchecks; k++) {
    printf("%-*s %7ld %10.2e %8.1e  %s\n", width, checks[k].name, checks[k].count,
           checks[k].maxerr, checks[k].tol, checks[k].fails ? "FAIL" : "ok");
    if (checks[k].fails) nfail++;
  }
  printf("\n%d of %d checks failed\n", nfail, nchecks);
  return nfail;
}

/* ---- random numbers (xorshift64) ------------------------------------------ */

static unsigned long long rng = GROUP_TEST_SEED;

static double Rand(void) /* uniform in [-1, 1] */
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return 2.0 * ((double)(rng >> 11) / 9007199254740992.0) - 1.0;
}

static void RandDir(RT d[3])
{
  double n;
  do {
    d[0] = Rand(); d[1] = Rand(); d[2] = Rand();
    n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  } while (n < 0.1);
  d[0] /= n; d[1] /= n; d[2] /= n;
}

/* ---- vectors -------------------------------------------------------------- */

static double MaxAbs(const RT *x, sunindextype n)
{
  double m = 0;
  sunindextype i;
  for (i = 0; i < n; i++)
    if (fabs(x[i]) > m || x[i] != x[i]) m = fabs(x[i]);
  return m;
}

static double MaxDiff(const RT *x, const RT *y, sunindextype n)
{
  double m = 0;
  sunindextype i;
  for (i = 0; i < n; i++) {
    double d = fabs(x[i] - y[i]);
    if (d > m || d != d) m = d;
  }
  return m;
}

/* r = a (x) b, the Hamilton product in long double (r may alias a or b) */
static void QMulL(const LD a[4], const LD b[4], LD r[4])
{
  LD t[4];
  t[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  t[1] = a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2];
  t[2] = a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3];
  t[3] = a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1];
  memcpy(r, t, sizeof t);
}

/* r = a x b in long double (r may alias a or b) */
static void CrossL(const LD a[3], const LD b[3], LD r[3])
{
  LD t[3];
  t[0] = a[1] * b[2] - a[2] * b[1];
  t[1] = a[2] * b[0] - a[0] * b[2];
  t[2] = a[0] * b[1] - a[1] * b[0];
  memcpy(r, t, sizeof t);
}

#endif
