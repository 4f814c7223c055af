/* -----------------------------------------------------------------------------
 * Lignum study models: Euler-parameter kinematics shared by the heavy top model
 * (models/heavy_top.c) and the IDA opponent (bench/ida_heavy_top.c).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * p = (p0, pbar) in R^4, matrices row-major (doc/theory.md).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_EXAMPLES_EULER_PARAMETERS_H
#define LGN_EXAMPLES_EULER_PARAMETERS_H

/* G(p) = [-pbar, -pbar~ + p0 I], 3 x 4 row-major */
static inline void ep_matrix_g(const double p[4], double G[12])
{
  G[0] = -p[1]; G[1] = p[0];  G[2] = p[3];   G[3] = -p[2];
  G[4] = -p[2]; G[5] = -p[3]; G[6] = p[0];   G[7] = p[1];
  G[8] = -p[3]; G[9] = p[2];  G[10] = -p[1]; G[11] = p[0];
}

/* R(p) = (p0^2 - pbar.pbar) I + 2 pbar pbar^T + 2 p0 pbar~ (row-major),
 * the quadratic form used in Phi (doc/theory.md). */
static inline void ep_rotation(const double p[4], double R[9])
{
  const double s = p[0] * p[0] - p[1] * p[1] - p[2] * p[2] - p[3] * p[3];
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) R[3 * i + j] = (i == j ? s : 0.0) + 2.0 * p[1 + i] * p[1 + j];
  R[1] -= 2.0 * p[0] * p[3]; R[2] += 2.0 * p[0] * p[2];
  R[3] += 2.0 * p[0] * p[3]; R[5] -= 2.0 * p[0] * p[1];
  R[6] -= 2.0 * p[0] * p[2]; R[7] += 2.0 * p[0] * p[1];
}

/* c = G a (3-vector) for G = G(p) row-major 3 x 4 */
static inline void ep_g_vec(const double G[12], const double a[4], double c[3])
{
  int k;
  for (k = 0; k < 3; k++)
    c[k] = G[4 * k] * a[0] + G[4 * k + 1] * a[1] + G[4 * k + 2] * a[2] + G[4 * k + 3] * a[3];
}

/* out (4 x 4 row-major) += s G1^T diag(J) G2 */
static inline void ep_add_gt_j_g(const double G1[12], const double J[3],
                                 const double G2[12], double s, double out[16])
{
  int i, j, k;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      double a = 0.0;
      for (k = 0; k < 3; k++) a += G1[4 * k + i] * J[k] * G2[4 * k + j];
      out[4 * i + j] += s * a;
    }
}

/* out (4 x 4 row-major) += s H(c), H(c) = [[0, -c^T], [c, -c~]], the matrix
 * with G(d)^T c = H(c) d */
static inline void ep_add_h(const double c[3], double s, double out[16])
{
  int i;
  for (i = 0; i < 3; i++) {
    out[1 + i] -= s * c[i];
    out[4 * (1 + i)] += s * c[i];
  }
  out[4 * 1 + 2] += s * c[2]; out[4 * 1 + 3] -= s * c[1];
  out[4 * 2 + 1] -= s * c[2]; out[4 * 2 + 3] += s * c[0];
  out[4 * 3 + 1] += s * c[1]; out[4 * 3 + 2] -= s * c[0];
}

#endif
