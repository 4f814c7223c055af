/* -----------------------------------------------------------------------------
 * Lignum study models: the N-body spherical pendulum chain (see chain.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include "chain.h"

#include <math.h>

RigidSystem *chain_create(int n, RigidFormulation formulation, SUNContext ctx)
{
  const double L = 1.0, mass = 1.0, radius = 0.02, pi = acos(-1.0);
  const double top[3] = {0.0, 0.0, 0.5 * L}, bottom[3] = {0.0, 0.0, -0.5 * L};
  const double origin[3] = {0.0, 0.0, 0.0};
  double joint[3] = {0.0, 0.0, 0.0};
  RigidSystem *sys = rigid_create(n, formulation, ctx);
  int k, i;
  if (sys == NULL) return NULL;
  for (k = 0; k < n; k++) {
    const double th = 0.5 * pi * (1.0 - (double)k / n), ph = 0.3 * (double)k / n;
    double d[3], e3[3], e1[3], e2[3], R[9], x[3], nrm;
    d[0] = sin(th) * cos(ph);
    d[1] = sin(th) * sin(ph);
    d[2] = -cos(th);
    /* body frame: e3 = -d (bottom to top), e1 horizontal, e2 = e3 x e1 */
    for (i = 0; i < 3; i++) e3[i] = -d[i];
    e1[0] = -sin(ph);
    e1[1] = cos(ph);
    e1[2] = 0.0;
    e2[0] = e3[1] * e1[2] - e3[2] * e1[1];
    e2[1] = e3[2] * e1[0] - e3[0] * e1[2];
    e2[2] = e3[0] * e1[1] - e3[1] * e1[0];
    nrm = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    for (i = 0; i < 3; i++) {
      e2[i] /= nrm;
      R[3 * i]     = e1[i];  /* columns e1, e2, e3 */
      R[3 * i + 1] = e2[i];
      R[3 * i + 2] = e3[i];
      x[i]         = joint[i] + 0.5 * L * d[i];
    }
    rigid_set_cylinder(sys, k, L, mass, radius);
    rigid_place(sys, k, x, R);
    if (k == 0) LGNJoints_AddSpherical(sys->joints, LGN_GROUND, origin, 0, top);
    else LGNJoints_AddSpherical(sys->joints, k - 1, bottom, k, top);
    for (i = 0; i < 3; i++) joint[i] += L * d[i];
  }
  return sys;
}
