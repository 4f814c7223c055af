/* -----------------------------------------------------------------------------
 * Lignum examples: Euler-parameter kinematics shared by the heavy top model
 * (examples/models/heavy_top.c) and the IDA opponent (bench/ida_heavy_top.c).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * p = (p0, pbar) in R^4, matrices row-major (spec numerics.md §3).
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
 * the quadratic form used in Phi (spec §3). */
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

#endif
