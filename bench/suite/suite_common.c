/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: what both drivers share
 * (consistent accelerations, the error measures of a finished run).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include "suite_run.h"

/* w(s) = B(q + s v, t + s) v + Phi_t(q + s v, t + s): the velocity
 * constraint along the straight line through (q, t) with slope (v, 1). */
static void VelocityConstraint(const SuiteProblem *p, double t, const double *q,
                               const double *v, double s, double *w)
{
  double qs[SUITE_MAXN], B[SUITE_MAXN * SUITE_MAXN], phit[SUITE_MAXN];
  int i, j;
  for (i = 0; i < p->n; i++) qs[i] = q[i] + s * v[i];
  p->jacobian(t + s, qs, B);
  if (p->phi_t != NULL) p->phi_t(t + s, qs, phit);
  for (j = 0; j < p->m; j++) {
    w[j] = p->phi_t != NULL ? phit[j] : 0.0;
    for (i = 0; i < p->n; i++) w[j] += B[j * p->n + i] * v[i];
  }
}

int suite_consistent_acceleration(const SuiteProblem *p, double t, const double *q,
                                  const double *v, double *vdot, double *lambda)
{
  enum { NA = 2 * SUITE_MAXN };
  double K[NA][NA + 1], M[SUITE_MAXN * SUITE_MAXN], B[SUITE_MAXN * SUITE_MAXN];
  double g[SUITE_MAXN], wp[SUITE_MAXN], wm[SUITE_MAXN];
  const int n = p->n, m = p->m, N = n + m;
  const double eps = 1e-6; /* central differences: error ~ eps^2 |w'''| */
  int i, j, k;
  p->mass(t, q, M);
  p->force(t, q, v, g);
  p->jacobian(t, q, B);
  VelocityConstraint(p, t, q, v, eps, wp);
  VelocityConstraint(p, t, q, v, -eps, wm);
  memset(K, 0, sizeof K);
  for (i = 0; i < n; i++) { /* [M B^T; B 0] [v'; lambda] = [-g; -z] */
    for (j = 0; j < n; j++) K[i][j] = M[i * n + j];
    for (j = 0; j < m; j++) K[i][n + j] = K[n + j][i] = B[j * n + i];
    K[i][N] = -g[i];
  }
  for (j = 0; j < m; j++) K[n + j][N] = -(wp[j] - wm[j]) / (2.0 * eps);
  for (k = 0; k < N; k++) { /* Gauss elimination with partial pivoting */
    int piv = k;
    for (i = k + 1; i < N; i++)
      if (fabs(K[i][k]) > fabs(K[piv][k])) piv = i;
    if (K[piv][k] == 0.0) return -1;
    if (piv != k)
      for (j = 0; j <= N; j++) {
        const double tmp = K[k][j];
        K[k][j] = K[piv][j];
        K[piv][j] = tmp;
      }
    for (i = k + 1; i < N; i++) {
      const double f = K[i][k] / K[k][k];
      for (j = k; j <= N; j++) K[i][j] -= f * K[k][j];
    }
  }
  for (k = N - 1; k >= 0; k--) {
    double s = K[k][N];
    for (j = k + 1; j < N; j++) s -= K[k][j] * K[j][N];
    K[k][N] = s / K[k][k];
  }
  for (i = 0; i < n; i++) vdot[i] = K[i][N];
  for (j = 0; j < m; j++) lambda[j] = K[n + j][N];
  return 0;
}

void suite_finish_result(const SuiteProblem *p, SuiteResult *res)
{
  double phi[SUITE_MAXN];
  int j;
  if (p->q_ref != NULL) {
    res->err = suite_mixed_error(p, res->q);
    res->err_v = suite_mixed_error_v(p, res->v);
  }
  res->mescd = res->err > 0.0 ? -log10(res->err) : INFINITY;
  p->constraints(res->t, res->q, phi);
  res->phi_end = 0.0;
  for (j = 0; j < p->m; j++)
    if (!(fabs(phi[j]) <= res->phi_end)) res->phi_end = fabs(phi[j]);
}
