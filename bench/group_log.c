/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Cost of one logarithm against one exponential (a timing loop, not a test):
 * LGNGroup_ComposeLog and LGNGroup_ComposeExp of SO(3) and SE(3) over 1024
 * prepared inputs, repeated, for small angles (the series branches of both,
 * angle < 0.1) and large ones (sin/cos against atan2). Prints ns per call.
 *   group_log [reps]       (default 20000 passes over the 1024 inputs)
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <lignum/lignum_group.h>

#define N 1024

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;

static double Rand(void) /* uniform in [-1, 1] */
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return 2.0 * ((double)(rng >> 11) / 9007199254740992.0) - 1.0;
}

static double Now(void)
{
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ns per call of exp and of log over the prepared inputs */
static void Run(LGNGroup G, const char *name, double amax, long reps)
{
  const int nq = (int)G->nq, nv = (int)G->nv;
  double *q1 = malloc(sizeof(double) * N * nq), *q2 = malloc(sizeof(double) * N * nq);
  double *w = malloc(sizeof(double) * N * nv), *wl = malloc(sizeof(double) * N * nv);
  double t0, te, tl, sum = 0;
  long r;
  int i, j;
  if (!q1 || !q2 || !w || !wl) exit(1);
  for (i = 0; i < N; i++) {
    double *q = q1 + i * nq, n = 0;
    for (j = 0; j < nq; j++) q[j] = Rand();
    for (j = nq - 4; j < nq; j++) n += q[j] * q[j];
    for (j = nq - 4; j < nq; j++) q[j] /= sqrt(n);
    for (j = 0; j < nv; j++) w[i * nv + j] = amax * 0.577 * Rand();
  }
  t0 = Now();
  for (r = 0; r < reps; r++)
    for (i = 0; i < N; i++) LGNGroup_ComposeExp(G, q1 + i * nq, w + i * nv, q2 + i * nq);
  te = (Now() - t0) / ((double)reps * N);
  t0 = Now();
  for (r = 0; r < reps; r++)
    for (i = 0; i < N; i++) LGNGroup_ComposeLog(G, q1 + i * nq, q2 + i * nq, wl + i * nv);
  tl = (Now() - t0) / ((double)reps * N);
  for (i = 0; i < N * nv; i++) sum += fabs(wl[i] - w[i]);
  printf("%-6s angles < %-5g exp %6.1f ns  log %6.1f ns  log/exp %.2f  (sum |log(exp(w)) - w| = %.1e)\n",
         name, amax, 1e9 * te, 1e9 * tl, tl / te, sum);
  free(q1); free(q2); free(w); free(wl);
}

int main(int argc, char **argv)
{
  long reps = argc > 1 ? atol(argv[1]) : 20000;
  LGNGroup so3 = LGNGroup_SO3(), se3 = LGNGroup_SE3();
  if (so3 == NULL || se3 == NULL || reps < 1) return 1;
  Run(so3, "SO(3)", 0.1, reps);
  Run(so3, "SO(3)", 3.0, reps);
  Run(se3, "SE(3)", 0.1, reps);
  Run(se3, "SE(3)", 3.0, reps);
  LGNGroup_Destroy(so3);
  LGNGroup_Destroy(se3);
  return 0;
}
